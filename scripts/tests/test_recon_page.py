"""The reconstruction's page (scripts/reconstruction/recon_page.py and its prose,
recon_page.md) against the committed page: written from the committed search.json it must
reproduce reference-data/paper/reconstruction/report.md line for line, and every paragraph of
the prose file must be one the page writes (and the other way round), so a paragraph cannot be
lost or left behind unseen when the wording or the code changes."""
import json
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
RECON = ROOT / "scripts" / "reconstruction"
OUT = ROOT / "reference-data" / "paper" / "reconstruction"
sys.path.insert(0, str(RECON))

import reconstruct  # noqa: E402
import recon_page  # noqa: E402
import recon_report  # noqa: E402


def test_every_paragraph_of_the_prose_is_written_and_every_written_one_exists():
    defined = set(recon_page._paragraphs())
    used = set(re.findall(r'prose\("([a-z0-9-]+)"', (RECON / "recon_page.py").read_text()))
    assert used == defined, f"unused: {sorted(defined - used)}; missing: {sorted(used - defined)}"


def test_a_paragraph_is_one_line_with_its_values_filled_in():
    text = recon_page.prose("identity", n_confirm=16, confirm_error=1.234e-15, n_search=9,
                            search_error=2e-14)
    assert "\n" not in text
    assert "over the 16 confirmation runs: 1.2e-15; over the 9 runs of the search: 2.0e-14." in text


def test_the_committed_search_reproduces_the_committed_page():
    result = json.loads((OUT / "search.json").read_text())
    result["evaluations"] = [reconstruct.expand(e) for e in result["evaluations"]]
    result["supported_tolerances"] = recon_report.supported_tolerances(result)
    plots = sorted(p.name for p in OUT.glob("table1-*.svg"))
    page = recon_page.report_text(result, plots)
    committed = (OUT / "report.md").read_text()
    assert page.splitlines() == committed.splitlines()
