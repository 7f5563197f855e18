"""The report page of uncertainty studies (issue 27): one V&V 20 row per comparison, the
converged statistics with their bootstrap intervals, the Sobol' indices as bar charts and the
output CDFs. Written as Markdown with SVG figures next to it (matplotlib), which
``impact report`` embeds as its uncertainty section (``<verify out>/uq/uq.md``).
"""
from __future__ import annotations

import csv
import json
import math
import os
from pathlib import Path
from typing import Any, Sequence

import numpy as np

from ._distributions import describe
from ._uq import UQResult
from ._vv20 import area_to_uniform, budget, printed_digit_uncertainty


def _root_of(path: str) -> Path:
    p = Path(path).resolve()
    for parent in [p, *p.parents]:
        if (parent / "reference-data").is_dir():
            return parent
    return Path.cwd()


def reference(spec: dict[str, Any], root: Path) -> tuple[float, float, str] | None:
    """``(D, u_D, the printed text)`` of an output's table reference in SI, or None (the
    declaration's reader has checked that the cell exists and holds a number)."""
    t = spec.get("table")
    if not t:
        return None
    with open(root / t["file"], newline="") as f:
        rows = list(csv.DictReader(f))
    first = next(iter(rows[0]))
    row = next(r for r in rows if r[first] == t["row"])
    text = row[t["column"]]
    scale = spec.get("scale") or 1.0
    return float(text) * scale, printed_digit_uncertainty(text, scale), text


def budget_rows(r: UQResult, study_path: str) -> list[dict[str, Any]]:
    """One V&V 20 row per output with a reference."""
    root = _root_of(study_path)
    rows = []
    for key, spec in r.study["outputs"].items():
        ref = reference(spec, root)
        if ref is None:
            continue
        d, u_d, printed = ref
        s = r.nominal_value(key)
        st = r.final.stats[key]
        u_num = r.mesh.get(key, {}).get("u_num", math.nan)
        row = budget(s, d, 0.0 if math.isnan(u_num) else u_num, r.u_input(key), u_d)
        half = u_d * math.sqrt(3.0)
        row.update(key=key, label=spec.get("label") or key, kind=spec.get("kind") or "none",
                   printed=printed, u_num_how=r.mesh.get(key, {}).get("how", "not run"),
                   area=area_to_uniform(r.declared_samples(key), d, half))
        rows.append(row)
    return rows


def _g(x: float) -> str:
    return f"{x:.4g}"


def _budget_table(rows: Sequence[dict[str, Any]]) -> str:
    out = ["| quantity | kind | S | D (printed) | E = S - D | u_num | u_input | u_D | u_val | "
           "abs(E) <= 2 u_val | model error E +- 2 u_val |",
           "|---|---|---|---|---|---|---|---|---|---|---|"]
    for b in rows:
        lo, hi = b["error_interval"]
        kind = "**calibration**" if b["kind"] == "calibration" else b["kind"]
        out.append(
            f"| {b['label']} | {kind} | {_g(b['S'])} | {_g(b['D'])} ({b['printed']}) | {_g(b['E'])} "
            f"({100 * b['E'] / abs(b['D']):+.1f} %) | {_g(b['u_num'])} | {_g(b['u_input'])} | "
            f"{_g(b['u_D'])} | {_g(b['u_val'])} | {'yes' if b['within'] else '**no**'} | "
            f"[{_g(lo)}, {_g(hi)}] |")
    out += ["", "| quantity | area metric (relative to abs(D)) | u_num from the mesh levels |",
            "|---|---|---|"]
    for b in rows:
        out.append(f"| {b['label']} | {_g(b['area'])} ({100 * b['area'] / abs(b['D']):.1f} %) | "
                   f"{b['u_num_how']} |")
    return "\n".join(out) + "\n"


def _convergence_table(r: UQResult) -> str:
    out = ["| output | N | runs | mean [95 % bootstrap] | std [95 % bootstrap] | largest total index | converged |",
           "|---|---|---|---|---|---|---|"]
    names = [i["key"] for i in r.study["inputs"]]
    for key in r.study["outputs"]:
        for s in r.steps:
            st = s.stats[key]
            top = int(np.argmax(st["ST"]))
            out.append(
                f"| {key} | {s.n} | {s.runs} | {_g(st['mean'])} [{_g(st['mean_ci'][0])}, "
                f"{_g(st['mean_ci'][1])}] | {_g(st['std'])} [{_g(st['std_ci'][0])}, "
                f"{_g(st['std_ci'][1])}] | {names[top]} {st['ST'][top]:.3f} +- "
                f"{st['ST_conf'][top]:.3f} | {'yes' if s.converged else '-'} |")
    return "\n".join(out) + "\n"


def dominant_inputs(r: UQResult, k: int = 2) -> dict[str, list[tuple[str, float]]]:
    """Per output, the ``k`` inputs with the largest total-order index."""
    names = [i["key"] for i in r.study["inputs"]]
    out = {}
    for key, st in r.final.stats.items():
        order = np.argsort(st["ST"])[::-1][:k]
        out[key] = [(names[i], st["ST"][i]) for i in order]
    return out


def _save(fig, axes, path: Path) -> str:
    """Legend on the first panel, tight layout, written as SVG and closed; its file name."""
    import matplotlib.pyplot as plt

    axes[0, 0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
    return path.name


def _indices_by_scene(r: UQResult, names: Sequence[str]):
    """A study of several scenes: per declared output and order (total, first), one panel with
    the scenes along x and a bar per input (95 % bootstrap intervals)."""
    import matplotlib.pyplot as plt

    outs = r.study["outputs"]
    keys = list(dict.fromkeys(o["key"] for o in outs.values()))
    labels = [sc["label"] for sc in r.study["scenes"]]
    fig, axes = plt.subplots(2 * len(keys), 1, figsize=(8, 2.6 * 2 * len(keys)), squeeze=False)
    x = np.arange(len(labels))
    width = 0.8 / len(names)
    for k, key in enumerate(keys):
        ids = [oid for oid, o in outs.items() if o["key"] == key]
        for row, (order, what) in enumerate((("ST", "total"), ("S1", "first"))):
            ax = axes[2 * k + row, 0]
            for j, name in enumerate(names):
                val = [r.final.stats[oid][order][j] for oid in ids]
                err = [r.final.stats[oid][f"{order}_conf"][j] for oid in ids]
                ax.bar(x - 0.4 + (j + 0.5) * width, val, width, yerr=err, label=name)
            ax.set_title(f"{key}: {what}-order index {order} per scene (N = {r.final.n})",
                         fontsize=9)
            ax.set_xticks(x, labels, fontsize=7)
            ax.set_ylabel("index (-)", fontsize=8)
    return fig, axes


def _figures(r: UQResult, rows: Sequence[dict[str, Any]], folder: Path, stem: str) -> list[str]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = [i["key"].split(".")[-1] for i in r.study["inputs"]]
    keys = list(r.study["outputs"])
    files = []
    if len(r.study["scenes"]) > 1:
        fig, axes = _indices_by_scene(r, names)
    else:
        fig, axes = plt.subplots(len(keys), 1, figsize=(7, 2.2 * len(keys)), squeeze=False)
        x = np.arange(len(names))
        for ax, key in zip(axes[:, 0], keys):
            st = r.final.stats[key]
            ax.bar(x - 0.2, st["S1"], 0.4, yerr=st["S1_conf"], label="first order S1")
            ax.bar(x + 0.2, st["ST"], 0.4, yerr=st["ST_conf"], label="total order ST")
            ax.set_title(f"{key} (N = {r.final.n})", fontsize=9)
            ax.set_xticks(x, names, fontsize=7, rotation=20)
            ax.set_ylabel("index (-)", fontsize=8)
    files.append(_save(fig, axes, folder / f"{stem}-indices.svg"))
    refs = {b["key"]: b for b in rows}
    fig, axes = plt.subplots(len(keys), 2, figsize=(8, 2.2 * len(keys)), squeeze=False)
    for (ax_c, ax_n), key in zip(axes, keys):
        s = np.sort(r.declared_samples(key))
        ax_c.step(s, np.arange(1, len(s) + 1) / len(s), where="post", label="simulated")
        if key in refs:
            ax_c.axvline(refs[key]["D"], color="k", ls="--", label="reference D")
            ax_c.axvline(refs[key]["S"], color="C1", ls=":", label="nominal S")
        ax_c.set_title(f"CDF of {key}", fontsize=9)
        ax_c.set_ylabel("CDF (-)", fontsize=8)
        n = [s_.n for s_ in r.steps]
        m = [s_.stats[key]["mean"] for s_ in r.steps]
        lo = [s_.stats[key]["mean_ci"][0] for s_ in r.steps]
        hi = [s_.stats[key]["mean_ci"][1] for s_ in r.steps]
        ax_n.errorbar(n, m, yerr=[np.subtract(m, lo), np.subtract(hi, m)], marker="o", capsize=3)
        ax_n.set_xscale("log", base=2)
        ax_n.set_title(f"mean of {key} vs N (95 % bootstrap)", fontsize=9)
        ax_n.set_xlabel("base sample size N", fontsize=8)
    files.append(_save(fig, axes, folder / f"{stem}-cdf-convergence.svg"))
    return files


WEAK_CORRELATION = 0.9
"""Below this correlation of the spread check's paired outputs the page says that the sampling
mesh does not model the declared mesh's spread point by point."""


def _surrogate_note(r: UQResult) -> str:
    lv = r.study["sampling"]["mesh"]
    m = r.study["scenes"][0]["mesh"]
    return (f" (sampled on the mesh level {lv}, {round(m['nx'] * lv)} x {round(m['ny'] * lv)}, "
            "a cheaper model of the spread; the samples carried onto the declared mesh by the "
            "affine map of the spread check below: u_input = std x ratio; the CDFs and area "
            "metrics are of the carried samples)")


def _spread_table(r: UQResult) -> str:
    """The spread check of a study sampled on a coarser mesh: the same points on both."""
    out = ["The first size's A and B points (the inputs' joint distribution) run on both meshes: "
           "the ratio of their standard deviations carries the converged spread onto the "
           "declared mesh, their means shift it.\n",
           "| output | points | mean, sampling mesh | mean, declared mesh | std, sampling mesh | "
           "std, declared mesh | ratio | correlation | u_input |",
           "|---|---|---|---|---|---|---|---|---|"]
    for oid, c in r.spread_check.items():
        out.append(f"| {oid} | {c['points']} | {_g(c['mean_sampled'])} | {_g(c['mean_declared'])} | "
                   f"{_g(c['std_sampled'])} | {_g(c['std_declared'])} | {c['ratio']:.3f} | "
                   f"{c['corr']:.4f} | {_g(r.u_input(oid))} |")
    weak = [oid for oid, c in r.spread_check.items() if not c["corr"] >= WEAK_CORRELATION]
    if weak:
        out.append(f"\nCorrelation below {WEAK_CORRELATION} ({', '.join(weak)}): the sampling "
                   "mesh does not follow the declared mesh point by point there; u_input keeps "
                   "the ratio of the spreads, but the indices and the CDF's shape are the "
                   "sampling mesh's.")
    return "\n".join(out) + "\n"


def _scenes_text(scenes: Sequence[dict[str, Any]]) -> str:
    """``scene `path``` or ``scenes `a`, `b`, ...`` (paths relative to the working folder)."""
    paths = [f"`{os.path.relpath(sc['path'])}`" for sc in scenes]
    return ("scene " if len(paths) == 1 else f"{len(paths)} scenes, the same design on each: ") \
        + ", ".join(paths)


def study_section(r: UQResult, study_path: str, folder: str | os.PathLike[str], stem: str) -> str:
    """The Markdown of one study (with its figures written into ``folder``), level-2 heading."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    rows = budget_rows(r, study_path)
    s = r.study
    conv = f"converged at N = {r.converged_at}" if r.converged_at else \
        f"**not converged** within N = {r.final.n} (the last row shows how far)"
    lines = [f"## {s['title']}\n",
             f"Declaration `{study_path}`; {_scenes_text(s['scenes'])}"
             + (f" with {json.dumps(s['set'])}" if s["set"] else "") + "; "
             f"{s['sampling']['method']} (Saltelli's design, seed {s['sampling']['seed']}), "
             f"{len(s['inputs'])} inputs, {r.final.runs} runs, {conv}; wall time "
             f"{r.wall_time_s:.0f} s.\n",
             "| input (scene key) | distribution (SI) | source |", "|---|---|---|"]
    for i in s["inputs"]:
        lines.append(f"| `{i['key']}` | {describe(i['kind'], i['distribution'])} | {i['source']} |")
    lines += ["", "### V&V 20 budget per comparison\n",
              "S: the declared scene (nominal inputs, declared mesh); D: the paper's printed value "
              "(computed, not measured: **calibration** = the plate was fitted to it, so agreement "
              "is the fit); u_num: the GCI on the declared mesh from the mesh levels "
              f"{s['mesh_levels']} by the project's rule, halved (the GCI as a 95 % expanded "
              "uncertainty); u_input: the standard deviation of the propagated inputs"
              + (_surrogate_note(r) if r.spread_check else "") + "; u_D: "
              "half a unit of the printed last digit as a uniform distribution (/sqrt 3); "
              "u_val = sqrt(u_num^2 + u_input^2 + u_D^2). Area metric: between the simulated "
              "CDF and D spread uniformly over its last digit. SI units (N s, N, m, s, m/s, Pa).\n",
              _budget_table(rows)]
    if r.spread_check:
        lines += ["### The spread on the sampling mesh and on the declared mesh\n",
                  _spread_table(r)]
    lines += ["### Convergence of the estimates\n"
              + (f"\nOn the sampling mesh (level {s['sampling']['mesh']}).\n"
                 if r.spread_check else ""),
              _convergence_table(r), "### Dominant inputs (total-order index)\n"]
    for key, top in dominant_inputs(r).items():
        lines.append(f"- `{key}`: " + ", ".join(f"`{n}` {v:.2f}" for n, v in top))
    lines.append("")
    for f in _figures(r, rows, folder, stem):
        lines.append(f"![{f}]({f})\n")
    return "\n".join(lines)
