"""Shared fixtures of the `impact` package's tests: the repository, the `impact` CLI built
from the same sources (target/release/impact, or $IMPACT_BIN), and small scenes."""
from __future__ import annotations

import os
import signal
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

# Ctrl-C is what the interrupt tests send. A shell that starts a job in the background without
# job control (`cmd &` in a script, a CI runner's nohup) starts it with SIGINT ignored, and
# Python then installs no KeyboardInterrupt handler, so those tests would fail (or a run meant
# to be stopped would go on for hours). The tests restore the terminal's behaviour; a handler
# set here is not inherited by the CLI and scripts they start, which get the default again.
if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)
# Small elasto-plastic impact (20 x 4 q4-sri, fixed dt, probe A): ~0.05 s a run.
SMALL = ROOT / "scripts" / "ci-scenes" / "impact-plastic.yaml"


@pytest.fixture(scope="session")
def cli() -> Path:
    """The `impact` command of this checkout (built by .ci/run before the tests)."""
    path = Path(os.environ.get("IMPACT_BIN", ROOT / "target" / "release" / "impact"))
    if not path.exists():
        subprocess.run(
            ["cargo", "build", "--release", "--quiet", "-p", "impact-verification", "--bin", "impact"],
            cwd=ROOT, check=True,
        )
    return path


@pytest.fixture(scope="session")
def small_scene() -> Path:
    return SMALL


def pytest_terminal_summary(terminalreporter, exitstatus, config):
    """The bad-input suite's counts by tool (test_bad_inputs.py), when it ran."""
    got = getattr(config, "_bad_inputs", None)
    if got:
        import bad_inputs

        results, seconds = got
        terminalreporter.write_line(bad_inputs.summary_line(results, seconds))
