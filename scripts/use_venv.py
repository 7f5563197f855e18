"""The one venv re-exec helper of scripts/: run a script with <repo>/.venv's Python.

    import use_venv
    use_venv.ensure(__file__, ["numpy", "scipy", "yaml"])

When a module the script needs is missing and <repo>/.venv exists (made by
scripts/setup-venv.sh), the script is re-executed there with the same arguments; without
the venv it exits naming the missing module and the command that makes the venv.
Standard library only (it runs before the script's own imports).
"""
from __future__ import annotations

import importlib.util
import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
VENV = ROOT / ".venv"


def ensure(script: str, modules: list[str]) -> None:
    missing = [m for m in modules if importlib.util.find_spec(m) is None]
    if not missing:
        return
    python = VENV / "bin" / "python"
    if python.exists() and Path(sys.prefix).resolve() != VENV.resolve():
        os.execv(str(python), [str(python), script, *sys.argv[1:]])
    sys.exit(f"{Path(script).name}: {', '.join(missing)} missing: run scripts/setup-venv.sh first")
