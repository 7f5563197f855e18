"""Probes: the element containing each probe and its integration point nearest to it.

ccx numbers the 2 x 2 x 2 points of the C3D8 it expands a CPE4/CAX4 into as
(xi, eta) = (-,-), (+,-), (-,+), (+,+) on each of the two layers (points 1-4 and 5-8, equal
in plane strain and axisymmetry); CPE4R/CAX4R have one point.
"""

import math

G = 1.0 / math.sqrt(3.0)
CCX_POINTS = [(-G, -G), (G, -G), (-G, G), (G, G)]


def shape(xi, eta):
    """Bilinear shape functions at (xi, eta), corners (-1,-1), (1,-1), (1,1), (-1,1)."""
    return [(1 - xi) * (1 - eta) / 4, (1 + xi) * (1 - eta) / 4,
            (1 + xi) * (1 + eta) / 4, (1 - xi) * (1 + eta) / 4]


def point_position(corners, xi, eta):
    """Physical position (m) of the natural point (xi, eta) of a 4-node element."""
    n = shape(xi, eta)
    return (sum(a * c[0] for a, c in zip(n, corners)), sum(a * c[1] for a, c in zip(n, corners)))


def locate(mesh, probes, reduced):
    """{name: (element index, ccx point number 1..4)} for each probe {name: {x, y}} (m)."""
    elements = dict(mesh.elements())
    out = {}
    for name, p in probes.items():
        x, y = mesh.fold(float(p["x"]), float(p["y"]))
        e = mesh.element_containing(x, y)
        if e is None:
            raise ValueError(f"probe {name} at ({x}, {y}) m lies outside the mesh")
        if reduced:
            out[name] = (e, 1)
            continue
        target = (0.5 * mesh.length - x, y) if mesh.axisymmetric else (x, y)
        corners = [mesh.ccx_xy(n) for n in elements[e]]
        # The solver's point order (-,-), (+,-), (+,+), (-,+) decides ties, as it does.
        order = [2, 1, 3, 4] if mesh.axisymmetric else [1, 2, 4, 3]
        dist = [math.dist(point_position(corners, *CCX_POINTS[k - 1]), target) for k in order]
        out[name] = (e, order[dist.index(min(dist))])
    return out
