"""Reading the CLI's files back exactly, and comparing runs with wall-clock keys aside."""
from __future__ import annotations

import csv
import json
from pathlib import Path

import numpy as np

import impact


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
