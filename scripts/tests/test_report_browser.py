"""The report's headless-browser check (scripts/report_browser_check.py, issue 13) on pages
written here: a page whose figures all render and whose tables fit (a wide table in a deliberate
scroll box included) passes; a page with a missing image, an empty SVG and a table wider than
the page fails with each problem named. Runs Debian's chromium (/usr/bin/chromium, installed by
scripts/setup-browser.sh); a missing browser fails the test rather than skipping it."""

from pathlib import Path

import pytest

import report_browser_check as rbc

FIGURE = (
    '<svg xmlns="http://www.w3.org/2000/svg" width="120" height="80">'
    '<rect x="5" y="5" width="110" height="70" fill="none" stroke="black"/>'
    '<path d="M10 70 L60 20 L110 50" stroke="blue" fill="none"/></svg>'
)
WIDE_ROW = "".join(f"<td>column-{i}-with-a-long-unbreakable-value</td>" for i in range(30))


def page(body: str) -> str:
    return (
        '<!DOCTYPE html><html><head><meta charset="utf-8"><style>'
        "body{max-width:1000px;margin:2em auto} td{white-space:nowrap}"
        ".scroll{overflow-x:auto}</style></head><body>"
        f"<h2>Figures</h2>{body}</body></html>"
    )


@pytest.fixture(autouse=True)
def browser_present():
    if not Path(rbc.CHROMIUM).exists():
        pytest.fail(f"{rbc.CHROMIUM} is missing: run scripts/setup-browser.sh")


def test_a_page_whose_figures_render_and_tables_fit_passes(tmp_path: Path):
    (tmp_path / "fig.svg").write_text(FIGURE)
    html = tmp_path / "index.html"
    html.write_text(
        page(
            f'<img src="fig.svg">{FIGURE}'
            "<table><tr><th>a</th><th>b</th></tr><tr><td>1</td><td>2</td></tr></table>"
            f'<h2>Wide, in its scroll box</h2><div class="scroll"><table><tr>{WIDE_ROW}</tr></table></div>'
        )
    )
    out = rbc.check_page(html, tmp_path / "screens")
    assert out.problems == []
    assert (out.imgs, out.svgs, out.tables, out.boxed) == (1, 1, 2, 1)
    # The whole page and one PNG per h2 section, each a real PNG.
    assert len(out.screenshots) == 3
    for png in out.screenshots:
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert rbc.main([str(html)]) == 0


def test_a_missing_image_an_empty_svg_and_an_overflowing_table_fail(tmp_path: Path):
    html = tmp_path / "index.html"
    html.write_text(
        page(
            '<img src="no-such-figure.png">'
            '<svg xmlns="http://www.w3.org/2000/svg" width="100" height="50"></svg>'
            f"<h2>Too wide</h2><table><tr><th>first</th>{WIDE_ROW}</tr></table>"
        )
    )
    out = rbc.check_page(html, None)
    text = "\n".join(out.problems)
    assert 'figure does not render: <img src="no-such-figure.png"> under "Figures"' in text
    assert "figure does not render: <svg> 100 x 50 px with 0 marks" in text
    assert "table overflows the page by" in text and "(columns first" in text
    assert "the page scrolls sideways" in text
    assert len(out.problems) == 4, text
    assert rbc.main([str(html)]) == 1
