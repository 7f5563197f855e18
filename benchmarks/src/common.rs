//! Scenes, timing and table helpers shared by the benchmarks.

use std::path::Path;

use impact_solver::scene::{Load, Pulse};
use impact_solver::{simulate, Outcome, Quiet, Scene};

pub const ELASTIC: &str = include_str!("../../verification/scenes/example-elastic.yaml");
pub const PLASTIC: &str = include_str!("../../verification/scenes/example-plastic.yaml");

/// The example scene (the paper plate), without field output and with sparse history.
pub fn example(plastic: bool) -> Scene {
    let text = if plastic { PLASTIC } else { ELASTIC };
    let mut s = Scene::from_yaml(
        text,
        Path::new(if plastic {
            "example-plastic"
        } else {
            "example-elastic"
        }),
    )
    .expect("the example scenes are valid");
    s.output.fields_every = None;
    s.output.every = Some(1e-5);
    s
}

/// The paper's verification load: 86.5 kN rectangular pulse of 1 ms on the elastic plate.
pub fn pulse() -> Scene {
    let mut s = example(false);
    s.load = Load::Pulse(Pulse {
        force: 86.5e3,
        duration: 1.0e-3,
    });
    s
}

/// Best (minimum) wall times of a scene over `repeats` runs after one warm-up run:
/// (setup s, time loop s) and the last outcome.
pub fn timed(scene: &Scene, repeats: usize) -> anyhow::Result<(f64, f64, Outcome)> {
    let mut best = (f64::INFINITY, f64::INFINITY);
    let mut last = simulate(scene, &mut Quiet)?;
    for _ in 0..repeats {
        last = simulate(scene, &mut Quiet)?;
        best.0 = best.0.min(last.summary.setup_time);
        best.1 = best.1.min(last.summary.loop_time);
    }
    Ok((best.0, best.1, last))
}

/// Writes rows as CSV (a header, then values; strings as given).
pub fn write_csv(path: &Path, header: &[&str], rows: &[Vec<String>]) -> anyhow::Result<()> {
    let mut text = header.join(",") + "\n";
    for r in rows {
        text += &(r.join(",") + "\n");
    }
    std::fs::write(path, text)?;
    Ok(())
}

/// A Markdown table.
pub fn markdown_table(header: &[&str], rows: &[Vec<String>]) -> String {
    let mut t = format!(
        "| {} |\n|{}|\n",
        header.join(" | "),
        vec!["---"; header.len()].join("|")
    );
    for r in rows {
        t += &format!("| {} |\n", r.join(" | "));
    }
    t
}
