"""Compare two history.csv files column by column (code-to-code check).

For each column present in both, prints max |a - b| and that divided by max |b| (b is the
reference). Rows are matched by position; their time_s must agree.
"""
from __future__ import annotations

import csv
from pathlib import Path

import numpy as np


def read_history(path: str | Path) -> dict[str, np.ndarray]:
    p = Path(path)
    if p.is_dir():
        p = p / "history.csv"
    with open(p, newline="") as fh:
        rows = list(csv.reader(fh))
    cols = rows[0]
    data = np.array([[float(x) if x.strip() != "" else np.nan for x in r] for r in rows[1:]])
    return {c: data[:, j] for j, c in enumerate(cols)}


def compare(a_path, b_path) -> list[tuple[str, float, float]]:
    a, b = read_history(a_path), read_history(b_path)
    n = min(len(a["time_s"]), len(b["time_s"]))
    if len(a["time_s"]) != len(b["time_s"]):
        print(f"warning: row counts differ ({len(a['time_s'])} vs {len(b['time_s'])}); "
              f"comparing the first {n}")
    out = []
    for c in a:
        if c not in b:
            continue
        x, y = a[c][:n], b[c][:n]
        both = ~(np.isnan(x) & np.isnan(y))
        if not both.any():
            continue
        diff = float(np.nanmax(np.abs(x[both] - y[both])))
        scale = float(np.nanmax(np.abs(y[both])))
        out.append((c, diff, diff / scale if scale > 0 else (0.0 if diff == 0 else np.inf)))
    return out


def main(a_path, b_path) -> int:
    res = compare(a_path, b_path)
    width = max(len(c) for c, _, _ in res)
    print(f"{'column':<{width}}  {'max |a-b|':>12}  {'rel. to max|b|':>14}")
    for c, d, r in res:
        print(f"{c:<{width}}  {d:12.4e}  {r:14.4e}")
    return 0
