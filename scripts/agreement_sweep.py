#!/usr/bin/env python3
"""Run `impact simulate` and the independent Python solver on a matrix of identical scenes
(same element, mesh and fixed dt) and tabulate their agreement.

    .venv/bin/python scripts/agreement_sweep.py --out /tmp/sweep [--only SUBSTR] [--big]

Writes OUT/<case>/{scene.yaml, rust/, python/, compare.json} and prints a Markdown table:
per case the largest L-inf/peak over the key history columns (and which column), the
largest relative difference of the summary metrics, the contact interval count and the wall
time ratio Python / Rust. `--big` adds the 80 x 16 cases (minutes of Python time).
"""
from __future__ import annotations

import argparse
import copy
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import yaml

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE))
sys.path.insert(1, str(HERE / "tests"))
from indep_fe.scene import with_dotted  # noqa: E402
from helpers import BASE as TEST_SCENE, PLASTIC  # noqa: E402
from indep_fe.compare import column_diffs, interval_steps, read_history, read_summary, summary_diffs  # noqa: E402

RUST = Path(os.environ.get("IMPACT_BIN", ROOT / "target" / "release" / "impact"))
PY = [str(ROOT / ".venv" / "bin" / "python"), "-m", "indep_fe", "simulate"]

# The Python tests' small scene (scripts/tests/helpers.py: the README's example plate and
# impactor, elastic) on a 20 x 4 mesh with a fixed dt.
BASE = with_dotted(TEST_SCENE, {"mesh.nx": 20, "time.end": 1.0e-3, "time.dt": {"fixed": 5.0e-7}})
TABLE = {"yield_stress": 250.0e6, "hardening": {"table": [[0.0, 250.0e6], [0.002, 262.0e6],
                                                          [0.05, 320.0e6]]}}
LAWS = {"paper1m": {"paper": {"length_unit": 1.0}}, "papermm": {"paper": {"length_unit": 1.0e-3}},
        "johnson": {"johnson": {"datum_depth": 0.010}}}
KEY_COLUMNS = ["contact_force_N", "indentation_m", "impactor_velocity_mps",
               "contact_half_width_m", "nodes_in_contact", "mid_uy_m",
               "top_uy_m", "A_von_mises_Pa", "plate_kinetic_J", "strain_energy_J",
               "plastic_work_J", "external_work_J"]


def with_overrides(**over) -> dict:
    return with_dotted(BASE, over)


def surface(contact="surface", radius=0.5, **over) -> dict:
    """BASE with the surface coupling (ALGORITHM.md 5b): the nodal keys removed, a 0.5 m nose
    (5 to 7 nodes in contact on the 20 x 4 mesh)."""
    return with_overrides(**{"load.impactor.youngs_modulus": None,
                             "load.impactor.poisson_ratio": None,
                             "load.impactor.contact_law": None,
                             "load.impactor.indentation_datum": None,
                             "load.impactor.contact": contact,
                             "load.impactor.nose_radius": radius, **over})


def cases(big: bool) -> dict[str, dict]:
    out = {}
    # small impact matrix: element x law x model x material, 20 x 4 (half) / 40 x 4 (full)
    for el in ["q4-full", "q4-sri", "q4-1pt"]:
        for law in ["paper1m", "johnson"]:
            for model in ["half", "full"]:
                for mat in ["el", "pl"]:
                    out[f"s20x4-{el}-{law}-{model}-{mat}"] = with_overrides(**{
                        "mesh.element": el, "mesh.model": model,
                        "mesh.nx": 20 if model == "half" else 40,
                        "load.impactor.contact_law": LAWS[law],
                        "material.plasticity": PLASTIC if mat == "pl" else None})
    # variants: mm reading of eq. (4), top-surface datum, graded mesh, table hardening,
    # after_contact stop, Table 2 impactor
    out["s20x4-q4-sri-papermm-half-el"] = with_overrides(**{"load.impactor.contact_law": LAWS["papermm"]})
    out["s20x4-q4-sri-papermm-half-pl"] = with_overrides(**{"load.impactor.contact_law": LAWS["papermm"],
                                                           "material.plasticity": PLASTIC})
    out["s20x4-q4-sri-topdatum-half-pl"] = with_overrides(**{
        "load.impactor.indentation_datum": "top-surface", "material.plasticity": PLASTIC})
    out["s20x4-q4-sri-mixednodes-half-pl"] = with_overrides(**{
        "load.impactor.force_node": "top-surface", "material.plasticity": PLASTIC})
    out["s20x8-q4-sri-graded3-half-pl"] = with_overrides(**{
        "mesh.ny": 8, "mesh.grading": 3.0, "time.dt.fixed": 1.0e-7, "material.plasticity": PLASTIC,
        "output.probes": {"A": {"x": 0.100, "y": 0.0}, "B": {"x": 0.150, "y": 0.02}}})
    out["s20x4-q4-1pt-hg0.1-full-pl"] = with_overrides(**{
        "mesh.element": "q4-1pt", "mesh.model": "full", "mesh.nx": 40, "mesh.hourglass": 0.1,
        "material.plasticity": PLASTIC})
    out["s20x4-q4-sri-table-half-pl"] = with_overrides(**{"material.plasticity": TABLE})
    out["s20x4-q4-sri-aftercontact-half-el"] = with_overrides(**{
        "time.end": {"after_contact": 2.0e-4}, "time.limit": 5e-3})
    out["s20x4-q4-sri-m10v15-half-pl"] = with_overrides(**{
        "load.impactor.mass": 10.0, "load.impactor.velocity": 15.0,
        "time.end": {"after_contact": 2.0e-4}, "material.plasticity": PLASTIC})
    # surface coupling (section 5b): enforcement x element x model x material, then variants
    enforcements = {"kin": "surface", "pen": {"surface": {"enforcement": "penalty"}}}
    for enf, contact in enforcements.items():
        for el in ["q4-full", "q4-sri", "q4-1pt"]:
            for model in ["half", "full"]:
                for mat in ["el", "pl"]:
                    out[f"s20x4-{el}-surface-{enf}-{model}-{mat}"] = surface(contact, **{
                        "mesh.element": el, "mesh.model": model,
                        "mesh.nx": 20 if model == "half" else 40,
                        "material.plasticity": PLASTIC if mat == "pl" else None})
    # (s_p = 1 shortens the stable step to 4.96e-7 s: dt 4e-7; its contact chatters, see README)
    for sp in [0.5, 1.0]:
        for mat in ["el", "pl"]:
            out[f"s20x4-q4-sri-surface-pen-sp{sp}-half-{mat}"] = surface(
                {"surface": {"enforcement": "penalty", "penalty_scale": sp}},
                **{"material.plasticity": PLASTIC if mat == "pl" else None,
                   "time.dt.fixed": 5.0e-7 if sp < 1 else 4.0e-7})
    for enf, contact in enforcements.items():
        out[f"s20x4-q4-sri-surface-{enf}-R0.05-half-pl"] = surface(
            contact, radius=0.05, **{"material.plasticity": PLASTIC})
        out[f"s20x8-q4-sri-surface-{enf}-graded3-half-pl"] = surface(contact, **{
            "mesh.ny": 8, "mesh.grading": 3.0, "time.dt.fixed": 1.0e-7,
            "material.plasticity": PLASTIC})
        out[f"s20x4-q4-sri-surface-{enf}-aftercontact-m10v15-half-pl"] = surface(contact, **{
            "load.impactor.mass": 10.0, "load.impactor.velocity": 15.0,
            "time.end": {"after_contact": 2.0e-4}, "material.plasticity": PLASTIC})
    # pulse (86.5 kN, 1 ms), small
    for mat in ["el", "pl"]:
        out[f"s20x4-pulse-q4-sri-half-{mat}"] = with_overrides(**{
            "load.impactor": None, "load.pulse": {"force": 86.5e3, "duration": 1.0e-3},
            "time.end": 3.0e-3, "material.plasticity": PLASTIC if mat == "pl" else None})
    if big:
        for el in ["q4-full", "q4-sri", "q4-1pt"]:
            for law in ["paper1m", "johnson"]:
                for mat in ["el", "pl"]:
                    out[f"b80x16-{el}-{law}-half-{mat}"] = with_overrides(**{
                        "mesh.nx": 80, "mesh.ny": 16, "mesh.element": el,
                        "time.end": 3.0e-3, "time.dt.fixed": 1.25e-7,
                        "load.impactor.contact_law": LAWS[law],
                        "material.plasticity": PLASTIC if mat == "pl" else None})
        for mat in ["el", "pl"]:
            out[f"b160x16-q4-sri-paper1m-full-{mat}"] = with_overrides(**{
                "mesh.nx": 160, "mesh.ny": 16, "mesh.model": "full", "time.end": 3.0e-3,
                "time.dt.fixed": 1.25e-7, "material.plasticity": PLASTIC if mat == "pl" else None})
            out[f"b80x16-pulse-q4-sri-half-{mat}"] = with_overrides(**{
                "mesh.nx": 80, "mesh.ny": 16, "time.dt.fixed": 1.25e-7,
                "load.impactor": None, "load.pulse": {"force": 86.5e3, "duration": 1.0e-3},
                "time.end": 3.0e-3, "material.plasticity": PLASTIC if mat == "pl" else None})
    return out


def run_case(name: str, scene: dict, out: Path) -> dict:
    d = out / name
    d.mkdir(parents=True, exist_ok=True)
    sp = d / "scene.yaml"
    sp.write_text(yaml.safe_dump(scene, sort_keys=False))
    t0 = time.perf_counter()
    subprocess.run([str(RUST), "simulate", str(sp), "--out", str(d / "rust"), "--quiet", "--force",
                    "--threads", "1"], check=True)
    t1 = time.perf_counter()
    subprocess.run(PY + [str(sp), "--out", str(d / "python")], check=True, cwd=HERE,
                   stdout=subprocess.DEVNULL)
    t2 = time.perf_counter()
    ha, hb = read_history(d / "rust"), read_history(d / "python")
    sa, sb = read_summary(d / "rust"), read_summary(d / "python")
    cd, problems = column_diffs(ha, hb)
    sd, sproblems = summary_diffs(sa, sb)
    na, nb, worst = interval_steps(sa, sb)
    res = {
        "case": name,
        "history": {c.name: {"linf": c.linf, "l2": c.l2, "peak": c.peak, "t": c.t_at_max}
                    for c in cd},
        "summary": {k: r for k, _, _, r in sd},
        "intervals": [na, nb, worst],
        "wall_rust_s": sa.get("wall_time_s"), "wall_python_s": sb.get("wall_time_s"),
        "process_rust_s": t1 - t0, "process_python_s": t2 - t1,
        "problems": problems + sproblems,
    }
    (d / "compare.json").write_text(json.dumps(res, indent=1) + "\n")
    return res


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", required=True)
    ap.add_argument("--only", default=None, help="run the cases whose name contains this")
    ap.add_argument("--big", action="store_true", help="add the 80 x 16 cases")
    args = ap.parse_args()
    out = Path(args.out)
    rows = []
    print("| case | worst key column | L-inf/peak | all columns L-inf/peak | summary max rel. diff | intervals (r/p, steps) | wall Py/Rust |")
    print("|---|---|---|---|---|---|---|")
    for name, sc in cases(args.big).items():
        if args.only and args.only not in name:
            continue
        r = run_case(name, sc, out)
        rows.append(r)
        key = {c: v for c, v in r["history"].items() if c in KEY_COLUMNS}
        kc = max(key, key=lambda c: key[c]["linf"])
        allmax = max(v["linf"] for v in r["history"].values())
        sm = max((v for k, v in r["summary"].items() if k not in ("dt_s", "n_steps", "n_elements")),
                 default=0.0)
        ia, ib, w = r["intervals"]
        ratio = (r["wall_python_s"] / r["wall_rust_s"]) if r["wall_rust_s"] else float("nan")
        print(f"| {name} | {kc} | {key[kc]['linf']:.1e} | {allmax:.1e} | {sm:.1e} | "
              f"{ia}/{ib}, {w} | {ratio:.0f} |" + (f" PROBLEMS: {r['problems']}" if r["problems"] else ""),
              flush=True)
    (out / "sweep.json").write_text(json.dumps(rows, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
