#!/usr/bin/env python3
"""Consistency checks of the transcribed Dokko & Kim (2004) Tables 1 and 2.

Plain python3, standard library only. Run from anywhere:

    python3 reference-data/paper/check_tables.py

Every number is read as the printed string and handled with exact decimal
arithmetic. A printed value with k digits after the decimal point is taken to
stand for an interval of +- half a unit in its last digit (0.5 * 10**-k); an
integer such as "2394" or "2260" is taken to be exact to its units digit
(half-unit 0.5), which for "2260" is the stricter of the two possible readings.

Checks (exit status 1 if any fails):
  Table 2  initial momentum = 10 kg * initial velocity (both are the prescribed
           inputs, so they are taken as exact);
           impulse = initial momentum - final momentum, per row and per case,
           within the rounding of the printed final momentum and impulse.
  Table 1  ratio (EP/E) = elasto_plastic / elastic: the interval of quotients
           allowed by the rounding of the two operands must overlap the
           printed ratio +- its own half-unit.
  Impactor m = (I_E - I_EP) / (v_EP - v_E) and v0 = I / m + v_final, solved
           from the two Table 1 rows, and the round hypothesis m = 18.0 kg,
           v0 = 10.0 m/s checked against both rows within the rounding of the
           printed impulses and final velocities.
"""
import csv
import os
import sys
from decimal import Decimal, ROUND_HALF_EVEN, ROUND_HALF_UP, getcontext

getcontext().prec = 40
HERE = os.path.dirname(os.path.abspath(__file__))
MASS_TABLE2 = Decimal("10")          # kg, printed in the caption of Table 2
M_HYP, V0_HYP = Decimal("18.0"), Decimal("10.0")   # derived round impactor of Table 1

failures = []


def half_unit(s):
    """Half a unit in the last printed digit of the string s."""
    s = s.strip().lstrip("+-")
    decimals = len(s.split(".")[1]) if "." in s else 0
    return Decimal("0.5") * Decimal(10) ** (-decimals)


def decimals_of(s):
    s = s.strip()
    return len(s.split(".")[1]) if "." in s else 0


def read(name):
    with open(os.path.join(HERE, name), newline="") as f:
        return list(csv.DictReader(f))


def fmt(x, nd=4):
    return f"{float(x):+.{nd}f}"


# ---------------------------------------------------------------- Table 2
t2 = read("table2.csv")
print("Table 2: impulse = initial momentum - final momentum (m = 10 kg)")
print("  tolerance = half-unit(final momentum) + half-unit(impulse); "
      "'strict' = printed impulse equals p0 - p_f rounded to its digits")
hdr = f"  {'v0':>5} {'case':<3} {'p0':>6} {'p_f':>8} {'I':>7} {'p0-p_f':>8} {'resid':>8} {'tol':>6} {'within':>6} {'strict':>12}"
print(hdr)
for row in t2:
    v0 = Decimal(row["initial_velocity_mps"])
    p0 = Decimal(row["initial_momentum_kgmps"])
    if MASS_TABLE2 * v0 != p0:
        failures.append(f"Table 2 v0={v0}: 10*v0={MASS_TABLE2 * v0} != printed p0 {p0}")
    for case, fk, ik in (("E", "elastic_final_momentum_kgmps", "elastic_impulse_Ns"),
                         ("EP", "ep_final_momentum_kgmps", "ep_impulse_Ns")):
        pf_s, i_s = row[fk], row[ik]
        pf, imp = Decimal(pf_s), Decimal(i_s)
        diff = p0 - pf
        resid = diff - imp
        tol = half_unit(pf_s) + half_unit(i_s)
        ok = abs(resid) <= tol
        q = Decimal(1).scaleb(-decimals_of(i_s))
        up = diff.quantize(q, rounding=ROUND_HALF_UP) == imp
        even = diff.quantize(q, rounding=ROUND_HALF_EVEN) == imp
        strict = "yes" if (up and even) else ("half-up only" if up else ("half-even only" if even else "NO"))
        print(f"  {row['initial_velocity_mps']:>5} {case:<3} {row['initial_momentum_kgmps']:>6} {pf_s:>8} {i_s:>7} "
              f"{str(diff):>8} {str(resid):>8} {str(tol):>6} {'ok' if ok else 'FAIL':>6} {strict:>12}")
        if not ok:
            failures.append(f"Table 2 v0={v0} {case}: residual {resid} beyond tolerance {tol}")

# ---------------------------------------------------------------- Table 1
t1 = read("table1.csv")
print()
print("Table 1: ratio (EP/E) = elasto_plastic / elastic, interval arithmetic on the printed digits")
print("  'strict' = printed ratio equals EP/E of the printed operands rounded to its digits")
print(f"  {'quantity':<30} {'E':>7} {'EP':>7} {'printed':>8} {'EP/E':>9} {'min':>9} {'max':>9} {'check':>6} {'strict':>6}")
for row in t1:
    e_s, p_s, r_s = row["elastic"], row["elasto_plastic"], row["ratio_ep_e"]
    e, p, r = Decimal(e_s), Decimal(p_s), Decimal(r_s)
    he, hp, hr = half_unit(e_s), half_unit(p_s), half_unit(r_s)
    corners = [(p + sp * hp) / (e + se * he) for sp in (-1, 1) for se in (-1, 1)]
    lo, hi = min(corners), max(corners)
    ok = hi >= r - hr and lo <= r + hr
    strict = (p / e).quantize(Decimal(1).scaleb(-decimals_of(r_s)), rounding=ROUND_HALF_UP) == r
    print(f"  {row['quantity']:<30} {e_s:>7} {p_s:>7} {r_s:>8} {float(p / e):>9.5f} "
          f"{float(lo):>9.5f} {float(hi):>9.5f} {'ok' if ok else 'FAIL':>6} {'yes' if strict else 'no':>6}")
    if not ok:
        failures.append(f"Table 1 {row['quantity']}: printed ratio {r} outside [{float(lo):.5f}, {float(hi):.5f}] +- {hr}")

# ---------------------------------------------------------------- impactor of Table 1
by_q = {row["quantity"]: row for row in t1}
i_e_s, i_p_s = by_q["impulse"]["elastic"], by_q["impulse"]["elasto_plastic"]
v_e_s, v_p_s = by_q["impactor_final_velocity"]["elastic"], by_q["impactor_final_velocity"]["elasto_plastic"]
i_e, i_p, v_e, v_p = map(Decimal, (i_e_s, i_p_s, v_e_s, v_p_s))
hi_e, hi_p, hv_e, hv_p = map(half_unit, (i_e_s, i_p_s, v_e_s, v_p_s))
m = (i_e - i_p) / (v_p - v_e)
m_lo = (i_e - i_p - hi_e - hi_p) / (v_p - v_e + hv_e + hv_p)
m_hi = (i_e - i_p + hi_e + hi_p) / (v_p - v_e - hv_e - hv_p)
v0_e, v0_p = i_e / m + v_e, i_p / m + v_p
print()
print("Impactor of Table 1 (impulse = m (v0 - v_final), v_final < 0 = rebound)")
print(f"  m  = ({i_e_s} - {i_p_s}) / ({v_p_s} - ({v_e_s})) = {float(m):.4f} kg   "
      f"(range from the printed digits {float(m_lo):.3f} .. {float(m_hi):.3f} kg)")
print(f"  v0 = I/m + v_final = {float(v0_e):.4f} m/s (elastic row), {float(v0_p):.4f} m/s (EP row)")
print(f"  hypothesis m = {M_HYP} kg, v0 = {V0_HYP} m/s "
      f"(kinetic energy {float(M_HYP * V0_HYP ** 2 / 2):.0f} J):")
print(f"  {'row':<4} {'I printed':>9} {'m(v0-vf)':>9} {'resid I':>8} {'tol I':>6} "
      f"{'v0 = I/m+vf':>12} {'resid v0':>9} {'check':>6}")
if not (m_lo <= M_HYP <= m_hi):
    failures.append(f"impactor: m = {M_HYP} outside the printed-digit range [{m_lo}, {m_hi}]")
for name, i_s, v_s, hi_, hv_ in (("E", i_e_s, v_e_s, hi_e, hv_e), ("EP", i_p_s, v_p_s, hi_p, hv_p)):
    imp, vf = Decimal(i_s), Decimal(v_s)
    pred = M_HYP * (V0_HYP - vf)
    resid = imp - pred
    tol = hi_ + M_HYP * hv_        # rounding of the printed impulse and final velocity
    v0_row = imp / M_HYP + vf
    ok = abs(resid) <= tol
    print(f"  {name:<4} {i_s:>9} {str(pred):>9} {str(resid):>8} {float(tol):>6.3f} "
          f"{float(v0_row):>12.5f} {float(v0_row - V0_HYP):>+9.5f} {'ok' if ok else 'FAIL':>6}")
    if not ok:
        failures.append(f"impactor row {name}: impulse residual {resid} beyond {tol}")

print()
if failures:
    print("FAILED:")
    for f in failures:
        print("  " + f)
    sys.exit(1)
print("All checks passed (within the rounding of the printed digits).")
