//! `impact diff` refuses what it cannot compare, with a message naming the file, the row or
//! key and what is expected, and exit status 2 (never "bit-identical"): a NaN or inf in a
//! history, a `time_s` column that runs backwards or repeats (a run's history written twice
//! over), a `summary.json` that is not a JSON object, and two runs with no common time
//! window. Small run folders written by hand (history.csv + summary.json), no solver run.

use std::path::{Path, PathBuf};
use std::process::Command;

const HEADER: &str = "time_s,contact_force_N,mid_uy_m,energy_balance_error";
const SUMMARY: &str =
    r#"{"impulse_Ns": 100.0, "peak_contact_force_N": 5000.0, "wall_time_s": 0.1}"#;

/// Rows of a small history: time (s), force (N), mid-span deflection (m), balance error.
fn rows(times: &[f64]) -> Vec<String> {
    times
        .iter()
        .map(|t| format!("{t:e},{:e},{:e},1e-12", 1e9 * t, -10.0 * t))
        .collect()
}

fn dir(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("diff-refuses-{name}"));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A run folder `d/name` with this summary text and these history rows.
fn run(d: &Path, name: &str, summary: &str, rows: &[String]) -> PathBuf {
    let out = d.join(name);
    std::fs::create_dir_all(&out).unwrap();
    std::fs::write(out.join("summary.json"), summary).unwrap();
    std::fs::write(
        out.join("history.csv"),
        format!("{HEADER}\n{}\n", rows.join("\n")),
    )
    .unwrap();
    out
}

/// `impact diff a b`: exit status, stdout, stderr.
fn diff(a: &Path, b: &Path) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_impact"))
        .arg("diff")
        .args([a, b])
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn assert_refused(a: &Path, b: &Path, words: &[&str]) {
    let (code, text, err) = diff(a, b);
    assert_eq!(code, 2, "stdout:\n{text}\nstderr:\n{err}");
    for w in words {
        assert!(err.contains(w), "{w:?} not in:\n{err}");
    }
}

#[test]
fn a_nan_or_inf_in_a_history_is_refused() {
    let d = dir("nan");
    let good = rows(&[0.0, 1e-6, 2e-6, 3e-6]);
    let a = run(&d, "a", SUMMARY, &good);
    for (name, bad) in [("nan", "NaN"), ("inf", "inf"), ("minus-inf", "-inf")] {
        let mut r = good.clone();
        r[2] = format!("2e-6,{bad},-2e-5,1e-12");
        let b = run(&d, name, SUMMARY, &r);
        // In one run, and in both at the same place (once called bit-identical).
        let at = format!(
            "{}: row 4, column contact_force_N",
            b.join("history.csv").display()
        );
        assert_refused(&a, &b, &[&at, bad, "finite"]);
        assert_refused(&b, &b, &[&at, bad]);
    }
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_time_column_that_is_not_strictly_increasing_is_refused() {
    let d = dir("time");
    let a = run(&d, "a", SUMMARY, &rows(&[0.0, 1e-6, 2e-6, 3e-6]));
    // Backwards: row 4 goes back from 2e-6 to 1.5e-6 s.
    let back = run(&d, "back", SUMMARY, &rows(&[0.0, 2e-6, 1.5e-6, 3e-6]));
    assert_refused(&back, &back, &["row 4", "time_s", "strictly increasing"]);
    assert_refused(&a, &back, &["back", "row 4", "time_s"]);
    // A repeated time.
    let twice = run(&d, "twice", SUMMARY, &rows(&[0.0, 1e-6, 1e-6, 2e-6]));
    assert_refused(&a, &twice, &["twice", "row 4", "time_s"]);
    // The whole history written out three times over (once called bit-identical).
    let one = rows(&[0.0, 1e-6, 2e-6, 3e-6]);
    let thrice: Vec<String> = (0..3).flat_map(|_| one.clone()).collect();
    let b = run(&d, "thrice", SUMMARY, &thrice);
    assert_refused(&a, &b, &["thrice", "row 6", "time_s"]);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_summary_that_is_not_a_json_object_is_refused() {
    let d = dir("summary");
    let r = rows(&[0.0, 1e-6, 2e-6]);
    let a = run(&d, "a", SUMMARY, &r);
    for (name, text, what) in [
        ("array", "[1, 2]", "an array"),
        ("number", "3.5", "a number"),
        ("null", "null", "null"),
        ("text", "\"done\"", "a string"),
    ] {
        let b = run(&d, name, text, &r);
        let file = b.join("summary.json").display().to_string();
        assert_refused(&b, &b, &[&file, "JSON object", what]);
        assert_refused(&a, &b, &[&file, "JSON object", what]);
    }
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn runs_without_a_common_time_window_are_refused() {
    let d = dir("window");
    let a = run(&d, "a", SUMMARY, &rows(&[0.0, 1e-6, 2e-6]));
    let later = run(&d, "later", SUMMARY, &rows(&[5e-6, 6e-6, 7e-6]));
    assert_refused(
        &a,
        &later,
        &["no common time window", "[0.000000e0, 2.000000e-6]"],
    );
    assert_refused(&later, &a, &["no common time window"]);
    // Touching at one instant is no window either.
    let after = run(&d, "after", SUMMARY, &rows(&[2e-6, 3e-6]));
    assert_refused(&a, &after, &["no common time window"]);
    // They overlap in [4, 6] us, but no row of A lies there.
    let sparse = run(&d, "sparse", SUMMARY, &rows(&[0.0, 1e-5]));
    let inside = run(&d, "inside", SUMMARY, &rows(&[4e-6, 6e-6]));
    assert_refused(
        &sparse,
        &inside,
        &["no row of", "[4.000000e-6, 6.000000e-6]"],
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// A negative `--tol` reaches the validator's message (as `--tol NaN` does), not the argument
/// parser's "unexpected argument '-1'" of the old command.
#[test]
fn a_negative_tolerance_is_refused_by_its_own_message() {
    let d = dir("negative-tol");
    let a = run(&d, "a", SUMMARY, &rows(&[0.0, 1e-6, 2e-6]));
    for tol in ["-1", "NaN"] {
        let out = Command::new(env!("CARGO_BIN_EXE_impact"))
            .arg("diff")
            .args([&a, &a])
            .args(["--tol", tol])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(
            err.contains(&format!("--tol = {tol}: must be a finite number >= 0")),
            "{err}"
        );
    }
    let _ = std::fs::remove_dir_all(&d);
}

/// Each history column carries the ISO/TS 18571 rating of B against A
/// (`impact_verification::review::iso18571`): 1.000 excellent for a column equal in both (a
/// constant one too, whose slopes are zero on both sides), lower for one scaled by 1.3.
#[test]
fn each_column_is_rated_by_iso_18571() {
    let d = dir("iso");
    let times: Vec<f64> = (0..200).map(|k| k as f64 * 1e-7).collect();
    let a = run(&d, "a", SUMMARY, &rows(&times));
    let scaled: Vec<String> = times
        .iter()
        .map(|t| format!("{t:e},{:e},{:e},1e-12", 1.3e9 * t, -10.0 * t))
        .collect();
    let b = run(&d, "b", SUMMARY, &scaled);
    let (_, text, _) = diff(&a, &b);
    let line = |name: &str| {
        text.lines()
            .find(|l| l.starts_with(name))
            .unwrap_or_else(|| panic!("{name} not in:\n{text}"))
            .to_string()
    };
    assert!(line("mid_uy_m").contains("1.000 excellent"), "{text}");
    let force = line("contact_force_N");
    assert!(
        !force.contains("excellent") && !force.contains(" - "),
        "{text}"
    );
    let balance = line("energy_balance_error");
    assert!(balance.contains("1.000 excellent"), "{text}");
    let _ = std::fs::remove_dir_all(&d);
}
