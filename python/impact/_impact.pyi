"""Stub of the native module `impact._impact` (Rust, pyo3). Use the documented functions of
`impact` instead; these are their building blocks."""

from typing import Any, Callable

import numpy as np
import numpy.typing as npt

TIMING_KEYS: list[str]

class SceneError(ValueError): ...
class RunError(RuntimeError): ...
class VerifyError(ValueError): ...

def read_scene(path: str) -> str: ...
def simulate(
    text: str,
    source: str,
    out: str | None = None,
    threads: int | None = None,
    overrides: str | None = None,
    warn: Callable[[str], None] | None = None,
    stop: Any | None = None,
) -> tuple[str, list[str], list[npt.NDArray[np.float64]]]: ...
def verify(
    selectors: list[str],
    filter: str | None = None,
    light: bool = False,
    jobs: int | None = None,
    out: str | None = None,
    report: bool = False,
    root: str | None = None,
) -> str: ...
def read_study(path: str) -> str: ...
def gci(values: list[float], ratio: float, formal: float) -> tuple[float, float, float, list[float]]: ...
def rigid_plastic(
    text: str, source: str, plastic_work: float, overrides: str | None = ...
) -> str | None: ...
def refusal(text: str, source: str, overrides: str | None = None) -> str | None: ...
def summary_keys(text: str, source: str, overrides: str | None = None) -> list[str]: ...
