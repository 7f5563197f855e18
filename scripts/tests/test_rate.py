"""Strain-rate (and temperature) dependent plasticity of indep_fe (indep_fe/rate.py) against
closed forms of ALGORITHM.md section 3b, one integration point at a time:

- constant-rate uniaxial strain eps = (edot t, 0, 0, 0): each step's trial von Mises stress
  rises by 2 mu de (de = edot dt), so once the flow is steady (q no longer changes) the return
  takes dk = 2/3 de per step and the equivalent plastic strain rate is exactly 2/3 edot; the
  steady flow stress is then the closed form q = sigma_s(k) * rate factor(2/3 edot):
  Cowper-Symonds sigma_y [1 + (kdot / D)^(1/q)], Johnson-Cook A [1 + C ln(kdot / rate0)]
  (perfectly plastic static curves, E_t = 0 and B = 0, so the flow does become steady); with
  hardening, at every plastic step the backward-Euler consistency q_new = sigma_s(k_new)
  R((k_new - k_old) / dt) Theta; below Johnson-Cook's reference rate the rate factor is 1;
- the heating identity of the thermal part: T - T0 = beta w / (rho c), w the plastic work
  density q_new dk summed over the steps, and the thermal factor Theta = 1 - T*^m taken from
  the start-of-step temperature;
- the vectorised root finder (bracketed_root) against scipy's brentq on random brackets;
- the scene keys of material.plasticity.rate and their refusals;
- the outputs of section 8 on a short run: column order, summary keys, heat_J = beta W_p.
The code-to-code check against the Rust solver is scripts/ci-compare.sh (two ci-scenes).
"""
import math

import numpy as np
import pytest
from scipy.optimize import brentq

from indep_fe.material import MaterialModel, lame, von_mises
from indep_fe.rate import RateDependence, bracketed_root
from indep_fe.scene import Material, Plasticity, RateLaw, SceneError, Thermal

E, NU, RHO = 207e9, 0.3, 7850.0
LAM, MU = lame(E, NU)
KB = LAM + 2 * MU / 3
DT = 5e-7
CS = RateLaw("cowper_symonds", D=40.4, q=5.0)
JC_A, JC_B, JC_N, JC_C = 176e6, 300e6, 0.3, 0.0089
THERMAL = Thermal(293.15, 1813.15, 473.0, 0.9)


def jc(B=JC_B, thermal=None, rate0=1.0):
    return RateLaw("johnson_cook", A=JC_A, B=B, n=JC_N, C=JC_C, reference_rate=rate0,
                   m=1.1, thermal=thermal)


def material(law, sy0=250e6, tangent=0.0):
    if law.kind == "johnson_cook":
        return Material(RHO, E, NU, Plasticity(law.A, rate=law))
    return Material(RHO, E, NU, Plasticity(sy0, linear_tangent=tangent, rate=law))


def constant_rate(mat, edot, nsteps, dt=DT):
    """Uniaxial strain at a constant rate; per step (q, k, kdot, dT before, work density)."""
    model = MaterialModel(mat, 1, dt)
    rows = []
    for i in range(1, nsteps + 1):
        dT0 = model.rate.dT[0]
        s, _, dw = model.update(np.array([[edot * dt * i, 0.0, 0.0, 0.0]]), np.ones(1))
        rows.append((von_mises(s[0]), model.k[0], model.rate.kdot[0], dT0, dw, s[0].copy()))
    return model, rows


def test_cowper_symonds_steady_flow_stress():
    edot = 500.0
    sy = 250e6
    model, rows = constant_rate(material(CS, sy), edot, 400)
    q, k, kdot, _, _, s = rows[-1]
    assert kdot == pytest.approx(2 * edot / 3, rel=1e-9)
    closed = sy * (1 + (2 * edot / 3 / CS.D) ** (1 / CS.q))
    assert q == pytest.approx(closed, rel=1e-12)
    # the stress itself: uniaxial strain with p = K e and the deviator of q
    e = edot * DT * 400
    p = KB * e
    assert np.allclose(s, [p + 2 * q / 3, p - q / 3, p - q / 3, 0.0], rtol=1e-12, atol=1e-6)
    assert q > 1.5 * sy            # the rate effect is large here (a factor 1.57)


@pytest.mark.parametrize("edot", [10.0, 3000.0])
def test_johnson_cook_steady_flow_stress(edot):
    model, rows = constant_rate(material(jc(B=0.0)), edot, 400)
    q, k, kdot, *_ = rows[-1]
    assert kdot == pytest.approx(2 * edot / 3, rel=1e-9)
    assert q == pytest.approx(JC_A * (1 + JC_C * math.log(2 * edot / 3 / 1.0)), rel=1e-12)


def test_johnson_cook_below_reference_rate_is_rate_independent():
    """Rate factor 1 below the reference rate: q = A + B k^n at every plastic step."""
    model, rows = constant_rate(material(jc(rate0=1e6)), 1000.0, 300)
    plastic = [r for r in rows if r[2] > 0]
    assert len(plastic) > 250
    for q, k, kdot, *_ in plastic:
        assert kdot < 1e6
        assert q == pytest.approx(JC_A + JC_B * k ** JC_N, rel=1e-13)


@pytest.mark.parametrize("law", ["cs", "jc"])
def test_backward_euler_consistency_with_hardening(law):
    """At every plastic step q_new = sigma_s(k_new) R(kdot), kdot = (k_new - k_old) / dt."""
    if law == "cs":
        H = E * 2e9 / (E - 2e9)
        mat, sig = material(CS, 250e6, 2e9), lambda k: 250e6 + H * k
        factor = lambda r: 1 + (r / CS.D) ** (1 / CS.q)
    else:
        mat, sig = material(jc()), lambda k: JC_A + JC_B * k ** JC_N
        factor = lambda r: 1 + JC_C * math.log(max(r, 1.0))
    edot = 2000.0
    _, rows = constant_rate(mat, edot, 800)
    k_old, n_plastic = 0.0, 0
    for q, k, kdot, *_ in rows:
        if kdot > 0:
            n_plastic += 1
            assert kdot == (k - k_old) / DT
            assert q == pytest.approx(sig(k) * factor(kdot), rel=1e-13)
        k_old = k
    assert n_plastic > 700
    # the rate tends to 2/3 edot as the hardening's share of the trial increment fades
    assert rows[-1][2] == pytest.approx(2 * edot / 3, rel=0.05)


def test_heating_identity_and_thermal_softening():
    """dT = beta w / (rho c) with w = sum q_new dk; Theta from the start-of-step temperature."""
    law = jc(thermal=THERMAL)
    model, rows = constant_rate(material(law), 20000.0, 300)
    work = sum(r[4] for r in rows)                 # weight 1: the work density
    dT = model.rate.dT[0]
    assert dT == pytest.approx(THERMAL.taylor_quinney * work / (RHO * THERMAL.specific_heat),
                               rel=1e-12)
    assert model.rate.temperature()[0] == pytest.approx(THERMAL.initial_temperature + dT,
                                                        rel=1e-15)
    assert dT > 20.0                               # heating matters (Theta ~ 0.99)
    k_old = 0.0
    for q, k, kdot, dT0, dw, _ in rows:
        if kdot > 0:
            theta = 1 - (dT0 / (THERMAL.melting_temperature - THERMAL.initial_temperature)) ** 1.1
            closed = (JC_A + JC_B * k ** JC_N) * (1 + JC_C * math.log(max(kdot, 1.0))) * theta
            # 1e-12: at strains ~3 the pressure K e ~ 5e11 Pa is 1000 q, and von_mises(s)
            # takes differences of the components
            assert q == pytest.approx(closed, rel=1e-12)
            assert dw == pytest.approx(q * (k - k_old), rel=1e-12)   # q_new dk
        k_old = k
    # the same run without heating flows at a higher stress (softening by Theta < 1)
    _, cold = constant_rate(material(jc()), 20000.0, 300)
    assert cold[-1][0] > rows[-1][0] * (1 + 1e-3)


def test_bracketed_root_matches_brentq():
    rng = np.random.default_rng(7)
    n = 300
    a, b, c = rng.uniform(0.5, 2, n), rng.uniform(0.1, 3, n), rng.uniform(1e-3, 1, n)
    f = lambda x, i: c[i] - a[i] * x - b[i] * np.sqrt(x) - x ** 5
    hi = np.full(n, 2.0)
    x = bracketed_root(f, np.zeros(n), hi, np.full(n, 1e-15))
    for i in range(n):
        ref = brentq(lambda t: f(np.array([t]), np.array([i]))[0], 0, 2, xtol=1e-300,
                     rtol=4 * np.finfo(float).eps)
        assert x[i] == pytest.approx(ref, rel=1e-13, abs=1e-300)


def test_scene_rate_keys():
    from helpers import scene
    sc = scene(**{"material.plasticity": {"yield_stress": 250e6, "hardening": {"linear": 1.5e9},
                                          "rate": {"cowper_symonds": {"D": 40.4, "q": 5}}}})
    assert sc.material.plasticity.rate == RateLaw("cowper_symonds", D=40.4, q=5.0)
    jc_keys = {"A": 176e6, "B": 300e6, "n": 0.3, "C": 0.0089, "reference_rate": 1.0, "m": 1.1,
               "thermal": {"initial_temperature": 293.15, "melting_temperature": 1813.15,
                           "specific_heat": 473.0, "taylor_quinney": 0.9}}
    sc = scene(**{"material.plasticity": {"rate": {"johnson_cook": jc_keys}}})
    pl = sc.material.plasticity
    assert pl.yield_stress == 176e6 and pl.rate.thermal == THERMAL
    bad = [
        ({"yield_stress": 250e6, "rate": {"johnson_cook": jc_keys}}, "left out"),
        ({"rate": {"johnson_cook": {**jc_keys, "m": None}}}, "needed with thermal"),
        ({"rate": {"johnson_cook": {**jc_keys, "thermal": {**jc_keys["thermal"],
                                                            "taylor_quinney": 1.5}}}}, r"\[0, 1\]"),
        ({"rate": {"johnson_cook": {**jc_keys, "thermal": {**jc_keys["thermal"],
                                                            "melting_temperature": 200}}}}, "above"),
        ({"yield_stress": 250e6, "hardening": {"linear": 1.5e9},
          "rate": {"cowper_symonds": {"D": 0, "q": 5}}}, "> 0"),
        ({"yield_stress": 250e6, "hardening": {"linear": 1.5e9},
          "rate": {"cowper_symonds": {"D": 40.4, "q": 5, "p": 1}}}, "unknown key"),
        ({"yield_stress": 250e6, "hardening": {"linear": 1.5e9}, "rate": {"zerilli": {}}}, "rate law"),
    ]
    for pl, msg in bad:
        with pytest.raises(SceneError, match=msg):
            scene(**{"material.plasticity": pl})


def test_a_preheated_point_starts_softened():
    """thermal.reference_temperature (section 3b): T* = (T0 + dT - Tr) / (Tm - Tr), so a point
    60 K above Tr with m = 1 starts at Theta = 1 - 60 / 150 = 0.6; absent, Tr is T0 (Theta 1);
    above T0 it is refused."""
    from helpers import scene
    jc = {"A": 250e6, "B": 0.0, "n": 1.0, "C": 0.0, "reference_rate": 1.0, "m": 1.0,
          "thermal": {"initial_temperature": 353.15, "melting_temperature": 443.15,
                      "specific_heat": 460.0, "taylor_quinney": 0.9}}
    theta = []
    for tr in (None, 293.15):
        th = dict(jc["thermal"], **({} if tr is None else {"reference_temperature": tr}))
        law = scene(**{"material.plasticity": {"rate": {"johnson_cook": {**jc, "thermal": th}}}}
                    ).material.plasticity.rate
        theta.append(RateDependence(law, None, 1.0, 1e-6, 7850.0, 1).theta()[0])
    assert theta[0] == 1.0 and theta[1] == pytest.approx(0.6, rel=1e-15)
    hot = dict(jc["thermal"], reference_temperature=400.0)
    with pytest.raises(SceneError, match="must not be above initial_temperature"):
        scene(**{"material.plasticity": {"rate": {"johnson_cook": {**jc, "thermal": hot}}}})


def test_simulation_outputs_with_rate_laws():
    """Section 8: the probe columns after each probe's von Mises stress, the summary keys;
    heat_J = beta x the final plastic work; the hottest point's rise from the heating identity
    bounded by the whole plate's heat."""
    from helpers import scene
    from indep_fe.solver import simulate
    jc_keys = {"A": 176e6, "B": 300e6, "n": 0.3, "C": 0.0089, "reference_rate": 1.0, "m": 1.1,
               "thermal": {"initial_temperature": 293.15, "melting_temperature": 1813.15,
                           "specific_heat": 473.0, "taylor_quinney": 0.9}}
    over = {"load.impactor.velocity": 30.0, "time.end": 2e-4,
            "output.probes": {"B": {"x": 0.1, "y": 0.02}, "A": {"x": 0.1, "y": 0.0}}}
    res = simulate(scene(**over, **{"material.plasticity": {"rate": {"johnson_cook": jc_keys}}}))
    cols = res.columns
    for p in "AB":
        j = cols.index(f"{p}_von_mises_Pa")
        assert cols[j + 1:j + 3] == [f"{p}_plastic_strain_rate_1_s", f"{p}_temperature_K"]
    sm = res.summary
    assert set(sm["max_plastic_strain_rate_1_s"]) == {"A", "B"}
    assert max(sm["max_plastic_strain_rate_1_s"].values()) > 100.0
    assert sm["max_plastic_strain_rate_1_s"]["A"] >= res.column("A_plastic_strain_rate_1_s").max()
    wp = res.column("plastic_work_J")[-1]
    assert wp > 0 and sm["heat_J"] == pytest.approx(0.9 * wp, rel=1e-14)
    assert sm["max_temperature_K"] >= res.column("A_temperature_K").max() > 293.15
    res = simulate(scene(**over, **{"material.plasticity": {
        "yield_stress": 250e6, "hardening": {"linear": 1.5e9},
        "rate": {"cowper_symonds": {"D": 40.4, "q": 5}}}}))
    assert "A_temperature_K" not in res.columns and "heat_J" not in res.summary
    j = res.columns.index("A_von_mises_Pa")
    assert res.columns[j + 1] == "A_plastic_strain_rate_1_s"
