"""CLI: python -m indep_fe simulate SCENE.yaml --out DIR | python -m indep_fe compare A B"""
from __future__ import annotations

import argparse
import json
import sys

from .contact import ContactLawExceeded
from .scene import SceneError, load_scene
from .solver import UnstableRun, simulate, write_outputs
from .step import StepTooSmall


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="indep_fe", description=__doc__)
    sub = ap.add_subparsers(dest="cmd", required=True)
    sim = sub.add_parser("simulate", help="run a scene, write history.csv and summary.json")
    sim.add_argument("scene", help="scene YAML file (SI units)")
    sim.add_argument("--out", required=True, help="output directory")
    sim.add_argument("--progress", action="store_true", help="print progress to stderr")
    sub.add_parser("compare", add_help=False,
                   help="compare two runs (same as scripts/compare.py; see compare --help)")
    argv = sys.argv[1:] if argv is None else argv
    if argv[:1] == ["compare"]:
        from .compare import main as compare_main
        return compare_main(argv[1:])
    args = ap.parse_args(argv)
    try:
        scene = load_scene(args.scene)
        res = simulate(scene, progress=args.progress)
    except (SceneError, ContactLawExceeded, UnstableRun, StepTooSmall, ValueError) as exc:
        print(f"indep_fe: error: {exc}", file=sys.stderr)
        return 2
    write_outputs(res, args.out)
    keys = ["impulse_Ns", "peak_contact_force_N", "max_plate_displacement_m",
            "contact_duration_s", "final_impactor_velocity_mps", "max_energy_balance_error",
            "dt_s", "n_steps", "wall_time_s"]
    print(json.dumps({k: res.summary[k] for k in keys}, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
