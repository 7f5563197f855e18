"""Surface contact of the rigid nose (ALGORITHM.md section 5b, `load.impactor.contact: surface`).

The nose is a rigid cylinder of radius R whose axis is at (x_c, y_c) = (L/2, h + R - delta_S).
The top-surface nodes within 1.1 R of x_c (reference x) are the candidates; a candidate at the
current position p = X + u, with d = p - (x_c, y_c) and g = R - |d| > 0, takes the penalty
force k_i g d / |d| and stores k_i g^2 / 2, k_i = s_p m_i lambda_i. The impactor moves by
central differences under the whole plate's force F = s P, P = -sum f_i,y (the modelled part's).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .mesh import PlateMesh


@dataclass
class SurfaceNose:
    R: float               # nose radius, m
    s_p: float             # penalty_scale
    m_s: float             # impactor mass (whole), kg
    v0: float              # initial velocity, m/s (positive toward the plate)
    s: float               # symmetry factor (2 half, 1 full)
    x_c: float             # axis x = L/2
    h: float               # plate thickness (top surface y = h)
    nodes: np.ndarray      # (n_c,) candidate node indices, in node order
    X: np.ndarray          # (n_c, 2) their reference coordinates
    k: np.ndarray          # (n_c,) penalty stiffnesses k_i = s_p m_i lambda_i, N/m (modelled part)
    m: np.ndarray          # (n_c,) their lumped masses (modelled part)
    weight: np.ndarray     # (n_c,) whole-plate count of each node: 1 on the axis or full model, else 2
    # state at t_n
    dS: float = 0.0                 # delta_S,n
    v_half: float | None = None     # v_S,n-1/2 (None at n = 0)
    F: float = 0.0                  # F_n (whole plate), F_0 = 0
    f: np.ndarray | None = None     # (n_c, 2) the nose's forces on the candidates at t_n
    energy: float = 0.0             # contact energy E_c at t_n (whole plate)
    n_contact: float = 0.0          # nodes with g > 0 (whole plate)
    half_width: float = 0.0         # largest |p_x - x_c| of a node in contact

    @classmethod
    def build(cls, pm: PlateMesh, length: float, thickness: float, radius: float, s_p: float,
              mass: float, velocity: float, node_mass: np.ndarray,
              lam_e: np.ndarray) -> "SurfaceNose":
        """Candidates and their penalty stiffnesses (section 5b). `node_mass` is the lumped mass
        per node (modelled part), `lam_e` the section 4 element eigenvalues."""
        nx, ny = pm.nx, pm.ny
        x_c = length / 2.0
        top = np.arange(nx + 1) + ny * (nx + 1)                      # nodes (i, ny), node order
        X = pm.coords[top]
        cand = np.flatnonzero(np.abs(X[:, 0] - x_c) <= 1.1 * radius)   # column indices i
        lam_top = lam_e[np.arange(nx) + (ny - 1) * nx]                 # elements (i, ny - 1)
        lam_i = np.array([max(lam_top[e] for e in (i - 1, i) if 0 <= e < nx) for i in cand])
        nodes = top[cand]
        m = node_mass[nodes]
        k = s_p * m * lam_i
        on_axis = X[cand, 0] == x_c
        weight = np.where(on_axis | (pm.symmetry == 1.0), 1.0, 2.0)
        return cls(R=radius, s_p=s_p, m_s=mass, v0=velocity, s=pm.symmetry, x_c=x_c,
                   h=thickness, nodes=nodes, X=X[cand].copy(), k=k, m=m, weight=weight,
                   f=np.zeros((cand.size, 2)))

    @property
    def description(self) -> str:
        sp = repr(float(self.s_p))
        return f"surface(penalty_scale={sp[:-2] if sp.endswith('.0') else sp})"

    def stable_step(self, dt_plate: float) -> float:
        """dt_crit = 2 / sqrt((2 / dt_p)^2 + max_i k_i / m_i) (Weyl's inequality)."""
        extra = float(np.max(self.k / self.m)) if self.k.size else 0.0
        return 2.0 / math.sqrt((2.0 / dt_plate) ** 2 + extra)

    def contact(self, u: np.ndarray, dS: float):
        """The nose's forces at displacement u and impactor displacement dS: returns
        (f (n_c, 2), F whole plate, E_c whole plate, nodes in contact (whole plate), half-width)."""
        y_c = self.h + self.R - dS
        p = self.X + np.stack([u[2 * self.nodes], u[2 * self.nodes + 1]], axis=1)
        dx = p[:, 0] - self.x_c
        dy = p[:, 1] - y_c
        dist = np.sqrt(dx * dx + dy * dy)
        g = self.R - dist
        on = (g > 0.0) & (dist > 0.0)
        f = np.zeros_like(p)
        scale = np.where(on, self.k * g / np.where(on, dist, 1.0), 0.0)
        f[:, 0] = scale * dx
        f[:, 1] = scale * dy
        P = -float(np.sum(f[:, 1]))
        E = self.s * float(np.sum(np.where(on, 0.5 * self.k * g * g, 0.0)))
        count = float(np.sum(self.weight[on]))
        half = float(np.max(np.abs(dx[on]))) if on.any() else 0.0
        return f, self.s * P, E, count, half

    def velocity(self, dt: float) -> float:
        """v_S,n = v_S,n-1/2 - dt F_n / (2m) (v0 at n = 0)."""
        if self.v_half is None:
            return self.v0
        return self.v_half - dt * self.F / (2.0 * self.m_s)

    def apply(self, f_ext: np.ndarray) -> None:
        """Section 6 step 2: the nose's forces at t_n on the candidates."""
        f_ext[2 * self.nodes] += self.f[:, 0]
        f_ext[2 * self.nodes + 1] += self.f[:, 1]

    def step(self, u_new: np.ndarray, dt: float) -> float:
        """Section 6 step 5: the impactor to n+1, then the forces at u_{n+1}, delta_S,n+1;
        returns the impulse increment (F_n + F_{n+1}) dt / 2."""
        F = self.F
        if self.v_half is None:
            self.v_half = self.v0 - dt * F / (2.0 * self.m_s)
        else:
            self.v_half = self.v_half - dt * F / self.m_s
        self.dS = self.dS + dt * self.v_half
        self.f, F_new, self.energy, self.n_contact, self.half_width = self.contact(u_new, self.dS)
        self.F = F_new
        return 0.5 * (F + F_new) * dt
