"""The repository's own files as a user meets them: every tracked file that starts with a
`#!` line (a script the READMEs run directly, e.g. `scripts/reconstruction/reconstruct.py`)
is executable in the checkout, so it never answers 'Permission denied'. Reference: the
READMEs' commands; the list of files comes from `git ls-files`."""
from __future__ import annotations

import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def tracked_scripts(root: Path) -> list[Path]:
    listed = subprocess.run(["git", "ls-files", "-z"], cwd=root, capture_output=True)
    if listed.returncode != 0:
        pytest.skip("not a git checkout: the tracked files are unknown")
    names = listed.stdout.split(b"\0")
    paths = [root / n.decode() for n in names if n]
    scripts = []
    for p in paths:
        if p.is_file() and not p.is_symlink():
            with open(p, "rb") as f:
                if f.read(2) == b"#!":
                    scripts.append(p)
    return scripts


def not_executable(paths: list[Path]) -> list[str]:
    return [str(p) for p in paths if not os.access(p, os.X_OK)]


def test_every_tracked_script_with_a_shebang_is_executable():
    scripts = tracked_scripts(ROOT)
    assert any(p.name == "reconstruct.py" for p in scripts)
    assert not_executable(scripts) == []


def test_the_check_finds_a_script_without_the_executable_bit(tmp_path):
    script = tmp_path / "run.py"
    script.write_text("#!/usr/bin/env python3\n")
    script.chmod(0o644)
    assert not_executable([script]) == [str(script)]
    script.chmod(0o755)
    assert not_executable([script]) == []
