"""The reconstruction's page, report.md: its sections in order, each a function that computes
its numbers from search.json's result and fills in its paragraphs from recon_page.md (the
page's prose) and its tables."""
from __future__ import annotations

import math
from functools import cache, partial
from pathlib import Path

import recon_core as rc
from recon_format import ROW_LABEL, ROWS, group_of, md_table, pct

PROSE = Path(__file__).resolve().parent / "recon_page.md"


def mark(rel: float, tol: float) -> str:
    return "yes" if abs(rel) <= tol else "**no**"



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


class Result(dict):
    """search.json's result, with the chosen set's parts the sections read most."""

    @property
    def best(self) -> dict:
        """The chosen set: law, pairing, parameters."""
        return self["best"]

    @property
    def params(self) -> dict:
        """The chosen plate's parameters (SI units)."""
        return self["best"]["params"]

    @property
    def confirm(self) -> dict:
        """The chosen set's confirmation runs on the default mesh."""
        return self["confirm"]

    @property
    def res(self) -> dict:
        """The chosen set's residuals against Tables 1 and 2."""
        return self["confirm"]["res"]

    @property
    def acc(self) -> dict:
        """The chosen set against the targets."""
        return self["confirm"]["acceptance"]


class Page(list):
    """The lines of a Markdown page; `page(line)` appends one."""

    def __call__(self, line: str) -> None:
        self.append(line)


@cache
def _paragraphs() -> dict[str, str]:
    """recon_page.md's paragraphs by name: the lines after `@@ name` up to the next, joined
    with spaces (the file's opening comment is not a paragraph)."""
    text = PROSE.read_text()
    text = text[text.index("-->") + len("-->"):]
    out = {}
    for block in text.split("\n@@ ")[1:]:
        name, _, body = block.partition("\n")
        lines = [line.rstrip() for line in body.strip("\n").split("\n") if line.strip()]
        out[name.strip()] = " ".join(lines)
    return out


def prose(name: str, **values) -> str:
    """Paragraph `name` of recon_page.md with `values` filled in."""
    return _paragraphs()[name].format(**values)


def _title(A: Page, result: Result) -> None:
    """The title, the page's provenance line and the quick-mode warning."""
    A("# Reproducing Dokko & Kim (2004)")
    A("")
    A(prose("title"))
    if result["quick"]:
        A("")
        A(prose("quick"))


def _summary(A: Page, result: Result) -> None:
    """The summary: the chosen set, the targets met, the identity, the search's size."""
    b, c, p, res, acc = result.best, result.confirm, result.params, result.res, result.acc
    fails = [k for k, e in res["t1"].items() if abs(e["rel"]) > (0.05 if k.split(":")[0] in rc.ROBUST else 0.10)]
    A(prose("summary-set", L_mm=p["L"] * 1e3, W_mm=p["W"] * 1e3, h_mm=p["h"] * 1e3,
            E_GPa=p["E"] / 1e9, nu=p["nu"], rho=p["rho"], sy_MPa=p["sy"] / 1e6,
            Et_GPa=p["Et"] / 1e9, r_mm=p["r"] * 1e3, law=b["law"],
            law_text=rc.LAW_TEXT[b["law"]], pairing=b["pairing"],
            pairing_text=rc.PAIRING_TEXT[b["pairing"]]))
    A(prose("summary-targets", targets=acc_text(acc)))
    n_in = sum(1 for k, e in res["t1"].items() if abs(e["rel"]) <= 0.10)
    A(prose("summary-in-band", n_in=n_in,
            robust=", all 6 robust ones within 5 %" if acc.get("robust_pass") else ""))
    if fails:
        A(prose("summary-out-of-band", quantities=", ".join(
            f"{rc.T1_LABEL[k.split(':')[0]]} {ROW_LABEL[k.split(':')[1]].lower()} "
            f"({pct(res['t1'][k]['rel'])})" for k in fails)))
    A(prose("summary-identity", confirm_error=c["max_impulse_momentum_error"],
            search_error=_search_identity_error(result),
            energy_error=c["max_energy_balance_error"]))
    A(prose("summary-search", n_evaluations=len(result["evaluations"]),
            n_runs=result["runs"]["executed"], n_cached=result["runs"]["cache_hits"],
            minutes=result["timing_s"]["total"] / 60))


def _search_identity_error(result: Result) -> float:
    """The largest impulse-momentum identity error over every run of the search."""
    return max(e["max_impulse_momentum_error"] for e in result["evaluations"]
               if not math.isnan(e["max_impulse_momentum_error"]))


def _unknowns(A: Page, result: Result) -> None:
    """Section 1: what the lost figures leave unknown."""
    fixed = result["fixed"]
    A(prose("unknowns", E_GPa=fixed["E"] / 1e9, nu=fixed["nu"], rho=fixed["rho"]))


def _search_method(A: Page, result: Result) -> None:
    """Section 2: the coordinates, the objective and the coarse mesh's check."""
    bud = result["budget"]
    A(prose("coordinates", L_mm=result["ref_L"] * 1e3))
    A("")
    A(md_table(["unknown", "range", "scale"],
               [[s["name"], f"{s['low']:g} - {s['high']:g}", "log" if s["log"] else "linear"]
                for s in result["space"]]
               + [["contact law", ", ".join(bud["laws"]), "-"],
                  ["pairing", ", ".join(bud["pairings"]), "-"]]))
    A("")
    A(prose("objective"))
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
    A(prose("meshes", search_mesh=" x ".join(map(str, result["meshes"]["search"])),
            default_mesh=" x ".join(map(str, result["meshes"]["confirm"])), n_sets=len(ms)))
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
    A(prose("mesh-change", robust=pct(max(d_rob, default=math.nan)).lstrip("+"),
            peak=pct(max(d_pk, default=math.nan)).lstrip("+")))


def _search_stages(A: Page, result: Result) -> None:
    """Section 2, continued: the search's stages and the elastic grid's candidates."""
    bud = result["budget"]
    b = result.best
    A(prose("stages"))
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
    A(prose("elastic-candidates", key=b["key"], candidates="; ".join(cand)))


def _chosen_parameters(A: Page, result: Result) -> None:
    """Section 3: the chosen set against the best set of every reading."""
    b, p, res = result.best, result.params, result.res
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
    mass = p["rho"] * p["L"] * p["W"] * p["h"]
    A(prose("chosen-derived", h_over_L=p["h"] / p["L"], mass=mass,
            ratio_t1=rc.T1_MASS / mass, ratio_t2=rc.T2_MASS / mass,
            stiffness=16 * p["E"] / (1 - p["nu"] ** 2) * p["W"] * p["h"] ** 3 / p["L"] ** 3,
            plastic_load_kN=8 * (2 / math.sqrt(3)) * p["sy"] * p["W"] * p["h"] ** 2 / 4 / p["L"] / 1e3))


def _table1(A: Page, result: Result, hist_plots: list[str]) -> None:
    """Section 4: Table 1 side by side, and which contact duration the paper printed."""
    c, res = result.confirm, result.res
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
    A(prose("table1-targets"))
    A("")
    el_runs = c["runs"][0]
    iv = el_runs["contact_intervals_s"]
    near = [e["elastic_intervals_ms"] for e in result["evaluations"]
            if e.get("elastic_intervals_ms") and abs(e["elastic_intervals_ms"][-1][1] / 0.605 - 1) < 0.15]
    one = [iv_ for iv_ in near if iv_[0][1] > 0.5 * iv_[-1][1]]
    one_st = sorted({e["stage"] for e in result["evaluations"] if e.get("elastic_intervals_ms")
                     and abs(e["elastic_intervals_ms"][-1][1] / 0.605 - 1) < 0.15
                     and e["elastic_intervals_ms"][0][1] > 0.5 * e["elastic_intervals_ms"][-1][1]})
    single = prose("single-contact", n_near=len(near), n_recontact=len(near) - len(one),
                   n_one=len(one), stages=", ".join(one_st) or "-")
    A(prose("contact-duration", n_intervals=len(iv),
            intervals=", ".join(f"{a * 1e3:.3f}-{bb * 1e3:.3f}" for a, bb in iv),
            last_end_ms=iv[-1][1] * 1e3, first_end_ms=iv[0][1] * 1e3,
            first_rel=pct(rc.rel(iv[0][1] * 1e3, 0.605), 0), single=single))
    if hist_plots:
        A("")
    for f in hist_plots:
        A(f"![{f}]({f})")


def _table2(A: Page, result: Result) -> None:
    """Section 5: Table 2 side by side."""
    c, res = result.confirm, result.res
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
    A(prose("table2-legend"))
    A("")
    A("![Table 2](table2.svg)")


def _identity(A: Page, result: Result) -> None:
    """Section 6: the impulse-momentum identity."""
    c = result.confirm
    A(prose("identity", n_confirm=len(c["runs"]), confirm_error=c["max_impulse_momentum_error"],
            n_search=result["runs"]["executed"], search_error=_search_identity_error(result)))


def _beam_family(A: Page, result: Result) -> None:
    """Section 7: the beam family and the contrasts off it."""
    fam = result["family"]
    A(prose("family"))
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
    A(prose("contrasts", factor=fam["factor"]))
    A("")
    rows = []
    for f in fam["contrasts"]:
        ok = f["J"] < 1e5
        rows.append([f["name"], f"{f['L'] * 1e3:.0f}", f"{f['W'] * 1e3:.0f}", f"{f['h'] * 1e3:.1f}",
                     f"{f['J']:.1f}" if ok else "fails"]
                    + [pct(f["rel"].get(k)) if ok and k in f["rel"] else "-" for k in FAMILY_KEYS])
    A(md_table(["change", "L mm", "W mm", "h mm", "J"] + [FAMILY_SHORT[k] for k in FAMILY_KEYS], rows))


def _tie_breakers(A: Page, result: Result) -> None:
    """Section 7, continued: the re-fits at other lengths and what breaks the tie."""
    bud, fam = result["budget"], result["family"]
    c, p, res, acc = result.confirm, result.params, result.res, result.acc
    if result["refit_confirm"]:
        A(prose("refits"))
        A("")
        rows = [[f"{r['L'] * 1e3:.0f}"] + params_row(r["params"])[1:] + [f"{r['J']:.2f}",
                acc_text(r["acceptance"])] for r in result["refit_confirm"]]
        rows.insert(0, [f"{p['L'] * 1e3:.0f} (chosen)"] + params_row(p)[1:]
                    + [f"{c['J']:.2f}", acc_text(acc)])
        A(md_table(["L mm", "W mm", "h mm", "yield MPa", "E_t GPa", "r mm", "J (80x16)",
                    "targets"], rows))
        A("")
    yt = result.get("yield_text")
    A(prose("tie"))
    A("")
    A(_within_family(result))
    if result["refit_confirm"]:
        rf = result["refit_confirm"][0]
        rp = rf["params"]
        same = (rf["acceptance"].get("t2_pass") == acc.get("t2_pass")
                and rf["acceptance"].get("robust_pass") == acc.get("robust_pass"))
        A(prose("tie-refit", L_mm=rf["L"] * 1e3, W_mm=rp["W"] * 1e3, h_mm=rp["h"] * 1e3,
                n_evaluations=bud["refit_fev"], J=rf["J"], J_chosen=c["J"],
                targets=acc_text(rf["acceptance"]),
                verdict=": it meets the same targets, so the data do not pin L." if same else "."))
    okl = [(k, v) for k, v in result["per_law"].items() if v["J"] < 1e5]
    A(prose("tie-readings", readings="; ".join(
        f"{k}: J = {v['J']:.1f}, robust worst {pct(v['acceptance']['robust_worst'])}, "
        f"Table 2 worst {pct(v['acceptance']['t2_worst'])}"
        for k, v in sorted(okl, key=lambda kv: kv[1]["J"]))))
    A(prose("tie-prior", L_mm=p["L"] * 1e3, W_mm=p["W"] * 1e3))
    if yt:
        A(prose("tie-yield-text", sy_MPa=p["sy"] / 1e6, times=2260 / (p["sy"] / 1e6),
                yield_MPa=yt["yield"] / 1e6, J=yt["J"], J_chosen=c["J"],
                targets=acc_text(yt["acceptance"])))


def _within_family(result: Result) -> str:
    """Section 7's first tie-breaker: how much moving along the beam family changes the
    residuals against leaving it, and where the family stops running."""
    fam = result["family"]
    p = result.params
    famok = [f for f in fam["family"] if f["J"] < 1e5]
    fambad = [f for f in fam["family"] if f["J"] >= 1e5]
    parts = [prose("tie-family")]
    base_f = min(famok, key=lambda f: abs(f["L"] - p["L"]))

    def dmax(f):
        return max(abs(f["rel"][k] - base_f["rel"][k]) for k in FAMILY_KEYS[:6]
                   if k in f["rel"] and k in base_f["rel"])
    step = [f for f in famok if abs(f["L"] - p["L"] * fam["factor"]) < 1e-9]
    offs = [(f["name"], dmax(f)) for f in fam["contrasts"][1:] if f["J"] < 1e5]
    if step and offs:
        mild = min(offs, key=lambda t: t[1])
        parts.append(prose("tie-family-step", factor=fam["factor"], L_mm=step[0]["L"] * 1e3,
                           along=pct(dmax(step[0])).lstrip("+"), mild=pct(mild[1]).lstrip("+"),
                           mild_name=mild[0], worst=pct(max(t[1] for t in offs)).lstrip("+")))
    if fambad:
        errs = [e for e in result["evaluations"] if e["stage"] == "family" and not e["res"]["ok"]]
        kinds = {"the contact law's maximum force per width (eq. 4 read in mm has one at "
                 "P* = l^2/(r c))" if "no root" in (e["res"].get("errors") or [""])[0] else
                 "an inverted element" for e in errs}
        parts.append(prose("tie-family-bound", L_mm=min(f["L"] for f in fambad) * 1e3,
                           W_mm=max(f["W"] for f in fambad) * 1e3,
                           limits=" / ".join(sorted(kinds))))
    parts.append(prose("tie-family-jumps"))
    return " ".join(parts)


def _contact_laws(A: Page, result: Result) -> None:
    """Section 8: the three readings of the contact law on the chosen set."""
    b = result.best
    A(prose("laws", law=b["law"]))
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
    A(prose("laws-shift", robust=pct(rob_sh).lstrip("+"), factor=pe["paper-mm"] / pe["paper-m"],
            johnson_kN=pe["johnson"], plastic=pct(ep_sh).lstrip("+")))


def _readings(A: Page, result: Result) -> None:
    """Section 9: which reading reproduces the paper, and what the literal one costs."""
    laws = {(r["law"], r["pairing"]): r for r in result["laws"]}
    b, c, res = result.best, result.confirm, result.res
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
    A(prose("reproducing", law=b["law"], pairing=b["pairing"], law_text=rc.LAW_TEXT[b["law"]],
            pairing_text=rc.PAIRING_TEXT[b["pairing"]], energy_error=c["max_energy_balance_error"]))
    A("")
    if lit:
        lv = lit[0]
        A(prose("literal", law=lv["law"], J=lv["J_coarse"], params=", ".join(
            f"{k} {v}" for k, v in zip(["L", "W", "h", "yield", "E_t", "r"], params_row(lv["params"])))))
        A("")
        if lv.get("coarse"):
            A(prose("literal-coarse"))
            A("")
            A.extend(residual_block(lv["coarse"]))
            A("")
        A(prose("literal-energy", errors=", ".join(
            f"{lw}: {max(laws[(lw, 'literal')][r_].get('max_energy_balance_error', float('nan')) for r_ in ROWS):.0%}"
            for lw in rc.LAWS if all("error" not in laws[(lw, "literal")][r_] for r_ in ROWS))))
        A(prose("literal-mesh", error=short_err(lv["res"].get("errors", ["(no failure)"])[0])))
        A(prose("literal-verdict"))


def _out_of_reach(A: Page, result: Result) -> None:
    """Section 10: what remains out of reach, and why."""
    res, acc = result.res, result.acc
    mst = result.get("mesh_study", [])
    if mst:
        A(prose("mesh-study"))
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
    literal = "" if lit_pk is None else " " + prose("reach-literal-gap", rel=pct(lit_pk))
    A(prose("reach-plastic-peak", ours_kN=pk["ours"], rel=pct(pk["rel"], 0), literal=literal))
    A(prose("reach-elastic-peak", ours_kN=pe["ours"], rel=pct(pe["rel"], 0)))
    sat = result.get("saturation", [])
    A(prose("reach-stress-a", ours_MPa=sa["ours"], rel=pct(sa["rel"], 0)))
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
    A(prose("reach-cap"))
    A(prose("reach-all", targets=acc_text(acc)))


def _point_a_and_pulse(A: Page, result: Result) -> None:
    """Section 11: point A and the pulse scenes."""
    c, p = result.confirm, result.params
    pa = c["runs"][0]["max_von_mises_Pa"], c["runs"][1]["max_von_mises_Pa"]
    names = {"A": "mid-span, bottom surface (chosen)", "A_mid_top": "mid-span, top surface",
             "A_clamp_top": "clamped edge, top", "A_clamp_bottom": "clamped edge, bottom",
             "A_quarter_bottom": "quarter span, bottom"}
    rows = [[names.get(k, k), f"{pa[0][k] / 1e6:.0f}", pct(rc.rel(pa[0][k] / 1e6, 2260)),
             f"{pa[1][k] / 1e6:.0f}", pct(rc.rel(pa[1][k] / 1e6, 285.4))] for k in pa[0]]
    A(prose("point-a"))
    A("")
    A(md_table(["probe", "elastic MPa", "vs 2260", "elasto-plastic MPa", "vs 285.4"], rows))
    A("")
    A(prose("point-a-choice"))
    A("")
    pu = result["pulse"]
    A(prose("pulse", duration_ms=pu["duration_s"] * 1e3, end_ms=pu["end_s"] * 1e3))
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
        A(prose("pulse-elastic-yields", stress_MPa=ve["max_von_mises_Pa"]["A"] / 1e6,
                sy_MPa=p["sy"] / 1e6))
        A("")
    A(prose("pulse-no-reference"))


def _conclusions(A: Page, result: Result) -> None:
    """Section 12: the paper's four conclusions, checked one by one."""
    c, p, res = result.confirm, result.params, result.res
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
    A(prose("conclusions-bound"))


def _tolerances(A: Page, result: Result) -> None:
    """Section 13: the tolerances the reconstruction supports."""
    c, res = result.confirm, result.res
    tol = result["supported_tolerances"]
    A(prose("tolerances"))
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
    A(prose("tolerances-pulse"))


def _files(A: Page, result: Result) -> None:
    """Section 14: the files beside the page."""
    p = result.params
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
    A(prose("rerun"))


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
    page, result = Page(), Result(result)
    for heading, write in sections:
        if heading:
            page(heading)
            page("")
        write(page, result)
        page("")
    return "\n".join(page)
