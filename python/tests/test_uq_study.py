"""`impact.uq` (issue 27): a study's declaration is validated with file:line:col messages
(bad distributions, a missing source, sizes that do not double, a key the scene does not have,
with the keys it has; test_uq_declaration.py: the rest of the whole-declaration check); the
declared distributions map the unit interval onto the declared moments; Saltelli's scrambled
Sobol' design is nested (the design of N is the first rows of 2 N's); and the CI study
(verification/uq/ci-coarse.yaml, 40 x 8 mesh, N = 4 and 8: 88 runs) gives the same rows on
one and two local workers, indices for every input and the yield stress as the dominant input
of the maximum displacement (the rigid-plastic scaling: the deflection goes as 1 / sigma_y)."""
from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
from helpers import without_timing, write_study

import impact
from impact import _impact
from impact._distributions import ppf
from impact._uq_design import saltelli

ROOT = Path(__file__).resolve().parents[2]
CI_STUDY = ROOT / "verification" / "uq" / "ci-coarse.yaml"


@pytest.mark.parametrize("inputs, sampling, message", [
    ("  material.youngs_modulus: {normal: {mean: 2.0e11, std: -1.0}, source: s}\n", None,
     r"study\.yaml:4:\d+: inputs\.material\.youngs_modulus\.normal\.std = -1: must be a finite number > 0"),
    ("  material.youngs_modulus: {normal: {mean: 2.0e11, std: 1.0e9}}\n", None,
     r"study\.yaml:4:\d+: inputs\.material\.youngs_modulus\.source: missing"),
    ("  plate.width: {uniform: {lower: 0.2, upper: 0.1}, source: s}\n", None,
     r"study\.yaml:4:\d+: inputs\.plate\.width\.uniform\.upper = 0\.1: must be > lower"),
    ("  plate.width: {truncated: {normal: {mean: 0.179, std: 0.001}, lower: 0.18, upper: 0.19}, source: s}\n", None,
     r"study\.yaml:4:\d+: inputs\.plate\.width\.truncated = \[0\.18, 0\.19\]: must hold the mean"),
    ("  plate.colour: {uniform: {lower: 1.0, upper: 2.0}, source: s}\n", None,
     r"study\.yaml:4:\d+: inputs\.plate\.colour: not a scene key: `plate` has no key `colour`; "
     r"its keys: ends, length, thickness, width"),
    ("  plate.width: {uniform: {lower: 0.17, upper: 0.18}, source: s}\n", "{method: sobol, seed: 1, sizes: [4, 6]}",
     r"study\.yaml:\d+:\d+: sampling\.sizes = \[4, 6\]: must be powers of two"),
    ("  plate.width: {gamma: {k: 1.0}, source: s}\n", None, r"study\.yaml:4:\d+: .*gamma"),
])
def test_a_bad_declaration_names_its_place(tmp_path, inputs, sampling, message):
    path = write_study(tmp_path, inputs, *( [sampling] if sampling else []))
    with pytest.raises(impact.SceneError, match=message):
        impact.uq(path)


def test_distributions_have_the_declared_moments():
    u = (np.arange(200_000) + 0.5) / 200_000
    x = ppf("lognormal", {"mean": 176e6, "cov": 0.07})(u)
    assert np.mean(x) == pytest.approx(176e6, rel=1e-4) and np.std(x) / np.mean(x) == pytest.approx(0.07, rel=1e-2)
    t = ppf("truncated", {"normal": {"mean": 0.0188, "std": 2e-4}, "lower": 0.0182, "upper": 0.0194})(u)
    assert t.min() >= 0.0182 and t.max() <= 0.0194 and np.mean(t) == pytest.approx(0.0188, rel=1e-6)
    assert ppf("uniform", {"lower": 1.0, "upper": 3.0})(np.array([0.25]))[0] == pytest.approx(1.5)


def test_the_sobol_design_is_nested_and_seeded():
    small, large = saltelli("sobol", 9, 8, 27), saltelli("sobol", 9, 16, 27)
    assert np.array_equal(small, large[: len(small)])
    assert np.array_equal(small, saltelli("sobol", 9, 8, 27))
    assert not np.array_equal(small, saltelli("sobol", 9, 8, 28))
    # row j * (D + 2) + 1 + i is A with column i from B
    a, ab0, b = small[0], small[1], small[10]
    assert ab0[0] == b[0] and np.array_equal(ab0[1:], a[1:])


@pytest.fixture(scope="module")
def ci_result():
    return impact.uq(CI_STUDY, jobs=2)


def test_the_ci_study_runs_and_names_the_dominant_input(ci_result):
    r = ci_result
    assert [s.n for s in r.steps] == [4, 8] and r.final.runs == 88
    names = [i["key"] for i in r.study["inputs"]]
    st = r.final.stats["max_plate_displacement_m"]
    assert len(st["ST"]) == len(names) == 9
    assert names[int(np.argmax(st["ST"]))] == "material.plasticity.yield_stress"
    assert st["std"] > 0 and st["mean_ci"][0] < st["mean"] < st["mean_ci"][1]
    assert set(r.mesh) == set(r.study["outputs"]) and all(m["u_num"] >= 0 for m in r.mesh.values())


def test_the_rows_do_not_depend_on_the_workers(ci_result):
    one = impact.uq(CI_STUDY, jobs=1, sizes=[4], mesh=False)
    a = [without_timing(x) for x in one.samples.to_dict("records")]
    b = [without_timing(x) for x in ci_result.samples.iloc[: len(a)].to_dict("records")]
    assert json.dumps(a, sort_keys=True) == json.dumps(b, sort_keys=True)


def _strata(x: np.ndarray, n: int) -> list[list[int]]:
    """Per column, the sorted indices of the n equal strata of [0, 1) its points fall in."""
    return [sorted(np.floor(x[:, j] * n).astype(int).tolist()) for j in range(x.shape[1])]


def test_the_latin_hypercube_design_holds_one_point_per_stratum_and_is_seeded():
    # 12 points: not a power of two, so a scrambled Sobol' set (stratified only in powers of
    # two) or plain random points would leave strata empty; a Latin hypercube fills each once
    from impact._uq_design import base_points

    pts = base_points("lhs", 5, 12, 27)
    assert _strata(pts, 12) == [list(range(12))] * 5
    with pytest.warns(UserWarning, match="power of 2"):
        assert _strata(base_points("sobol", 5, 12, 27), 12) != [list(range(12))] * 5
    d, n = 9, 16
    u = saltelli("lhs", d, n, 27)
    step = d + 2
    a, b = u[0::step], u[step - 1::step]
    # A and B are each a Latin hypercube in the d inputs, and not the same one
    assert _strata(a, n) == [list(range(n))] * d and _strata(b, n) == [list(range(n))] * d
    assert not np.array_equal(a, b)
    # the AB rows are A with one column from B, as Saltelli's design reads them
    for i in range(d):
        mixed = u[i + 1::step]
        assert np.array_equal(mixed[:, i], b[:, i])
        assert np.array_equal(np.delete(mixed, i, 1), np.delete(a, i, 1))
    # a fixed seed gives the same design, another seed or size another
    assert np.array_equal(u, saltelli("lhs", d, n, 27))
    assert not np.array_equal(u, saltelli("lhs", d, n, 28))
    assert not np.array_equal(u[: len(saltelli("lhs", d, 8, 27))], saltelli("lhs", d, 8, 27))


def test_a_latin_hypercube_study_runs_each_size_afresh(tmp_path):
    # two inputs on a 20 x 4 elastic plate: the LHS design is not nested, so each size is run
    # whole (N (D + 2) runs, not the sum over sizes), and its A and B rows, mapped back through
    # the inputs' CDFs, hold one point per stratum
    scene = ROOT / "verification" / "scenes" / "paper-elastic.yaml"
    path = tmp_path / "lhs.yaml"
    path.write_text(
        f"title: lhs\nscene: {scene}\nset: {{mesh.nx: 20, mesh.ny: 4}}\ninputs:\n"
        "  plate.width: {uniform: {lower: 0.178, upper: 0.180}, source: s}\n"
        "  material.youngs_modulus: {uniform: {lower: 2.0e11, upper: 2.14e11}, source: s}\n"
        "sampling: {method: lhs, seed: 5, sizes: [4, 8]}\n"
        "convergence: {mean: 1.0e-9, std: 1.0e-9, total_index: 1.0e-9}\n"
        "mesh_levels: [0.25, 0.5, 1.0]\noutputs: {impulse_Ns: {}}\n")
    r = impact.uq(path, jobs=2, mesh=False)
    assert [s.n for s in r.steps] == [4, 8] and [s.runs for s in r.steps] == [16, 32]
    assert len(r.samples) == 32 and r.converged_at is None
    step = 4
    rows = r.samples.iloc[np.sort(np.concatenate([np.arange(0, 32, step), np.arange(3, 32, step)]))]
    w = (rows["plate.width"].to_numpy() - 0.178) / 0.002
    e = (rows["material.youngs_modulus"].to_numpy() - 2.0e11) / 1.4e10
    a_rows = np.column_stack([w, e])[0::2]
    assert _strata(a_rows, 8) == [list(range(8))] * 2
    again = impact.uq(path, jobs=1, sizes=[8], mesh=False)
    keep = [c for c in r.samples.columns if c not in impact.TIMING_KEYS]
    assert r.samples[keep].astype(str).equals(again.samples[keep].astype(str))


@pytest.fixture(scope="module")
def two_scene_study(tmp_path_factory):
    # two of Table 2's elastic scenes on a 20 x 4 mesh, sampled on its 10 x 2 level: one
    # design of two inputs run on both, the spread checked on both meshes (reference-data is
    # linked beside the study, whose tables are read from the repository's root)
    folder = tmp_path_factory.mktemp("two-scenes")
    (folder / "reference-data").symlink_to(ROOT / "reference-data")
    t2 = ROOT / "verification" / "scenes" / "paper-table2"
    path = folder / "two.yaml"
    path.write_text(
        f"title: two\nscenes:\n  - {{scene: {t2 / 'v01.25-elastic.yaml'}, label: slow, row: '1.25'}}\n"
        f"  - {{scene: {t2 / 'v15.00-elastic.yaml'}, label: fast, row: '15'}}\n"
        "set: {mesh.nx: 20, mesh.ny: 4}\ninputs:\n"
        "  plate.thickness: {uniform: {lower: 0.0182, upper: 0.0194}, source: s}\n"
        "  material.youngs_modulus: {uniform: {lower: 2.0e11, upper: 2.14e11}, source: s}\n"
        "sampling: {method: sobol, seed: 3, sizes: [4, 8], mesh: 0.5}\n"
        "convergence: {mean: 1.0e-9, std: 1.0e-9, total_index: 1.0e-9}\n"
        "mesh_levels: [0.25, 0.5, 1.0]\noutputs:\n"
        "  impulse_Ns: {table: {file: reference-data/paper/table2.csv, column: elastic_impulse_Ns}, kind: calibration}\n")
    return path, impact.uq(path, jobs=2)


def test_a_study_of_several_scenes_runs_one_design_on_each(two_scene_study):
    _, r = two_scene_study
    assert list(r.study["outputs"]) == ["impulse_Ns [slow]", "impulse_Ns [fast]"]
    assert [s.runs for s in r.steps] == [2 * 4 * 4, 2 * 8 * 4]
    slow, fast = (r.samples[r.samples["scene"] == s] for s in ("slow", "fast"))
    inputs = ["plate.thickness", "material.youngs_modulus"]
    assert len(slow) == len(fast) == 32
    assert slow[inputs].to_numpy().tolist() == fast[inputs].to_numpy().tolist()
    # each output is its own scene's: 10 kg at 1.25 and 15 m/s rebound with about 2 m v0
    assert r.final.stats["impulse_Ns [slow]"]["mean"] == pytest.approx(24.5, rel=0.03)
    assert r.final.stats["impulse_Ns [fast]"]["mean"] == pytest.approx(290.0, rel=0.03)
    # the sampled runs are on the 10 x 2 level, S on the declared 20 x 4 mesh
    assert set(slow["n_elements"]) == {20} and r.nominal[0]["n_elements"] == 80
    assert r.nominal_value("impulse_Ns [fast]") == r.nominal[1]["impulse_Ns"]
    assert set(r.mesh) == set(r.study["outputs"])


def test_the_spread_check_carries_the_samples_onto_the_declared_mesh(two_scene_study):
    _, r = two_scene_study
    for oid, c in r.spread_check.items():
        assert c["points"] == 8 and c["level"] == 0.5
        assert c["ratio"] == pytest.approx(c["std_declared"] / c["std_sampled"])
        y = r.declared_samples(oid)
        assert r.u_input(oid) == pytest.approx(r.final.stats[oid]["std"] * c["ratio"], rel=1e-12)
        assert float(np.std(y, ddof=1)) == pytest.approx(r.u_input(oid), rel=1e-12)
        raw = np.asarray(r.final.stats[oid]["samples"])
        assert np.mean(y) - np.mean(raw) == pytest.approx(
            c["mean_declared"] - c["mean_sampled"] + (c["ratio"] - 1) * (np.mean(raw) - c["mean_sampled"]))


def test_the_page_of_a_study_of_several_scenes(two_scene_study, tmp_path):
    from impact._uq_page import budget_rows, study_section

    path, r = two_scene_study
    rows = budget_rows(r, str(path))
    assert [(b["label"], b["printed"]) for b in rows] == [("impulse_Ns, slow", "24.46"),
                                                          ("impulse_Ns, fast", "294.2")]
    assert all(b["u_input"] == r.u_input(b["key"]) and b["kind"] == "calibration" for b in rows)
    page = study_section(r, str(path), tmp_path, "two")
    assert "2 scenes, the same design on each" in page
    assert "### The spread on the sampling mesh and on the declared mesh" in page
    assert (tmp_path / "two-indices.svg").exists() and (tmp_path / "two-cdf-convergence.svg").exists()


def test_a_weakly_correlated_spread_check_is_said(two_scene_study):
    import dataclasses

    from impact._uq_page import _spread_table

    _, r = two_scene_study
    check = {oid: dict(c) for oid, c in r.spread_check.items()}
    assert "Correlation below" not in _spread_table(dataclasses.replace(
        r, spread_check={oid: {**c, "corr": 0.99} for oid, c in check.items()}))
    check["impulse_Ns [slow]"]["corr"] = 0.2
    text = _spread_table(dataclasses.replace(r, spread_check=check))
    assert "Correlation below 0.9 (impulse_Ns [slow])" in text
