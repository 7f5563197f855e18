"""Finite deformation (ALGORITHM.md section 3c, indep_fe/finite.py) on homogeneous paths: every
node of a small block follows x = F X and the element kernel alone is stepped (no inertia).

MESH  A 10 mm square block, 2 x 2 quads graded 2:1 along x (the half model of a 20 mm plate),
      each element (q4-full, q4-sri F-bar, q4-1pt) in turn.
CHECKS
  - rigid rotation of a pre-stressed block: the Cauchy stress is the stretched one rotated,
    exactly (round-off), and the stored energy does not change (objectivity);
  - elastic simple shear against Dienes' (1979) closed form for the Green-Naghdi rate, second
    order in the step; the right edge's force against sigma n l on the tilted current edge;
  - the deformed-step factor (section 3c) and the inversion check (section 7), and a run
    stopped by the deformed-step check at the step impact simulate stops at;
  - the scene key `kinematics` and the summary's "kinematics": "finite".
Each test also shows that small kinematics (section 2's strain B u, Cauchy on the reference)
misses by order one, so a formulation that ignored the rotation would fail it.
"""
import numpy as np
import pytest

from helpers import scene
from indep_fe.elements import elastic_matrix, formulation, global_operators, kinematics
from indep_fe.finite import FiniteKinematics, inverted_element, polar_rotation, rotate
from indep_fe.material import MaterialModel, lame
from indep_fe.mesh import build_mesh
from indep_fe.scene import Material, MeshSpec, Plate, SceneError
from indep_fe.solver import UnstableRun, simulate

E, NU, W, H = 200e9, 0.3, 0.01, 0.01
LAM, MU = lame(E, NU)
ELEMENTS = ["q4-full", "q4-sri", "q4-1pt"]


def block(element):
    pm = build_mesh(Plate(2 * H, W, H), MeshSpec(2, 2, element, "half", grading=2.0))
    kin = kinematics(pm)
    fk = FiniteKinematics(element, pm, kin, W)
    return pm, kin, fk, MaterialModel(Material(7850.0, E, NU), fk.nel * fk.npt)


def displacement(pm, F):
    """u = (F - I) X at every node, dofs (u_x0, u_y0, ...)."""
    return (pm.coords @ (F - np.eye(2)).T).ravel()


def rotation(theta):
    c, s = np.cos(theta), np.sin(theta)
    return np.array([[c, -s], [s, c]])


def small_strain_stress(pm, kin, element, u):
    """Section 2-3's stress at u (small kinematics), the control."""
    form = formulation(element, pm, kin, W, LAM, MU, 0.05)
    Bg, _ = global_operators(form, pm)
    return (Bg @ u).reshape(-1, 4) @ elastic_matrix(LAM, MU).T


def test_polar_rotation_and_rotate():
    R, U = rotation(0.7), np.array([[1.2, 0.1], [0.1, 0.9]])
    c, s = polar_rotation(R @ U)
    assert np.allclose([c, s], [np.cos(0.7), np.sin(0.7)], rtol=0, atol=1e-15)
    t = np.array([3.0, -1.0, 0.5, 2.0])
    T = np.array([[t[0], t[3]], [t[3], t[1]]])
    Tr = R @ T @ R.T
    assert np.allclose(rotate(t, c, s), [Tr[0, 0], Tr[1, 1], 0.5, Tr[0, 1]], rtol=0,
                       atol=1e-14)


@pytest.mark.parametrize("element", ELEMENTS)
def test_rigid_rotation_of_prestressed_block(element):
    """A 0.1 % uniaxial-strain stretch in 10 steps, then a rigid rotation through 2 rad in 200
    steps: sigma(theta) = R sigma_1 R^T and the strain energy stays that of the stretch."""
    pm, kin, fk, mat = block(element)
    F1 = np.diag([1.001, 1.0])
    for k in range(1, 11):
        sig1, energy1, _, _ = fk.update(displacement(pm, np.diag([1 + 1e-4 * k, 1.0])), mat)
    # the stretch: e^_xx = sum of the midpoint increments ~ ln 1.001, Kirchhoff / det F
    e_xx = sum(2e-4 / (2 + (2 * k - 1) * 1e-4) for k in range(1, 11))
    assert e_xx == pytest.approx(np.log(1.001), rel=1e-8)
    expected1 = np.array([LAM + 2 * MU, LAM, LAM, 0.0]) * e_xx / 1.001
    assert np.allclose(sig1, expected1, rtol=0, atol=1e-12 * expected1[0])
    # each step's symmetric part of L is round-off of |G| ~ 1, i.e. ~1e-13 of the 1e-3 strain:
    # measured <= 1.2e-12 (stress) and 7.5e-13 (energy) after 200 steps; bound 2e-11 = 200 x 1e-13
    n = 200
    err = derr = 0.0
    for k in range(1, n + 1):
        theta = 2.0 * k / n
        u = displacement(pm, rotation(theta) @ F1)
        sig, energy, _, f = fk.update(u, mat)
        expected = rotate(sig1[0], np.cos(theta), np.sin(theta))
        err = max(err, np.abs(sig - expected).max() / np.abs(sig1).max())
        derr = max(derr, abs(energy - energy1) / energy1)
    print(f"{element}: stress error {err:.2e}, energy change {derr:.2e}")
    assert err < 2e-11 and derr < 2e-11
    # control: small kinematics sees the strain of the rotation, cos(2) - 1 = -1.4: order one
    small = small_strain_stress(pm, kin, element, u)
    assert np.abs(small - expected).max() > 0.5 * E


def dienes(gamma):
    """Dienes (1979), simple shear under the Green-Naghdi rate, tan b = gamma / 2:
    (sigma_xx = -sigma_yy, sigma_xy)."""
    b = np.arctan(gamma / 2)
    sxx = 4 * MU * (np.cos(2 * b) * np.log(np.cos(b)) + b * np.sin(2 * b) - np.sin(b) ** 2)
    sxy = 2 * MU * np.cos(2 * b) * (2 * b - 2 * np.tan(2 * b) * np.log(np.cos(b)) - np.tan(b))
    return sxx, sxy


def shear(element, gamma_max, n):
    """Simple shear F = [[1, gamma], [0, 1]] to gamma_max in n steps: the largest stress error
    against Dienes over the path (relative to mu), and the last state."""
    pm, kin, fk, mat = block(element)
    err = 0.0
    for k in range(1, n + 1):
        g = gamma_max * k / n
        u = displacement(pm, np.array([[1.0, g], [0.0, 1.0]]))
        sig, _, _, f = fk.update(u, mat)
        sxx, sxy = dienes(g)
        err = max(err, np.abs(sig - [sxx, -sxx, 0.0, sxy]).max() / MU)
    return err, pm, kin, u, sig, f


@pytest.mark.parametrize("element", ELEMENTS)
def test_simple_shear_against_dienes(element):
    """Elastic simple shear to gamma = 4 (b = 63 deg): error 4.2e-6 mu at 400 steps, 1.7e-5 at
    200 (the midpoint increment with the mid-step rotation: second order, observed 2.0000);
    tolerance 10x the measured."""
    gamma = 4.0
    err200, *_ = shear(element, gamma, 200)
    err400, pm, kin, u, sig, f = shear(element, gamma, 400)
    assert err400 < 5e-5
    assert np.log2(err200 / err400) == pytest.approx(2.0, abs=0.05)
    # the right edge X = H (current edge tilted to (gamma, 1)) carries sigma (1, -gamma) H W
    right = np.flatnonzero(np.isclose(pm.coords[:, 0], H))
    resultant = np.array([f[2 * right].sum(), f[2 * right + 1].sum()])
    S = np.array([[sig[0, 0], sig[0, 3]], [sig[0, 3], sig[0, 1]]])
    expected = S @ np.array([1.0, -gamma]) * H * W
    assert np.allclose(resultant, expected, rtol=0, atol=1e-12 * np.abs(expected).max())
    # the stress is homogeneous (every point), J = 1 (no pressure)
    assert np.allclose(sig, sig[0], rtol=0, atol=1e-12 * MU)
    # control: small kinematics gives sigma_xy = mu gamma = 4 mu against Dienes' 2.3 mu
    small = small_strain_stress(pm, kin, element, u)
    sxx, sxy = dienes(gamma)
    assert abs(small[0, 3] - sxy) > 1.0 * MU and abs(small[0, 0] - sxx) > 1.0 * MU


@pytest.mark.parametrize("element", ELEMENTS)
def test_deformed_step_factor_and_inversion(element):
    """Section 3c's sqrt(S_ref / S_cur): 1 under a rotation, 0.5 under F = I / 2 (gradients
    doubled); section 7's inversion check: a reflected block is inverted, a rotated one not."""
    pm, _, fk, _ = block(element)
    factor, _ = fk.step_factor(displacement(pm, rotation(2.5)))
    assert factor == pytest.approx(1.0, rel=1e-14)
    factor, _ = fk.step_factor(displacement(pm, 0.5 * np.eye(2)))
    assert factor == pytest.approx(0.5, rel=1e-14)
    assert inverted_element(pm, displacement(pm, rotation(2.5))) is None
    assert inverted_element(pm, displacement(pm, np.diag([-1.0, 1.0]))) == 0


def test_scene_kinematics_key_and_summary():
    assert scene().kinematics == "small"
    with pytest.raises(SceneError, match="kinematics must be small"):
        scene(kinematics="large")
    small = simulate(scene(**{"time.end": 5e-5}))
    finite = simulate(scene(kinematics="finite", **{"time.end": 5e-5}))
    assert "kinematics" not in small.summary and finite.summary["kinematics"] == "finite"
    # at 10 m/s and 50 us the two agree to the small rotations (not to round-off)
    a, b = small.column("mid_uy_m"), finite.column("mid_uy_m")
    assert 0 < np.abs(a - b).max() < 1e-2 * np.abs(a).max()


def test_run_stops_when_the_deformed_step_falls_below_dt():
    """Section 3c: a 100 m/s rigid nose (surface coupling) on the 10 x 4 elasto-plastic plate at
    cfl 0.98 compresses element 9 until its stable step, dt_plate sqrt(S_ref / S_cur), is below
    dt: the check at step 64 stops the run (impact simulate: the same step, element and
    numbers); with time.allow_unstable_dt the run goes on to its end."""
    over = {f"load.impactor.{k}": None for k in ("youngs_modulus", "poisson_ratio",
                                                 "contact_law", "indentation_datum")}
    over.update({"kinematics": "finite", "load.impactor.contact": "surface",
                 "load.impactor.nose_radius": 0.5, "load.impactor.velocity": 100.0,
                 "time.dt": {"cfl": 0.98}, "time.end": 3e-4,
                 "material.plasticity": {"yield_stress": 250.0e6,
                                         "hardening": {"linear": 1.5e9}}})
    with pytest.raises(UnstableRun, match=r"at step 64 .* stable step 7.965648e-07 s "
                                          r"\(element 9\) is below dt"):
        simulate(scene(**over))
    res = simulate(scene(**over, **{"time.allow_unstable_dt": True}))
    assert res.summary["n_steps"] == 376
