"""The surface coupling of the rigid nose (ALGORITHM.md section 5b, `contact: surface`).

Hand computations of the penalty stiffness, force and energy of single nodes, the energy as the
force's potential, the stable step, the impactor's momentum against the trapezoidal impulse,
the energy balance, the half model against the full one, the scene keys and the history layout.
"""
import math

import numpy as np
import pytest

from helpers import PLASTIC, scene
from indep_fe.scene import SceneError
from indep_fe.solver import _discretise, history_columns, simulate

NODAL = ("youngs_modulus", "poisson_ratio", "contact_law", "indentation_datum")


def surface_scene(contact="surface", **over):
    """The helpers' 10 x 4 half model with the surface coupling (nodal keys removed)."""
    base = {f"load.impactor.{k}": None for k in NODAL}
    base.update({"load.impactor.contact": contact, "load.impactor.nose_radius": 0.5,
                 "time.dt": {"fixed": 5.0e-7}})
    base.update(over)
    return scene(**base)


# ---------------------------------------------------------------- scene keys
def test_surface_keys():
    sc = surface_scene()
    imp = sc.impactor
    assert (imp.coupling, imp.penalty_scale) == ("surface", 0.1)
    assert imp.contact_law is None and imp.youngs_modulus is None
    assert surface_scene({"surface": {"penalty_scale": 0.3}}).impactor.penalty_scale == 0.3
    assert surface_scene({"surface": {}}).impactor.penalty_scale == 0.1
    assert scene(**{"load.impactor.contact": "nodal"}).impactor.coupling == "nodal"


@pytest.mark.parametrize("key, value", [("youngs_modulus", 207e9), ("poisson_ratio", 0.3),
                                        ("contact_law", {"paper": {"length_unit": 1.0}}),
                                        ("indentation_datum", "mid-plane"),
                                        ("force_node", "top-surface")])
def test_nodal_keys_are_refused_with_surface(key, value):
    with pytest.raises(SceneError, match=f"{key} belongs to the nodal coupling"):
        surface_scene(**{f"load.impactor.{key}": value})


@pytest.mark.parametrize("contact", [{"surface": {"penalty_scale": 0.0}},
                                     {"surface": {"penalty_scale": 1.5}},
                                     {"surface": {"penalty": 0.1}}, "paper", {"nodal": {}}])
def test_bad_contact_is_refused(contact):
    with pytest.raises(SceneError):
        surface_scene(contact)


def test_nodal_coupling_still_needs_its_law():
    with pytest.raises(SceneError, match="contact_law"):
        scene(**{"load.impactor.contact_law": None})


# ---------------------------------------------------------------- candidates, stiffness, step
def test_candidates_and_penalty_stiffness_by_hand():
    sc = surface_scene(**{"load.impactor.nose_radius": 0.02,
                          "load.impactor.contact": {"surface": {"penalty_scale": 0.25}}})
    pl, _, _, dt_crit = _discretise(sc)
    nose, pm = pl.nose, pl.pm
    nx, ny = pm.nx, pm.ny                        # 10 x 4 half model, dx = 10 mm, dy = 5 mm
    # top nodes (j = ny) with |x - L/2| <= 1.1 R = 22 mm: x = 0.08, 0.09, 0.10 (i = 8, 9, 10)
    assert list(nose.nodes) == [8 + ny * (nx + 1), 9 + ny * (nx + 1), 10 + ny * (nx + 1)]
    rho, W, dx, dy = 7850.0, 0.2, 0.01, 0.005
    m_el = rho * dx * dy * W / 4.0               # each element gives rho A W / 4 to each node
    assert np.allclose(nose.m, [2 * m_el, 2 * m_el, m_el], rtol=1e-14)
    # uniform mesh: every element has the same lambda_e, = (2 / dt_p)^2
    lam = (2.0 / pl.dt_plate) ** 2
    assert np.allclose(nose.k, 0.25 * nose.m * lam, rtol=1e-12)
    assert nose.weight.tolist() == [2.0, 2.0, 1.0]       # the axis node counted once
    # dt_crit = 2 / sqrt((2/dt_p)^2 + max k/m) = dt_p / sqrt(1 + s_p) here
    assert dt_crit == pytest.approx(pl.dt_plate / math.sqrt(1.25), rel=1e-14)
    res = simulate(sc)
    assert res.summary["contact_step_factor"] == pytest.approx(1 / math.sqrt(1.25), rel=1e-14)
    assert res.summary["contact_law"] == "surface(penalty_scale=0.25)"


def test_penalty_stiffness_takes_the_larger_neighbour_eigenvalue():
    """Graded mesh: node i takes max(lambda of elements (i-1, ny-1), (i, ny-1))."""
    sc = surface_scene(**{"mesh.grading": 3.0})
    pl, _, _, _ = _discretise(sc)
    from indep_fe.elements import elastic_matrix, element_eigenvalues, formulation, kinematics
    from indep_fe.material import lame
    kin = kinematics(pl.pm)
    lam_, mu = lame(207e9, 0.3)
    lam_e = element_eigenvalues(formulation("q4-sri", pl.pm, kin, 0.2, lam_, mu, 0.05),
                                elastic_matrix(lam_, mu), kin, 7850.0, 0.2)
    nx, ny = pl.pm.nx, pl.pm.ny
    top_row = lam_e[(ny - 1) * nx:]
    assert np.all(np.diff(top_row) > 0)            # smaller elements toward mid-span
    i = pl.nose.nodes - ny * (nx + 1)
    want = [top_row[0] if c == 0 else top_row[c - 1] if c == nx else max(top_row[c - 1], top_row[c])
            for c in i]
    assert np.allclose(pl.nose.k, 0.1 * pl.nose.m * np.array(want), rtol=1e-14)


# ---------------------------------------------------------------- force and energy of one node
def test_one_node_force_and_energy_by_hand():
    sc = surface_scene(**{"load.impactor.nose_radius": 0.02})   # candidates x = 0.08, 0.09, 0.10
    pl, _, _, _ = _discretise(sc)
    nose = pl.nose
    R, h, ndof = 0.02, 0.02, 2 * pl.pm.n_nodes
    u = np.zeros(ndof)
    # nose down by dS = 1e-4; the node at x = 0.09 pulled up by 2.5 mm and right by 1 mm
    dS = 1.0e-4
    node = nose.nodes[1]
    u[2 * node], u[2 * node + 1] = 1.0e-3, 2.5e-3
    f, F, E, count, half = nose.contact(u, dS)
    # axis node: d = (0, -(R - dS)), g = dS, force k dS straight down
    k0, k1 = nose.k[2], nose.k[1]
    dx1, dy1 = (0.09 + 1.0e-3) - 0.1, (h + 2.5e-3) - (h + R - dS)
    dist1 = math.hypot(dx1, dy1)
    g1 = R - dist1
    assert g1 > 0
    assert f[2] == pytest.approx([0.0, -k0 * dS], rel=1e-10, abs=0)
    assert f[1] == pytest.approx([k1 * g1 * dx1 / dist1, k1 * g1 * dy1 / dist1], rel=1e-9)
    assert np.all(f[0] == 0.0)                     # x = 0.08: |d| > R
    P = -(f[1][1] + f[2][1])
    assert F == pytest.approx(2.0 * P, rel=1e-14)                    # whole plate, s = 2
    assert E == pytest.approx(2.0 * (k0 * dS ** 2 + k1 * g1 ** 2) / 2.0, rel=1e-9)
    assert count == 3.0                            # the axis node once, x = 0.09 twice
    assert half == pytest.approx(abs(dx1), rel=1e-12)


def test_penalty_energy_is_the_potential_of_the_force():
    """d(E_c / s)/d(u) = -f on every candidate dof (central differences)."""
    sc = surface_scene(**{"load.impactor.nose_radius": 0.05})
    pl, _, _, _ = _discretise(sc)
    nose, s = pl.nose, pl.s
    rng = np.random.default_rng(1)
    u = np.zeros(2 * pl.pm.n_nodes)
    u[2 * nose.nodes] = rng.uniform(-2e-4, 2e-4, nose.nodes.size)
    u[2 * nose.nodes + 1] = rng.uniform(-1e-4, 0.0, nose.nodes.size)
    dS = 3.0e-4
    f, _, _, _, _ = nose.contact(u, dS)
    eps = 1e-9
    for j, node in enumerate(nose.nodes):
        for c in (0, 1):
            up, um = u.copy(), u.copy()
            up[2 * node + c] += eps
            um[2 * node + c] -= eps
            dE = (nose.contact(up, dS)[2] - nose.contact(um, dS)[2]) / (2 * eps) / s
            assert dE == pytest.approx(-f[j, c], rel=1e-5, abs=1e-6 * np.abs(f).max())


def test_no_penetration_no_force():
    pl, _, _, _ = _discretise(surface_scene())
    f, F, E, count, half = pl.nose.contact(np.zeros(2 * pl.pm.n_nodes), 0.0)
    assert F == 0.0 and E == 0.0 and count == 0.0 and half == 0.0 and not f.any()


# ---------------------------------------------------------------- whole runs
@pytest.mark.parametrize("plastic", [False, True])
def test_impactor_momentum_equals_the_trapezoidal_impulse(plastic):
    over = {"material.plasticity": PLASTIC} if plastic else {}
    res = simulate(surface_scene(**over))
    s = res.summary
    F = res.column("contact_force_N")
    assert s["peak_contact_force_N"] > 1e5 and s["impulse_Ns"] > 10.0
    assert s["impulse_momentum_error"] < 1e-13
    assert 18.0 * (10.0 - s["final_impactor_velocity_mps"]) == pytest.approx(s["impulse_Ns"],
                                                                           rel=1e-13)
    # the history's velocity is v_S,n of section 5b: v0 at t = 0, then below it
    v = res.column("impactor_velocity_mps")
    assert v[0] == 10.0 and v[-1] == s["final_impactor_velocity_mps"]
    assert F[0] == 0.0


def test_energy_balance_and_columns():
    res = simulate(surface_scene(**{"time.end": 6.0e-4}))
    assert res.columns == history_columns(["A"], impact=True, surface=True)
    i = res.columns.index("impactor_velocity_mps")
    assert res.columns[i + 1:i + 3] == ["contact_half_width_m", "nodes_in_contact"]
    assert res.summary["max_energy_balance_error"] < 1e-3
    n = res.column("nodes_in_contact")
    assert n.max() >= 3 and np.array_equal(n, np.round(n))
    assert res.summary["max_nodes_in_contact"] >= n.max()
    assert res.summary["max_contact_half_width_m"] >= res.column("contact_half_width_m").max() > 0
    # indentation = delta_S + u_y of the top mid-span node
    assert np.array_equal(res.column("indentation_m"),
                          res.column("impactor_displacement_m") + res.column("top_uy_m"))
    # contact energy, force and half-width vanish together
    F, Ec = res.column("contact_force_N"), res.column("contact_energy_J")
    assert np.array_equal(F == 0, Ec == 0) and np.array_equal(F == 0, n == 0)


def test_half_model_equals_full_model():
    half = simulate(surface_scene(**{"time.end": 3.0e-4}))
    full = simulate(surface_scene(**{"time.end": 3.0e-4, "mesh.model": "full", "mesh.nx": 20}))
    for c in ("contact_force_N", "mid_uy_m", "impactor_velocity_mps", "nodes_in_contact",
              "contact_half_width_m", "contact_energy_J", "strain_energy_J"):
        a, b = half.column(c), full.column(c)
        assert np.abs(a - b).max() <= 1e-9 * np.abs(a).max(), c
    assert half.summary["max_nodes_in_contact"] == full.summary["max_nodes_in_contact"] >= 3
