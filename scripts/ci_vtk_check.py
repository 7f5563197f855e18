#!/usr/bin/env python3
"""Read back the VTK field output of `impact simulate` with meshio and check it.

    .venv/bin/python scripts/ci_vtk_check.py SCENE RUST_OUT [PY_OUT]

SCENE must have `output.fields` and an elastic material. Checks, for every frame listed in
RUST_OUT/fields.pvd:
- the mesh: point count (nx+1)(ny+1), nx*ny quads, point coordinates equal to the independent
  Python mesh (contract numbering), connectivity equal to the contract's;
- the arrays: point data displacement_m, velocity_mps (3 components, z = 0); cell data
  sxx_Pa, syy_Pa, szz_Pa, sxy_Pa, von_mises_Pa, eqps; all finite; constrained dofs zero;
- the frame times: those of the output schedule (first step with n dt >= k every, and t = 0);
- the mid-span displacements: u_y at the top, mid-plane and bottom mid-span nodes equal to
  the history's top_uy_m, mid_uy_m, bottom_uy_m at that time (RUST_OUT: exactly; PY_OUT,
  the independent code, to 1e-8 of the column's peak);
- the stresses: element-average stresses recomputed independently (indep_fe's B-bar / B
  operators and plane-strain D from the frame's displacement, averaged with the
  integration weights) equal to the file's to 1e-9 of the largest; von_mises_Pa equal to the
  von Mises stress of the file's components; eqps = 0.
Exit status 1 on any failure.
"""
from __future__ import annotations

import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import meshio
import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from indep_fe.compare import read_history  # noqa: E402
from indep_fe.elements import elastic_matrix, formulation, global_operators, kinematics  # noqa: E402
from indep_fe.material import lame, von_mises  # noqa: E402
from indep_fe.mesh import build_mesh  # noqa: E402
from indep_fe.scene import load_scene  # noqa: E402
from indep_fe.solver import steps_for  # noqa: E402

failures: list[str] = []


def check(ok: bool, what: str) -> None:
    if not ok:
        failures.append(what)
        print(f"  FAIL {what}")


def main(argv: list[str]) -> int:
    if len(argv) not in (2, 3):
        print(__doc__, file=sys.stderr)
        return 2
    scene_path, rust_out = Path(argv[0]), Path(argv[1])
    py_out = Path(argv[2]) if len(argv) == 3 else None
    sc = load_scene(scene_path)
    if sc.material.plasticity is not None:
        print("ci_vtk_check: the stress recomputation needs an elastic scene", file=sys.stderr)
        return 2
    raw = __import__("yaml").safe_load(scene_path.read_text())
    fields_every = float(raw["output"]["fields"]["every"])
    ms = sc.mesh
    pm = build_mesh(sc.plate, ms)
    kin = kinematics(pm)
    lam, mu = lame(sc.material.youngs_modulus, sc.material.poisson_ratio)
    form = formulation(ms.element, pm, kin, sc.plate.width, lam, mu, ms.hourglass)
    Bg, _ = global_operators(form, pm)
    D = elastic_matrix(lam, mu)
    nel, ngp = form.w.shape

    hist_r = read_history(rust_out)
    hist_p = read_history(py_out) if py_out else None
    summary_dt = __import__("json").loads((rust_out / "summary.json").read_text())["dt_s"]

    pvd = ET.parse(rust_out / "fields.pvd").getroot()
    frames = [(float(d.get("timestep")), rust_out / d.get("file")) for d in pvd.iter("DataSet")]
    n_last = round(hist_r["time_s"][-1] / summary_dt)
    expected = sorted({0} | {steps_for(k * fields_every, summary_dt)
                             for k in range(1, int(n_last * summary_dt / fields_every) + 2)
                             if steps_for(k * fields_every, summary_dt) <= n_last} | {n_last})
    got = [round(t / summary_dt) for t, _ in frames]
    check(got == expected, f"frame steps {got} != expected {expected}")
    print(f"ci_vtk_check: {len(frames)} frames in {rust_out / 'fields.pvd'}, dt = {summary_dt:.6e} s")

    for t, path in frames:
        m = meshio.read(path)
        tag = f"{path.name} (t = {t:.6e} s)"
        check(m.points.shape == (pm.n_nodes, 3), f"{tag}: points {m.points.shape} != ({pm.n_nodes}, 3)")
        check(np.allclose(m.points[:, :2], pm.coords, rtol=0, atol=1e-15 * sc.plate.length),
              f"{tag}: point coordinates differ from the contract mesh")
        quads = [c for c in m.cells if c.type == "quad"]
        check(len(m.cells) == 1 and len(quads) == 1 and quads[0].data.shape == (pm.n_elements, 4),
              f"{tag}: cells {[(c.type, c.data.shape) for c in m.cells]} != one block of {pm.n_elements} quads")
        if quads:
            check(np.array_equal(quads[0].data, pm.conn), f"{tag}: connectivity differs from the contract's")
        for name in ["displacement_m", "velocity_mps"]:
            a = m.point_data.get(name)
            check(a is not None and a.shape == (pm.n_nodes, 3) and np.all(np.isfinite(a))
                  and np.all(a[:, 2] == 0), f"{tag}: point data {name} missing or malformed")
        cell = {k: np.asarray(v[0]) for k, v in m.cell_data.items()}
        for name in ["sxx_Pa", "syy_Pa", "szz_Pa", "sxy_Pa", "von_mises_Pa", "eqps"]:
            check(name in cell and cell[name].shape == (pm.n_elements,) and
                  np.all(np.isfinite(cell[name])), f"{tag}: cell data {name} missing or malformed")
        if failures:
            break
        u = m.point_data["displacement_m"][:, :2].ravel()
        check(np.all(u[pm.fixed_dofs] == 0), f"{tag}: constrained dofs are not zero")
        # mid-span displacements against the histories
        i_r = np.flatnonzero(np.abs(hist_r["time_s"] - t) <= 1e-12 * max(t, 1e-300) + 1e-300)
        check(i_r.size == 1, f"{tag}: no history row at this time")
        if i_r.size != 1:
            continue
        for col, node in [("top_uy_m", pm.top), ("mid_uy_m", pm.mid), ("bottom_uy_m", pm.bottom)]:
            v = u[2 * node + 1]
            check(v == hist_r[col][i_r[0]],
                  f"{tag}: VTK u_y {v!r} at the {col} node != Rust history {hist_r[col][i_r[0]]!r}")
            if hist_p is not None:
                peak = np.abs(hist_p[col]).max()
                check(abs(v - hist_p[col][i_r[0]]) <= 1e-8 * peak,
                      f"{tag}: VTK u_y {v!r} at the {col} node vs Python history "
                      f"{hist_p[col][i_r[0]]!r}: {abs(v - hist_p[col][i_r[0]]) / peak:.2e} of the peak")
        # element-average stress recomputed independently from the frame's displacement
        eps = (Bg @ u).reshape(nel, ngp, 4)
        s = eps @ D.T                                  # (xx, yy, zz, xy)
        avg = np.einsum("eg,egc->ec", form.w, s) / form.w.sum(axis=1)[:, None]
        scale = max(np.abs(avg).max(), 1.0)
        for c, name in enumerate(["sxx_Pa", "syy_Pa", "szz_Pa", "sxy_Pa"]):
            d = np.abs(cell[name] - avg[:, c]).max() / scale
            check(d <= 1e-9, f"{tag}: {name} differs from the recomputed element average by {d:.2e}")
        fs = np.stack([cell["sxx_Pa"], cell["syy_Pa"], cell["szz_Pa"], cell["sxy_Pa"]], axis=1)
        d = np.abs(von_mises(fs) - cell["von_mises_Pa"]).max() / max(cell["von_mises_Pa"].max(), 1.0)
        check(d <= 1e-12, f"{tag}: von_mises_Pa differs from its components' by {d:.2e}")
        check(np.all(cell["eqps"] == 0), f"{tag}: eqps not zero in an elastic run")
    last_u = np.abs(u).max() if frames else 0.0
    if failures:
        print(f"ci_vtk_check: FAIL ({len(failures)})")
        return 1
    print(f"ci_vtk_check: OK ({len(frames)} frames, {pm.n_nodes} points, {pm.n_elements} quads; "
          f"largest |u| in the last frame {last_u:.3e} m)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
