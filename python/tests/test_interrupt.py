"""Ctrl-C during sweeps and uncertainty studies (defect reported by a user: a study went on
running, printed a traceback and could leave a half-written output folder). Checked against
the CLI's contract for `impact simulate` (staged output, solver/src/output/out_dir.rs; Ctrl-C
leaves the output folder as it was): a local sweep stops within a second of SIGINT although
its runs under way take seconds (they must be stopped, not waited for); the study script
(scripts/uq-study.py), on the local pool and on Dask, prints one line, exits 130 within the
bound and leaves the previous output as it was, with no staging folder beside it; and the
staging moves files in only once all are written. No timing luck: SIGINT comes from a hook
after the first run, or once the script says its study runs, whose runs (~6 s each, hundreds)
outlast every bound many times over."""
from __future__ import annotations

import os
import select
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest
from helpers import ROOT

import impact
from impact import _sweep

PLASTIC = ROOT / "verification" / "scenes" / "paper-plastic.yaml"
# A run of paper-plastic.yaml on a 160 x 32 mesh takes seconds; on 20 x 4, a few ms.
SLOW, FAST = {"mesh.nx": 160, "mesh.ny": 32}, {"mesh.nx": 20, "mesh.ny": 4}
OWNED = ("uq.md", "uq.json", "study*-*.svg")


def previous_output(out: Path) -> dict[str, str]:
    """An earlier complete output in ``out`` (and a file of the user's), as written."""
    out.mkdir()
    files = {"uq.md": "previous page\n", "uq.json": "{}\n", "study1-indices.svg": "<svg/>\n",
             "notes.txt": "the user's\n"}
    for name, text in files.items():
        (out / name).write_text(text)
    return files


@pytest.fixture
def staging():
    """The staging of an output folder (impact._staging)."""
    from impact import _staging

    return _staging


def contents(out: Path) -> dict[str, str]:
    return {p.name: p.read_text() for p in out.iterdir()}


def no_staging_beside(out: Path) -> bool:
    return not [p for p in out.parent.iterdir() if p.name.startswith(f".{out.name}.partial-")]


def test_staging_leaves_the_previous_output_when_interrupted(tmp_path, staging):
    out = tmp_path / "uq"
    before = previous_output(out)
    with pytest.raises(KeyboardInterrupt):
        with staging.staged(out, OWNED) as stage:
            (stage / "study1-indices.svg").write_text("half")
            raise KeyboardInterrupt
    assert contents(out) == before and no_staging_beside(out)


def test_staging_replaces_the_writers_files_and_keeps_the_others(tmp_path, staging):
    out = tmp_path / "uq"
    before = previous_output(out)
    with staging.staged(out, OWNED) as stage:
        assert stage.parent == out.parent and stage.name == f".uq.partial-{os.getpid()}"
        (stage / "uq.md").write_text("new page\n")
        (stage / "study1-cdf-convergence.svg").write_text("<svg/>\n")
        assert contents(out) == before
    assert contents(out) == {"uq.md": "new page\n", "study1-cdf-convergence.svg": "<svg/>\n",
                             "notes.txt": "the user's\n"}
    assert no_staging_beside(out)


def test_ctrl_c_during_the_moves_waits_until_they_are_done(tmp_path, monkeypatch, staging):
    out = tmp_path / "uq"
    previous_output(out)
    replace = os.replace

    def replace_then_ctrl_c(src, dst):
        replace(src, dst)
        signal.raise_signal(signal.SIGINT)

    monkeypatch.setattr(staging.os, "replace", replace_then_ctrl_c)
    with pytest.raises(KeyboardInterrupt):
        with staging.staged(out, OWNED) as stage:
            for name in ("uq.md", "uq.json", "study1-indices.svg"):
                (stage / name).write_text("new\n")
    assert contents(out) == {"uq.md": "new\n", "uq.json": "new\n", "study1-indices.svg": "new\n",
                             "notes.txt": "the user's\n"}
    assert no_staging_beside(out)


def test_a_stale_staging_folder_of_a_dead_writer_is_removed(tmp_path, staging):
    out = tmp_path / "uq"
    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"],
                          capture_output=True, text=True, check=True).stdout.strip()
    (tmp_path / f".uq.partial-{dead}").mkdir()
    with staging.staged(out, OWNED) as stage:
        (stage / "uq.md").write_text("page\n")
    assert contents(out) == {"uq.md": "page\n"} and no_staging_beside(out)


def test_a_local_sweep_stops_within_a_second_of_ctrl_c(monkeypatch):
    run_row = _sweep.run_row
    started, interrupted = [], []

    def run_then_ctrl_c(*args):
        started.append(args[2])
        row = run_row(*args)
        if not interrupted:  # after the first run: Ctrl-C, as a terminal sends it
            interrupted.append(time.monotonic())
            signal.pthread_kill(threading.main_thread().ident, signal.SIGINT)
        return row

    monkeypatch.setattr(_sweep, "run_row", run_then_ctrl_c)
    threads = threading.active_count()
    with pytest.raises(KeyboardInterrupt):
        impact.sweep(PLASTIC, [FAST, SLOW, SLOW, SLOW, SLOW], jobs=2)
    stopped = time.monotonic() - interrupted[0]
    assert stopped < 1.0, f"the sweep took {stopped:.2f} s to stop"
    # the slow runs under way were stopped (their threads are gone); the first run's thread
    # may have taken one more before the interrupt was seen, the others never started
    assert threading.active_count() == threads and len(started) <= 3


SLOW_STUDY = f"""title: a study that takes hours (704 runs of seconds each)
scene: {PLASTIC}
set: {{mesh.nx: 160, mesh.ny: 32}}
inputs:
  plate.width: {{uniform: {{lower: 0.178, upper: 0.180}}, source: s}}
  material.youngs_modulus: {{uniform: {{lower: 2.0e11, upper: 2.14e11}}, source: s}}
sampling: {{method: sobol, seed: 1, sizes: [64, 128]}}
convergence: {{mean: 1.0e-9, std: 1.0e-9, total_index: 1.0e-9}}
mesh_levels: [0.25, 0.5, 1.0]
outputs: {{impulse_Ns: {{}}}}
"""


@pytest.mark.parametrize("pool", [["--jobs", "2"], ["--dask", "2"]], ids=["threads", "dask"])
def test_the_study_script_stops_on_ctrl_c_and_leaves_the_output_as_it_was(tmp_path, pool):
    if pool[0] == "--dask":
        pytest.importorskip("distributed")
    study = tmp_path / "slow.yaml"
    study.write_text(SLOW_STUDY)
    out = tmp_path / "uq"
    before = previous_output(out)
    # its own process group, as a terminal's foreground job: Ctrl-C reaches the Dask workers too
    p = subprocess.Popen([sys.executable, str(ROOT / "scripts" / "uq-study.py"), str(study),
                          "--out", str(out), *pool], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True, cwd=ROOT, start_new_session=True)
    try:
        first_output(p.stdout, within=60.0)
        assert p.stdout.readline().startswith(f"uq: {study}: running")
        time.sleep(2.0)  # into the runs: the declaration's checks take milliseconds
        sent = time.monotonic()
        os.killpg(p.pid, signal.SIGINT)
        said_after = first_output(p.stderr, within=10.0) - sent
        exited_after = exit_time(p, within=10.0) - sent
    finally:
        if p.poll() is None:
            os.killpg(p.pid, signal.SIGKILL)
            p.wait()
    said = p.stderr.read()
    assert said == f"uq: interrupted (Ctrl-C): nothing written, {out} is as it was\n", said
    assert p.returncode == 130
    # stopped within a second; the interpreter's teardown (pandas, scipy, matplotlib, Dask
    # unloaded) adds a few tenths on a busy machine
    assert said_after < 1.0 and exited_after < 2.0, (said_after, exited_after)
    assert contents(out) == before and no_staging_beside(out)


def first_output(stream, within: float) -> float:
    """When ``stream`` has something to read (time.monotonic), waiting at most ``within`` s."""
    ready, _, _ = select.select([stream], [], [], within)
    assert ready, f"nothing written within {within} s"
    return time.monotonic()


def exit_time(p: subprocess.Popen, within: float) -> float:
    """When ``p`` exited (time.monotonic), waiting at most ``within`` s."""
    try:
        p.wait(timeout=within)
    except subprocess.TimeoutExpired:
        pytest.fail(f"still running {within} s after Ctrl-C")
    return time.monotonic()
