import numpy as np
import pytest

from indep_fe.material import Hardening, MaterialModel, lame, von_mises
from indep_fe.scene import Material, Plasticity

E, NU, SY0, ET = 207e9, 0.3, 250e6, 1.5e9
LAM, MU = lame(E, NU)
KB = LAM + 2 * MU / 3


def uniaxial_strain_exact(e, hard_k_of_e):
    """Closed form for eps = (e, 0, 0, 0) increasing monotonically from 0: q = 2 mu (e - 1.5 k),
    p = K e, s_xx = p + 2q/3, s_yy = s_zz = p - q/3, eps_p = (k, -k/2, -k/2, 0)."""
    k = hard_k_of_e(e)
    q = 2 * MU * (e - 1.5 * k)
    p = KB * e
    return np.stack([p + 2 * q / 3, p - q / 3, p - q / 3, 0 * e], axis=-1), k


def run_path(mat, strains, w=1.0):
    model = MaterialModel(mat, 1)
    out, ks, work = [], [], 0.0
    for e in strains:
        s, _, dw = model.update(np.array([[e, 0.0, 0.0, 0.0]]), np.array([w]))
        out.append(s[0].copy())
        ks.append(model.k[0])
        work += dw
    return np.array(out), np.array(ks), work, model


def test_elastic_plane_strain():
    mat = Material(7850.0, E, NU)
    model = MaterialModel(mat, 1)
    eps = np.array([[1e-4, -2e-4, 0.0, 3e-4]])
    s, energy, _ = model.update(eps, np.array([2.0]))
    tr = -1e-4
    assert np.allclose(s[0], [LAM * tr + 2 * MU * 1e-4, LAM * tr - 4 * MU * 1e-4, LAM * tr,
                              MU * 3e-4])
    assert energy == pytest.approx(2.0 * 0.5 * (s[0, 0] * 1e-4 - s[0, 1] * 2e-4 + s[0, 3] * 3e-4))


@pytest.mark.parametrize("nsteps", [1, 7, 200])
def test_radial_return_uniaxial_strain_linear(nsteps):
    H = E * ET / (E - ET)
    mat = Material(7850.0, E, NU, Plasticity(SY0, linear_tangent=ET))
    strains = np.linspace(0, 8e-3, nsteps + 1)[1:]
    s, k, work, model = run_path(mat, strains)
    kfun = lambda e: np.maximum(0.0, (2 * MU * e - SY0) / (3 * MU + H))
    s_ex, k_ex = uniaxial_strain_exact(strains, kfun)
    assert np.allclose(s, s_ex, rtol=1e-12, atol=1e-12 * SY0)
    assert np.allclose(k, k_ex, rtol=1e-12, atol=1e-18)
    assert np.allclose(model.eps_p[0], [k_ex[-1], -k_ex[-1] / 2, -k_ex[-1] / 2, 0.0], atol=1e-18)
    # on the yield surface, and plastic work exact for linear hardening
    assert von_mises(s[-1]) == pytest.approx(SY0 + H * k_ex[-1], rel=1e-12)
    assert work == pytest.approx(SY0 * k_ex[-1] + H * k_ex[-1] ** 2 / 2, rel=1e-12)


def test_radial_return_unloading_is_elastic():
    mat = Material(7850.0, E, NU, Plasticity(SY0, linear_tangent=ET))
    s, k, _, _ = run_path(mat, [4e-3, 3e-3])
    assert k[1] == k[0] > 0
    ds = s[1] - s[0]
    assert np.allclose(ds, [(LAM + 2 * MU) * -1e-3, LAM * -1e-3, LAM * -1e-3, 0.0])


@pytest.mark.parametrize("nsteps", [1, 13, 300])
def test_radial_return_uniaxial_strain_table(nsteps):
    table = [(0.0, SY0), (0.002, 290e6), (0.01, 320e6)]
    mat = Material(7850.0, E, NU, Plasticity(SY0, table=table))
    hard = Hardening(E, SY0, table=table)
    strains = np.linspace(0, 3e-2, nsteps + 1)[1:]     # goes beyond the last table point
    s, k, _, _ = run_path(mat, strains)
    # closed form: 2 mu (e - 1.5 k) = sigma_y(k) wherever plastic
    plastic = k > 0
    assert plastic[-1] and k[-1] > 0.01
    resid = 2 * MU * (strains - 1.5 * k) - hard(k)
    assert np.abs(resid[plastic]).max() < 1e-6 * SY0
    s_ex, _ = uniaxial_strain_exact(strains, lambda e: k)
    assert np.allclose(s, s_ex, rtol=1e-11, atol=1e-9 * SY0)


def test_table_hardening_equals_linear():
    H = E * ET / (E - ET)
    tab = Hardening(E, SY0, table=[(0.0, SY0), (1.0, SY0 + H)])
    lin = Hardening(E, SY0, tangent=ET)
    q = np.array([300e6, 900e6, 2.6e9])
    k = np.array([0.0, 0.01, 0.2])
    assert np.allclose(tab.return_map(q, k, MU), lin.return_map(q, k, MU), rtol=1e-12)
    # beyond the table: the curve holds its last value
    flat = Hardening(E, SY0, table=[(0.0, SY0), (0.001, 300e6)])
    dk = flat.return_map(np.array([400e6]), np.array([0.002]), MU)
    assert dk[0] == pytest.approx((400e6 - 300e6) / (3 * MU), rel=1e-13)


def test_radial_return_general_state_consistency():
    """Random strains: the returned stress is on the updated yield surface, deviatoric flow."""
    rng = np.random.default_rng(3)
    mat = Material(7850.0, E, NU, Plasticity(SY0, linear_tangent=ET))
    model = MaterialModel(mat, 50)
    eps = rng.normal(size=(50, 4)) * 3e-3
    eps[:, 2] = 0.0
    s, _, _ = model.update(eps, np.ones(50))
    H = E * ET / (E - ET)
    yielded = model.k > 0
    assert yielded.sum() > 10
    assert np.allclose(von_mises(s[yielded]), SY0 + H * model.k[yielded], rtol=1e-12)
    assert np.allclose(model.eps_p[:, :3].sum(1), 0.0, atol=1e-15)   # plastic incompressibility
    assert np.all(von_mises(s[~yielded]) <= SY0)


@pytest.mark.parametrize("table", [[[0.01, 300e6]], [[0.0, 260e6], [0.01, 300e6]], []])
def test_hardening_table_must_start_at_yield(table):
    """A table whose first row is not (0, yield_stress) is an error, never patched."""
    from helpers import scene
    from indep_fe.scene import SceneError
    with pytest.raises(SceneError, match="table"):
        scene(**{"material.plasticity": {"yield_stress": 250e6, "hardening": {"table": table}}})
