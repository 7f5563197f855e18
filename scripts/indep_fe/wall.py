"""The rigid, frictionless planar wall y = 0 (ALGORITHM.md section 5c), written from that text:
kinematic enforcement on every node with a free u_y, the wall's dissipation from the impulse
times the mean of the velocities before and after (booked at t_n as the kinetic energy is read), the bearing force (the body's own force on
the held nodes), the foot radius, the contact radius, the bar's length, Taylor's undeformed
length and the side's outline.
SI units: forces N and energies J of the whole body (the symmetry factor s applied)."""
from __future__ import annotations

import numpy as np

TOUCH = 1e-9     # a node lower than TOUCH h touches the wall (h the body's thickness)
GROWTH = 0.005   # a section whose radius has grown by this fraction counts as deformed (5c)


def impulse_work(impulse: np.ndarray, before: np.ndarray, after, first: bool
                 ) -> tuple[float, float]:
    """The work of impulses (N s, per dof) that take half-step velocities from `before` to
    `after` (m/s): W_n = sum J (before + after) / 2 (the change of the half-step kinetic
    energy), and the share of it in section 7's kinetic energy at t_n, read with the mean
    velocity v_n = (before + after) / 2: sum (J / 2) (before + v_n) / 2 = sum J (3 before +
    after) / 8 (0 at t_0, whose kinetic energy is the initial one)."""
    W = float(np.sum(impulse * 0.5 * (before + after)))
    return W, 0.0 if first else float(np.sum(impulse * (3.0 * before + after) / 8.0))


class RigidWall:
    def __init__(self, coords: np.ndarray, inv_m: np.ndarray, m_node: np.ndarray, s: float,
                 thickness: float, top: int, bottom: int):
        """top, bottom: the axis nodes at the bar's two ends (the axis is the bottom one's x)."""
        self.X, self.Y = coords[:, 0].copy(), coords[:, 1].copy()
        self.free = inv_m[1::2] != 0.0          # nodes with a free u_y
        self.im = inv_m[1::2]
        self.m = m_node
        self.s, self.axis_x, self.touch = s, self.X[bottom], TOUCH * thickness
        self.top, self.bottom = top, bottom
        self.R = np.zeros(self.X.size)          # the wall's force on each u_y at t_n, N
        self.done = 0.0                         # sum_{k<n} W_k, J
        self.W = 0.0                            # W_n, J
        self.W_at_t_n = 0.0                     # the share of W_n in the kinetic energy at t_n, J
        self.touched = np.zeros(self.X.size, dtype=bool)
        self.bearing = 0.0                      # B_n = s sum of f_int on the held nodes, N
        self.max_bearing = 0.0
        self.max_foot = 0.0
        outer = float(np.min(self.X))             # the side: the reference's outer surface
        self.side = np.flatnonzero(self.X == outer)
        self.side = self.side[np.argsort(self.Y[self.side], kind="stable")]
        self.r0 = self.axis_x - outer
        self.outline = (np.zeros(0), np.zeros(0))  # (heights, radii) of the side at the last reading

    def launch(self, velocity: float) -> np.ndarray:
        """v_0: -velocity on every free u_y (m/s), per dof."""
        v = np.zeros(2 * self.X.size)
        v[1::2] = np.where(self.free, -velocity, 0.0)
        return v

    def solve(self, u: np.ndarray, v_half: np.ndarray, f_int: np.ndarray, dt: float,
              first: bool, h: float | None = None) -> float:
        """Step 2 of t_n: R_i from the contact-free prediction; returns F_n (N). dt is
        dt_{n+1/2} (s), h the velocity step (s): dt/2 at n = 0, else dt, unless given
        (section 6b: the mean of the two steps)."""
        h = (0.5 * dt if first else dt) if h is None else h
        self.done += self.W
        y = self.Y + u[1::2]
        v_free = v_half[1::2] - h * f_int[1::2] * self.im
        hit = self.free & (y + dt * v_free < 0.0)
        v_wall = -y / dt
        self.R = np.where(hit, self.m * (v_wall - v_free) / h, 0.0)
        self.W, self.W_at_t_n = impulse_work(self.s * h * self.R, v_half[1::2], v_wall, first)
        self.bearing = self.s * float(np.sum(np.where(hit, f_int[1::2], 0.0)))
        self.max_bearing = max(self.max_bearing, self.bearing)
        return self.s * float(np.sum(self.R))

    def apply(self, f_ext: np.ndarray) -> None:
        f_ext[1::2] += self.R

    @property
    def energy(self) -> float:
        """The wall's dissipation at t_n, J."""
        return -(self.done + self.W_at_t_n)

    def reading(self, u: np.ndarray) -> tuple[float, float, float, float, float]:
        """The history's wall columns at u_n: foot_radius_m (the nodes that have touched the
        wall), bar_length_m (top minus bottom axis node), contact_radius_m (the nodes touching
        it now), bearing_force_N and undeformed_length_m; keeps the side's outline."""
        on = self.Y + u[1::2] <= self.touch
        self.touched |= on
        r = self.axis_x - (self.X + u[0::2])
        contact = float(np.max(r[on])) if on.any() else 0.0
        foot = float(np.max(r[self.touched])) if self.touched.any() else 0.0
        self.max_foot = max(self.max_foot, foot)
        y = self.Y + u[1::2]
        rs, ys = r[self.side], y[self.side]
        self.outline = (ys - y[self.bottom], rs)
        return (foot, float(y[self.top] - y[self.bottom]), contact, self.bearing,
                self.undeformed_length(rs, ys))

    def undeformed_length(self, rs: np.ndarray, ys: np.ndarray) -> float:
        """Taylor's X (section 5c): scanning the side from the top down, the first node whose
        radius reaches (1 + GROWTH) r0, and the point between it and the node above where the
        radius is (1 + GROWTH) r0, linear in the current height; X is the top side node's
        height minus that point's (0 when the top node has reached it, the whole side's height
        when none has), m."""
        threshold = (1.0 + GROWTH) * self.r0
        top = len(rs) - 1
        above = top
        for k in range(top, -1, -1):
            if rs[k] >= threshold:
                if k == top:
                    return 0.0
                t = (rs[k] - threshold) / (rs[k] - rs[above])
                return float(ys[top] - (ys[k] + t * (ys[above] - ys[k])))
            above = k
        return float(ys[top] - ys[0])

    def summary(self, v: np.ndarray, peak: float, release: float | None,
                row: tuple[float, float, float, float, float], plate, eqps: float | None) -> dict:
        """summary.json's wall (section 5c) from the last row's reading; v is v_{n+1/2} of the
        last step."""
        foot, length = row[0], row[1]
        rebound = float(np.sum(self.m * v[1::2]) / np.sum(self.m)) if release is not None else None
        return {
            "peak_force_N": self.max_bearing,
            "peak_step_force_N": peak,
            "release_time_s": release,
            "final_length_m": length,
            "length_ratio": length / plate.thickness,
            "foot_radius_m": foot,
            "foot_radius_ratio": foot / (0.5 * plate.length),
            "max_foot_radius_m": self.max_foot,
            "rebound_velocity_mps": rebound,
            "dissipated_energy_J": self.energy,
            "max_equivalent_plastic_strain": eqps,
            "undeformed_length_m": row[4],
            "final_outline": {"height_m": self.outline[0].tolist(),
                              "radius_m": self.outline[1].tolist()},
        }
