#!/usr/bin/env python3
"""Opens the V&V report (index.html) in headless Chromium and checks that a reader sees it whole:
every figure renders, no table overflows the page, no table cell breaks a word, and no legend
covers a plot's data.

- A figure is every <img> (loaded, natural size > 0) and every inline <svg> (laid out with a
  size > 0 and drawing something: at least one path, line, rect, circle, polyline, polygon or
  text element).
- A table overflows when its right edge lies beyond the page's content column (the <body>'s
  box) or the page scrolls sideways (document scrollWidth > clientWidth). A table inside a
  deliberate scroll box (an ancestor with CSS overflow-x auto or scroll, e.g. a wide benchmark
  table in its own box) may be wider than the page, but that box itself must fit.
- Tables inside closed <details> are opened first, so they are checked too.
- No table cell breaks a word across lines: every whitespace-separated word of a cell's text
  (within one text node) lies on one line, measured with the client rectangles of its text
  range (a word split as "stat|us" or "rel 1.0e-|8" has rectangles on two lines).
- No legend covers a plot's data: every SVG figure (inline, or an <img> with an SVG data URI)
  that marks its legend (rect.legend-box, as the report's plots and the benchmarks' do)
  also marks its data area (rect.data-area), and the two rectangles do not overlap. Figures
  without a marked legend are not judged (counted apart).

Screenshots of the page's top and of each top-level section (h2), each cut at 4000 px, go to --screens, for review.

The browser is the system's Debian chromium (/usr/bin/chromium, installed by
scripts/setup-browser.sh), driven by Playwright (pinned in scripts/requirements.txt); nothing
downloads a browser of its own. Exit status: 0 when everything renders and fits, 1 when not
(each problem printed), 2 when the page or the browser cannot be opened.
"""

from __future__ import annotations

import argparse
import re
import shutil
import sys
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

CHROMIUM = "/usr/bin/chromium"
# Headless, no sandbox (CI runs as root), and nothing that reaches the network on its own.
CHROMIUM_ARGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]
VIEWPORT = {"width": 1280, "height": 900}

# Runs in the page: the problems with figures and tables, and what was checked.
INSPECT_JS = r"""
() => {
  const problems = [];
  const where = (el) => {
    const h = [];
    let e = el;
    while (e && e !== document.body) {
      let p = e.previousElementSibling;
      while (p && !/^H[1-4]$/.test(p.tagName)) p = p.previousElementSibling;
      if (p) { h.push(p.textContent.trim().slice(0, 60)); break; }
      e = e.parentElement;
    }
    return h.length ? `under "${h[0]}"` : "at the top";
  };
  document.querySelectorAll("details").forEach((d) => { d.open = true; });
  const imgs = [...document.querySelectorAll("img")];
  for (const img of imgs) {
    if (!img.complete || img.naturalWidth === 0 || img.naturalHeight === 0) {
      problems.push(`figure does not render: <img src="${(img.getAttribute("src") || "").slice(0, 80)}"> ${where(img)}`);
    }
  }
  // Top-level inline SVGs (not the ones nested inside another SVG).
  const svgs = [...document.querySelectorAll("svg")].filter((s) => !s.parentElement.closest("svg"));
  for (const svg of svgs) {
    const r = svg.getBoundingClientRect();
    const marks = svg.querySelectorAll("path,line,rect,circle,polyline,polygon,text").length;
    if (r.width <= 0 || r.height <= 0 || marks === 0) {
      problems.push(`figure does not render: <svg> ${Math.round(r.width)} x ${Math.round(r.height)} px with ${marks} marks ${where(svg)}`);
    }
  }
  const column = document.body.getBoundingClientRect();
  const scrollBox = (el) => {
    for (let e = el.parentElement; e && e !== document.body; e = e.parentElement) {
      const o = getComputedStyle(e).overflowX;
      if (o === "auto" || o === "scroll") return e;
    }
    return null;
  };
  const tables = [...document.querySelectorAll("table")];
  let boxed = 0;
  for (const t of tables) {
    const box = scrollBox(t);
    if (box) boxed += 1;
    const fits = box || t;
    const r = fits.getBoundingClientRect();
    if (r.right > column.right + 1) {
      const what = box ? "the scroll box of a table" : "table";
      const head = [...t.querySelectorAll("th")].slice(0, 3).map((h) => h.textContent.trim()).join(", ");
      problems.push(`${what} overflows the page by ${Math.round(r.right - column.right)} px (columns ${head}...) ${where(t)}`);
    }
  }
  const doc = document.documentElement;
  if (doc.scrollWidth > doc.clientWidth + 1) {
    problems.push(`the page scrolls sideways: ${doc.scrollWidth} px wide in a ${doc.clientWidth} px window`);
  }
  // Words split across lines inside table cells.
  let cells = 0, words = 0, broken = 0;
  const lines = (rects) => {
    const tops = [];
    for (const r of rects) {
      if (r.width <= 0 || r.height <= 0) continue;
      if (!tops.some((t) => Math.abs(t - r.top) < r.height / 2)) tops.push(r.top);
    }
    return tops.length;
  };
  for (const cell of document.querySelectorAll("td, th")) {
    cells += 1;
    const walk = document.createTreeWalker(cell, NodeFilter.SHOW_TEXT);
    for (let node = walk.nextNode(); node; node = walk.nextNode()) {
      if (node.parentElement.closest("svg")) continue;
      for (const m of node.data.matchAll(/\S+/g)) {
        words += 1;
        const range = document.createRange();
        range.setStart(node, m.index);
        range.setEnd(node, m.index + m[0].length);
        if (lines(range.getClientRects()) > 1) {
          broken += 1;
          if (broken <= 20) {
            problems.push(`a table cell breaks the word "${m[0].slice(0, 40)}" across lines ${where(cell.closest("table"))}`);
          }
        }
      }
    }
  }
  if (broken > 20) problems.push(`... and ${broken - 20} more words broken across lines`);
  // Legends over the data area, read from the marks the plots carry.
  const rect = (svg, cls) => {
    const r = svg.querySelector(`rect.${cls}`);
    if (!r) return null;
    return ["x", "y", "width", "height"].map((a) => parseFloat(r.getAttribute(a)));
  };
  const overlap = (a, b) => a[0] < b[0] + b[2] && b[0] < a[0] + a[2] && a[1] < b[1] + b[3] && b[1] < a[1] + a[3];
  let legends = 0, unmarked = 0;
  const judge = (svg, el) => {
    const legend = rect(svg, "legend-box");
    if (!legend) { unmarked += 1; return; }
    legends += 1;
    const data = rect(svg, "data-area");
    if (!data) {
      problems.push(`a plot marks its legend but not its data area ${where(el)}`);
    } else if (overlap(legend, data)) {
      problems.push(`a legend covers the data area of a plot (legend ${legend.map(Math.round)}, data ${data.map(Math.round)}) ${where(el)}`);
    }
  };
  for (const svg of svgs) judge(svg, svg);
  for (const img of imgs) {
    const src = img.getAttribute("src") || "";
    const head = "data:image/svg+xml;base64,";
    if (!src.startsWith(head)) continue;
    const text = new TextDecoder().decode(Uint8Array.from(atob(src.slice(head.length)), (c) => c.charCodeAt(0)));
    const svg = new DOMParser().parseFromString(text, "image/svg+xml").documentElement;
    judge(svg, img);
  }
  return { problems, imgs: imgs.length, svgs: svgs.length, tables: tables.length, boxed,
           cells, words, legends, unmarked };
}
"""


@dataclass
class Outcome:
    """What the check found on one page."""

    problems: list[str] = field(default_factory=list)
    imgs: int = 0
    svgs: int = 0
    tables: int = 0
    boxed: int = 0
    cells: int = 0
    words: int = 0
    legends: int = 0
    unmarked: int = 0
    screenshots: list[Path] = field(default_factory=list)

    def line(self) -> str:
        return (
            f"browser check: {self.imgs + self.svgs} figures ({self.imgs} img, {self.svgs} svg), "
            f"{self.tables} tables ({self.boxed} in scroll boxes, {self.cells} cells, {self.words} words "
            f"kept whole), {self.legends} legends outside the data area ({self.unmarked} figures "
            f"without a marked legend), {len(self.problems)} problems, {len(self.screenshots)} screenshots"
        )


def slug(text: str) -> str:
    return re.sub(r"[^a-z0-9]+", "-", text.lower()).strip("-")[:40] or "section"


# Each screenshot is cut at this height (px): the screenshots are for a reviewer's eye. The
# light report is 271 104 px tall (2026-11-30); its uncut PNG (20 MB) took Chromium about 30 s,
# its default timeout, and failed the gate once on a slower run.
CLIP_HEIGHT_PX = 4000


def screenshots(page, screens: Path) -> list[Path]:
    """The page's top, then each h2 section (heading to the next h2) as its own PNG."""
    screens.mkdir(parents=True, exist_ok=True)
    taken = []
    width = page.evaluate("() => document.documentElement.clientWidth")
    top = screens / "00-page-top.png"
    clip = {"x": 0, "y": 0, "width": width, "height": CLIP_HEIGHT_PX}
    page.screenshot(path=str(top), full_page=True, clip=clip)
    taken.append(top)
    boxes = page.evaluate(
        """() => {
          const hs = [...document.querySelectorAll("h2")];
          const end = document.documentElement.scrollHeight;
          return hs.map((h, i) => {
            const top = h.getBoundingClientRect().top + window.scrollY;
            const next = i + 1 < hs.length ? hs[i + 1].getBoundingClientRect().top + window.scrollY : end;
            return { text: h.textContent.trim(), top, height: Math.max(1, next - top) };
          });
        }"""
    )
    for i, b in enumerate(boxes, start=1):
        path = screens / f"{i:02d}-{slug(b['text'])}.png"
        clip = {"x": 0, "y": b["top"], "width": width, "height": min(b["height"], CLIP_HEIGHT_PX)}
        page.screenshot(path=str(path), full_page=True, clip=clip)
        taken.append(path)
    return taken


def check_page(html: Path, screens: Path | None) -> Outcome:
    """Opens `html` in headless Chromium, returns what renders and what does not."""
    from playwright.sync_api import sync_playwright

    profile = Path(tempfile.mkdtemp(prefix="impact-browser-"))
    try:
        with sync_playwright() as p:
            browser = p.chromium.launch_persistent_context(
                str(profile),
                executable_path=CHROMIUM,
                headless=True,
                args=CHROMIUM_ARGS,
                viewport=VIEWPORT,
            )
            try:
                page = browser.new_page()
                page.goto(html.resolve().as_uri(), wait_until="load")
                found = page.evaluate(INSPECT_JS)
                out = Outcome(
                    problems=found["problems"],
                    imgs=found["imgs"],
                    svgs=found["svgs"],
                    tables=found["tables"],
                    boxed=found["boxed"],
                    cells=found["cells"],
                    words=found["words"],
                    legends=found["legends"],
                    unmarked=found["unmarked"],
                )
                if screens is not None:
                    out.screenshots = screenshots(page, screens)
                return out
            finally:
                browser.close()
    finally:
        shutil.rmtree(profile, ignore_errors=True)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("html", type=Path, help="the report's index.html")
    ap.add_argument("--screens", type=Path, help="folder for the PNG screenshots")
    args = ap.parse_args(argv)
    if not args.html.is_file():
        print(f"error: {args.html}: no such file", file=sys.stderr)
        return 2
    if not Path(CHROMIUM).exists():
        print(f"error: {CHROMIUM} is missing: run scripts/setup-browser.sh", file=sys.stderr)
        return 2
    try:
        out = check_page(args.html, args.screens)
    except Exception as e:  # the browser did not start or the page did not open
        print(f"error: cannot open {args.html} in {CHROMIUM}: {e}", file=sys.stderr)
        return 2
    for p in out.problems:
        print(f"  {p}")
    print(out.line())
    if out.screenshots:
        print(f"screenshots: {out.screenshots[0].parent}")
    return 1 if out.problems else 0


if __name__ == "__main__":
    sys.exit(main())
