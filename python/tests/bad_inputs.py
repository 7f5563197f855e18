"""The bad-input suite (issue 28): every case of verification/bad-inputs/cases.yaml run with a
timeout and checked.

A case names a tool (``simulate``: ``impact simulate`` on a scene file; ``python``:
``impact.simulate`` on a dict scene; ``diff``, ``report``, ``verify``: those commands on
run folders, a ``results.json`` and a case folder), what it changes in a small valid input
(a field set to a value, a field removed, an edit of the raw text, a file of a run folder
replaced) and what must come of it: the exit status (the exception for Python), what the
message must say, the field it must name and where (``file:line:col`` for a file), the
warnings (exactly those), and for an accepted run sane outputs. Every case also asserts: no
panic, the timeout not reached, and nothing half-written left in the output folder.

``python python/tests/bad_inputs.py`` runs the suite alone and prints the counts by tool
(``--explore`` prints what each case gave, for writing expectations; ``-k TEXT`` selects).
"""
from __future__ import annotations

import argparse
import copy
import json
import math
import os
import re
import select
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

ROOT = Path(__file__).resolve().parents[2]
SUITE = ROOT / "verification" / "bad-inputs"
TIMEOUT_S = 20.0
PANIC = ("panicked at", "RUST_BACKTRACE", "PanicException")
OUTPUT_FILES = {"history.csv", "summary.json", "fields", "fields.pvd"}
TIMING = {"wall_time_s", "setup_time_s", "loop_time_s", "ns_per_element_step", "threads_fallback"}
# Staging folders and locks a run leaves beside its --out when it is not cleaned up.
LEFTOVER = re.compile(r"\.partial-\d+$|\.lock(-\d+-\d+)?$")


# --------------------------------------------------------------------------------------
# Block YAML edits: set, remove, rename a dotted key of a scene written one value per line.


def _key_lines(text: str) -> list[tuple[int, int, str, int]]:
    """(line index, indent, key, column of the value) of every `key:` line."""
    out = []
    for i, raw in enumerate(text.split("\n")):
        if raw.lstrip().startswith("#"):
            continue
        m = re.match(r"^( *)([A-Za-z0-9_.-]+):( |$)", raw)
        if m:
            out.append((i, len(m.group(1)), m.group(2), m.end()))
    return out


def locate(text: str, dotted: str) -> tuple[int, int, int] | None:
    """(line index, indent, value column) of a dotted key, 0-based; None if absent."""
    stack: list[tuple[int, str]] = []
    for i, indent, key, vcol in _key_lines(text):
        while stack and stack[-1][0] >= indent:
            stack.pop()
        stack.append((indent, key))
        if ".".join(k for _, k in stack) == dotted:
            return i, indent, vcol
    return None


def _block_end(lines: list[str], i: int, indent: int) -> int:
    j = i + 1
    while j < len(lines) and (not lines[j].strip() or len(lines[j]) - len(lines[j].lstrip()) > indent):
        j += 1
    return j


def yaml_set(text: str, dotted: str, raw: str) -> str:
    """The text with `dotted: raw` (replacing the key's value and children, or added at the
    end of its parent, parents created as needed)."""
    lines = text.split("\n")
    at = locate(text, dotted)
    if at is None:
        parent, _, leaf = dotted.rpartition(".")
        if not parent:
            if lines and lines[-1] == "":
                lines.insert(len(lines) - 1, f"{leaf}: {raw}".rstrip())
            else:
                lines.append(f"{leaf}: {raw}".rstrip())
            return "\n".join(lines)
        if locate(text, parent) is None:
            text = yaml_set(text, parent, "")
            lines = text.split("\n")
        pi, pindent, _ = locate(text, parent)
        lines.insert(_block_end(lines, pi, pindent), " " * (pindent + 2) + f"{leaf}: {raw}".rstrip())
        return "\n".join(lines)
    i, indent, vcol = at
    key = lines[i][:vcol].rstrip()
    lines[i:_block_end(lines, i, indent)] = [f"{key} {raw}".rstrip()]
    return "\n".join(lines)


def yaml_remove(text: str, dotted: str) -> str:
    lines = text.split("\n")
    at = locate(text, dotted)
    if at is None:
        raise KeyError(dotted)
    i, indent, _ = at
    del lines[i:_block_end(lines, i, indent)]
    return "\n".join(lines)


def yaml_rename(text: str, dotted: str, new: str) -> tuple[str, tuple[int, int]]:
    """The text with the key renamed, and the key's 1-based line and column."""
    lines = text.split("\n")
    i, indent, _ = locate(text, dotted)
    old = dotted.rpartition(".")[2]
    lines[i] = lines[i][:indent] + new + lines[i][indent + len(old):]
    return "\n".join(lines), (i + 1, indent + 1)


def dict_set(scene: dict, dotted: str, value: Any) -> None:
    keys = dotted.split(".")
    d = scene
    for k in keys[:-1]:
        if not isinstance(d.get(k), dict):
            d[k] = {}
        d = d[k]
    d[keys[-1]] = value


def dict_remove(scene: dict, dotted: str) -> None:
    keys = dotted.split(".")
    d = scene
    for k in keys[:-1]:
        d = d[k]
    del d[keys[-1]]


def dict_rename(scene: dict, dotted: str, new: str) -> None:
    keys = dotted.split(".")
    d = scene
    for k in keys[:-1]:
        d = d[k]
    d[new] = d.pop(keys[-1])


def python_value(text: str) -> Any:
    """The Python value a YAML scalar stands for (PyYAML reads 1e300 as a string: YAML 1.1)."""
    special = {".nan": math.nan, ".inf": math.inf, "-.inf": -math.inf, "~": None}
    if text in special:
        return special[text]
    try:
        return int(text)
    except ValueError:
        pass
    try:
        return float(text)
    except ValueError:
        return yaml.safe_load(text)


# --------------------------------------------------------------------------------------
# The table.


@dataclass
class Case:
    id: str
    tool: str
    spec: dict
    expect: dict
    # Where the changed value sits (1-based line, column) in the edited file, if known.
    where: dict = field(default_factory=dict)


def _rule_accepts(rule: Any, x: float) -> bool:
    if rule == "positive":
        return x > 0
    if rule == "non_negative":
        return x >= 0
    if rule == "finite":
        return True
    if rule == "integer":
        return True
    kind, lo, hi = rule[0], float(rule[1]), float(rule[2])  # open | closed | open-closed | closed-open
    left = x > lo if kind in ("open", "open-closed") else x >= lo
    right = x < hi if kind in ("open", "closed-open") else x <= hi
    return left and right


SHOWN = {".nan": "NaN", ".inf": "inf", "-.inf": "-inf"}


def _field_cases(f: dict, values: dict, explore: bool) -> list[Case]:
    """The cases of one numeric field x every bad value."""
    integer = f.get("integer", False)
    cases = []
    for name, v in values.items():
        outcome = f.get(name)
        if outcome is None and name in ("negative", "zero"):
            outcome = "ok" if _rule_accepts(f["rule"], float(v["yaml"])) else {"refused": True}
        if outcome is None:
            outcome = v.get("integer" if integer else "expect", v.get("expect"))
        if outcome is None:
            if not explore:
                raise ValueError(f"{f['field']} x {name}: no expectation")
            outcome = {"exit": -1}
        if outcome == "skip":
            continue
        expect = {"exit": 0} if outcome == "ok" else copy.deepcopy(outcome)
        if expect.pop("refused", False):
            expect["says"] = [f"= {SHOWN.get(v['yaml'], v['yaml'])}"] + f.get("allowed", [])
        expect.setdefault("exit", 2)
        if expect["exit"] != 0 and "at" in f:
            expect.setdefault("at", f["at"])
        if v.get("same_as_base") and expect["exit"] == 0:
            expect.setdefault("same_as_base", True)
        expect.setdefault("field", f["field"])
        value = f'"{f["value"]}"' if name == "quoted" else v["yaml"]
        spec = {"base": f["base"], "set": {f["field"]: value}}
        for tool in ("simulate", "python"):
            if tool == "python" and v.get("python") == "skip":
                continue
            e = copy.deepcopy(expect)
            python = e.pop("python", {})
            if tool == "python":
                e.pop("at", None)
                e.update(python)
            cases.append(Case(f"{tool}:{f['field']}={name}", tool, copy.deepcopy(spec), e))
    return cases


def load_cases(path: Path = SUITE / "cases.yaml", explore: bool = False) -> list[Case]:
    """The generated cases (fields x values), then the cases written out, in table order."""
    table = yaml.safe_load(path.read_text())
    cases: list[Case] = []
    for f in table["fields"]:
        cases += _field_cases(f, table["values"], explore)
    for c in table["cases"]:
        tools = c.get("tools", [c.get("tool", "simulate")])
        for tool in tools:
            e = copy.deepcopy(c.get("expect", {}))
            if tool == "python":
                e.pop("at", None)
                e.update(c.get("python_expect", {}))
            spec = {k: v for k, v in c.items() if k not in ("id", "tool", "tools", "expect", "python_expect")}
            cid = f"{tool}:{c['id']}"
            cases.append(Case(cid, tool, spec, e))
    ids = [c.id for c in cases]
    dup = {i for i in ids if ids.count(i) > 1}
    if dup:
        raise ValueError(f"duplicate case ids: {sorted(dup)}")
    return cases


# --------------------------------------------------------------------------------------
# Running.


@dataclass
class Result:
    case: Case
    exit: int | None = None          # exit status (Python: 0, or 2 for an exception)
    message: str = ""                # stderr (+ stdout), or the exception's text
    warnings: list[str] = field(default_factory=list)
    raised: str | None = None        # Python: the exception's type
    seconds: float = 0.0
    hung: bool = False
    problems: list[str] = field(default_factory=list)
    detail: dict = field(default_factory=dict)

    @property
    def passed(self) -> bool:
        return not self.problems


class Context:
    """The CLI, a scratch folder, and inputs made once (run folders, a results.json)."""

    def __init__(self, cli: Path, scratch: Path, python: str = sys.executable):
        self.cli = Path(cli)
        self.scratch = scratch
        self.python = python
        self.bases = {p.stem: p.read_text() for p in (SUITE / "base").glob("*.yaml")}
        self._made: dict[str, Any] = {}
        self._n = 0

    def folder(self, name: str) -> Path:
        self._n += 1
        d = self.scratch / f"{self._n:04d}-{re.sub(r'[^A-Za-z0-9_.=-]+', '_', name)[:60]}"
        d.mkdir(parents=True)
        return d

    def run(self, args: list[str], cwd: Path | None = None, timeout: float = TIMEOUT_S) -> tuple[int | None, str, str, float, bool]:
        start = time.monotonic()
        try:
            p = subprocess.run([str(a) for a in args], capture_output=True, text=True, timeout=timeout,
                               cwd=cwd, errors="replace")
            return p.returncode, p.stdout, p.stderr, time.monotonic() - start, False
        except subprocess.TimeoutExpired as e:
            out = e.stdout.decode(errors="replace") if isinstance(e.stdout, bytes) else (e.stdout or "")
            err = e.stderr.decode(errors="replace") if isinstance(e.stderr, bytes) else (e.stderr or "")
            return None, out, err, time.monotonic() - start, True

    def base_run(self, name: str) -> Path:
        """A folder with `impact simulate` of the base scene `name` (made once)."""
        key = f"run:{name}"
        if key not in self._made:
            d = self.folder(key) / "run"
            scene = d.parent / "scene.yaml"
            scene.write_text(self.bases[name])
            code, _, err, _, _ = self.run([self.cli, "simulate", scene, "--out", d, "--quiet"])
            if code != 0:
                raise RuntimeError(f"the base scene {name} does not run: {err}")
            self._made[key] = d
        return self._made[key]

    def base_summary(self, name: str) -> dict:
        return json.loads((self.base_run(name) / "summary.json").read_text())

    def verify_out(self) -> Path:
        """A verify output folder of the base case (made once)."""
        key = "verify"
        if key not in self._made:
            root = self.repo(self.bases_case(), None)
            out = root.parent / "verify-out"
            code, _, err, _, _ = self.run([self.cli, "verify", "--root", root, "--out", out])
            if code != 0:
                raise RuntimeError(f"the base case does not pass: {err}")
            self._made[key] = out
        return self._made[key]

    def bases_case(self) -> str:
        return (SUITE / "base" / "case.yaml").read_text()

    def repo(self, case_text: str | None, spec: dict | None) -> Path:
        """A throw-away repository with verification/cases/s/c/{case.yaml,scene.yaml}."""
        root = self.folder("repo") / "repo"
        case_dir = root / "verification" / "cases" / "s" / "c"
        case_dir.mkdir(parents=True)
        (case_dir / "scene.yaml").write_text(self.bases["impact"])
        if case_text is not None:
            (case_dir / "case.yaml").write_text(case_text)
        return root


def _first_difference(old: str, new: str) -> tuple[int, int] | None:
    """(1-based line, column) where `new` first differs from `old`."""
    a, b = old.split("\n"), new.split("\n")
    for i, (x, y) in enumerate(zip(a, b)):
        if x != y:
            col = next((j for j, (p, q) in enumerate(zip(x, y)) if p != q), min(len(x), len(y)))
            return i + 1, col + 1
    return (min(len(a), len(b)) + 1, 1) if len(a) != len(b) else None


def _edit_text(text: str, spec: dict) -> tuple[str, dict]:
    """Applies a case's edits to YAML text; returns the text and where the changed value is."""
    where: dict = {}
    original = text
    for dotted, raw in (spec.get("also") or {}).items():
        text = yaml_set(text, dotted, str(raw))
    for dotted, raw in (spec.get("set") or {}).items():
        text = yaml_set(text, dotted, str(raw))
        at = locate(text, dotted)
        if at:
            i, indent, vcol = at
            where = {"value": (i + 1, vcol + 1), "key": (i + 1, indent + 1)}
    for dotted in spec.get("remove") or []:
        parent = dotted.rpartition(".")[0]
        text = yaml_remove(text, dotted)
        if parent:
            pi, pindent, _ = locate(text, parent)
            where = {"parent": (pi + 1, pindent + 1)}
        else:
            where = {"parent": (1, 1)}
    for dotted, new in (spec.get("rename") or {}).items():
        text, key = yaml_rename(text, dotted, new)
        where = {"key": key}
    for edit in spec.get("text") or []:
        if "replace" in edit:
            old, new = edit["replace"]
            if old not in text:
                raise ValueError(f"text edit: {old!r} not in the base")
            text = text.replace(old, new, 1)
        if "append" in edit:
            text = text + edit["append"]
        if "prepend" in edit:
            text = edit["prepend"] + text
        if "whole" in edit:
            text = edit["whole"]
    where["diff"] = _first_difference(original, text)
    return text, where


def _dict_scene(ctx: Context, spec: dict) -> dict:
    scene = yaml.safe_load(ctx.bases[spec.get("base", "impact")])
    for dotted, raw in (spec.get("also") or {}).items():
        dict_set(scene, dotted, python_value(str(raw)))
    for dotted, raw in (spec.get("set") or {}).items():
        dict_set(scene, dotted, python_value(str(raw)) if not isinstance(raw, (dict, list)) else raw)
    for dotted, value in (spec.get("set_python") or {}).items():
        dict_set(scene, dotted, value)
    for dotted in spec.get("remove") or []:
        dict_remove(scene, dotted)
    for dotted, new in (spec.get("rename") or {}).items():
        dict_rename(scene, dotted, new)
    return scene


def run_simulate(ctx: Context, case: Case) -> Result:
    spec = case.spec
    d = ctx.folder(case.id)
    res = Result(case)
    if "scene_text" in spec:
        text, where = spec["scene_text"], {}
    else:
        text, where = _edit_text(ctx.bases[spec.get("base", "impact")], spec)
    case.where = where
    scene = d / "scene.yaml"
    scene.write_text(text, newline="")
    out = d / "out"
    for name, content in (spec.get("out_holds") or {}).items():
        (out / name).parent.mkdir(parents=True, exist_ok=True)
        (out / name).write_text(content)
    for name, content in (spec.get("beside") or {}).items():
        (d / name).parent.mkdir(parents=True, exist_ok=True)
        (d / name).write_text(content.replace("{pid}", str(os.getpid())))
    args = [ctx.cli, "simulate", spec.get("scene_arg", "scene.yaml").replace("{dir}", str(d)),
            "--out", spec.get("out_arg", "out").replace("{dir}", str(d))]
    args += [a.replace("{dir}", str(d)) for a in spec.get("args", [])]
    before = _listing(d)
    code, stdout, stderr, res.seconds, res.hung = ctx.run(args, cwd=d)
    res.exit, res.message = code, stderr + stdout
    res.warnings = [line[len("warning: "):] for line in stderr.splitlines() if line.startswith("warning: ")]
    res.detail["dir"] = d
    res.detail["before"] = before
    return res


def _listing(d: Path) -> set[str]:
    return {str(p.relative_to(d)) for p in d.rglob("*")}


PY_DRIVER = r'''
import json, math, os, signal, sys, time, warnings
import impact

class Hang(Exception):
    pass

def alarm(*_):
    raise Hang()

signal.signal(signal.SIGALRM, alarm)
for line in open(sys.argv[1]):
    job = json.loads(line)
    scene = job["scene"]
    def restore(v):
        if isinstance(v, dict):
            if set(v) == {"__float__"}:
                return float(v["__float__"])
            return {k: restore(x) for k, x in v.items()}
        if isinstance(v, list):
            return [restore(x) for x in v]
        return v
    scene = restore(scene)
    if job.get("as_text"):
        scene = job["as_text"]
    kwargs = restore(job.get("kwargs", {}))
    out = {"id": job["id"]}
    start = time.monotonic()
    caught = []
    signal.setitimer(signal.ITIMER_REAL, job["timeout"])
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            run = impact.simulate(scene, **kwargs)
        out["exit"] = 0
        out["summary"] = run.summary
        out["run_warnings"] = run.warnings
        out["rows"] = len(run.history.get("time_s", []))
        out["warnings"] = [str(w.message) for w in caught if issubclass(w.category, impact.SceneWarning)]
        out["other_warnings"] = [str(w.message) for w in caught if not issubclass(w.category, impact.SceneWarning)]
    except Hang:
        out["hung"] = True
    except BaseException as e:
        out["exit"] = 2
        out["raised"] = type(e).__name__
        out["message"] = str(e)
        out["warnings"] = [str(w.message) for w in caught if issubclass(w.category, impact.SceneWarning)]
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
    out["seconds"] = time.monotonic() - start
    print(json.dumps(out, default=str), flush=True)
'''


def _jsonable(v: Any) -> Any:
    if isinstance(v, float) and not math.isfinite(v):
        return {"__float__": repr(v)}
    if isinstance(v, dict):
        return {k: _jsonable(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_jsonable(x) for x in v]
    return v


def run_python_batch(ctx: Context, cases: list[Case]) -> list[Result]:
    """The Python cases in one driver process (restarted after a case that hangs)."""
    jobs = []
    for c in cases:
        d = ctx.folder(c.id)
        kwargs = dict(c.spec.get("kwargs", {}))
        if "out" in kwargs:
            kwargs["out"] = str(d / kwargs["out"])
        scene = _dict_scene(ctx, c.spec) if "scene_python" not in c.spec else c.spec["scene_python"]
        job = {"id": c.id, "scene": _jsonable(scene), "kwargs": _jsonable(kwargs), "timeout": TIMEOUT_S}
        if "scene_text" in c.spec:
            job["as_text"] = c.spec["scene_text"]
        jobs.append((c, d, job))
    results: dict[str, Result] = {}
    pending = list(jobs)
    while pending:
        env = dict(os.environ, PYTHONWARNINGS="default")
        # The jobs in a file (a pipe would fill while the driver's answers are not yet read).
        jobs_file = ctx.folder("python-jobs") / "jobs.jsonl"
        jobs_file.write_text("".join(json.dumps(j) + "\n" for _, _, j in pending))
        proc = subprocess.Popen([ctx.python, "-c", PY_DRIVER, str(jobs_file)], stdout=subprocess.PIPE,
                                stderr=subprocess.DEVNULL, text=True, env=env)
        assert proc.stdout
        done = 0
        for c, d, _ in pending:
            ready, _, _ = select.select([proc.stdout], [], [], TIMEOUT_S + 10.0)
            line = proc.stdout.readline() if ready else ""
            res = Result(c)
            res.detail["dir"] = d
            if not line:
                res.hung = True
                res.message = "no answer from the Python driver" + ("" if ready else " (timeout)")
                proc.kill()
                results[c.id] = res
                done += 1
                break
            got = json.loads(line)
            res.hung = bool(got.get("hung"))
            res.exit = got.get("exit")
            res.message = got.get("message", "")
            res.raised = got.get("raised")
            res.warnings = got.get("warnings", [])
            res.seconds = got.get("seconds", 0.0)
            res.detail.update({k: got[k] for k in ("summary", "run_warnings", "other_warnings", "rows") if k in got})
            results[c.id] = res
            done += 1
        else:
            proc.wait(timeout=30)
        pending = pending[done:]
    return [results[c.id] for c in cases]


def run_diff(ctx: Context, case: Case) -> Result:
    spec = case.spec
    d = ctx.folder(case.id)
    a = d / "A"
    b = d / "B"
    shutil.copytree(ctx.base_run(spec.get("a", "impact")), a)
    if spec.get("b_from"):
        shutil.copytree(ctx.base_run(spec["b_from"]), b)
    else:
        shutil.copytree(ctx.base_run(spec.get("a", "impact")), b)
    for name, content in (spec.get("b_files") or {}).items():
        target = b / name
        if content is None:
            if target.is_dir():
                shutil.rmtree(target)
            else:
                target.unlink()
        elif content == "<folder>":
            target.unlink()
            target.mkdir()
        else:
            target.write_text(content)
    if "history" in spec:
        rows = (b / "history.csv").read_text().split("\n")
        header, body = rows[0], [r for r in rows[1:] if r]
        body = _history_edit(header, body, spec["history"])
        (b / "history.csv").write_text("\n".join([header] + body) + "\n" if body is not None else header + "\n")
    if "summary" in spec:
        s = json.loads((b / "summary.json").read_text())
        for k, v in spec["summary"].items():
            if v == "<remove>":
                s.pop(k)
            else:
                s[k] = v
        (b / "summary.json").write_text(json.dumps(s, indent=2))
    if "b_arg" in spec:
        b = Path(spec["b_arg"].replace("{dir}", str(d)))
    args = [ctx.cli, "diff", a, b] + spec.get("args", [])
    res = Result(case)
    code, stdout, stderr, res.seconds, res.hung = ctx.run(args, cwd=d)
    res.exit, res.message = code, stderr + stdout
    res.detail["stdout"] = stdout
    return res


def _history_edit(header: str, body: list[str], edit: dict) -> list[str] | None:
    cols = header.split(",")
    if "cell" in edit:
        row, col, value = edit["cell"]
        cells = body[row].split(",")
        cells[cols.index(col)] = value
        body[row] = ",".join(cells)
    if edit.get("swap"):
        i, j = edit["swap"]
        body[i], body[j] = body[j], body[i]
    if edit.get("twice"):
        body = body + body
    if edit.get("repeat_row") is not None:
        body.insert(edit["repeat_row"], body[edit["repeat_row"]])
    if edit.get("truncate_last"):
        body[-1] = body[-1][: len(body[-1]) // 2].rstrip(",")
    if edit.get("extra_field"):
        body[0] = body[0] + ",1.0"
    if edit.get("header_only"):
        return None
    if edit.get("shift_time") is not None:
        out = []
        for r in body:
            cells = r.split(",")
            cells[0] = repr(float(cells[0]) + edit["shift_time"])
            out.append(",".join(cells))
        body = out
    return body


def run_report(ctx: Context, case: Case) -> Result:
    spec = case.spec
    d = ctx.folder(case.id)
    src = d / "from"
    shutil.copytree(ctx.verify_out(), src)
    results = src / "results.json"
    if "results_text" in spec:
        results.write_text(spec["results_text"])
    if "results_folder" in spec:
        results.unlink()
        results.mkdir()
    for edit in spec.get("results") or []:
        r = json.loads(results.read_text())
        path, op = edit["at"], edit.get("op", "set")
        parent, key = _json_parent(r, path)
        if op == "remove":
            del parent[key]
        elif op == "append_copy":
            parent[key].append(copy.deepcopy(parent[key][0]))
        else:
            parent[key] = edit["value"]
        results.write_text(json.dumps(r, indent=2))
    out = d / "report"
    args = [ctx.cli, "report", "--from", spec.get("from_arg", "from"), "--out", "report"] + spec.get("args", [])
    res = Result(case)
    code, stdout, stderr, res.seconds, res.hung = ctx.run(args, cwd=d)
    res.exit, res.message = code, stderr + stdout
    res.detail["report"] = out
    return res


def _json_parent(r: Any, path: str) -> tuple[Any, Any]:
    parts = [int(p) if p.isdigit() else p for p in re.split(r"[.\[\]]+", path) if p]
    node = r
    for p in parts[:-1]:
        node = node[p]
    return node, parts[-1]


def run_verify(ctx: Context, case: Case) -> Result:
    spec = case.spec
    text, where = _edit_text(ctx.bases_case(), spec)
    case.where = where
    root = ctx.repo(None, spec)
    case_dir = root / "verification" / "cases" / "s" / "c"
    if spec.get("case_yaml") == "<folder>":
        (case_dir / "case.yaml").mkdir()
    elif spec.get("case_yaml") == "<missing>":
        pass
    else:
        (case_dir / "case.yaml").write_text(text)
    if "scene" in spec:
        scene_text, _ = _edit_text(ctx.bases["impact"], spec["scene"])
        (case_dir / "scene.yaml").write_text(scene_text)
    out = root.parent / "out"
    args = [ctx.cli, "verify", "--root", root, "--out", out] + spec.get("args", [])
    res = Result(case)
    code, stdout, stderr, res.seconds, res.hung = ctx.run(args, cwd=root.parent)
    res.exit, res.message = code, stderr + stdout
    results = out / "results.json"
    if results.is_file():
        try:
            r = json.loads(results.read_text())
            rows = [k for c in r.get("cases", []) for k in c.get("checks", [])]
            res.detail["rows"] = rows
            res.message += "\n" + "\n".join(f"{k.get('status')} {k.get('id')}: {k.get('message', '')}" for k in rows)
        except json.JSONDecodeError:
            pass
    return res


# --------------------------------------------------------------------------------------
# Checking.


def check(ctx: Context, res: Result) -> Result:
    c, e, p = res.case, res.case.expect, res.problems
    if res.hung:
        p.append(f"no answer within {TIMEOUT_S:.0f} s (hang)")
        return res
    for word in PANIC:
        if word in res.message or (res.raised or "") == word:
            p.append(f"panic text {word!r} in the output")
    want_exit = e.get("exit", 0)
    if c.tool == "python":
        want = e.get("raises", None if want_exit == 0 else "SceneError")
        if want is None and res.exit != 0:
            p.append(f"raised {res.raised}: {res.message[:300]}")
        elif want is not None and res.raised != want:
            p.append(f"expected {want}, got {res.raised or 'no exception'}: {res.message[:300]}")
    elif res.exit != want_exit:
        p.append(f"exit {res.exit}, expected {want_exit}: {res.message[-600:]}")
    msg = res.message
    for part in e.get("says", []):
        if part not in msg:
            p.append(f"the message does not say {part!r}: {msg[-600:]}")
    if res.exit != 0 and e.get("field"):
        if e["field"] not in msg:
            p.append(f"the message does not name the field {e['field']!r}: {msg[-600:]}")
    _check_location(res)
    _check_warnings(res)
    if c.tool == "simulate":
        _check_out_dir(res)
        if res.exit == 0:
            _check_outputs(ctx, res)
    if c.tool == "python":
        if res.exit == 0:
            _check_python_run(ctx, res)
        d = res.detail["dir"]
        left = [n for n in _listing(d) if LEFTOVER.search(n)]
        if left:
            p.append(f"left behind: {left}")
        out = c.spec.get("kwargs", {}).get("out")
        if out and not Path(out).is_absolute() and res.exit != 0 and (d / out).exists():
            p.append("the refused run left its out= folder")
    if c.tool == "report":
        _check_report(res)
    if c.tool == "diff" and "last_line" in e:
        last = res.detail["stdout"].strip().splitlines()[-1] if res.detail["stdout"].strip() else ""
        if e["last_line"] not in last:
            p.append(f"the last line {last!r} does not say {e['last_line']!r}")
    return res


def _check_location(res: Result) -> None:
    c, e = res.case, res.case.expect
    at = e.get("at", "value" if (c.tool == "simulate" and res.exit != 0 and c.spec.get("set")) else
               "parent" if (c.tool == "simulate" and res.exit != 0 and c.spec.get("remove")) else None)
    if c.tool == "python":
        if res.exit != 0 and res.raised == "SceneError" and "<dict>" not in res.message and e.get("dict_named", True) \
                and "scene_text" not in c.spec and "scene_python" not in c.spec:
            res.problems.append(f"the dict scene is not named <dict>: {res.message[:300]}")
        return
    if at is None or at == "none":
        return
    file = e.get("file", "scene.yaml" if c.tool == "simulate" else "case.yaml")
    if at == "file":
        want = f"{file}: "
        if want not in res.message:
            res.problems.append(f"the message does not name {want!r}: {res.message[-500:]}")
        return
    if re.fullmatch(r"\d+:\d+", str(at)):
        where = tuple(int(x) for x in str(at).split(":"))
    elif at == "line":
        pos = c.where.get("value") or c.where.get("key") or c.where.get("parent") or c.where.get("diff")
        if pos is None:
            res.problems.append("no position known for this case")
            return
        line = pos[0]
        if not re.search(rf"{re.escape(file)}:{line}:\d+", res.message):
            res.problems.append(f"the message does not point at line {line} of {file}: {res.message[-500:]}")
        return
    else:
        where = c.where.get(at)
        if where is None:
            res.problems.append(f"no {at!r} position known for this case")
            return
    want = f"{file}:{where[0]}:{where[1]}"
    if want not in res.message:
        res.problems.append(f"the message does not point at {want}: {res.message[-500:]}")


def _check_warnings(res: Result) -> None:
    want = res.case.expect.get("warns", [])
    if res.case.tool not in ("simulate", "python"):
        return
    got = res.warnings
    for w in want:
        if not any(w in g for g in got):
            res.problems.append(f"no warning says {w!r}; warnings: {got}")
    for g in got:
        if not any(w in g for w in want):
            res.problems.append(f"unexpected warning: {g}")
    if res.case.tool == "simulate" and res.exit == 0 and got:
        summary = res.detail["dir"] / "out" / "summary.json"
        if summary.is_file():
            kept = json.loads(summary.read_text()).get("warnings", [])
            if kept != got:
                res.problems.append(f"summary.json's warnings {kept} are not those printed {got}")


def _check_out_dir(res: Result) -> None:
    d: Path = res.detail["dir"]
    out = Path(res.case.spec.get("out_arg", "out").replace("{dir}", str(d)))
    out = out if out.is_absolute() else d / out
    after = _listing(d)
    leaves = set(res.case.expect.get("leaves", []))
    left = sorted(n for n in after if LEFTOVER.search(n) and n not in leaves)
    if left:
        res.problems.append(f"left beside or in the output folder: {left}")
    if res.exit != 0:
        new = sorted(after - res.detail["before"])
        if new and not res.case.expect.get("out_may_exist"):
            res.problems.append(f"a refused run left files: {new[:5]}")


def _finite_numbers(v: Any, at: str, bad: list[str]) -> None:
    if isinstance(v, bool) or v is None or isinstance(v, str):
        return
    if isinstance(v, (int, float)):
        if not math.isfinite(v):
            bad.append(at)
    elif isinstance(v, dict):
        for k, x in v.items():
            _finite_numbers(x, f"{at}.{k}" if at else k, bad)
    elif isinstance(v, list):
        for i, x in enumerate(v):
            _finite_numbers(x, f"{at}[{i}]", bad)


def _check_summary(ctx: Context, res: Result, summary: dict) -> None:
    bad: list[str] = []
    _finite_numbers(summary, "", bad)
    if bad:
        res.problems.append(f"summary values not finite: {bad[:5]}")
    if not summary.get("n_steps", 0) >= 1:
        res.problems.append(f"n_steps = {summary.get('n_steps')}")
    if res.case.expect.get("same_as_base"):
        base = ctx.base_summary(res.case.spec.get("base", "impact"))
        strip = lambda s: {k: v for k, v in s.items() if k not in TIMING and k != "warnings"}
        if strip(base) != strip(summary):
            diff = [k for k in set(base) | set(summary) if k not in TIMING and base.get(k) != summary.get(k)]
            res.problems.append(f"not the base run's result: {sorted(diff)[:6]}")
    for key, want in (res.case.expect.get("summary") or {}).items():
        if summary.get(key) != want:
            res.problems.append(f"summary {key} = {summary.get(key)!r}, expected {want!r}")


def _check_outputs(ctx: Context, res: Result) -> None:
    d: Path = res.detail["dir"]
    out = d / "out"
    names = {p.name for p in out.iterdir()} if out.is_dir() else set()
    if not {"history.csv", "summary.json"} <= names or names - OUTPUT_FILES - set(res.case.spec.get("out_holds") or {}):
        res.problems.append(f"the output folder holds {sorted(names)}")
        return
    _check_summary(ctx, res, json.loads((out / "summary.json").read_text()))
    rows = (out / "history.csv").read_text().splitlines()
    times = []
    for r in rows[1:]:
        cells = [float(x) for x in r.split(",")]
        if not all(math.isfinite(x) for x in cells):
            res.problems.append(f"history.csv holds a value that is not finite: {r[:120]}")
            break
        times.append(cells[0])
    if any(b <= a for a, b in zip(times, times[1:])) or not times:
        res.problems.append("history.csv's time_s does not strictly increase")


def _check_python_run(ctx: Context, res: Result) -> None:
    summary = res.detail.get("summary")
    if not isinstance(summary, dict):
        res.problems.append("no summary")
        return
    _check_summary(ctx, res, summary)
    if res.detail.get("run_warnings", []) != res.warnings:
        res.problems.append(f"Run.warnings {res.detail.get('run_warnings')} are not the SceneWarnings {res.warnings}")
    if res.detail.get("other_warnings"):
        res.problems.append(f"other warnings: {res.detail['other_warnings']}")
    if res.detail.get("rows", 0) < 1:
        res.problems.append("an empty history")


def _check_report(res: Result) -> None:
    out: Path = res.detail["report"]
    if res.exit != 0:
        if out.exists():
            res.problems.append("a refused report left its --out folder")
        return
    md = out / "report.md"
    if not md.is_file():
        res.problems.append("no report.md")
        return
    text = md.read_text()
    for part in res.case.expect.get("report_says", []):
        if part not in text:
            res.problems.append(f"report.md does not say {part!r}")
    for part in res.case.expect.get("report_not", []):
        if part in text:
            res.problems.append(f"report.md says {part!r}")


RUNNERS = {"simulate": run_simulate, "diff": run_diff, "report": run_report, "verify": run_verify}


def run_all(cli: Path, scratch: Path, cases: list[Case], python: str = sys.executable) -> list[Result]:
    ctx = Context(cli, scratch, python)
    results: dict[str, Result] = {}
    py = [c for c in cases if c.tool == "python"]
    for r in run_python_batch(ctx, py) if py else []:
        results[r.case.id] = check(ctx, r)
    for c in cases:
        if c.tool == "python":
            continue
        special = c.spec.get("special")
        if special:
            r = SPECIALS[special](ctx, c)
        else:
            r = RUNNERS[c.tool](ctx, c)
        results[c.id] = check(ctx, r) if not special else r
    return [results[c.id] for c in cases]


# --------------------------------------------------------------------------------------
# Cases that need more than one process: runs at once into one folder, Ctrl-C.


def _long_scene(ctx: Context) -> str:
    """The tiny pulse run for seconds of wall time (3.4 million steps to its end)."""
    text = yaml_set(ctx.bases["pulse"], "time.end", "5.0")
    text = yaml_set(text, "output.every", "1.0e-3")
    return text


def special_concurrent(ctx: Context, case: Case) -> Result:
    """A second run into the folder a first run is writing into is refused naming the other
    run and its lock; the first finishes (or is stopped) and the lock is gone."""
    res = Result(case)
    d = ctx.folder(case.id)
    (d / "long.yaml").write_text(_long_scene(ctx))
    (d / "short.yaml").write_text(ctx.bases["impact"])
    first = subprocess.Popen([str(ctx.cli), "simulate", "long.yaml", "--out", "out", "--quiet"], cwd=d,
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 10
        while not (d / ".out.lock").exists() and time.monotonic() < deadline:
            time.sleep(0.01)
        code, out, err, res.seconds, res.hung = ctx.run([ctx.cli, "simulate", "short.yaml", "--out", "out"], cwd=d)
        res.exit, res.message = code, err + out
        first.send_signal(signal.SIGINT)
        first_err = first.communicate(timeout=TIMEOUT_S)[1]
    finally:
        if first.poll() is None:
            first.kill()
    e = case.expect
    if code != 2:
        res.problems.append(f"the second run exited {code}: {res.message[-400:]}")
    for part in e.get("says", []):
        if part not in res.message:
            res.problems.append(f"the refusal does not say {part!r}: {res.message[-400:]}")
    if first.returncode != 130:
        res.problems.append(f"the first run, stopped by SIGINT, exited {first.returncode}: {first_err[-300:]}")
    left = sorted(n for n in _listing(d) if LEFTOVER.search(n) or n.startswith("out"))
    if left:
        res.problems.append(f"left behind: {left}")
    return res


def special_sigint(ctx: Context, case: Case) -> Result:
    """SIGINT stops a run within a second, exit 130, nothing left in or beside --out."""
    res = Result(case)
    d = ctx.folder(case.id)
    (d / "long.yaml").write_text(_long_scene(ctx))
    proc = subprocess.Popen([str(ctx.cli), "simulate", "long.yaml", "--out", "out", "--quiet"], cwd=d,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(0.5)
    start = time.monotonic()
    proc.send_signal(signal.SIGINT)
    try:
        _, err = proc.communicate(timeout=TIMEOUT_S)
    except subprocess.TimeoutExpired:
        proc.kill()
        res.hung = True
        res.problems.append("SIGINT did not stop the run")
        return res
    res.seconds = time.monotonic() - start
    res.exit, res.message = proc.returncode, err
    if proc.returncode != 130:
        res.problems.append(f"exit {proc.returncode} after SIGINT: {err[-300:]}")
    if res.seconds > 2.0:
        res.problems.append(f"stopped {res.seconds:.1f} s after SIGINT")
    for part in case.expect.get("says", []):
        if part not in err:
            res.problems.append(f"does not say {part!r}: {err[-300:]}")
    left = sorted(n for n in _listing(d) if n != "long.yaml")
    if left:
        res.problems.append(f"left behind: {left}")
    return res


SPECIALS = {"concurrent": special_concurrent, "sigint": special_sigint}


def counts(results: list[Result]) -> dict[str, tuple[int, int]]:
    out: dict[str, list[int]] = {}
    for r in results:
        n = out.setdefault(r.case.tool, [0, 0])
        n[0] += 1
        n[1] += r.passed
    return {k: (v[0], v[1]) for k, v in sorted(out.items())}


def summary_line(results: list[Result], seconds: float | None = None) -> str:
    c = counts(results)
    total = sum(n for n, _ in c.values())
    passed = sum(p for _, p in c.values())
    parts = ", ".join(f"{tool} {p}/{n}" for tool, (n, p) in c.items())
    hangs = sum(r.hung for r in results)
    panics = sum(any("panic" in x for x in r.problems) for r in results)
    t = f" in {seconds:.1f} s" if seconds is not None else ""
    return f"bad-input suite: {passed} of {total} cases pass ({parts}); {hangs} hangs, {panics} panics{t}"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cli", default=os.environ.get("IMPACT_BIN", ROOT / "target" / "release" / "impact"))
    ap.add_argument("-k", default="", help="only cases whose id contains this")
    ap.add_argument("--explore", action="store_true", help="print what every case gave")
    ap.add_argument("--keep", action="store_true", help="keep the scratch folder")
    args = ap.parse_args()
    cases = [c for c in load_cases(explore=args.explore) if args.k in c.id]
    scratch = Path(tempfile.mkdtemp(prefix="bad-inputs-"))
    start = time.monotonic()
    try:
        results = run_all(Path(args.cli), scratch, cases)
    finally:
        if not args.keep:
            shutil.rmtree(scratch, ignore_errors=True)
    for r in results:
        if args.explore or not r.passed:
            status = "ok  " if r.passed else "FAIL"
            print(f"{status} {r.case.id}: exit {r.exit} {r.raised or ''} ({r.seconds:.2f} s)")
            print(f"     message: {r.message.strip()[-400:]!r}")
            if r.warnings:
                print(f"     warnings: {r.warnings}")
            for prob in r.problems:
                print(f"     - {prob}")
    print(summary_line(results, time.monotonic() - start))
    return 0 if all(r.passed for r in results) else 1


if __name__ == "__main__":
    sys.exit(main())
