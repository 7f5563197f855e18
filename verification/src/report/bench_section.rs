//! The report's "Performance: work-precision, throughput, stability" section: the page
//! `impact-bench` writes next to its results (`benchmarks.md`: machine, sizes, targets met or
//! missed, the work-precision plots and Pareto fronts, throughput with the Python side by side,
//! stability; benchmarks/src/page.rs), embedded as the reconstruction page is: headings under
//! the section, its plots copied to `plots/benchmarks/` for report.md and inlined in
//! index.html, and its status and number cells styled as the report's own tables.

use std::path::Path;

use serde_json::{json, Value};

use crate::report::markdown::{embed, modified, Embed};

/// The command that writes the folder and its page.
pub const HOW: &str = "cargo run --release -p impact-benchmarks -- all --out DIR";

/// The page's file name in the benchmarks folder.
pub const PAGE: &str = "benchmarks.md";

/// The report's section; the page's title repeats it and is dropped when embedded.
const SECTION: &str = "Performance: work-precision, throughput, stability";

/// The context of the performance section. `dir`: the benchmarks folder (None: none given
/// and none found). The page's plots are copied to `out/plots/benchmarks/` for report.md.
pub fn context(dir: Option<&Path>, out: &Path) -> Value {
    let Some(dir) = dir.filter(|d| d.is_dir()) else {
        // The templates say how to produce it; `given` is the folder asked for, if any.
        return json!({"present": false, "given": dir.map(|d| d.display().to_string()), "how": HOW});
    };
    let shown = dir.display().to_string();
    let path = dir.join(PAGE);
    let Ok(text) = std::fs::read_to_string(&path) else {
        return json!({"present": true, "page": false, "dir": shown, "how": HOW});
    };
    let e = embed(
        &text,
        &Embed {
            base: dir,
            top_level: 3,
            anchor_prefix: "perf-",
            out,
            copy_to: "plots/benchmarks",
            section_title: Some(SECTION),
        },
    );
    json!({
        "present": true, "page": true, "dir": shown, "how": HOW,
        "written": modified(&path).unwrap_or_else(|| "unknown".into()),
        "html": styled_cells(&e.html), "md": e.md, "missing": e.missing,
    })
}

/// The class of a table cell of the page (its HTML text): met / bounded OK, missed /
/// UNBOUNDED FAIL, coarse SKIP, a number (or a bound "<= 6.0", a mesh "80x16") num.
fn cell_class(text: &str) -> Option<&'static str> {
    let bare = text
        .trim()
        .trim_start_matches("&lt;= ")
        .trim_start_matches("&lt; ");
    let numeric = !bare.is_empty()
        && (bare.parse::<f64>().is_ok() || bare.split('x').all(|p| p.parse::<u64>().is_ok()));
    match text {
        "met" | "bounded" => Some("OK"),
        "missed" | "UNBOUNDED" => Some("FAIL"),
        "coarse" => Some("SKIP"),
        _ if numeric => Some("num"),
        _ => None,
    }
}

/// `html` with each plain `<td>` given the class of its text (see [`cell_class`]).
fn styled_cells(html: &str) -> String {
    let mut out = String::with_capacity(html.len() + html.len() / 8);
    let mut rest = html;
    while let Some(i) = rest.find("<td>") {
        out.push_str(&rest[..i]);
        let cell = &rest[i + "<td>".len()..];
        let text = cell.find("</td>").map_or("", |j| &cell[..j]);
        match cell_class(text) {
            Some(c) => out.push_str(&format!("<td class=\"{c}\">")),
            None => out.push_str("<td>"),
        }
        rest = cell;
    }
    out.push_str(rest);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cells_take_the_report_classes() {
        let html = "<tr><td>q4-sri</td><td>25.0</td><td>&lt;= 6.0</td><td>missed</td><td>met</td><td>80x16</td><td>coarse</td><td>UNBOUNDED</td><td>-</td></tr>";
        assert_eq!(
            styled_cells(html),
            "<tr><td>q4-sri</td><td class=\"num\">25.0</td><td class=\"num\">&lt;= 6.0</td><td class=\"FAIL\">missed</td><td class=\"OK\">met</td><td class=\"num\">80x16</td><td class=\"SKIP\">coarse</td><td class=\"FAIL\">UNBOUNDED</td><td>-</td></tr>"
        );
    }
}
