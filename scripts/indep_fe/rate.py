"""Strain-rate and temperature dependent plasticity (ALGORITHM.md section 3b), written from that
section alone.

The flow stress is the static curve sigma_s(k) times a rate factor of the equivalent plastic
strain rate kdot = dk / dt (backward Euler over the run's step dt) and, with Johnson-Cook's
`thermal`, a thermal factor Theta = 1 - T*^m of the temperature at the START of the step
(explicit in temperature). The return is section 3's radial return with dk from the
rate-dependent consistency condition, solved point by point:

- Cowper-Symonds:  q_tr - 3 mu dk = sigma_s(k + dk) (1 + x),  x = (dk / (D dt))^(1/q),
  solved in x on [0, q_tr / sigma_s(k) - 1], dk = D dt x^q;
- Johnson-Cook:    q_tr - 3 mu dk = (A + B (k + dk)^n) [1 + C ln(max(dk / (rate0 dt), 1))] Theta,
  solved in dk on [0, (q_tr - sigma_s(k) Theta) / (3 mu)].

Both residuals decrease strictly on their brackets (positive at 0, <= 0 at the upper end), so
the root is unique. ALGORITHM.md describes a Newton iteration safeguarded by bisection that
stops at |f| <= 1e-14 q_tr; this module solves the same equation its own way, all yielding
points at once, by a bracketing method without derivatives (Illinois regula falsi guarded by
bisection, `bracketed_root`) down to the last bits of the root: the converged roots agree to
far below the CI gate (1e-8) and nothing here is shared with the Rust code.

Plastic work density q_new dk (q_new = q_tr - 3 mu dk); the stored rate is
(k_new - k_old) / dt (0 where a point does not flow); heating dT += beta w / (rho c).
"""
from __future__ import annotations

import math

import numpy as np

from .scene import RateLaw

EPS = np.finfo(float).eps
FTOL = 1e-15          # |f| <= FTOL q_tr: f within a few roundings of its terms (each ~q_tr)


class JohnsonCookStatic:
    """Johnson-Cook's static curve sigma_s(k) = A + B k^n (k >= 0)."""

    def __init__(self, A: float, B: float, n: float):
        self.A, self.B, self.n = A, B, n

    def __call__(self, k):
        return self.A + self.B * np.power(k, self.n)


class RateDependence:
    """The rate law of a material and its per-point state: the last step's equivalent plastic
    strain rate `kdot` and the temperature rise `dT` (section 3b)."""

    def __init__(self, law: RateLaw, static, mu: float, dt: float, density: float,
                 n_points: int):
        if dt is None or not (dt > 0 and math.isfinite(dt)):
            raise ValueError("the rate law needs the run's time step dt > 0")
        self.law, self.static, self.mu, self.dt, self.rho = law, static, mu, dt, density
        self.kdot = np.zeros(n_points)
        self.dT = np.zeros(n_points)
        self.thermal = law.thermal

    # -- thermal factor ---------------------------------------------------------------------
    def theta(self) -> np.ndarray:
        """Theta = 1 - T*^m, T* = clamp((T - Tr) / (Tm - Tr), 0, 1) with T = T0 + dT, from the
        current (start of step) temperature; 1 without heating. Tr, the reference
        temperature, is T0 unless the scene gives it (a preheated shot)."""
        if self.thermal is None:
            return np.ones_like(self.dT)
        th = self.thermal
        tr = th.initial_temperature if th.reference_temperature is None else th.reference_temperature
        rise = self.dT if tr == th.initial_temperature else self.dT + (th.initial_temperature - tr)
        ts = np.clip(rise / (th.melting_temperature - tr), 0.0, 1.0)
        return 1.0 - np.power(ts, self.law.m)

    def temperature(self) -> np.ndarray:
        return self.thermal.initial_temperature + self.dT

    # -- the consistency condition ----------------------------------------------------------
    def _residual_cs(self, q_tr, k):
        """f(x) of Cowper-Symonds for the lanes `idx`, and dk(x)."""
        D, qe, mu3, dt, sig = self.law.D, self.law.q, 3 * self.mu, self.dt, self.static
        dk_of = lambda x: D * dt * np.power(x, qe)

        def f(x, idx):
            dk = dk_of(x)
            return q_tr[idx] - mu3 * dk - sig(k[idx] + dk) * (1.0 + x)
        return f, dk_of

    def _residual_jc(self, q_tr, k, theta):
        C, mu3, sig = self.law.C, 3 * self.mu, self.static
        ref = self.law.reference_rate * self.dt       # dk at the reference rate

        def f(dk, idx):
            # rate factor 1 at and below the reference rate (no softening by slow flow)
            r = 1.0 + C * np.log(np.maximum(dk / ref, 1.0))
            return q_tr[idx] - mu3 * dk - sig(k[idx] + dk) * r * theta[idx]

        def f_pow(y, idx):
            # at and below the reference rate from k = 0, in y = dk^n (the static curve
            # A + B y is then linear; dk^n itself is infinitely steep at 0)
            dk = np.power(y, 1.0 / self.law.n)
            return q_tr[idx] - mu3 * dk - (self.law.A + self.law.B * y) * theta[idx]

        def f_log(s, idx):
            # above the reference rate, in s = ln dk: f(e^s), the rate factor 1 + C (s - ln ref)
            dk = np.exp(s)
            return (q_tr[idx] - mu3 * dk
                    - sig(k[idx] + dk) * (1.0 + C * (s - math.log(ref))) * theta[idx])
        return f, f_pow, f_log

    def return_map(self, q_tr: np.ndarray, k: np.ndarray, theta: np.ndarray) -> np.ndarray:
        """dk >= 0 of every yielding point (q_tr > sigma_s(k) Theta given)."""
        if self.law.kind == "cowper_symonds":
            f, dk_of = self._residual_cs(q_tr, k)
            hi = q_tr / self.static(k) - 1.0
            return dk_of(bracketed_root(f, np.zeros(q_tr.size), np.maximum(hi, 0.0),
                                        FTOL * q_tr))
        # Johnson-Cook: the rate factor has a kink at the reference rate (dk = ref); the root
        # is below it where f(ref) <= 0 (rate factor 1 there: a smooth equation in dk), above
        # it otherwise, where it is solved in ln dk (the rate factor linear in it)
        f, f_pow, f_log = self._residual_jc(q_tr, k, theta)
        hi = np.maximum((q_tr - self.static(k) * theta) / (3 * self.mu), 0.0)
        ref = self.law.reference_rate * self.dt
        ftol = FTOL * q_tr
        idx = np.arange(q_tr.size)
        above = (hi > ref) & (f(np.full(q_tr.size, ref), idx) > 0.0)
        dk = np.empty(q_tr.size)
        slow = np.flatnonzero(~above & (k > 0.0))
        if slow.size:
            f_slow = lambda x, i: f(x, slow[i])
            dk[slow] = bracketed_root(f_slow, np.zeros(slow.size), np.minimum(hi[slow], ref),
                                      ftol[slow])
        first = np.flatnonzero(~above & (k <= 0.0))
        if first.size:
            n = self.law.n
            f_first = lambda y, i: f_pow(y, first[i])
            y = bracketed_root(f_first, np.zeros(first.size),
                               np.power(np.minimum(hi[first], ref), n), ftol[first])
            dk[first] = np.power(y, 1.0 / n)
        fast = np.flatnonzero(above)
        if fast.size:
            f_fast = lambda s, i: f_log(s, fast[i])
            dk[fast] = np.exp(bracketed_root(f_fast, np.full(fast.size, math.log(ref)),
                                             np.log(hi[fast]), ftol[fast]))
        return dk

    # -- after the return -------------------------------------------------------------------
    def commit(self, yielding: np.ndarray, k_old: np.ndarray, k_new: np.ndarray,
               work_density: np.ndarray) -> None:
        """The rate state (k_new - k_old) / dt (0 elsewhere) and the adiabatic heating
        dT += beta w / (rho c) of the yielding points."""
        self.kdot[:] = 0.0
        self.kdot[yielding] = (k_new - k_old) / self.dt
        if self.thermal is not None:
            th = self.thermal
            self.dT[yielding] += th.taylor_quinney * work_density / (self.rho * th.specific_heat)


def bracketed_root(f, lo: np.ndarray, hi: np.ndarray, ftol: np.ndarray,
                   max_iter: int = 400) -> np.ndarray:
    """The root in [lo, hi] (per lane) of a residual f(x, idx) (idx: the lanes' positions in
    these arrays) that decreases through zero there (positive at lo, <= 0 at hi), to the last
    bits: vectorised Illinois (regula falsi that halves
    the stale end's value when one end is kept twice), with a bisection step after an
    iterate whose |f| is not below half the previous one's. A lane stops at an x with |f(x)| <= ftol (per lane;
    callers pass a few roundings of the stresses f is the difference of), or when its bracket is
    within 4 machine epsilons of its ends (then the midpoint). A lane whose f(hi) >= 0 (the root
    at the upper end to round-off, e.g. hi ~ lo) returns hi; one whose f(lo) <= 0 returns lo."""
    n = hi.size
    lo = lo.astype(float).copy()
    hi = hi.astype(float).copy()
    idx_all = np.arange(n)
    flo = f(lo, idx_all)
    fhi = f(hi, idx_all)
    x = hi.copy()                            # lanes with fhi >= 0 keep hi
    active = np.flatnonzero((fhi < 0.0) & (flo > 0.0) & (hi > lo))
    x[(flo <= 0.0)] = lo[(flo <= 0.0)]
    last = np.zeros(n, np.int8)              # +1: lo replaced last, -1: hi replaced last
    bisect_next = np.zeros(n, bool)
    f_prev = np.full(n, np.inf)              # |f| of the previous iterate
    for _ in range(max_iter):
        if active.size == 0:
            break
        a, b, fa, fb = lo[active], hi[active], flo[active], fhi[active]
        mid = a + 0.5 * (b - a)
        done = (mid <= a) | (mid >= b) | (b - a <= 4 * EPS * np.maximum(np.abs(a), np.abs(b)))
        x[active[done]] = mid[done]
        keep = ~done
        active, a, b, fa, fb, mid = (active[keep], a[keep], b[keep], fa[keep], fb[keep],
                                     mid[keep])
        if active.size == 0:
            break
        with np.errstate(divide="ignore", invalid="ignore"):
            c = b - fb * (b - a) / (fb - fa)
        use_mid = bisect_next[active] | ~((c > a) & (c < b))
        c = np.where(use_mid, mid, c)
        fc = f(c, active)
        zero = np.abs(fc) <= ftol[active]
        x[active[zero]] = c[zero]
        up = fc > 0.0                        # the root is above c: c is the new lower end
        dn = fc < 0.0
        i_up, i_dn = active[up], active[dn]
        # Illinois: the end kept twice in a row has its value halved
        stale_hi = i_up[last[i_up] == 1]
        fhi[stale_hi] *= 0.5
        stale_lo = i_dn[last[i_dn] == -1]
        flo[stale_lo] *= 0.5
        lo[i_up], flo[i_up], last[i_up] = c[up], fc[up], 1
        hi[i_dn], fhi[i_dn], last[i_dn] = c[dn], fc[dn], -1
        # guard: an iterate that did not halve |f| of the one before is followed by bisection
        bisect_next[active] = ~use_mid & (np.abs(fc) > 0.5 * f_prev[active])
        f_prev[active] = np.abs(fc)
        active = active[~zero]
    else:
        x[active] = lo[active] + 0.5 * (hi[active] - lo[active])
    return x
