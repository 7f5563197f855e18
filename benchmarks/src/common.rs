//! Scenes, timing and table helpers shared by the benchmarks.

use std::path::Path;

use impact_solver::simd::KernelPath;
use impact_solver::{simulate_on, History, Outcome, Quiet, Scene};

const ELASTIC: &str = include_str!("../../verification/scenes/paper-elastic.yaml");
const PLASTIC: &str = include_str!("../../verification/scenes/paper-plastic.yaml");
const PULSE: &str = include_str!("../../verification/scenes/paper-pulse-elastic.yaml");

/// A scene of the paper's case on the reconstructed plate, without field output and with a
/// history row every 1e-5 s (as `reference-data/independent/scenes/table1-*.yaml`).
fn sparse(text: &str, name: &str) -> Scene {
    let mut s = Scene::from_yaml(text, Path::new(name)).expect("the paper scenes are valid");
    s.output.fields_every = None;
    s.output.every = Some(1e-5);
    s
}

/// The Table 1 impact (18 kg at 10 m/s) on the reconstructed paper plate, 80 x 16 q4-sri, 3 ms.
pub fn paper(plastic: bool) -> Scene {
    if plastic {
        sparse(PLASTIC, "paper-plastic.yaml")
    } else {
        sparse(ELASTIC, "paper-elastic.yaml")
    }
}

/// The paper's verification load on the elastic reconstructed plate: 86.5 kN rectangular
/// pulse of 1.279 ms (verification/scenes/paper-pulse-elastic.yaml).
pub fn pulse() -> Scene {
    sparse(PULSE, "paper-pulse-elastic.yaml")
}

/// Best (minimum) wall times of a scene over `repeats` runs after one warm-up run:
/// (setup s, time loop s) and the last outcome.
pub fn timed(scene: &Scene, repeats: usize) -> anyhow::Result<(f64, f64, Outcome)> {
    timed_on(scene, repeats, KernelPath::fastest())
}

/// [`timed`] with the element kernels on `path`.
pub fn timed_on(
    scene: &Scene,
    repeats: usize,
    path: KernelPath,
) -> anyhow::Result<(f64, f64, Outcome)> {
    let once = || -> anyhow::Result<Outcome> {
        let mut history = History::default();
        let (summary, mesh) = simulate_on(scene, &mut Quiet, None, &mut history, path)?;
        Ok(Outcome {
            summary,
            history,
            mesh,
        })
    };
    let mut best = (f64::INFINITY, f64::INFINITY);
    let mut last = once()?;
    for _ in 0..repeats {
        last = once()?;
        best.0 = best.0.min(last.summary.setup_time);
        best.1 = best.1.min(last.summary.loop_time);
    }
    Ok((best.0, best.1, last))
}

/// Writes rows as CSV (a header, then values; strings as given, quoted only where a value
/// holds a comma, a quote or a line break, e.g. a stability note).
pub fn write_csv(path: &Path, header: &[&str], rows: &[Vec<String>]) -> anyhow::Result<()> {
    let mut w = csv::Writer::from_path(path)?;
    w.write_record(header)?;
    for r in rows {
        w.write_record(r)?;
    }
    w.flush()?;
    Ok(())
}

/// A Markdown table; a `|` or line break inside a cell is escaped so the row stays one row.
pub fn markdown_table<S: AsRef<str>>(header: &[S], rows: &[Vec<String>]) -> String {
    let cells = |r: &mut dyn Iterator<Item = &str>| -> String {
        r.map(|c| c.replace('|', "\\|").replace('\n', " "))
            .collect::<Vec<_>>()
            .join(" | ")
    };
    let mut t = format!(
        "| {} |\n|{}|\n",
        cells(&mut header.iter().map(AsRef::as_ref)),
        vec!["---"; header.len()].join("|")
    );
    for r in rows {
        t += &format!("| {} |\n", cells(&mut r.iter().map(String::as_str)));
    }
    t
}
