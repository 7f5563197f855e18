"""`impact.uq` (issue 27): a study's declaration is validated with file:line:col messages
(bad distributions, a missing source, sizes that do not double, a key the scene refuses); the
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
from helpers import without_timing

import impact
from impact import _impact
from impact._distributions import ppf
from impact._uq_design import saltelli

ROOT = Path(__file__).resolve().parents[2]
CI_STUDY = ROOT / "verification" / "uq" / "ci-coarse.yaml"


def write_study(tmp_path: Path, inputs: str, sampling: str = "{method: sobol, seed: 1, sizes: [4, 8]}") -> Path:
    scene = ROOT / "verification" / "scenes" / "paper-plastic.yaml"
    text = (f"title: t\nscene: {scene}\ninputs:\n{inputs}sampling: {sampling}\n"
            "convergence: {mean: 0.01, std: 0.1, total_index: 0.1}\n"
            "mesh_levels: [0.25, 0.5, 1.0]\noutputs: {impulse_Ns: {}}\n")
    path = tmp_path / "study.yaml"
    path.write_text(text)
    return path


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
     r"study\.yaml:4:\d+: inputs\.plate\.colour: not a settable scene key"),
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
