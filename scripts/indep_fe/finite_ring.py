"""Finite deformation in the axisymmetric ring (ALGORITHM.md section 3e, `geometry:
axisymmetric` with `kinematics: finite`): section 3c's updated Lagrangian step on section 3d's
ring, written on the reference geometry (weights w = 2 pi R det J_ref, m^3, whole ring).

A point's deformation gradient is block diagonal: the in-plane F = I + G (section 3c) and the
hoop stretch F_t = 1 + g_t, g_t = sum_a h_a u_x,a = u_r / R (h_a = -N_a / R, 1/m). The hoop is
principal and does not rotate. Per point the state holds G_n, g_t,n and the unrotated strain
e^ (xx, yy, zz = hoop, gamma_xy). One step:
    in-plane: section 3c's midpoint step (unrotated_increment);
    hoop:     e^_zz += (g_t - g_t,n) / (1 + (g_t,n + g_t) / 2);
    tau = R tau^ R^T (R in-plane), P = tau F^-T in-plane, P_t = tau_zz / F_t;
  q4-full: f_a += w P dN_a/dX, f_x,a += w P_t h_a at each 2x2 point;
  q4-sri:  F-bar on the ring's volume, alpha = (J_bar / J)^(1/3), J = det F F_t,
           J_bar = sum w J / sum w; deviator d = tau - m (1, 1, 1, 0) on the point's own F, F_t,
           and the mean m = tr(tau) / 3 through c = M w J / V (M = sum w m, V = sum w J);
  q4-1pt:  the ring's mean rows (mb_x, mb_y, mh), weight V (its reference volume); the
           hourglass forces of section 3d are added by the solver on the total displacements.
Output: the Cauchy stress tau / (det F F_t) (the bars for q4-sri).

Written from the text of ALGORITHM.md alone (no code shared with the Rust solver).
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from .axisymmetric import Ring
from .elements import Kinematics
from .finite import (centroid_difference, deformed_step_factor, det2, gradient_operator,
                     inv_t2, piola_weighted, polar_rotation, rotate, unrotated_increment)
from .mesh import PlateMesh


def hoop_operator(pm: PlateMesh, h: np.ndarray) -> sp.csr_matrix:
    """Sparse operator u -> per point g_t = sum_a h_a u_x,a; h (nel, npts, 4 nodes) (1/m)."""
    nel, npt = h.shape[:2]
    rows = np.broadcast_to(np.arange(nel * npt).reshape(nel, npt, 1), h.shape).ravel()
    cols = np.broadcast_to((2 * pm.conn)[:, None, :], h.shape).ravel()
    return sp.csr_matrix((h.ravel(), (rows, cols)), shape=(nel * npt, 2 * pm.n_nodes))


class FiniteRing:
    """The finite-deformation ring kernel of one plate (section 3e), with its state."""

    def __init__(self, element: str, pm: PlateMesh, kin: Kinematics, ring: Ring):
        self.element = element
        self.pm = pm
        bx, by = centroid_difference(kin)
        self.b_ref = (bx[:, 0], by[:, 0])                  # (nel, 4) each, the deformed-step check
        self.S_ref = (bx[:, 0] ** 2 + by[:, 0] ** 2).sum(axis=1)
        if element == "q4-1pt":
            self.D = gradient_operator(pm, ring.mbx[:, None], ring.mby[:, None])
            self.H = hoop_operator(pm, ring.mh[:, None])
            self.w = ring.V[:, None]                        # (nel, 1) m^3
        elif element in ("q4-full", "q4-sri"):
            self.D = gradient_operator(pm, kin.dNdx, kin.dNdy)
            self.H = hoop_operator(pm, ring.h)
            self.w = ring.w                                 # (nel, 4) m^3
        else:
            raise ValueError(f"unknown element {element}")
        self.DT, self.HT = self.D.T.tocsr(), self.H.T.tocsr()
        self.nel, self.npt = self.w.shape
        self.w_flat = self.w.ravel()
        self.V_ref = self.w.sum(axis=1)                     # (nel,) reference ring volume
        n = self.nel * self.npt
        self.Gn = np.zeros((n, 2, 2))                       # last step's G (F_bar - I: sri)
        self.gtn = np.zeros(n)                              # last step's g_t (F_t,bar - 1: sri)
        self.e_hat = np.zeros((n, 4))                       # unrotated strain (gamma_xy)

    def current_volume(self, J: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(V, J_bar) per element: V = sum_gp w J (m^3), J_bar = V / V_ref."""
        V = (self.w_flat * J).reshape(self.nel, self.npt).sum(axis=1)
        return V, V / self.V_ref

    def update(self, u: np.ndarray, material) -> tuple[np.ndarray, float, float, np.ndarray]:
        """Section 3e at u_n: the material update (once per step), committing G, g_t and e^.
        Returns (Cauchy stress (npts, 4) (xx, yy, zz, xy), strain energy, plastic work
        increment, internal force vector)."""
        eye = np.eye(2)
        G = (self.D @ u).reshape(-1, 2, 2)
        gt = self.H @ u
        F, Ft = eye + G, 1.0 + gt
        sri = self.element == "q4-sri"
        if sri:
            J = det2(F) * Ft
            V, J_bar = self.current_volume(J)
            alpha = np.cbrt(np.repeat(J_bar, self.npt) / J)
            G_step = alpha[:, None, None] * F - eye
            gt_step = alpha * Ft - 1.0
        else:
            G_step, gt_step = G, gt
        d_hat = unrotated_increment(self.Gn, G_step)
        self.e_hat[:, 0] += d_hat[:, 0]
        self.e_hat[:, 1] += d_hat[:, 1]
        self.e_hat[:, 2] += (gt_step - self.gtn) / (1.0 + 0.5 * (self.gtn + gt_step))
        self.e_hat[:, 3] += 2.0 * d_hat[:, 3]
        # the material of section 3 (3b) at e^: the unrotated Kirchhoff stress, per reference volume
        tau_hat, energy, dwork = material.update(self.e_hat, self.w_flat)
        F_rot = eye + G_step                                # F (F_bar for q4-sri)
        c, s = polar_rotation(F_rot)
        tau = rotate(tau_hat, c, s)                         # the hoop (zz) unchanged
        FinvT = inv_t2(F)                                   # the point's own F, F_t
        if sri:
            m = (tau[:, 0] + tau[:, 1] + tau[:, 2]) / 3.0
            dev = tau - m[:, None] * np.array([1.0, 1.0, 1.0, 0.0])
            f = self.DT @ piola_weighted(dev, FinvT, self.w_flat)
            f += self.HT @ (self.w_flat * dev[:, 2] / Ft)
            # the mean stress on the variation of the current volume: c = M w J / V per point
            M = (self.w_flat * m).reshape(self.nel, self.npt).sum(axis=1)
            cpt = np.repeat(M / V, self.npt) * self.w_flat * J
            f += self.DT @ (cpt[:, None, None] * FinvT).ravel()
            f += self.HT @ (cpt / Ft)
        else:
            f = self.DT @ piola_weighted(tau, FinvT, self.w_flat)
            f += self.HT @ (self.w_flat * tau[:, 2] / Ft)
        self.Gn, self.gtn = G_step, gt_step
        cauchy = tau / (det2(F_rot) * (1.0 + gt_step))[:, None]
        return cauchy, energy, dwork, f

    def step_factor(self, u: np.ndarray) -> tuple[float, int]:
        """Section 3c's deformed-step factor on the section's in-plane geometry (section 3e)."""
        return deformed_step_factor(self.pm, self.b_ref, self.S_ref, u)
