"""`uq`: an uncertainty study run from its declaration (issue 27).

The declaration (a YAML file, ``verification/uq/*.yaml``) is read and validated by the native
module with ``file:line:col`` messages. Its inputs are sampled by Saltelli's design on a
scrambled Sobol' sequence (or Latin hypercubes) with the declared seed, the runs go through
:func:`impact.sweep` (a local pool or a Dask cluster: the rows are bit-identical either way), and
the base size ``N`` doubles through the declared sizes until the mean, the standard deviation
and the total-order indices of every output move less than the declared tolerances from
``N / 2`` to ``N``. First- and total-order Sobol' indices come from SALib (Jansen's estimators,
bootstrap intervals); the mean and standard deviation from the ``2 N`` rows of ``A`` and ``B``
(the inputs' joint distribution), with percentile bootstrap intervals. The numerical
uncertainty comes from the declared mesh levels by the project's GCI rule (``impact._impact.gci``).
"""
from __future__ import annotations

import json
import os
import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from . import _impact
from ._distributions import ppf
from ._sweep import sweep
from ._uq_design import propagation_rows, saltelli

if TYPE_CHECKING:
    import pandas
    from distributed import Client

BOOTSTRAP = 1000
"""Bootstrap resamples for every interval (95 %)."""


class StudyRunError(RuntimeError):
    """A run of the study failed: the message lists the failed rows and their errors."""


@dataclass
class Step:
    """The estimates at one base size ``n`` (``runs = n (D + 2)``), per output."""

    n: int
    runs: int
    stats: dict[str, dict[str, Any]]
    converged: bool


@dataclass
class UQResult:
    """A finished study.

    Attributes:
        study: the validated declaration (dict), with its inputs and outputs.
        samples: one row per run (the sweep's frame: the inputs' columns, the summaries).
        steps: the estimates at each base size, in order; ``steps[-1]`` is the final one.
        converged_at: the base size at which every output converged (None: not within the
            declared sizes).
        nominal: the summary of the scene as declared (the study's ``S``).
        mesh: per output, the values on the mesh levels and its ``u_num`` with how it was formed.
        wall_time_s: the study's wall time (runs and analysis), s.
    """

    study: dict[str, Any]
    samples: "pandas.DataFrame"
    steps: list[Step]
    converged_at: int | None
    nominal: dict[str, Any]
    mesh: dict[str, dict[str, Any]] = field(default_factory=dict)
    wall_time_s: float = 0.0

    @property
    def final(self) -> Step:
        return self.steps[-1]


def output_value(row: Any, key: str) -> float:
    """A summary value by its dotted key (``max_von_mises_Pa.A``) from a row or a dict."""
    head, _, rest = key.partition(".")
    v = row[head]
    return float(v[rest]) if rest else float(v)


def _percentile_interval(samples: np.ndarray, stat, rng: np.random.Generator) -> tuple[float, float]:
    n = len(samples)
    reps = np.array([stat(samples[rng.integers(0, n, n)]) for _ in range(BOOTSTRAP)])
    lo, hi = np.percentile(reps, [2.5, 97.5])
    return float(lo), float(hi)


def _estimates(y: np.ndarray, d: int, n: int, names: list[str], seed: int) -> dict[str, Any]:
    """Mean and std (with bootstrap intervals) and the Sobol' indices of one output."""
    from SALib.analyze import sobol

    prop = y[propagation_rows(d, n)]
    rng = np.random.default_rng(seed)
    std = lambda s: float(np.std(s, ddof=1))  # noqa: E731
    si = sobol.analyze({"num_vars": d, "names": names, "bounds": [[0.0, 1.0]] * d}, y,
                       calc_second_order=False, num_resamples=BOOTSTRAP, conf_level=0.95,
                       seed=seed)
    return {
        "mean": float(np.mean(prop)), "mean_ci": _percentile_interval(prop, np.mean, rng),
        "std": std(prop), "std_ci": _percentile_interval(prop, std, rng),
        "S1": [float(x) for x in si["S1"]], "S1_conf": [float(x) for x in si["S1_conf"]],
        "ST": [float(x) for x in si["ST"]], "ST_conf": [float(x) for x in si["ST_conf"]],
        "samples": [float(x) for x in prop],
    }


def _converged(prev: dict[str, Any], cur: dict[str, Any], tol: dict[str, float]) -> bool:
    scale = max(abs(cur["mean"]), 1e-300)
    moved_mean = abs(cur["mean"] - prev["mean"]) / scale
    moved_std = abs(cur["std"] - prev["std"]) / max(cur["std"], 1e-300)
    moved_st = max(abs(a - b) for a, b in zip(cur["ST"], prev["ST"]))
    return moved_mean <= tol["mean"] and moved_std <= tol["std"] and moved_st <= tol["total_index"]


def _run_rows(scene: str, fixed: dict, keys: list[str], x: np.ndarray, client,
              jobs) -> "pandas.DataFrame":
    overrides = [{**fixed, **{k: float(v) for k, v in zip(keys, row)}} for row in x]
    df = sweep(scene, overrides, client=client, jobs=jobs)
    failed = df[df["error"].notna()]
    if len(failed):
        lines = [f"row {i}: {df.loc[i, 'error']}" for i in failed.index[:5]]
        raise StudyRunError(f"{len(failed)} of {len(df)} runs failed:\n" + "\n".join(lines))
    return df


def _mesh_uncertainty(scene: str, study: dict, outputs: list[str], nominal: dict,
                      client, jobs) -> dict[str, dict[str, Any]]:
    """``u_num`` per output from the declared mesh levels by the project's GCI rule (formal
    order 2), as a standard uncertainty ``GCI / 2`` (the GCI taken as a 95 % expanded
    uncertainty, as the project's evidence page does); a series the rule refuses (not
    asymptotic) gets ``3 |f_1 - f_1/2| / 2``, the last increment with the safety factor 3,
    and says so."""
    nx, ny = study["mesh"]["nx"], study["mesh"]["ny"]
    levels = study["mesh_levels"]
    over = [{**study["set"], "mesh.nx": round(nx * lv), "mesh.ny": max(2, round(ny * lv))}
            for lv in levels]
    df = sweep(scene, over, client=client, jobs=jobs)
    out = {}
    for key in outputs:
        values = [output_value(r, key) for _, r in df.iterrows()]
        fine = output_value(nominal, key)
        try:
            g, fs, p, orders = _impact.gci(values, 2.0, 2.0)
            u = 0.5 * g * abs(fine)
            how = f"GCI {100 * g:.2g} %, Fs {fs:g}, p {p:.2f} (orders {', '.join(f'{o:.2f}' for o in orders)})"
        except ValueError as e:
            u = 0.5 * 3.0 * abs(values[-1] - values[-2])
            why = str(e).split(": ")[1] if ": " in str(e) else str(e)
            how = f"no GCI, not asymptotic ({why}): Fs 3 x the last increment"
        out[key] = {"levels": levels, "values": values, "u_num": u, "how": how}
    return out


def uq(study: str | os.PathLike[str], *, client: "Client | str | None" = None,
       jobs: int | None = None, sizes: list[int] | None = None, mesh: bool = True) -> UQResult:
    """Runs the study declared in the file ``study`` and returns its :class:`UQResult`.

    Args:
        study: the declaration (YAML; see ``verification/uq/`` and the README).
        client, jobs: as for :func:`impact.sweep` (a Dask client or address; local runs at a time).
        sizes: the base sizes ``N`` to go through instead of the declared ones (each twice
            the one before); the study stops at the first size where every output converged.
        mesh: also run the declared mesh levels for ``u_num``.

    Raises:
        SceneError: the declaration is refused (``file:line:col: field = value: allowed``).
        StudyRunError: a sampled run failed (the rows and their messages).
    """
    import pandas

    t0 = time.perf_counter()
    decl = json.loads(_impact.read_study(os.fspath(study)))
    scene = decl["scene"]
    inputs = decl["inputs"]
    keys = [i["key"] for i in inputs]
    maps = [ppf(i["kind"], i["distribution"]) for i in inputs]
    d = len(inputs)
    samp = decl["sampling"]
    sizes = list(sizes or samp["sizes"])
    outputs = list(decl["outputs"])
    frames: list[pandas.DataFrame] = []
    steps: list[Step] = []
    converged_at = None
    done = 0
    for n in sizes:
        u = saltelli(samp["method"], d, n, samp["seed"])
        if samp["method"] != "sobol":
            frames, done = [], 0
        x = np.column_stack([m(u[done:, j]) for j, m in enumerate(maps)])
        frames.append(_run_rows(scene, decl["set"], keys, x, client, jobs))
        done = len(u)
        df = pandas.concat(frames, ignore_index=True)
        stats = {k: _estimates(np.array([output_value(r, k) for _, r in df.iterrows()]), d, n,
                               keys, samp["seed"]) for k in outputs}
        ok = bool(steps) and all(_converged(steps[-1].stats[k], stats[k], decl["convergence"])
                                 for k in outputs)
        steps.append(Step(n=n, runs=len(df), stats=stats, converged=ok))
        if ok:
            converged_at = n
            break
    from ._run import simulate

    nominal = simulate(scene, threads=1, overrides=decl["set"]).summary
    result = UQResult(study=decl, samples=pandas.concat(frames, ignore_index=True), steps=steps,
                      converged_at=converged_at, nominal=nominal)
    if mesh:
        result.mesh = _mesh_uncertainty(scene, decl, outputs, nominal, client, jobs)
    result.wall_time_s = time.perf_counter() - t0
    return result
