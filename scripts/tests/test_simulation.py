import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from helpers import PLASTIC, scene
from indep_fe.elements import (elastic_matrix, element_dofs, element_stiffness, formulation,
                               kinematics)
from indep_fe.material import lame
from indep_fe.mesh import build_mesh
from indep_fe.scene import load_scene
from indep_fe.solver import history_columns, simulate, steps_for

SCRIPTS = Path(__file__).resolve().parents[1]
EXAMPLE_YAML = """
plate: {length: 0.200, width: 0.200, thickness: 0.020}
material:
  density: 7850.0
  youngs_modulus: 207.0e9
  poisson_ratio: 0.3
  plasticity:                      # omitted for an elastic run
    yield_stress: 250.0e6
    hardening: {linear: 1.5e9}     # tangent modulus E_t, Pa
mesh: {nx: 80, ny: 16, element: q4-sri, model: half}
load:
  impactor:
    mass: 18.0
    velocity: 10.0
    nose_radius: 0.010
    youngs_modulus: 207.0e9
    poisson_ratio: 0.3
    contact_law: {paper: {length_unit: 1.0}}   # or {johnson: {datum_depth: 0.010}}
    indentation_datum: mid-plane
time:
  end: 3.0e-3
  dt: {cfl: 0.8}
output:
  every: 1.0e-6
  probes: {A: {x: 0.100, y: 0.0}}
  fields: {every: 1.0e-4}          # VTK output: ignore in Python
"""

SPEC_COLUMNS = ["time_s", "contact_force_N", "indentation_m", "impactor_displacement_m",
                "impactor_velocity_mps", "top_uy_m", "mid_uy_m", "bottom_uy_m",
                "A_sxx_Pa", "A_syy_Pa", "A_sxy_Pa", "A_szz_Pa", "A_von_mises_Pa",
                "plate_kinetic_J", "impactor_kinetic_J", "strain_energy_J", "plastic_work_J",
                "hourglass_energy_J", "contact_energy_J", "external_work_J",
                "energy_balance_error"]


def test_example_scene_parses(tmp_path):
    p = tmp_path / "s.yaml"
    p.write_text(EXAMPLE_YAML)
    sc = load_scene(p)
    assert sc.material.youngs_modulus == 207.0e9      # PyYAML reads '207.0e9' as a string
    assert sc.material.plasticity.linear_tangent == 1.5e9
    assert sc.mesh.element == "q4-sri" and sc.mesh.grading == 1.0 and sc.mesh.hourglass == 0.05
    assert sc.impactor.contact_law.kind == "paper" and sc.impactor.force_node == "mid-plane"
    assert sc.time.end == 3.0e-3 and sc.time.cfl == 0.8 and sc.time.limit == 0.05
    assert [(p.name, p.x, p.y) for p in sc.output.probes] == [("A", 0.1, 0.0)]


def test_history_layout():
    sc = scene()
    res = simulate(sc)
    assert res.columns == SPEC_COLUMNS == history_columns(["A"])
    dt = res.summary["dt_s"]
    n = res.summary["n_steps"]
    assert n == steps_for(3.0e-4, dt)
    t = res.column("time_s")
    expected = sorted({0} | {steps_for(k * 1e-5, dt) for k in range(1, 31)} | {n})
    assert np.allclose(t / dt, expected, rtol=0, atol=1e-9)
    first = res.rows[0]
    assert first[SPEC_COLUMNS.index("impactor_velocity_mps")] == 10.0
    assert first[SPEC_COLUMNS.index("impactor_kinetic_J")] == 900.0
    assert res.summary["n_elements"] == 40
    for key in ["impulse_Ns", "peak_contact_force_N", "max_plate_displacement_m",
                "contact_intervals_s", "contact_duration_s", "final_impactor_velocity_mps",
                "max_von_mises_Pa", "max_energy_balance_error", "dt_s", "n_steps",
                "n_elements", "wall_time_s"]:
        assert key in res.summary
    assert set(res.summary["max_von_mises_Pa"]) == {"A"}


CASES = [(el, law, pl) for el in ["q4-full", "q4-sri", "q4-1pt"]
         for law in [{"paper": {"length_unit": 1.0}}, {"johnson": {"datum_depth": 0.01}}]
         for pl in [False, True]]


@pytest.mark.parametrize("element,law,plastic", CASES)
def test_impulse_identity_and_energy(element, law, plastic):
    sc = scene(**{"mesh.element": element, "load.impactor.contact_law": law,
                  "material.plasticity": PLASTIC if plastic else None, "time.end": 6e-4})
    s = simulate(sc).summary
    # impulse = m (v0 - v_final) is an identity of eqs (19)-(20) with the trapezoidal integral
    assert s["impulse_Ns"] == pytest.approx(18.0 * (10.0 - s["final_impactor_velocity_mps"]),
                                            rel=1e-12)
    assert s["impulse_Ns"] > 50
    assert s["max_energy_balance_error"] < (2e-4 if plastic else 1e-4)


def test_energy_balance_small_elastic_impact():
    sc = scene(**{"mesh.nx": 20, "mesh.ny": 4, "time.end": 1.0e-3})
    res = simulate(sc)
    assert res.summary["max_energy_balance_error"] < 2e-5
    total = sum(res.column(c) for c in SPEC_COLUMNS[13:19])
    assert np.allclose(total, 900.0, rtol=2e-5)
    assert res.column("plastic_work_J").max() == 0.0


def test_force_and_datum_pairing_energy():
    """reference-data/paper/README.md: force on the top node with alpha from the mid-plane does not conserve energy,
    a matched pair does (elasto-plastic, where the through-thickness crush is large)."""
    base = {"material.plasticity": PLASTIC, "time.end": 6e-4}
    top = simulate(scene(**base, **{"load.impactor.indentation_datum": "top-surface"})).summary
    mixed = simulate(scene(**base, **{"load.impactor.force_node": "top-surface"})).summary
    assert top["max_energy_balance_error"] < 1e-3
    assert mixed["max_energy_balance_error"] > 3 * top["max_energy_balance_error"]


@pytest.mark.parametrize("element", ["q4-sri", "q4-1pt"])
@pytest.mark.parametrize("plastic", [False, True])
def test_half_model_equals_full_model(element, plastic):
    over = {"mesh.element": element, "mesh.grading": 2.0, "time.end": 2e-4,
            "material.plasticity": PLASTIC if plastic else None,
            "output.probes": {"A": {"x": 0.09, "y": 0.0}, "B": {"x": 0.11, "y": 0.0}}}
    half = simulate(scene(**over))
    full = simulate(scene(**over, **{"mesh.model": "full", "mesh.nx": 20}))
    assert half.summary["dt_s"] == pytest.approx(full.summary["dt_s"], rel=1e-13)
    for col in ["contact_force_N", "mid_uy_m", "top_uy_m", "plate_kinetic_J", "strain_energy_J",
                "plastic_work_J", "hourglass_energy_J", "A_von_mises_Pa"]:
        a, b = half.column(col), full.column(col)
        assert np.allclose(a, b, rtol=0, atol=1e-9 * max(np.abs(a).max(), 1e-300)), col
    # the mirrored probe B of the half model is probe A's mirror image in the full model
    assert np.allclose(half.column("B_sxx_Pa"), half.column("A_sxx_Pa"))
    assert np.allclose(full.column("B_sxx_Pa"), full.column("A_sxx_Pa"), rtol=1e-8,
                       atol=1e-8 * np.abs(full.column("A_sxx_Pa")).max())


def test_after_contact_stop():
    sc = scene(**{"time.end": {"after_contact": 5e-5}, "mesh.nx": 20, "mesh.ny": 4})
    res = simulate(sc)
    s = res.summary
    dt = s["dt_s"]
    end = s["contact_intervals_s"][-1][1]
    assert end is not None and res.column("contact_force_N")[-1] == 0.0
    # first step n with t_n - t_sep >= after (t_sep: first t_n with F = 0 after contact)
    n_end = round(end / dt)
    n = s["n_steps"]
    assert n * dt - n_end * dt >= 5e-5 - 1e-9 * dt > (n - 1) * dt - n_end * dt
    assert s["stop_reason"] == "after_contact"
    # a hard limit before that wins
    res2 = simulate(scene(**{"time.end": {"after_contact": 5e-5}, "time.limit": 1e-4}))
    assert res2.summary["n_steps"] == steps_for(1e-4, res2.summary["dt_s"])


def test_pulse_load():
    sc = scene(**{"load.impactor": None, "load.pulse": {"force": 86.5e3, "duration": 1.0e-4},
                  "time.end": 3e-4})
    res = simulate(sc)
    s = res.summary
    dt = s["dt_s"]
    F = res.column("contact_force_N")
    t = res.column("time_s")
    assert np.all(F[t < 1e-4 - 1e-12] == 86.5e3) and np.all(F[t >= 1e-4] == 0.0)
    assert s["impulse_Ns"] == pytest.approx(86.5e3 * 1e-4, abs=86.5e3 * dt)
    assert s["final_impactor_velocity_mps"] is None
    # pulse scenes omit the impactor columns (not empty cells)
    assert res.columns == [c for c in SPEC_COLUMNS if c not in
                           ("indentation_m", "impactor_displacement_m", "impactor_velocity_mps")]
    assert res.column("external_work_J")[-1] > 0
    # the balance error is relative to the largest energy of the whole run, so it is small
    # from the first step on (no start-up transient of a running denominator)
    err = res.column("energy_balance_error")
    assert err.max() < 1e-3
    assert s["max_energy_balance_error"] >= err.max()
    # the pulse interval ends when the force drops to 0
    assert s["contact_intervals_s"] == [[0.0, steps_for(1e-4, dt) * dt]]


def test_balance_error_uses_the_whole_run_scale():
    res = simulate(scene(**{"mesh.nx": 20, "mesh.ny": 4, "time.end": 2e-4, "output.every": None,
                            "material.plasticity": PLASTIC}))      # a row every step
    cols = res.columns
    E = sum(res.column(c) for c in cols[cols.index("plate_kinetic_J"):cols.index("external_work_J")])
    imb = np.abs(E - E[0] - res.column("external_work_J"))
    S = max(np.abs(E).max(), np.abs(res.column("external_work_J")).max())
    assert np.allclose(res.column("energy_balance_error"), imb / S, rtol=1e-12, atol=0)


def test_open_contact_interval_closes_at_the_final_time():
    res = simulate(scene(**{"time.end": 1e-4}))        # still in contact at 0.1 ms
    s = res.summary
    assert res.column("contact_force_N")[-1] > 0
    assert s["contact_intervals_s"][-1][1] == pytest.approx(s["final_time_s"], rel=0, abs=0)
    assert s["contact_duration_s"] == s["final_time_s"]


def test_no_contact_duration_is_zero():
    res = simulate(scene(**{"load.impactor": None, "load.pulse": {"force": 0.0, "duration": 1e-4},
                            "time.end": 1e-5}))
    assert res.summary["contact_intervals_s"] == [] and res.summary["contact_duration_s"] == 0.0


def test_probe_columns_sorted_by_name():
    res = simulate(scene(**{"time.end": 1e-5, "output.probes": {"Z": {"x": 0.05, "y": 0.0},
                                                               "B": {"x": 0.1, "y": 0.0}}}))
    probe_cols = [c for c in res.columns if c.endswith("_Pa")]
    assert probe_cols == [f"{p}_{q}" for p in "BZ"
                          for q in ("sxx_Pa", "syy_Pa", "sxy_Pa", "szz_Pa", "von_mises_Pa")]


def _static_solution(element, nx, ny, P=1e5):
    sc = scene(**{"mesh.nx": nx, "mesh.ny": ny, "mesh.element": element})
    pm = build_mesh(sc.plate, sc.mesh)
    kin = kinematics(pm)
    lam, mu = lame(207e9, 0.3)
    form = formulation(element, pm, kin, 0.2, lam, mu, 0.05)
    Ke = element_stiffness(form, elastic_matrix(lam, mu))
    ed = element_dofs(pm)
    nd = 2 * pm.n_nodes
    K = sp.coo_matrix((Ke.ravel(), (np.repeat(ed, 8, 1).ravel(), np.tile(ed, (1, 8)).ravel())),
                      shape=(nd, nd)).tocsr()
    free = np.setdiff1d(np.arange(nd), pm.fixed_dofs)
    f = np.zeros(nd)
    f[2 * pm.top + 1] = -P / 2
    u = np.zeros(nd)
    u[free] = spla.spsolve(K[free][:, free].tocsc(), f[free])
    return u[2 * pm.mid + 1]


def test_static_clamped_beam_vs_timoshenko():
    P, L, h, W, E, nu = 1e5, 0.2, 0.02, 0.2, 207e9, 0.3
    mu = E / (2 * (1 + nu))
    d = P * L ** 3 / (192 * E / (1 - nu ** 2) * W * h ** 3 / 12) + P * L / (4 * 5 / 6 * mu * W * h)
    assert -_static_solution("q4-sri", 20, 4) == pytest.approx(d, rel=0.03)
    full = [-_static_solution("q4-full", nx, ny) for nx, ny in [(10, 2), (20, 4), (40, 8)]]
    assert full[0] < full[1] < full[2] < 1.01 * d      # full integration converges from below


def test_step_load_dynamic_amplification():
    """Suddenly applied constant load: the first peak of the mid-plane deflection is close
    to twice the static one (single dominant mode), and they are computed independently."""
    static = _static_solution("q4-sri", 20, 4)
    sc = scene(**{"mesh.nx": 20, "mesh.ny": 4, "load.impactor": None,
                  "load.pulse": {"force": 1e5, "duration": 1.0}, "time.end": 1.2e-3})
    res = simulate(sc)
    assert res.column("mid_uy_m").min() / static == pytest.approx(2.0, abs=0.06)


def test_fixed_dt_above_critical_refused():
    with pytest.raises(ValueError, match="critical"):
        simulate(scene(**{"time.dt": {"fixed": 1e-5}}))


def test_cli(tmp_path):
    p = tmp_path / "s.yaml"
    p.write_text(EXAMPLE_YAML.replace("nx: 80, ny: 16", "nx: 8, ny: 2")
                 .replace("end: 3.0e-3", "end: 1.0e-4"))
    out = tmp_path / "out"
    r = subprocess.run([sys.executable, "-m", "indep_fe", "simulate", str(p), "--out", str(out)],
                       cwd=SCRIPTS, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    header = (out / "history.csv").read_text().splitlines()[0].split(",")
    assert header == SPEC_COLUMNS
    s = json.loads((out / "summary.json").read_text())
    assert s["n_elements"] == 16 and math.isfinite(s["impulse_Ns"])


def test_pulse_end_uses_the_force_applied_at_the_next_step():
    """F_pulse(t_{n+1}) with t_{n+1} = (n+1) dt, not t_n + dt: with dt = 5e-7 and a 5e-4 s
    pulse, 999 dt + dt rounds below 5e-4 while 1000 dt does not. The trapezoidal impulse must
    match the applied-force history (F at steps 0..999, 0 from step 1000 on)."""
    dt, F = 5e-7, 86.5e3
    assert 999 * dt + dt < 5e-4 <= 1000 * dt
    sc = scene(**{"load.impactor": None, "load.pulse": {"force": F, "duration": 5.0e-4},
                  "time.end": 5.5e-4, "time.dt": {"fixed": dt}, "output.every": None})
    res = simulate(sc)
    f = res.column("contact_force_N")
    assert f[999] == F and f[1000] == 0.0
    assert res.summary["impulse_Ns"] == pytest.approx(F * 999.5 * dt, rel=1e-13)
    assert res.summary["contact_intervals_s"] == [[0.0, 1000 * dt]]
