#!/usr/bin/env python3
"""CalculiX (ccx 2.20) adapter of the verification matrix (adapters/README.md).

Usage: python3 run.py OUT_DIR/scene.yaml OUT_DIR
       python3 run.py OUT_DIR/problem.json OUT_DIR
Reads OUT_DIR/scene.json, writes OUT_DIR/job.inp, runs `ccx -i job` there, and writes
history.csv, summary.json and adapter.json; for a builtin's problem (problem.py), fields.json
and adapter.json. Exit 0 done, 3 not expressible, 1 failed (one line on stderr naming the
scene and ccx's last lines).
"""

import math
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import contract  # noqa: E402
import deck  # noqa: E402
import history  # noqa: E402
import nose as nose_mod  # noqa: E402
import probes as probe_lookup  # noqa: E402
import problem as problem_mod  # noqa: E402
import results  # noqa: E402
import runner  # noqa: E402
import scene as scene_io  # noqa: E402
from mesh import PlateMesh  # noqa: E402
from wedge import ring_factor as wedge_ring_factor  # noqa: E402

EXIT_FAILED, EXIT_NOT_EXPRESSIBLE = 1, 3


def ccx_version():
    """'2.20' from `ccx -v`, or 'unknown'."""
    try:
        out = subprocess.run(["ccx", "-v"], capture_output=True, text=True, timeout=30).stdout
    except (OSError, subprocess.SubprocessError):
        return "unknown"
    m = re.search(r"Version\s+(\S+)", out)
    return m.group(1) if m else "unknown"


def courant_step(log_path):
    """ccx's own stable step ('initial stable time increment' in its log), s, or None."""
    with open(log_path, encoding="utf-8", errors="replace") as f:
        found = re.findall(r"initial stable time increment:\s*(\S+)", f.read())
    return float(found[-1]) if found else None


def simulate(scene_yaml, out_dir):
    """Translate, run and read back one scene; raises NotExpressible, CcxFailed, DatError."""
    s = scene_io.settings(scene_io.load(scene_yaml))
    scene_io.check_expressible(s)
    mesh = PlateMesh(s)
    reduced = s["mesh"]["element"] == "q4-1pt"
    located = probe_lookup.locate(mesh, s["output"]["probes"], reduced)
    if s["load"][0] == "impactor":
        return simulate_contact(s, mesh, located, out_dir)
    dt_scene = deck.time_step(s, mesh)
    wedge = s["geometry"] == "axisymmetric" and s["load"][0] == "wall"
    if wedge:
        located = {}  # (no probe stresses on the wedge)
        write = lambda path, dt, every, end=None: deck.write_wedge(s, mesh, path, dt, every, end)
    else:
        write = lambda path, dt, every, end=None: deck.write(s, mesh, located, path, dt, every, end)
    write(os.path.join(out_dir, "probe.inp"), dt_scene, 0, 3 * dt_scene)
    probe_wall, probe_cpu, probe_log = runner.run(out_dir, "probe")
    dt_ccx = courant_step(probe_log) or dt_scene
    dt, every = deck.output_step(s, min(dt_scene, dt_ccx))
    info = write(os.path.join(out_dir, "job.inp"), dt, every)
    wall, cpu, log_path = runner.run(out_dir)
    wall, cpu = wall + probe_wall, cpu + probe_cpu
    if dt_ccx < dt_scene:
        info["substitutions"].append(
            f"time step {dt:.6g} s: ccx's own stable estimate {dt_ccx:.6g} s is below the "
            f"scene's {dt_scene:.6g} s (time.dt.fixed, or cfl times the adapter's bound)")
    blocks = results.parse(os.path.join(out_dir, "job.dat"))
    factor = deck.report_factor(s)
    if wedge:
        s["wedge"], factor = info["wedge"], wedge_ring_factor()
    rows = history.build(s, mesh, located, blocks, factor, scene_io.end_time(s),
                         (info["time_offset_s"], info["lift_m"]))
    cols = history.columns(s, located)
    n_elements = mesh.nx * mesh.ny
    summary = contract.summary(s, cols, rows, n_elements, dt)
    if s["kinematics"] == "small":  # ccx keeps the step it selected (= dt) without NLGEOM
        summary["n_steps"] = math.ceil(scene_io.end_time(s) / dt - 1e-9)
    adapter = {"code": "calculix", "version": ccx_version(), "input": ["probe.inp", "job.inp"],
               "wall_time_s": wall, "cpu_time_s": cpu,
               "substitutions": info["substitutions"], "n_elements": n_elements,
               "ccx_element": info["ccx_type"], "dt_scene_s": dt_scene,
               "dt_ccx_estimate_s": dt_ccx, "dt_s": dt}
    contract.write(out_dir, cols, rows, summary, adapter)


def simulate_contact(s, mesh, located, out_dir):
    """The rigid nose in surface contact (nose.py): one implicit run, no probe run (ccx's
    explicit stable step does not bound an implicit step)."""
    info = nose_mod.write_contact(s, mesh, located, os.path.join(out_dir, "job.inp"))
    wall, cpu, _ = runner.run(out_dir)
    blocks = results.parse(os.path.join(out_dir, "job.dat"))
    rows = history.build(s, mesh, located, blocks, deck.report_factor(s), scene_io.end_time(s))
    cols = history.columns(s, located)
    n_elements = mesh.nx * mesh.ny
    summary = contract.summary(s, cols, rows, n_elements, info["dt"])
    adapter = {"code": "calculix", "version": ccx_version(), "input": ["job.inp"],
               "wall_time_s": wall, "cpu_time_s": cpu,
               "substitutions": info["substitutions"], "n_elements": n_elements,
               "n_steps": len(rows) - 1, "ccx_element": info["ccx_type"],
               "dt_s": info["dt"]}
    contract.write(out_dir, cols, rows, summary, adapter)


def main(argv):
    """Entry point: returns the exit status."""
    if len(argv) != 3:
        print("usage: run.py SCENE_YAML|PROBLEM_JSON OUT_DIR", file=sys.stderr)
        return 2
    scene_yaml, out_dir = argv[1], argv[2]
    try:
        if os.path.basename(scene_yaml) == "problem.json":
            problem_mod.solve(scene_yaml, out_dir, ccx_version())
        else:
            simulate(scene_yaml, out_dir)
    except scene_io.NotExpressible as e:
        print(f"not expressible: {e.feature}: {e.reason}", file=sys.stderr)
        return EXIT_NOT_EXPRESSIBLE
    except (runner.CcxFailed, results.DatError, OSError, ValueError, KeyError) as e:
        contract.remove(out_dir)
        message = str(e) if not isinstance(e, KeyError) else f"missing key {e}"
        print(f"calculix: {scene_yaml}: {message}", file=sys.stderr)
        return EXIT_FAILED
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
