"""Small scenes for the tests (plain dicts, parsed like a YAML file)."""

import numpy as np
from skfem import MeshQuad

from indep_fe.elements import kinematics
from indep_fe.mesh import PlateMesh, build_mesh
from indep_fe.scene import parse_scene, with_dotted

BASE = {
    "plate": {"length": 0.200, "width": 0.200, "thickness": 0.020},
    "material": {"density": 7850.0, "youngs_modulus": 207.0e9, "poisson_ratio": 0.3},
    "mesh": {"nx": 10, "ny": 4, "element": "q4-sri", "model": "half"},
    "load": {"impactor": {"mass": 18.0, "velocity": 10.0, "nose_radius": 0.010,
                          "youngs_modulus": 207.0e9, "poisson_ratio": 0.3,
                          "contact_law": {"paper": {"length_unit": 1.0}},
                          "indentation_datum": "mid-plane"}},
    "time": {"end": 3.0e-4, "dt": {"cfl": 0.8}},
    "output": {"every": 1.0e-5, "probes": {"A": {"x": 0.100, "y": 0.0}}},
}

PLASTIC = {"yield_stress": 250.0e6, "hardening": {"linear": 1.5e9}}


def scene(**over):
    """BASE with dotted-path overrides, e.g. scene(**{"mesh.element": "q4-1pt"})."""
    return parse_scene(with_dotted(BASE, over))


def plate_mesh(sc, distort=0.0):
    """The scene's mesh and kinematics; `distort` > 0 moves the interior nodes by up to that
    fraction of the smallest spacing (seeded): a general quad mesh."""
    pm = build_mesh(sc.plate, sc.mesh)
    if distort:
        rng = np.random.default_rng(1)
        c = pm.coords.copy()
        nx, ny = pm.nx, pm.ny
        h = min(np.diff(pm.xs).min(), np.diff(pm.ys).min())
        interior = [i + j * (nx + 1) for j in range(1, ny) for i in range(1, nx)]
        c[interior] += distort * h * rng.uniform(-1, 1, (len(interior), 2))
        pm = PlateMesh(pm.nx, pm.ny, pm.xs, pm.ys, MeshQuad(c.T.copy(), pm.conn.T.copy()), c,
                       pm.conn, pm.fixed_dofs, pm.top, pm.mid, pm.bottom, pm.symmetry)
    return pm, kinematics(pm)
