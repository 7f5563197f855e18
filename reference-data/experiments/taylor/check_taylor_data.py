#!/usr/bin/env python3
"""Consistency checks of the transcribed Taylor impact shots in this directory.

Plain python3, standard library only. Run from anywhere:

    python3 reference-data/experiments/taylor/check_taylor_data.py

Re-reads ofhc-copper.csv, etp-copper.csv, al-6061-t6.csv, profiles/*.csv,
johnson-cook-constants.csv and the two tables of PROVENANCE.md, and checks what
a transcription slip would break (exit status 1 if any check fails):

  units      every numeric column name ends in its unit (_m, _m_s, _K, _kg_m3, _mm)
  sources    every source key used in a CSV is listed in PROVENANCE.md (section
             "Sources") and in README.md
  ids        shot ids unique over all files, of the form <source>-<material>-<n>
  geometry   Lf < L0; Dm > D0; Xf <= Lf; D0 < W <= Dm (when both are given)
  ranges     density and initial temperature plausible for the material; every
             impact speed inside the range PROVENANCE.md states for its source
  counts     shots per (source, file) equal to the count stated in PROVENANCE.md
  printed    D0, L0, Lf, Xf, Dm and W recomputed from the printed values (in mm,
             as the source file prints them, e.g. "0.895*L0" or "1.5*D0") equal
             the SI columns to round-off
  profiles   every profile file belongs to exactly one existing shot and that
             shot names it; z and r positive, printed mm equal to the SI columns,
             the top of the outline within 2 % of Lf, the radius at the top within
             3 % of D0/2, and W, Dm where marked as read off the outline agree
             with it to 0.15 mm
  constants  the Johnson-Cook table has a unit and a listed source on every row,
             and the OFHC copper constants are those of Johnson & Cook (1983)

Each check is a function taking the loaded data and returning a list of
failure messages, so the tests can feed it deliberately broken copies.
"""
from __future__ import annotations

import copy
import csv
import math
import re
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
SHOT_FILES = ("ofhc-copper.csv", "etp-copper.csv", "al-6061-t6.csv")
TEXT_COLUMNS = {"shot_id", "source", "material", "profile_derived", "profile", "notes"}
UNIT_SUFFIXES = ("_m", "_m_s", "_K", "_kg_m3", "_mm")
# (SI column, printed column) pairs for the lengths
LENGTHS = (
    ("initial_diameter_m", "printed_D0_mm"),
    ("initial_length_m", "printed_L0_mm"),
    ("final_length_m", "printed_Lf_mm"),
    ("undeformed_length_m", "printed_Xf_mm"),
    ("foot_diameter_m", "printed_Dm_mm"),
    ("width_at_0.2L0_m", "printed_W_mm"),
)
# plausible ranges, not data: a slip of a digit or a misplaced decimal point falls outside
DENSITY = {"OFHC copper": (8800, 9000), "ETP copper": (8800, 9000), "6061-T6 aluminium": (2600, 2800)}
TEMPERATURE_K = (250, 1300)
# Johnson & Cook (1983), Table 1, OFHC copper, as widely quoted (see PROVENANCE.md)
JC83_COPPER = {"A": 90e6, "B": 292e6, "n": 0.31, "C": 0.025, "m": 1.09, "melting_temperature": 1356}
REL = 1e-9          # round-off allowed between the printed value and the SI value
PROFILE_MM = 0.15   # agreement of W, Dm with the outline they were read from


def read_csv(path: Path):
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        return list(reader.fieldnames or []), list(reader)


def load(root: Path = HERE) -> dict:
    """Everything the checks look at, as plain lists and strings."""
    data = {"shots": {}, "profiles": {}, "constants": read_csv(root / "johnson-cook-constants.csv"),
            "provenance": (root / "PROVENANCE.md").read_text(),
            "readme": (root / "README.md").read_text()}
    for name in SHOT_FILES:
        data["shots"][name] = read_csv(root / name)
    for p in sorted((root / "profiles").glob("*.csv")):
        data["profiles"]["profiles/" + p.name] = read_csv(p)
    return data


def all_rows(data):
    for name, (_, rows) in data["shots"].items():
        for r in rows:
            yield name, r


def num(s):
    return None if s is None or s.strip() == "" else float(s)


def section(text: str, title: str) -> str:
    """The text of the markdown section '## title' (up to the next '## ')."""
    m = re.search(r"^## " + re.escape(title) + r"\s*$(.*?)(?=^## |\Z)", text, re.M | re.S)
    return m.group(1) if m else ""


def provenance_sources(text: str) -> set[str]:
    return set(re.findall(r"^\|\s*`([a-z0-9]+)`\s*\|", section(text, "Sources"), re.M))


def provenance_counts(text: str) -> dict:
    """{(source, file): (shots, lowest speed, highest speed)} from the table 'Shots per source'."""
    out = {}
    for m in re.finditer(r"^\|\s*`([a-z0-9]+)`\s*\|\s*`([\w.-]+\.csv)`\s*\|\s*(\d+)\s*\|\s*([\d.]+)\s*\|\s*([\d.]+)\s*\|",
                         section(text, "Shots per source"), re.M):
        out[(m.group(1), m.group(2))] = (int(m.group(3)), float(m.group(4)), float(m.group(5)))
    return out


def evaluate_printed(expr: str, d0: float | None = None, l0: float | None = None) -> float:
    """A printed value such as '9.1', '0.895*L0', '1.5*D0' or '0.516*30.9', in mm."""
    if not re.fullmatch(r"\d+(\.\d+)?(\*(\d+(\.\d+)?|D0|L0))?", expr):
        raise ValueError(f"not a printed value: {expr!r}")
    value = 1.0
    for factor in expr.split("*"):
        if factor == "D0":
            value *= d0
        elif factor == "L0":
            value *= l0
        else:
            value *= float(factor)
    return value


# ------------------------------------------------------------------ checks
def check_units(data) -> list[str]:
    bad = []
    tables = [(n, h) for n, (h, _) in data["shots"].items()] + [(n, h) for n, (h, _) in data["profiles"].items()]
    for name, header in tables:
        for col in header:
            if col not in TEXT_COLUMNS and not col.endswith(UNIT_SUFFIXES):
                bad.append(f"{name}: column {col!r} has no unit in its name")
    header, rows = data["constants"]
    if "unit" not in header:
        bad.append("johnson-cook-constants.csv: no unit column")
    for r in rows:
        if not (r.get("unit") or "").strip():
            bad.append(f"johnson-cook-constants.csv: {r.get('material')} {r.get('parameter')} has no unit")
    return bad


def check_sources(data) -> list[str]:
    listed = provenance_sources(data["provenance"])
    used = {r["source"] for _, r in all_rows(data)} | {r["source"] for r in data["constants"][1]}
    bad = [f"source {s!r} is used but not listed in PROVENANCE.md (Sources)" for s in sorted(used - listed)]
    bad += [f"source {s!r} is used but not named in README.md" for s in sorted(used) if f"`{s}`" not in data["readme"]]
    return bad


def check_ids(data) -> list[str]:
    bad, seen = [], {}
    for name, r in all_rows(data):
        sid = r["shot_id"]
        if sid in seen:
            bad.append(f"shot id {sid!r} in {name} repeats one in {seen[sid]}")
        seen[sid] = name
        if not re.fullmatch(r"[a-z0-9]+-[a-z]+-\d+", sid) or not sid.startswith(r["source"] + "-"):
            bad.append(f"{name}: shot id {sid!r} does not read <source>-<material>-<n> with source {r['source']!r}")
    return bad


def check_geometry(data) -> list[str]:
    bad = []
    for name, r in all_rows(data):
        d0, l0 = num(r["initial_diameter_m"]), num(r["initial_length_m"])
        lf, xf = num(r["final_length_m"]), num(r["undeformed_length_m"])
        dm, w = num(r["foot_diameter_m"]), num(r["width_at_0.2L0_m"])
        sid = r["shot_id"]
        if None in (d0, l0, lf):
            bad.append(f"{sid}: D0, L0 and Lf must all be given")
            continue
        if not lf < l0:
            bad.append(f"{sid}: Lf {lf} is not below L0 {l0}")
        if dm is not None and not dm > d0:
            bad.append(f"{sid}: Dm {dm} is not above D0 {d0}")
        if xf is not None and not xf <= lf:
            bad.append(f"{sid}: Xf {xf} exceeds Lf {lf}")
        if w is not None and not d0 < w:
            bad.append(f"{sid}: W {w} is not above D0 {d0}")
        if w is not None and dm is not None and not w <= dm:
            bad.append(f"{sid}: W {w} exceeds Dm {dm}")
    return bad


def check_ranges(data) -> list[str]:
    bad = []
    stated = provenance_counts(data["provenance"])
    for name, r in all_rows(data):
        sid = r["shot_id"]
        lo, hi = DENSITY.get(r["material"], (math.inf, -math.inf))
        rho = num(r["density_kg_m3"])
        if rho is None or not lo <= rho <= hi:
            bad.append(f"{sid}: density {r['density_kg_m3']} outside {lo}-{hi} kg/m^3 for {r['material']!r}")
        t0 = num(r["initial_temperature_K"])
        if t0 is None or not TEMPERATURE_K[0] <= t0 <= TEMPERATURE_K[1]:
            bad.append(f"{sid}: initial temperature {r['initial_temperature_K']} K outside {TEMPERATURE_K}")
        key = (r["source"], name)
        u = num(r["impact_speed_m_s"])
        if key not in stated:
            bad.append(f"{sid}: PROVENANCE.md states no speed range for {key}")
        elif u is None or not stated[key][1] <= u <= stated[key][2]:
            bad.append(f"{sid}: speed {r['impact_speed_m_s']} m/s outside the stated "
                       f"{stated[key][1]:g}-{stated[key][2]:g} m/s of {r['source']}")
    return bad


def check_counts(data) -> list[str]:
    stated = provenance_counts(data["provenance"])
    found = {}
    for name, r in all_rows(data):
        found[(r["source"], name)] = found.get((r["source"], name), 0) + 1
    bad = []
    for key in sorted(set(stated) | set(found)):
        n_stated = stated.get(key, (0,))[0]
        if n_stated != found.get(key, 0):
            bad.append(f"{key[0]} in {key[1]}: {found.get(key, 0)} shots, PROVENANCE.md states {n_stated}")
    return bad


def check_printed(data) -> list[str]:
    bad = []
    for name, r in all_rows(data):
        sid = r["shot_id"]
        try:
            d0 = evaluate_printed(r["printed_D0_mm"])
            l0 = evaluate_printed(r["printed_L0_mm"], d0=d0)
        except (ValueError, TypeError) as e:
            bad.append(f"{sid}: {e}")
            continue
        for si_col, pr_col in LENGTHS:
            si, pr = r[si_col].strip(), r[pr_col].strip()
            if (si == "") != (pr == ""):
                bad.append(f"{sid}: {si_col} and {pr_col} are not both given or both empty")
                continue
            if si == "":
                continue
            try:
                mm = evaluate_printed(pr, d0=d0, l0=l0)
            except (ValueError, TypeError) as e:
                bad.append(f"{sid}: {pr_col}: {e}")
                continue
            if not math.isclose(float(si), mm * 1e-3, rel_tol=REL, abs_tol=0.0):
                bad.append(f"{sid}: {si_col} = {si} m but the printed {pr!r} gives {mm * 1e-3:.10g} m")
    return bad


def check_profiles(data) -> list[str]:
    bad = []
    shots = {r["shot_id"]: r for _, r in all_rows(data)}
    named = {r["profile"]: r["shot_id"] for r in shots.values() if r["profile"].strip()}
    for path in data["profiles"]:
        sid = Path(path).stem
        if sid not in shots:
            bad.append(f"{path}: no shot {sid!r} in the shot files")
        elif shots[sid]["profile"] != path:
            bad.append(f"{path}: shot {sid} names {shots[sid]['profile']!r} instead")
    for path, sid in named.items():
        if path not in data["profiles"]:
            bad.append(f"shot {sid} names {path!r}, which does not exist")
    for path, (header, rows) in data["profiles"].items():
        sid = Path(path).stem
        if not rows:
            bad.append(f"{path}: no points")
            continue
        if sid not in shots:
            continue  # reported above
        r = shots[sid]
        z = [float(p["z_m"]) for p in rows]
        rad = [float(p["radius_m"]) for p in rows]
        for p in rows:
            if not (math.isclose(float(p["z_m"]), float(p["printed_z_mm"]) * 1e-3, rel_tol=REL, abs_tol=1e-15)
                    and math.isclose(float(p["radius_m"]), float(p["printed_radius_mm"]) * 1e-3, rel_tol=REL)):
                bad.append(f"{path}: point {p} SI and printed mm disagree")
        if min(z) < 0 or min(rad) <= 0:
            bad.append(f"{path}: negative z or non-positive radius")
        lf, d0 = float(r["final_length_m"]), float(r["initial_diameter_m"])
        top = max(z)
        if abs(top - lf) > 0.02 * lf:
            bad.append(f"{path}: top of the outline {top:.6g} m is not within 2 % of Lf {lf:.6g} m")
        r_top = rad[z.index(top)]
        if abs(r_top - d0 / 2) > 0.03 * d0 / 2:
            bad.append(f"{path}: radius at the top {r_top:.6g} m is not within 3 % of D0/2 {d0 / 2:.6g} m")
        derived = set(filter(None, r["profile_derived"].split(";")))
        if "Dm" in derived and abs(2 * max(rad) - float(r["foot_diameter_m"])) > PROFILE_MM * 1e-3:
            bad.append(f"{path}: Dm {r['foot_diameter_m']} m is marked as read off the outline, which gives {2 * max(rad):.6g} m")
        if "W" in derived:
            zw = 0.2 * float(r["initial_length_m"])
            pts = sorted(zip(z, rad))
            w = next((2 * (r0 + (r1 - r0) * (zw - z0) / (z1 - z0))
                      for (z0, r0), (z1, r1) in zip(pts, pts[1:]) if z0 <= zw <= z1 and z1 > z0), None)
            if w is None or abs(w - float(r["width_at_0.2L0_m"])) > PROFILE_MM * 1e-3:
                bad.append(f"{path}: W {r['width_at_0.2L0_m']} m is marked as read off the outline, which gives {w} m")
    return bad


def check_constants(data) -> list[str]:
    bad = []
    header, rows = data["constants"]
    for col in ("material", "parameter", "value", "unit", "source"):
        if col not in header:
            bad.append(f"johnson-cook-constants.csv: no column {col!r}")
    if bad:
        return bad
    seen = set()
    for r in rows:
        key = (r["material"], r["parameter"])
        if key in seen:
            bad.append(f"johnson-cook-constants.csv: {key} twice")
        seen.add(key)
        try:
            float(r["value"])
        except ValueError:
            bad.append(f"johnson-cook-constants.csv: {key} value {r['value']!r} is not a number")
    copper = {r["parameter"]: float(r["value"]) for r in rows if r["material"] == "OFHC copper" and r["source"] == "jc83"}
    for p, v in JC83_COPPER.items():
        if p not in copper or not math.isclose(copper[p], v, rel_tol=REL):
            bad.append(f"johnson-cook-constants.csv: OFHC copper {p} = {copper.get(p)}, Johnson & Cook (1983) give {v}")
    return bad


CHECKS = {
    "units": check_units, "sources": check_sources, "ids": check_ids, "geometry": check_geometry,
    "ranges": check_ranges, "counts": check_counts, "printed": check_printed,
    "profiles": check_profiles, "constants": check_constants,
}


def run(data) -> dict[str, list[str]]:
    return {name: fn(copy.deepcopy(data)) for name, fn in CHECKS.items()}


def main() -> int:
    data = load()
    n = sum(len(rows) for _, rows in data["shots"].values())
    print(f"{n} shots in {len(SHOT_FILES)} files, {len(data['profiles'])} profiles")
    results = run(data)
    for name, failures in results.items():
        print(f"  {name:<10} {'ok' if not failures else 'FAIL'}")
        for f in failures:
            print(f"      {f}")
    if any(results.values()):
        return 1
    print("All checks passed.")
    return 0


if __name__ == "__main__":
    sys.exit(main())
