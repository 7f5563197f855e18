"""A builtin's boundary-value problem (adapters/README.md, "Problems"): `problem.json` -> a
static ccx deck (`job.inp`) -> `fields.json`. Small strain, plane strain (`CPE4`/`CPE4R`) or
axisymmetric (`CAX4`/`CAX4R`, nodes at `(r, z)`, forces the whole ring's), linear elastic or
von Mises with linear isotropic hardening (`*PLASTIC`, two points of the flow curve). A
`static` problem: every prescribed displacement (`*BOUNDARY`) and load (`*CLOAD`) applied in one
`*STATIC` step; a `static path`: the same scaled by each load factor in turn, one fixed
increment per factor (`*STATIC, DIRECT` with the factors as an `*AMPLITUDE`). At each, each
node's displacement and internal force (ccx's `RF`: the reaction at a held dof, the residual at
a free one), the stress at every integration point and, with plasticity, its equivalent plastic
strain (`PEEQ`). ccx expands a `CPE4` into a one-layer `C3D8` with 8 points
(`CPE4R`: 1), a `CAX4` into a 2-degree wedge (its radial displacement and forces below); the
stresses are those points'. Lengths m, forces N (the section's whole width; none about the
axis), stresses Pa (about the axis `s_rr, s_zz, s_tt, s_rz`, as ccx prints them). A `static
contact` problem (a rigid cylinder pressed in) is written and read by indenter.py.
"""

import json
import math
import os

import contract
import deck
import indenter
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
    if p.get("problem") not in ("static", "static path", "static contact"):
        raise NotExpressible(f"problem {p.get('problem')!r}",
                             "only 'static', 'static path' and 'static contact' problems are written")
    if p.get("geometry") not in GEOMETRY:
        raise NotExpressible(f"geometry {p.get('geometry')!r}",
                             f"one of {', '.join(GEOMETRY)}")
    if p.get("element") not in ELEMENTS:
        raise NotExpressible(f"element {p.get('element')!r}", f"one of {', '.join(ELEMENTS)}")


def material_lines(m):
    """*MATERIAL M: elastic, and the linear flow curve `sigma_y + H eps_p` (two points, at
    eps_p = 0 and 1; `H = E E_t / (E - E_t)`) when the problem has plasticity."""
    e = m["youngs_modulus_Pa"]
    lines = ["*MATERIAL, NAME=M", "*ELASTIC", f"{deck.num(e)}, {deck.num(m['poisson_ratio'])}"]
    if m.get("plasticity"):
        sy, et = m["plasticity"]["yield_stress_Pa"], m["plasticity"]["tangent_modulus_Pa"]
        h = e * et / (e - et)
        lines += ["*PLASTIC", f"{deck.num(sy)}, 0.", f"{deck.num(sy + h)}, 1."]
    return lines


def step_lines(p):
    """The *STEP: one *STATIC increment, or a fixed increment per load factor of a path."""
    factors = p.get("load_factors")
    if factors is None:
        return ["*STEP", "*STATIC", "*BOUNDARY"], ""
    n = len(factors)
    amplitude = ["*AMPLITUDE, NAME=PATH", "0., 0."]
    amplitude += [f"{deck.num((k + 1) / n)}, {deck.num(f)}" for k, f in enumerate(factors)]
    return amplitude + [f"*STEP, INC={n + 1}", "*STATIC, DIRECT", f"{deck.num(1 / n)}, 1.",
                        "*BOUNDARY, AMPLITUDE=PATH"], ", AMPLITUDE=PATH"


def deck_lines(p):
    """The deck's lines and (ccx element type, substitutions)."""
    if p["problem"] == "static contact":
        return indenter.deck_lines(p)
    ccx_type, sub = deck.ELEMENT[(GEOMETRY[p["geometry"]], p["element"])]
    lines = ["*NODE"]
    lines += [f"{i + 1}, {deck.num(x)}, {deck.num(y)}, 0." for i, (x, y) in enumerate(p["nodes_m"])]
    lines.append(f"*ELEMENT, TYPE={ccx_type}, ELSET=EALL")
    lines += [f"{k + 1}, " + ", ".join(str(n + 1) for n in e) for k, e in enumerate(p["elements"])]
    lines += ["*NSET, NSET=NALL"] + deck.lines_of(list(range(1, len(p["nodes_m"]) + 1)))
    lines += material_lines(p["material"])
    lines += ["*SOLID SECTION, ELSET=EALL, MATERIAL=M",
              deck.num(p["width_m"]) if p["geometry"] == "plane strain" else ""]
    step, amplitude = step_lines(p)
    lines += step
    lines += [f"{n + 1}, {d + 1}, {d + 1}, {deck.num(v)}" for n, d, v in p["prescribed_m"]]
    if p.get("loads_N"):
        lines += [f"*CLOAD{amplitude}"]
        lines += [f"{n + 1}, {d + 1}, {deck.num(v)}" for n, d, v in p["loads_N"]]
    plastic = ", PEEQ" if p["material"].get("plasticity") else ""
    lines += ["*NODE PRINT, NSET=NALL", "U, RF", "*EL PRINT, ELSET=EALL", f"S{plastic}",
              "*END STEP"]
    return lines, (ccx_type, [sub] if sub else [])


def by_point(rows, n_elements, width):
    """Per element, its points' values (`width` numbers after element and point) in point order."""
    out = [[] for _ in range(n_elements)]
    for r in sorted(rows, key=lambda r: (r[0], r[1])):
        out[int(r[0]) - 1].append(r[2:2 + width] if width > 1 else r[2])
    return out


def fields_at(blocks, p, k):
    """fields.json's arrays from job.dat's k-th output (of each kind)."""
    n_nodes, n_elements = len(p["nodes_m"]), len(p["elements"])
    u = results.nodal(results.series(blocks, "U", "NALL")[k][1])
    f = results.nodal(results.series(blocks, "F", "NALL")[k][1])
    stresses = by_point(results.series(blocks, "S", "EALL")[k][1], n_elements, 4)
    missing = [e + 1 for e in range(n_elements) if not stresses[e]]
    if missing or len(u) < n_nodes or len(f) < n_nodes:
        raise results.DatError(f"job.dat is short: {len(u)} displacements, {len(f)} forces for "
                               f"{n_nodes} nodes, no stress for elements {missing}")
    out = {"displacements_m": [u[i + 1][:2] for i in range(n_nodes)],
           "nodal_forces_N": [f[i + 1][:2] for i in range(n_nodes)],
           "point_stresses_Pa": stresses}
    if p["material"].get("plasticity"):
        out["point_eqps"] = by_point(results.series(blocks, "PEEQ", "EALL")[k][1], n_elements, 1)
    if p["geometry"] == "axisymmetric":
        c = math.cos(HALF_WEDGE)
        out["displacements_m"] = [[ur / c, uz] for ur, uz in out["displacements_m"]]
        out["nodal_forces_N"] = None
    return out


def fields(blocks, p):
    """fields.json: the one output of a static problem, or `{"steps": [...]}` of a path's."""
    if p["problem"] == "static contact":
        return indenter.fields(blocks, p)
    if p.get("load_factors") is None:
        return fields_at(blocks, p, -1)
    n, got = len(p["load_factors"]), len(results.series(blocks, "S", "EALL"))
    if got != n:
        raise results.DatError(f"job.dat has {got} outputs for the path's {n} load factors")
    return {"steps": [fields_at(blocks, p, k) for k in range(n)]}


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
               "n_elements": len(p["elements"]),
               "n_steps": len(p.get("load_factors") or [1]), "ccx_element": ccx_type}
    contract.write_all(out_dir, {"fields.json": json.dumps(out, indent=1) + "\n",
                                 "adapter.json": json.dumps(adapter, indent=2) + "\n"})
