//! The command line has one set of defaults and explains itself (issue 13): every option of
//! every `impact` subcommand has help text, `verify --out` defaults to the README's
//! `out/verification`, and `--jobs 0` / `--threads 0` are refused with a message, and so is a
//! thread count above 4 x the cores (at most 256): `--threads 65535` once spent minutes
//! starting threads.
//! Reference: the list of CLI inconsistencies.

use std::process::Command;

fn impact(args: &[&str]) -> (i32, String, String) {
    let o = Command::new(env!("CARGO_BIN_EXE_impact"))
        .args(args)
        .output()
        .unwrap();
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

#[test]
fn every_option_has_help_text() {
    for sub in ["simulate", "verify", "lint", "report", "diff"] {
        let (code, help, _) = impact(&[sub, "--help"]);
        assert_eq!(code, 0);
        // clap prints an option and its help on one line, or the help on the next lines.
        let lines: Vec<&str> = help.lines().collect();
        for (i, line) in lines.iter().enumerate() {
            let t = line.trim_start();
            if !t.starts_with("--") && !(t.starts_with('-') && t.chars().nth(2) == Some(',')) {
                continue;
            }
            let own_text = t.split("  ").filter(|s| !s.trim().is_empty()).count() > 1;
            let next_text = lines
                .get(i + 1)
                .is_some_and(|n| n.starts_with("          ") && !n.trim().is_empty());
            assert!(own_text || next_text, "{sub}: no help for {t:?}\n{help}");
        }
    }
}

#[test]
fn defaults_follow_the_readme_and_zero_workers_are_refused() {
    let (_, help, _) = impact(&["verify", "--help"]);
    assert!(help.contains("[default: out/verification]"), "{help}");
    let (code, _, err) = impact(&["verify", "--jobs", "0"]);
    assert_eq!(code, 2);
    assert!(err.contains("--jobs"), "{err}");
    let (code, _, err) = impact(&["simulate", "s.yaml", "--out", "o", "--threads", "0"]);
    assert_eq!(code, 2);
    assert!(err.contains("--threads"), "{err}");
}

#[test]
fn a_thread_count_above_the_bound_is_refused_at_once() {
    let max = impact_solver::kernels::thread_count::max_threads();
    for n in [max + 1, 65535, 1_000_000_000] {
        let n = n.to_string();
        let mut child = Command::new(env!("CARGO_BIN_EXE_impact"))
            .args(["simulate", "no-such.yaml", "--out", "o", "--threads", &n])
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        // Killed when still starting threads after 60 s: a failure, not a test that hangs.
        let started = std::time::Instant::now();
        while child.try_wait().unwrap().is_none() {
            if started.elapsed().as_secs() > 60 {
                let _ = child.kill();
                let _ = child.wait();
                panic!("--threads {n}: still running after 60 s");
            }
            std::thread::sleep(std::time::Duration::from_millis(20));
        }
        let out = child.wait_with_output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        let says = format!("--threads = {n}: must be an integer from 1 to {max} ");
        assert!(
            err.contains(&says) && !err.contains("no-such.yaml"),
            "{err}"
        );
    }
    // The bound itself is accepted (the run then fails on the missing scene).
    let (code, _, err) = impact(&[
        "simulate",
        "no-such.yaml",
        "--out",
        "o",
        "--threads",
        &max.to_string(),
    ]);
    assert_eq!(code, 2);
    assert!(
        err.contains("no-such.yaml") && !err.contains("must be an integer"),
        "{err}"
    );
}
