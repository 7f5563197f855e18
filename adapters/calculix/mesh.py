"""The plate's structured mesh, node for node the solver's (solver/src/mesh/plate.rs).

Node (i, j) has index i + j (nx + 1), element (i, j) index i + j nx (ccx numbers are index + 1).
Coordinates in m. In the axisymmetric geometry ccx's x is the radius r = L/2 - x (the axis at
the solver's mid-span line) and each element's corners are reordered to stay counter-clockwise.
"""

import math


def station_grid(length, thickness):
    """Grid step of the stations, m: 2^(ceil(log2 max(L, h)) - 53), as the solver rounds."""
    return 2.0 ** (math.ceil(math.log2(max(length, thickness))) - 53)


def stations(sizes, end, grid):
    """Stations from 0 by element sizes (m) rounded to grid; the last one is `end` exactly."""
    at, x = [0.0], 0.0
    for size in sizes:
        x += math.floor(size / grid + 0.5) * grid
        at.append(x)
    at[-1] = end
    return at


def x_stations(length, nx, grading, model, grid):
    """Node x (m): uniform or geometric with largest/smallest = grading, smallest at mid-span."""
    half_elements = nx if model == "half" else nx // 2
    ratio = grading ** (-1.0 / (half_elements - 1)) if half_elements > 1 else 1.0
    sizes = [ratio ** i for i in range(half_elements)]
    total = sum(sizes)
    half = stations((s / total * 0.5 * length for s in sizes), 0.5 * length, grid)
    if model == "half":
        return half
    return half + [length - x for x in reversed(half[:-1])]


class PlateMesh:
    """Nodes, elements, supports and the named nodes of the scene's plate."""

    def __init__(self, s):
        plate, mesh = s["plate"], s["mesh"]
        self.length, self.h = float(plate["length"]), float(plate["thickness"])
        self.nx, self.ny = int(mesh["nx"]), int(mesh["ny"])
        self.model = mesh["model"]
        self.axisymmetric = s["geometry"] == "axisymmetric"
        grid = station_grid(self.length, self.h)
        self.xs = x_stations(self.length, self.nx, float(mesh["grading"]), self.model, grid)
        self.ys = stations([self.h / self.ny] * self.ny, self.h, grid)
        self.i_mid = self.nx if self.model == "half" else self.nx // 2
        self.ends = plate["ends"]

    def node(self, i, j):
        """Index of node (i, j)."""
        return i + j * (self.nx + 1)

    def solver_xy(self, n):
        """The solver's (x, y) of node index n, m."""
        return self.xs[n % (self.nx + 1)], self.ys[n // (self.nx + 1)]

    def ccx_xy(self, n):
        """ccx's coordinates of node index n, m: (x, y), or (r, z) in the axisymmetric one."""
        x, y = self.solver_xy(n)
        return (0.5 * self.length - x, y) if self.axisymmetric else (x, y)

    def elements(self):
        """[(index, [4 node indices in ccx's counter-clockwise order])] in element order."""
        out = []
        for j in range(self.ny):
            for i in range(self.nx):
                c = [self.node(i, j), self.node(i + 1, j), self.node(i + 1, j + 1),
                     self.node(i, j + 1)]
                if self.axisymmetric:
                    c = [c[1], c[0], c[3], c[2]]
                out.append((i + j * self.nx, c))
        return out

    def supports(self):
        """{node index: set of ccx dofs (1 = x or r, 2 = y or z) held at zero}."""
        fix = {"clamped": {1, 2}, "roller": {1}, "slider": {2}, "free": set()}[self.ends]
        held = {}
        for j in range(self.ny + 1):
            held.setdefault(self.node(0, j), set()).update(fix)
            end = self.node(self.nx, j)
            if self.model == "half":
                held.setdefault(end, set()).add(1)
            else:
                held.setdefault(end, set()).update(fix)
        return {n: d for n, d in held.items() if d}

    def mid_span(self):
        """{'top', 'mid', 'bottom'}: the mid-span node indices."""
        return {"top": self.node(self.i_mid, self.ny), "mid": self.node(self.i_mid, self.ny // 2),
                "bottom": self.node(self.i_mid, 0)}

    def top_nodes_tributary(self):
        """[(node index, tributary length along x, m)] of the top surface."""
        first = self.ny * (self.nx + 1)
        out = []
        for i in range(self.nx + 1):
            left = self.xs[i] - self.xs[i - 1] if i > 0 else 0.0
            right = self.xs[i + 1] - self.xs[i] if i < self.nx else 0.0
            out.append((first + i, 0.5 * (left + right)))
        return out

    def bottom_nodes(self):
        """Node indices of the bottom face y = 0."""
        return [self.node(i, 0) for i in range(self.nx + 1)]

    def smallest_sizes(self):
        """(smallest element length along x, element height), m."""
        dx = min(b - a for a, b in zip(self.xs, self.xs[1:]))
        return dx, self.h / self.ny

    def fold(self, x, y):
        """A probe point in the modelled part: x > L/2 mirrored to L - x in the half model."""
        if self.model == "half" and x > 0.5 * self.length:
            return self.length - x, y
        return x, y

    def element_containing(self, x, y):
        """The first element (lowest index) whose bounding box holds (x, y), or None."""
        tol = 1e-12 * self.length
        for j in range(self.ny):
            if not self.ys[j] - tol <= y <= self.ys[j + 1] + tol:
                continue
            for i in range(self.nx):
                if self.xs[i] - tol <= x <= self.xs[i + 1] + tol:
                    return i + j * self.nx
        return None
