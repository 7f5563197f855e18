"""Finite deformation (ALGORITHM.md section 3c, `kinematics: finite`): updated Lagrangian in the
Green-Naghdi frame, written on the reference geometry.

Per integration point the state holds the last step's displacement gradient G_n (2 x 2,
`[[xX, xY], [yX, yY]]`) and the unrotated strain e^ `(xx, yy, zz, gamma_xy)`. One step:
    G = du/dX (q4-sri: F-bar, G_bar = alpha F - I, alpha = sqrt(J_c / J)),
    F_mid = I + (G_n + G) / 2,  L = (G - G_n) F_mid^-1,  d = sym L,
    d^ = R_m^T d R_m (R_m the polar rotation of F_mid),  e^ += (d^xx, d^yy, 0, 2 d^xy),
    tau^ = material(e^)  (section 3 unchanged, densities per reference volume),
    tau = R tau^ R^T  (R that of F = I + G, or F_bar),
    f = sum w_ref P dN/dX with P = tau F^-T (the point's own F);
q4-sri splits tau into the in-plane mean m = (tau_xx + tau_yy) / 2, whose sum M = sum w_ref m
acts through the centroid's F_c as P_c = M F_c^-T, and the rest at each point. Output stress is
the Cauchy stress tau / det F (F_bar for q4-sri).

Written from the text of ALGORITHM.md alone (no code shared with the Rust solver).
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from .elements import Kinematics
from .mesh import PlateMesh

CHECK_EVERY = 32   # steps between the inversion and deformed-step checks (sections 3c, 7)


def polar_rotation(F: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(c, s) of the rotation R = [[c, -s], [s, c]] of the polar decomposition of 2 x 2
    F (..., 2, 2) with det F > 0 (section 3c)."""
    a = F[..., 0, 0] + F[..., 1, 1]
    b = F[..., 1, 0] - F[..., 0, 1]
    n = np.sqrt(a * a + b * b)
    return a / n, b / n


def rotate(t: np.ndarray, c: np.ndarray, s: np.ndarray) -> np.ndarray:
    """R t R^T of symmetric t = (xx, yy, zz, xy) (..., 4) by R = [[c, -s], [s, c]]; zz unchanged."""
    xx, yy, zz, xy = t[..., 0], t[..., 1], t[..., 2], t[..., 3]
    cc, ss, cs = c * c, s * s, c * s
    return np.stack([cc * xx + ss * yy - 2 * cs * xy,
                     ss * xx + cc * yy + 2 * cs * xy,
                     zz,
                     cs * (xx - yy) + (cc - ss) * xy], axis=-1)


def det2(F: np.ndarray) -> np.ndarray:
    return F[..., 0, 0] * F[..., 1, 1] - F[..., 0, 1] * F[..., 1, 0]


def unrotated_increment(Gn: np.ndarray, G: np.ndarray) -> np.ndarray:
    """Section 3c's in-plane step from G_n to G (npts, 2, 2): F_mid = I + (G_n + G) / 2,
    L = (G - G_n) F_mid^-1, d = sym L, and d^ = R_m^T d R_m (R_m the polar rotation of F_mid),
    returned as (xx, yy, 0, xy) (npts, 4) (tensor shear, not gamma)."""
    F_mid = np.eye(2) + 0.5 * (Gn + G)
    L = (G - Gn) @ np.swapaxes(inv_t2(F_mid), 1, 2)
    d = 0.5 * (L + np.swapaxes(L, 1, 2))
    cm, sm = polar_rotation(F_mid)
    d_vec = np.stack([d[:, 0, 0], d[:, 1, 1], np.zeros(len(d)), d[:, 0, 1]], axis=1)
    return rotate(d_vec, cm, -sm)                           # R_m^T d R_m


def inv_t2(F: np.ndarray) -> np.ndarray:
    """F^-T of 2 x 2 matrices (..., 2, 2)."""
    J = det2(F)
    out = np.empty_like(F)
    out[..., 0, 0] = F[..., 1, 1] / J
    out[..., 0, 1] = -F[..., 1, 0] / J
    out[..., 1, 0] = -F[..., 0, 1] / J
    out[..., 1, 1] = F[..., 0, 0] / J
    return out


def piola_weighted(t: np.ndarray, FinvT: np.ndarray, w: np.ndarray) -> np.ndarray:
    """w P = w tau F^-T of the in-plane tau = (xx, yy, zz, xy) (zz not used), flattened per point
    as (xX, xY, yX, yY); w (npts,) the weights (m^3)."""
    T = np.empty((len(t), 2, 2))
    T[:, 0, 0], T[:, 1, 1] = t[:, 0], t[:, 1]
    T[:, 0, 1] = T[:, 1, 0] = t[:, 3]
    return (w[:, None, None] * (T @ FinvT)).ravel()


def gradient_operator(pm: PlateMesh, dX: np.ndarray, dY: np.ndarray) -> sp.csr_matrix:
    """Sparse operator u -> per point (G_xX, G_xY, G_yX, G_yY); dX, dY (nel, npts, 4 nodes).
    Its transpose maps per-point (w P_xX, w P_xY, w P_yX, w P_yY) to nodal forces."""
    nel, npt = dX.shape[:2]
    ndof = 2 * pm.n_nodes
    rows, cols, vals = [], [], []
    base = 4 * np.arange(nel * npt).reshape(nel, npt, 1)
    xd = np.broadcast_to((2 * pm.conn)[:, None, :], dX.shape)
    yd = xd + 1
    for comp, (d, dofs) in enumerate(((dX, xd), (dY, xd), (dX, yd), (dY, yd))):
        rows.append(np.broadcast_to(base + comp, dX.shape).ravel())
        cols.append(dofs.ravel())
        vals.append(d.ravel())
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                         shape=(4 * nel * npt, ndof))


def centroid_difference(kin: Kinematics) -> tuple[np.ndarray, np.ndarray]:
    """The centroid derivatives in the one-point element's difference form (section 2):
    nodes 2 and 3 take nodes 0 and 1's negated. (nel, 1, 4) each."""
    bx = np.stack([kin.bx[:, 0], kin.bx[:, 1], -kin.bx[:, 0], -kin.bx[:, 1]], axis=1)
    by = np.stack([kin.by[:, 0], kin.by[:, 1], -kin.by[:, 0], -kin.by[:, 1]], axis=1)
    return bx[:, None, :], by[:, None, :]


class FiniteKinematics:
    """The finite-deformation element kernel of one plate (section 3c), with its state."""

    def __init__(self, element: str, pm: PlateMesh, kin: Kinematics, width: float):
        self.element = element
        self.pm = pm
        bx, by = centroid_difference(kin)
        self.b_ref = (bx[:, 0], by[:, 0])                  # (nel, 4) each
        self.area_w = kin.area * width                      # A W per element
        if element == "q4-1pt":
            self.D = gradient_operator(pm, bx, by)
            self.w = self.area_w[:, None]                   # (nel, 1)
        elif element in ("q4-full", "q4-sri"):
            self.D = gradient_operator(pm, kin.dNdx, kin.dNdy)
            self.w = kin.detJw * width                      # (nel, 4) w_ref = det J W
        else:
            raise ValueError(f"unknown element {element}")
        self.Dc = gradient_operator(pm, bx, by) if element == "q4-sri" else None
        self.DT = self.D.T.tocsr()
        self.DcT = self.Dc.T.tocsr() if self.Dc is not None else None
        nel, npt = self.w.shape
        self.nel, self.npt = nel, npt
        self.w_flat = self.w.ravel()
        self.Gn = np.zeros((nel * npt, 2, 2))               # last step's gradient (G_bar: sri)
        self.e_hat = np.zeros((nel * npt, 4))               # unrotated strain (gamma_xy)
        self.S_ref = (bx[:, 0] ** 2 + by[:, 0] ** 2).sum(axis=1)

    def gradients(self, u: np.ndarray) -> tuple[np.ndarray, np.ndarray | None]:
        """Each point's own G (npts, 2, 2) and, for q4-sri, the centroid's G_c (nel, 2, 2)."""
        G = (self.D @ u).reshape(-1, 2, 2)
        Gc = (self.Dc @ u).reshape(-1, 2, 2) if self.Dc is not None else None
        return G, Gc

    def update(self, u: np.ndarray, material) -> tuple[np.ndarray, float, float, np.ndarray]:
        """Section 3c at u_n: the material update (once per step), committing G and e^.
        Returns (Cauchy stress (npts, 4) (xx, yy, zz, xy), strain energy, plastic work
        increment, internal force vector)."""
        eye = np.eye(2)
        G, Gc = self.gradients(u)
        F = eye + G
        if self.Dc is not None:
            # F-bar: G_bar = alpha F - I, alpha = sqrt(J_c / J) (J, J_c of the 2 x 2 F, F_c)
            Fc = eye + Gc
            alpha = np.sqrt(np.repeat(det2(Fc), self.npt) / det2(F))
            G_step = alpha[:, None, None] * F - eye
        else:
            G_step = G
        d_hat = unrotated_increment(self.Gn, G_step)
        self.e_hat[:, 0] += d_hat[:, 0]
        self.e_hat[:, 1] += d_hat[:, 1]
        self.e_hat[:, 3] += 2.0 * d_hat[:, 3]
        # the material of section 3 (3b) at e^: the unrotated Kirchhoff stress, per reference volume
        tau_hat, energy, dwork = material.update(self.e_hat, self.w_flat)
        F_rot = eye + G_step                                # F (F_bar for q4-sri)
        c, s = polar_rotation(F_rot)
        tau = rotate(tau_hat, c, s)
        # forces: P = tau F^-T with the point's own F
        FinvT = inv_t2(F)
        if self.Dc is not None:
            m = 0.5 * (tau[:, 0] + tau[:, 1])
            t_dev = tau.copy()
            t_dev[:, 0] -= m
            t_dev[:, 1] -= m
            f = self.DT @ piola_weighted(t_dev, FinvT, self.w_flat)
            M = (self.w_flat * m).reshape(self.nel, self.npt).sum(axis=1)
            Pc = M[:, None, None] * inv_t2(Fc)
            f += self.DcT @ Pc.ravel()
        else:
            f = self.DT @ piola_weighted(tau, FinvT, self.w_flat)
        self.Gn = G_step
        cauchy = tau / det2(F_rot)[:, None]
        return cauchy, energy, dwork, f

    def step_factor(self, u: np.ndarray) -> tuple[float, int]:
        """Section 3c's deformed-step factor and its element (deformed_step_factor)."""
        return deformed_step_factor(self.pm, self.b_ref, self.S_ref, u)


def deformed_step_factor(pm: PlateMesh, b_ref: tuple[np.ndarray, np.ndarray], S_ref: np.ndarray,
                         u: np.ndarray) -> tuple[float, int]:
    """min_e sqrt(S_ref / S_cur) and its element, S = sum_a |grad N_a|^2 at the centroid on
    the reference and the current configuration (section 3c's deformed-step check, on the
    section's in-plane geometry also in the ring, section 3e); b_ref the centroid's
    (b_x, b_y) (nel, 4) each (1/m)."""
    bx, by = b_ref
    ux, uy = u[2 * pm.conn], u[2 * pm.conn + 1]
    # the centroid's F_c; the current gradients are F_c^-T grad_X N_a
    Fc = np.empty((len(bx), 2, 2))
    Fc[:, 0, 0] = 1.0 + (ux * bx).sum(1)
    Fc[:, 0, 1] = (ux * by).sum(1)
    Fc[:, 1, 0] = (uy * bx).sum(1)
    Fc[:, 1, 1] = 1.0 + (uy * by).sum(1)
    FiT = inv_t2(Fc)
    gx = FiT[:, 0, 0, None] * bx + FiT[:, 0, 1, None] * by
    gy = FiT[:, 1, 0, None] * bx + FiT[:, 1, 1, None] * by
    S_cur = (gx * gx + gy * gy).sum(axis=1)
    ratio = np.sqrt(S_ref / S_cur)
    e = int(np.argmin(ratio))
    return float(ratio[e]), e


def inverted_element(pm: PlateMesh, u: np.ndarray) -> int | None:
    """The first element with a deformed corner Jacobian <= 0 (section 7), or None. At corner a
    of a bilinear quad det J is (x_{a+1} - x_a) x (x_{a-1} - x_a) / 4."""
    x = pm.coords + u.reshape(-1, 2)
    xe = x[pm.conn]                                         # (nel, 4, 2)
    nxt = np.roll(xe, -1, axis=1) - xe
    prv = np.roll(xe, 1, axis=1) - xe
    detc = nxt[..., 0] * prv[..., 1] - nxt[..., 1] * prv[..., 0]
    bad = np.flatnonzero((detc <= 0).any(axis=1))
    return int(bad[0]) if bad.size else None
