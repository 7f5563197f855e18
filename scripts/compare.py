#!/usr/bin/env python3
"""Compare a Rust run with a Python run: scripts/compare.py RUST_OUT PY_OUT [--tol T] [--plots DIR]

Per history column: L-inf and L2 (rms) differences relative to the column's peak; summary
metrics; the wall time of each side and their ratio. Exit status 1 when --tol is exceeded.
See `scripts/compare.py --help` and scripts/README.md. Runs with <repo>/.venv (re-executes
itself there when numpy is missing).
"""
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import use_venv  # noqa: E402

use_venv.ensure(__file__, ["numpy"])
from indep_fe.compare import main  # noqa: E402

if __name__ == "__main__":
    sys.exit(main())
