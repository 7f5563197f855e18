#!/usr/bin/env python3
"""Wall time of a 1024-sample uncertainty propagation of the Table 1 elasto-plastic case
(issue 27, section 4): the inputs of verification/uq/paper-plastic.yaml at 1024 scrambled
Sobol' points (seed 27), run through ``impact.sweep`` with 2 local workers and on a Dask
``LocalCluster`` of 2 single-threaded worker processes; the two frames must be bit-identical
(wall-clock keys aside). The per-sample overhead is the sweep's wall time per sample and
worker less the solver's own time per run (``wall_time_s`` of the summaries), and against a
plain ``impact simulate`` of the nominal scene (the CLI, process start and files included).

    .venv/bin/python scripts/uq-timing.py [--n 1024] [--out out/uq-timing.json]
"""
from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
STUDY = ROOT / "verification/uq/paper-plastic.yaml"


def overrides(n: int) -> list[dict]:
    from impact import _impact
    from impact._distributions import ppf
    from impact._uq_design import base_points

    decl = json.loads(_impact.read_study(str(STUDY)))
    u = base_points("sobol", len(decl["inputs"]), n, decl["sampling"]["seed"])
    cols = [ppf(i["kind"], i["distribution"])(u[:, j]) for j, i in enumerate(decl["inputs"])]
    return [{i["key"]: float(c[k]) for i, c in zip(decl["inputs"], cols)} for k in range(n)]


def cli_time(repeats: int = 3) -> float:
    best = float("inf")
    for _ in range(repeats):
        with tempfile.TemporaryDirectory() as d:
            t0 = time.perf_counter()
            subprocess.run([str(ROOT / "target/release/impact"), "simulate",
                            str(ROOT / "verification/scenes/paper-plastic.yaml"), "--out", d,
                            "--force", "--quiet", "--threads", "1"], check=True)
            best = min(best, time.perf_counter() - t0)
    return best


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=1024)
    ap.add_argument("--out", default="out/uq-timing.json")
    args = ap.parse_args()
    import impact
    from dask.distributed import Client, LocalCluster

    scene = ROOT / "verification/scenes/paper-plastic.yaml"
    over = overrides(args.n)
    t0 = time.perf_counter()
    local = impact.sweep(scene, over, jobs=2)
    t_local = time.perf_counter() - t0
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True) as cluster, \
            Client(cluster) as client:
        t0 = time.perf_counter()
        dask = impact.sweep(scene, over, client=client)
        t_dask = time.perf_counter() - t0
    keep = [c for c in local.columns if c not in impact.TIMING_KEYS]
    same = local[keep].astype(str).equals(dask[keep].astype(str))
    solver = float(np.mean(local["wall_time_s"]))
    cli = cli_time()
    res = {"n": args.n, "local_2_workers_s": t_local, "dask_localcluster_2_workers_s": t_dask,
           "identical_rows": bool(same), "failed_runs": int(local["error"].notna().sum()),
           "solver_time_per_run_s": solver, "cli_simulate_s": cli,
           "local_per_sample_overhead_s": 2 * t_local / args.n - solver,
           "dask_per_sample_overhead_s": 2 * t_dask / args.n - solver}
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text(json.dumps(res, indent=1) + "\n")
    print(json.dumps(res, indent=1))
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
