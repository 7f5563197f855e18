#!/usr/bin/env python3
"""Analytical reference: d'Alembert's solution for the 1-D bar of the wave-speed suite.

A column of plane-strain elements with every u_x held (one element wide, roller ends and the
symmetry plane) is a bar in uniaxial strain with wave speed c = sqrt((lambda + 2 mu) / rho).
A step traction sigma on its top end (y = h), bottom end free: every wave that reaches a
point adds a displacement ramp v (t - t_arrival), v = sigma / (rho c), arriving at depth d at
(d + 2 k h) / c (down-going) and (2 h - d + 2 k h) / c (reflected at the free bottom), k >= 0.

Writes reference-data/analytical/dalembert-bar/history.csv (time_s, top_uy_m, mid_uy_m,
bottom_uy_m; m, negative = down) at t_n = n dt, dt = (h / ny) / c, n = 0..steps, for the scene
verification/cases/wave-speed/strip/bar.yaml. Standard library only.
"""
import math
import pathlib

E, NU, RHO = 207.0e9, 0.3, 7850.0
H, NY, SIGMA, STEPS = 0.02, 16, 1.0e6, 40

LAM = E * NU / ((1 + NU) * (1 - 2 * NU))
MU = E / (2 * (1 + NU))
C = math.sqrt((LAM + 2 * MU) / RHO)
DT = (H / NY) / C
V = SIGMA / (RHO * C)


def downward_displacement(depth: float, t: float) -> float:
    u, k = 0.0, 0
    while (depth + 2 * k * H) / C <= t:
        u += V * (t - (depth + 2 * k * H) / C)
        reflected = (2 * H - depth + 2 * k * H) / C
        if reflected <= t:
            u += V * (t - reflected)
        k += 1
    return u


def main() -> None:
    out = pathlib.Path(__file__).resolve().parent.parent / "reference-data/analytical/dalembert-bar/history.csv"
    lines = ["time_s,top_uy_m,mid_uy_m,bottom_uy_m"]
    for n in range(STEPS + 1):
        t = n * DT
        values = [-downward_displacement(d, t) for d in (0.0, H / 2, H)]
        lines.append(",".join(repr(x) for x in [t, *values]))
    out.write_text("\n".join(lines) + "\n")
    print(f"dt = {DT!r} s (scene time.dt.fixed), end = {STEPS * DT!r} s; wrote {out}")


if __name__ == "__main__":
    main()
