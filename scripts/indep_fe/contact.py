"""Contact law alpha(P) = P (a - b ln P), P = F / W (ALGORITHM.md section 5), and the
eq. (21) root solve (section 6 step 5)."""
from __future__ import annotations

import math

from .scene import ContactLaw, Impactor, Material


class ContactLawExceeded(RuntimeError):
    pass


class Law:
    def __init__(self, a: float, b: float, width: float, description: str):
        self.a, self.b, self.width = a, b, width
        self.p_star = math.exp(a / b - 1.0)       # maximum of alpha(P)
        self.description = description

    def alpha(self, P: float) -> float:
        return 0.0 if P <= 0.0 else P * (self.a - self.b * math.log(P))

    def dalpha(self, P: float) -> float:
        return self.a - self.b * (1.0 + math.log(P))

    def energy(self, F: float) -> float:
        """Exact potential E_c = W (P alpha(P)/2 - b P^2/4)."""
        if F <= 0.0:
            return 0.0
        P = F / self.width
        return self.width * (P * self.alpha(P) / 2.0 - self.b * P * P / 4.0)

    def solve(self, alpha_free: float, c: float, guess: float | None = None) -> float:
        """F in (0, W P*] with g(F) = alpha(F/W) + c F - alpha_free = 0, c = dt^2/(6m) >= 0.
        Safeguarded Newton with bisection; g is increasing and concave on the interval."""
        W = self.width
        g = lambda F: self.alpha(F / W) + c * F - alpha_free
        lo, hi = 0.0, W * self.p_star
        g_hi = g(hi)
        if g_hi < 0.0:
            raise ContactLawExceeded(
                f"contact law maximum exceeded: the indentation {alpha_free:.6g} m needs more "
                f"than the law's maximum alpha(P*) = {self.alpha(self.p_star):.6g} m at "
                f"P* = {self.p_star:.6g} N/m (F = {hi:.6g} N); eq. (21) has no root on the "
                f"physical branch ({self.description})")
        if g_hi == 0.0:
            return hi
        F = guess if guess is not None and lo < guess < hi else 0.5 * hi
        for _ in range(200):
            gF = g(F)
            if gF == 0.0:
                return F
            if gF < 0.0:
                lo = F
            else:
                hi = F
            dg = self.dalpha(F / W) / W + c
            Fn = F - gF / dg if dg > 0.0 else -1.0
            if not (lo < Fn < hi):
                Fn = 0.5 * (lo + hi)
            if abs(Fn - F) <= 4e-16 * abs(F) or hi - lo <= 4e-16 * hi:
                return Fn
            F = Fn
        return F


def make_law(imp: Impactor, mat: Material, width: float) -> Law:
    r = imp.nose_radius
    E, nu = mat.youngs_modulus, mat.poisson_ratio
    Es, nus = imp.youngs_modulus, imp.poisson_ratio
    cl: ContactLaw = imp.contact_law
    if cl.kind == "paper":
        l = cl.length_unit
        c = (1 - nus ** 2) / (math.pi * Es) + 1.0 / (math.pi * E)
        return Law(c * (1.0 + math.log(l * l / (r * c))), c, width,
                   f"paper law, length_unit = {l} m")
    if cl.kind == "johnson":
        d = cl.datum_depth
        chis = (1 - nus ** 2) / (math.pi * Es)
        chip = (1 - nu ** 2) / (math.pi * E)
        estar = 1.0 / ((1 - nus ** 2) / Es + (1 - nu ** 2) / E)
        lk = math.log(4 * r / (math.pi * estar))
        a = (chis * (2 * math.log(4 * r) - lk - 1.0)
             + chip * (2 * math.log(2 * d) - lk - nu / (1 - nu)))
        return Law(a, chis + chip, width, f"johnson law, datum_depth = {d} m")
    raise ValueError(cl.kind)
