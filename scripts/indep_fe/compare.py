"""Code-to-code comparison of two runs (`impact simulate` and `indep_fe`, or any two outputs
with the history.csv / summary.json layout of ALGORITHM.md section 8).

History: rows are matched by position and their `time_s` must agree. For every column in
both files, with a = first run (RUST_OUT), b = second run (PY_OUT) and
peak = max(max|a|, max|b|):

    L-inf/peak = max|a - b| / peak,     L2/peak = sqrt(mean((a - b)^2)) / peak

(0 when both are identically 0). `energy_balance_error` is already a ratio to the run's energy
scale, so its differences are reported as they are (peak := 1).

Summary: relative differences |a - b| / max(|a|, |b|) of the scalar metrics, the probes'
max von Mises stress (and, with a rate law, max plastic strain rate; with `thermal` the max
temperature and the heat), the contact intervals (difference in steps), and the wall time of
each side with the ratio b / a.

Exit status of `main`: 0 when every gated difference is within its tolerance, 1 when one is
not (or the two runs are not comparable: different columns, times or step counts), 2 on
unreadable inputs.
"""
from __future__ import annotations

import argparse
import csv
import json
import math
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

# scalar summary metrics compared relatively, and those compared exactly
# (contact_step_factor .. max_nodes_in_contact: surface-coupling scenes only; max_temperature_K,
# heat_J: rate laws with thermal only (ALGORITHM.md 3b); dt_min_s, dt_max_s: a step re-estimated
# at every step only (6b); each compared when either run has it)
SUMMARY_METRICS = ["impulse_Ns", "peak_contact_force_N", "max_plate_displacement_m",
                   "final_impactor_velocity_mps", "contact_duration_s", "contact_step_factor",
                   "max_contact_half_width_m", "max_nodes_in_contact", "max_temperature_K",
                   "heat_J", "dt_min_s", "dt_max_s"]
# summary objects compared key by key: per probe (max_plastic_strain_rate_1_s: with a rate law
# only) and the rigid wall's (section 5c: wall scenes only)
SUMMARY_PER_PROBE = ["max_von_mises_Pa", "max_plastic_strain_rate_1_s", "wall"]
SUMMARY_EXACT = ["dt_s", "n_steps", "n_elements"]
# columns drawn by --plots (those present), each in its own panel with the difference below
PLOT_COLUMNS = ["contact_force_N", "indentation_m", "impactor_velocity_mps",
                "contact_half_width_m", "nodes_in_contact", "mid_uy_m",
                "top_uy_m", "bottom_uy_m", "plate_kinetic_J", "impactor_kinetic_J",
                "strain_energy_J", "plastic_work_J", "contact_energy_J", "external_work_J",
                "energy_balance_error"]
SELF_NORMALISED = {"energy_balance_error"}


def read_history(path: str | Path) -> dict[str, np.ndarray]:
    p = Path(path)
    if p.is_dir():
        p = p / "history.csv"
    with open(p, newline="") as fh:
        rows = list(csv.reader(fh))
    cols = rows[0]
    data = np.array([[float(x) if x.strip() != "" else np.nan for x in r] for r in rows[1:]],
                    dtype=float).reshape(len(rows) - 1, len(cols))
    return {c: data[:, j] for j, c in enumerate(cols)}


def read_summary(path: str | Path) -> dict:
    p = Path(path)
    if p.is_dir():
        p = p / "summary.json"
    return json.loads(p.read_text()) if p.exists() else {}


@dataclass
class ColumnDiff:
    name: str
    peak: float
    linf: float          # max |a - b| / peak
    l2: float            # rms(a - b) / peak
    t_at_max: float      # time of the largest difference
    a_at_max: float
    b_at_max: float


def column_diffs(a: dict, b: dict) -> tuple[list[ColumnDiff], list[str]]:
    """Differences of the common columns, and problems that make the runs incomparable."""
    problems = []
    only_a = [c for c in a if c not in b]
    only_b = [c for c in b if c not in a]
    if only_a or only_b:
        problems.append(f"columns differ: only in first {only_a}, only in second {only_b}")
    na, nb = len(a["time_s"]), len(b["time_s"])
    n = min(na, nb)
    if na != nb:
        problems.append(f"row counts differ ({na} vs {nb}); compared the first {n}")
    ta, tb = a["time_s"][:n], b["time_s"][:n]
    if n and np.max(np.abs(ta - tb)) > 1e-12 * max(np.max(np.abs(ta)), 1e-300):
        problems.append(f"time_s differ (max {np.max(np.abs(ta - tb)):.3e} s)")
    out = []
    for c in a:
        if c not in b or c == "time_s":
            continue
        x, y = a[c][:n], b[c][:n]
        if np.isnan(x).any() or np.isnan(y).any():
            problems.append(f"{c}: empty cells")
            x, y = np.nan_to_num(x), np.nan_to_num(y)
        d = np.abs(x - y)
        peak = 1.0 if c in SELF_NORMALISED else float(max(np.abs(x).max(initial=0),
                                                              np.abs(y).max(initial=0)))
        i = int(np.argmax(d)) if n else 0
        if peak > 0:
            linf, l2 = float(d.max(initial=0)) / peak, float(np.sqrt(np.mean(d * d))) / peak
        else:
            linf = l2 = 0.0
        out.append(ColumnDiff(c, peak, linf, l2, float(ta[i]) if n else math.nan,
                              float(x[i]) if n else math.nan, float(y[i]) if n else math.nan))
    return out, problems


def rel(a, b) -> float:
    if a is None or b is None:
        return 0.0 if a is None and b is None else math.inf
    s = max(abs(a), abs(b))
    return abs(a - b) / s if s > 0 else 0.0


def curve_rows(name: str, a: dict, b: dict) -> list[tuple[str, object, object, float]]:
    """A summary object of lists (wall.final_outline: height_m, radius_m), a row per list: the
    pair of values that differ most, and that difference over the list's largest size (as the
    history's Linf/peak: a height of 1e-20 m against 3e-20 m is not a difference of 67 %), inf
    when the lengths differ or a side lacks the list."""
    rows = []
    for q in sorted(set(a) | set(b)):
        la, lb = a.get(q), b.get(q)
        if la is None or lb is None or len(la) != len(lb) or not la:
            rows.append((f"{name}.{q}", None if la is None else len(la),
                         None if lb is None else len(lb), math.inf))
            continue
        k = max(range(len(la)), key=lambda i: abs(la[i] - lb[i]))
        peak = max(max(abs(x) for x in la), max(abs(x) for x in lb))
        rows.append((f"{name}.{q}", la[k], lb[k], abs(la[k] - lb[k]) / peak if peak > 0 else 0.0))
    return rows


def summary_diffs(sa: dict, sb: dict) -> tuple[list[tuple[str, object, object, float]], list[str]]:
    """(metric, a, b, relative difference) rows; problems (exact keys that differ)."""
    rows, problems = [], []
    for k in SUMMARY_METRICS:
        if k in sa or k in sb:
            rows.append((k, sa.get(k), sb.get(k), rel(sa.get(k), sb.get(k))))
    for key in SUMMARY_PER_PROBE:
        if key not in sa and key not in sb:
            continue
        oa, ob = sa.get(key) or {}, sb.get(key) or {}
        for p in sorted(set(oa) | set(ob)):
            if isinstance(oa.get(p), dict) or isinstance(ob.get(p), dict):
                rows += curve_rows(f"{key}.{p}", oa.get(p) or {}, ob.get(p) or {})
                continue
            rows.append((f"{key}.{p}", oa.get(p), ob.get(p), rel(oa.get(p), ob.get(p))))
    if "max_energy_balance_error" in sa and "max_energy_balance_error" in sb:
        ea, eb = sa["max_energy_balance_error"], sb["max_energy_balance_error"]
        rows.append(("max_energy_balance_error", ea, eb, abs(ea - eb)))   # already a ratio
    # section 3c: summary.json names the kinematics of finite runs only (absent: small)
    ka, kb = sa.get("kinematics", "small"), sb.get("kinematics", "small")
    if ka != kb:
        problems.append(f"kinematics differs: {ka} vs {kb}")
    # section 3d: and the geometry of axisymmetric runs only (absent: plane-strain)
    ga, gb = sa.get("geometry", "plane-strain"), sb.get("geometry", "plane-strain")
    if ga != gb:
        problems.append(f"geometry differs: {ga} vs {gb}")
    # section 6b: and the step's update of every-step runs only (absent: once)
    ua, ub = sa.get("dt_update", "once"), sb.get("dt_update", "once")
    if ua != ub:
        problems.append(f"dt_update differs: {ua} vs {ub}")
    for k in SUMMARY_EXACT:
        if k in sa and k in sb:
            r = rel(sa[k], sb[k])
            rows.append((k, sa[k], sb[k], r))
            if k != "dt_s" and r != 0:
                problems.append(f"{k} differs: {sa[k]} vs {sb[k]}")
            if k == "dt_s" and r > 1e-12:
                problems.append(f"dt_s differs: {sa[k]} vs {sb[k]} (not the same time step)")
    return rows, problems


def interval_steps(sa: dict, sb: dict) -> tuple[int, int, int | None]:
    """(count a, count b, largest endpoint difference in steps, None if counts differ)."""
    ia, ib = sa.get("contact_intervals_s") or [], sb.get("contact_intervals_s") or []
    dt = sa.get("dt_s") or sb.get("dt_s")
    if len(ia) != len(ib) or not dt:
        return len(ia), len(ib), None
    worst = 0
    for (a0, a1), (b0, b1) in zip(ia, ib):
        worst = max(worst, round(abs(a0 - b0) / dt), round(abs(a1 - b1) / dt))
    return len(ia), len(ib), worst


def plot(a: dict, b: dict, out_dir: Path, labels: tuple[str, str], fmt: str, title: str) -> list[Path]:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out_dir.mkdir(parents=True, exist_ok=True)
    n = min(len(a["time_s"]), len(b["time_s"]))
    t = a["time_s"][:n] * 1e3
    cols = [c for c in PLOT_COLUMNS if c in a and c in b]
    cols += [c for c in a if c.endswith(("_von_mises_Pa", "_plastic_strain_rate_1_s",
                                          "_temperature_K")) and c in b]
    files = []
    for c in cols:
        x, y = a[c][:n], b[c][:n]
        fig, (ax, axd) = plt.subplots(2, 1, figsize=(7, 5), sharex=True,
                                      gridspec_kw={"height_ratios": [3, 1.3]})
        ax.plot(t, x, "-", lw=1.8, label=labels[0])
        ax.plot(t, y, "--", lw=1.2, label=labels[1])
        ax.set_ylabel(c)
        ax.set_title(f"{title}: {c}", fontsize=10)
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
        axd.plot(t, y - x, "-", lw=1.0, color="tab:red")
        axd.set_ylabel(f"{labels[1]} - {labels[0]}", fontsize=8)
        axd.set_xlabel("time (ms)")
        axd.grid(alpha=0.3)
        fig.tight_layout()
        f = out_dir / f"{c}.{fmt}"
        fig.savefig(f)
        plt.close(fig)
        files.append(f)
    return files


def parse_col_tols(items: list[str]) -> dict[str, float]:
    out = {}
    for it in items or []:
        name, _, val = it.partition("=")
        if not _:
            raise ValueError(f"--tol-column wants NAME=VALUE, got {it!r}")
        out[name] = float(val)
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(
        prog="compare.py",
        description="Compare two runs (history.csv + summary.json): history L2 and L-inf "
                    "differences relative to each column's peak, summary metrics, wall times. "
                    "Exit status 1 when a tolerance is exceeded.",
        formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    ap.add_argument("a", metavar="RUST_OUT", help="first output directory (the Rust run)")
    ap.add_argument("b", metavar="PY_OUT", help="second output directory (the Python run)")
    ap.add_argument("--tol", type=float, default=None,
                    help="gate: largest allowed L-inf/peak of every history column and "
                         "relative difference of every summary metric (default: report only)")
    ap.add_argument("--tol-column", action="append", metavar="NAME=VALUE",
                    help="per-column (or summary metric) tolerance overriding --tol; repeatable")
    ap.add_argument("--interval-steps", type=int, default=0,
                    help="gate: contact interval endpoints may differ by this many steps "
                         "(default 0; only with --tol)")
    ap.add_argument("--labels", default="rust,python", help="names of the two runs (a,b)")
    ap.add_argument("--plots", metavar="DIR", help="write overlay plots into DIR")
    ap.add_argument("--format", default="svg", choices=["svg", "png"], help="plot format")
    ap.add_argument("--title", default=None, help="plot title (default: PY_OUT's name)")
    ap.add_argument("--json", metavar="FILE", help="also write the numbers as JSON")
    args = ap.parse_args(argv)

    try:
        ha, hb = read_history(args.a), read_history(args.b)
        sa, sb = read_summary(args.a), read_summary(args.b)
        col_tol = parse_col_tols(args.tol_column)
    except (OSError, ValueError, IndexError) as exc:
        print(f"compare.py: error: {exc}", file=sys.stderr)
        return 2
    la, lb = (args.labels.split(",") + ["b"])[:2]

    cdiffs, problems = column_diffs(ha, hb)
    sdiffs, sproblems = summary_diffs(sa, sb)
    problems += sproblems
    failures = []

    def tol_for(name):
        return col_tol.get(name, args.tol)

    print(f"== history: {args.a} ({la}) vs {args.b} ({lb}), {min(len(ha['time_s']), len(hb['time_s']))} rows")
    w = max([len(c.name) for c in cdiffs] + [6])
    print(f"{'column':<{w}}  {'peak':>11}  {'Linf/peak':>10}  {'L2/peak':>10}  {'t at max (s)':>12}  {la + ' there':>13}  {lb + ' there':>13}")
    for c in cdiffs:
        tol = tol_for(c.name)
        flag = ""
        if tol is not None and not c.linf <= tol:
            flag = "  FAIL"
            failures.append(f"history {c.name}: Linf/peak {c.linf:.3e} > {tol:.1e}")
        print(f"{c.name:<{w}}  {c.peak:11.4e}  {c.linf:10.3e}  {c.l2:10.3e}  {c.t_at_max:12.6e}  "
              f"{c.a_at_max:13.6e}  {c.b_at_max:13.6e}{flag}")

    print("== summary")
    print(f"{'metric':<28}  {la:>22}  {lb:>22}  {'rel. diff':>10}")
    for k, va, vb, r in sdiffs:
        tol = tol_for(k)
        flag = ""
        if tol is not None and k not in SUMMARY_EXACT and not r <= tol:
            flag = "  FAIL"
            failures.append(f"summary {k}: {r:.3e} > {tol:.1e}")
        fa = "null" if va is None else f"{va:.15g}"
        fb = "null" if vb is None else f"{vb:.15g}"
        print(f"{k:<28}  {fa:>22}  {fb:>22}  {r:10.3e}{flag}")
    na, nb, worst = interval_steps(sa, sb)
    if worst is None:
        print(f"contact intervals: {na} vs {nb}  (counts differ)")
        if args.tol is not None:
            failures.append(f"contact intervals: {na} vs {nb}")
    else:
        print(f"contact intervals: {na} vs {nb}, endpoints differ by at most {worst} step(s)")
        if args.tol is not None and worst > args.interval_steps:
            failures.append(f"contact interval endpoints differ by {worst} steps > {args.interval_steps}")

    wa, wb = sa.get("wall_time_s"), sb.get("wall_time_s")
    ratio = wb / wa if wa and wb else None
    if wa is not None and wb is not None:
        print(f"== wall time: {la} {wa:.4g} s, {lb} {wb:.4g} s, {lb}/{la} = "
              + (f"{ratio:.1f}" if ratio else "n/a"))

    for p in problems:
        print(f"problem: {p}")
    failures += problems

    if args.plots:
        files = plot(ha, hb, Path(args.plots), (la, lb), args.format,
                     args.title or Path(args.b).resolve().name)
        print(f"== {len(files)} plots in {args.plots}")
    if args.json:
        Path(args.json).write_text(json.dumps({
            "a": str(args.a), "b": str(args.b),
            "history": {c.name: {"peak": c.peak, "linf_over_peak": c.linf, "l2_over_peak": c.l2,
                                 "t_at_max_s": c.t_at_max} for c in cdiffs},
            "summary": {k: {"a": va, "b": vb, "rel_diff": r} for k, va, vb, r in sdiffs},
            "contact_intervals": {"a": na, "b": nb, "max_endpoint_steps": worst},
            "wall_time_s": {"a": wa, "b": wb, "ratio_b_over_a": ratio},
            "problems": problems, "failures": failures}, indent=1) + "\n")

    if failures:
        print(f"FAIL ({len(failures)}): " + "; ".join(failures))
        return 1
    if args.tol is not None:
        print(f"OK: within tolerance {args.tol:g}" + (f" (overrides {col_tol})" if col_tol else ""))
    return 0
