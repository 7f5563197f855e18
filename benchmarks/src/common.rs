//! Scenes, timing and table helpers shared by the benchmarks.

use std::path::Path;

use impact_solver::simd::KernelPath;
use impact_solver::{simulate_on, History, Outcome, Quiet, Scene};

const ELASTIC: &str = include_str!("../../verification/scenes/paper-elastic.yaml");
const PLASTIC: &str = include_str!("../../verification/scenes/paper-plastic.yaml");
const PULSE: &str = include_str!("../../verification/scenes/paper-pulse-elastic.yaml");
const TAYLOR: &str = include_str!("../../verification/scenes/taylor-bar-kamoulakos.yaml");
const TAYLOR_42CRMO4: &str = include_str!("../../verification/scenes/taylor-bar-42crmo4.yaml");

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

/// The Taylor bar of Kamoulakos (verification/scenes/taylor-bar-kamoulakos.yaml: finite
/// deformation, 10 x 36 q4-sri, 80 us, the step fixed at cfl 0.02), history every 1e-6 s;
/// `every_step`: the step re-estimated at every step at cfl 0.8 instead.
pub fn taylor_bar(every_step: bool) -> Scene {
    let mut s = Scene::from_yaml(TAYLOR, Path::new("taylor-bar-kamoulakos.yaml"))
        .expect("the Taylor bar scene is valid");
    s.output.every = Some(1e-6);
    if every_step {
        s.time.dt = impact_solver::scene::DtChoice::Cfl(0.8);
        s.time.dt_update = impact_solver::scene::DtUpdate::EveryStep;
    }
    s
}

/// DynELA's Johnson-Cook Taylor bar of 42CrMo4 (verification/scenes/taylor-bar-42crmo4.yaml:
/// axisymmetric 5 x 50 q4-sri, finite deformation, heating, 287 m/s, 80 us, the step
/// re-estimated every step at cfl 0.8), as the scene file has it.
pub fn taylor_bar_42crmo4() -> Scene {
    Scene::from_yaml(TAYLOR_42CRMO4, Path::new("taylor-bar-42crmo4.yaml"))
        .expect("the 42CrMo4 Taylor bar scene is valid")
}

/// The paper's verification load on the elastic reconstructed plate: 86.5 kN rectangular
/// pulse of 1.279 ms (verification/scenes/paper-pulse-elastic.yaml).
pub fn pulse() -> Scene {
    sparse(PULSE, "paper-pulse-elastic.yaml")
}

/// Short runs are repeated until their timed runs add up to this (s), for a steadier minimum
/// where timer resolution and interrupts weigh most; it adds well under a second to a whole
/// `all`.
const SHORT_RUNS_TOTAL_S: f64 = 0.05;
/// At most this many runs of a short scene.
const MAX_RUNS: usize = 10;

/// Wall times of a scene's timed runs and its outcome (the same bits on every run).
pub struct Timing {
    /// Best (minimum) setup time over the runs, s.
    pub setup: f64,
    /// Best (minimum) time-loop time over the runs, s.
    pub time_loop: f64,
    /// How many runs were timed.
    pub runs: usize,
    /// Spread of the runs' loop times: largest / smallest - 1 (0 for one run).
    pub spread: f64,
    pub outcome: Outcome,
}

/// [`timed_on`] on this processor's fastest kernels.
pub fn timed(scene: &Scene, runs: usize) -> anyhow::Result<Timing> {
    timed_on(scene, runs, KernelPath::fastest())
}

/// Times `runs` runs of `scene` with the element kernels on `path` (short ones more, up to
/// [`MAX_RUNS`], until they add up to [`SHORT_RUNS_TOTAL_S`]) and keeps the minimum. There is
/// no separate untimed warm-up run: the first run is a sample like the others, and the minimum
/// leaves it out when it is the slower (the warm-up was a third of the work-precision time).
pub fn timed_on(scene: &Scene, runs: usize, path: KernelPath) -> anyhow::Result<Timing> {
    let once = || -> anyhow::Result<Outcome> {
        let mut history = History::default();
        let (summary, mesh) = simulate_on(scene, &mut Quiet, None, &mut history, path)?;
        Ok(Outcome {
            summary,
            history,
            mesh,
        })
    };
    let (mut loops, mut total) = (Vec::new(), 0.0);
    let mut setup = f64::INFINITY;
    loop {
        let o = once()?;
        setup = setup.min(o.summary.setup_time);
        loops.push(o.summary.loop_time);
        total += o.summary.setup_time + o.summary.loop_time;
        let enough = loops.len() >= runs.max(1) && total >= SHORT_RUNS_TOTAL_S;
        if enough || loops.len() >= MAX_RUNS.max(runs) {
            let best = loops.iter().copied().fold(f64::INFINITY, f64::min);
            let worst = loops.iter().copied().fold(0.0, f64::max);
            return Ok(Timing {
                setup,
                time_loop: best,
                runs: loops.len(),
                spread: if best > 0.0 { worst / best - 1.0 } else { 0.0 },
                outcome: o,
            });
        }
    }
}

/// Writes `text` to `path` whole: staged beside it (a hidden name with this process's id),
/// then moved in, so a reader never sees it half-written.
pub fn write_whole(path: &Path, text: &str) -> anyhow::Result<()> {
    let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("file");
    let staged = path.with_file_name(format!(".{name}.partial-{}", std::process::id()));
    std::fs::write(&staged, text)?;
    std::fs::rename(&staged, path)?;
    Ok(())
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
