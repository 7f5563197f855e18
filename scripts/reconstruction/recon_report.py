"""Tables, plots, provenance, report.md and the paper scenes from reconstruct.py's search.json.

`write_report(result, out)` writes into `out` (reference-data/paper/reconstruction/):
  table1.csv, table2.csv, contact-law.csv, family.csv, mesh-sensitivity.csv,
  evaluations.csv, best.json, *.svg, PROVENANCE.md, report.md
`write_scenes(result)` writes verification/scenes/paper-*.yaml and paper-table2/.
"""
from __future__ import annotations

import csv
import json
import math
from functools import partial
from pathlib import Path

import recon_core as rc

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
SCENES = ROOT / "verification" / "scenes"

ROWS = ("elastic", "plastic")
ROW_LABEL = {"elastic": "Elastic", "plastic": "Elasto-plastic"}


# ------------------------------------------------------------------------------- formatting
def pct(x: float | None, d: int = 1) -> str:
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "-"
    return f"{100 * x:+.{d}f} %"


def num(x: float | None, d: int = 3) -> str:
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "-"
    return f"{x:.{d}g}" if abs(x) >= 1e5 or (abs(x) < 1e-3 and x != 0) else f"{x:.{d}f}"


def sig(x: float, n: int = 4) -> str:
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "-"
    if x == 0:
        return "0"
    d = max(0, n - 1 - int(math.floor(math.log10(abs(x)))))
    return f"{x:.{d}f}"


def md_table(head: list[str], rows: list[list[str]]) -> str:
    out = ["| " + " | ".join(head) + " |", "|" + "|".join("---" for _ in head) + "|"]
    out += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    return "\n".join(out)


def target_of(q: str) -> str:
    return "5 %" if q in rc.ROBUST else "10 %"


def group_of(q: str, row: str) -> str:
    if q in rc.ROBUST:
        return "robust"
    if q == "contact_duration" and row == "plastic":
        return "intermediate"
    return "fragile"


# ------------------------------------------------------------------------------- svg plots
def read_history(path: Path) -> dict:
    with open(path) as f:
        rd = csv.reader(f)
        head = next(rd)
        cols = [[] for _ in head]
        for row in rd:
            for i, v in enumerate(row):
                cols[i].append(float(v) if v not in ("", "nan") else math.nan)
    return dict(zip(head, cols))


# ------------------------------------------------------------------------------- data files
def t1_rows(res: dict) -> list[dict]:
    rows = []
    for q in rc.T1_KEYS:
        for row in ROWS:
            e = res["t1"].get(f"{q}:{row}")
            if e is None:
                continue
            rows.append({"quantity": q, "row": row, "group": group_of(q, row),
                         "unit": rc.PAPER_UNITS[q], "paper": e["paper"], "ours": e["ours"],
                         "rel": e["rel"], "target": 0.05 if q in rc.ROBUST else 0.10})
    return rows


def write_csv(path: Path, head: list[str], rows: list[list]) -> None:
    with open(path, "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(head)
        for r in rows:
            w.writerow([f"{v:.6g}" if isinstance(v, float) else v for v in r])


def write_data(result: dict, out: Path) -> None:
    c = result["confirm"]
    # Table 1 side by side
    write_csv(out / "table1.csv",
              ["quantity", "row", "group", "unit", "paper", "ours", "residual_rel", "target_rel",
               "within_target"],
              [[r["quantity"], r["row"], r["group"], r["unit"], r["paper"], r["ours"], r["rel"],
                r["target"], "yes" if abs(r["rel"]) <= r["target"] else "no"]
               for r in t1_rows(c["res"])])
    # Table 2 side by side, with the identity of every run
    runs = {(q["table"], q["row"], q["v0"]): q for q in c["runs"]}
    rows = []
    for v0 in rc.T2_V0:
        for row in ROWS:
            e = c["res"]["t2"].get(f"{row}:{v0:g}")
            q = runs[("t2", row, v0)]
            if e is None:
                rows.append([v0, row, "", "", "", "", "", q.get("error", "")])
                continue
            pf_paper = rc.T2_MASS * v0 - e["paper"]
            rows.append([v0, row, e["paper"], e["ours"], e["rel"], pf_paper,
                         rc.T2_MASS * q["final_impactor_velocity_mps"],
                         q["impulse_momentum_error"]])
    write_csv(out / "table2.csv",
              ["v0_mps", "row", "paper_impulse_Ns", "ours_impulse_Ns", "residual_rel",
               "paper_final_momentum_kgmps", "ours_final_momentum_kgmps",
               "impulse_momentum_error"], rows)
    # contact-law comparison on the chosen set
    rows = []
    for L in result["laws"]:
        for row in ROWS:
            v = L[row]
            if "error" in v:
                rows.append([L["law"], L["pairing"], row] + [""] * 8 + [v["error"][:200]])
                continue
            rows.append([L["law"], L["pairing"], row] + [v[q] for q in rc.T1_KEYS]
                        + [v["n_intervals"], v["max_energy_balance_error"], ""])
    write_csv(out / "contact-law.csv",
              ["law", "pairing", "row"] + list(rc.T1_KEYS)
              + ["n_contact_intervals", "max_energy_balance_error", "error"], rows)
    # family and contrasts
    fam = result["family"]
    keys = sorted({k for f in fam["family"] for k in f["rel"]})
    rows = [["family", f["L"], f["W"], f["h"], f["J"]] + [f["rel"].get(k, "") for k in keys]
            for f in fam["family"]]
    rows += [[f"contrast: {f['name']}", f["L"], f["W"], f["h"], f["J"]]
             + [f["rel"].get(k, "") for k in keys] for f in fam["contrasts"]]
    rows += [[f"refit at L = {f['L']:g}", f["L"], f["W"], f["h"], f["J"]]
             + [f["rel"].get(k, "") for k in keys] for f in result["refit"]]
    write_csv(out / "family.csv", ["what", "L_m", "W_m", "h_m", "J"] + keys, rows)
    # mesh sensitivity
    rows = []
    for m in result["mesh_check"]:
        meshes = list(m["by_mesh"])
        ref = m["by_mesh"][meshes[0]]
        for mesh in meshes:
            v = m["by_mesh"][mesh]
            for k in sorted(k for k in v if k not in ("ok", "errors")):
                if k in ref and isinstance(ref.get(k), float):
                    rows.append([m["law"], m["pairing"], mesh, k, v[k], ref[k],
                                 rc.rel(v[k], ref[k]) if ref[k] else ""])
            if not v["ok"]:
                rows.append([m["law"], m["pairing"], mesh, "error", "", "", v["errors"][0][:200]])
    write_csv(out / "mesh-sensitivity.csv",
              ["law", "pairing", "mesh", "quantity", "value", "value_on_" + list(
                  result["mesh_check"][0]["by_mesh"])[0], "rel_to_default_mesh"], rows)
    # every evaluation of the search
    rows = []
    for e in result["evaluations"]:
        x = e["x"]
        acc = e["acceptance"]
        rows.append([e["stage"], e["law"], e["pairing"], "x".join(map(str, e["mesh"])),
                     "+".join(e["rows"]), e["plate"]["L"], e["plate"]["W"], e["plate"]["h"],
                     x["sy"], x["Et"], x["r"], e["J"], acc.get("robust_worst", ""),
                     acc.get("all_worst", ""), acc.get("t2_worst", ""),
                     e["max_energy_balance_error"], e["max_impulse_momentum_error"],
                     "" if e["res"]["ok"] else e["res"]["errors"][0][:160]])
    write_csv(out / "evaluations.csv",
              ["stage", "law", "pairing", "mesh", "rows", "L_m", "W_m", "h_m", "yield_Pa",
               "Et_Pa", "r_m", "J", "robust_worst_rel", "t1_worst_rel", "t2_worst_rel",
               "max_energy_balance_error", "max_impulse_momentum_error", "error"], rows)
    # the chosen set
    p = result["best"]["params"]
    best = {"law": result["best"]["law"], "pairing": result["best"]["pairing"],
            "contact_law_block": rc.law_block(p),
            "plate": {"length_m": p["L"], "width_m": p["W"], "thickness_m": p["h"]},
            "material": {"density": p["rho"], "youngs_modulus": p["E"], "poisson_ratio": p["nu"],
                         "yield_stress": p["sy"], "hardening_linear_Et": p["Et"]},
            "impactor": {"nose_radius_m": p["r"], "youngs_modulus": p["Es"],
                         "poisson_ratio": p["nus"]},
            "J_default_mesh": c["J"], "acceptance_default_mesh": c["acceptance"]}
    (out / "best.json").write_text(json.dumps(best, indent=1) + "\n")


# ------------------------------------------------------------------------------- plots
def _plt():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    plt.rcParams.update({"svg.hashsalt": "dokko-kim-2004", "font.size": 10,
                         "figure.figsize": (6.4, 4.0), "axes.grid": True, "grid.alpha": 0.3})
    return plt


def _save(fig, path: Path, png_dir: Path | None = None) -> None:
    fig.tight_layout()
    fig.savefig(path, format="svg", metadata={"Date": None})
    if png_dir is not None:
        fig.savefig(png_dir / (path.stem + ".png"), dpi=80)
    import matplotlib.pyplot as plt
    plt.close(fig)


def plot_table2(result: dict, out: Path, png_dir=None) -> None:
    plt = _plt()
    c = result["confirm"]["res"]["t2"]
    v = list(rc.T2_V0)
    fig, ax = plt.subplots()
    colors = {"elastic": "tab:blue", "plastic": "tab:red"}
    for row in ROWS:
        paper = [c[f"{row}:{x:g}"]["paper"] for x in v]
        ours = [c[f"{row}:{x:g}"]["ours"] if f"{row}:{x:g}" in c else math.nan for x in v]
        ax.plot(v, ours, "-o", color=colors[row], ms=4, label=f"{ROW_LABEL[row]}: ours")
        ax.plot(v, paper, "s", color=colors[row], mfc="none", ms=8,
                label=f"{ROW_LABEL[row]}: paper (Table 2)")
    ax.set_xlabel("initial velocity v0 (m/s)")
    ax.set_ylabel("impulse (N s)")
    ax.set_title("Table 2, m = 10 kg: impulse vs initial velocity (80 x 16 mesh)")
    ax.legend()
    _save(fig, out / "table2.svg", png_dir)


def plot_family(result: dict, out: Path, png_dir=None) -> None:
    plt = _plt()
    fam = result["family"]["family"]
    ok = [f for f in fam if f["J"] < 1e5]
    bad = [f for f in fam if f["J"] >= 1e5]
    fig, ax = plt.subplots()
    ax.plot([f["L"] * 1e3 for f in ok], [f["J"] for f in ok], "-o", color="tab:blue",
            label="chosen set moved along h ~ L^2, W L^3 fixed")
    top = max((f["J"] for f in ok), default=10) * 1.1
    if bad:
        ax.plot([f["L"] * 1e3 for f in bad], [top * 0.97] * len(bad), "x", color="tab:red", ms=9,
                label="run fails (contact law maximum)")
    for f in result.get("refit", []):
        ax.plot([f["L"] * 1e3], [f["J"]], "s", color="tab:green", ms=8,
                label=f"re-fitted at L = {f['L'] * 1e3:.0f} mm")
    ax.axvline(result["best"]["params"]["L"] * 1e3, color="0.5", ls=":", lw=1)
    ax.set_ylim(0, top)
    ax.set_xlabel("plate length L (mm)")
    ax.set_ylabel("objective J (40 x 8 mesh)")
    ax.set_title("The beam family: objective along (L s, W / s^3, h s^2)")
    ax.legend()
    _save(fig, out / "family.svg", png_dir)


def plot_histories(work: Path, out: Path, png_dir=None) -> list[str]:
    hs = {}
    for row in ROWS:
        f = work / f"t1-{row}" / "history.csv"
        if f.exists():
            hs[row] = read_history(f)
    if len(hs) < 2:
        return []
    plt = _plt()
    fig, axs = plt.subplots(3, 1, figsize=(6.4, 7.5), sharex=True)
    colors = {"elastic": "tab:blue", "plastic": "tab:red"}
    for (col, scale, ylabel), ax in zip((("contact_force_N", 1e-3, "contact force (kN)"),
                                         ("mid_uy_m", 1e3, "mid-plane u_y at mid-span (mm)"),
                                         ("A_von_mises_Pa", 1e-6, "von Mises at A (MPa)")), axs):
        for row, h in hs.items():
            ax.plot([t * 1e3 for t in h["time_s"]], [y * scale for y in h[col]],
                    color=colors[row], lw=1.0, label=ROW_LABEL[row])
        ax.set_ylabel(ylabel)
    axs[-1].text(0.99, 0.95, "history sampled every 10 us; peaks in the tables use every step",
                 transform=axs[-1].transAxes, ha="right", va="top", fontsize=8)
    axs[0].set_title("Table 1 impact (18 kg, 10 m/s), chosen set, 80 x 16")
    axs[0].legend()
    axs[-1].set_xlabel("time (ms)")
    _save(fig, out / "table1-histories.svg", png_dir)
    return ["table1-histories.svg"]


def plot_elastic_grid(result: dict, out: Path, png_dir=None) -> None:
    key = result["best"]["key"]
    g = result["elastic_grid"].get(key)
    if not g:
        return
    import numpy as np
    plt = _plt()
    H, S = np.array(g["h"]) * 1e3, np.array(g["S"]) * 1e6
    J = np.array([[v if v is not None and v < 1e5 else np.nan for v in row] for row in g["J"]])
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    im = ax.imshow(np.log10(J), origin="lower", cmap="viridis_r", aspect="auto")
    for i in range(len(H)):
        for j in range(len(S)):
            t = "fails" if np.isnan(J[i, j]) else (f"{J[i, j]:.1f}" if J[i, j] < 100 else f"{J[i, j]:.0f}")
            ax.text(j, i, t, ha="center", va="center", fontsize=8,
                    color="w" if not np.isnan(J[i, j]) and J[i, j] > 40 else "k")
    ax.set_xticks(range(len(S)), [f"{x:.2f}" for x in S])
    ax.set_yticks(range(len(H)), [f"{x:.1f}" for x in H])
    ax.set_xlabel("S = W_eq h_eq^3 (1e-6 m^4)")
    ax.set_ylabel("h_eq (mm)")
    ax.grid(False)
    ax.set_title(f"Elastic rows only: J_elastic ({key}, r = {result['budget']['grid_r'] * 1e3:g} mm, 40 x 8)")
    fig.colorbar(im, label="log10 J_elastic")
    _save(fig, out / "elastic-grid.svg", png_dir)


# ------------------------------------------------------------------------------- scenes
def scene_header(result: dict, what: str, tolerances: list[str]) -> str:
    b = result["best"]
    p = b["params"]
    lines = [
        f"# {what}",
        "# Dokko & Kim (2004) on the RECONSTRUCTED plate: the paper's Fig. 1 (plate, material, nose",
        "# radius) is lost; these values were fitted to Tables 1-2 by scripts/reconstruction/reconstruct.py. See",
        "# reference-data/paper/reconstruction/report.md for how, the residuals and the non-uniqueness.",
        f"# Chosen set: L = {p['L'] * 1e3:.1f} mm, W = {p['W'] * 1e3:.1f} mm, h = {p['h'] * 1e3:.2f} mm, "
        f"yield {p['sy'] / 1e6:.1f} MPa, E_t = {p['Et'] / 1e9:.3f} GPa,",
        f"# r = {p['r'] * 1e3:.2f} mm, contact law: {rc.LAW_TEXT[b['law']]};",
        f"# pairing: {rc.PAIRING_TEXT[b['pairing']]}.",
        f"# Fixed: steel E = {p['E'] / 1e9:g} GPa, nu = {p['nu']}, rho = {p['rho']:g}; impactor E = "
        f"{p['Es'] / 1e9:g} GPa, nu = {p['nus']}.",
        f"# Solver commit at reconstruction: {result['solver_commit'][:12]}; search of {result['date']}.",
        "# Comparisons against the paper are code-to-literature (its numbers are computed, not measured).",
    ]
    if tolerances:
        lines.append("# Tolerances the reconstruction supports (see report.md, 'Tolerances'):")
        lines += [f"#   {t}" for t in tolerances]
    return "\n".join(lines) + "\n"


def dump_scene(s: dict) -> str:
    import yaml
    return yaml.safe_dump(s, sort_keys=False, default_flow_style=None, width=100)


def write_scenes(result: dict) -> list[Path]:
    p = result["best"]["params"]
    tol = result.get("supported_tolerances", {})
    written = []
    SCENES.mkdir(parents=True, exist_ok=True)
    (SCENES / "paper-table2").mkdir(exist_ok=True)
    for row in ROWS:
        s = rc.scene(p, mass=rc.T1_MASS, v0=rc.T1_V0, plastic=row == "plastic",
                     mesh=(80, 16), probes=rc.point_a(p), every=1.0e-6)
        s["title"] = f"Dokko & Kim (2004) Table 1, {ROW_LABEL[row].lower()} (reconstructed plate)"
        s = {"title": s.pop("title"), **s}
        s["time"] = {"end": 3.0e-3, "dt": {"cfl": 0.8}}
        tl = [f"{rc.T1_LABEL[q]}: {tol[f'{q}:{row}']}" for q in rc.T1_KEYS if f"{q}:{row}" in tol]
        text = scene_header(result, f"Table 1, {ROW_LABEL[row].lower()} row: m = 18.0 kg, "
                            "v0 = 10.0 m/s (derived, reference-data/paper/impactor-table1.md); "
                            "point A = mid-span, bottom surface.", tl) + dump_scene(s)
        f = SCENES / f"paper-{row}.yaml"
        f.write_text(text)
        written.append(f)
    pulse = result["pulse"]
    for row in ROWS:
        s = rc.pulse_scene(p, plastic=row == "plastic", mesh=(80, 16), force=86.5e3,
                           duration=pulse["duration_s"], end=pulse["end_s"], every=1.0e-6)
        s = {"title": f"Dokko & Kim (2004) verification pulse, 86.5 kN, {ROW_LABEL[row].lower()} "
                      "(reconstructed plate)", **s}
        text = scene_header(result, (
            f"The paper's verification case: a rectangular pulse of 86.5 kN (whole width) on the "
            f"top mid-span node, {ROW_LABEL[row].lower()}.\n# Duration (not in the paper): "
            f"{pulse['duration_s'] * 1e3:.3f} ms = the elasto-plastic contact duration of Table 1, "
            "the longest time scale the paper gives;\n# it covers several fundamental periods "
            "of the reconstructed plate, so the run shows the dynamic overshoot and the\n# "
            "oscillation about the quasi-static response, then the free vibration after the "
            f"pulse (end {pulse['end_s'] * 1e3:g} ms).\n# Point A (probe A) = mid-span, bottom "
            "surface: the 'center point' of Figs. 5-6, regular (not under the load, not at a "
            "clamped corner).\n# No reference values: Figs. 5-6 (the ANSYS comparison) are lost; "
            "compare with the independent code."), []) + dump_scene(s)
        f = SCENES / f"paper-pulse-{row}.yaml"
        f.write_text(text)
        written.append(f)
    for v0 in rc.T2_V0:
        for row in ROWS:
            s = rc.scene(p, mass=rc.T2_MASS, v0=v0, plastic=row == "plastic", mesh=(80, 16),
                         every=1.0e-5, after_contact=0.5e-3, limit=0.01)
            s = {"title": f"Dokko & Kim (2004) Table 2, v0 = {v0:g} m/s, {ROW_LABEL[row].lower()} "
                          "(reconstructed plate)", **s}
            paper = rc.read_paper()[1]
            ref = {r["v0"]: r for r in paper}[v0][row]
            tl = [f"impulse: paper {ref} N s; {tol.get('t2', '')}",
                  "impulse = m (v0 - v_final): an identity of the method, to round-off "
                  "(impulse_momentum_error < 1e-12)"]
            text = scene_header(result, f"Table 2 (m = 10 kg), v0 = {v0:g} m/s, "
                                f"{ROW_LABEL[row].lower()}.", tl) + dump_scene(s)
            f = SCENES / "paper-table2" / f"v{v0:05.2f}-{row}.yaml"
            f.write_text(text)
            written.append(f)
    return written


# ------------------------------------------------------------------------------- report
def mark(rel: float, tol: float) -> str:
    return "yes" if abs(rel) <= tol else "**no**"


def supported_tolerances(result: dict) -> dict:
    """What the reconstruction supports, per quantity: the residual of the chosen set on the
    default mesh, widened by the spread over comparably good sets (the re-fits at another
    plate length whose default-mesh J is within 1.5x of the chosen one) and by the change
    80x16 -> 160x32, rounded up
    (1 % steps below 10 %, 5 % steps above) and never below the issue's target (a tighter
    band would claim more than a reconstruction with these non-uniquenesses can)."""
    c = result["confirm"]["res"]
    alts = [r["res"] for r in result.get("refit_confirm", []) if r["res"]["ok"]
            and r["J"] <= 1.5 * result["confirm"]["J"]]
    ms = {tuple(m["mesh"]): m for m in result.get("mesh_study", []) if m["ok"]}
    fine, finer = ms.get((80, 16)), ms.get((160, 32))
    out = {}
    for k, e in c["t1"].items():
        q = k.split(":")[0]
        target = 0.05 if q in rc.ROBUST else 0.10
        worst = abs(e["rel"])
        spread = 0.0
        for a in alts:
            if k in a["t1"]:
                spread = max(spread, abs(a["t1"][k]["rel"] - e["rel"]))
        dm = 0.0
        if fine and finer and k in fine["t1"] and k in finer["t1"]:
            dm = abs(finer["t1"][k] - fine["t1"][k]) / abs(e["paper"])
        need = worst + spread + dm
        step = 0.01 if need < 0.095 else 0.05
        tol = max(math.ceil(need / step - 1e-9) * step, target)
        out[k] = (f"{tol * 100:.0f} % relative (residual {pct(e['rel'])}; + spread over comparably "
                  f"good sets {pct(spread).lstrip('+')}; + mesh 80x16->160x32 "
                  f"{pct(dm).lstrip('+')}; target {target * 100:.0f} %)")
        out[f"{k}:value"] = tol
        out[f"{k}:parts"] = {"residual": e["rel"], "spread": spread, "mesh": dm, "need": need}
    worst_t2 = max(abs(e["rel"]) for e in c["t2"].values())
    for a in alts:
        worst_t2 = max(worst_t2, max(abs(e["rel"]) for e in a["t2"].values()))
    t2tol = max(math.ceil(worst_t2 / 0.005 - 1e-9) * 0.005, 0.03)
    out["t2"] = (f"supported tolerance {t2tol * 100:.1f} % relative (worst residual of the sweep, "
                 f"chosen and comparably good sets: {pct(worst_t2).lstrip('+')}; target 3 %)")
    out["t2:value"] = t2tol
    out["t2:worst"] = worst_t2
    return out


def write_report(result: dict, out: Path) -> None:
    out.mkdir(parents=True, exist_ok=True)
    result["supported_tolerances"] = supported_tolerances(result)
    write_data(result, out)
    workdir = ROOT / result.get("work", "out/" + ("reconstruct-quick" if result["quick"] else "reconstruct"))
    png = workdir / "png"
    png.mkdir(parents=True, exist_ok=True)
    plot_table2(result, out, png)
    plot_family(result, out, png)
    plot_elastic_grid(result, out, png)
    work = workdir / "confirm"
    for old in out.glob("table1-*.svg"):
        old.unlink()
    hist_plots = plot_histories(work, out, png)
    (out / "report.md").write_text(report_text(result, hist_plots))
    result["report_writer_sha256"] = rc.sha256_file(Path(__file__))
    (out / "PROVENANCE.md").write_text(provenance_text(result, out))


def provenance_text(result: dict, out: Path) -> str:
    files = sorted(p.name for p in out.iterdir() if p.is_file() and p.name != "PROVENANCE.md")
    sha = {f: rc.sha256_file(out / f) for f in files}
    L = ["# Provenance of `reference-data/paper/reconstruction/`", "",
         "Everything here is written by `scripts/reconstruction/reconstruct.py` (with `scripts/reconstruction/recon_core.py` "
         "and `scripts/reconstruction/recon_report.py`) from runs of `impact simulate`. Nothing was edited by "
         "hand.", "",
         "| item | value |", "|---|---|",
         f"| command | `{result['command']}` (run from the repository root with `.venv/bin/python`) |",
         f"| date (UTC) | {result['date']} |",
         f"| git HEAD at run time | `{result['solver_commit']}` |",
         f"| solver/ modified in the working tree at run time | {result['solver_dirty']} |",
         f"| solver binary | `{result.get('solver_binary', {}).get('path', '?')}`, built from "
         f"{result.get('solver_binary', {}).get('built_from', '?')} |",
         f"| solver binary sha256 | `{result['solver_binary_sha256']}` |"]
    built = str(result.get("solver_binary", {}).get("built_from", "")).split(" ")[0]
    if len(built) == 40:
        import subprocess
        try:
            log = subprocess.run(["git", "log", "--format=%h %s", f"{built}..HEAD", "--",
                                  "solver"], cwd=ROOT, capture_output=True, text=True,
                                 check=True).stdout.strip().splitlines()
        except (OSError, subprocess.CalledProcessError):
            log = ["(git unavailable)"]
        L.append("| solver/ commits between the binary's commit and HEAD (when this page was "
                 "written) | " + ("none" if not log else "; ".join(x[:110] for x in log)) + " |")
    for f, h in result["script_sha256"].items():
        L.append(f"| scripts/{f} sha256 (at the search) | `{h}` |")
    L.append(f"| scripts/reconstruction/recon_report.py sha256 (wrote this page) | "
             f"`{result.get('report_writer_sha256', '?')}` |")
    L += [f"| runs executed / from cache | {result['runs']['executed']} / "
          f"{result['runs']['cache_hits']} |",
          f"| wall time of the invocation | {result['timing_s']['total']:.0f} s on 2 parallel "
          "runs (machine shared with other jobs) |", "",
          "The binary is copied into the work folder (`out/reconstruct/impact`) before the search, "
          "so a concurrent rebuild cannot change it mid-run; every run is cached in "
          "`out/reconstruct/runs.json` under the sha256 of the binary and the scene text, so an "
          "interrupted search resumes and a re-run with the same binary repeats no simulation.", "",
          "## Files", "", "| file | sha256 |", "|---|---|"]
    L += [f"| `{f}` | `{sha[f]}` |" for f in files]
    L += ["", "Library versions: those pinned in `scripts/requirements.txt` (numpy, scipy, pyyaml; "
          "matplotlib is not used: the SVGs are written directly).", ""]
    return "\n".join(L)


def t1_val(res: dict, q: str, row: str):
    e = res["t1"].get(f"{q}:{row}")
    return e


def fmt_q(q: str, v: float) -> str:
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return "-"
    if q == "max_plate_displacement":
        return f"{v:.3f}"
    if q == "contact_duration":
        return f"{v:.3f}"
    if q == "impactor_final_velocity":
        return f"{v:.2f}"
    if q == "impulse":
        return f"{v:.1f}"
    return f"{v:.0f}" if abs(v) >= 100 else f"{v:.1f}"


def residual_block(res: dict, with_t2: bool = True) -> list[str]:
    """Compact Table 1 (+ Table 2) residual table of one set."""
    head = ["quantity", "paper E", "ours E", "res. E", "paper EP", "ours EP", "res. EP"]
    rows = []
    for q in rc.T1_KEYS:
        e, p = t1_val(res, q, "elastic"), t1_val(res, q, "plastic")
        rows.append([rc.T1_LABEL[q],
                     fmt_q(q, e["paper"]) if e else "-", fmt_q(q, e["ours"]) if e else "-",
                     pct(e["rel"]) if e else "-",
                     fmt_q(q, p["paper"]) if p else "-", fmt_q(q, p["ours"]) if p else "-",
                     pct(p["rel"]) if p else "-"])
    L = [md_table(head, rows)]
    if with_t2 and res["t2"]:
        el = [pct(res["t2"][f"elastic:{v:g}"]["rel"]) if f"elastic:{v:g}" in res["t2"] else "-"
              for v in rc.T2_V0]
        pl = [pct(res["t2"][f"plastic:{v:g}"]["rel"]) if f"plastic:{v:g}" in res["t2"] else "-"
              for v in rc.T2_V0]
        L += ["", md_table(["Table 2 impulse residual"] + [f"{v:g} m/s" for v in rc.T2_V0],
                           [["elastic"] + el, ["elasto-plastic"] + pl])]
    return L


def short_err(e: str) -> str:
    """'t2 plastic v0=12.5: error: run stopped at step 96 (t = ...): element 1279 (...) has
    inverted: ...' -> 't2 plastic v0=12.5: element 1279 inverted at t = 1.2e-05 s'."""
    import re
    where = e.split(":")[0]
    t = re.search(r"t = ([0-9.e+-]+) s", e)
    tt = f" at t = {float(t.group(1)):.2g} s" if t else ""
    if "inverted" in e:
        el = re.search(r"element (\d+)", e)
        return f"{where}: element {el.group(1) if el else '?'} (under the top node) inverted{tt}"
    if "no root" in e:
        return f"{where}: contact law maximum exceeded{tt}"
    return e[:120]


def params_row(p: dict) -> list[str]:
    return [f"{p['L'] * 1e3:.1f}", f"{p['W'] * 1e3:.1f}", f"{p['h'] * 1e3:.2f}",
            f"{p['sy'] / 1e6:.0f}", f"{p['Et'] / 1e9:.2f}", f"{p['r'] * 1e3:.2f}"]


def acc_text(a: dict) -> str:
    if not a.get("ok", True) or "t2_worst" not in a:
        return "run failed"
    return (f"Table 2 worst {pct(a['t2_worst'])} ({'pass' if a['t2_pass'] else 'FAIL'}); robust "
            f"Table 1 worst {pct(a['robust_worst'])} ({'pass' if a['robust_pass'] else 'FAIL'}); "
            f"all Table 1 worst {pct(a['all_worst'])} ({'pass' if a['all_pass'] else 'FAIL'})")


# Section 7's columns: the Table 1 residuals shown for the members of the beam family.
FAMILY_KEYS = ["impulse:elastic", "impactor_final_velocity:elastic", "max_plate_displacement:elastic",
            "impulse:plastic", "impactor_final_velocity:plastic", "max_plate_displacement:plastic",
            "max_effective_stress_point_a:plastic"]
FAMILY_SHORT = {"impulse:elastic": "I E", "impactor_final_velocity:elastic": "v_f E",
         "max_plate_displacement:elastic": "disp E", "impulse:plastic": "I EP",
         "impactor_final_velocity:plastic": "v_f EP", "max_plate_displacement:plastic": "disp EP",
         "max_effective_stress_point_a:plastic": "stress A EP"}


class Page(list):
    """The lines of a Markdown page; `page(line)` appends one."""

    def __call__(self, line: str) -> None:
        self.append(line)


def _title(A: Page, result: dict) -> None:
    """The title, the page's provenance line and the quick-mode warning."""
    A("# Reproducing Dokko & Kim (2004)")
    A("")
    A("*A page of the V&V report. Written by `scripts/reconstruction/reconstruct.py`; all numbers below come "
      "from `search.json` beside this file. The paper's tables are computed results of the "
      "authors' program: matching them is a code-to-literature comparison, not a validation "
      "against experiment.*")
    if result["quick"]:
        A("")
        A("> **QUICK MODE** (smoke test, tiny budget): the numbers below are not the reconstruction.")


def _summary(A: Page, result: dict) -> None:
    """The summary: the chosen set, the targets met, the identity, the search's size."""
    b = result["best"]
    c = result["confirm"]
    p = b["params"]
    res = c["res"]
    acc = c["acceptance"]
    fails = [k for k, e in res["t1"].items() if abs(e["rel"]) > (0.05 if k.split(":")[0] in rc.ROBUST else 0.10)]
    A(f"- **Chosen set** (one parameter set for both Table 1 rows and all 14 Table 2 runs): "
      f"plate L = {p['L'] * 1e3:.0f} mm, W = {p['W'] * 1e3:.0f} mm, h = {p['h'] * 1e3:.2f} mm; "
      f"steel E = {p['E'] / 1e9:g} GPa, nu = {p['nu']}, rho = {p['rho']:g} kg/m3, yield "
      f"{p['sy'] / 1e6:.0f} MPa, linear hardening E_t = {p['Et'] / 1e9:.2f} GPa; nose radius "
      f"r = {p['r'] * 1e3:.2f} mm; contact law **{b['law']}** ({rc.LAW_TEXT[b['law']]}); "
      f"pairing **{b['pairing']}** ({rc.PAIRING_TEXT[b['pairing']]}).")
    A(f"- **Against the targets of issue 5** (default mesh 80 x 16 q4-sri, half model): "
      f"{acc_text(acc)}.")
    n_in = sum(1 for k, e in res["t1"].items() if abs(e["rel"]) <= 0.10)
    A(f"- **{n_in} of the 12 Table 1 values** are within 10 %, all 6 robust ones within 5 %."
      if acc.get("robust_pass") else f"- **{n_in} of the 12 Table 1 values** are within 10 %.")
    if fails:
        A("- **Out of the 10 % band**: " + ", ".join(
            f"{rc.T1_LABEL[k.split(':')[0]]} {ROW_LABEL[k.split(':')[1]].lower()} "
            f"({pct(res['t1'][k]['rel'])})" for k in fails)
          + ". Section 10 gives the evidence of why, and the best achievable.")
    A(f"- **Impulse-momentum identity** `impulse = m (v0 - v_final)`: largest relative error "
      f"{c['max_impulse_momentum_error']:.1e} over the 16 confirmation runs, and "
      f"{max(e['max_impulse_momentum_error'] for e in result['evaluations'] if not math.isnan(e['max_impulse_momentum_error'])):.1e} "
      f"over every run of the search: round-off. Energy balance of the chosen reading: "
      f"largest error {c['max_energy_balance_error']:.1e}.")
    A(f"- **Search**: {len(result['evaluations'])} parameter-set evaluations, "
      f"{result['runs']['executed']} simulations run ({result['runs']['cache_hits']} from the "
      f"cache), {result['timing_s']['total'] / 60:.1f} min wall time on 2 parallel runs.")


def _unknowns(A: Page, result: dict) -> None:
    """Section 1: what the lost figures leave unknown."""
    A("Fig. 1 of the paper (plate and impactor data) is lost, with Fig. 4 (mesh, point A) and the "
      "history plots. Known: plane strain, half model, two clamped edges, rigid line-nose "
      "impactor, the contact law (4) and the algorithm; Table 1's impactor follows from the "
      "table (m = 18.0 kg, v0 = 10.0 m/s, `reference-data/paper/impactor-table1.md`), Table 2's "
      "is printed (10 kg, 1.25-15 m/s). Unknown and searched: plate length L, width W, "
      "thickness h, yield stress, hardening, nose radius r, the reading of eq. (4) (its hidden "
      "length: metres or millimetres, or a consistent Johnson line-contact law), and the "
      "force/indentation pairing (the energy-consistent default, force on the mid-plane node "
      "the indentation is read from, or the paper read literally: indentation from the "
      "mid-plane, force on the top-surface node). Fixed: steel plate and impactor, "
      f"E = {result['fixed']['E'] / 1e9:g} GPa, nu = {result['fixed']['nu']}, "
      f"rho = {result['fixed']['rho']:g} kg/m3 (E enters the beam response only through "
      "E W h^3, which the search covers through W and h).")


def _search_method(A: Page, result: dict) -> None:
    """Section 2: the coordinates, the objective and the coarse mesh's check."""
    bud = result["budget"]
    A("**Coordinates.** Beam theory makes the response depend on the plate through "
      "E' W h^3 / L^3 (stiffness), rho W h L (mass) and sigma_y W h^2 / L (fully plastic load), "
      "so (L, W, h) -> (L s, W / s^3, h s^2) leaves all three unchanged: a one-parameter "
      f"family. The search therefore works at L = {result['ref_L'] * 1e3:.0f} mm with the "
      "beam-equivalent thickness h_eq and the bending stiffness S = W h_eq^3 (W = S / h_eq^3), "
      "plus yield, E_t and r; L is then varied along the family (section 7).")
    A("")
    A(md_table(["unknown", "range", "scale"],
               [[s["name"], f"{s['low']:g} - {s['high']:g}", "log" if s["log"] else "linear"]
                for s in result["space"]]
               + [["contact law", ", ".join(bud["laws"]), "-"],
                  ["pairing", ", ".join(bud["pairings"]), "-"]]))
    A("")
    A("**Objective.** J = sum over the 12 Table 1 values and 14 Table 2 impulses of "
      "((ours - paper) / |paper| / scale)^2, with the scale weighting the robust quantities over "
      "the fragile ones:")
    A("")
    sc = result["scales"]
    A(md_table(["quantity", "scale", "why"], [
        ["Table 2 impulses (14)", pct(sc["t2"], 0).lstrip("+"), "robust; the 3 % target"],
        ["impulse, final velocity, max. mid-plane displacement (both rows)",
         pct(sc["impulse"], 0).lstrip("+"), "robust; the 5 % target"],
        ["contact duration, elasto-plastic", pct(sc["contact_duration:plastic"], 0).lstrip("+"),
         "one contact interval, but ends on a slow separation"],
        ["peak force (both rows), stress at A (both rows), elastic contact duration",
         pct(sc["max_contact_load"], 0).lstrip("+"),
         "fragile (mesh, law reading, re-contacts): half the weight of their 10 % target"]]))
    A("")
    ms = result["mesh_check"]
    A(f"**Meshes.** The search runs on the {result['meshes']['search'][0]} x "
      f"{result['meshes']['search'][1]} q4-sri half model (about 8x cheaper than the default "
      f"{result['meshes']['confirm'][0]} x {result['meshes']['confirm'][1]}); every reported "
      "residual is re-computed on the default mesh. The coarse mesh was checked first on "
      f"{len(ms)} parameter sets (`mesh-sensitivity.csv`): relative change from the default mesh")
    A("")
    rows = []
    for m in ms:
        meshes = list(m["by_mesh"])
        ref = m["by_mesh"][meshes[0]]
        for mesh in meshes[1:]:
            v = m["by_mesh"][mesh]
            def d(k):
                if k in v and k in ref and isinstance(v[k], float) and ref[k]:
                    return pct(rc.rel(v[k], ref[k]))
                return "fail" if not v["ok"] or not ref["ok"] else "-"
            rows.append([f"{m['law']}/{m['pairing']}", mesh,
                         d("impulse:elastic"), d("impulse:plastic"),
                         d("impactor_final_velocity:plastic"),
                         d("max_plate_displacement:plastic"), d("t2 plastic:2.5"),
                         d("max_contact_load:elastic"), d("max_contact_load:plastic"),
                         d("max_effective_stress_point_a:plastic")])
    A(md_table(["set", "mesh", "impulse E", "impulse EP", "v_final EP", "disp. EP",
                "T2 EP 2.5 m/s", "peak F E", "peak F EP", "stress A EP"], rows))
    A("")
    rob_keys = ("impulse:elastic", "impulse:plastic", "impactor_final_velocity:plastic",
                "max_plate_displacement:plastic", "max_plate_displacement:elastic",
                "impactor_final_velocity:elastic", "t2 plastic:2.5", "t2 plastic:10",
                "t2 elastic:2.5", "t2 elastic:10")
    d_rob, d_pk = [], []
    for m in ms:
        meshes = list(m["by_mesh"])
        ref = m["by_mesh"][meshes[0]]
        for mesh in meshes[1:]:
            v = m["by_mesh"][mesh]
            d_rob += [abs(rc.rel(v[k], ref[k])) for k in rob_keys
                      if isinstance(v.get(k), float) and isinstance(ref.get(k), float)]
            k = "max_contact_load:plastic"
            if isinstance(v.get(k), float) and isinstance(ref.get(k), float):
                d_pk.append(abs(rc.rel(v[k], ref[k])))
    A(f"Over these sets the robust quantities (both Table 1 impulses, final velocities and "
      f"displacements, the Table 2 impulses at 2.5 and 10 m/s) move by at most "
      f"{pct(max(d_rob, default=math.nan)).lstrip('+')} between the coarse and the default "
      f"mesh, inside their weights; the elasto-plastic peak force moves by up to "
      f"{pct(max(d_pk, default=math.nan)).lstrip('+')}: it is not a property of the plate "
      "but of the discretisation under the point force (section 10). Where a column reads "
      "'fail', the literal pairing failed on the default mesh while the coarse mesh still "
      "runs (section 9).")


def _search_stages(A: Page, result: dict) -> None:
    """Section 2, continued: the search's stages and the elastic grid's candidates."""
    bud = result["budget"]
    b = result["best"]
    A("**Stages** (all cached, resumable; times are wall-clock with 2 runs in parallel):")
    A("")
    ts = result["timing_s"]
    nh, nS = len(bud["grid_h"]), len(bud["grid_S"])
    A(md_table(["stage", "what", "time"], [
        ["mesh", "coarse vs default mesh on a few sets (above)", f"{ts.get('mesh', 0):.0f} s"],
        ["elastic grid", f"{nh} x {nS} grid over (h_eq, S) per law x pairing, r = "
         f"{bud['grid_r'] * 1e3:g} mm, elastic rows only (they do not depend on yield or "
         f"hardening); keeps the {bud['grid_keep']} best distinct points",
         f"{ts.get('elastic-grid', 0):.0f} s"],
        ["plastic grid", f"{len(bud['grid_sy'])} x {len(bud['grid_Et'])} grid over (yield, E_t) "
         "at each kept point, elasto-plastic rows only; J = J_elastic + J_plastic",
         f"{ts.get('plastic-grid', 0):.0f} s"],
        ["polish", f"Nelder-Mead over all 5 unknowns on the full objective, {bud['polish_fev']} "
         "evaluations, from the best grid point of each law (default pairing) and of the best "
         "literal combination", f"{ts.get('polish', 0):.0f} s"],
        ["confirm", "each polished set, rounded to 3 significant digits, on the default mesh; "
         "the chosen set is the best one that runs there", f"{ts.get('confirm', 0):.0f} s"],
        ["mesh study", "Table 1 of the chosen set on 20x4 ... 160x32", f"{ts.get('mesh-study', 0):.0f} s"],
        ["family", "the chosen set moved along h ~ L^2, W L^3 fixed, and off it",
         f"{ts.get('family', 0):.0f} s"],
        ["refit", f"re-fit at L = {', '.join(f'{x:g}' for x in bud['refit_L'])} m "
         f"({bud['refit_fev']} evaluations each)", f"{ts.get('refit', 0):.0f} s"],
        ["yield text", f"re-fit with the yield fixed at {bud['text_yield'] / 1e6:.0f} MPa "
         "(the text's 'almost 10 times')", f"{ts.get('yield-text', 0):.0f} s"],
        ["saturation", "hardening capped at a flow stress (a table), elasto-plastic rows",
         f"{ts.get('saturation', 0):.0f} s"],
        ["laws, pulse", "contact-law comparison, pulse scenes (default mesh)",
         f"{ts.get('laws', 0) + ts.get('pulse', 0):.0f} s"],
        ["**total**", f"{result['runs']['executed']} simulations", f"**{ts['total']:.0f} s**"]]))
    A("")
    A("![elastic grid](elastic-grid.svg)")
    A("")
    eg = result["elastic_grid"].get(b["key"], {})
    cand = []
    for e0 in eg.get("best", []):
        pls = [e for e in result["evaluations"] if e["stage"] == "plastic-grid"
               and f"{e['law']}/{e['pairing']}" == b["key"]
               and abs(e["x"]["h_eq"] - e0["h_eq"]) < 1e-9 and abs(e["x"]["S"] - e0["S"]) < 1e-15]
        jp = min((e["J"] for e in pls), default=math.nan)
        cand.append(f"h_eq = {e0['h_eq'] * 1e3:.1f} mm, S = {e0['S'] * 1e6:.2f}e-6 m^4 "
                    f"(W_eq = {e0['S'] / e0['h_eq'] ** 3 * 1e3:.0f} mm): J_elastic = "
                    f"{e0['J_el']:.2f}, best J_plastic on the (yield, E_t) grid = {jp:.2f}")
    A(f"For the chosen reading ({b['key']}) the elastic rows alone keep these distinct grid "
      "points: " + "; ".join(cand) + ". The elastic rows pin the bending stiffness S much "
      "better than the thickness (the valleys run along h_eq); the elasto-plastic rows "
      "(and with them the point-A stress) decide between the basins.")


def _chosen_parameters(A: Page, result: dict) -> None:
    """Section 3: the chosen set against the best set of every reading."""
    b = result["best"]
    p = b["params"]
    res = result["confirm"]["res"]
    pl = result["polish"]
    rows = []
    for key, v in sorted(result["per_law"].items(), key=lambda kv: kv[1]["J"]):
        pp = v["params"]
        rows.append([("**" + key + "**") if key == b["key"] else key]
                    + params_row(pp) + [f"{v['J_coarse']:.2f}",
                                        f"{v['J']:.2f}" if v["J"] < 1e5 else "fails",
                                        acc_text(v["acceptance"]) if v["J"] < 1e5 else
                                        "does not run on the default mesh: "
                                        + short_err(v["res"].get("errors", ["?"])[0])])
    A(md_table(["law/pairing", "L mm", "W mm", "h mm", "yield MPa", "E_t GPa", "r mm",
                "J (40x8)", "J (80x16)", "targets (80x16)"], rows))
    A("")
    A(f"The chosen set is the first row: the best objective among the sets that run on the "
      "default mesh. Derived quantities: h/L = "
      f"{p['h'] / p['L']:.3f}; plate mass {p['rho'] * p['L'] * p['W'] * p['h']:.2f} kg "
      f"(impactor/plate mass ratio {rc.T1_MASS / (p['rho'] * p['L'] * p['W'] * p['h']):.2f} in "
      f"Table 1, {rc.T2_MASS / (p['rho'] * p['L'] * p['W'] * p['h']):.2f} in Table 2); "
      f"clamped-beam central stiffness 16 E' W h^3 / L^3 = "
      f"{16 * p['E'] / (1 - p['nu'] ** 2) * p['W'] * p['h'] ** 3 / p['L'] ** 3:.3g} N/m "
      "(bending only); the paper's own numbers imply about 4.9e8 N/m (reference-data/paper/README.md); "
      f"fully plastic load of the clamped beam 8 M_p / L with M_p = (2/sqrt 3) sigma_y W h^2 / 4: "
      f"{8 * (2 / math.sqrt(3)) * p['sy'] * p['W'] * p['h'] ** 2 / 4 / p['L'] / 1e3:.0f} kN.")


def _table1(A: Page, result: dict, hist_plots: list[str]) -> None:
    """Section 4: Table 1 side by side, and which contact duration the paper printed."""
    c = result["confirm"]
    res = c["res"]
    rows = []
    for q in rc.T1_KEYS:
        e, pp = res["t1"][f"{q}:elastic"], res["t1"][f"{q}:plastic"]
        tg = 0.05 if q in rc.ROBUST else 0.10
        rows.append([rc.T1_LABEL[q] + (" *(robust)*" if q in rc.ROBUST else ""),
                     fmt_q(q, e["paper"]), fmt_q(q, e["ours"]), pct(e["rel"]), mark(e["rel"], tg),
                     fmt_q(q, pp["paper"]), fmt_q(q, pp["ours"]), pct(pp["rel"]), mark(pp["rel"], tg),
                     f"{pp['paper'] / e['paper']:.3f}", f"{pp['ours'] / e['ours']:.3f}"])
    A(md_table(["quantity", "paper E", "ours E", "residual", "in target", "paper EP", "ours EP",
                "residual", "in target", "ratio EP/E paper", "ratio ours"], rows))
    A("")
    A("Targets: 5 % for the robust quantities, 10 % for the others. Final velocities are signed "
      "(negative = rebound); displacements are the most negative mid-plane mid-span u_y.")
    A("")
    el_runs = c["runs"][0]
    iv = el_runs["contact_intervals_s"]
    near = [e["elastic_intervals_ms"] for e in result["evaluations"]
            if e.get("elastic_intervals_ms") and abs(e["elastic_intervals_ms"][-1][1] / 0.605 - 1) < 0.15]
    one = [iv_ for iv_ in near if iv_[0][1] > 0.5 * iv_[-1][1]]
    one_st = sorted({e["stage"] for e in result["evaluations"] if e.get("elastic_intervals_ms")
                     and abs(e["elastic_intervals_ms"][-1][1] / 0.605 - 1) < 0.15
                     and e["elastic_intervals_ms"][0][1] > 0.5 * e["elastic_intervals_ms"][-1][1]})
    single_txt = (f"of the {len(near)} elastic Table 1 runs of the search whose whole contact "
                  f"lies within 15 % of 0.605 ms, {len(near) - len(one)} separate and re-contact "
                  f"(first interval shorter than half the whole) and {len(one)} have one long "
                  f"first contact (stages: {', '.join(one_st) or '-'}); the chosen set is of the "
                  "first kind, so for it the readings differ and the data decide")
    A(f"**Which contact duration the paper printed.** Our elastic impact has {len(iv)} contact "
      "intervals: " + ", ".join(f"{a * 1e3:.3f}-{bb * 1e3:.3f}" for a, bb in iv) + " ms. The "
      f"paper's 0.605 ms is the end of the last interval (ours {iv[-1][1] * 1e3:.3f} ms), not "
      f"the first (ours {iv[0][1] * 1e3:.3f} ms, {pct(rc.rel(iv[0][1] * 1e3, 0.605), 0)}). "
      "Independent evidence from the paper alone: a striker on a spring stays in contact for half "
      "a period, T = pi sqrt(m/k); the elastic row gives k = m (v0/delta)^2 = 18 (10/1.903e-3)^2 "
      "= 4.97e8 N/m from its displacement and k = m (pi/T)^2 = 4.85e8 N/m with T = 0.605 ms: "
      "the same stiffness, so 0.605 ms spans the whole impact, from first contact to the final "
      "separation, as a half period of the striker on the plate. A first interval of 0.605 ms "
      "followed by re-contacts would make the whole contact longer than that half period, "
      "inconsistent with the printed displacement. The two readings coincide only when the "
      "impact has a single contact interval: "
      f"{single_txt}. The report and the scenes use the end of the last interval "
      "(`contact_duration_s`, i.e. the whole contact) and list every interval.")
    if hist_plots:
        A("")
    for f in hist_plots:
        A(f"![{f}]({f})")


def _table2(A: Page, result: dict) -> None:
    """Section 5: Table 2 side by side."""
    c = result["confirm"]
    res = c["res"]
    runs = {(q["table"], q["row"], q["v0"]): q for q in c["runs"]}
    rows = []
    for v0 in rc.T2_V0:
        r_ = [f"{v0:g}"]
        for row in ROWS:
            e = res["t2"].get(f"{row}:{v0:g}")
            q = runs[("t2", row, v0)]
            if e is None:
                r_ += ["-", "fails", "-", "-", "-"]
                continue
            r_ += [f"{e['paper']:.2f}", f"{e['ours']:.2f}", pct(e["rel"], 2),
                   f"{rc.T2_MASS * q['final_impactor_velocity_mps']:.2f}",
                   f"{q['impulse_momentum_error']:.0e}"]
        rows.append(r_)
    A(md_table(["v0 m/s", "paper I E", "ours I E", "residual", "ours p_f E", "identity E",
                "paper I EP", "ours I EP", "residual", "ours p_f EP", "identity EP"], rows))
    A("")
    A("I = impulse (N s), p_f = final momentum m v_final (kg m/s, negative = rebound); "
      "'identity' = |I - m (v0 - v_final)| / I of that run. Target: 3 %.")
    A("")
    A("![Table 2](table2.svg)")


def _identity(A: Page, result: dict) -> None:
    """Section 6: the impulse-momentum identity."""
    c = result["confirm"]
    allid = [e["max_impulse_momentum_error"] for e in result["evaluations"]
             if not math.isnan(e["max_impulse_momentum_error"])]
    A(f"`impulse_momentum_error` = |trapezoidal impulse - m (v0 - v_final)| / impulse, per run. "
      f"Largest value over the {len(c['runs'])} confirmation runs: "
      f"{c['max_impulse_momentum_error']:.1e}; over the {result['runs']['executed']} runs of "
      f"the search: {max(allid):.1e}. Eqs. (19)-(20) with the trapezoidal impulse make it an "
      "identity of the method, whatever the reading of the paper; it holds to round-off in "
      "every run, including the energy-inconsistent literal reading. (Table 2 of the paper shows "
      "the same identity to its printed digits; reference-data/paper/PROVENANCE.md.)")


def _beam_family(A: Page, result: dict) -> None:
    """Section 7: the beam family and the contrasts off it."""
    fam = result["family"]
    A("**The beam family, numerically.** The chosen set moved along (L, W, h) -> "
      "(L s, W / s^3, h s^2) (40 x 8 mesh, objective J as in the search):")
    A("")
    rows = []
    for f in fam["family"]:
        ok = f["J"] < 1e5
        rows.append([f"{f['L'] * 1e3:.0f}", f"{f['W'] * 1e3:.0f}", f"{f['h'] * 1e3:.1f}",
                     f"{f['h'] / f['L']:.3f}", f"{f['J']:.2f}" if ok else "fails"]
                    + [pct(f["rel"].get(k)) if ok and k in f["rel"] else "-" for k in FAMILY_KEYS]
                    + [pct(f["acceptance"].get("t2_worst")) if ok else "-"])
    A(md_table(["L mm", "W mm", "h mm", "h/L", "J"] + [FAMILY_SHORT[k] for k in FAMILY_KEYS] + ["T2 worst"],
               rows))
    A("")
    A("![family](family.svg)")
    A("")
    A(f"Leaving the family by the factor {fam['factor']:g} in the listed way (same mesh):")
    A("")
    rows = []
    for f in fam["contrasts"]:
        ok = f["J"] < 1e5
        rows.append([f["name"], f"{f['L'] * 1e3:.0f}", f"{f['W'] * 1e3:.0f}", f"{f['h'] * 1e3:.1f}",
                     f"{f['J']:.1f}" if ok else "fails"]
                    + [pct(f["rel"].get(k)) if ok and k in f["rel"] else "-" for k in FAMILY_KEYS])
    A(md_table(["change", "L mm", "W mm", "h mm", "J"] + [FAMILY_SHORT[k] for k in FAMILY_KEYS], rows))


def _tie_breakers(A: Page, result: dict) -> None:
    """Section 7, continued: the re-fits at other lengths and what breaks the tie."""
    bud, fam = result["budget"], result["family"]
    c = result["confirm"]
    p = result["best"]["params"]
    res = c["res"]
    acc = c["acceptance"]
    if result["refit_confirm"]:
        A("**Re-fitted at other lengths** (all five unknowns re-optimised at that L, then "
          "confirmed on the default mesh):")
        A("")
        rows = [[f"{r['L'] * 1e3:.0f}"] + params_row(r["params"])[1:] + [f"{r['J']:.2f}",
                acc_text(r["acceptance"])] for r in result["refit_confirm"]]
        rows.insert(0, [f"{p['L'] * 1e3:.0f} (chosen)"] + params_row(p)[1:]
                    + [f"{c['J']:.2f}", acc_text(acc)])
        A(md_table(["L mm", "W mm", "h mm", "yield MPa", "E_t GPa", "r mm", "J (80x16)",
                    "targets"], rows))
        A("")
    yt = result.get("yield_text")
    A("**What breaks the tie.**")
    A("")
    famok = [f for f in fam["family"] if f["J"] < 1e5]
    fambad = [f for f in fam["family"] if f["J"] >= 1e5]
    why_bad = ""
    if fambad:
        errs = [e for e in result["evaluations"] if e["stage"] == "family" and not e["res"]["ok"]]
        kinds = {"the contact law's maximum force per width (eq. 4 read in mm has one at "
                 "P* = l^2/(r c))" if "no root" in (e["res"].get("errors") or [""])[0] else
                 "an inverted element" for e in errs}
        why_bad = (f" Members with L >= {min(f['L'] for f in fambad) * 1e3:.0f} mm "
                   f"(W <= {max(f['W'] for f in fambad) * 1e3:.0f} mm) do not run: the force per "
                   f"unit width exceeds " + " / ".join(sorted(kinds)) + ", so the reading itself "
                   "bounds the family from above.")
    base_f = min(famok, key=lambda f: abs(f["L"] - p["L"]))
    def dmax(f):
        return max(abs(f["rel"][k] - base_f["rel"][k]) for k in FAMILY_KEYS[:6]
                   if k in f["rel"] and k in base_f["rel"])
    step = [f for f in famok if abs(f["L"] - p["L"] * fam["factor"]) < 1e-9]
    offs = [(f["name"], dmax(f)) for f in fam["contrasts"][1:] if f["J"] < 1e5]
    txt = (f"- *Within the beam family* only what beam theory leaves out distinguishes the "
           "members: the thickness ratio h/L (shear, through-thickness wave transit, the local "
           "indentation of the mid-plane datum) and the force per unit width P = F/W in the "
           "contact law.")
    if step and offs:
        mild = min(offs, key=lambda t: t[1])
        txt += (f" Moving along the family by the factor {fam['factor']:g} (L = "
                f"{step[0]['L'] * 1e3:.0f} mm) changes the six robust Table 1 residuals by at "
                f"most {pct(dmax(step[0])).lstrip('+')}; leaving it by the same factor changes "
                f"them by {pct(mild[1]).lstrip('+')} ({mild[0]}, the mildest) to "
                f"{pct(max(t[1] for t in offs)).lstrip('+')}.")
    A(txt + why_bad + " J along the family is not monotone: the elastic impact's re-contacts "
      "make the elastic final velocity and duration jump between neighbours, by a few per cent.")
    if result["refit_confirm"]:
        rf = result["refit_confirm"][0]
        rp = rf["params"]
        same = (rf["acceptance"].get("t2_pass") == acc.get("t2_pass")
                and rf["acceptance"].get("robust_pass") == acc.get("robust_pass"))
        A(f"- *Re-fitting at another length* (L = {rf['L'] * 1e3:.0f} mm, W = "
          f"{rp['W'] * 1e3:.0f} mm, h = {rp['h'] * 1e3:.2f} mm, all five unknowns free, "
          f"{bud['refit_fev']} evaluations) reaches J = {rf['J']:.1f} on the default mesh "
          f"against {c['J']:.1f} for the chosen set, with {acc_text(rf['acceptance'])}"
          + (": it meets the same targets, so the data do not pin L." if same else "."))
    okl = [(k, v) for k, v in result["per_law"].items() if v["J"] < 1e5]
    A("- *Across the readings*, the contact-law variant shifts the elastic peak force and the "
      "elastic restitution (section 8); re-fitted with its own plate each reading reaches "
      + "; ".join(f"{k}: J = {v['J']:.1f}, robust worst {pct(v['acceptance']['robust_worst'])}, "
                  f"Table 2 worst {pct(v['acceptance']['t2_worst'])}" for k, v in
                  sorted(okl, key=lambda kv: kv[1]["J"]))
      + " (default mesh; section 3). The readings are ranked by the data, but not by a wide "
      "margin, and each comes with its own plate: the law and the plate are not separable.")
    A("- *The tie is broken by a prior, not by the data*: the search length is the round "
      f"L = {p['L'] * 1e3:.0f} mm, which with W = {p['W'] * 1e3:.0f} mm is close to a square "
      "plate, the most natural reading of Fig. 1's 'rectangular plate with length L, width W' "
      "(and the first-guess plate of reference-data/paper/README.md); a shorter member needs a much wider plate "
      "(W L^3 fixed). Neighbouring members of the family reproduce the tables about as well, "
      "and the scenes say so.")
    if yt:
        A(f"- *The text's clue on the yield stress.* Section 4 says the elastic stress at A is "
          f"'almost 10 times as large as the yield stress': 2260 MPa / 10 = 226 MPa, so a yield of "
          f"about 230-260 MPa, where our fit gives {p['sy'] / 1e6:.0f} MPa "
          f"({2260 / (p['sy'] / 1e6):.1f} times). Fixing the yield at "
          f"{yt['yield'] / 1e6:.0f} MPa and re-fitting the rest gives J = {yt['J']:.2f} on the "
          f"default mesh (chosen: {c['J']:.2f}); {acc_text(yt['acceptance'])}. Table 2 points "
          "the same way at its low end: the paper's rows at 1.25 m/s are identical (no "
          "yielding), while our fitted plate yields slightly there. Yet the tables as a whole "
          "pull the yield below the text's hint within this model (the 2.5-7.5 m/s "
          "elasto-plastic impulses need early yielding); the hint is recorded, not imposed.")


def _contact_laws(A: Page, result: dict) -> None:
    """Section 8: the three readings of the contact law on the chosen set."""
    b = result["best"]
    A("Everything but the law is the chosen set; default mesh; force on the datum (default "
      f"pairing). Shift = relative to the chosen reading ({b['law']}).")
    A("")
    laws = {(r["law"], r["pairing"]): r for r in result["laws"]}
    base = laws[(b["law"], "default")]
    head = ["quantity", "row"] + [f"{lw}" for lw in rc.LAWS] + [f"shift {lw}" for lw in rc.LAWS
                                                                  if lw != b["law"]] + ["paper"]
    rows = []
    for q in rc.T1_KEYS:
        for row in ROWS:
            vals, shifts = [], []
            for lw in rc.LAWS:
                v = laws[(lw, "default")][row]
                vals.append(fmt_q(q, v[q]) if "error" not in v else "fails")
                if lw != b["law"]:
                    shifts.append(pct(rc.rel(v[q], base[row][q])) if "error" not in v
                                  and "error" not in base[row] else "-")
            rows.append([rc.T1_LABEL[q], ROW_LABEL[row]] + vals + shifts
                        + [fmt_q(q, rc.read_paper()[0][q][row])])
    rows.append(["energy balance error (max)", "both"]
                + [f"{max(laws[(lw, 'default')][r_].get('max_energy_balance_error', math.nan) for r_ in ROWS):.0e}"
                   for lw in rc.LAWS] + [""] * (len(rc.LAWS) - 1) + [""])
    A(md_table(head, rows))
    A("")
    def sh(q, row, lw):
        v, b0 = laws[(lw, "default")][row], base[row]
        return abs(rc.rel(v[q], b0[q])) if "error" not in v and "error" not in b0 else math.nan
    others = [lw for lw in rc.LAWS if lw != b["law"]]
    rob_sh = max(sh(q, row, lw) for q in rc.ROBUST for row in ROWS for lw in others)
    ep_sh = max(sh(q, "plastic", lw) for q in rc.T1_KEYS for lw in others)
    pe = {lw: laws[(lw, "default")]["elastic"].get("max_contact_load", math.nan) for lw in rc.LAWS}
    A(f"Switching the reading with the plate fixed moves the robust quantities by up to "
      f"{pct(rob_sh).lstrip('+')} (mostly the elastic final velocity, i.e. the elastic "
      f"restitution) and the elastic peak force by a factor "
      f"{pe['paper-mm'] / pe['paper-m']:.2f} between the metre and millimetre readings "
      f"(Johnson's consistent law lies between: {pe['johnson']:.0f} kN). The elasto-plastic "
      f"row moves by at most {pct(ep_sh).lstrip('+')}: the plate yields under the load "
      "long before the contact compliance matters. Each reading re-fitted with its own plate "
      "is in section 3.")


def _readings(A: Page, result: dict) -> None:
    """Section 9: which reading reproduces the paper, and what the literal one costs."""
    laws = {(r["law"], r["pairing"]): r for r in result["laws"]}
    b = result["best"]
    c = result["confirm"]
    res = c["res"]
    rows = []
    for lw in rc.LAWS:
        for pr in ("default", "literal"):
            r = laws[(lw, pr)]
            cells = [f"{lw} / {pr}"]
            for row in ROWS:
                v = r[row]
                if "error" in v:
                    cells += ["fails: " + ("element inverted under the top node" if "inverted" in v["error"]
                                           else v["error"][:60]), "-", "-", "-"]
                else:
                    cells += [fmt_q("impulse", v["impulse"]), fmt_q("max_contact_load", v["max_contact_load"]),
                              fmt_q("max_plate_displacement", v["max_plate_displacement"]),
                              f"{v['max_energy_balance_error']:.1e}"]
            rows.append(cells)
    A(md_table(["reading", "I E", "peak F E kN", "disp E", "energy error E",
                "I EP", "peak F EP kN", "disp EP", "energy error EP"], rows))
    A("")
    lit = [v for k, v in result["per_law"].items() if k.endswith("/literal")]
    A(f"**The reproducing reading** is {b['law']} with the {b['pairing']} pairing: "
      f"{rc.LAW_TEXT[b['law']]}, {rc.PAIRING_TEXT[b['pairing']]}. It closes the energy "
      f"balance to {c['max_energy_balance_error']:.0e} and runs on every mesh tried.")
    A("")
    if lit:
        lv = lit[0]
        A(f"**The paper read literally** (indentation from the mid-plane, force on the top node) "
          f"was searched too. Its best set on the coarse mesh ({lv['law']}, "
          + ", ".join(f"{k} {v}" for k, v in zip(["L", "W", "h", "yield", "E_t", "r"],
                                                   params_row(lv["params"])))
          + f" in mm / MPa / GPa) reaches J = {lv['J_coarse']:.2f} there, "
          "lower than the default reading, mainly because a force on the top node over a "
          "yielding top element gives a larger elasto-plastic peak force and a lower stress at A. "
          "What it costs:")
        A("")
        if lv.get("coarse"):
            A("Its residuals on the 40 x 8 mesh, where it runs:")
            A("")
            A.extend(residual_block(lv["coarse"]))
            A("")
        A("- **Energy does not balance**: the plate receives f d(u_top) while the contact "
          "spring and the impactor account for f d(u_mid); the through-thickness compression "
          "under the point force is counted twice. The balance error of the chosen plate read "
          "literally is " + ", ".join(
              f"{lw}: {max(laws[(lw, 'literal')][r_].get('max_energy_balance_error', float('nan')) for r_ in ROWS):.0%}"
              for lw in rc.LAWS if all('error' not in laws[(lw, 'literal')][r_] for r_ in ROWS))
          + " of the largest energy of the run (default pairing: < 1e-4).")
        A("- **It is not mesh-convergent and breaks on the default mesh**: a point force on a "
          "surface node over yielding material punches that node in; on the 80 x 16 mesh the "
          "element under the top node inverts and the run stops: "
          + short_err(lv["res"].get("errors", ["(no failure)"])[0]) + ".")
        A("- So the paper's numbers that favour the literal reading (the elasto-plastic peak "
          "force) are the ones that depend on its discretisation; no mesh-independent statement "
          "can be made with it, and it cannot be the reproducing reading of a verification suite.")


def _out_of_reach(A: Page, result: dict) -> None:
    """Section 10: what remains out of reach, and why."""
    res = result["confirm"]["res"]
    acc = result["confirm"]["acceptance"]
    mst = result.get("mesh_study", [])
    if mst:
        A("**Table 1 of the chosen set on four meshes** (same parameters, q4-sri half model):")
        A("")
        rows = []
        for q in rc.T1_KEYS:
            for row in ROWS:
                k = f"{q}:{row}"
                rows.append([rc.T1_LABEL[q], ROW_LABEL[row]]
                            + [fmt_q(q, m["t1"][k]) if m["ok"] and k in m["t1"] else "fails"
                               for m in mst] + [fmt_q(q, res["t1"][k]["paper"])])
        A(md_table(["quantity", "row"] + ["x".join(map(str, m["mesh"])) for m in mst] + ["paper"],
                   rows))
        A("")
    pk = res["t1"]["max_contact_load:plastic"]
    lit_pk = None
    for k_, v_ in result["per_law"].items():
        if k_.endswith("/literal") and v_.get("coarse") and "max_contact_load:plastic" in v_["coarse"]["t1"]:
            lit_pk = v_["coarse"]["t1"]["max_contact_load:plastic"]["rel"]
    sa = res["t1"]["max_effective_stress_point_a:plastic"]
    pe = res["t1"]["max_contact_load:elastic"]
    A(f"- **Elasto-plastic peak contact force** (ours {pk['ours']:.0f} kN, paper 1106 kN, "
      f"{pct(pk['rel'], 0)}). In our runs it is the force while the material around the loaded "
      "node first yields; it falls with every refinement (table above) because a point force on "
      "a node of a yielding continuum has no mesh-independent limit. The paper's 1106 kN belongs "
      "to its own (lost) mesh and to its literal force node. No plate parameter moves it into "
      "the band without wrecking the robust quantities (the search tried, with this quantity "
      "at a low weight); the literal reading narrows the gap"
      + (f" (to {pct(lit_pk)} on the 40 x 8 mesh, where it still runs)" if lit_pk is not None else "")
      + " at the cost of section 9. Out of reach with a mesh-independent model: report it, do "
      "not fit it.")
    A(f"- **Elastic peak contact force** (ours {pe['ours']:.0f} kN, {pct(pe['rel'], 0)}): the "
      "largest spike of a fluctuating force (several contacts and separations); it depends on "
      "the reading of eq. (4) by a factor of about 2 and on the mesh by several per cent "
      "(table above). For a given plate it is within reach to about 10-15 %; comparably good "
      "plates differ by more (section 13).")
    sat = result.get("saturation", [])
    A(f"- **Elasto-plastic stress at A** (ours {sa['ours']:.0f} MPa, paper 285.4 MPa, "
      f"{pct(sa['rel'], 0)}): with linear hardening the bottom fibre at mid-span hardens to "
      f"yield + H k at the plastic strain k it reaches. A hardening curve capped at a flow "
      "stress brings it into the band without changing the robust quantities:")
    if sat:
        A("")
        rows = []
        for o in sat:
            if not o["ok"]:
                rows.append([f"{o['s_sat'] / 1e6:.0f}" if o["s_sat"] else "none (linear)", "fails"] + ["-"] * 5)
                continue
            r_ = o["rel"]
            rows.append([f"{o['s_sat'] / 1e6:.0f}" if o["s_sat"] else "none (linear)",
                         f"{o['J_plastic_rows']:.2f}",
                         pct(r_.get("max_effective_stress_point_a:plastic")),
                         pct(r_.get("impulse:plastic")), pct(r_.get("impactor_final_velocity:plastic")),
                         pct(r_.get("max_plate_displacement:plastic")),
                         pct(max((abs(v) for k, v in r_.items() if k.startswith("t2 ")), default=math.nan))])
        A(md_table(["flow-stress cap MPa", "J (EP rows, 80x16)", "stress A EP", "I EP", "v_f EP",
                    "disp EP", "T2 EP worst (absolute)"], rows))
        A("")
    A("  The cap is one more parameter fitted to this one number (at a cap just above 285 MPa the "
      "stress at A equals the cap by construction), so it proves only that the mismatch is a "
      "matter of the unknown hardening curve at large strain, not of the method. The chosen set "
      "keeps the linear hardening of the search; the capped variant is documented here.")
    A("- **All twelve Table 1 values within 10 % with one parameter set** is therefore out of "
      "reach with the energy-consistent reading on a mesh-independent basis; the best "
      f"achievable is what the chosen set gives: {acc_text(acc)}.")


def _point_a_and_pulse(A: Page, result: dict) -> None:
    """Section 11: point A and the pulse scenes."""
    c = result["confirm"]
    p = result["best"]["params"]
    pa = c["runs"][0]["max_von_mises_Pa"], c["runs"][1]["max_von_mises_Pa"]
    names = {"A": "mid-span, bottom surface (chosen)", "A_mid_top": "mid-span, top surface",
             "A_clamp_top": "clamped edge, top", "A_clamp_bottom": "clamped edge, bottom",
             "A_quarter_bottom": "quarter span, bottom"}
    rows = [[names.get(k, k), f"{pa[0][k] / 1e6:.0f}", pct(rc.rel(pa[0][k] / 1e6, 2260)),
             f"{pa[1][k] / 1e6:.0f}", pct(rc.rel(pa[1][k] / 1e6, 285.4))] for k in pa[0]]
    A("Point A is lost with Fig. 4. Candidates, maximum von Mises stress of the chosen set "
      "(default mesh; the value at the integration point nearest the probe):")
    A("")
    A(md_table(["probe", "elastic MPa", "vs 2260", "elasto-plastic MPa", "vs 285.4"], rows))
    A("")
    A("Mid-span bottom matches the elastic value and is a regular point (not under the point "
      "force, not in a clamped corner, whose stress is singular and grows with refinement; the "
      "default pairing loads the mid-plane, so top and bottom at mid-span read alike). It is "
      "also the 'center point' of the paper's pulse verification (Figs. 5-6). Point A = "
      "(x = L/2, y = 0).")
    A("")
    pu = result["pulse"]
    A(f"**Pulse scenes** (`paper-pulse-{{elastic,plastic}}.yaml`): 86.5 kN over the whole width, "
      f"rectangular, on the top mid-span node, duration {pu['duration_s'] * 1e3:.3f} ms = the "
      "elasto-plastic contact duration of Table 1 (the paper does not give it; this is the "
      "longest time scale it prints, long enough for the plate to overshoot and oscillate about "
      f"the quasi-static deflection), run to {pu['end_s'] * 1e3:g} ms. Results on the chosen "
      "plate (default mesh):")
    A("")
    rows = []
    for row in ROWS:
        v = pu["results"][row]
        if v.get("error"):
            rows.append([ROW_LABEL[row], "fails", "-", "-"])
            continue
        rows.append([ROW_LABEL[row], f"{v['max_plate_displacement_m'] * 1e3:.3f}",
                     f"{v['max_von_mises_Pa']['A'] / 1e6:.0f}", f"{v['max_energy_balance_error']:.1e}"])
    A(md_table(["pulse", "max. mid-plane disp. mm", "max. stress at A MPa", "energy balance error"],
               rows))
    A("")
    ve = pu["results"]["elastic"]
    if not ve.get("error") and ve["max_von_mises_Pa"]["A"] > p["sy"]:
        A(f"The elastic pulse's stress at A ({ve['max_von_mises_Pa']['A'] / 1e6:.0f} MPa, raised "
          "by the dynamic overshoot of a suddenly applied load) exceeds the "
          f"reconstructed yield ({p['sy'] / 1e6:.0f} MPa): 86.5 kN yields this plate, so the "
          "elasto-plastic pulse scene is the physically consistent one; the elastic one stays "
          "useful as a linear reference.")
        A("")
    A("There is no reference value: Figs. 5-6 compared the paper's program with ANSYS and are "
      "lost. These scenes are for the pulse suite's code-to-code and invariant checks.")


def _conclusions(A: Page, result: dict) -> None:
    """Section 12: the paper's four conclusions, checked one by one."""
    c = result["confirm"]
    p = result["best"]["params"]
    res = c["res"]
    e_ = {q: res["t1"][f"{q}:elastic"]["ours"] for q in rc.T1_KEYS}
    p_ = {q: res["t1"][f"{q}:plastic"]["ours"] for q in rc.T1_KEYS}
    t2i = {(row, v): res["t2"][f"{row}:{v:g}"]["ours"] for row in ROWS for v in rc.T2_V0
           if f"{row}:{v:g}" in res["t2"]}
    dec = [v for v in rc.T2_V0 if ("plastic", v) in t2i and t2i[("plastic", v)] < t2i[("elastic", v)] * 0.999]
    eq = [v for v in rc.T2_V0 if ("plastic", v) in t2i and abs(t2i[("plastic", v)] / t2i[("elastic", v)] - 1) < 1e-3]
    A(md_table(["conclusion", "paper", "ours (chosen set, default mesh)", "holds"], [
        ["1. Impulse decreases", "351.8 -> 221.2 N s; Table 2: lower at every v0 >= 2.5 m/s, equal at 1.25",
         f"{e_['impulse']:.1f} -> {p_['impulse']:.1f} N s; Table 2: lower at v0 = "
         f"{', '.join(f'{v:g}' for v in dec)} m/s, equal (elastic impact) at {', '.join(f'{v:g}' for v in eq) or '-'}",
         ("yes" if p_["impulse"] < e_["impulse"] and len(dec) >= 6 else "no")
         + ("" if eq else " (at 1.25 m/s our plate already yields a little: "
            f"{pct(rc.rel(t2i[('plastic', 1.25)], t2i[('elastic', 1.25)]))}; the paper's does "
            "not, a hint of a higher yield, see section 7)")],
        ["2. Displacement increases", "-1.903 -> -4.802 mm",
         f"{e_['max_plate_displacement']:.3f} -> {p_['max_plate_displacement']:.3f} mm "
         "(plus a permanent set after the impact)",
         "yes" if p_["max_plate_displacement"] < e_["max_plate_displacement"] else "no"],
        ["3. Contact lasts longer", "0.605 -> 1.279 ms",
         f"{e_['contact_duration']:.3f} -> {p_['contact_duration']:.3f} ms "
         f"({len(c['runs'][0]['contact_intervals_s'])} -> {len(c['runs'][1]['contact_intervals_s'])} contact intervals)",
         "yes" if p_["contact_duration"] > e_["contact_duration"] else "no"],
        ["4. Stress is more realistic (bounded by the hardening curve)",
         "2260 MPa ('almost 10 times' yield) -> 285.4 MPa",
         f"{e_['max_effective_stress_point_a']:.0f} MPa ({e_['max_effective_stress_point_a'] / (p['sy'] / 1e6):.1f} x yield) -> "
         f"{p_['max_effective_stress_point_a']:.0f} MPa = yield {p['sy'] / 1e6:.0f} MPa + hardening "
         f"(implied plastic strain at A {((p_['max_effective_stress_point_a'] * 1e6 - p['sy']) / (p['E'] * p['Et'] / (p['E'] - p['Et']))):.1%});"
         " with the capped curve of section 10 the stress at A never exceeds the cap",
         "yes" if p_["max_effective_stress_point_a"] < e_["max_effective_stress_point_a"] / 3 else "no"]]))
    A("")
    A("The radial return keeps every integration point on or inside the hardening curve "
      "(`solver/ALGORITHM.md` section 3), so 'bounded by the hardening curve' holds by "
      "construction; the check above is that the bound is what limits the stress at A.")


def _tolerances(A: Page, result: dict) -> None:
    """Section 13: the tolerances the reconstruction supports."""
    c = result["confirm"]
    res = c["res"]
    tol = result["supported_tolerances"]
    A("For the harness (table1, momentum-impulse and pulse suites): the tolerance each "
      "quantity can honestly be given against the paper on the scenes of "
      "`verification/scenes/paper-*.yaml`. It adds to the residual of the chosen set the "
      "spread over comparably good sets (the re-fit at another length, J within 1.5x of the "
      "chosen set's) and the change from 80x16 to 160x32, rounds up, and never goes below the "
      "issue's target: a quantity that happens to land within 1 % of the paper is not "
      "thereby pinned to 1 % by a reconstruction with these non-uniquenesses.")
    A("")
    rows = []
    for q in rc.T1_KEYS:
        for row in ROWS:
            k = f"{q}:{row}"
            pr_ = tol[k + ":parts"]
            rows.append([rc.T1_LABEL[q], ROW_LABEL[row], group_of(q, row),
                         pct(pr_["residual"]), pct(pr_["spread"]).lstrip("+"),
                         pct(pr_["mesh"]).lstrip("+"), f"{tol[k + ':value'] * 100:.0f} %",
                         "5 %" if q in rc.ROBUST else "10 %"])
    rows.append(["Table 2 impulses (14)", "both", "robust",
                 pct(max((abs(e["rel"]) for e in res["t2"].values()), default=math.nan)),
                 f"worst {pct(tol['t2:worst']).lstrip('+')}", "-",
                 f"{tol['t2:value'] * 100:.1f} %", "3 %"])
    rows.append(["impulse = m (v0 - v_final)", "every run", "identity",
                 f"{c['max_impulse_momentum_error']:.0e}", "-", "-", "1e-12 (round-off)",
                 "round-off"])
    rows.append(["energy balance (default pairing)", "every run", "invariant",
                 f"{c['max_energy_balance_error']:.0e}", "-", "-", "1e-3", "-"])
    A(md_table(["quantity", "row", "kind", "residual (80x16)", "spread (comparable sets)",
                "mesh 80->160", "supported tolerance", "issue target"], rows))
    A("")
    A("Pulse scenes: no paper reference (Figs. 5-6 lost): compare with the independent code and "
      "the invariants only.")


def _files(A: Page, result: dict) -> None:
    """Section 14: the files beside the page."""
    p = result["best"]["params"]
    A(md_table(["file", "content"], [
        ["`search.json`", "everything: settings, every evaluation (parameters, residuals, J), "
         "grids, polish, family, confirmations, laws, pulse, timing"],
        ["`evaluations.csv`", "one row per evaluated parameter set"],
        ["`best.json`", "the chosen set"],
        ["`table1.csv`, `table2.csv`", "paper vs ours (default mesh), residuals, identity"],
        ["`contact-law.csv`", "the three laws x two pairings on the chosen set"],
        ["`family.csv`", "the beam family, the contrasts, the re-fits"],
        ["`mesh-sensitivity.csv`", "coarse vs default mesh"],
        ["`*.svg`", "plots"],
        ["`PROVENANCE.md`", "script and solver hashes, commit, date, command"]]))
    A("")
    A("Re-run: `scripts/setup-venv.sh && cargo build --release -p impact-verification && "
      "scripts/reconstruction/reconstruct.py` (about 15 min on 2 cores; `--quick` for a smoke test under 3 min; "
      "`--report-only` rewrites this page from `search.json`).")


def report_text(result: dict, hist_plots: list[str]) -> str:
    """The page `report.md`: its sections in order, from `search.json`'s result. Each is its
    heading (None: it continues the section before), what its writer appends, and the blank
    line that closes it."""
    sections = (
        (None, _title),
        ("## Summary", _summary),
        ("## 1. What had to be reconstructed", _unknowns),
        ("## 2. How the parameters were found", _search_method),
        (None, _search_stages),
        ("## 3. The chosen parameters", _chosen_parameters),
        ("## 4. Table 1 side by side (default mesh)", partial(_table1, hist_plots=hist_plots)),
        ("## 5. Table 2 side by side (default mesh, m = 10 kg)", _table2),
        ("## 6. The impulse-momentum identity", _identity),
        ("## 7. Non-uniqueness: what fits equally well, and what breaks the tie", _beam_family),
        (None, _tie_breakers),
        ("## 8. The contact law: three readings on the chosen set", _contact_laws),
        ("## 9. Which reading reproduces the paper, and what it costs", _readings),
        ("## 10. What remains out of reach, and why", _out_of_reach),
        ("## 11. Point A and the pulse scenes", _point_a_and_pulse),
        ("## 12. The paper's four conclusions, checked one by one", _conclusions),
        ("## 13. Tolerances the reconstruction supports", _tolerances),
        ("## 14. Files", _files),
    )
    page = Page()
    for heading, write in sections:
        if heading:
            page(heading)
            page("")
        write(page, result)
        page("")
    return "\n".join(page)
