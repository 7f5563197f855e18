"""`impact.uq` checks a study's declaration whole before its first run (defects reported by a
user: an unknown output key ran every sample and then died with a bare KeyError; `seed: -1`
said "expected an integer"; a Poisson ratio range reaching 0.5 was refused as "not a settable
scene key"). Each refusal gives file:line:col, the field, the value and what is allowed, and
no run starts (the native run is replaced by one that fails the test). Against: the solver's
own rules (solver/src/input/validate: `material.poisson_ratio` in (-1, 0.5) exclusive), the
scene's keys (solver/scene.schema.json), the seed's type (an unsigned 64-bit integer), and the
summaries of real runs of every CI scene and the paper's scenes (the outputs the check allows
are exactly the numbers a run writes)."""
from __future__ import annotations

import json
import re

import pytest
from helpers import ROOT, write_study

import impact
from impact import _impact

WIDTH = "  plate.width: {uniform: {lower: 0.178, upper: 0.180}, source: s}\n"
POISSON_RULE = r"material\.poisson_ratio = {v}: must lie in \(-1, 0\.5\) \(exclusive\)"


@pytest.fixture
def no_runs(monkeypatch):
    """Any run of the solver fails the test: the declaration must be refused before."""
    def run(*args, **kwargs):
        raise AssertionError("a run started before the declaration was refused")

    monkeypatch.setattr(_impact, "simulate", run)


@pytest.mark.parametrize("outputs, key", [
    ("{impulse_Nss: {}}", r"impulse_Nss"),
    ("{impulse_Ns: {}, max_von_mises_Pa.Z: {}}", r"max_von_mises_Pa\.Z"),
])
def test_an_unknown_output_is_refused_before_any_run(tmp_path, no_runs, outputs, key):
    path = write_study(tmp_path, WIDTH, outputs=outputs)
    with pytest.raises(impact.SceneError) as e:
        impact.uq(path, jobs=1)
    assert re.match(rf".*study\.yaml:8:\d+: outputs\.{key}: not a number of the summary of "
                    r".*paper-plastic\.yaml: an output is one of its numeric keys: impulse_Ns, "
                    r"peak_contact_force_N, .*max_von_mises_Pa\.A, ", str(e.value)), str(e.value)


def test_an_output_shared_by_a_base_study_is_named_where_it_is_declared(tmp_path, no_runs):
    base = write_study(tmp_path, WIDTH, outputs="{impulse_N: {}}").rename(tmp_path / "base.yaml")
    scene = ROOT / "verification" / "scenes" / "paper-plastic.yaml"
    (tmp_path / "derived.yaml").write_text(
        f"title: d\nscene: {scene}\nbased_on: {{study: {base.name}}}\n"
        "sampling: {method: sobol, seed: 1, sizes: [4, 8]}\n"
        "convergence: {mean: 0.01, std: 0.1, total_index: 0.1}\nmesh_levels: [0.25, 0.5, 1.0]\n")
    with pytest.raises(impact.SceneError, match=r"base\.yaml:8:\d+: outputs\.impulse_N: not a number"):
        impact.uq(tmp_path / "derived.yaml", jobs=1)


@pytest.mark.parametrize("seed, shown", [("-1", "-1"), ("1.5", "1.5"), ("abc", '"abc"'),
                                         ("18446744073709551616", r"1\.8446744073709552e\+19")])
def test_the_seed_must_be_a_non_negative_integer(tmp_path, no_runs, seed, shown):
    path = write_study(tmp_path, WIDTH, sampling=f"{{method: sobol, seed: {seed}, sizes: [4, 8]}}")
    with pytest.raises(impact.SceneError,
                       match=rf"study\.yaml:5:\d+: sampling\.seed = {shown}: must be a non-negative "
                             r"integer, 0 to 18446744073709551615 \(the seed of"):
        impact.uq(path, jobs=1)


@pytest.mark.parametrize("distribution, field, value", [
    ("uniform: {lower: 0.3, upper: 0.5}", "uniform.upper", "0.5"),
    ("uniform: {lower: 0.45, upper: 0.55}", "uniform.upper", "0.55"),
    ("truncated: {normal: {mean: 0.45, std: 0.02}, lower: 0.4, upper: 0.5}", "truncated.upper", "0.5"),
    ("normal: {mean: 0.55, std: 0.01}", "normal.mean", "0.55"),
])
def test_a_poisson_ratio_reaching_one_half_is_refused_by_the_solvers_rule(tmp_path, no_runs,
                                                                         distribution, field, value):
    path = write_study(tmp_path, f"  material.poisson_ratio: {{{distribution}, source: s}}\n")
    with pytest.raises(impact.SceneError) as e:
        impact.uq(path, jobs=1)
    message = str(e.value)
    assert re.match(rf".*study\.yaml:4:\d+: inputs\.material\.poisson_ratio\.{re.escape(field)} = "
                    rf"{re.escape(value)}: .*paper-plastic\.yaml does not allow it: "
                    + POISSON_RULE.format(v=re.escape(value)) + "$", message), message
    assert "settable" not in message


def test_a_poisson_ratio_range_inside_the_rule_is_accepted(tmp_path):
    path = write_study(tmp_path, "  material.poisson_ratio: {uniform: {lower: 0.25, upper: 0.35}, source: s}\n")
    decl = impact._uq.read(path)
    assert [i["key"] for i in decl["inputs"]] == ["material.poisson_ratio"]


def test_a_normal_poisson_ratio_that_draws_beyond_one_half_is_refused_before_any_run(tmp_path, no_runs):
    # mean 0.3 is allowed; one standard deviation of 0.2 above it is not, and the design of
    # N = 8 (24 runs) draws well beyond it
    path = write_study(tmp_path, "  material.poisson_ratio: {normal: {mean: 0.3, std: 0.2}, source: s}\n")
    with pytest.raises(impact.SceneError) as e:
        impact.uq(path, jobs=1)
    message = str(e.value)
    assert re.match(r".*study\.yaml:4:\d+: inputs\.material\.poisson_ratio\.normal: the design draws "
                    r"0\.\d+ \(the largest of its 36 values, N up to 8\), which .*paper-plastic\.yaml "
                    r"does not allow: " + POISSON_RULE.format(v=r"0\.\d+")
                    + r"; narrow the distribution or truncate it", message), message


def test_an_unknown_input_key_lists_the_keys_allowed(tmp_path, no_runs):
    path = write_study(tmp_path, "  material.plastcity.yield_stress: {uniform: {lower: 1.0e8, upper: 2.0e8}, source: s}\n")
    with pytest.raises(impact.SceneError,
                       match=r"study\.yaml:4:\d+: inputs\.material\.plastcity\.yield_stress: not a scene "
                             r"key: `material` has no key `plastcity`; its keys: density, plasticity, "
                             r"poisson_ratio, youngs_modulus$"):
        impact.uq(path, jobs=1)


def _numbers(summary: dict, prefix: str = "") -> tuple[set[str], set[str]]:
    """The dotted keys of a summary that hold numbers, and those that hold null."""
    numbers, nulls = set(), set()
    for k, v in summary.items():
        if isinstance(v, dict):
            n, z = _numbers(v, f"{prefix}{k}.")
            numbers |= n
            nulls |= z
        elif isinstance(v, (int, float)) and not isinstance(v, bool):
            numbers.add(prefix + k)
        elif v is None:
            nulls.add(prefix + k)
    return numbers, nulls


# The wall's keys that are null while the body is still on the wall at the end.
NULL_UNTIL_RELEASE = {"wall.release_time_s", "wall.rebound_velocity_mps"}
SCENES = sorted((ROOT / "scripts" / "ci-scenes").glob("*.yaml")) + [
    ROOT / "verification" / "scenes" / name
    for name in ("paper-plastic.yaml", "paper-elastic-surface.yaml", "paper-pulse-elastic.yaml")]


@pytest.mark.filterwarnings("ignore::impact.SceneWarning")
@pytest.mark.parametrize("scene", SCENES, ids=lambda p: p.name)
def test_the_outputs_allowed_are_the_numbers_a_run_writes(scene):
    overrides = {"mesh.nx": 20, "mesh.ny": 4} if scene.parent.name == "scenes" else None
    summary = impact.simulate(scene, threads=1, overrides=overrides).summary
    numbers, nulls = _numbers(summary)
    allowed = set(_impact.summary_keys(_impact.read_scene(str(scene)), str(scene),
                                       overrides and json.dumps(overrides)))
    assert numbers <= allowed, f"numbers the check refuses: {sorted(numbers - allowed)}"
    assert allowed <= numbers | (nulls & NULL_UNTIL_RELEASE), \
        f"keys the check allows that the run does not write as numbers: {sorted(allowed - numbers)}"
