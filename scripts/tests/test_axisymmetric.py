"""The Python FE's axisymmetric ring elements (ALGORITHM.md section 3d) against closed forms:
the ring patch test (u_r = a r, u_z = b z: strain (a, b, a, 0) at every point and interior
nodal forces zero, on a graded and a distorted mesh), the ring volume pi R^2 h (Pappus), the
stable step's unequal-mass eigenvalue against the generalised eigenproblem K x = lambda M x, and
the scene's refusals. Each check is run against a named wrong model that it must reject."""
import numpy as np
import pytest
import scipy.linalg

from helpers import plate_mesh, scene
from indep_fe.axisymmetric import Ring, ring_eigenvalues, ring_formulation
from indep_fe.elements import elastic_matrix, element_stiffness, global_operators
from indep_fe.material import lame
from indep_fe.scene import SceneError

ELEMENTS = ["q4-full", "q4-sri", "q4-1pt"]
A_R, B_Z = 1.0e-3, -4.0e-4      # the patch's radial and axial strains (1)
AXI = {"geometry": "axisymmetric", "load": {"pulse": {"force": 1.0e3, "duration": 1.0e-3}},
       "mesh.nx": 8, "mesh.grading": 3.0}


def ring_setup(element, distort):
    sc = scene(**AXI, **{"mesh.element": element})
    pm, kin = plate_mesh(sc, distort)
    lam, mu = lame(sc.material.youngs_modulus, sc.material.poisson_ratio)
    ring = Ring(pm, kin)
    return sc, pm, kin, ring, ring_formulation(element, pm, kin, ring, lam, mu, 0.05), lam, mu


def patch_field(pm):
    """u_r = a r, u_z = b z as (u_x, u_y) dofs: r = x_axis - x, u_x = -u_r."""
    r = pm.coords[pm.top, 0] - pm.coords[:, 0]
    u = np.zeros(2 * pm.n_nodes)
    u[0::2], u[1::2] = -A_R * r, B_Z * pm.coords[:, 1]
    return u


def interior_residual(pm, form, lam, mu, u):
    """max |f| at the interior nodes / max |f| over all nodes, f = sum w B^T D B u (+ hourglass)."""
    Bg, G = global_operators(form, pm)
    s = (Bg @ u).reshape(-1, 4) @ elastic_matrix(lam, mu).T
    f = Bg.T @ (s * form.w.reshape(-1, 1)).ravel()
    if G is not None:
        f += G.T @ (np.repeat(form.k_hg, 2) * (G @ u))
    interior = [i + j * (pm.nx + 1) for j in range(1, pm.ny) for i in range(1, pm.nx)]
    fi = f.reshape(-1, 2)[interior]
    return np.abs(fi).max() / np.abs(f).max()


@pytest.mark.parametrize("distort", [0.0, 0.3])
@pytest.mark.parametrize("element", ELEMENTS)
def test_ring_patch_strain_exact(element, distort):
    _, pm, _, _, form, _, _ = ring_setup(element, distort)
    Bg, G = global_operators(form, pm)
    eps = (Bg @ patch_field(pm)).reshape(-1, 4)
    # measured <= 6.9e-15 relative (distorted mesh; 2.6e-15 graded): 1e-13 is ~15x that
    assert np.abs(eps - [A_R, B_Z, A_R, 0.0]).max() <= 1e-13 * A_R
    if G is not None:    # a linear field has no hourglass mode
        # measured <= 6.8e-21 m against displacements ~1e-4 m
        assert np.abs(G @ patch_field(pm)).max() <= 1e-17


@pytest.mark.parametrize("distort", [0.0, 0.3])
@pytest.mark.parametrize("element", ELEMENTS)
def test_ring_patch_interior_forces_vanish(element, distort):
    """A uniform stress with s_rr = s_theta is in equilibrium: 2 pi r det J weights make the
    assembled interior forces the integral of d(N r)/dr, zero up to round-off."""
    _, pm, _, _, form, lam, mu = ring_setup(element, distort)
    # measured <= 2.8e-15 of the largest (boundary) force: 1e-13 is ~35x that
    assert interior_residual(pm, form, lam, mu, patch_field(pm)) <= 1e-13


@pytest.mark.parametrize("element", ELEMENTS)
def test_plane_weights_fail_the_ring_patch(element):
    """Wrong model: the plane-strain weights det J W with the hoop row (the ring's 2 pi r
    forgotten) leave interior forces as large as any (measured ratio 1.0)."""
    sc, pm, kin, _, form, lam, mu = ring_setup(element, 0.0)
    form.w = (kin.detJw * sc.plate.width) if form.n_gp == 4 else (kin.area * sc.plate.width)[:, None]
    assert interior_residual(pm, form, lam, mu, patch_field(pm)) > 0.05


def test_centroid_dilatation_fails_the_ring_patch():
    """Wrong model: q4-sri on the centroid's dilatation (plane b_x, b_y and the hoop -N_a/r at
    the centroid) instead of the ring's mean one: interior forces do not vanish (measured
    0.0175 of the largest force, against <= 2.8e-15 for the mean one)."""
    _, pm, kin, ring, _, lam, mu = ring_setup("q4-sri", 0.3)
    r_c = pm.coords[pm.top, 0] - kin.centroid[:, 0]
    ring.mbx, ring.mby, ring.mh = kin.bx, kin.by, np.repeat(-0.25 / r_c[:, None], 4, axis=1)
    form = ring_formulation("q4-sri", pm, kin, ring, lam, mu, 0.05)
    assert interior_residual(pm, form, lam, mu, patch_field(pm)) > 1e-4


def test_ring_volume_and_masses():
    """The row-sum masses add up to rho pi R^2 h (the whole round plate, R = L/2), exact for
    the 2x2 rule; the plane lumping rho A W (the slab) does not."""
    sc, pm, kin, ring, _, _, _ = ring_setup("q4-sri", 0.3)
    R, h, rho = sc.plate.length / 2, sc.plate.thickness, sc.material.density
    exact = rho * np.pi * R * R * h
    assert abs(ring.node_masses(rho).sum() - exact) <= 1e-14 * exact   # measured 3.6e-16
    # the slab's mass: measured 0.363 off
    assert abs(rho * kin.area.sum() * sc.plate.width - exact) > 0.1 * exact


@pytest.mark.parametrize("element", ELEMENTS)
def test_stable_step_unequal_masses(element):
    """lambda_max(M^-1/2 K M^-1/2) with sqrt(m_i m_j) equals the largest root of
    det(K - lambda M); the element's mean nodal mass (a wrong model) does not: on the axis
    element (nodal masses differing by 2.18x) it is off by 0.048 (q4-full) and 0.18 (q4-sri,
    q4-1pt)."""
    sc, pm, _, ring, form, lam, mu = ring_setup(element, 0.3)
    D = elastic_matrix(lam, mu)
    m_e = ring.node_masses(sc.material.density)
    lam_e = ring_eigenvalues(form, D, m_e)
    K = element_stiffness(form, D)
    for e in (0, pm.nx - 1, pm.nx * pm.ny - 1):      # rim, axis, axis-top elements
        ref = scipy.linalg.eigh(K[e], np.diag(np.repeat(m_e[e], 2)), eigvals_only=True)[-1]
        assert abs(lam_e[e] - ref) <= 1e-13 * ref     # measured <= 1.3e-15
    axis = pm.nx - 1
    wrong = np.linalg.eigvalsh(K[axis])[-1] / m_e[axis].mean()
    assert abs(wrong - lam_e[axis]) > 0.02 * lam_e[axis]


@pytest.mark.parametrize("over, words", [
    ({"mesh.model": "full"}, "mesh.model: half"),
    ({"geometry": "cylindrical"}, "plane-strain | axisymmetric"),
])
def test_scene_refusals(over, words):
    with pytest.raises(SceneError, match=words):
        scene(**{**AXI, **over})


def test_nodal_impactor_refused():
    with pytest.raises(SceneError, match="contact: surface"):
        scene(**{"geometry": "axisymmetric"})


def test_static_solve_refuses_the_ring():
    """The static solve is plane-strain only: an axisymmetric scene is refused, not solved as a
    slab."""
    from indep_fe.static import static_deflection
    with pytest.raises(SceneError, match="plane-strain scenes only"):
        static_deflection(scene(**AXI))
