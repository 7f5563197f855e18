"""The scene reader refuses what it does not know and honours `plate.ends`.

Reference: the scene contract of solver/ALGORITHM.md and the Rust parser (unknown keys are
refused; `plate.ends`: clamped u_x = u_y = 0, roller u_x = 0, slider u_y = 0 at both ends,
the half model keeping u_x = 0 on its symmetry plane).
"""
import numpy as np
import pytest

from helpers import scene
from indep_fe.mesh import build_mesh
from indep_fe.scene import SceneError


@pytest.mark.parametrize("path", ["plate.colour", "mesh.elements", "load.impactor.speed",
                                  "time.stop", "output.probes.A.z", "title2"])
def test_unknown_keys_are_refused(path):
    with pytest.raises(SceneError, match="unknown key"):
        scene(**{path: 1.0})


@pytest.mark.parametrize("path, value", [("load.traction", {"normal": 1e6, "duration": 1e-4}),
                                         ("mesh.distortion", 0.1)])
def test_contract_keys_this_solver_lacks_are_refused(path, value):
    with pytest.raises(SceneError, match="not supported"):
        scene(**{path: value})


def test_a_bad_end_support_is_refused():
    with pytest.raises(SceneError, match="plate.ends"):
        scene(**{"plate.ends": "hinged"})


def _fixed(ends, model):
    sc = scene(**{"plate.ends": ends, "mesh.model": model, "mesh.nx": 4, "mesh.ny": 2})
    assert sc.plate.ends == ends
    pm = build_mesh(sc.plate, sc.mesh)
    return pm, set(pm.fixed_dofs.tolist())


@pytest.mark.parametrize("model", ["half", "full"])
@pytest.mark.parametrize("ends, comps", [("clamped", (0, 1)), ("roller", (0,)),
                                         ("slider", (1,))])
def test_ends_fix_the_components_the_contract_names(ends, comps, model):
    pm, fixed = _fixed(ends, model)
    nx, ny = pm.nx, pm.ny
    left = [j * (nx + 1) for j in range(ny + 1)]
    right = [nx + j * (nx + 1) for j in range(ny + 1)]
    expected = {2 * n + c for n in left for c in comps}
    if model == "half":
        expected |= {2 * n for n in right}              # symmetry plane: u_x = 0
    else:
        expected |= {2 * n + c for n in right for c in comps}
    assert fixed == expected
    assert np.all(np.isin(pm.fixed_dofs, sorted(expected)))
