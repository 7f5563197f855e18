"""ASME V&V 20 budget of one comparison and the area validation metric (V&V 10.1).

- ``E = S - D``, ``u_val = sqrt(u_num^2 + u_input^2 + u_D^2)``; the model error lies in
  ``E +- k u_val``; with ``k = 2`` ``|E| <= 2 u_val`` says the comparison cannot tell the model
  from the reference at that level (ASME V&V 20-2009).
- The area metric (Ferson, Oberkampf & Ginzburg 2008; ASME V&V 10.1-2012): the area between the
  model's CDF and the reference's, in the output's unit.
"""
from __future__ import annotations

import math
from typing import Callable, Sequence

import numpy as np


def budget(s: float, d: float, u_num: float, u_input: float, u_d: float, k: float = 2.0) -> dict:
    """One V&V 20 row (all in the output's unit): ``E``, ``u_val``, the verdict and the interval
    ``[E - k u_val, E + k u_val]`` for the model error."""
    for name, u in (("u_num", u_num), ("u_input", u_input), ("u_D", u_d)):
        if not (math.isfinite(u) and u >= 0.0):
            raise ValueError(f"{name} = {u}: must be a finite number >= 0")
    e = s - d
    u_val = math.sqrt(u_num**2 + u_input**2 + u_d**2)
    return {
        "S": s, "D": d, "E": e, "u_num": u_num, "u_input": u_input, "u_D": u_d,
        "u_val": u_val, "within": abs(e) <= k * u_val,
        "error_interval": (e - k * u_val, e + k * u_val),
    }


def printed_digit_uncertainty(text: str, scale: float = 1.0) -> float:
    """The standard uncertainty of a printed number from its digits: half a unit of the last
    printed digit, as a uniform distribution, ``a / sqrt(3)`` (times ``scale``, e.g. to SI)."""
    t = text.strip().lstrip("+-")
    decimals = len(t.split(".")[1]) if "." in t else 0
    return 0.5 * 10.0 ** (-decimals) / math.sqrt(3.0) * abs(scale)


def area_metric(cdf_a: Callable[[np.ndarray], np.ndarray], cdf_b: Callable[[np.ndarray], np.ndarray],
                lower: float, upper: float, points: int = 200_001) -> float:
    """``integral |F_a(x) - F_b(x)| dx`` over ``[lower, upper]`` (trapezoids on a uniform grid),
    which must hold both distributions' mass."""
    x = np.linspace(lower, upper, points)
    return float(np.trapezoid(np.abs(cdf_a(x) - cdf_b(x)), x))


def empirical_cdf(samples: Sequence[float]) -> Callable[[np.ndarray], np.ndarray]:
    """The step CDF of samples."""
    s = np.sort(np.asarray(samples, dtype=float))
    return lambda x: np.searchsorted(s, x, side="right") / len(s)


def area_to_uniform(samples: Sequence[float], centre: float, half_width: float) -> float:
    """Area between the samples' CDF and a uniform reference on ``centre +- half_width`` (a
    printed number and its last digit)."""
    s = np.asarray(samples, dtype=float)
    lo = min(s.min(), centre - half_width)
    hi = max(s.max(), centre + half_width)
    pad = 1e-9 * max(abs(lo), abs(hi), 1e-300) + 1e-6 * (hi - lo)
    ref = lambda x: np.clip((x - (centre - half_width)) / (2 * half_width), 0.0, 1.0)  # noqa: E731
    return area_metric(empirical_cdf(s), ref, lo - pad, hi + pad)
