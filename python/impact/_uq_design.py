"""Sampling designs in the unit hypercube for an uncertainty study, with a fixed seed.

Saltelli's design for first- and total-order Sobol' indices (Saltelli et al. 2010, the layout
SALib's ``sobol.analyze`` reads with ``calc_second_order=False``): two matrices ``A`` and ``B``
of ``N`` points each (the two halves of a ``2 D``-dimensional scrambled Sobol' sequence, or two
Latin hypercubes), and per base point ``j`` the rows ``A_j, AB_j^1 ... AB_j^D, B_j``, where
``AB^i`` is ``A`` with column ``i`` taken from ``B``: ``N (D + 2)`` runs.

With ``sobol`` the designs are nested: the first ``N (D + 2)`` rows of the design of ``2 N`` are
the design of ``N`` (the scrambled sequence's first ``N`` points do not depend on how many are
drawn), so a study that doubles ``N`` runs only the new rows.
"""
from __future__ import annotations

import numpy as np


def base_points(method: str, d: int, n: int, seed: int) -> np.ndarray:
    """``n`` points in ``[0, 1)^d`` (``sobol``: scrambled Sobol', ``lhs``: Latin hypercube)."""
    from scipy.stats import qmc

    if method == "sobol":
        return qmc.Sobol(d=d, scramble=True, seed=seed).random(n)
    if method == "lhs":
        return qmc.LatinHypercube(d=d, seed=seed + n).random(n)
    raise ValueError(f"sampling method {method!r}: sobol or lhs")


def saltelli(method: str, d: int, n: int, seed: int) -> np.ndarray:
    """The ``N (D + 2)`` x ``D`` design, rows ``A_j, AB_j^1..AB_j^D, B_j`` per base point."""
    ab = base_points(method, 2 * d, n, seed)
    a, b = ab[:, :d], ab[:, d:]
    rows = np.empty((n * (d + 2), d))
    step = d + 2
    rows[0::step] = a
    rows[step - 1 :: step] = b
    for i in range(d):
        mixed = a.copy()
        mixed[:, i] = b[:, i]
        rows[i + 1 :: step] = mixed
    return rows


def propagation_rows(d: int, n: int) -> np.ndarray:
    """Indices of the rows of a Saltelli design of ``n`` base points that sample the inputs'
    joint distribution (the ``A`` and ``B`` rows: ``2 n`` points)."""
    step = d + 2
    a = np.arange(0, n * step, step)
    return np.sort(np.concatenate([a, a + step - 1]))
