"""The Python FE's step re-estimated at every step (ALGORITHM.md section 6b, `time.dt.update:
every-step`) against identities of central differences with unequal steps: the trapezoidal wall
impulse equals the bar's momentum change over steps of unequal length; with equal steps the path
is the fixed-step one; the run lands on its end with rows at the first step at or past each
`k every`; on a crushing Taylor bar the step follows the mesh where a fixed step is refused; the
default of update (every-step on the wall under finite kinematics); the 1e-3 floor; the scene's
refusals. Each check names the wrong model it rejects."""
import math

import numpy as np
import pytest

from helpers import scene
from indep_fe import solver as solver_mod
from indep_fe.scene import SceneError
from indep_fe.solver import UnstableRun, simulate
from indep_fe.step import REACH, StepPlan, StepTooSmall, velocity_step

E, RHO, L, A, V = 200.0e9, 7800.0, 0.1, 0.005, 10.0   # Pa, kg/m^3, m, m (half-width), m/s
BAR = {"plate": {"length": 2 * A, "width": 1.0, "thickness": L, "ends": "free"},
       "material": {"density": RHO, "youngs_modulus": E, "poisson_ratio": 0.0},
       "mesh": {"nx": 2, "ny": 20, "element": "q4-sri", "model": "half"},
       "kinematics": "finite",
       "load": {"wall": {"velocity": V}},
       "time": {"end": 6.0e-5, "dt": {"cfl": 0.9, "update": "every-step"}},
       "output": {"every": 2.0e-6}}
# the coarse copper Taylor bar of scripts/ci-scenes/axisym-wall-taylor-every-step.yaml
TAYLOR = {"geometry": "axisymmetric",
          "plate": {"length": 6.4e-3, "width": 1.0, "thickness": 32.4e-3, "ends": "free"},
          "material": {"density": 8970.0, "youngs_modulus": 110.0e9, "poisson_ratio": 0.3,
                       "plasticity": {"yield_stress": 314.0e6, "hardening": {"linear": 0.0}}},
          "mesh": {"nx": 4, "ny": 12, "element": "q4-1pt", "model": "half"},
          "kinematics": "finite",
          "load": {"wall": {"velocity": 227.0}},
          "time": {"end": 4.0e-5, "dt": {"cfl": 0.9, "update": "every-step"}},
          "output": {"every": 5.0e-7}}


def _momentum_error(res) -> float:
    """|impulse - M (V + v_rebound)| / impulse for the bar released before the end (F_N = 0):
    the trapezoid sum (F_n-1 + F_n) dt_{n-1/2} / 2 equals sum h_n F_n exactly when the velocity
    step is h_n = (dt_{n-1/2} + dt_{n+1/2}) / 2 (internal forces sum to zero)."""
    wall = res.summary["wall"]
    assert wall["release_time_s"] is not None
    mass = RHO * 2 * A * 1.0 * L
    return abs(res.summary["impulse_Ns"] - mass * (V + wall["rebound_velocity_mps"])) / \
        res.summary["impulse_Ns"]


def test_wall_impulse_is_the_momentum_change_over_unequal_steps(monkeypatch):
    """Within 1e-12 (measured 0.0, the steps ranging over dt_max / dt_min = 1 + 4.9e-4: the
    tolerance is round-off). The velocity step h_n = dt_{n+1/2} instead of the mean breaks the
    identity by 6.1e-7 (asserted > 1e-7)."""
    res = simulate(scene(**BAR))
    s = res.summary
    assert s["dt_update"] == "every-step" and s["dt_max_s"] > s["dt_min_s"]
    assert _momentum_error(res) < 1e-12
    monkeypatch.setattr(solver_mod, "velocity_step", lambda prev, dt: 0.5 * dt if prev is None else dt)
    assert _momentum_error(simulate(scene(**BAR))) > 1e-7


def test_equal_steps_reproduce_the_fixed_step_path(monkeypatch):
    """With the estimate held at the first step, every-step is the fixed-step run up to its last
    row: every column but time_s (summed, not n dt: within 1e-15 of the end) bit-identical, the
    same steps and rows; the last row differs only as the fixed run overshoots time.end (to
    6.04e-5 s) where every-step cuts its last step onto it. A velocity step of dt_{1/2} (not
    dt_{1/2} / 2) at n = 0 would change every column."""
    assert all(velocity_step(d, d) == d for d in np.geomspace(1e-12, 1e-3, 997))
    fixed = simulate(scene(**{**BAR, "time": {"end": 6.0e-5, "dt": {"cfl": 0.9, "update": "once"}}}))
    dt = fixed.summary["dt_s"]
    monkeypatch.setattr(StepPlan, "estimate", lambda self, u, n: dt)
    held = simulate(scene(**BAR))
    assert held.summary["n_steps"] == fixed.summary["n_steps"]
    assert len(held.rows) == len(fixed.rows)
    for col in fixed.columns:
        a, b = fixed.column(col), held.column(col)
        if col == "time_s":
            assert np.max(np.abs(a - b)[:-1]) <= 1e-15 * 6.0e-5
            assert a[-1] > 6.0e-5 and b[-1] == pytest.approx(6.0e-5, rel=1e-15)
        elif col != "energy_balance_error":
            assert np.array_equal(a[:-1], b[:-1]), col


def test_lands_on_the_end_with_rows_at_each_k_every():
    """Every step's row (no `every`): t_{n+1} - t_n is the dt_s column of row n (the step from
    t_n; to the round-off of the differences, 1e-12 relative), the step before the end cut (shorter than its estimate), the run ends at time.end
    within 1e-15 relative. With `every`: the rows are t_0, the first step at or past each
    k every (within 1e-9 dt_{n+1/2}) and the last. A run that stops at n dt_first would end
    off the end by up to a step; rows by n dt_first would drift with the steps."""
    res = simulate(scene(**{**BAR, "output": {}}))
    t, dts = res.column("time_s"), res.column("dt_s")
    assert np.allclose(np.diff(t)[:-1], dts[:-2], rtol=1e-12, atol=0.0)
    # the cut step (3.3e-8 s here, after steps of 4.44e-7 s) and the column holding it
    assert np.diff(t)[-1] == pytest.approx(dts[-2], rel=1e-9) and dts[-2] < 0.5 * dts[-3]
    assert t[-1] == pytest.approx(6.0e-5, rel=1e-15)
    assert res.summary["final_time_s"] == t[-1]
    every = 2.0e-6
    rows = simulate(scene(**BAR)).column("time_s")
    want = [0]
    for k in range(1, 31):
        hit = next(n for n in range(len(t)) if t[n] >= k * every - REACH * dts[n])
        want.append(hit)
    expect = t[sorted(set(want) | {len(t) - 1})]
    assert np.array_equal(rows, expect)


def test_the_step_follows_a_crushing_taylor_bar():
    """The fixed step at cfl 0.9 is refused by section 3c's deformed-step check once the foot
    crushes; every-step runs to the end with the step falling to under 0.35 of the first
    (measured 0.294) and the energy balanced within 5e-3 (measured 1.2e-3)."""
    with pytest.raises(UnstableRun, match="deformed mesh's stable step"):
        simulate(scene(**{**TAYLOR, "time": {"end": 4.0e-5, "dt": {"cfl": 0.9, "update": "once"}}}))
    res = simulate(scene(**TAYLOR))
    s = res.summary
    assert s["dt_min_s"] / s["dt_s"] < 0.35 and s["dt_max_s"] == s["dt_s"]
    assert s["max_energy_balance_error"] < 5e-3
    assert s["final_time_s"] == pytest.approx(4.0e-5, rel=1e-15)


def test_every_step_is_the_default_of_a_finite_body_on_the_wall():
    """time.dt.update not written: every-step for the finite Taylor bar given a cfl (its foot
    crushes), once under small kinematics and with a fixed step; written, it is kept. A reader
    that defaulted to once everywhere (the paper's reading) fails the first assertion."""
    def update(**over):
        return scene(**{**TAYLOR, **over}).time.update
    omitted = {"time": {"end": 4.0e-5, "dt": {"cfl": 0.9}}}
    assert update(**omitted) == "every-step"
    assert update(**omitted, kinematics="small") == "once"
    assert update(time={"end": 4.0e-5, "dt": {"fixed": 1.0e-9}}) == "once"
    assert update(time={"end": 4.0e-5, "dt": {"cfl": 0.9, "update": "once"}}) == "once"


class _Shrinking:
    """A stand-in for the finite kinematics: the ratio sqrt(S_ref / S_cur) is u[0] on element 7."""
    def step_factor(self, u):
        return float(u[0]), 7


def test_floor_names_the_element_and_the_step():
    """At 1e-3 of the first step the run stops with the element, its ratio and the step; just
    above the floor it goes on. A floor at 1e-3 of dt_plate instead of the first step (twice it
    here, cfl 0.5) would already stop the ratio 1.01e-3."""
    plan = StepPlan(cfl=0.5, dt_plate=2.0e-7, finite=_Shrinking())
    assert plan.estimate(np.array([1.0]), 0) == pytest.approx(1.0e-7, rel=1e-15)
    assert plan.estimate(np.array([1.01e-3]), 5) == pytest.approx(1.01e-10, rel=1e-12)
    with pytest.raises(StepTooSmall, match=r"step 9 .*element 7.*9\.9"):
        plan.estimate(np.array([0.99e-3]), 9)


@pytest.mark.parametrize("change", [{"kinematics": "small"},
                                    {"time.dt": {"fixed": 1e-7, "update": "every-step"}},
                                    {"time.dt.update": "each-step"}])
def test_refusals(change):
    """every-step needs finite kinematics and a cfl; the update is once | every-step."""
    with pytest.raises(SceneError):
        scene(**{**BAR, **{k: v for k, v in change.items()}})


def test_floor_is_a_clear_cli_error(tmp_path, monkeypatch, capsys):
    """Through the CLI the floor is an error line naming the element (exit 2), not a traceback:
    the deformed-step ratio forced to 1 at t_0 and 1e-4 after (a stand-in for a crushed
    element)."""
    import yaml
    from indep_fe.__main__ import main
    from indep_fe.finite import FiniteKinematics
    calls = []

    def ratio(self, u):
        calls.append(1)
        return (1.0 if len(calls) == 1 else 1e-4), 3

    monkeypatch.setattr(FiniteKinematics, "step_factor", ratio)
    path = tmp_path / "bar.yaml"
    path.write_text(yaml.safe_dump(BAR))
    assert main(["simulate", str(path), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("indep_fe: error: at step 1") and "element 3" in err
