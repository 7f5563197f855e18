"""Axisymmetric ring elements (ALGORITHM.md section 3d, `geometry: axisymmetric`), written from
that text alone: the half model's section is the diametral half-section of a round plate, rim at
x = 0, axis at x_axis = L/2, radius r = x_axis - x, so u_r = -u_x.

Everything is for the whole ring (2 pi rad): weights w = 2 pi r det J (m^3), row-sum masses
m_a = rho sum_gp N_a w (kg). The strain row zz is the hoop strain u_r / r = sum_a h_a u_x,a with
h_a = -N_a / r (1/m). As in elements.py each formulation is a strain operator B (4 x 8 per
point) and a weight, strain = B u_e and f_e = sum_gp w B^T s:
  q4-full: B at each 2x2 point with the hoop row;
  q4-sri:  B-bar on the ring's mean dilatation (rows xx, yy, zz each + (m_vol - vol_gp) / 3,
           m_vol = (mb_x + mh, mb_y) the mean rows), whose B^T s is section 3d's deviatoric
           point force plus M (mb_x + mh, mb_y), M = sum_gp w p_m;
  q4-1pt:  one point with the mean rows and weight V; hourglass control with k_hg on V.
"""
from __future__ import annotations

import numpy as np

from .elements import GAUSS_2X2, Formulation, Kinematics, b_standard, element_stiffness
from .mesh import PlateMesh


def shape_at_gauss() -> np.ndarray:
    """(4 gp, 4 nodes) N_a = (1 + xi xi_a)(1 + eta eta_a) / 4 at the 2x2 points."""
    xa = np.array([-1.0, 1.0, 1.0, -1.0])
    ea = np.array([-1.0, -1.0, 1.0, 1.0])
    xi, eta = GAUSS_2X2[:, 0:1], GAUSS_2X2[:, 1:2]
    return (1.0 + xi * xa) * (1.0 + eta * ea) / 4.0


class Ring:
    """The ring quantities of every element: radius, weights, hoop rows, mean rows (m, 1/m)."""

    def __init__(self, pm: PlateMesh, kin: Kinematics):
        x_axis = pm.coords[pm.top, 0]                       # the mid-span (axis) nodes' x
        N = shape_at_gauss()                                  # (gp, a)
        r_node = x_axis - pm.coords[pm.conn, 0]               # (nel, a) r_a
        self.N = N
        self.r = r_node @ N.T                                 # (nel, gp) r = sum_a N_a r_a
        self.w = 2.0 * np.pi * self.r * kin.detJw             # (nel, gp) m^3
        self.V = self.w.sum(axis=1)                           # (nel,) ring volume
        self.h = -N[None, :, :] / self.r[:, :, None]          # (nel, gp, a) 1/m
        wn = self.w / self.V[:, None]
        self.mbx = np.einsum("eg,ega->ea", wn, kin.dNdx)
        self.mby = np.einsum("eg,ega->ea", wn, kin.dNdy)
        self.mh = np.einsum("eg,ega->ea", wn, self.h)

    def node_masses(self, density: float) -> np.ndarray:
        """(nel, 4) row-sum masses m_a = rho sum_gp N_a w of each element's nodes, kg."""
        return density * np.einsum("eg,ga->ea", self.w, self.N)


def _with_hoop(B: np.ndarray, h: np.ndarray) -> np.ndarray:
    B[..., 2, 0::2] = h
    return B


def ring_formulation(name: str, pm: PlateMesh, kin: Kinematics, ring: Ring,
                     lam: float, mu: float, kappa: float) -> Formulation:
    """Section 3d's three elements as (B, w) (whole ring)."""
    if name == "q4-full":
        return Formulation(name, _with_hoop(b_standard(kin.dNdx, kin.dNdy), ring.h),
                           ring.w, kin.gp_xy)
    if name == "q4-sri":
        B = _with_hoop(b_standard(kin.dNdx, kin.dNdy), ring.h)
        dvol = np.zeros(B.shape[:2] + (8,))
        dvol[..., 0::2] = (ring.mbx + ring.mh)[:, None, :] - kin.dNdx - ring.h
        dvol[..., 1::2] = ring.mby[:, None, :] - kin.dNdy
        for c in range(3):
            B[..., c, :] += dvol / 3.0
        return Formulation(name, B, ring.w, kin.gp_xy)
    if name == "q4-1pt":
        B = _with_hoop(b_standard(ring.mbx, ring.mby), ring.mh)[:, None]
        x = pm.coords[pm.conn, 0]
        y = pm.coords[pm.conn, 1]
        hv = np.array([1.0, -1.0, 1.0, -1.0])
        gamma = (hv[None, :] - (x @ hv)[:, None] * kin.bx - (y @ hv)[:, None] * kin.by) / 4.0
        k_hg = kappa * (lam + 2 * mu) * ring.V * ((kin.bx ** 2).sum(1) + (kin.by ** 2).sum(1))
        return Formulation(name, B, ring.V[:, None], kin.centroid[:, None, :], gamma, k_hg)
    raise ValueError(f"unknown element {name}")


def ring_eigenvalues(form: Formulation, D: np.ndarray, m_e: np.ndarray) -> np.ndarray:
    """(nel,) lambda_max(M_e^-1/2 K_e M_e^-1/2) with the element's unequal row-sum masses
    (entry ij scaled by 1 / sqrt(m_i m_j)), section 3d's stable step."""
    K = element_stiffness(form, D)
    s = 1.0 / np.sqrt(np.repeat(m_e, 2, axis=1))              # (nel, 8 dofs)
    return np.linalg.eigvalsh(K * s[:, :, None] * s[:, None, :])[:, -1]


def ring_node_masses(pm: PlateMesh, m_e: np.ndarray) -> np.ndarray:
    """Global lumped masses (kg, whole ring) from the elements' row sums."""
    m = np.zeros(pm.n_nodes)
    np.add.at(m, pm.conn, m_e)
    return m
