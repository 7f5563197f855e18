//! `impact report` reads results.json strictly: a malformed file is refused with a message
//! naming the file, the key and what was expected (never a template error such as "tried to
//! use - operator on unsupported types"), and the counts it prints are recounted from the
//! check rows, not taken from the stored `counts` (an unknown status word is an error naming
//! its row). Hand-written results.json files.

mod support;

use std::path::Path;

use impact_verification::report::{write_report_with, ReportOptions};
use support::temp_dir;

/// One check row of results.json with this status and known failure (`null` or a reason).
fn check(id: &str, status: &str, known: &str) -> String {
    format!(
        r#"{{"id": "{id}", "title": "check {id}", "status": "{status}", "computed": 1.0,
        "reference": 1.0, "error": 0.0, "error_kind": "relative", "compare": "within",
        "tolerance": "rel 1.0e-2", "tolerance_reason": "fixture", "reference_kind": "analytical",
        "reference_source": "fixture", "message": "", "known_failure": {known}}}"#
    )
}

fn case(checks: &[String]) -> String {
    format!(
        r#"{{"suite": "fixture", "case": "five-checks", "id": "F-1", "title": "Five checks",
        "checks": [{}]}}"#,
        checks.join(", ")
    )
}

/// Writes `text` as `dir/verify/results.json` and the report from it; the error as text.
fn report(dir: &Path, text: &str) -> Result<String, String> {
    let from = dir.join("verify");
    std::fs::create_dir_all(&from).unwrap();
    std::fs::write(from.join("results.json"), text).unwrap();
    let opts = ReportOptions {
        benchmarks: Some(dir.join("no-benchmarks")),
        reconstruction: Some(dir.join("no-page.md")),
    };
    write_report_with(&from, &dir.join("out"), &opts)
        .map(|_| std::fs::read_to_string(dir.join("out").join("report.md")).unwrap())
        .map_err(|e| format!("{e:#}"))
}

#[test]
fn a_malformed_results_json_is_refused_naming_the_file_and_the_key() {
    let dir = temp_dir("malformed-results");
    let file = dir
        .join("verify")
        .join("results.json")
        .display()
        .to_string();
    let ok = check("a", "OK", "null");
    let cases = [
        ("[]", "top level", "a JSON object"),
        (r#"{"counts": {"ok": 0}}"#, "cases", "missing"),
        (r#"{"cases": 3}"#, "cases", "an array"),
        (r#"{"cases": [7]}"#, "cases[0]", "an object"),
        (
            r#"{"cases": [{"suite": "s", "checks": []}]}"#,
            "cases[0].case",
            "a string",
        ),
        (
            r#"{"cases": [{"suite": "s", "case": "c"}]}"#,
            "cases[0].checks",
            "missing",
        ),
        (
            r#"{"cases": [{"suite": "s", "case": "c", "checks": {}}]}"#,
            "cases[0].checks",
            "an array",
        ),
        (
            &format!(
                r#"{{"cases": [{{"suite": "s", "case": "c", "checks": [{ok}, {{"id": "b"}}]}}]}}"#
            ),
            "cases[0].checks[1] (s/c check b)",
            "missing field `title`",
        ),
        ("{\"cases\": [", "not JSON", "EOF"),
    ];
    for (text, key, expected) in cases {
        let err = report(&dir, text).expect_err(text);
        assert!(
            err.contains(&file) && err.contains(key) && err.contains(expected),
            "{text}: {key:?} and {expected:?} not both in:\n{err}"
        );
        assert!(!err.contains("operator") && !err.contains("html:"), "{err}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_counts_are_recounted_from_the_rows() {
    let dir = temp_dir("recount-results");
    // Stored counts claim five OK; the rows hold 2 OK, 1 XPASS, 1 known FAIL, 1 FAIL.
    let rows = [
        check("a", "OK", "null"),
        check("b", "OK", "null"),
        check("c", "OK", "\"declared\""),
        check("d", "FAIL", "\"declared\""),
        check("e", "FAIL", "null"),
    ];
    let text = format!(
        r#"{{"counts": {{"ok": 5, "fail": 0, "skip": 0}}, "cases": [{}]}}"#,
        case(&rows)
    );
    let md = report(&dir, &text).unwrap();
    assert!(
        md.contains("**2 OK, 1 known FAIL, 1 unexpected FAIL, 1 XPASS, 0 SKIP** of 5 checks"),
        "{md}"
    );
    // An unknown status word is an error naming its row, whatever the counts say.
    let mut rows = rows.to_vec();
    rows[2] = check("c", "PASSED", "null");
    let text = format!(
        r#"{{"counts": {{"ok": 5, "fail": 0, "skip": 0}}, "cases": [{}]}}"#,
        case(&rows)
    );
    let err = report(&dir, &text).unwrap_err();
    assert!(
        err.contains("cases[0].checks[2] (fixture/five-checks check c)")
            && err.contains("PASSED")
            && err.contains("`OK`, `FAIL`, `SKIP`"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
