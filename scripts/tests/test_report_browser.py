"""The report's headless-browser check (scripts/report_browser_check.py) on pages written here: a
page whose figures all render and whose tables fit (a wide table in a deliberate scroll box
included) passes; a page with a missing image, an empty SVG and a table wider than the page
fails with each problem named; a narrow table whose cells break words ("stat|us", as the
report's old `overflow-wrap: anywhere` did) fails, the same table with the report's rule (words
kept whole) passes; a plot whose marked legend box overlaps its marked data area fails, inline
or as an SVG data URI, and one with the legend below passes. Runs Debian's chromium (/usr/bin/chromium, installed by
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
    # The page's top and one PNG per h2 section, each a real PNG.
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


NARROW = (
    '<table style="width:60px"><tr><th>status</th><th>tolerance</th></tr>'
    '<tr><td>OK</td><td>rel <span class="tok">1.0e-8</span></td></tr></table>'
)


def test_words_broken_across_lines_in_a_table_cell_fail(tmp_path: Path):
    # The old stylesheet: headers broken anywhere ("stat|us"), cells at emergency breaks.
    html = tmp_path / "index.html"
    html.write_text(page("<style>th,td{overflow-wrap:anywhere}</style>" + NARROW))
    out = rbc.check_page(html, None)
    text = "\n".join(out.problems)
    assert 'a table cell breaks the word "status" across lines' in text, text
    assert 'breaks the word "tolerance"' in text, text
    assert rbc.main([str(html)]) == 1


def test_words_kept_whole_pass(tmp_path: Path):
    # The report's rule: no overflow-wrap, break-prone words in span.tok kept on one line.
    html = tmp_path / "index.html"
    html.write_text(page("<style>th,td{overflow-wrap:normal}.tok{white-space:nowrap}</style>" + NARROW))
    out = rbc.check_page(html, None)
    assert out.problems == [], out.problems
    assert out.cells == 4 and out.words == 5


def plot(legend_y: int) -> str:
    """A plot as the report draws it: data area 76..550 x 30..300, the legend box at legend_y."""
    return (
        '<svg xmlns="http://www.w3.org/2000/svg" width="560" height="400">'
        '<path d="M80 290 L540 40" stroke="blue" fill="none"/>'
        '<rect class="data-area" x="76" y="30" width="474" height="270" fill="none" stroke="none"/>'
        f'<g class="legend"><rect class="legend-box" x="8" y="{legend_y}" width="544" height="40" '
        'fill="#ffffff" stroke="#999999"/><text x="40" y="20">runs</text></g></svg>'
    )


def test_a_legend_over_the_data_area_fails_inline_and_as_an_image(tmp_path: Path):
    import base64

    inside = plot(legend_y=40)
    uri = "data:image/svg+xml;base64," + base64.b64encode(inside.encode()).decode()
    html = tmp_path / "index.html"
    html.write_text(page(inside + f'<img src="{uri}">'))
    out = rbc.check_page(html, None)
    over = [p for p in out.problems if "a legend covers the data area" in p]
    assert len(over) == 2, out.problems
    assert out.legends == 2


def test_a_legend_below_the_data_area_passes_and_an_unmarked_data_area_fails(tmp_path: Path):
    html = tmp_path / "index.html"
    html.write_text(page(plot(legend_y=340) + FIGURE))
    out = rbc.check_page(html, None)
    assert out.problems == [], out.problems
    assert (out.legends, out.unmarked) == (1, 1)
    html.write_text(page(plot(legend_y=340).replace('class="data-area"', 'class="other"')))
    out = rbc.check_page(html, None)
    assert any("marks its legend but not its data area" in p for p in out.problems), out.problems
