"""Store another code's run as a reference of kind `other code` (reference-data/codes/README.md).

    python3 scripts/store_code_run.py RUN_DIR reference-data/codes/CODE/NAME

RUN_DIR is one scene's folder of `impact verify --code CODE` (OUT/codes/CODE/runs/SUITE/CASE/
SCENE/). Copies what a check reads (summary.json, history.csv), the adapter's record
(adapter.json), the scene it ran (scene.yaml, its schema modeline pointed at
solver/scene.schema.json) and the input files the record lists, and
nothing else; refuses a folder whose adapter.json is not CODE's, or a NAME folder that exists.
"""

import json
import os
import shutil
import sys
from pathlib import Path


def main(run_dir: Path, target: Path) -> None:
    code = target.parent.name
    record = json.loads((run_dir / "adapter.json").read_text())
    if record.get("code") != code:
        sys.exit(f"{run_dir}/adapter.json says the run is {record.get('code')!r}, not {code!r}'s")
    if target.exists():
        sys.exit(f"{target} exists: remove it first to store a new run")
    names = ["summary.json", "history.csv", "adapter.json", "scene.yaml", *record.get("input", [])]
    missing = [n for n in names if not (run_dir / n).is_file()]
    if missing:
        sys.exit(f"{run_dir}: no {', '.join(missing)}")
    target.mkdir(parents=True)
    for n in names:
        shutil.copyfile(run_dir / n, target / n)
    schema_modeline(target / "scene.yaml")
    print(f"stored {len(names)} files of {code}'s run in {target}")


def schema_modeline(scene: Path) -> None:
    """Points the scene's first line (the editors' schema modeline) at solver/scene.schema.json
    from where the scene now lies, as every scene file of the repository does."""
    root = Path(__file__).resolve().parent.parent
    schema = os.path.relpath(root / "solver" / "scene.schema.json", scene.resolve().parent)
    lines = scene.read_text().splitlines(keepends=True)
    modeline = f"# yaml-language-server: $schema={schema}\n"
    if lines and lines[0].startswith("# yaml-language-server: $schema="):
        lines[0] = modeline
    else:
        lines.insert(0, modeline)
    scene.write_text("".join(lines))


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(Path(sys.argv[1]), Path(sys.argv[2]))
