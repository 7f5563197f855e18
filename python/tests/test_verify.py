"""`impact.verify` against `impact verify` of the same checkout on the fast suites: the same
results.json (counts, cases, checks), selectors and filter as the CLI, the files written with
`out=`, and errors for selectors that match nothing."""
from __future__ import annotations

import json
import subprocess

import pytest
from conftest import ROOT

import impact

SUITES = ["hertz", "patch", "wave-speed"]


def test_results_equal_the_cli(cli, tmp_path):
    subprocess.run([cli, "verify", *SUITES, "--light", "--out", tmp_path / "cli"],
                   cwd=ROOT, check=True, capture_output=True)
    cli_results = json.loads((tmp_path / "cli" / "results.json").read_text())
    v = impact.verify(*SUITES, light=True, jobs=2, root=ROOT, out=tmp_path / "py")
    assert v.results == cli_results
    assert (tmp_path / "py" / "results.json").read_text() == (
        tmp_path / "cli" / "results.json").read_text()
    assert (tmp_path / "py" / "junit.xml").read_text() == (tmp_path / "cli" / "junit.xml").read_text()
    assert v.counts["ok"] > 0 and v.passed == (v.counts["unexpected"] == 0)
    # The selection's impact runs bring the history invariants (summary against history.csv).
    suites = set(SUITES) | {"invariants"}
    assert {c["suite"] for c in v.results["cases"]} == suites
    frame = v.to_pandas()
    assert len(frame) == sum(v.counts.values())
    assert set(frame["suite"]) == suites


def test_filter_and_errors():
    v = impact.verify("hertz", filter="hertz", light=True, root=ROOT)
    assert all("hertz" in f"{c['suite']}/{c['case']}/{k['id']}"
               for c in v.results["cases"] for k in c["checks"])
    with pytest.raises(impact.VerifyError, match="no case matches"):
        impact.verify("no-such-suite", root=ROOT)
    with pytest.raises(ValueError, match="out="):
        impact.verify("hertz", report=True, root=ROOT)
