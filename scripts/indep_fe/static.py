"""Static solve of a pulse scene with the independent FE: the equilibrium K u = f of the plate
under the pulse's force held on (linear elastic; the same mesh, elements and force node as
the time loop), the value the dynamic response oscillates about.

    python -m indep_fe.static SCENE.yaml --out FILE.json

writes {top_uy_m, mid_uy_m, bottom_uy_m, force_N, n_dofs} (displacements of the mid-span nodes,
signed: negative = down) and prints it.
"""
from __future__ import annotations

import argparse
import json
import sys

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from .elements import element_dofs, element_stiffness, elastic_matrix, formulation, kinematics
from .material import lame
from .mesh import build_mesh
from .scene import Scene, SceneError, load_scene


def static_deflection(scene: Scene) -> dict:
    """Mid-span displacements (m) of the plate under the pulse force held on."""
    if scene.pulse is None:
        raise SceneError("static: the scene needs a pulse load")
    if scene.material.plasticity is not None:
        raise SceneError("static: linear elastic scenes only (no plasticity block)")
    if scene.geometry != "plane-strain":
        raise SceneError("static: plane-strain scenes only (geometry: axisymmetric, section 3d, "
                         "is implemented by the time loop, not by this solve)")
    plate, mat, ms = scene.plate, scene.material, scene.mesh
    pm = build_mesh(plate, ms)
    lam, mu = lame(mat.youngs_modulus, mat.poisson_ratio)
    form = formulation(ms.element, pm, kinematics(pm), plate.width, lam, mu, ms.hourglass)
    ke = element_stiffness(form, elastic_matrix(lam, mu))          # (nel, 8, 8)
    edofs = element_dofs(pm)
    ndof = 2 * pm.n_nodes
    rows = np.repeat(edofs, 8, axis=1).ravel()
    cols = np.tile(edofs, (1, 8)).ravel()
    K = sp.csr_matrix((ke.ravel(), (rows, cols)), shape=(ndof, ndof))
    f = np.zeros(ndof)
    f[2 * pm.top + 1] = -scene.pulse.force / pm.symmetry            # the modelled part's share
    free = np.ones(ndof, bool)
    free[pm.fixed_dofs] = False
    u = np.zeros(ndof)
    u[free] = spla.spsolve(K[free][:, free].tocsc(), f[free])
    return {"top_uy_m": float(u[2 * pm.top + 1]), "mid_uy_m": float(u[2 * pm.mid + 1]),
            "bottom_uy_m": float(u[2 * pm.bottom + 1]), "force_N": scene.pulse.force,
            "n_dofs": int(free.sum())}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="indep_fe.static", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene", help="scene YAML file with a pulse load (SI units)")
    ap.add_argument("--out", help="JSON file to write")
    args = ap.parse_args(argv)
    try:
        result = static_deflection(load_scene(args.scene))
    except (SceneError, ValueError) as exc:
        print(f"indep_fe.static: error: {exc}", file=sys.stderr)
        return 2
    text = json.dumps(result, indent=1) + "\n"
    if args.out:
        with open(args.out, "w") as fh:
            fh.write(text)
    print(text, end="")
    return 0


if __name__ == "__main__":
    sys.exit(main())
