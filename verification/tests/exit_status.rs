//! The exit status of `impact verify` (issue 10, section 3), run as a process on scratch
//! repositories whose one case uses the cheap `hertz-law` builtin:
//! - 0 when every failing check is a declared known failure and none passes unexpectedly;
//! - 1 on an undeclared failure, and on a known failure that passes (XPASS);
//! - a case that does not parse is a FAIL row of that case (exit 1) and the other suites still
//!   run (issue 13); 2 on bad usage.
//!
//! The matrix's total line counts the known failures apart from the unexpected ones.
//! While it works, verify prints each case as it finishes with its checks' verdicts and run
//! time, then a one-line total (issue 13, "say what is happening").

use std::path::PathBuf;
use std::process::Command;
use std::sync::atomic::{AtomicUsize, Ordering};

static COUNTER: AtomicUsize = AtomicUsize::new(0);

/// A check of the law's round-trip error against `value` within `absolute`.
fn round_trip_check(id: &str, value: f64, source: &str, absolute: &str, reason: &str) -> String {
    format!(
        "\n  - id: {id}\n    title: check {id}\n    measure: {{metric: round_trip_max_rel}}\n    \
         reference: {{kind: analytical, value: {value:?}, source: \"{source}\"}}\n    \
         tolerance: {{absolute: {absolute}, reason: \"{reason}\"}}\n"
    )
}

/// A passing check (round-off of the law's inverse is far below 1e-9).
fn passes() -> String {
    round_trip_check("passes", 0.0, "closed form", "1.0e-9", "round-off")
}

/// A failing check (the round-trip error is not 1).
fn fails() -> String {
    round_trip_check(
        "fails",
        1.0,
        "deliberately wrong",
        "1.0e-3",
        "a test of the exit status",
    )
}

fn known(check: &str) -> String {
    format!("{}    known_failure: \"declared for the test\"\n", check)
}

fn scratch(checks: &str) -> PathBuf {
    let root = std::env::temp_dir().join(format!(
        "impact-exit-{}-{}",
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::SeqCst)
    ));
    let _ = std::fs::remove_dir_all(&root);
    let dir = root.join("verification/cases/suite/case");
    std::fs::create_dir_all(&dir).unwrap();
    let yaml = format!(
        "id: c1\ntitle: t\nrequirement: {{id: REQ-1, text: The solver shall do a thing.}}\n\
         category: code verification\nscenes:\n  law: {{builtin: hertz-law}}\nchecks:{checks}"
    );
    std::fs::write(dir.join("case.yaml"), yaml).unwrap();
    root
}

/// (exit code, stdout, stderr) of `impact verify` on a scratch repository.
fn verify(checks: &str, extra: &[&str]) -> (i32, String, String) {
    let root = scratch(checks);
    let result = verify_in(&root, extra);
    let _ = std::fs::remove_dir_all(&root);
    result
}

/// (exit code, stdout, stderr) of `impact verify --root ROOT --out ROOT/out`.
fn verify_in(root: &std::path::Path, extra: &[&str]) -> (i32, String, String) {
    let o = Command::new(env!("CARGO_BIN_EXE_impact"))
        .args(["verify", "--jobs", "1", "--root"])
        .arg(root)
        .arg("--out")
        .arg(root.join("out"))
        .args(extra)
        .output()
        .expect("run impact");
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

#[test]
fn only_declared_known_failures_exit_0() {
    let (code, stdout, _) = verify(&format!("{}{}", passes(), known(&fails())), &[]);
    assert_eq!(code, 0, "{stdout}");
    assert!(
        stdout.contains("1 OK, 1 known FAIL, 0 unexpected FAIL, 0 XPASS, 0 SKIP"),
        "{stdout}"
    );
    assert!(stdout.contains("FAIL*"), "{stdout}");
}

#[test]
fn an_undeclared_failure_exits_1() {
    let (code, stdout, _) = verify(
        &format!(
            "{}{}{}",
            passes(),
            known(&fails()).replace("id: fails", "id: fails-known"),
            fails()
        ),
        &[],
    );
    assert_eq!(code, 1, "{stdout}");
    assert!(
        stdout.contains("1 OK, 1 known FAIL, 1 unexpected FAIL, 0 XPASS, 0 SKIP"),
        "{stdout}"
    );
}

#[test]
fn a_known_failure_that_passes_exits_1() {
    let (code, stdout, _) = verify(&known(&passes()), &[]);
    assert_eq!(code, 1, "{stdout}");
    assert!(stdout.contains("XPASS"), "{stdout}");
    assert!(
        stdout.contains("0 OK, 0 known FAIL, 0 unexpected FAIL, 1 XPASS, 0 SKIP"),
        "{stdout}"
    );
}

#[test]
fn a_broken_case_is_a_fail_row_and_the_other_suites_run() {
    let root = scratch(&passes());
    let broken = root.join("verification/cases/another/broken");
    std::fs::create_dir_all(&broken).unwrap();
    std::fs::write(broken.join("case.yaml"), "id: [not, a, string]\n").unwrap();
    let (code, stdout, stderr) = verify_in(&root, &[]);
    assert_eq!(code, 1, "{stdout}{stderr}");
    assert!(
        stderr.contains("another/broken is broken") && stderr.contains("case.yaml:1:"),
        "names the case and the file: {stderr}"
    );
    assert!(
        stdout.contains("1 OK, 0 known FAIL, 1 unexpected FAIL"),
        "the good case ran: {stdout}"
    );
    let results = std::fs::read_to_string(root.join("out/results.json")).unwrap();
    assert!(results.contains("\"case-loads\""), "{results}");
    assert!(
        stderr.contains("verify: 2 cases, 2 checks: 1 OK, 1 FAIL (exit 1, "),
        "the total counts the broken case's FAIL row: {stderr}"
    );
    let _ = std::fs::remove_dir_all(&root);
}

#[test]
fn bad_usage_exits_2() {
    let (code, _, stderr) = verify(&passes(), &["--no-such-flag"]);
    assert_eq!(code, 2, "{stderr}");
}

#[test]
fn each_case_is_announced_as_it_finishes_with_its_verdicts_then_a_total() {
    let root = scratch(&format!("{}{}", passes(), known(&fails())));
    // A second case in another suite whose one check fails (a new failure).
    let other = root.join("verification/cases/other/case");
    std::fs::create_dir_all(&other).unwrap();
    let yaml = std::fs::read_to_string(root.join("verification/cases/suite/case/case.yaml"))
        .unwrap()
        .replace("id: c1", "id: c2")
        .replace("REQ-1", "REQ-2");
    let yaml = format!("{}{}", &yaml[..yaml.find("checks:").unwrap() + 7], fails());
    std::fs::write(other.join("case.yaml"), yaml).unwrap();
    let (code, stdout, stderr) = verify_in(&root, &[]);
    assert_eq!(code, 1, "{stdout}{stderr}");
    for line in [
        "finished suite/case: 1 OK, 1 FAIL* (1 run, ",
        "finished other/case: 0 OK, 1 FAIL (1 run, ",
        "verify: 2 cases, 3 checks: 1 OK, 1 FAIL*, 1 FAIL (exit 1, ",
    ] {
        assert!(stderr.contains(line), "expected {line:?} in: {stderr}");
    }
    // The total comes last, after every case's line.
    let total = stderr.find("verify: 2 cases").unwrap();
    assert!(stderr.rfind("finished ").unwrap() < total, "{stderr}");
    let _ = std::fs::remove_dir_all(&root);
}
