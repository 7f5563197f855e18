import numpy as np
import pytest
import scipy.sparse as sp
from skfem import Basis, ElementQuad1, ElementVector, asm
from skfem.models.elasticity import linear_elasticity

from helpers import plate_mesh as setup, scene
from indep_fe.elements import (GAUSS_2X2, critical_dt, elastic_matrix, element_dofs,
                               element_stiffness, formulation, global_operators,
                               lumped_mass)
from indep_fe.material import MaterialModel, lame
from indep_fe.mesh import build_mesh, find_element

ELEMENTS = ["q4-full", "q4-sri", "q4-1pt"]


def test_numbering_and_midspan_nodes():
    sc = scene(**{"mesh.nx": 6, "mesh.ny": 4})
    pm = build_mesh(sc.plate, sc.mesh)
    nx, ny = 6, 4
    for j in range(ny + 1):
        for i in range(nx + 1):
            assert np.allclose(pm.coords[i + j * (nx + 1)], [pm.xs[i], pm.ys[j]])
    assert np.array_equal(pm.conn[1 + 2 * nx], [1 + 2 * 7, 2 + 2 * 7, 2 + 3 * 7, 1 + 3 * 7])
    assert pm.coords[pm.top].tolist() == [0.1, 0.02]
    assert pm.coords[pm.mid].tolist() == [0.1, 0.01]
    assert pm.coords[pm.bottom].tolist() == [0.1, 0.0]
    # half model: x = 0 clamped, x = L/2 symmetric
    fixed = set(pm.fixed_dofs.tolist())
    for j in range(ny + 1):
        n0, n1 = j * (nx + 1), nx + j * (nx + 1)
        assert {2 * n0, 2 * n0 + 1, 2 * n1} <= fixed and 2 * n1 + 1 not in fixed
    assert len(fixed) == 3 * (ny + 1)


@pytest.mark.parametrize("model", ["half", "full"])
def test_grading(model):
    sc = scene(**{"mesh.nx": 8, "mesh.grading": 4.0, "mesh.model": model})
    pm = build_mesh(sc.plate, sc.mesh)
    dx = np.diff(pm.xs)
    assert dx.max() / dx.min() == pytest.approx(4.0, rel=1e-12)
    L = sc.plate.length
    if model == "half":
        assert np.argmin(dx) == 7 and pm.xs[-1] == L / 2
        assert np.allclose(dx[1:] / dx[:-1], dx[1] / dx[0])
    else:
        assert pm.xs[4] == L / 2 and pm.xs[-1] == L
        assert np.allclose(dx, dx[::-1])
        assert dx[3] == dx.min()
        assert pm.coords[pm.mid].tolist() == [L / 2, sc.plate.thickness / 2]


def test_gauss_points_area_mass():
    sc = scene(**{"mesh.nx": 5, "mesh.grading": 2.0})
    pm, kin = setup(sc)
    for e in [0, 7, 19]:
        xy = pm.coords[pm.conn[e]]
        for g, (xi, eta) in enumerate(GAUSS_2X2):
            N = np.array([(1 + xi * a) * (1 + eta * b) / 4
                          for a, b in [(-1, -1), (1, -1), (1, 1), (-1, 1)]])
            assert np.allclose(kin.gp_xy[e, g], N @ xy, atol=1e-15)
        assert np.allclose(kin.centroid[e], xy.mean(0))
    assert kin.area.sum() == pytest.approx(0.1 * 0.02, rel=1e-13)
    m = lumped_mass(pm, kin, 7850.0, 0.2)
    assert m.sum() == pytest.approx(7850.0 * 0.1 * 0.02 * 0.2, rel=1e-13)


@pytest.mark.parametrize("element", ELEMENTS)
def test_patch_constant_strain(element):
    """Linear displacement field on a distorted mesh: exact constant strain at every point,
    no hourglass mode, zero residual force at interior nodes."""
    sc = scene(**{"mesh.nx": 6, "mesh.ny": 4, "mesh.element": element})
    pm, kin = setup(sc, distort=0.3)
    lam, mu = lame(207e9, 0.3)
    form = formulation(element, pm, kin, 0.2, lam, mu, 0.05)
    B, G = global_operators(form, pm)
    A = np.array([[1.0e-3, 2.0e-4], [-5.0e-4, 3.0e-4]])
    u = (pm.coords @ A.T).ravel()
    eps = (B @ u).reshape(-1, 4)
    assert np.allclose(eps, [A[0, 0], A[1, 1], 0.0, A[0, 1] + A[1, 0]], rtol=0, atol=1e-15)
    if G is not None:
        assert np.allclose(G @ u, 0.0, atol=1e-17)
    mat = MaterialModel(sc.material, eps.shape[0])
    s, _, _ = mat.update(eps, form.w.ravel())
    f = B.T @ (form.w.ravel()[:, None] * s).ravel()
    nx = pm.nx
    interior = np.array([i + j * (nx + 1) for j in range(1, pm.ny) for i in range(1, nx)])
    dofs = np.concatenate([2 * interior, 2 * interior + 1])
    assert np.abs(f[dofs]).max() < 1e-9 * np.abs(f).max()


@pytest.mark.parametrize("element", ELEMENTS)
def test_internal_force_equals_stiffness(element):
    """f_int(u) from the stress path equals K u from the element stiffness (elastic)."""
    sc = scene(**{"mesh.nx": 4, "mesh.ny": 2, "mesh.element": element})
    pm, kin = setup(sc, distort=0.2)
    lam, mu = lame(207e9, 0.3)
    form = formulation(element, pm, kin, 0.2, lam, mu, 0.05)
    D = elastic_matrix(lam, mu)
    Ke = element_stiffness(form, D)
    edofs = element_dofs(pm)
    ndof = 2 * pm.n_nodes
    K = sp.coo_matrix((Ke.ravel(), (np.repeat(edofs, 8, axis=1).ravel(),
                                    np.tile(edofs, (1, 8)).ravel())), shape=(ndof, ndof)).tocsr()
    u = np.random.default_rng(2).normal(size=ndof) * 1e-5
    B, G = global_operators(form, pm)
    mat = MaterialModel(sc.material, B.shape[0] // 4)
    s, energy, _ = mat.update((B @ u).reshape(-1, 4), form.w.ravel())
    f = B.T @ (form.w.ravel()[:, None] * s).ravel()
    hg = 0.0
    if G is not None:
        q = (G @ u).reshape(-1, 2)
        f += G.T @ (form.k_hg[:, None] * q).ravel()
        hg = 0.5 * np.sum(form.k_hg * (q ** 2).sum(1))
    Ku = K @ u
    assert np.allclose(f, Ku, rtol=0, atol=1e-12 * np.abs(Ku).max())
    assert energy + hg == pytest.approx(0.5 * u @ Ku, rel=1e-12)
    # stiffness is symmetric positive semi-definite with 3 rigid-body modes per element
    ev = np.linalg.eigvalsh(Ke)
    assert np.all(ev[:, :3] < 1e-9 * ev[:, -1:]) and np.all(ev[:, 3:] > 1e-6 * ev[:, -1:])


def test_full_integration_matches_skfem_assembly():
    """q4-full global stiffness equals scikit-fem's own plane-strain linear_elasticity form."""
    sc = scene(**{"mesh.nx": 5, "mesh.ny": 2, "mesh.element": "q4-full", "mesh.grading": 1.7})
    pm, kin = setup(sc, distort=0.2)
    lam, mu = lame(207e9, 0.3)
    form = formulation("q4-full", pm, kin, 1.0, lam, mu, 0.05)
    Ke = element_stiffness(form, elastic_matrix(lam, mu))
    edofs = element_dofs(pm)
    ndof = 2 * pm.n_nodes
    K = sp.coo_matrix((Ke.ravel(), (np.repeat(edofs, 8, axis=1).ravel(),
                                    np.tile(edofs, (1, 8)).ravel())), shape=(ndof, ndof)).toarray()
    vb = Basis(pm.skfem_mesh, ElementVector(ElementQuad1()), intorder=3)
    assert np.array_equal(vb.nodal_dofs, np.stack([2 * np.arange(pm.n_nodes), 2 * np.arange(pm.n_nodes) + 1]))
    Ksk = asm(linear_elasticity(lam, mu), vb).toarray()
    assert np.allclose(K, Ksk, rtol=0, atol=1e-10 * np.abs(K).max())


def test_critical_dt_rectangles():
    """Square q4-full element, eigenvalue bound vs a direct generalized eigenproblem."""
    sc = scene(**{"mesh.nx": 5, "mesh.ny": 2, "mesh.element": "q4-full"})
    pm, kin = setup(sc)
    lam, mu = lame(207e9, 0.3)
    form = formulation("q4-full", pm, kin, 0.2, lam, mu, 0.05)
    D = elastic_matrix(lam, mu)
    dt = critical_dt(form, D, kin, 7850.0, 0.2)
    Ke = element_stiffness(form, D)[0]
    m = 7850.0 * kin.area[0] * 0.2 / 4
    wmax = np.sqrt(np.linalg.eigvalsh(Ke / m).max())
    assert dt == pytest.approx(2 / wmax, rel=1e-12)
    # and the dilatational wave bound is of the right size: dt ~ h / c_p
    cp = np.sqrt((lam + 2 * mu) / 7850.0)
    assert 0.5 < dt / (0.01 / cp) < 1.0


def test_find_element_and_probe_mirroring():
    sc = scene(**{"mesh.nx": 4, "mesh.ny": 2})
    pm = build_mesh(sc.plate, sc.mesh)
    assert find_element(pm, 0.1, 0.0, 0.2) == 3
    assert find_element(pm, 0.025, 0.01, 0.2) == 0       # shared corner: lowest index
    full = build_mesh(sc.plate, scene(**{"mesh.nx": 4, "mesh.ny": 2, "mesh.model": "full"}).mesh)
    assert find_element(full, 0.1, 0.0, 0.2) == 1
