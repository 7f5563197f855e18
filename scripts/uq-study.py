#!/usr/bin/env python3
"""Runs the declared uncertainty studies (issue 27) and writes the report's uncertainty page.

    .venv/bin/python scripts/uq-study.py --out out/verification/uq [--ci] [--jobs N]
        [--dask N] [STUDY.yaml ...]

Default studies (the main job): Table 1 under the point force (verification/uq/paper-plastic.yaml,
paper-elastic.yaml) and under surface contact (paper-plastic-surface.yaml,
paper-elastic-surface.yaml), and Table 2's impulses (table2-plastic.yaml, table2-elastic.yaml:
seven scenes each); ``--ci`` runs verification/uq/ci-coarse.yaml (a coarse mesh, a few tens of
runs). Writes
``uq.md`` (embedded by ``impact report`` as its uncertainty section), its SVG figures and
``uq.json`` (the budget rows and the converged statistics). ``--dask N`` runs the sweeps on a
Dask LocalCluster of N single-threaded workers instead of the local pool.

The files are written into ``.OUT.partial-PID`` beside ``--out`` and moved in at the end,
replacing the page, data and figures of an earlier run (``impact simulate`` stages its output
alike). Exit status: 0 written; 130 on Ctrl-C (within a second; one line; ``--out`` left as
it was); 2 when a declaration is refused (its message, ``file:line:col: ...``, before any
run); 1 when runs of a study failed (their rows and messages).
"""
from __future__ import annotations

import argparse
import contextlib
import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "scripts"))

MAIN = ["verification/uq/paper-plastic.yaml", "verification/uq/paper-elastic.yaml",
        "verification/uq/paper-plastic-surface.yaml", "verification/uq/paper-elastic-surface.yaml",
        "verification/uq/table2-plastic.yaml", "verification/uq/table2-elastic.yaml"]
# The Table 1 rows under both couplings, shown side by side: (point force, surface contact).
COUPLINGS = [("verification/uq/paper-plastic.yaml", "verification/uq/paper-plastic-surface.yaml"),
             ("verification/uq/paper-elastic.yaml", "verification/uq/paper-elastic-surface.yaml")]
CI = ["verification/uq/ci-coarse.yaml"]
RIGID_PLASTIC_SCENES = [("Table 1, 18 kg at 10 m/s", f"verification/scenes/paper-plastic{c}.yaml", c)
                        for c in ("", "-surface")] + [
    (f"Table 2, 10 kg at {v:g} m/s", f"verification/scenes/paper-table2/v{v:05.2f}-plastic.yaml", "")
    for v in (1.25, 2.5, 5.0, 7.5, 10.0, 12.5, 15.0)]


def rigid_plastic_section(jobs: int | None) -> str:
    """The energy ratio of every elasto-plastic impact and the plastic work no mechanism can
    take (issue 27, section 3), beside the coupling that produced it."""
    import impact
    from impact import _impact

    lines = ["## Rigid-plastic numbers of the elasto-plastic impacts\n",
             "Jones's rigid-plastic theory of a clamped beam struck by a mass (closed forms: "
             "`analytical/src/rigid_plastic.rs`): E_r = K / U_c, the striker's kinetic energy over "
             "the elastic energy the plate stores at the collapse load P_c = 8 M_p / L (with "
             "shear). Below E_r = 1 no mechanism forms: all plastic work is local (under the "
             "nose); above, the plastic work beyond K - U_c cannot come from the mechanism. The "
             "band's checks are the matrix case `rigid-plastic/paper-impacts` (E_r >= 10).\n",
             "| impact | coupling | K (J) | E_r (-) | band (mm) | max displacement (mm) | plastic work (J) | local, no mechanism (J) |",
             "|---|---|---|---|---|---|---|---|"]
    for title, path, coupling in RIGID_PLASTIC_SCENES:
        run = impact.simulate(ROOT / path, threads=1).summary
        text = _impact.read_scene(str(ROOT / path))
        wp = run["final_energy_J"]["plastic_work"]
        m = json.loads(_impact.rigid_plastic(text, path, wp))
        k = m["rigid_plastic_energy_ratio"] * m["rigid_plastic_elastic_energy_J"]
        lines.append(
            f"| {title} | {run['contact_law']} | {k:.1f} | {m['rigid_plastic_energy_ratio']:.2f} | "
            f"{1e3 * m['rigid_plastic_lower_m']:.2f} to {1e3 * m['rigid_plastic_upper_m']:.2f} | "
            f"{-1e3 * run['max_plate_displacement_m']:.3f} | {wp:.1f} | "
            f"{m['rigid_plastic_local_dissipation_J']:.1f} |")
    return "\n".join(lines) + "\n"


def couplings_section(summary: dict) -> str:
    """Table 1's V&V 20 rows under the point force and under surface contact side by side,
    from the studies' budgets (those that ran)."""
    pairs = [(a, b) for a, b in COUPLINGS if a in summary and b in summary]
    if not pairs:
        return ""
    g = lambda x: f"{x:.4g}"  # noqa: E731
    lines = ["## Table 1 under both couplings\n",
             "The same comparisons, inputs and sampling under the point force of eq. (4) and under "
             "the rigid nose in surface contact (its own mesh levels and GCI for u_num; no "
             "contact-law input). The plate was fitted under the point force, so the surface "
             "rows predict with the other coupling on that plate; D is the same calibration "
             "value. Full budgets in the studies' sections.\n",
             "| quantity | D | point: S | E | u_num | u_val | abs(E) <= 2 u_val | surface: S | E | "
             "u_num | u_val | abs(E) <= 2 u_val |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for point, surface in pairs:
        other = {b["key"]: b for b in summary[surface]["budget"]}
        for a in summary[point]["budget"]:
            b = other.get(a["key"])
            cells = [a["label"], g(a["D"])]
            for x in (a, b):
                cells += ([g(x["S"]), g(x["E"]), g(x["u_num"]), g(x["u_val"]),
                           "yes" if x["within"] else "**no**"] if x else ["-"] * 5)
            lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


# What this script writes into --out, and replaces there: the page, its data, its figures.
OWNED = ("uq.md", "uq.json", "study*-*.svg")
INTRO = ("# Uncertainty: V&V 20 budgets, Sobol' indices, rigid-plastic bounds\n\n"
         "Written by `scripts/uq-study.py` with `impact.uq`. The paper's numbers are "
         "computed results, not measurements: each row is a code-to-literature comparison. "
         "Every Table 1 number and all 14 Table 2 impulses entered the reconstruction's "
         "objective (reference-data/paper/reconstruction/report.md section 2): they are "
         "**calibration**, none is held out, so |E| <= 2 u_val there shows the fit is as good "
         "as the uncertainties, not validation (held-out residuals of other fits: the "
         "reconstruction's evidence page, section 1). The surface-contact rows use the plate "
         "fitted under the point force.\n")


def write_page(studies: list[str], folder: Path, client, args) -> None:
    """Runs the studies and writes uq.md, uq.json and the figures into ``folder``."""
    import impact
    from impact._uq_page import budget_rows, dominant_inputs, study_section

    page = [INTRO]
    summary = {}
    for i, path in enumerate(studies):
        rel = str(Path(path))
        print(f"uq: {rel}: running", flush=True)
        r = impact.uq(ROOT / path if not Path(path).is_absolute() else path,
                      client=client, jobs=None if client else args.jobs)
        page.append(study_section(r, rel, folder, f"study{i + 1}"))
        summary[rel] = {"converged_at": r.converged_at, "runs": r.final.runs,
                        "wall_time_s": r.wall_time_s, "budget": budget_rows(r, rel),
                        "dominant": dominant_inputs(r)}
        print(f"uq: {rel}: {r.final.runs} runs, converged at N = {r.converged_at}, "
              f"{r.wall_time_s:.0f} s", flush=True)
    if not args.ci:
        page.append(couplings_section(summary))
        page.append(rigid_plastic_section(args.jobs))
    (folder / "uq.md").write_text("\n".join(page))
    (folder / "uq.json").write_text(json.dumps(summary, indent=1, default=str) + "\n")


@contextlib.contextmanager
def dask_client(workers: int):
    """A client of a Dask LocalCluster of ``workers`` single-threaded processes (0: None, the
    local pool), both closed at the end, also on Ctrl-C. Ctrl-C is this process's to handle:
    the workers (in its process group, so a terminal's Ctrl-C reaches them too) ignore it,
    their runs under way stop with their cancelled tasks, and their warnings about those are
    not shown."""
    if not workers:
        yield None
        return
    import logging
    import signal

    from dask.distributed import Client, LocalCluster

    with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                      silence_logs=logging.ERROR) as cluster, Client(cluster) as client:
        client.run(lambda: signal.signal(signal.SIGINT, signal.SIG_IGN) and None)
        yield client


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("studies", nargs="*")
    ap.add_argument("--out", default="out/verification/uq")
    ap.add_argument("--ci", action="store_true", help="the small CI study")
    ap.add_argument("--jobs", type=int, default=None)
    ap.add_argument("--dask", type=int, default=0, help="run on a Dask LocalCluster of N workers")
    args = ap.parse_args()
    import impact
    from impact._staging import staged

    studies = args.studies or (CI if args.ci else MAIN)
    out = Path(args.out)
    try:
        with staged(out, OWNED) as folder, dask_client(args.dask) as client:
            write_page(studies, folder, client, args)
    except KeyboardInterrupt:
        print(f"uq: interrupted (Ctrl-C): nothing written, {out} is as it was", file=sys.stderr)
        return 130
    except impact.SceneError as e:
        print(f"uq: {e}", file=sys.stderr)
        return 2
    except impact.StudyRunError as e:
        print(f"uq: {e}", file=sys.stderr)
        return 1
    print(f"uq: wrote {out / 'uq.md'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
