"""A builtin's boundary-value problem (adapters/README.md, "Problems"): `problem.json` -> a
static ccx deck (`job.inp`) -> `fields.json`. Linear elastic, small strain, plane strain
(`CPE4`/`CPE4R`) or axisymmetric (`CAX4`/`CAX4R`, nodes at `(r, z)`, forces the whole ring's): every
prescribed displacement (`*BOUNDARY`) and load (`*CLOAD`) applied in one `*STATIC` step, then each node's displacement and
internal force (ccx's `RF`: the reaction at a held dof, the residual at a free one) and the
stress at every integration point. ccx expands a `CPE4` into a one-layer `C3D8` with 8 points
(`CPE4R`: 1), a `CAX4` into a 2-degree wedge (its radial displacement and forces below); the
stresses are those points'. Lengths m, forces N (the section's whole width; none about the
axis), stresses Pa (about the axis `s_rr, s_zz, s_tt, s_rz`, as ccx prints them).
"""

import json
import math
import os

import contract
import deck
import results
import runner
from scene import NotExpressible

ELEMENTS = ("q4-full", "q4-sri", "q4-1pt")
# The contract's geometry -> deck.ELEMENT's.
GEOMETRY = {"plane strain": "plane-strain", "axisymmetric": "axisymmetric"}


# About the axis ccx expands each element into a 2-degree wedge (nodes at +-1 degree) and
# prints, for a node of the section, its wedge nodes' global components (measured on the
# ring's patch test: a node held at u_r = 3e-5 m prints 2.999543E-05, 3e-5 cos 1 deg). The
# radial displacement is that over cos 1 deg. Its printed forces are the same global sums, in
# which the constraints that keep the wedge's nodes in their meridian planes carry the hoop
# stress (the free interior node of that patch prints f_x = -1105 N, 2 s_tt A sin 1 deg with
# its tributary area A): the radial residual is not among them, so the adapter writes none.
HALF_WEDGE = math.radians(1.0)


def load(path):
    """The problem as written by the harness."""
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def check_expressible(p):
    """NotExpressible for a problem this adapter does not write."""
    if p.get("problem") != "static":
        raise NotExpressible(f"problem {p.get('problem')!r}", "only 'static' problems are written")
    if p.get("geometry") not in GEOMETRY:
        raise NotExpressible(f"geometry {p.get('geometry')!r}",
                             f"one of {', '.join(GEOMETRY)}")
    if p.get("element") not in ELEMENTS:
        raise NotExpressible(f"element {p.get('element')!r}", f"one of {', '.join(ELEMENTS)}")


def deck_lines(p):
    """The deck's lines and (ccx element type, substitutions)."""
    ccx_type, sub = deck.ELEMENT[(GEOMETRY[p["geometry"]], p["element"])]
    m = p["material"]
    lines = ["*NODE"]
    lines += [f"{i + 1}, {deck.num(x)}, {deck.num(y)}, 0." for i, (x, y) in enumerate(p["nodes_m"])]
    lines.append(f"*ELEMENT, TYPE={ccx_type}, ELSET=EALL")
    lines += [f"{k + 1}, " + ", ".join(str(n + 1) for n in e) for k, e in enumerate(p["elements"])]
    lines += ["*NSET, NSET=NALL"] + deck.lines_of(list(range(1, len(p["nodes_m"]) + 1)))
    lines += ["*MATERIAL, NAME=M", "*ELASTIC",
              f"{deck.num(m['youngs_modulus_Pa'])}, {deck.num(m['poisson_ratio'])}",
              "*SOLID SECTION, ELSET=EALL, MATERIAL=M",
              deck.num(p["width_m"]) if p["geometry"] == "plane strain" else "",
              "*STEP", "*STATIC", "*BOUNDARY"]
    lines += [f"{n + 1}, {d + 1}, {d + 1}, {deck.num(v)}" for n, d, v in p["prescribed_m"]]
    if p.get("loads_N"):
        lines += ["*CLOAD"] + [f"{n + 1}, {d + 1}, {deck.num(v)}" for n, d, v in p["loads_N"]]
    lines += ["*NODE PRINT, NSET=NALL", "U, RF", "*EL PRINT, ELSET=EALL", "S", "*END STEP"]
    return lines, (ccx_type, [sub] if sub else [])


def fields(blocks, p):
    """fields.json's arrays from job.dat's blocks."""
    n_nodes, n_elements = len(p["nodes_m"]), len(p["elements"])
    u = results.nodal(results.series(blocks, "U", "NALL")[-1][1])
    f = results.nodal(results.series(blocks, "F", "NALL")[-1][1])
    stresses = [[] for _ in range(n_elements)]
    for r in sorted(results.series(blocks, "S", "EALL")[-1][1], key=lambda r: (r[0], r[1])):
        stresses[int(r[0]) - 1].append(r[2:6])
    missing = [k + 1 for k in range(n_elements) if not stresses[k]]
    if missing or len(u) < n_nodes or len(f) < n_nodes:
        raise results.DatError(f"job.dat is short: {len(u)} displacements, {len(f)} forces for "
                               f"{n_nodes} nodes, no stress for elements {missing}")
    if p["geometry"] == "axisymmetric":
        c = math.cos(HALF_WEDGE)
        return {"displacements_m": [[u[i + 1][0] / c, u[i + 1][1]] for i in range(n_nodes)],
                "nodal_forces_N": None, "point_stresses_Pa": stresses}
    return {"displacements_m": [u[i + 1][:2] for i in range(n_nodes)],
            "nodal_forces_N": [f[i + 1][:2] for i in range(n_nodes)],
            "point_stresses_Pa": stresses}


def solve(problem_json, out_dir, version):
    """Write, run and read back one problem; raises NotExpressible, CcxFailed, DatError."""
    p = load(problem_json)
    check_expressible(p)
    lines, (ccx_type, subs) = deck_lines(p)
    with open(os.path.join(out_dir, "job.inp"), "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")
    wall, cpu, _ = runner.run(out_dir)
    out = fields(results.parse(os.path.join(out_dir, "job.dat")), p)
    adapter = {"code": "calculix", "version": version, "input": ["job.inp"],
               "wall_time_s": wall, "cpu_time_s": cpu, "substitutions": subs,
               "n_elements": len(p["elements"]), "n_steps": 1, "ccx_element": ccx_type}
    contract.write_all(out_dir, {"fields.json": json.dumps(out, indent=1) + "\n",
                                 "adapter.json": json.dumps(adapter, indent=2) + "\n"})
