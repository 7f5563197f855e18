"""Bilinear quad kinematics from scikit-fem and the three element formulations
(ALGORITHM.md section 2): q4-full, q4-sri (B-bar), q4-1pt (+ Flanagan-Belytschko hourglass).

Strain components are ordered (xx, yy, zz, gamma_xy) (engineering shear); element dofs are
ordered (u_x0, u_y0, u_x1, u_y1, ...). Every element formulation is expressed as a strain
operator B (per integration point, 4 x 8) and a weight w = det J * gauss weight * W, so that
    strain = B u_e,    f_e = sum_gp w B^T s.
For q4-sri, B is Hughes' B-bar, whose B^T s equals B_std^T s + p_m (b_c - b) (ALGORITHM.md).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from skfem import CellBasis, ElementQuad1

from .mesh import PlateMesh

_G = 1.0 / np.sqrt(3.0)
# 2x2 Gauss points of [-1, 1]^2 in the contract order (-,-), (+,-), (+,+), (-,+), weight 1 each.
GAUSS_2X2 = np.array([[-_G, -_G], [_G, -_G], [_G, _G], [-_G, _G]])


def _to_skfem_ref(xi_eta: np.ndarray) -> np.ndarray:
    """skfem's ElementQuad1 lives on [0, 1]^2 (nodes (0,0), (1,0), (1,1), (0,1)), our xi, eta on
    [-1, 1]^2 with nodes (-1,-1), (1,-1), (1,1), (-1,1): same local order, x_sk = (xi + 1) / 2."""
    return ((np.asarray(xi_eta, float) + 1.0) / 2.0).T.copy()


@dataclass
class Kinematics:
    dNdx: np.ndarray    # (nel, 4 gp, 4 nodes) at the 2x2 points
    dNdy: np.ndarray
    detJw: np.ndarray   # (nel, 4 gp) det J * gauss weight (area measure, no width)
    gp_xy: np.ndarray   # (nel, 4 gp, 2) physical coordinates of the 2x2 points
    bx: np.ndarray      # (nel, 4) centroid derivatives
    by: np.ndarray
    area: np.ndarray    # (nel,) sum of the 2x2 det J
    centroid: np.ndarray  # (nel, 2)


def kinematics(pm: PlateMesh) -> Kinematics:
    mesh = pm.skfem_mesh
    elem = ElementQuad1()
    # skfem weights sum to 1 on its unit reference square: (det J_sk)(1/4) = (det J_ours)(1).
    b4 = CellBasis(mesh, elem, quadrature=(_to_skfem_ref(GAUSS_2X2), np.full(4, 0.25)))
    grads = np.stack([b4.basis[a][0].grad for a in range(4)])     # (4 nodes, 2, nel, ngp)
    dNdx = np.ascontiguousarray(grads[:, 0].transpose(1, 2, 0))
    dNdy = np.ascontiguousarray(grads[:, 1].transpose(1, 2, 0))
    detJw = np.asarray(b4.dx)
    gp_xy = np.asarray(b4.mapping.F(b4.X)).transpose(1, 2, 0)       # (nel, ngp, 2)

    b1 = CellBasis(mesh, elem, quadrature=(_to_skfem_ref(np.zeros((1, 2))), np.ones(1)))
    g1 = np.stack([b1.basis[a][0].grad[:, :, 0] for a in range(4)])  # (4 nodes, 2, nel)
    bx = np.ascontiguousarray(g1[:, 0].T)
    by = np.ascontiguousarray(g1[:, 1].T)
    centroid = np.asarray(b1.mapping.F(b1.X))[:, :, 0].T
    return Kinematics(dNdx, dNdy, detJw, gp_xy, bx, by, detJw.sum(axis=1), centroid)


def b_standard(dndx: np.ndarray, dndy: np.ndarray) -> np.ndarray:
    """(..., 4 nodes) derivatives -> (..., 4 strains, 8 dofs) standard plane-strain B."""
    shape = dndx.shape[:-1]
    B = np.zeros(shape + (4, 8))
    B[..., 0, 0::2] = dndx
    B[..., 1, 1::2] = dndy
    B[..., 3, 0::2] = dndy
    B[..., 3, 1::2] = dndx
    return B


@dataclass
class Formulation:
    name: str
    B: np.ndarray          # (nel, ngp, 4, 8)
    w: np.ndarray          # (nel, ngp) det J * weight * W (whole width)
    gp_xy: np.ndarray      # (nel, ngp, 2)
    gamma: np.ndarray | None = None   # (nel, 4) hourglass shape vectors (q4-1pt)
    k_hg: np.ndarray | None = None    # (nel,) hourglass stiffness (q4-1pt)

    @property
    def n_gp(self) -> int:
        return self.B.shape[1]


def formulation(name: str, pm: PlateMesh, kin: Kinematics, width: float,
                lam: float, mu: float, kappa: float) -> Formulation:
    if name == "q4-full":
        return Formulation(name, b_standard(kin.dNdx, kin.dNdy), kin.detJw * width, kin.gp_xy)
    if name == "q4-sri":
        B = b_standard(kin.dNdx, kin.dNdy)
        # B-bar: eps_bar = eps + shift (1, 1, 1, 0), shift = (e_c - e)/3
        dvol = np.zeros(B.shape[:2] + (8,))
        dvol[..., 0::2] = kin.bx[:, None, :] - kin.dNdx
        dvol[..., 1::2] = kin.by[:, None, :] - kin.dNdy
        for c in range(3):
            B[..., c, :] += dvol / 3.0
        return Formulation(name, B, kin.detJw * width, kin.gp_xy)
    if name == "q4-1pt":
        B = b_standard(kin.bx, kin.by)[:, None]                      # (nel, 1, 4, 8)
        w = (kin.area * width)[:, None]
        x = pm.coords[pm.conn, 0]                                      # (nel, 4)
        y = pm.coords[pm.conn, 1]
        h = np.array([1.0, -1.0, 1.0, -1.0])
        hx = x @ h
        hy = y @ h
        gamma = (h[None, :] - hx[:, None] * kin.bx - hy[:, None] * kin.by) / 4.0
        k_hg = kappa * (lam + 2 * mu) * kin.area * width * (
            (kin.bx * kin.bx).sum(1) + (kin.by * kin.by).sum(1))
        return Formulation(name, B, w, kin.centroid[:, None, :], gamma, k_hg)
    raise ValueError(f"unknown element {name}")


def elastic_matrix(lam: float, mu: float) -> np.ndarray:
    """4x4 plane-strain D for (xx, yy, zz, gamma_xy)."""
    D = np.zeros((4, 4))
    D[:3, :3] = lam
    D[[0, 1, 2], [0, 1, 2]] += 2 * mu
    D[3, 3] = mu
    return D


def element_dofs(pm: PlateMesh) -> np.ndarray:
    """(nel, 8) global dofs of each element in (ux0, uy0, ux1, ...) order."""
    return np.stack([2 * pm.conn, 2 * pm.conn + 1], axis=2).reshape(-1, 8)


def element_stiffness(form: Formulation, D: np.ndarray) -> np.ndarray:
    """(nel, 8, 8) elastic element stiffness, hourglass stiffness included."""
    K = np.einsum("egci,cd,egdj,eg->eij", form.B, D, form.B, form.w, optimize=True)
    if form.gamma is not None:
        gg = form.k_hg[:, None, None] * form.gamma[:, :, None] * form.gamma[:, None, :]
        K[:, 0::2, 0::2] += gg
        K[:, 1::2, 1::2] += gg
    return K


def lumped_mass(pm: PlateMesh, kin: Kinematics, density: float, width: float) -> np.ndarray:
    """Per-node lumped (row-sum) mass: each element gives rho A W / 4 to each node."""
    m = np.zeros(pm.n_nodes)
    np.add.at(m, pm.conn, np.repeat((density * kin.area * width / 4.0)[:, None], 4, axis=1))
    return m


def element_eigenvalues(form: Formulation, D: np.ndarray, kin: Kinematics, density: float,
                        width: float) -> np.ndarray:
    """(nel,) lambda_e = lambda_max(M_e^-1/2 K_e M_e^-1/2), M_e = rho A W / 4 I (section 4)."""
    K = element_stiffness(form, D)
    return np.linalg.eigvalsh(K)[:, -1] / (density * kin.area * width / 4.0)


def critical_dt(form: Formulation, D: np.ndarray, kin: Kinematics, density: float,
                width: float) -> float:
    """dt_crit = 2 / sqrt(max_e lambda_e)."""
    return 2.0 / np.sqrt(element_eigenvalues(form, D, kin, density, width).max())


def global_operators(form: Formulation, pm: PlateMesh):
    """Sparse global strain operator (rows: gp-major, 4 strains each) and, for q4-1pt, the
    hourglass operator (rows: element-major, (q_x, q_y))."""
    ndof = 2 * pm.n_nodes
    edofs = element_dofs(pm)                                # (nel, 8)
    nel, ngp = form.B.shape[:2]
    rows = np.broadcast_to(np.arange(nel * ngp * 4).reshape(nel, ngp, 4, 1), form.B.shape)
    cols = np.broadcast_to(edofs[:, None, None, :], form.B.shape)
    B = sp.csr_matrix((form.B.ravel(), (rows.ravel(), cols.ravel())), shape=(nel * ngp * 4, ndof))
    B.eliminate_zeros()
    G = None
    if form.gamma is not None:
        r = np.concatenate([np.repeat(2 * np.arange(nel), 4), np.repeat(2 * np.arange(nel) + 1, 4)])
        c = np.concatenate([(2 * pm.conn).ravel(), (2 * pm.conn + 1).ravel()])
        v = np.concatenate([form.gamma.ravel(), form.gamma.ravel()])
        G = sp.csr_matrix((v, (r, c)), shape=(2 * nel, ndof))
    return B, G
