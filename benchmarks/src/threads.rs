//! `impact-bench threads`: does the element loop's team of threads ever make a run slower
//! (issue 28)? The paper's Table 1 elasto-plastic scene (80 x 16 q4-sri, 3 ms) on one thread,
//! on the team that never falls back (its parts claimed by whoever comes first, never timed),
//! and on the default (the team, falling back to one thread when it is measured slower), each
//! run in turn (interleaved A/B/C, so a change of the machine's load hits all three alike),
//! the minimum of several runs; first on the machine as it is ("idle"), then with all cores but
//! one busy (a spinning child process per core, started here and killed after). Writes
//! `threads.csv`.
//!
//! Targets: busy, the default at most 1.1 x the one-thread time; idle, the default at most
//! 1.05 x the team without fallback (it keeps the team's gain: the fallback's probes cost a
//! block of one-thread steps now and then). Not in `all`: it loads the machine on purpose.

use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::Instant;

use impact_solver::kernels::fallback::{with_policy, Policy};
use impact_solver::kernels::thread_count::cores;
use impact_solver::workers::with_threads;
use impact_solver::{simulate, Quiet, Scene};

use crate::common::{paper, write_csv};

/// The busy machine's target: default / one thread, at most.
const BUSY_TARGET: f64 = 1.1;
/// The idle machine's target: default / team without fallback, at most.
const IDLE_TARGET: f64 = 1.05;

/// One way to run: its name, threads and fallback policy.
type Way = (&'static str, usize, Policy);

/// Spinning child processes (`sh -c 'while :; do :; done'`), killed when dropped.
struct Busy(Vec<Child>);

impl Busy {
    fn start(processes: usize) -> anyhow::Result<Busy> {
        let spin = || {
            Command::new("sh")
                .args(["-c", "while :; do :; done"])
                .stdin(Stdio::null())
                .spawn()
        };
        let children = (0..processes)
            .map(|_| spin())
            .collect::<Result<Vec<_>, _>>()?;
        // Let the scheduler see them running before the first timed run.
        std::thread::sleep(std::time::Duration::from_millis(200));
        Ok(Busy(children))
    }
}

impl Drop for Busy {
    fn drop(&mut self) {
        for c in &mut self.0 {
            let _ = c.kill();
            let _ = c.wait();
        }
    }
}

/// The runs of one way: wall times (s), and how many fell back.
#[derive(Default)]
struct Runs {
    wall_s: Vec<f64>,
    fell_back: usize,
}

impl Runs {
    fn min(&self) -> f64 {
        self.wall_s.iter().copied().fold(f64::INFINITY, f64::min)
    }

    fn median(&self) -> f64 {
        let mut w = self.wall_s.clone();
        w.sort_by(f64::total_cmp);
        w[w.len() / 2]
    }
}

/// The 1-minute load average (/proc/loadavg), "-" where there is none.
fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|t| t.split_whitespace().next().map(str::to_string))
        .unwrap_or_else(|| "-".into())
}

/// Runs every way `repeats` times in turn; each run's history must keep the first's bits.
fn interleaved(scene: &Scene, ways: &[Way], repeats: usize) -> anyhow::Result<Vec<Runs>> {
    let mut runs: Vec<Runs> = ways.iter().map(|_| Runs::default()).collect();
    let mut first: Option<Vec<u64>> = None;
    for _ in 0..repeats {
        for (&(name, threads, policy), r) in ways.iter().zip(&mut runs) {
            let started = Instant::now();
            let o = with_threads(threads, || {
                with_policy(policy, || simulate(scene, &mut Quiet))
            })?;
            r.wall_s.push(started.elapsed().as_secs_f64());
            r.fell_back += usize::from(o.summary.threads_fallback.is_some());
            let bits: Vec<u64> = o.history.values.iter().map(|x| x.to_bits()).collect();
            match &first {
                None => first = Some(bits),
                Some(b) if *b != bits => anyhow::bail!("{name}: not the first run's bits"),
                Some(_) => {}
            }
        }
    }
    Ok(runs)
}

/// The `threads.csv` rows of one load: the ways' runs and the target of the default's.
fn rows(load: &str, average: &str, ways: &[Way], runs: &[Runs]) -> Vec<Vec<String>> {
    let (one, team) = (runs[0].min(), runs[1].min());
    ways.iter()
        .zip(runs)
        .map(|(&(name, threads, _), r)| {
            let (target, status) = match (name, load) {
                ("default", "idle") => (
                    format!("<= {IDLE_TARGET} x team-without-fallback"),
                    r.min() <= IDLE_TARGET * team,
                ),
                ("default", _) => (
                    format!("<= {BUSY_TARGET} x one-thread"),
                    r.min() <= BUSY_TARGET * one,
                ),
                _ => ("-".into(), true),
            };
            let status = match (target.as_str(), status) {
                ("-", _) => "-",
                (_, true) => "met",
                (_, false) => "missed",
            };
            vec![
                load.to_string(),
                average.to_string(),
                name.to_string(),
                threads.to_string(),
                r.wall_s.len().to_string(),
                format!("{:.3}", r.min()),
                format!("{:.3}", r.median()),
                format!("{:.2}", r.min() / one),
                r.fell_back.to_string(),
                target,
                status.to_string(),
            ]
        })
        .collect()
}

/// Runs the benchmark and writes `out/threads.csv`.
pub fn run(out: &Path, quick: bool) -> anyhow::Result<()> {
    let scene = paper(true);
    let cores = cores();
    let repeats = if quick { 2 } else { 5 };
    let ways: [Way; 3] = [
        ("one-thread", 1, Policy::Measure),
        ("team-without-fallback", cores, Policy::Never),
        ("default", cores, Policy::Measure),
    ];
    let mut table = Vec::new();
    // Busy: every core but the run's first; on one core only the idle machine.
    let loads = if cores > 1 {
        vec![0, cores - 1]
    } else {
        vec![0]
    };
    for busy in loads {
        let average = load_average();
        let _spinning = Busy::start(busy)?;
        let load = match busy {
            0 => "idle".to_string(),
            n => format!("busy: {n} spinning process(es)"),
        };
        let runs = interleaved(&scene, &ways, repeats)?;
        let rows = rows(&load, &average, &ways, &runs);
        for r in &rows {
            println!("threads: {}", r.join(", "));
        }
        table.extend(rows);
    }
    write_csv(
        &out.join("threads.csv"),
        &[
            "load",
            "load_average_1min_before",
            "run",
            "threads",
            "runs",
            "min_wall_s",
            "median_wall_s",
            "min_over_one_thread",
            "runs_that_fell_back",
            "target",
            "status",
        ],
        &table,
    )
}
