"""Plane-strain small-strain material (ALGORITHM.md section 3): linear elastic, and von Mises
plasticity with isotropic hardening by radial return in total-strain form; with
`plasticity.rate`, the rate (and temperature) dependent return of section 3b (rate.py).

Strain in: (xx, yy, zz, gamma_xy) engineering shear. Stress out: (xx, yy, zz, xy).
Plastic strain state: (xx, yy, zz, xy) with the TENSOR shear component.
"""
from __future__ import annotations

import numpy as np

from .scene import Material

SQ32 = np.sqrt(1.5)


def lame(E: float, nu: float) -> tuple[float, float]:
    return E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))


def von_mises(s: np.ndarray) -> np.ndarray:
    sxx, syy, szz, sxy = s[..., 0], s[..., 1], s[..., 2], s[..., 3]
    return np.sqrt(((sxx - syy) ** 2 + (syy - szz) ** 2 + (szz - sxx) ** 2) / 2 + 3 * sxy ** 2)


class Hardening:
    """sigma_y(k): linear (sigma_y0 + H k, H = E E_t / (E - E_t)) or a piecewise-linear table
    in k that holds its last value beyond its last point."""

    def __init__(self, E: float, sigma_y0: float, tangent: float | None = None,
                 table: list[tuple[float, float]] | None = None):
        if table is not None:
            self.k_pts = np.array([r[0] for r in table], float)
            self.s_pts = np.array([r[1] for r in table], float)
            self.H = None
        else:
            et = 0.0 if tangent is None else tangent
            self.H = E * et / (E - et)
            self.sigma_y0 = sigma_y0

    def __call__(self, k: np.ndarray) -> np.ndarray:
        if self.H is not None:
            return self.sigma_y0 + self.H * k
        return np.interp(k, self.k_pts, self.s_pts)

    def return_map(self, q: np.ndarray, k: np.ndarray, mu: float) -> np.ndarray:
        """dk >= 0 solving q - 3 mu dk - sigma_y(k + dk) = 0 (q > sigma_y(k) given)."""
        if self.H is not None:
            return (q - self(k)) / (3 * mu + self.H)
        # Piecewise linear: G(kt) = q - 3 mu (kt - k) - sigma_y(kt) is linear between table
        # points (and decreasing while every slope > -3 mu), so the root is found exactly by
        # locating the bracketing segment and interpolating linearly on it.
        K, S = self.k_pts, self.s_pts
        G = lambda kt: q - 3 * mu * (kt - k) - self(kt)
        Gb = q[:, None] - 3 * mu * (K[None, :] - k[:, None]) - S[None, :]
        cand = (K[None, :] > k[:, None]) & (Gb <= 0)
        has = cand.any(axis=1)
        jr = np.argmax(cand, axis=1)                       # first bracketing table point
        kr = K[jr]
        kl = np.maximum(k, np.where(jr > 0, K[np.maximum(jr - 1, 0)], -np.inf))
        Gl = G(kl)
        Gr = Gb[np.arange(q.size), jr]
        with np.errstate(divide="ignore", invalid="ignore"):
            inside = kl + Gl * (kr - kl) / (Gl - Gr)
        # beyond the last point sigma_y is constant: G has slope -3 mu
        kl_out = np.maximum(k, K[-1])
        beyond = kl_out + G(kl_out) / (3 * mu)
        return np.where(has, inside, beyond) - k


class MaterialModel:
    def __init__(self, mat: Material, n_points: int, dt: float | None = None):
        """`dt`: the run's time step, needed by a rate law (section 3b) only."""
        self.lam, self.mu = lame(mat.youngs_modulus, mat.poisson_ratio)
        self.plastic = mat.plasticity is not None
        self.eps_p = np.zeros((n_points, 4))
        self.k = np.zeros(n_points)
        self.rate = None
        if self.plastic and mat.plasticity.rate is not None \
                and mat.plasticity.rate.kind == "johnson_cook":
            from .rate import JohnsonCookStatic, RateDependence
            law = mat.plasticity.rate
            self.hard = JohnsonCookStatic(law.A, law.B, law.n)
            self.rate = RateDependence(law, self.hard, self.mu, dt, mat.density, n_points)
        elif self.plastic:
            pl = mat.plasticity
            self.hard = Hardening(mat.youngs_modulus, pl.yield_stress, pl.linear_tangent, pl.table)
            if pl.rate is not None:
                from .rate import RateDependence
                self.rate = RateDependence(pl.rate, self.hard, self.mu, dt, mat.density, n_points)
            if pl.table is not None:
                slopes = np.diff(self.hard.s_pts) / np.diff(self.hard.k_pts)
                if slopes.size and slopes.min() <= -3 * self.mu:
                    raise ValueError("hardening table softens faster than -3 mu: return map not unique")

    def update(self, eps: np.ndarray, w: np.ndarray):
        """Stress at total strain eps (n, 4), committing the plastic state.
        Returns (stress (n,4), elastic strain energy sum w s:eps_e/2, plastic-work increment)."""
        lam, mu = self.lam, self.mu
        ee = eps.copy()
        ee[:, 3] *= 0.5                      # tensor shear
        ee -= self.eps_p                     # elastic strain, tensor form
        tr = ee[:, 0] + ee[:, 1] + ee[:, 2]
        s = 2 * mu * ee
        s[:, :3] += lam * tr[:, None]
        dwork = 0.0
        if self.plastic:
            p = (s[:, 0] + s[:, 1] + s[:, 2]) / 3.0
            d = s.copy()
            d[:, :3] -= p[:, None]
            dd = d[:, 0] ** 2 + d[:, 1] ** 2 + d[:, 2] ** 2 + 2 * d[:, 3] ** 2
            q = np.sqrt(1.5 * dd)
            sy = self.hard(self.k)
            if self.rate is not None:
                theta = self.rate.theta()       # start-of-step temperature (section 3b)
                sy = sy * theta
            yielding = np.flatnonzero(q > sy)
            if yielding.size:
                ky = self.k[yielding]
                if self.rate is None:
                    dk = self.hard.return_map(q[yielding], ky, mu)
                else:
                    dk = self.rate.return_map(q[yielding], ky, theta[yielding])
                n = d[yielding] / np.sqrt(dd[yielding])[:, None]
                self.eps_p[yielding] += (SQ32 * dk)[:, None] * n
                s[yielding] -= (2 * mu * SQ32 * dk)[:, None] * n
                self.k[yielding] = ky + dk
                if self.rate is None:
                    dwork = float(np.sum(0.5 * (sy[yielding] + self.hard(ky + dk)) * dk
                                         * w[yielding]))
                else:
                    # section 3b: backward Euler's dissipation q_new dk, q_new = q_tr - 3 mu dk
                    wd = (q[yielding] - 3 * mu * dk) * dk
                    dwork = float(np.sum(wd * w[yielding]))
                    self.rate.commit(yielding, ky, self.k[yielding], wd)
                ee[yielding] -= (SQ32 * dk)[:, None] * n
            elif self.rate is not None:
                self.rate.kdot[:] = 0.0
        # s : eps_e with shear counted twice (ee holds the tensor shear)
        energy = 0.5 * float(np.sum(w * (s[:, 0] * ee[:, 0] + s[:, 1] * ee[:, 1] +
                                         s[:, 2] * ee[:, 2] + 2 * s[:, 3] * ee[:, 3])))
        return s, energy, dwork
