#!/usr/bin/env python3
"""Calibration is not validation: evidence for the reconstructed plate (issue 10, sections 2, 4).

    scripts/reconstruction/recon_evidence.py             # all three studies (~10 min of one core, nice'd)
    scripts/reconstruction/recon_evidence.py --no-runs   # only what the stored search data gives (seconds)

1. Leave-out study. The reconstruction (scripts/reconstruction/reconstruct.py) fitted one plate to all 26
   numbers of Tables 1 and 2, so agreement with them is calibration. Here each group (the
   elasto-plastic Table 1 row, the elastic row, the Table 2 elastic and elasto-plastic
   impulses) and each single number is left out: the plate is re-chosen without it, by the
   reconstruction's own objective, among the sets the search evaluated on its 40 x 8 mesh
   (search.json), and the left-out numbers are predicted. Those held-out residuals are the
   literature evidence; the in-sample residuals beside them show what fitting buys.
2. V&V 20 bands for each Table 1 comparison: E = S - D against
   u_val = sqrt(u_num^2 + u_input^2 + u_D^2), with u_num from the mesh study of the chosen set
   (40x8, 80x16, 160x32: GCI of the declared 80x16 mesh, k = 2 taken as 95 %, so u = GCI/2;
   Fs = 3 when no order is established), u_input from the spread of comparably good plates
   (uniform over +-spread: spread/sqrt(3)), u_D from the paper's printed digits.
3. The lost mesh. The paper's mesh (Fig. 4) is lost; a 2004 explicit code would use a coarse
   half model. Mesh (10x2, 20x4, and 40x8 from the search) and stress-recovery point at A
   (integration point nearest A, as the solver's probe; or the nodal average at the corner node
   A, which in the half model is the element average of the one element there) are discrete
   unknowns: for each, the continuous unknowns are re-fitted (Nelder-Mead from the chosen set,
   all 12 Table 1 values weighted at their 10 % target, Table 2 at 3 %); reported: whether any
   set reproduces all 12 Table 1 values within 10 %, and, re-fitted without the
   elasto-plastic row, whether its prediction survives.

Writes reference-data/paper/reconstruction/evidence.json and evidence.md. Runs are cached in
out/recon-evidence/runs.json (keyed by the solver binary's sha256 and the scene text).
"""
from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(HERE.parent))
import use_venv  # noqa: E402

use_venv.ensure(__file__, ["numpy", "scipy", "yaml"])

import argparse  # noqa: E402
import json  # noqa: E402
import math  # noqa: E402
import re  # noqa: E402
import subprocess  # noqa: E402
import tempfile  # noqa: E402

sys.path.insert(0, str(HERE))
import recon_core as rc  # noqa: E402
import reconstruct as rs  # noqa: E402

OUT = ROOT / "reference-data" / "paper" / "reconstruction"
ROWS = ("elastic", "plastic")
T1 = [f"{q}:{row}" for row in ROWS for q in rc.T1_KEYS]
T2 = [f"t2 {row}:{v:g}" for row in ROWS for v in rc.T2_V0]
ALL = T1 + T2
GROUPS = {
    "elasto-plastic Table 1 row": [k for k in T1 if k.endswith(":plastic")],
    "elastic Table 1 row": [k for k in T1 if k.endswith(":elastic")],
    "Table 2, elastic impulses": [k for k in T2 if " elastic:" in k],
    "Table 2, elasto-plastic impulses": [k for k in T2 if " plastic:" in k],
}
# the 10 % question of section 4: every Table 1 value at its 10 % target, Table 2 at 3 %
SCALE_10 = {**{k: 0.10 for k in T1}, **{k: 0.03 for k in T2}}


def scale(k: str) -> float:
    return rs.SCALES["t2"] if k.startswith("t2 ") else rs.scale_of(k)


def flat(res: dict) -> dict:
    """{key: relative residual} over the 26 numbers of one evaluation's residuals."""
    out = {}
    for k, v in res["t1"].items():
        out[k] = v["rel"] if isinstance(v, dict) else v[1]
    for k, v in res["t2"].items():
        out[f"t2 {k}"] = v["rel"] if isinstance(v, dict) else v[1]
    return out


def J(rel: dict, keys, scales=None) -> float:
    return sum((rel[k] / (scales[k] if scales else scale(k))) ** 2 for k in keys)


# ---------------------------------------------------------------------------------------------
# 1. leave-out
# ---------------------------------------------------------------------------------------------
def pool(search: dict) -> list[dict]:
    """The complete evaluations on the search mesh: the chosen reading, all 26 numbers."""
    out = []
    for e in search["evaluations"]:
        if (e["law"], e["pairing"]) != (search["confirm"]["law"], search["confirm"]["pairing"]):
            continue
        if tuple(e["mesh"]) != tuple(search["meshes"]["search"]) or not e["res"].get("ok"):
            continue
        rel = flat(e["res"])
        if all(k in rel and math.isfinite(rel[k]) for k in ALL):
            out.append({"stage": e["stage"], "x": e["x"], "L": e["L"], "rel": rel})
    return out


def leave_out(candidates: list[dict]) -> dict:
    full = min(candidates, key=lambda c: J(c["rel"], ALL))
    groups = {}
    for name, keys in GROUPS.items():
        train = [k for k in ALL if k not in keys]
        best = min(candidates, key=lambda c: J(c["rel"], train))
        groups[name] = {
            "keys": keys, "x": best["x"], "L": best["L"], "stage": best["stage"],
            "held_out": {k: best["rel"][k] for k in keys},
            "in_sample": {k: full["rel"][k] for k in keys},
            "train_worst": max(abs(best["rel"][k]) for k in train),
        }
    single = {}
    for k in ALL:
        best = min(candidates, key=lambda c: J(c["rel"], [q for q in ALL if q != k]))
        single[k] = {"held_out": best["rel"][k], "in_sample": full["rel"][k]}
    return {"n_candidates": len(candidates), "full": {"x": full["x"], "L": full["L"]},
            "groups": groups, "single": single}


# ---------------------------------------------------------------------------------------------
# 2. V&V 20 bands
# ---------------------------------------------------------------------------------------------
def printed_digits(v: float) -> float:
    """Half a unit of the last printed digit of a Table 1 value, relative."""
    s = f"{v}"
    dec = len(s.split(".")[1]) if "." in s else 0
    return 0.5 * 10 ** (-dec) / abs(v)


def vv20(search: dict) -> dict:
    ms = {tuple(m["mesh"]): m["t1"] for m in search["mesh_study"] if m.get("ok")}
    parts = search["supported_tolerances"]
    res = search["confirm"]["res"]["t1"]
    out = {}
    for k in T1:
        q, row = k.split(":")
        f1, f2, f3 = (ms[m][k] for m in ((40, 8), (80, 16), (160, 32)))
        d21, d32 = f2 - f1, f3 - f2
        p = math.log(abs(d21 / d32)) / math.log(2.0) if d32 != 0 and d21 * d32 > 0 else None
        if p is not None and 0.5 <= p <= 4.0:
            gci = 1.25 * abs(d32 / f2) * 2 ** p / (2 ** p - 1)
            how = f"GCI, order {p:.2f}, Fs 1.25"
        else:
            gci = 3.0 * abs(d32 / f2)
            how = "no order established: Fs 3 x abs(80x16 - 160x32)"
        u_num = gci / 2.0
        spread = abs(parts.get(f"{k}:parts", {}).get("spread", 0.0))
        u_input = spread / math.sqrt(3.0)
        paper = res[k]["paper"]
        u_d = printed_digits(paper)
        u_val = math.sqrt(u_num ** 2 + u_input ** 2 + u_d ** 2)
        e = res[k]["rel"]
        out[k] = {"S": res[k]["ours"], "D": paper, "E_rel": e, "u_num": u_num, "u_num_how": how,
                  "u_input": u_input, "u_D": u_d, "u_val": u_val,
                  "within_2u": abs(e) <= 2.0 * u_val}
    return out


# ---------------------------------------------------------------------------------------------
# 3. the lost mesh
# ---------------------------------------------------------------------------------------------
def cell_of_a(mesh) -> int:
    """The half model's element with the corner node A (mid-span, bottom): the last of the
    bottom row (elements numbered row by row from the clamp, bottom row first)."""
    return int(mesh[0]) - 1


VM = re.compile(r'<DataArray type="Float64" Name="von_mises_Pa" format="ascii">\s*(.*?)\s*'
                r'</DataArray>', re.S)


class Lost:
    def __init__(self, binary: Path, work: Path):
        self.binary = binary
        self.runner = rc.Runner(binary, work / "runs.json", jobs=1)
        self.fields_cache_path = work / "nodal.json"
        self.fields = (json.loads(self.fields_cache_path.read_text())
                       if self.fields_cache_path.exists() else {})
        self.n_eval = 0

    def nodal_a(self, scene: dict, mesh) -> float:
        """Max over time of the von Mises stress of the element average at A, MPa."""
        s = json.loads(json.dumps(scene))
        s["output"]["fields"] = {"every": 5.0e-6}
        text = rc.dump(s)
        key = self.runner.key(text)
        if key in self.fields:
            return self.fields[key]
        with tempfile.TemporaryDirectory(prefix="recon-ev-") as tmp:
            (Path(tmp) / "s.yaml").write_text(text)
            r = subprocess.run(["nice", str(self.binary), "simulate", str(Path(tmp) / "s.yaml"),
                                "--out", str(Path(tmp) / "o"), "--quiet"],
                               capture_output=True, text=True)
            if r.returncode != 0:
                return math.nan
            vmax = 0.0
            for f in sorted((Path(tmp) / "o" / "fields").glob("*.vtu")):
                m = VM.search(f.read_text())
                vals = m.group(1).split()
                vmax = max(vmax, float(vals[cell_of_a(mesh)]))
        self.fields[key] = vmax / 1e6
        self.fields_cache_path.write_text(json.dumps(self.fields))
        return vmax / 1e6

    def evaluate(self, x: dict, mesh, recovery: str) -> dict | None:
        """Relative residuals of the 26 numbers with the stress at A from `recovery`."""
        p = rs.params(x, "paper-mm", "default")
        tags, scenes = rs.scenes_for(p, mesh)
        results = self.runner.run_many(scenes)
        r = rs.residuals(tags, results)
        self.n_eval += 1
        if not r["ok"]:
            return None
        rel = flat(r)
        if recovery == "nodal":
            for (tab, row, _), sc in zip(tags, scenes):
                if tab == "t1":
                    k = f"max_effective_stress_point_a:{row}"
                    rel[k] = rc.rel(self.nodal_a(sc, mesh),
                                    rs.PAPER_T1["max_effective_stress_point_a"][row])
        return rel

    def refit(self, x0: dict, mesh, recovery: str, keys, fev: int) -> dict:
        best = {"J": math.inf}

        def f(u):
            x = rs.from_unit(u)
            ev = self.evaluate(x, mesh, recovery)
            if ev is None:
                return 1e6
            j = J(ev, keys, SCALE_10)
            if self.n_eval % 20 == 0:
                print(f"  {mesh[0]}x{mesh[1]}/{recovery}: {self.n_eval} evaluations, "
                      f"best J {min(best['J'], j):.2f}", flush=True)
            if j < best["J"]:
                best.update({"J": j, "x": x, "rel": ev})
            return j

        rs.nelder_mead(f, rs.to_unit(x0), fev, 0.08)
        self.runner.save()
        return best


def lost_mesh(search: dict, cand: list[dict], lost: Lost | None, fev: int) -> dict:
    x0 = {k: v for k, v in search["confirm"]["x"].items()}
    out = {}
    # 40 x 8: the search's own evaluations (integration-point recovery only)
    best = min(cand, key=lambda c: J(c["rel"], ALL, SCALE_10))
    out["40x8/gauss"] = summarise(best["rel"], None, "the search's evaluations (no re-fit)")
    if lost is None:
        return out
    for mesh in ((10, 2), (20, 4)):
        for recovery in ("gauss", "nodal"):
            fit = lost.refit(x0, mesh, recovery, ALL, fev)
            held = lost.refit(x0, mesh, recovery, [k for k in ALL if not k.endswith(":plastic")],
                              fev)
            out[f"{mesh[0]}x{mesh[1]}/{recovery}"] = summarise(
                fit.get("rel"), held.get("rel"), f"re-fit, {fev} evaluations", fit.get("x"))
    out["evaluations"] = lost.n_eval
    out["runs"] = {"executed": lost.runner.n_run, "cache_hits": lost.runner.n_hit,
                   "run_wall_s": round(lost.runner.run_wall_s, 1)}
    return out


def summarise(rel: dict | None, held: dict | None, how: str, x: dict | None = None) -> dict:
    if rel is None:
        return {"how": how, "failed": True}
    worst = max(T1, key=lambda k: abs(rel[k]))
    s = {"how": how, "x": x, "t1": {k: rel[k] for k in T1},
         "t2_worst": max(abs(rel[k]) for k in T2),
         "t1_worst_key": worst, "t1_worst": rel[worst],
         "all_12_within_10": all(abs(rel[k]) <= 0.10 for k in T1)}
    if held is not None:
        ep = [k for k in T1 if k.endswith(":plastic")]
        s["held_out_ep_row"] = {k: held[k] for k in ep}
        s["held_out_ep_within_10"] = all(abs(held[k]) <= 0.10 for k in ep)
    return s


# ---------------------------------------------------------------------------------------------
# page
# ---------------------------------------------------------------------------------------------
def pct(v: float) -> str:
    return f"{100 * v:+.1f} %"


def label(k: str) -> str:
    if k.startswith("t2 "):
        row, v = k[3:].split(":")
        return f"Table 2 {'E' if row == 'elastic' else 'EP'} impulse, {v} m/s"
    q, row = k.split(":")
    return f"{rc.T1_LABEL[q]}, {'E' if row == 'elastic' else 'EP'}"


def page(ev: dict) -> str:
    lo = ev["leave_out"]
    lines = [
        "# Calibration and validation evidence for the reconstructed plate",
        "",
        "Written by `scripts/reconstruction/recon_evidence.py` from `search.json` (and, for section 3, its own "
        "coarse-mesh runs). **No validation against experiment has been performed: the paper's "
        "Tables 1 and 2 are computed results of the authors' program, and the plate was "
        "calibrated to all 26 of their numbers.** Agreement with a number the plate was fitted "
        "to is calibration; the evidence is what a re-fit without it predicts.",
        "",
        "## 1. Leave-out study (held-out residuals)",
        "",
        f"Each group is left out, the plate re-chosen by the reconstruction's objective among "
        f"the {lo['n_candidates']} complete sets the search evaluated on its 40 x 8 mesh, and "
        "the left-out numbers predicted (residuals on that mesh; the default mesh moves them by "
        "the mesh column of the reconstruction report's section 13).",
        "",
        "| left out | number | held-out residual | in-sample residual |",
        "|---|---|---|---|",
    ]
    for name, g in lo["groups"].items():
        for k in g["keys"]:
            lines.append(f"| {name} | {label(k)} | {pct(g['held_out'][k])} | "
                         f"{pct(g['in_sample'][k])} |")
    lines += ["", "Summary per group (worst |residual|):", "",
              "| left out | worst held-out | worst in-sample | worst on the rest after the re-fit |",
              "|---|---|---|---|"]
    for name, g in lo["groups"].items():
        wh = max(abs(v) for v in g["held_out"].values())
        wi = max(abs(v) for v in g["in_sample"].values())
        lines.append(f"| {name} | {100 * wh:.1f} % | {100 * wi:.1f} % | "
                     f"{100 * g['train_worst']:.1f} % |")
    lines += ["", "Leave-one-out over the 26 numbers:", "",
              "| number | held-out | in-sample |", "|---|---|---|"]
    for k, s in lo["single"].items():
        lines.append(f"| {label(k)} | {pct(s['held_out'])} | {pct(s['in_sample'])} |")
    lines += ["", "## 2. Uncertainty of each Table 1 comparison (ASME V&V 20)", "",
              "E = S - D (relative to D) against u_val = sqrt(u_num^2 + u_input^2 + u_D^2); "
              "u_num from the mesh study of the chosen set at the declared 80 x 16 mesh, "
              "u_input from the spread of comparably good plates, u_D from the printed digits. "
              "|E| <= 2 u_val: the comparison cannot tell the model from the paper at that "
              "level; beyond it the difference is a model (or reading) difference.", "",
              "| quantity | S | D | E | u_num | u_input | u_D | u_val | abs(E) <= 2 u_val | u_num from |",
              "|---|---|---|---|---|---|---|---|---|---|"]
    for k, b in ev["vv20"].items():
        lines.append(f"| {label(k)} | {b['S']:.4g} | {b['D']:.4g} | {pct(b['E_rel'])} | "
                     f"{100 * b['u_num']:.1f} % | {100 * b['u_input']:.1f} % | "
                     f"{100 * b['u_D']:.2f} % | {100 * b['u_val']:.1f} % | "
                     f"{'yes' if b['within_2u'] else '**no**'} | {b['u_num_how']} |")
    lm = ev["lost_mesh"]
    lines += ["", "## 3. The lost mesh as an unknown", "",
              "Mesh and stress-recovery point at A as discrete unknowns, the plate re-fitted for "
              "each (all 12 Table 1 values at their 10 % target, Table 2 at 3 %). The default "
              "mesh (80 x 16) stays for everything that is not a paper comparison.", "",
              "| mesh / recovery at A | how | EP peak force | EP stress at A | E stress at A | "
              "worst Table 1 | worst Table 2 | all 12 within 10 %? | EP row held out: predicted "
              "peak force, stress at A | survives? |",
              "|---|---|---|---|---|---|---|---|---|---|"]
    for name, s in lm.items():
        if not isinstance(s, dict) or "how" not in s:
            continue
        if s.get("failed"):
            lines.append(f"| {name} | {s['how']} | run failed | | | | | | | |")
            continue
        t = s["t1"]
        held = s.get("held_out_ep_row")
        held_txt = (f"{pct(held['max_contact_load:plastic'])}, "
                    f"{pct(held['max_effective_stress_point_a:plastic'])}" if held else "-")
        surv = ("-" if held is None else ("yes" if s["held_out_ep_within_10"] else "no"))
        lines.append(
            f"| {name} | {s['how']} | {pct(t['max_contact_load:plastic'])} | "
            f"{pct(t['max_effective_stress_point_a:plastic'])} | "
            f"{pct(t['max_effective_stress_point_a:elastic'])} | "
            f"{label(s['t1_worst_key'])} {pct(s['t1_worst'])} | {100 * s['t2_worst']:.1f} % | "
            f"{'yes' if s['all_12_within_10'] else 'no'} | {held_txt} | {surv} |")
    if "runs" in lm:
        r = lm["runs"]
        lines += ["", f"This invocation: {lm['evaluations']} evaluations, {r['executed']} runs "
                      f"executed ({r['cache_hits']} from the cache of earlier invocations), "
                      f"{r['run_wall_s']} s of runs."]
    lines += ["", ev["answer"], "", "## Provenance", "",
              "| item | value |", "|---|---|"]
    lines += [f"| {k} | `{v}` |" for k, v in sorted(ev["provenance"].items())]
    lines.append("")
    return "\n".join(lines)


def answer(lm: dict) -> str:
    found = [n for n, s in lm.items() if isinstance(s, dict) and s.get("all_12_within_10")]
    if not found:
        return ("**Answer.** No mesh and recovery point tried reproduces all 12 Table 1 values "
                "within 10 %: the two out-of-reach values (elasto-plastic peak force, "
                "elasto-plastic stress at A) are not explained by a coarse mesh of this "
                "element alone (table above for how far each gets).")
    surv = [n for n in found if lm[n].get("held_out_ep_within_10")]
    return (f"**Answer.** All 12 Table 1 values within 10 % on: {', '.join(found)}. "
            f"Held out (re-fitted without the elasto-plastic row), the prediction survives on: "
            f"{', '.join(surv) if surv else 'none'}.")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--no-runs", action="store_true", help="only the stored search data")
    ap.add_argument("--impact", default=str(ROOT / "target" / "release" / "impact"))
    ap.add_argument("--work", default=str(ROOT / "out" / "recon-evidence"))
    ap.add_argument("--fev", type=int, default=60, help="Nelder-Mead evaluations per re-fit")
    ap.add_argument("--out", default=str(OUT))
    a = ap.parse_args()
    search = json.loads((OUT / "search.json").read_text())
    cand = pool(search)
    ev = {"leave_out": leave_out(cand), "vv20": vv20(search)}
    lost = None
    if not a.no_runs:
        if not Path(a.impact).exists():
            sys.exit(f"recon_evidence.py: {a.impact} missing: cargo build --release -p "
                     "impact-verification")
        Path(a.work).mkdir(parents=True, exist_ok=True)
        lost = Lost(Path(a.impact), Path(a.work))
    ev["lost_mesh"] = lost_mesh(search, cand, lost, a.fev)
    ev["answer"] = answer(ev["lost_mesh"])
    ev["provenance"] = {
        "command": "scripts/reconstruction/recon_evidence.py " + " ".join(sys.argv[1:]),
        "search_json_sha256": rc.sha256_file(OUT / "search.json"),
        "script_sha256": rc.sha256_file(Path(__file__)),
        "solver_binary_sha256": lost.runner.bin_sha if lost else None,
        "git_head": rs.git("rev-parse", "HEAD"),
    }
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "evidence.json").write_text(json.dumps(ev, indent=1, sort_keys=True) + "\n")
    (out / "evidence.md").write_text(page(ev))
    print(f"wrote {out / 'evidence.json'} and {out / 'evidence.md'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
