#!/usr/bin/env python3
"""Writes alpha-steel.csv: the line-contact law's indentation for steel on steel, three
readings, from the formulas of reference-data/paper/contact-law.md (section 1 and 5), written
here independently of the Rust solver. Plain python3, no packages. Run from anywhere:

    python3 reference-data/contact-law/make_alpha_steel.py
"""
import math
import os

E = Es = 207e9
nu = nus = 0.3
r = d = 0.010
pi = math.pi
c = (1 - nus**2) / (pi * Es) + 1 / (pi * E)          # paper: chi_p without (1 - nu^2)
cs = (1 - nus**2) / (pi * Es)
cp = (1 - nu**2) / (pi * E)
Est = 1 / ((1 - nus**2) / Es + (1 - nu**2) / E)


def paper(P, l):
    return P * c * (1 - math.log(P * r * c / l**2))


def johnson(P):
    a = math.sqrt(4 * P * r / (pi * Est))
    return cs * P * (2 * math.log(4 * r / a) - 1) + cp * P * (2 * math.log(2 * d / a) - nu / (1 - nu))


out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "alpha-steel.csv")
with open(out, "w") as f:
    f.write("P_N_per_m,alpha_paper_l1m_m,alpha_paper_l1mm_m,alpha_johnson_d10mm_m,ratio_l1m_over_l1mm\n")
    for label, P in (("1e5", 1e5), ("1e6", 1e6), ("1e7", 1e7)):
        a1, a2, aj = paper(P, 1.0), paper(P, 1e-3), johnson(P)
        f.write(f"{label},{a1:.17g},{a2:.17g},{aj:.17g},{a1 / a2:.17g}\n")
