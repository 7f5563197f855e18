//! `impact diff`'s closing summary lists what moved, largest relative move first, the physical
//! quantities (forces, displacements, impulse, ...) before the bookkeeping ones (round-off
//! residuals such as `impulse_momentum_error` and the energy balance error), so that its
//! headline is the largest physical move and not a residual going from 3.5e-15 to 9.5e-16
//! (a relative move of 73 %). `--tol` still judges every compared value (exit 1 beyond it).

use std::path::{Path, PathBuf};
use std::process::Command;

fn run(d: &Path, name: &str, summary: &str, history: &str) -> PathBuf {
    let out = d.join(name);
    std::fs::create_dir_all(&out).unwrap();
    std::fs::write(out.join("summary.json"), summary).unwrap();
    std::fs::write(out.join("history.csv"), history).unwrap();
    out
}

fn diff(args: &[&Path]) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_impact"))
        .arg("diff")
        .args(args)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    let err = String::from_utf8_lossy(&out.stderr);
    (out.status.code().unwrap_or(-1), format!("{text}{err}"))
}

#[test]
fn the_closing_summary_leads_with_the_largest_physical_move() {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join("diff-moves");
    let _ = std::fs::remove_dir_all(&d);
    let a = run(
        &d,
        "a",
        r#"{"impulse_Ns": 100.0, "impulse_momentum_error": 3.5e-15, "max_energy_balance_error": 1.0e-5, "n_steps": 3, "wall_time_s": 0.1}"#,
        "time_s,contact_force_N,mid_uy_m,energy_balance_error\n0,0,0,0\n1e-6,1000,-1e-5,1e-12\n2e-6,2000,-2e-5,2e-12\n",
    );
    // Force +2 % of its peak at 2 us, impulse +0.1 %, deflection unchanged; the residuals
    // move by large fractions of themselves.
    let b = run(
        &d,
        "b",
        r#"{"impulse_Ns": 100.1, "impulse_momentum_error": 9.5e-16, "max_energy_balance_error": 1.1e-5, "n_steps": 3, "wall_time_s": 0.2}"#,
        "time_s,contact_force_N,mid_uy_m,energy_balance_error\n0,0,0,0\n1e-6,1000,-1e-5,5e-12\n2e-6,2040,-2e-5,2e-12\n",
    );
    let (code, text) = diff(&[&a, &b]);
    assert_eq!(code, 1, "{text}");
    let last = text.lines().last().unwrap();
    assert!(
        last.ends_with("largest relative change 2.000e-2 in contact_force_N"),
        "{text}"
    );
    // The moves in order: physical by size, then bookkeeping by size.
    let listed = |name: &str| {
        text.lines()
            .position(|l| l.trim_start().starts_with(&format!("{name} ")) && l.contains("move"))
            .unwrap_or_else(|| panic!("{name} not listed as a move:\n{text}"))
    };
    let order = [
        listed("contact_force_N"),
        listed("impulse_Ns"),
        listed("energy_balance_error"),
        listed("impulse_momentum_error"),
        listed("max_energy_balance_error"),
    ];
    assert!(order.windows(2).all(|w| w[0] < w[1]), "{order:?}\n{text}");
    assert!(
        !text
            .lines()
            .any(|l| l.contains("move") && (l.contains("mid_uy_m") || l.contains("n_steps"))),
        "unmoved values listed:\n{text}"
    );
    // A tolerance above the physical moves still sees the residuals beyond it.
    let (code, text) = diff(&[&a, &b, Path::new("--tol"), Path::new("0.05")]);
    assert_eq!(code, 1, "{text}");
    assert!(text.contains("3 beyond --tol 0.05"), "{text}");
    let _ = std::fs::remove_dir_all(&d);
}
