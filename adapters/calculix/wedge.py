"""The axisymmetric geometry under the wall as a 3-D wedge of C3D8 (C3D6 on the axis).

ccx 2.20 ignores initial velocities on the CAX4 elements it expands (measured), so the ring
is built by hand: each node (r, z) off the axis becomes two nodes (r cos a, z, -+r sin a) with
the half-angle a; its tangential displacement is held in a cylindrical *TRANSFORM about the
y axis, so every node moves in its meridian plane (exact axisymmetry, any a). Chords carry
the hoop strain u_r / r exactly; the wedge is pi / (sin a cos a) of the ring. Lengths m.
"""

import math

HALF_ANGLE = math.radians(5.0)


def ring_factor():
    """The whole ring's forces, masses and energies over the wedge's (-)."""
    return math.pi / (math.sin(HALF_ANGLE) * math.cos(HALF_ANGLE))


class Wedge:
    """Node numbers of the wedge built on the solver's section (mesh.PlateMesh)."""

    def __init__(self, mesh):
        self.mesh = mesh
        self.ids, self.radius, self.coords = {}, {}, []
        for n in range((mesh.nx + 1) * (mesh.ny + 1)):
            r, z = mesh.ccx_xy(n)
            sides = (0,) if r == 0.0 else (-1, 1)
            for side in sides:
                self.coords.append((r * math.cos(HALF_ANGLE), z, side * r * math.sin(HALF_ANGLE)))
                self.ids[(n, side)] = len(self.coords)
                self.radius[len(self.coords)] = r

    def node(self, n, side):
        """The wedge node of section node n on a side (-1, +1; the axis node for either)."""
        return self.ids.get((n, side)) or self.ids[(n, 0)]

    def on_axis(self, n):
        """Whether section node n lies on the axis."""
        return (n, 0) in self.ids

    def elements(self):
        """([C3D8 rows], [C3D6 rows]) as (number, [node numbers])."""
        hexes, wedges = [], []
        for e, (a, b, c, d) in self.mesh.elements():
            if self.on_axis(a) and self.on_axis(d):
                wedges.append((e + 1, [self.node(a, 0), self.node(b, 1), self.node(b, -1),
                                       self.node(d, 0), self.node(c, 1), self.node(c, -1)]))
            else:
                hexes.append((e + 1, [self.node(p, -1) for p in (a, b, c, d)]
                              + [self.node(p, 1) for p in (a, b, c, d)]))
        return hexes, wedges

    def off_axis(self):
        """Node numbers off the axis (their dofs are radial, tangential, axial)."""
        return [i for i, r in self.radius.items() if r > 0.0]

    def axis(self):
        """Node numbers on the axis (global dofs)."""
        return [i for i, r in self.radius.items() if r == 0.0]

    def foot(self):
        """(off-axis, axis) node numbers of the bottom face."""
        nodes = [i for n in self.mesh.bottom_nodes() for i in {self.node(n, -1), self.node(n, 1)}]
        return ([i for i in nodes if self.radius[i] > 0.0],
                [i for i in nodes if self.radius[i] == 0.0])

    def mid_span(self):
        """{'top', 'mid', 'bottom'}: the axis node numbers of the solver's mid-span nodes."""
        return {k: self.node(n, 0) for k, n in self.mesh.mid_span().items()}
