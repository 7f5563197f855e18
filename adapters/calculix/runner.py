"""Run ccx on OUT_DIR/job.inp, forwarding SIGTERM/SIGINT to it, and judge the run."""

import os
import resource
import shutil
import signal
import subprocess
import time


class CcxFailed(Exception):
    """ccx is missing, rejected the deck, crashed or wrote no usable output."""


def last_lines(path, n=3):
    """The last n non-empty lines of a text file, joined with ' | ' (empty when unreadable)."""
    try:
        with open(path, encoding="utf-8", errors="replace") as f:
            lines = [l.strip() for l in f if l.strip()]
    except OSError:
        return ""
    return " | ".join(lines[-n:])


def error_lines(path):
    """ccx's '*ERROR' lines in its log."""
    try:
        with open(path, encoding="utf-8", errors="replace") as f:
            return [l.strip() for l in f if "*ERROR" in l]
    except OSError:
        return []


def run(out_dir, job="job"):
    """Run `ccx -i job` in out_dir; returns (wall s, cpu s, log path). Raises CcxFailed."""
    exe = shutil.which("ccx")
    if exe is None:
        raise CcxFailed("ccx not found on PATH")
    log_path = os.path.join(out_dir, f"{job}.log")
    env = dict(os.environ, OMP_NUM_THREADS=os.environ.get("OMP_NUM_THREADS", "1"))
    start, cpu0 = time.monotonic(), resource.getrusage(resource.RUSAGE_CHILDREN)
    held = {"child": None, "signal": None}

    def forward(signum, _frame):
        """Pass SIGTERM/SIGINT on to ccx (or, before it starts, to the start)."""
        held["signal"] = signum
        if held["child"] is not None:
            held["child"].send_signal(signum)

    old = {sig: signal.signal(sig, forward) for sig in (signal.SIGTERM, signal.SIGINT)}
    try:
        with open(log_path, "w", encoding="utf-8") as log:
            held["child"] = subprocess.Popen([exe, "-i", job], cwd=out_dir, stdout=log,
                                             stderr=subprocess.STDOUT, env=env)
            if held["signal"] is not None:
                held["child"].send_signal(held["signal"])
            rc = held["child"].wait()
    finally:
        child = held["child"]
        if child is not None and child.poll() is None:
            child.kill()
            child.wait()
        for sig, handler in old.items():
            signal.signal(sig, handler)
    wall = time.monotonic() - start
    cpu1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (cpu1.ru_utime - cpu0.ru_utime) + (cpu1.ru_stime - cpu0.ru_stime)
    if rc < 0 or held["signal"] is not None:
        sig = -rc if rc < 0 else held["signal"]
        raise CcxFailed(f"ccx killed by signal {sig}: {last_lines(log_path)}")
    errors = error_lines(log_path)
    if errors or rc != 0:
        raise CcxFailed(f"ccx exit status {rc}: " + (" | ".join(errors[-3:]) or last_lines(log_path)))
    return wall, cpu, log_path
