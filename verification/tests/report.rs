//! The V&V report's pages from other tools, on small fixtures (not the real folders): the
//! reconstruction page of issue 5 and the benchmarks of issue 6, present, missing, found at
//! their default place, a benchmarks folder with files missing, and the note when the
//! benchmarks ran at `--quick` size (meta.json). The report of the real
//! matrix is tested in matrix.rs.

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
fn report_names_the_benchmark_files_that_are_missing() {
    let dir = temp_dir("partial");
    let from = dir.join("verify");
    write_empty_results(&from);
    let bench = dir.join("bench");
    write_benchmarks(&bench);
    for f in ["work-precision.csv", "throughput-runs.csv", "stability.md"] {
        std::fs::remove_file(bench.join(f)).unwrap();
    }
    let opts = ReportOptions {
        benchmarks: Some(bench),
        reconstruction: Some(dir.join("none.md")),
    };
    write_report_with(&from, &from, &opts).unwrap();
    let md = std::fs::read_to_string(from.join("report.md")).unwrap();
    let html = std::fs::read_to_string(from.join("index.html")).unwrap();
    assert!(md.contains("**Not in this folder:** `work-precision.csv` (`impact-bench work-precision --out DIR`); `throughput-runs.csv` (`impact-bench throughput --out DIR`); `stability.md` (`impact-bench stability --out DIR`)."), "{md}");
    // The plots are still there; without stability.md its CSVs are shown (commas in notes kept).
    assert!(html.contains("impact-fixture plot") && md.contains("![work-precision pulse-fixture]"));
    assert!(!md.contains("Pareto front:"), "no front without the CSV");
    assert!(md.contains("| uniform | elastic | 1.2 | stopped | NaN | NaN | step 96: element 20 (around x = 2.5e-3 m, y = 7.5e-3 m) has inverted |"), "{md}");
    assert!(html.contains("<td class=\"SKIP\">coarse</td>"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// The benchmarks' meta.json (impact-bench writes it) says when they ran at `--quick` size:
/// the report's benchmark section carries the note then, and not for a full run or a folder
/// without meta.json.
#[test]
fn report_notes_benchmarks_run_at_quick_size() {
    let dir = temp_dir("quick");
    let from = dir.join("verify");
    write_empty_results(&from);
    let bench = dir.join("bench");
    write_benchmarks(&bench);
    let note = "benchmarks ran at quick size (work-precision: meshes 10x2, 20x4 (wave 4x10, 4x20); CFL 0.9; 1 timed repeat";
    let report = |meta: Option<&str>| {
        let _ = std::fs::remove_file(bench.join("meta.json"));
        if let Some(m) = meta {
            std::fs::write(bench.join("meta.json"), m).unwrap();
        }
        let opts = ReportOptions {
            benchmarks: Some(bench.clone()),
            reconstruction: Some(dir.join("none.md")),
        };
        write_report_with(&from, &from, &opts).unwrap();
        (
            std::fs::read_to_string(from.join("report.md")).unwrap(),
            std::fs::read_to_string(from.join("index.html")).unwrap(),
        )
    };
    let (md, html) = report(Some(QUICK_META));
    assert!(md.contains(&format!("**Note:** {note}")), "{md}");
    assert!(md.contains("; throughput; stability)"), "{md}");
    assert!(html.contains(&format!("Note: {note}")), "{html}");
    for meta in [Some(FULL_META), None] {
        let (md, html) = report(meta);
        assert!(
            !md.contains("quick size") && !html.contains("quick size"),
            "{meta:?}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// meta.json as `impact-bench all --quick` writes it.
const QUICK_META: &str = r#"{"quick": true, "benchmarks": {
  "throughput": {"quick": true}, "stability": {"quick": true},
  "work-precision": {"quick": true, "sizes": "meshes 10x2, 20x4 (wave 4x10, 4x20); CFL 0.9; 1 timed repeat"}}}"#;
/// meta.json as `impact-bench all` (default sizes) writes it.
const FULL_META: &str = r#"{"quick": false, "benchmarks": {
  "throughput": {"quick": false}, "stability": {"quick": false},
  "work-precision": {"quick": false, "sizes": "meshes 10x2, 20x4, 40x8, 80x16 (wave 4x10, 4x20, 4x40, 4x80); CFL 0.3, 0.6, 0.9; 2 timed repeats"}}}"#;
