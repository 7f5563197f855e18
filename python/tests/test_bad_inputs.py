"""The bad-input suite (issue 28) in CI: every case of verification/bad-inputs/cases.yaml (the
runner: bad_inputs.py) run once per session with a timeout, one test per case. A case fails on
a hang, a panic, a wrong exit status or exception, a message that does not name its field (and
for a file its line and column) or say what is wrong, warnings other than those expected, an
accepted run whose outputs are not sane (or not the base run's, where that is expected), or
anything left half-written in or beside the output folder. The counts by tool are printed at
the end of the session (conftest.py)."""
from __future__ import annotations

import time

import pytest

import bad_inputs

CASES = bad_inputs.load_cases()


@pytest.fixture(scope="session")
def outcomes(cli, tmp_path_factory, request):
    start = time.monotonic()
    results = bad_inputs.run_all(cli, tmp_path_factory.mktemp("bad-inputs"), CASES)
    request.config._bad_inputs = (results, time.monotonic() - start)
    return {r.case.id: r for r in results}


def test_the_suite_has_at_least_300_cases_over_every_tool():
    tools = {c.tool for c in CASES}
    assert len(CASES) >= 300
    assert tools == {"simulate", "python", "diff", "report", "verify"}


@pytest.mark.parametrize("case_id", [c.id for c in CASES])
def test_bad_input(case_id, outcomes):
    r = outcomes[case_id]
    assert r.passed, "\n".join([f"{case_id}: exit {r.exit} {r.raised or ''}", *r.problems])
