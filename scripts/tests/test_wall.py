"""The Python FE's rigid wall (ALGORITHM.md section 5c) against the 1-D elastic bar striking a
rigid wall (nu = 0: exactly 1-D; contact for 2 L/c, stress rho c v0, rebound at v0) and the
energy identity of free masses (the wall takes exactly the kinetic energy of the nodes it
stops), and the scene's refusals. Each check names the wrong model it rejects."""
import math

import numpy as np
import pytest

from helpers import scene
from indep_fe.scene import SceneError
from indep_fe.solver import simulate
from indep_fe.wall import RigidWall

E, RHO, L, A, V = 200.0e9, 7800.0, 0.1, 0.005, 10.0   # Pa, kg/m^3, m, m (radius), m/s
BAR = {"plate": {"length": 2 * A, "width": 1.0, "thickness": L, "ends": "free"},
       "material": {"density": RHO, "youngs_modulus": E, "poisson_ratio": 0.0},
       "mesh": {"nx": 2, "ny": 80, "element": "q4-sri", "model": "half"},
       "load": {"wall": {"velocity": V}},
       "time": {"end": 3 * L / math.sqrt(E / RHO), "dt": {"cfl": 0.9}},
       "output": {}}


@pytest.mark.parametrize("geometry", ["plane-strain", "axisymmetric"])
def test_elastic_bar_against_1d_waves(geometry):
    """Duration within 5 % (measured +0.69 %: one step late), the plateau stress within 5e-5
    (measured -4.8e-6), the rebound within 5 % (measured -0.94 %). A bar twice as stiff gives
    -29 % duration; a wall force counted twice +100 % stress; a sticking wall never releases."""
    res = simulate(scene(**BAR, geometry=geometry))
    c = math.sqrt(E / RHO)
    T, area = 2 * L / c, (math.pi * A * A if geometry == "axisymmetric" else 2 * A * 1.0)
    wall = res.summary["wall"]
    assert wall["release_time_s"] == pytest.approx(T, rel=0.05)
    t, F = res.column("time_s"), res.column("contact_force_N")
    plateau = F[(t >= 0.25 * T) & (t <= 0.75 * T)].mean() / area
    assert plateau == pytest.approx(RHO * c * V, rel=5e-5)
    assert wall["rebound_velocity_mps"] == pytest.approx(V, rel=0.05)
    assert res.summary["impulse_Ns"] == pytest.approx(
        RHO * area * L * (V + wall["rebound_velocity_mps"]), rel=1e-12)


def test_free_masses_lose_exactly_their_kinetic_energy():
    """Two rows of free masses, no internal force: the bottom row stops at t_0, the top row
    lands mid-step; the dissipation equals the kinetic energy (a wall that books the impulse
    against the displacement increment instead, u_{n+1} - u_n = 0 for the stopping row, would
    book nothing for it)."""
    coords = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 0.35], [1.0, 0.35]])
    m = np.array([2.0, 2.0, 2.0, 2.0])
    inv_m = np.repeat(1.0 / m, 2)
    w = RigidWall(coords, inv_m, m, 2.0, 1.0, 3, 1)
    dt = 0.1
    v, u = w.launch(1.0), np.zeros(8)
    ke0 = 2.0 * 0.5 * np.sum(np.repeat(m, 2) * v * v)
    for n in range(12):
        w.solve(u, v, np.zeros(8), dt, first=n == 0)
        f = np.zeros(8)
        w.apply(f)
        v = v + (0.5 * dt if n == 0 else dt) * f * inv_m
        u = u + dt * v
    assert np.allclose(v, 0.0, atol=1e-15)
    assert w.energy == pytest.approx(ke0, rel=1e-14)


@pytest.mark.parametrize("change", [{"plate.ends": "clamped"}, {"mesh.model": "full"},
                                    {"time.end": {"after_contact": 1.0e-6}},
                                    {"load.wall.velocity": -1.0}])
def test_refusals(change):
    with pytest.raises(SceneError):
        scene(**BAR, **change)
