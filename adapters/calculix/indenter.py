"""A builtin's problem with a rigid cylinder pressed into a plane-strain section (`static
contact`, ../README.md "Problems"; the Hertz line contact). Lengths m, forces N, stresses Pa.

As for the nose in surface contact (nose.py), the section is written as what ccx makes of a
CPE4, a one-layer C3D8 slab of the section's width with u_z = 0 on every node, and the
cylinder as a rigid ring of C3D8 elements (`*RIGID BODY`, its reference node at the centre)
along the arc over the surface nodes, with segments of at most a quarter of the surface's
node spacing (their sag 3.6e-3 and 9e-4 of the Hertz gap a^2 / 2R on its 88 and 176 blocks). The pair is ccx's
penalty `SURFACE TO SURFACE` (frictionless), the section's surface the slave, with the slope
nose.PENALTY_PER_MODULUS E / dy. One `*STATIC` step of INCREMENTS increments moves the
reference node by the prescribed displacement.

The contact force on a node is its internal force. ccx's printed RF at a free node is the
residual with the contact included (0 there), and its nodal contact pressure (`CPRESS`,
extrapolated from the faces' points) does not sum to the contact force (measured on the
Hertz block: 1.0 to 2.2 times ccx's own total `CF` as the penalty slope goes from 5 to 50
E / dy). So the adapter computes every node's internal force from the elements' printed
stresses at their eight points, `f_a = sum_g B_a^T s_g det J_g` (ccx's 2 x 2 x 2 Gauss points,
xi fastest, weights 1). It reproduces ccx's RF at the held nodes to the printed digits, and on
the top surface it sums to ccx's `CF` (both checked by the tests). C3D8R's hourglass forces
are not printed, so q4-1pt is not expressible here.
"""

import math

import deck
import nose
import results
from scene import NotExpressible

INCREMENTS = 10
ELEMENT = {"q4-full": ("C3D8", None),
           "q4-sri": ("C3D8", "q4-sri -> C3D8 in a one-layer slab (no B-bar element in ccx)")}
G = 1.0 / math.sqrt(3.0)
# ccx's C3D8 integration points (xi fastest, then eta, then zeta) and its corner nodes.
POINTS = [(x, y, z) for z in (-G, G) for y in (-G, G) for x in (-G, G)]
CORNERS = [(-1, -1, -1), (1, -1, -1), (1, 1, -1), (-1, 1, -1),
           (-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1)]


def check_expressible(p):
    """NotExpressible for an indenter problem this module does not write."""
    if p["geometry"] != "plane strain":
        raise NotExpressible(f"geometry {p['geometry']!r}", "an indenter on a plane-strain section only")
    if p["element"] not in ELEMENT:
        raise NotExpressible(f"element {p['element']!r}", "q4-full or q4-sri (C3D8): the contact "
                             "forces come from the 8 points' stresses; C3D8R's hourglass forces "
                             "are not printed")


def slab(p):
    """*NODE and *ELEMENT of the section as a slab: node n + 1 at z = 0, n + 1 + N at z = W."""
    count, width = len(p["nodes_m"]), float(p["width_m"])
    out = ["*NODE, NSET=NSLAB"]
    for n, (x, y) in enumerate(p["nodes_m"]):
        out += [f"{n + 1}, {deck.num(x)}, {deck.num(y)}, 0.",
                f"{n + 1 + count}, {deck.num(x)}, {deck.num(y)}, {deck.num(width)}"]
    out.append(f"*ELEMENT, TYPE={ELEMENT[p['element']][0]}, ELSET=EALL")
    for k, e in enumerate(p["elements"]):
        out.append(f"{k + 1}, " + ", ".join(str(n + 1) for n in e) + ", "
                   + ", ".join(str(n + 1 + count) for n in e))
    return out


def surface_elements(p):
    """The elements whose 2-D edge from their third to their fourth node lies on the surface."""
    on = set(p["indenter"]["surface_nodes"])
    return [k for k, e in enumerate(p["elements"]) if e[2] in on and e[3] in on]


def surface_faces(p):
    """The slab's faces under the surface nodes: face S5 (nodes 3-7-8-4) of each surface element."""
    return [f"{k + 1}, S5" for k in surface_elements(p)]


def depth_under_surface(p):
    """The smallest depth of a surface element (its fourth node to its first), m: the penalty
    slope's length."""
    nodes = p["nodes_m"]
    return min(math.dist(nodes[p["elements"][k][3]], nodes[p["elements"][k][0]])
               for k in surface_elements(p))


def arc(p):
    """The ring's stations: angles from the lowest point (x = touch + R sin phi) over the
    surface nodes' x range, at most a quarter of their smallest spacing apart."""
    ind = p["indenter"]
    r, (tx, _) = float(ind["radius_m"]), ind["touch_m"]
    xs = sorted(p["nodes_m"][n][0] for n in ind["surface_nodes"])
    spacing = min(b - a for a, b in zip(xs, xs[1:]) if b > a)
    lo, hi = (math.asin(max(-1.0, min(1.0, (x - tx) / r))) for x in (xs[0], xs[-1]))
    segments = max(1, math.ceil((hi - lo) * r / (0.25 * spacing)))
    return [lo + (hi - lo) * k / segments for k in range(segments + 1)]


def ring(p, first_node, first_element):
    """The rigid ring's lines and its reference node."""
    ind, width = p["indenter"], float(p["width_m"])
    r, (tx, ty) = float(ind["radius_m"]), ind["touch_m"]
    thick = 0.1 * r
    phis = arc(p)
    node = lambda k, inner, back: first_node + 4 * k + 2 * inner + back  # noqa: E731
    out = ["*NODE, NSET=NRING"]
    for k, phi in enumerate(phis):
        for inner, rr in ((0, r), (1, r - thick)):
            x, y = nose.arc_point((tx, ty), r, rr, -phi)  # phi grows toward +x here
            out += [f"{node(k, inner, b)}, {deck.num(x)}, {deck.num(y)}, {deck.num(b * width)}"
                    for b in (0, 1)]
    ref = node(len(phis) - 1, 1, 1) + 1
    out += ["*NODE, NSET=NREF", f"{ref}, {deck.num(tx)}, {deck.num(ty + r)}, {deck.num(width / 2)}",
            "*NODE, NSET=NROT", f"{ref + 1}, {deck.num(tx)}, {deck.num(ty + r)}, {deck.num(width / 2)}",
            "*ELEMENT, TYPE=C3D8, ELSET=ERING"]
    for k in range(len(phis) - 1):
        a, b = k, k + 1
        out.append(f"{first_element + k}, " + ", ".join(str(n) for n in (
            node(a, 0, 0), node(b, 0, 0), node(b, 1, 0), node(a, 1, 0),
            node(a, 0, 1), node(b, 0, 1), node(b, 1, 1), node(a, 1, 1))))
    out += ["*SURFACE, NAME=SRING, TYPE=ELEMENT"]
    out += [f"{first_element + k}, S3" for k in range(len(phis) - 1)]  # face 1-2-6-5: outer
    return out, ref


def deck_lines(p):
    """The deck's lines and (ccx element type, substitutions)."""
    check_expressible(p)
    count, ind = len(p["nodes_m"]), p["indenter"]
    m = p["material"]
    dy = depth_under_surface(p)
    lines = slab(p) + ["*SURFACE, NAME=SSLAB, TYPE=ELEMENT"] + surface_faces(p)
    ring_lines, ref = ring(p, 2 * count + 1, len(p["elements"]) + 1)
    lines += ring_lines
    lines += ["*MATERIAL, NAME=RING", "*ELASTIC", f"{deck.num(m['youngs_modulus_Pa'])}, 0.3",
              "*SOLID SECTION, ELSET=ERING, MATERIAL=RING",
              f"*RIGID BODY, ELSET=ERING, REF NODE={ref}, ROT NODE={ref + 1}",
              "*MATERIAL, NAME=M", "*ELASTIC",
              f"{deck.num(m['youngs_modulus_Pa'])}, {deck.num(m['poisson_ratio'])}",
              "*SOLID SECTION, ELSET=EALL, MATERIAL=M",
              "*BOUNDARY", "NSLAB, 3, 3, 0."]
    for n, d, v in p["prescribed_m"]:
        lines += [f"{n + 1}, {d + 1}, {d + 1}, {deck.num(v)}",
                  f"{n + 1 + count}, {d + 1}, {d + 1}, {deck.num(v)}"]
    lines += [f"{ref}, 3, 3, 0.", f"{ref + 1}, 1, 3, 0.",
              "*SURFACE INTERACTION, NAME=C", "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR",
              deck.num(nose.PENALTY_PER_MODULUS * m["youngs_modulus_Pa"] / dy),
              "*CONTACT PAIR, INTERACTION=C, TYPE=SURFACE TO SURFACE", "SSLAB, SRING",
              "*STEP, INC=1000", "*STATIC", f"{1 / INCREMENTS}, 1., 1e-5, {1 / INCREMENTS}",
              "*BOUNDARY"]
    lines += [f"{ref}, {d + 1}, {d + 1}, {deck.num(v)}" for d, v in enumerate(ind["displacement_m"])]
    lines += ["*NODE PRINT, NSET=NSLAB, FREQUENCY=1000", "U, RF",
              "*EL PRINT, ELSET=EALL, FREQUENCY=1000", "S",
              "*CONTACT PRINT, SLAVE=SSLAB, MASTER=SRING, FREQUENCY=1000", "CF", "*END STEP"]
    ccx_type, sub = ELEMENT[p["element"]]
    return lines, (ccx_type, [sub] if sub else [])


def internal_forces(coords, stresses):
    """The internal forces (fx, fy, fz) of a C3D8's eight nodes, N, from its `coords` (8
    (x, y, z), m) and `stresses` (s_xx, s_yy, s_zz, s_xy, s_xz, s_yz at POINTS, Pa)."""
    f = [[0.0] * 3 for _ in range(8)]
    for (xi, eta, zeta), (sxx, syy, szz, sxy, sxz, syz) in zip(POINTS, stresses):
        dn = [(0.125 * a * (1 + eta * b) * (1 + zeta * c), 0.125 * b * (1 + xi * a) * (1 + zeta * c),
               0.125 * c * (1 + xi * a) * (1 + eta * b)) for a, b, c in CORNERS]
        j = [[sum(dn[k][i] * coords[k][col] for k in range(8)) for col in range(3)] for i in range(3)]
        inv, det = inverse3(j)
        sig = ((sxx, sxy, sxz), (sxy, syy, syz), (sxz, syz, szz))
        for k in range(8):
            g = [sum(inv[i][q] * dn[k][q] for q in range(3)) for i in range(3)]
            for i in range(3):
                f[k][i] += (sig[i][0] * g[0] + sig[i][1] * g[1] + sig[i][2] * g[2]) * det
    return f


def inverse3(a):
    """The inverse of the 3 x 3 matrix a and its determinant."""
    c = [[a[(i + 1) % 3][(j + 1) % 3] * a[(i + 2) % 3][(j + 2) % 3]
          - a[(i + 1) % 3][(j + 2) % 3] * a[(i + 2) % 3][(j + 1) % 3] for i in range(3)]
         for j in range(3)]
    det = sum(a[0][k] * c[k][0] for k in range(3))
    return [[c[i][j] / det for j in range(3)] for i in range(3)], det


def fields(blocks, p):
    """fields.json of the step's end: the z = 0 layer's displacements, each node's internal
    force (both layers', from the stresses) and the stresses at the eight points."""
    count, width = len(p["nodes_m"]), float(p["width_m"])
    u = results.nodal(results.series(blocks, "U", "NSLAB")[-1][1])
    by_element = {}
    for r in results.series(blocks, "S", "EALL")[-1][1]:
        by_element.setdefault(int(r[0]), []).append((int(r[1]), r[2:8]))
    if len(u) < 2 * count or len(by_element) < len(p["elements"]):
        raise results.DatError(f"job.dat is short: {len(u)} displacements for {2 * count} slab "
                               f"nodes, stresses of {len(by_element)} of {len(p['elements'])} elements")
    forces = [[0.0, 0.0] for _ in range(count)]
    stresses = []
    for k, e in enumerate(p["elements"]):
        points = [s for _, s in sorted(by_element[k + 1])]
        coords = [(*p["nodes_m"][n], 0.0) for n in e] + [(*p["nodes_m"][n], width) for n in e]
        for n, f in zip(list(e) + list(e), internal_forces(coords, points)):
            forces[n][0] += f[0]
            forces[n][1] += f[1]
        stresses.append([s[:4] for s in points])
    return {"displacements_m": [u[n + 1][:2] for n in range(count)],
            "nodal_forces_N": forces, "point_stresses_Pa": stresses}
