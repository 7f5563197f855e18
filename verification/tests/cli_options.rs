//! The command line has one set of defaults and explains itself (issue 13): every option of
//! every `impact` subcommand has help text, `verify --out` defaults to the README's
//! `out/verification`, and `--jobs 0` / `--threads 0` are refused with a message.
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
