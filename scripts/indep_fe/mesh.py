"""Structured plate mesh (ALGORITHM.md section 1), built with scikit-fem's MeshQuad.

The node / element numbering of the contract is
    node (i, j)    -> i + j (nx + 1)
    element (i, j) -> i + j nx, local nodes (i,j), (i+1,j), (i+1,j+1), (i,j+1) (counter-clockwise).
skfem's MeshQuad.init_tensor numbers things differently, so the skfem mesh is re-indexed into
the contract numbering by coordinates (never by assuming skfem's internal order).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from skfem import MeshQuad

from .scene import MeshSpec, Plate


def graded_spacing(n: int, length: float, grading: float) -> np.ndarray:
    """n+1 node coordinates on [0, length]: geometric sizes, largest/smallest = grading,
    smallest element at `length` (mid-span)."""
    if grading == 1.0 or n == 1:
        x = np.linspace(0.0, length, n + 1)
    else:
        q = grading ** (1.0 / (n - 1))
        sizes = q ** np.arange(n - 1, -1, -1, dtype=float)   # largest at x = 0
        sizes *= length / sizes.sum()
        x = np.concatenate([[0.0], np.cumsum(sizes)])
    x[0], x[-1] = 0.0, length
    return x


def node_lines(plate: Plate, spec: MeshSpec) -> tuple[np.ndarray, np.ndarray]:
    L, h = plate.length, plate.thickness
    if spec.model == "half":
        xs = graded_spacing(spec.nx, L / 2, spec.grading)
    else:
        left = graded_spacing(spec.nx // 2, L / 2, spec.grading)
        xs = np.concatenate([left, (L - left[::-1])[1:]])
        xs[spec.nx // 2] = L / 2
    ys = np.linspace(0.0, h, spec.ny + 1)
    ys[-1] = h
    return xs, ys


@dataclass
class PlateMesh:
    nx: int
    ny: int
    xs: np.ndarray          # (nx+1,) node x lines
    ys: np.ndarray          # (ny+1,) node y lines
    skfem_mesh: MeshQuad    # skfem mesh in contract numbering (p columns = nodes, t columns = elements)
    coords: np.ndarray      # (nnode, 2)
    conn: np.ndarray        # (nel, 4) contract local order
    fixed_dofs: np.ndarray  # constrained dof indices (dof = 2 node + comp)
    top: int                # mid-span node indices
    mid: int
    bottom: int
    symmetry: float         # s = 2 (half) or 1 (full)

    @property
    def n_nodes(self) -> int:
        return self.coords.shape[0]

    @property
    def n_elements(self) -> int:
        return self.conn.shape[0]


def build_mesh(plate: Plate, spec: MeshSpec) -> PlateMesh:
    nx, ny = spec.nx, spec.ny
    xs, ys = node_lines(plate, spec)
    sk = MeshQuad.init_tensor(xs, ys)

    # --- nodes: skfem node -> (i, j) by coordinates -> contract index
    px, py = sk.p
    i = np.argmin(np.abs(px[:, None] - xs[None, :]), axis=1)
    j = np.argmin(np.abs(py[:, None] - ys[None, :]), axis=1)
    assert np.allclose(xs[i], px, rtol=0, atol=1e-12 * plate.length)
    assert np.allclose(ys[j], py, rtol=0, atol=1e-12 * plate.length)
    new_of_old = i + j * (nx + 1)
    assert np.unique(new_of_old).size == new_of_old.size == (nx + 1) * (ny + 1)
    coords = np.empty((new_of_old.size, 2))
    coords[new_of_old] = sk.p.T

    # --- elements: each skfem element -> its lower-left node (i, j) -> contract index;
    #     local order from coordinates: (min x, min y), (max x, min y), (max x, max y), (min x, max y)
    t_new = new_of_old[sk.t]                       # (4, nel) nodes in contract numbering
    ex, ey = coords[t_new, 0], coords[t_new, 1]    # (4, nel)
    conn = np.empty((sk.t.shape[1], 4), dtype=np.int64)
    right = ex > ex.mean(axis=0)
    upper = ey > ey.mean(axis=0)
    for a, (r, u) in enumerate([(False, False), (True, False), (True, True), (False, True)]):
        sel = (right == r) & (upper == u)
        assert np.all(sel.sum(axis=0) == 1)
        local = np.argmax(sel, axis=0)
        conn_a = t_new[local, np.arange(t_new.shape[1])]
        conn[:, a] = conn_a
    ll = conn[:, 0]
    el_index = (ll % (nx + 1)) + (ll // (nx + 1)) * nx
    order = np.empty_like(el_index)
    order[el_index] = np.arange(el_index.size)
    conn = conn[order]
    # sanity: the contract numbering
    ii, jj = np.meshgrid(np.arange(nx), np.arange(ny))
    ii, jj = ii.ravel(), jj.ravel()   # element index = ii + jj nx (row-major in j)
    n0 = ii + jj * (nx + 1)
    assert np.array_equal(conn, np.stack([n0, n0 + 1, n0 + nx + 2, n0 + nx + 1], axis=1))

    mesh = MeshQuad(coords.T.copy(), conn.T.copy())
    assert np.array_equal(mesh.t, conn.T), "skfem re-ordered the element nodes"

    # --- boundary conditions
    node = lambda i_, j_: i_ + j_ * (nx + 1)
    jall = np.arange(ny + 1)
    # ends: clamped u_x = u_y = 0, roller u_x = 0, slider u_y = 0, free: none (ALGORITHM.md,
    # plate.ends)
    comps = {"clamped": (0, 1), "roller": (0,), "slider": (1,), "free": ()}[plate.ends]
    support = lambda i_: [2 * node(i_, jall) + c for c in comps]
    fixed = support(0) or [np.zeros(0, dtype=int)]
    if spec.model == "half":
        fixed.append(2 * node(nx, jall))                  # symmetry: u_x = 0 at x = L/2
        imid, s = nx, 2.0
    else:
        fixed += support(nx)
        imid, s = nx // 2, 1.0
    fixed_dofs = np.unique(np.concatenate(fixed))

    return PlateMesh(nx, ny, xs, ys, mesh, coords, conn, fixed_dofs,
                     top=node(imid, ny), mid=node(imid, ny // 2), bottom=node(imid, 0), symmetry=s)


def find_element(pm: PlateMesh, x: float, y: float, length: float) -> int:
    """First (lowest index) element whose bounding box contains (x, y)."""
    tol = 1e-12 * length
    ex = pm.coords[pm.conn, 0]
    ey = pm.coords[pm.conn, 1]
    inside = ((ex.min(1) - tol <= x) & (x <= ex.max(1) + tol) &
              (ey.min(1) - tol <= y) & (y <= ey.max(1) + tol))
    hits = np.flatnonzero(inside)
    if hits.size == 0:
        raise ValueError(f"probe ({x}, {y}) is outside the modelled plate")
    return int(hits[0])
