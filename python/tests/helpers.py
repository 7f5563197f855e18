"""Reading the CLI's files back exactly, comparing runs with wall-clock keys aside, and
writing small study declarations."""
from __future__ import annotations

import csv
import json
from pathlib import Path

import numpy as np

import impact

ROOT = Path(__file__).resolve().parents[2]


def read_history(path: Path) -> dict[str, np.ndarray]:
    """history.csv as float64 columns. The CLI writes Rust's shortest round-trip digits and
    Python's float() rounds correctly, so the values are the solver's bits."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    return {name: np.array([float(r[c]) for r in body]) for c, name in enumerate(header)}


def read_summary(path: Path) -> dict:
    return json.loads(path.read_text())


def without_timing(summary: dict) -> dict:
    return {k: v for k, v in summary.items() if k not in impact.TIMING_KEYS}


def assert_same_history(a: dict[str, np.ndarray], b: dict[str, np.ndarray]) -> None:
    assert list(a) == list(b)
    for name in a:
        assert a[name].dtype == np.float64 and b[name].dtype == np.float64
        # Bit for bit: compare the raw bytes (also tells -0.0 from 0.0, and NaN payloads).
        assert a[name].tobytes() == b[name].tobytes(), name


def write_study(folder: Path, inputs: str, sampling: str = "{method: sobol, seed: 1, sizes: [4, 8]}",
                outputs: str = "{impulse_Ns: {}}", scene: str = "paper-plastic.yaml") -> Path:
    """``folder/study.yaml`` on a scene of verification/scenes: ``inputs`` (indented lines)
    on line 4, ``sampling`` on the line after them, ``outputs`` on the last line."""
    text = (f"title: t\nscene: {ROOT / 'verification' / 'scenes' / scene}\ninputs:\n{inputs}"
            f"sampling: {sampling}\nconvergence: {{mean: 0.01, std: 0.1, total_index: 0.1}}\n"
            f"mesh_levels: [0.25, 0.5, 1.0]\noutputs: {outputs}\n")
    path = folder / "study.yaml"
    path.write_text(text)
    return path
