"""Scene builder, cached parallel runner and residuals for scripts/reconstruction/reconstruct.py.

A parameter set is a plain dict (see DEFAULTS). `scene(p, ...)` turns it into a scene dict;
`Runner.run_many` runs scenes (`jobs` at a time, default 2) through the Python package's
`impact.sweep` (in process, GIL released; `backend="cli"`: `impact simulate` subprocesses),
caching the summary subset of every run in a JSON file keyed by the scene text and the sha256
of the solver (the native module, or the binary), so an interrupted search resumes where it
stopped.
"""
from __future__ import annotations

import concurrent.futures as cf
import csv
import hashlib
import json
import math
import os
import subprocess
import tempfile
import threading
import time
from pathlib import Path

import yaml

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
PAPER = ROOT / "reference-data" / "paper"

# Fixed by the reconstruction (steel plate, steel impactor). The rest is searched.
DEFAULTS = {
    "L": 0.200, "W": 0.200, "h": 0.020,          # m
    "E": 207.0e9, "nu": 0.3, "rho": 7850.0,      # plate material
    "sy": 250.0e6, "Et": 1.5e9,                  # yield (Pa), linear tangent modulus (Pa)
    "table": None,                               # optional hardening table [[k, s], ...]
    "r": 0.010,                                  # nose radius, m
    "Es": 207.0e9, "nus": 0.3,                   # impactor
    "law": "paper-m",                            # paper-m | paper-mm | johnson (| paper-r)
    "pairing": "default",                        # default (force on the datum) | literal
}

LAWS = ("paper-m", "paper-mm", "johnson")
PAIRINGS = ("default", "literal")
LAW_TEXT = {
    "paper-m": "eq. (4) evaluated in metres (hidden length l = 1 m)",
    "paper-mm": "eq. (4) evaluated in millimetres (hidden length l = 1 mm)",
    "johnson": "Johnson's 2-D line contact, plate datum at the mid-plane (depth h/2)",
    "paper-r": "eq. (4) with l = r (hypothesis of contact-law.md)",
}
PAIRING_TEXT = {
    "default": "force and indentation datum both at the mid-plane node (energy-consistent)",
    "literal": "indentation from the mid-plane node, force on the top-surface node (the paper read literally)",
    "top": "force and indentation datum both at the top-surface node",
}

# Table 1 impactor (derived in reference-data/paper/impactor-table1.md) and Table 2's.
T1_MASS, T1_V0 = 18.0, 10.0
T2_MASS = 10.0
T2_V0 = (1.25, 2.5, 5.0, 7.5, 10.0, 12.5, 15.0)


def law_block(p: dict) -> dict:
    law = p["law"]
    if law == "paper-m":
        return {"paper": {"length_unit": 1.0}}
    if law == "paper-mm":
        return {"paper": {"length_unit": 1.0e-3}}
    if law == "paper-r":
        return {"paper": {"length_unit": float(p["r"])}}
    if law == "johnson":
        if p["pairing"] == "top":
            raise ValueError("johnson with the top-surface datum is not searched")
        return {"johnson": {"datum_depth": float(p["h"]) / 2}}
    raise ValueError(f"unknown law {law}")


def material_block(p: dict, plastic: bool) -> dict:
    m = {"density": float(p["rho"]), "youngs_modulus": float(p["E"]),
         "poisson_ratio": float(p["nu"])}
    if plastic:
        if p.get("table"):
            hard = {"table": [[float(a), float(b)] for a, b in p["table"]]}
        else:
            hard = {"linear": float(p["Et"])}
        m["plasticity"] = {"yield_stress": float(p["sy"]), "hardening": hard}
    return m


def impactor_block(p: dict, mass: float, v0: float) -> dict:
    imp = {
        "mass": float(mass), "velocity": float(v0), "nose_radius": float(p["r"]),
        "youngs_modulus": float(p["Es"]), "poisson_ratio": float(p["nus"]),
        "contact_law": law_block(p),
    }
    if p["pairing"] == "literal":
        imp["indentation_datum"] = "mid-plane"
        imp["force_node"] = "top-surface"
    elif p["pairing"] == "top":
        imp["indentation_datum"] = "top-surface"
    else:
        imp["indentation_datum"] = "mid-plane"
    return imp


def plate_block(p: dict) -> dict:
    return {"length": float(p["L"]), "width": float(p["W"]), "thickness": float(p["h"])}


def scene(p: dict, *, mass: float, v0: float, plastic: bool, mesh: tuple[int, int],
          probes: dict | None = None, after_contact: float = 0.2e-3, limit: float = 0.02,
          every: float = 1.0e-4, cfl: float = 0.8, element: str = "q4-sri") -> dict:
    s = {
        "plate": plate_block(p),
        "material": material_block(p, plastic),
        "mesh": {"nx": int(mesh[0]), "ny": int(mesh[1]), "element": element, "model": "half"},
        "load": {"impactor": impactor_block(p, mass, v0)},
        "time": {"end": {"after_contact": float(after_contact)}, "limit": float(limit),
                 "dt": {"cfl": float(cfl)}},
        "output": {"every": float(every)},
    }
    if probes:
        s["output"]["probes"] = probes
    return s


def point_a(p: dict) -> dict:
    """Point A: mid-span, bottom surface (see report.md for the choice)."""
    return {"A": {"x": float(p["L"]) / 2, "y": 0.0}}


def pulse_scene(p: dict, *, plastic: bool, mesh: tuple[int, int], force: float, duration: float,
                end: float, every: float = 1.0e-6, cfl: float = 0.8) -> dict:
    return {
        "plate": plate_block(p),
        "material": material_block(p, plastic),
        "mesh": {"nx": int(mesh[0]), "ny": int(mesh[1]), "element": "q4-sri", "model": "half"},
        "load": {"pulse": {"force": float(force), "duration": float(duration)}},
        "time": {"end": float(end), "dt": {"cfl": float(cfl)}},
        "output": {"every": float(every), "probes": point_a(p)},
    }


def dump(s: dict) -> str:
    return yaml.safe_dump(s, sort_keys=False, default_flow_style=None, width=100)


KEEP = ("impulse_Ns", "peak_contact_force_N", "max_plate_displacement_m", "contact_intervals_s",
        "contact_duration_s", "final_impactor_velocity_mps", "max_von_mises_Pa",
        "max_energy_balance_error", "impulse_momentum_error", "dt_s", "n_steps", "n_elements",
        "wall_time_s", "stop_reason", "final_time_s", "contact_law", "indentation_datum",
        "force_node", "plastic", "initial_energy_J", "final_energy_J")


def sha256_file(path: Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


class Runner:
    """Runs scenes `jobs` at a time with a JSON cache on disk: through `impact.sweep` (backend
    "sweep", the package built from python/) or `impact simulate` processes (backend "cli")."""

    def __init__(self, binary: Path, cache_path: Path, jobs: int = 2, backend: str = "cli"):
        self.backend = backend
        if backend == "sweep":
            import impact
            self.binary = Path(impact._impact.__file__)
        else:
            self.binary = Path(binary)
        self.bin_sha = sha256_file(self.binary)
        self.cache_path = Path(cache_path)
        self.jobs = jobs
        self.lock = threading.Lock()
        self.cache: dict = {}
        if self.cache_path.exists():
            self.cache = json.loads(self.cache_path.read_text())
        self.n_run = 0
        self.n_hit = 0
        self.run_wall_s = 0.0
        self._dirty = 0

    def key(self, text: str) -> str:
        return hashlib.sha256((self.bin_sha + "\n" + text).encode()).hexdigest()[:32]

    def save(self) -> None:
        with self.lock:
            self.cache_path.parent.mkdir(parents=True, exist_ok=True)
            tmp = self.cache_path.with_suffix(".tmp")
            tmp.write_text(json.dumps(self.cache, separators=(",", ":")))
            os.replace(tmp, self.cache_path)
            self._dirty = 0

    def _cached(self, text: str) -> dict | None:
        with self.lock:
            res = self.cache.get(self.key(text))
            if res is not None:
                self.n_hit += 1
            return res

    def _store(self, text: str, res: dict, wall_s: float) -> None:
        with self.lock:
            self.cache[self.key(text)] = res
            self.n_run += 1
            self.run_wall_s += wall_s
            self._dirty += 1
            dirty = self._dirty
        if dirty >= 64:
            self.save()

    def _simulate(self, sc: Path, out: Path) -> str | None:
        """One run writing the CLI's files into `out`; the error text of a failed run."""
        if self.backend == "sweep":
            import impact
            try:
                impact.simulate(sc, out=out, threads=1)
                return None
            except (impact.SceneError, impact.RunError) as e:
                return str(e)
        r = subprocess.run([str(self.binary), "simulate", str(sc), "--out", str(out),
                            "--quiet"], capture_output=True, text=True)
        return None if r.returncode == 0 else (r.stderr.strip() or r.stdout.strip())

    def _run_one(self, text: str, keep: Path | None = None) -> dict:
        if keep is None and (res := self._cached(text)) is not None:
            return res
        with tempfile.TemporaryDirectory(prefix="recon-") as tmp:
            sc = Path(tmp) / "scene.yaml"
            sc.write_text(text)
            out = Path(tmp) / "out"
            t0 = time.perf_counter()
            error = self._simulate(sc, out)
            dt = time.perf_counter() - t0
            if error is not None:
                res = {"error": error[-400:]}
            else:
                s = json.loads((out / "summary.json").read_text())
                res = {k2: s[k2] for k2 in KEEP if k2 in s}
                if keep is not None:
                    keep.mkdir(parents=True, exist_ok=True)
                    for f in ("history.csv", "summary.json"):
                        (keep / f).write_bytes((out / f).read_bytes())
                    (keep / "scene.yaml").write_text(text)
        self._store(text, res, dt)
        return res

    def _sweep(self, scenes: list[dict], texts: list[str], which: list[int]) -> dict[int, dict]:
        """The runs `which` (not cached, nothing kept) through `impact.sweep`: scenes with the
        same top-level keys form one sweep whose overrides are those keys' whole subtrees
        (an override replaces the subtree), on `jobs` threads."""
        import impact
        groups: dict[tuple, list[int]] = {}
        for i in which:
            groups.setdefault(tuple(scenes[i]), []).append(i)
        done = {}
        for keys, members in groups.items():
            t0 = time.perf_counter()
            frame = impact.sweep(texts[members[0]], [{k: scenes[i][k] for k in keys}
                                                     for i in members], jobs=self.jobs)
            dt = (time.perf_counter() - t0) / len(members)
            for i, row in zip(members, frame.to_dict("records")):
                error = row.get("error")
                if isinstance(error, str):
                    res = {"error": ("error: " + error)[-400:]}
                else:
                    # a key this run's summary lacks is NaN in the frame (JSON has no NaN)
                    res = {k: _plain(k, row[k]) for k in KEEP if k in row
                           and not (isinstance(row[k], float) and math.isnan(row[k]))}
                self._store(texts[i], res, dt)
                done[i] = res
        return done

    def run_many(self, scenes: list[dict], keep: list[Path | None] | None = None) -> list[dict]:
        texts = [dump(s) for s in scenes]
        keep = keep or [None] * len(texts)
        if self.backend == "sweep":
            results = {i: self._cached(t) for i, (t, k) in enumerate(zip(texts, keep)) if k is None}
            todo = [i for i, r in results.items() if r is None]
            results.update(self._sweep(scenes, texts, todo) if todo else {})
            kept = [i for i, k in enumerate(keep) if k is not None]
            results.update(zip(kept, self._pool(lambda i: self._run_one(texts[i], keep[i]), kept)))
            return [results[i] for i in range(len(texts))]
        return self._pool(lambda i: self._run_one(texts[i], keep[i]), range(len(texts)))

    def _pool(self, run, items) -> list:
        """`run` over `items`, `jobs` at a time (threads: both backends release the GIL while a
        run works: a subprocess wait, or the package's native call)."""
        items = list(items)
        if self.jobs <= 1 or len(items) <= 1:
            return [run(i) for i in items]
        with cf.ThreadPoolExecutor(max_workers=self.jobs) as ex:
            return list(ex.map(run, items))


INT_KEYS = ("n_steps", "n_elements")


def _plain(key: str, value):
    """A DataFrame cell as summary.json holds it: numpy scalars as Python numbers, and the
    integer counts that pandas widened to float (a column with a failed run's NaN) as int."""
    if hasattr(value, "item"):
        value = value.item()
    if key in INT_KEYS and isinstance(value, float) and value.is_integer():
        return int(value)
    return value


def read_paper() -> tuple[dict, list[dict]]:
    t1 = {}
    with open(PAPER / "table1.csv") as f:
        for row in csv.DictReader(f):
            t1[row["quantity"]] = {"elastic": float(row["elastic"]),
                                   "plastic": float(row["elasto_plastic"]), "unit": row["unit"]}
    t2 = []
    with open(PAPER / "table2.csv") as f:
        for row in csv.DictReader(f):
            t2.append({"v0": float(row["initial_velocity_mps"]),
                       "elastic": float(row["elastic_impulse_Ns"]),
                       "plastic": float(row["ep_impulse_Ns"])})
    return t1, t2


T1_KEYS = ("impulse", "max_contact_load", "max_plate_displacement", "contact_duration",
           "impactor_final_velocity", "max_effective_stress_point_a")
T1_LABEL = {
    "impulse": "Impulse (N s)",
    "max_contact_load": "Max. contact load (kN)",
    "max_plate_displacement": "Max. displacement (mm)",
    "contact_duration": "Contact duration (ms)",
    "impactor_final_velocity": "Final velocity (m/s)",
    "max_effective_stress_point_a": "Max. stress at A (MPa)",
}
ROBUST = ("impulse", "max_plate_displacement", "impactor_final_velocity")


def t1_values(res: dict, duration: str = "last") -> dict:
    """Table 1 quantities (in the paper's units) of one run."""
    if "error" in res:
        return {}
    iv = res["contact_intervals_s"]
    dur = (iv[-1][1] if duration == "last" else iv[0][1]) if iv else 0.0
    return {
        "impulse": res["impulse_Ns"],
        "max_contact_load": res["peak_contact_force_N"] / 1e3,
        "max_plate_displacement": res["max_plate_displacement_m"] * 1e3,
        "contact_duration": dur * 1e3,
        "impactor_final_velocity": res["final_impactor_velocity_mps"],
        "max_effective_stress_point_a": res.get("max_von_mises_Pa", {}).get("A", math.nan) / 1e6,
    }


def rel(ours: float, paper: float) -> float:
    return (ours - paper) / abs(paper)

PAPER_UNITS = {"impulse": "N s", "max_contact_load": "kN", "max_plate_displacement": "mm",
               "contact_duration": "ms", "impactor_final_velocity": "m/s",
               "max_effective_stress_point_a": "MPa"}
