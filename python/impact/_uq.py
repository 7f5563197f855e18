"""`uq`: an uncertainty study run from its declaration (issue 27).

The declaration (a YAML file, ``verification/uq/*.yaml``) is read and validated by the native
module with ``file:line:col`` messages. Its inputs are sampled by Saltelli's design on a
scrambled Sobol' sequence (or Latin hypercubes) with the declared seed, the runs go through
:func:`impact.sweep` (a local pool or a Dask cluster: the rows are bit-identical either way), and
the base size ``N`` doubles through the declared sizes until the mean, the standard deviation
and the total-order indices of every output move less than the declared tolerances from
``N / 2`` to ``N``. A study of several scenes (``scenes:``, e.g. Table 2's velocities) runs
the same design on each; its outputs are the declared ones per scene (``key [label]``), and all
of them must converge. With ``sampling.mesh`` the sampled runs use that coarser mesh level (a
cheaper model of the spread); the first size's ``A`` and ``B`` points then run on both meshes,
and the samples are carried onto the declared mesh by the affine map those points give
(``y -> m_declared + ratio (y - m_sampled)``, the ratio of the two meshes' spreads and their
means on the same points): ``u_input`` is the converged standard deviation times the ratio. First- and total-order Sobol' indices come from SALib (Jansen's estimators,
bootstrap intervals); the mean and standard deviation from the ``2 N`` rows of ``A`` and ``B``
(the inputs' joint distribution), with percentile bootstrap intervals. The numerical
uncertainty comes from the declared mesh levels by the project's GCI rule (``impact._impact.gci``).

The whole declaration is checked before the first run: the native reader's rules (with
``file:line:col``: the seed's range, each input's key and the values its distribution declares
on every scene, each output a number of every scene's summary), then here every input's
smallest and largest draw of the designs to be run, on every scene as the runs set it (an
unbounded distribution can draw what a scene refuses: a normal Poisson ratio beyond 0.5).
Ctrl-C stops a study within a second (see :func:`impact.sweep`).
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
        study: the validated declaration (dict): its scenes (with their declared mesh), inputs
            and ``outputs``, a dict ``id -> {key, scene, table, scale, kind, label}`` (the id is
            the summary key, ``key [scene label]`` in a study of several scenes).
        samples: one row per run (the sweep's frame: the inputs' columns, the summaries,
            ``scene``: its label), scene after scene, each in the design's order.
        steps: the estimates at each base size, in order; ``steps[-1]`` is the final one.
        converged_at: the base size at which every output converged (None: not within the
            declared sizes).
        nominal: per scene (in declared order) its summary as declared (the study's ``S``).
        mesh: per output id, the values on the mesh levels and its ``u_num`` with how it was
            formed.
        spread_check: with ``sampling.mesh``, per output id the spread of the first size's ``A``
            and ``B`` points on the sampling mesh and on the declared mesh (``points``,
            ``level``, ``mean_sampled``, ``mean_declared``, ``std_sampled``, ``std_declared``,
            ``ratio``, ``corr``); empty otherwise.
        wall_time_s: the study's wall time (runs and analysis), s.
    """

    study: dict[str, Any]
    samples: "pandas.DataFrame"
    steps: list[Step]
    converged_at: int | None
    nominal: list[dict[str, Any]]
    mesh: dict[str, dict[str, Any]] = field(default_factory=dict)
    spread_check: dict[str, dict[str, Any]] = field(default_factory=dict)
    wall_time_s: float = 0.0

    @property
    def final(self) -> Step:
        return self.steps[-1]

    def declared_samples(self, oid: str) -> np.ndarray:
        """The propagated samples of ``oid`` (the final size's ``A`` and ``B`` rows) on the
        declared mesh: as run, or carried there from the sampling mesh by the spread check's
        affine map (shifted onto the declared mesh's spread alone when the sampled one has
        none)."""
        y = np.asarray(self.final.stats[oid]["samples"])
        c = self.spread_check.get(oid)
        if c is None:
            return y
        if not c["std_sampled"] > 0:
            return y - c["mean_sampled"] + c["mean_declared"]
        return c["mean_declared"] + c["ratio"] * (y - c["mean_sampled"])

    def u_input(self, oid: str) -> float:
        """The input uncertainty of ``oid`` on the declared mesh: the standard deviation of
        :meth:`declared_samples` (the converged one times the spread ratio of the meshes when
        the runs were sampled on another)."""
        c = self.spread_check.get(oid)
        if c is not None and not c["std_sampled"] > 0:
            return c["std_declared"]
        return float(np.std(self.declared_samples(oid), ddof=1))

    def nominal_value(self, oid: str) -> float:
        """The output ``oid`` of its scene as declared (``S``)."""
        o = self.study["outputs"][oid]
        return output_value(self.nominal[o["scene"]], o["key"])


def output_value(row: Any, key: str) -> float:
    """A summary value by its dotted key (``max_von_mises_Pa.A``) from a row or a dict; a
    run whose summary holds no number there (a wall's release time while the body is still on
    it) raises StudyRunError naming the key and what it holds."""
    head, _, rest = key.partition(".")
    try:
        v = row[head]
        return float(v[rest]) if rest else float(v)
    except (KeyError, TypeError, ValueError) as e:
        held = row.get(head, "nothing") if hasattr(row, "get") else "nothing"
        raise StudyRunError(f"output {key}: a run's summary holds no number there "
                            f"({head} = {held!r}: {e!r})") from None


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


def _at_level(scene: dict, level: float) -> dict[str, int]:
    """The overrides of a scene's declared mesh scaled by ``level`` (``ny`` at least 2)."""
    nx, ny = scene["mesh"]["nx"], scene["mesh"]["ny"]
    return {"mesh.nx": round(nx * level), "mesh.ny": max(2, round(ny * level))}


def _spread_check(decl: dict, x: np.ndarray, keys: list[str], client,
                  jobs) -> dict[str, dict[str, Any]]:
    """The points ``x`` run on the sampling mesh and on the declared mesh, per scene: per
    output the two standard deviations, their ratio (declared / sampled) and the correlation."""
    level = decl["sampling"]["mesh"]
    out = {}
    for i, sc in enumerate(decl["scenes"]):
        coarse = _run_rows(sc["path"], {**decl["set"], **_at_level(sc, level)}, keys, x, client,
                           jobs)
        fine = _run_rows(sc["path"], decl["set"], keys, x, client, jobs)
        for oid, o in decl["outputs"].items():
            if o["scene"] != i:
                continue
            a = np.array([output_value(r, o["key"]) for _, r in coarse.iterrows()])
            b = np.array([output_value(r, o["key"]) for _, r in fine.iterrows()])
            sa, sb = float(np.std(a, ddof=1)), float(np.std(b, ddof=1))
            corr = float(np.corrcoef(a, b)[0, 1]) if sa > 0 and sb > 0 else float("nan")
            out[oid] = {"points": len(x), "level": level, "mean_sampled": float(np.mean(a)),
                        "mean_declared": float(np.mean(b)), "std_sampled": sa,
                        "std_declared": sb, "ratio": sb / sa if sa > 0 else float("nan"),
                        "corr": corr}
    return out


def _mesh_uncertainty(scene: dict, study: dict, outputs: dict[str, dict], nominal: dict,
                      client, jobs) -> dict[str, dict[str, Any]]:
    """``u_num`` per output of one scene from the declared mesh levels by the project's GCI
    rule (formal order 2), as a standard uncertainty ``GCI / 2`` (the GCI taken as a 95 %
    expanded uncertainty, as the project's evidence page does); a series the rule refuses (not
    asymptotic) gets ``3 |f_1 - f_1/2| / 2``, the last increment with the safety factor 3,
    and says so."""
    levels = study["mesh_levels"]
    over = [{**study["set"], **_at_level(scene, lv)} for lv in levels]
    df = sweep(scene["path"], over, client=client, jobs=jobs)
    out = {}
    for oid, o in outputs.items():
        values = [output_value(r, o["key"]) for _, r in df.iterrows()]
        fine = output_value(nominal, o["key"])
        try:
            g, fs, p, orders = _impact.gci(values, 2.0, 2.0)
            u = 0.5 * g * abs(fine)
            how = f"GCI {100 * g:.2g} %, Fs {fs:g}, p {p:.2f} (orders {', '.join(f'{o:.2f}' for o in orders)})"
        except ValueError as e:
            u = 0.5 * 3.0 * abs(values[-1] - values[-2])
            why = str(e).split(": ")[1] if ": " in str(e) else str(e)
            how = f"no GCI, not asymptotic ({why}): Fs 3 x the last increment"
        out[oid] = {"levels": levels, "values": values, "u_num": u, "how": how}
    return out


def read(study: str | os.PathLike[str]) -> dict[str, Any]:
    """The validated declaration as a dict (``outputs`` keyed by their id, in declared
    order); raises SceneError with the place of what the rules refuse."""
    decl = json.loads(_impact.read_study(os.fspath(study)))
    decl["outputs"] = {o["id"]: o for o in decl["outputs"]}
    return decl


def _design(sampling: dict[str, Any], maps: list, n: int) -> np.ndarray:
    """The inputs' values of the Saltelli design of base size ``n`` (one row per run)."""
    u = saltelli(sampling["method"], len(maps), n, sampling["seed"])
    return np.column_stack([m(u[:, j]) for j, m in enumerate(maps)])


def _check_draws(decl: dict[str, Any], maps: list, sizes: list[int], fixed: list[dict]) -> None:
    """Every input's smallest and largest value over the designs of ``sizes``, each set on
    every scene as its runs set it (``fixed``: the study's ``set`` and sampling mesh): a value
    a scene refuses raises SceneError at the input's declaration, before any run."""
    x = np.vstack([_design(decl["sampling"], maps, n) for n in sizes])
    texts = [_impact.read_scene(os.fspath(sc["path"])) for sc in decl["scenes"]]
    for j, inp in enumerate(decl["inputs"]):
        for which, value in (("smallest", float(x[:, j].min())), ("largest", float(x[:, j].max()))):
            for sc, text, set_ in zip(decl["scenes"], texts, fixed):
                why = _impact.refusal(text, os.fspath(sc["path"]),
                                      json.dumps({**set_, inp["key"]: value}))
                if why:
                    drawn = f"{value:.6g} (the {which} of its {len(x)} values, N up to {max(sizes)})"
                    raise _impact.SceneError(_refused_draw(inp, drawn, sc["path"], why))


def _refused_draw(inp: dict[str, Any], drawn: str, scene: str, why: str) -> str:
    """The message for a value the design draws that a scene refuses: where the input is
    declared, the value, the scene's rule, and what to do."""
    return (f"{inp['at']}: inputs.{inp['key']}.{inp['kind']}: the design draws {drawn}, which "
            f"{scene} does not allow: {why}; narrow the distribution or truncate it to the "
            "values allowed (truncated: {normal | lognormal: {...}, lower, upper})")


def uq(study: str | os.PathLike[str], *, client: "Client | str | None" = None,
       jobs: int | None = None, sizes: list[int] | None = None, mesh: bool = True) -> UQResult:
    """Runs the study declared in the file ``study`` and returns its :class:`UQResult`.

    Args:
        study: the declaration (YAML; see ``verification/uq/`` and docs/user-guide.md).
        client, jobs: as for :func:`impact.sweep` (a Dask client or address; local runs at a time).
        sizes: the base sizes ``N`` to go through instead of the declared ones (each twice
            the one before); the study stops at the first size where every output converged.
        mesh: also run the declared mesh levels for ``u_num``.

    Raises:
        SceneError: the declaration is refused (``file:line:col: field = value: allowed``).
        StudyRunError: a sampled run failed (the rows and their messages).
    """
    import pandas

    from ._run import simulate

    t0 = time.perf_counter()
    decl = read(study)
    scenes = decl["scenes"]
    inputs = decl["inputs"]
    keys = [i["key"] for i in inputs]
    maps = [ppf(i["kind"], i["distribution"]) for i in inputs]
    d = len(inputs)
    samp = decl["sampling"]
    sizes = list(sizes or samp["sizes"])
    outputs = decl["outputs"]
    level = samp.get("mesh")
    fixed = [{**decl["set"], **(_at_level(sc, level) if level else {})} for sc in scenes]
    _check_draws(decl, maps, sizes, fixed)
    frames: list[list[pandas.DataFrame]] = [[] for _ in scenes]
    steps: list[Step] = []
    converged_at = None
    done = 0
    for n in sizes:
        if samp["method"] != "sobol":
            frames, done = [[] for _ in scenes], 0
        design = _design(samp, maps, n)
        x = design[done:]
        for sc, set_, fr in zip(scenes, fixed, frames):
            fr.append(_run_rows(sc["path"], set_, keys, x, client, jobs))
        done = len(design)
        per_scene = [pandas.concat(fr, ignore_index=True) for fr in frames]
        stats = {oid: _estimates(np.array([output_value(r, o["key"])
                                           for _, r in per_scene[o["scene"]].iterrows()]),
                                 d, n, keys, samp["seed"]) for oid, o in outputs.items()}
        ok = bool(steps) and all(_converged(steps[-1].stats[k], stats[k], decl["convergence"])
                                 for k in outputs)
        steps.append(Step(n=n, runs=sum(len(f) for f in per_scene), stats=stats, converged=ok))
        if ok:
            converged_at = n
            break
    nominal = [simulate(sc["path"], threads=1, overrides=decl["set"]).summary for sc in scenes]
    samples = pandas.concat([pandas.concat(fr, ignore_index=True).assign(scene=sc["label"])
                             for sc, fr in zip(scenes, frames)], ignore_index=True)
    result = UQResult(study=decl, samples=samples, steps=steps, converged_at=converged_at,
                      nominal=nominal)
    if level:
        x0 = _design(samp, maps, sizes[0])[propagation_rows(d, sizes[0])]
        result.spread_check = _spread_check(decl, x0, keys, client, jobs)
    if mesh:
        for i, sc in enumerate(scenes):
            mine = {oid: o for oid, o in outputs.items() if o["scene"] == i}
            result.mesh.update(_mesh_uncertainty(sc, decl, mine, nominal[i], client, jobs))
    result.wall_time_s = time.perf_counter() - t0
    return result
