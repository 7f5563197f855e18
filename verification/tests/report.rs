//! The V&V report's pages from other tools, on small fixtures (not the real folders): the
//! reconstruction page of issue 5 and the benchmarks' page (benchmarks.md, issue 6) present,
//! missing, found at their default place, and a benchmarks folder without its page. What the
//! benchmarks' page holds is tested with its writer (benchmarks/src/page_tests.rs); the report
//! of the real matrix in matrix.rs.

mod support;

use impact_verification::report::{write_report_with, ReportOptions};
use support::*;

#[test]
fn report_embeds_the_reconstruction_page_and_the_benchmarks() {
    let dir = temp_dir("present");
    let from = dir.join("verify");
    write_empty_results(&from);
    write_benchmarks(&dir.join("bench"));
    let page = write_reconstruction(&dir.join("recon"));
    let out = dir.join("report");
    let opts = ReportOptions {
        benchmarks: Some(dir.join("bench")),
        reconstruction: Some(page),
    };
    write_report_with(&from, &out, &opts).unwrap();
    assert_sections_present(&out);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn report_says_how_to_produce_what_is_missing() {
    let dir = temp_dir("missing");
    let from = dir.join("verify");
    write_empty_results(&from);
    // Given, but not there.
    let bench = dir.join("no-such-benchmarks");
    let opts = ReportOptions {
        benchmarks: Some(bench.clone()),
        reconstruction: Some(dir.join("recon").join("report.md")),
    };
    write_report_with(&from, &from, &opts).unwrap();
    assert_sections_missing(&from, Some(&bench));
    // Not given, and no <from>/benchmarks: the default finds nothing.
    let opts = ReportOptions {
        benchmarks: None,
        reconstruction: Some(dir.join("recon").join("report.md")),
    };
    write_report_with(&from, &from, &opts).unwrap();
    assert_sections_missing(&from, None);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn report_finds_benchmarks_next_to_the_verify_results() {
    let dir = temp_dir("default");
    let from = dir.join("verify");
    write_empty_results(&from);
    write_benchmarks(&from.join("benchmarks"));
    let page = write_reconstruction(&dir.join("recon"));
    let opts = ReportOptions {
        benchmarks: None,
        reconstruction: Some(page),
    };
    write_report_with(&from, &from, &opts).unwrap();
    assert_sections_present(&from);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn report_says_when_the_benchmarks_folder_has_no_page() {
    let dir = temp_dir("nopage");
    let from = dir.join("verify");
    write_empty_results(&from);
    let bench = dir.join("bench");
    write_benchmarks(&bench);
    std::fs::remove_file(bench.join("benchmarks.md")).unwrap();
    let opts = ReportOptions {
        benchmarks: Some(bench.clone()),
        reconstruction: Some(dir.join("none.md")),
    };
    write_report_with(&from, &from, &opts).unwrap();
    let md = std::fs::read_to_string(from.join("report.md")).unwrap();
    let html = std::fs::read_to_string(from.join("index.html")).unwrap();
    assert!(
        md.contains(&format!(
            "**No benchmark page:** the folder `{}` has no `benchmarks.md`",
            bench.display()
        )) && md.contains("`cargo run --release -p impact-benchmarks -- all --out DIR`"),
        "{md}"
    );
    assert!(html.contains("<b>No benchmark page:</b>"));
    // Its CSVs are not drawn in the page's place.
    assert!(
        !md.contains("table1-elasto-plastic") && !html.contains("id=\"perf-"),
        "{md}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
