"""Surface contact of the rigid nose (ALGORITHM.md section 5b, `load.impactor.contact: surface`).

The nose is a rigid cylinder of radius R whose axis is at (x_c, y_c) = (L/2, h + R - delta_S).
The top-surface nodes within 1.1 R of x_c (reference x) are the candidates. A candidate at
displacement u has d = (d_x, e - R), d_x = (x - x_c) + u_x, e = (y - h) + u_y + delta_S, the
penetration g = (2 e R - e^2 - d_x^2) / (R + |d|) (= R - |d| without the cancellation near R) and
the outward normal n = d / |d|. Two enforcements:

- kinematic (the default; predictor-corrector): at step 2 of t_n, from f_int(u_n), the
  contact-free positions at t_{n+1} are predicted and the forces lambda_i n_i (and their
  reaction on the impactor) that close the linearised gaps are solved in closed form on an
  active set; the contact energy is the kinetic energy its impulses took out (their work,
  booked at t_n as section 7 reads the kinetic energy: wall.impulse_work).
A node at or above the nose's centre (d_y >= 0: it has crossed the nose; the Rust solver stops
there) takes no force, so that the contact never pulls.
- penalty: f_i = k_i g n at u_n, k_i = s_p m_i lambda_i, energy k_i g^2 / 2.

The impactor moves by central differences under the whole plate's force F = s P,
P = -sum f_i,y (the modelled part's).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .mesh import PlateMesh
from .wall import impulse_work


MAX_ACTIVE_SET_PASSES = 64


@dataclass
class SurfaceNose:
    R: float               # nose radius, m
    enforcement: str       # kinematic | penalty
    s_p: float | None      # penalty_scale (penalty only)
    m_s: float             # impactor mass (whole), kg
    v0: float              # initial velocity, m/s (positive toward the plate)
    s: float               # symmetry factor (2 half, 1 full)
    x_c: float             # axis x = L/2
    h: float               # plate thickness (top surface y = h)
    nodes: np.ndarray      # (n_c,) candidate node indices, in node order
    X: np.ndarray          # (n_c, 2) their reference coordinates
    k: np.ndarray          # (n_c,) penalty stiffnesses k_i = s_p m_i lambda_i, N/m (0: kinematic)
    m: np.ndarray          # (n_c,) their lumped masses (modelled part)
    im: np.ndarray         # (n_c, 2) inverse mass of each of their dofs, 0 when fixed
    weight: np.ndarray     # (n_c,) whole-plate count of each node: 1 on the axis or full model, else 2
    # state at t_n
    dS: float = 0.0                 # delta_S,n
    v_half: float | None = None     # v_S,n-1/2 (None at n = 0)
    F: float = 0.0                  # F_n (whole plate), F_0 = 0 (penalty)
    f: np.ndarray | None = None     # (n_c, 2) the nose's forces on the candidates at t_n
    energy: float = 0.0             # contact energy E_c at t_n (whole plate)
    n_contact: float = 0.0          # nodes in contact (whole plate)
    half_width: float = 0.0         # largest |d_x| of a node in contact
    # kinematic: the work of the contact impulses before step n, and F_n-1 for the impulse
    work: float = 0.0
    F_prev: float | None = None
    passes: int = 0                 # active-set passes of the last solve

    @classmethod
    def build(cls, pm: PlateMesh, length: float, thickness: float, radius: float,
              enforcement: str, s_p: float | None, mass: float, velocity: float,
              node_mass: np.ndarray, inv_m: np.ndarray, lam_e: np.ndarray) -> "SurfaceNose":
        """Candidates, their inverse masses and (penalty) stiffnesses (section 5b). `node_mass`
        is the lumped mass per node (modelled part), `inv_m` the inverse mass per dof (0 on a
        fixed dof), `lam_e` the section 4 element eigenvalues."""
        if enforcement not in ("kinematic", "penalty"):
            raise ValueError(f"unknown enforcement {enforcement!r}")
        nx, ny = pm.nx, pm.ny
        x_c = length / 2.0
        top = np.arange(nx + 1) + ny * (nx + 1)                      # nodes (i, ny), node order
        X = pm.coords[top]
        cand = np.flatnonzero(np.abs(X[:, 0] - x_c) <= 1.1 * radius)   # column indices i
        nodes = top[cand]
        m = node_mass[nodes]
        if enforcement == "penalty":
            lam_top = lam_e[np.arange(nx) + (ny - 1) * nx]             # elements (i, ny - 1)
            lam_i = np.array([max(lam_top[e] for e in (i - 1, i) if 0 <= e < nx) for i in cand])
            k = s_p * m * lam_i
        else:
            k = np.zeros(cand.size)
        im = np.stack([inv_m[2 * nodes], inv_m[2 * nodes + 1]], axis=1)
        on_axis = X[cand, 0] == x_c
        weight = np.where(on_axis | (pm.symmetry == 1.0), 1.0, 2.0)
        return cls(R=radius, enforcement=enforcement, s_p=s_p, m_s=mass, v0=velocity,
                   s=pm.symmetry, x_c=x_c, h=thickness, nodes=nodes, X=X[cand].copy(), k=k,
                   m=m, im=im, weight=weight, f=np.zeros((cand.size, 2)))

    @property
    def kinematic(self) -> bool:
        return self.enforcement == "kinematic"

    @property
    def description(self) -> str:
        if self.kinematic:
            return "surface(kinematic)"
        sp = repr(float(self.s_p))
        return f"surface(penalty, penalty_scale={sp[:-2] if sp.endswith('.0') else sp})"

    def stable_step(self, dt_plate: float) -> float:
        """Kinematic: the plate's. Penalty: dt_crit = 2 / sqrt((2 / dt_p)^2 + max_i k_i / m_i)
        (Weyl's inequality)."""
        if self.kinematic:
            return dt_plate
        extra = float(np.max(self.k / self.m)) if self.k.size else 0.0
        return 2.0 / math.sqrt((2.0 / dt_plate) ** 2 + extra)

    def candidate_u(self, u: np.ndarray) -> np.ndarray:
        """(n_c, 2) the candidates' displacements."""
        return np.stack([u[2 * self.nodes], u[2 * self.nodes + 1]], axis=1)

    def gap(self, uc: np.ndarray, dS: float):
        """Section 5b at candidate displacements uc (n_c, 2) and impactor displacement dS:
        returns (d_x, d_y, |d|, g)."""
        dx = (self.X[:, 0] - self.x_c) + uc[:, 0]
        e = (self.X[:, 1] - self.h) + uc[:, 1] + dS
        dy = e - self.R
        dist = np.sqrt(dx * dx + dy * dy)
        g = (2.0 * e * self.R - e * e - dx * dx) / (self.R + dist)
        return dx, dy, dist, g

    # ------------------------------------------------------------------ penalty
    def contact(self, u: np.ndarray, dS: float):
        """Penalty: the nose's forces at displacement u and impactor displacement dS: returns
        (f (n_c, 2), F whole plate, E_c whole plate, nodes in contact (whole plate), half-width)."""
        dx, dy, dist, g = self.gap(self.candidate_u(u), dS)
        on = (g > 0.0) & (dist > 0.0) & (dy < 0.0)
        f = np.zeros((self.nodes.size, 2))
        scale = np.where(on, self.k * g / np.where(on, dist, 1.0), 0.0)
        f[:, 0] = scale * dx
        f[:, 1] = scale * dy
        P = -float(np.sum(f[:, 1]))
        E = self.s * float(np.sum(np.where(on, 0.5 * self.k * g * g, 0.0)))
        count = float(np.sum(self.weight[on]))
        half = float(np.max(np.abs(dx[on]))) if on.any() else 0.0
        return f, self.s * P, E, count, half

    # ------------------------------------------------------------------ kinematic
    def free_velocity(self, vc: np.ndarray, fc: np.ndarray, dt: float, first: bool,
                      h: float | None = None) -> tuple[float, np.ndarray]:
        """The velocity step h of step 3 (default dt/2 at n = 0, else dt; section 6b: given) and
        the candidates' contact-free v_{n+1/2} = v_{n-1/2} - h f_int / m ((n_c, 2))."""
        hs = (0.5 * dt if first else dt) if h is None else h
        return hs, vc - hs * fc * self.im

    def kinematic_forces(self, uc: np.ndarray, vc: np.ndarray, fc: np.ndarray, dt: float,
                         first: bool, h: float | None = None):
        """The kinematic solve of section 5b from the candidates' u_n, v_{n-1/2} and f_int(u_n)
        (each (n_c, 2)): returns (lambda (n_c,), n (n_c, 2), d_x at the prediction). dt is
        dt_{n+1/2}, h the velocity step (default dt/2 at n = 0, else dt; section 6b: given)."""
        hs, v_free = self.free_velocity(vc, fc, dt, first, h)
        up = uc + dt * v_free                               # contact-free u_{n+1}
        dp = self.dS + dt * (self.v0 if first else self.v_half)
        dx, dy, dist, g = self.gap(up, dp)
        ok = dist > 0.0
        safe = np.where(ok, dist, 1.0)
        nx_, ny_ = np.where(ok, dx / safe, 0.0), np.where(ok, dy / safe, 0.0)
        w = self.im[:, 0] * nx_ * nx_ + self.im[:, 1] * ny_ * ny_
        a = ny_
        c = dt * hs
        r = self.s / self.m_s
        usable = ok & (w > 0.0) & (ny_ < 0.0)
        wsafe = np.where(usable, w, 1.0)
        active = usable & (g > 0.0)
        self.passes = 0
        for _ in range(MAX_ACTIVE_SET_PASSES):
            self.passes += 1
            num = float(np.sum(np.where(active, a * g / (c * wsafe), 0.0)))
            den = 1.0 + r * float(np.sum(np.where(active, a * a / wsafe, 0.0)))
            S = num / den
            rhs = g / c - r * a * S
            new = usable & (rhs > 0.0)
            if np.array_equal(new, active):
                break
            active = new
        else:   # not settled after 64 passes: the last set, with its own S
            num = float(np.sum(np.where(active, a * g / (c * wsafe), 0.0)))
            den = 1.0 + r * float(np.sum(np.where(active, a * a / wsafe, 0.0)))
            rhs = g / c - r * a * (num / den)
        lam = np.where(active, rhs / wsafe, 0.0)
        return lam, np.stack([nx_, ny_], axis=1), dx

    def solve(self, u: np.ndarray, v_half: np.ndarray, f_int: np.ndarray, dt: float,
              first: bool, h: float | None = None, dt_prev: float | None = None) -> float:
        """Section 6 step 2 of t_n (kinematic): the nose's forces f_n, F_n from f_int(u_n), then
        the work of their impulses h f_n on the candidates and -h F_n on the impactor (energy:
        minus the works of the steps before and the share of this one at t_n). Returns the
        impulse increment (F_n-1 + F_n) dt / 2 (0 at n = 0; section 6b: on the previous
        step's length dt_prev)."""
        uc, vc, fc = self.candidate_u(u), self.candidate_u(v_half), self.candidate_u(f_int)
        lam, nrm, dx = self.kinematic_forces(uc, vc, fc, dt, first, h)
        self.f = lam[:, None] * nrm
        self.F = self.s * float(np.sum(lam * (-nrm[:, 1])))
        on = lam > 0.0
        self.n_contact = float(np.sum(self.weight[on]))
        self.half_width = float(np.max(np.abs(dx[on]))) if on.any() else 0.0
        hs, v_free = self.free_velocity(vc, fc, dt, first, h)
        after = v_free + hs * self.f * self.im
        W_plate, at_plate = impulse_work(self.s * hs * self.f, vc, after, first)
        before = self.v0 if first else self.v_half
        W_body, at_body = impulse_work(np.array([-hs * self.F]), before,
                                       before - hs * self.F / self.m_s, first)
        self.energy = -(self.work + at_plate + at_body)
        self.work += W_plate + W_body
        di = 0.0
        if self.F_prev is not None:
            di = 0.5 * (self.F_prev + self.F) * (dt if dt_prev is None else dt_prev)
        self.F_prev = self.F
        return di

    # ------------------------------------------------------------------ both
    def velocity(self, dt: float) -> float:
        """v_S,n = v_S,n-1/2 - dt F_n / (2m) (v0 at n = 0); dt the velocity step (section 6b:
        h_n, so v_S,n is the mean of v_S,n-1/2 and v_S,n+1/2)."""
        if self.v_half is None:
            return self.v0
        return self.v_half - dt * self.F / (2.0 * self.m_s)

    def apply(self, f_ext: np.ndarray) -> None:
        """Section 6 step 2: the nose's forces at t_n on the candidates."""
        f_ext[2 * self.nodes] += self.f[:, 0]
        f_ext[2 * self.nodes + 1] += self.f[:, 1]

    def step(self, u_new: np.ndarray, dt: float, h: float | None = None) -> float:
        """Section 6 step 5: the impactor to n+1; penalty: then the forces at u_{n+1},
        delta_S,n+1. Returns the impulse increment (F_n + F_{n+1}) dt / 2 (penalty; the kinematic
        one is counted by `solve` at n+1). dt is dt_{n+1/2}; h the velocity step (default dt/2
        at n = 0, else dt; section 6b: the mean of the two steps)."""
        F = self.F
        if self.v_half is None:
            self.v_half = self.v0 - (0.5 * dt if h is None else h) * F / self.m_s
        else:
            self.v_half = self.v_half - (dt if h is None else h) * F / self.m_s
        self.dS = self.dS + dt * self.v_half
        if self.kinematic:
            return 0.0
        self.f, F_new, self.energy, self.n_contact, self.half_width = self.contact(u_new, self.dS)
        self.F = F_new
        return 0.5 * (F + F_new) * dt
