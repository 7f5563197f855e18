//! `impact diff RUN_A RUN_B`: two runs of the same scene are bit-identical (exit 0, every
//! value `same`), and a deliberately changed scene (impactor 10 -> 10.5 m/s, the kind of
//! change a pull request makes) is reported key by key and column by column, beyond a tight
//! --tol (exit 1) and within a loose one (exit 0). Reference: determinism of the solver and
//! the momentum scaling of the impact (a 5 % faster impactor moves the impulse by percents).

use std::path::{Path, PathBuf};
use std::process::Command;

const EXAMPLE: &str = include_str!("../scenes/example-elastic.yaml");

fn small_scene(velocity: &str) -> String {
    EXAMPLE
        .replace("nx: 80, ny: 16", "nx: 20, ny: 4")
        .replace("end: 3.0e-3", "end: 6.0e-4")
        .replace("velocity: 10.0", &format!("velocity: {velocity}"))
        .replace("  fields: {every: 1.0e-4}", "")
}

fn dir(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("diff-{name}"));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn impact(args: &[&Path]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_impact"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn simulate(d: &Path, name: &str, velocity: &str) -> PathBuf {
    let scene = d.join(format!("{name}.yaml"));
    std::fs::write(&scene, small_scene(velocity)).unwrap();
    let out = d.join(name);
    let (code, _, err) = impact(&[
        Path::new("simulate"),
        &scene,
        Path::new("--out"),
        &out,
        Path::new("--quiet"),
    ]);
    assert_eq!(code, 0, "{err}");
    out
}

#[test]
fn same_scene_twice_is_bit_identical_and_a_changed_scene_is_reported() {
    let d = dir("changed");
    let a = simulate(&d, "a", "10.0");
    let again = simulate(&d, "again", "10.0");
    let b = simulate(&d, "b", "10.5");

    let (code, text, err) = impact(&[Path::new("diff"), &a, &again]);
    assert_eq!(code, 0, "{text}{err}");
    assert!(text.contains("0 beyond --tol 0"), "{text}");
    assert!(text.contains("all compared values bit-identical"), "{text}");
    assert!(
        text.contains("wall_time_s") && text.contains("timing"),
        "{text}"
    );

    let (code, text, err) = impact(&[Path::new("diff"), &a, &b]);
    assert_eq!(code, 1, "{text}{err}");
    for key in ["impulse_Ns", "peak_contact_force_N", "contact_force_N"] {
        let line = text
            .lines()
            .find(|l| l.starts_with(key))
            .unwrap_or_else(|| panic!("no line for {key}:\n{text}"));
        assert!(line.ends_with("BEYOND"), "{line}");
    }
    // The impulse grows with the impact momentum: a few percent for 5 % more speed.
    let diff = impact_verification::diff::diff_runs(&a, &b, 0.0).unwrap();
    let impulse = diff.keys.iter().find(|k| k.key == "impulse_Ns").unwrap();
    assert!((0.01..0.1).contains(&impulse.rel.unwrap()), "{:?}", impulse);
    assert!(diff.columns.iter().any(|c| c.column == "contact_force_N"));

    // A tolerance above every relative change accepts the branch.
    let (code, text, _) = impact(&[
        Path::new("diff"),
        &a,
        &b,
        Path::new("--tol"),
        Path::new("10"),
    ]);
    assert_eq!(code, 0, "{text}");
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_folder_without_a_run_is_an_error_naming_it() {
    let d = dir("empty");
    let (code, _, err) = impact(&[Path::new("diff"), &d, &d]);
    assert_eq!(code, 2);
    assert!(
        err.contains("summary.json") && err.contains("impact simulate"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&d);
}
