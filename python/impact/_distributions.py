"""The declared input distributions of an uncertainty study, mapped from the unit interval.

A study's declaration is read and validated by the native module (``file:line:col`` messages,
``verification/src/uq/distribution.rs``); here each validated input becomes a percent-point
function ``u -> x`` (``u`` in (0, 1)), so that a design in the unit hypercube (scrambled Sobol'
or Latin hypercube) becomes samples of the inputs:

- ``uniform {lower, upper}``;
- ``normal {mean, std}``;
- ``lognormal {mean, cov}``: ``ln x`` normal with ``sigma = sqrt(ln(1 + cov^2))`` and
  ``mu = ln(mean) - sigma^2 / 2``, so that the mean and the coefficient of variation are the
  declared ones;
- ``truncated {normal | lognormal, lower, upper}``: the distribution restricted to
  ``[lower, upper]`` (``u`` mapped onto ``[F(lower), F(upper)]``).
"""
from __future__ import annotations

import math
from typing import Any, Callable, Mapping

import numpy as np


def _frozen(kind: str, d: Mapping[str, Any]):
    from scipy import stats

    if kind == "uniform":
        return stats.uniform(loc=d["lower"], scale=d["upper"] - d["lower"])
    if kind == "normal":
        return stats.norm(loc=d["mean"], scale=d["std"])
    if kind == "lognormal":
        sigma = math.sqrt(math.log1p(d["cov"] ** 2))
        return stats.lognorm(s=sigma, scale=d["mean"] * math.exp(-0.5 * sigma * sigma))
    raise ValueError(f"unknown distribution {kind!r}")


def ppf(kind: str, d: Mapping[str, Any]) -> Callable[[np.ndarray], np.ndarray]:
    """The percent-point function (inverse CDF) of a validated input's distribution."""
    if kind == "truncated":
        inner_kind = "normal" if "normal" in d else "lognormal"
        inner = _frozen(inner_kind, d[inner_kind])
        lo, hi = inner.cdf(d["lower"]), inner.cdf(d["upper"])
        return lambda u: np.clip(inner.ppf(lo + np.asarray(u) * (hi - lo)), d["lower"], d["upper"])
    frozen = _frozen(kind, d)
    return lambda u: frozen.ppf(np.asarray(u))


def describe(kind: str, d: Mapping[str, Any]) -> str:
    """The distribution in one line, SI values as declared."""
    if kind == "uniform":
        return f"uniform [{d['lower']:.4g}, {d['upper']:.4g}]"
    if kind == "normal":
        return f"normal (mean {d['mean']:.4g}, std {d['std']:.3g})"
    if kind == "lognormal":
        return f"lognormal (mean {d['mean']:.4g}, CoV {d['cov']:.3g})"
    inner = "normal" if "normal" in d else "lognormal"
    return f"{describe(inner, d[inner])} truncated to [{d['lower']:.4g}, {d['upper']:.4g}]"
