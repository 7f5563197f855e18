//! `impact`: the command-line front of the solver and of the verification matrix.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use impact_solver::output::RunOptions;
use impact_solver::progress::ProgressMode;
use impact_verification::codes::Code;
use impact_verification::report::ReportOptions;
use impact_verification::run::runner::{self, Options, Repo};

/// Signals closer than this to the first one are taken as the same stop request, s.
const REPEATED_SIGNAL_WINDOW: std::time::Duration = std::time::Duration::from_secs(1);

#[derive(Parser)]
#[command(
    name = "impact",
    version,
    about = "Explicit impact solver (Dokko & Kim 2004) and its verification"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run one scene: writes history.csv, summary.json (and VTK fields if asked) to --out.
    Simulate {
        /// Scene file (YAML, SI units; every key: docs/scene-reference.md).
        scene: PathBuf,
        /// Output folder (created; earlier outputs of the same names are replaced). Refused
        /// when it is `/`, the home folder, or a non-empty folder without an earlier run.
        #[arg(long)]
        out: PathBuf,
        /// No progress and no summary (warnings and errors still print).
        #[arg(long)]
        quiet: bool,
        /// Largest memory the run may take, e.g. 16G, 500M (powers of 1000); default: the
        /// memory available on this machine. A scene whose estimate exceeds it is refused.
        #[arg(long, value_parser = parse_memory)]
        max_memory: Option<f64>,
        /// Write into a non-empty --out folder that holds no earlier run.
        #[arg(long)]
        force: bool,
        /// Threads for the element loop (1 to 4 x the cores, at most 256; default: the number
        /// of cores). Results are bit-identical for every thread count.
        #[arg(long, value_parser = parse_threads)]
        threads: Option<usize>,
        /// When the run stops on an error or Ctrl-C after it began, keep what it wrote in
        /// --out: history.csv up to the stop, the field frames, and stopped.json (why and when)
        /// instead of summary.json. Without it nothing is left behind.
        #[arg(long)]
        keep_partial: bool,
    },
    /// Run the verification matrix: prints suite/case/check/status, writes results.json,
    /// junit.xml and matrix.txt to --out. Exit status: 0 when every failing check is a
    /// declared known failure and none passes unexpectedly, 1 on an unexpected FAIL or an
    /// XPASS (a known failure that passes), 2 on bad input or usage.
    Verify {
        /// Suites (folder names under verification/cases), case ids or suite/case; default all.
        selectors: Vec<String>,
        /// Only checks whose suite/case/check name contains this text.
        #[arg(long)]
        filter: Option<String>,
        /// Parallel runs, >= 1 (default: the number of cores).
        #[arg(long, value_parser = clap::value_parser!(u16).range(1..))]
        jobs: Option<u16>,
        /// Output folder (where the README and docs/user-guide.md look for the report).
        #[arg(long, default_value = "out/verification")]
        out: PathBuf,
        /// Leave out the cases marked heavy (what `cargo test` runs).
        #[arg(long)]
        light: bool,
        /// Also write the V&V report (index.html, report.md) to --out.
        #[arg(long)]
        report: bool,
        /// With --report: the benchmarks folder (`impact-bench all --out DIR`) for the
        /// performance section (default: <out>/benchmarks if it exists).
        #[arg(long, requires = "report")]
        benchmarks: Option<PathBuf>,
        /// With --report: the reconstruction page (default:
        /// reference-data/paper/reconstruction/report.md).
        #[arg(long, requires = "report")]
        reconstruction: Option<PathBuf>,
        /// Repository root (default: found from the current folder).
        #[arg(long)]
        root: Option<PathBuf>,
        /// An earlier verify output folder (e.g. of the main branch): results.json gains per
        /// check the baseline value, the change and the change as a fraction of the
        /// tolerance, and the report opens with "What changed".
        #[arg(long)]
        baseline: Option<PathBuf>,
        /// Run only shard K of N (e.g. 2/4): a deterministic, cost-balanced share of the
        /// jobs; writes their results to <out>/shard.json for --merge.
        #[arg(long, value_name = "K/N", conflicts_with = "report")]
        shard: Option<impact_verification::run::shard::Shard>,
        /// Merge the shard folders (all N shards of one run) into the results a single run
        /// writes (results.json, junit.xml, matrix.txt, runs/, with --report the report).
        #[arg(long, value_name = "DIR", num_args = 1.., conflicts_with_all = ["shard", "selectors", "filter", "light"])]
        merge: Vec<PathBuf>,
        /// The code to verify (repeatable; default `impact`, this solver): another code's
        /// name runs the cases through its adapter, adapters/NAME/ (adapters/README.md), and
        /// its rows follow impact's, evaluated by the same checks.
        #[arg(long = "code", value_name = "NAME", conflicts_with_all = ["shard", "merge"])]
        codes: Vec<String>,
        /// Evaluate the checks on results computed elsewhere: DIR/<suite>/<case>/<scene>/
        /// with history.csv and summary.json in the adapter contract (adapters/README.md);
        /// the rows carry DIR's name as their code.
        #[arg(long, value_name = "DIR", conflicts_with_all = ["shard", "merge"])]
        results_from: Option<PathBuf>,
    },
    /// Check the cases: reference kinds, tolerance reasons, unique requirement ids, skip
    /// reasons, provenance of reference files, and that every scene loads with its overrides
    /// (wrong models' included).
    Lint {
        /// Repository root (default: found from the current folder).
        #[arg(long)]
        root: Option<PathBuf>,
    },
    /// Write the scene's JSON Schema (solver/scene.schema.json, read by editors through the
    /// first line of every scene file) and the scene reference generated from it
    /// (docs/scene-reference.md), both from the scene's types.
    Schema {
        /// Repository root (default: found from the current folder).
        #[arg(long)]
        root: Option<PathBuf>,
    },
    /// Compare two `simulate` output folders: every summary.json key, and per history.csv
    /// column the largest absolute and relative difference on A's time grid and the ISO/TS
    /// 18571 rating of B against A; exits 1 when anything differs by more than --tol.
    Diff {
        /// The first run's output folder (the reference, e.g. from the main branch).
        run_a: PathBuf,
        /// The second run's output folder.
        run_b: PathBuf,
        /// Largest relative difference accepted: |A - B| over max(|A|, |B|) for a summary
        /// number, over the column's peak |A| for a history column (default 0: bit-identical,
        /// as runs are deterministic).
        #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
        tol: f64,
    },
    /// Write the V&V report (index.html, report.md) from a verify output folder.
    Report {
        /// Folder written by `impact verify`.
        #[arg(long)]
        from: PathBuf,
        /// Where to write the report (default: the same folder).
        #[arg(long)]
        out: Option<PathBuf>,
        /// The benchmarks folder (`impact-bench all --out DIR`) for the performance section
        /// (default: <from>/benchmarks or <out>/benchmarks, whichever exists).
        #[arg(long)]
        benchmarks: Option<PathBuf>,
        /// The reconstruction page (default: reference-data/paper/reconstruction/report.md).
        #[arg(long)]
        reconstruction: Option<PathBuf>,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Simulate {
            scene,
            out,
            quiet,
            max_memory,
            force,
            threads,
            keep_partial,
        } => {
            let options = RunOptions {
                progress: match (quiet, std::io::stderr().is_terminal()) {
                    (true, _) => ProgressMode::Off,
                    (false, true) => ProgressMode::Bar,
                    (false, false) => ProgressMode::Lines,
                },
                max_memory,
                force,
                // The history streams to history.csv: memory does not grow with time.end.
                keep_history: false,
                stop: None,
                keep_partial,
            };
            simulate(&scene, &out, &options, threads, quiet)
        }
        Command::Verify {
            selectors,
            filter,
            jobs,
            out,
            light,
            report,
            benchmarks,
            reconstruction,
            root,
            baseline,
            shard,
            merge,
            codes,
            results_from,
        } => {
            let report = report.then_some(ReportOptions {
                benchmarks,
                reconstruction,
            });
            let split = match (shard, merge.is_empty()) {
                (Some(s), _) => Split::Shard(s),
                (None, false) => Split::Merge(merge),
                (None, true) => Split::Whole,
            };
            verify(
                selectors,
                filter,
                jobs,
                out,
                light,
                report,
                root,
                baseline,
                split,
                CodeArgs {
                    codes,
                    results_from,
                },
            )
        }
        Command::Lint { root } => lint(root),
        Command::Schema { root } => schema(root),
        Command::Diff { run_a, run_b, tol } => {
            match impact_verification::review::diff::diff_runs(&run_a, &run_b, tol) {
                Ok(d) => {
                    print!("{}", d.text());
                    if d.n_beyond() > 0 {
                        ExitCode::from(1)
                    } else {
                        ExitCode::SUCCESS
                    }
                }
                Err(e) => {
                    eprintln!("error: {e:#}");
                    ExitCode::from(2)
                }
            }
        }
        Command::Report {
            from,
            out,
            benchmarks,
            reconstruction,
        } => {
            let out = out.unwrap_or_else(|| from.clone());
            let opts = ReportOptions {
                benchmarks,
                reconstruction,
            };
            match impact_verification::report::write_report_with(&from, &out, &opts) {
                Ok(files) => {
                    for f in files {
                        println!("wrote {}", f.display());
                    }
                    ExitCode::SUCCESS
                }
                Err(e) => {
                    eprintln!("error: {e:#}");
                    ExitCode::from(2)
                }
            }
        }
    }
}

fn repo(root: Option<PathBuf>) -> Result<Repo, ExitCode> {
    let found = match root {
        Some(r) => Repo::find(&r),
        None => std::env::current_dir().ok().and_then(|d| Repo::find(&d)),
    };
    found.ok_or_else(|| {
        eprintln!("error: no verification/cases folder here or above (use --root)");
        ExitCode::from(2)
    })
}

fn schema(root: Option<PathBuf>) -> ExitCode {
    let repo = match repo(root) {
        Ok(r) => r,
        Err(c) => return c,
    };
    match impact_solver::input::schema::write_files(&repo.root) {
        Ok(files) => {
            for f in files {
                println!("wrote {}", f.display());
            }
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: impact schema: {e}");
            ExitCode::from(2)
        }
    }
}

fn lint(root: Option<PathBuf>) -> ExitCode {
    let repo = match repo(root) {
        Ok(r) => r,
        Err(c) => return c,
    };
    let (cases, errors) = impact_verification::definition::case::load_cases(&repo.cases_dir());
    let mut findings: Vec<String> = impact_verification::definition::lint::lint(&repo, &cases)
        .iter()
        .map(ToString::to_string)
        .collect();
    // Every scene loads with its overrides (the reader's own message, file:line:col).
    findings.extend(
        cases
            .iter()
            .flat_map(impact_verification::run::plan::scene_problems),
    );
    for e in &errors {
        eprintln!("error: {e}");
    }
    for f in &findings {
        eprintln!("lint: {f}");
    }
    let checks: usize = cases.iter().map(|c| c.file.checks.len()).sum();
    if errors.is_empty() && findings.is_empty() {
        println!("lint: {} cases, {checks} checks: clean", cases.len());
        ExitCode::SUCCESS
    } else {
        eprintln!(
            "lint: {} unreadable case file(s), {} finding(s)",
            errors.len(),
            findings.len()
        );
        ExitCode::from(2)
    }
}

/// The codes `impact verify` runs the cases on (`--code`, `--results-from`).
struct CodeArgs {
    codes: Vec<String>,
    results_from: Option<PathBuf>,
}

impl CodeArgs {
    /// The codes named, each found (an adapter's folder, a results folder) before any run;
    /// `impact` alone when none is named. With another code, Ctrl-C is handled here.
    fn resolve(self, root: &Path) -> Result<Vec<Code>, String> {
        let mut names = self.codes;
        if names.is_empty() && self.results_from.is_none() {
            names.push("impact".into());
        }
        let mut codes = Vec::new();
        for name in &names {
            if names.iter().filter(|n| *n == name).count() > 1 {
                return Err(format!("--code {name} is given twice"));
            }
            codes.push(Code::find(root, name)?);
        }
        if let Some(dir) = &self.results_from {
            let code = Code::results_from(root, dir)?;
            if names.contains(&code.name()) {
                return Err(format!(
                    "--results-from {}: its name {:?} is also a --code",
                    dir.display(),
                    code.name()
                ));
            }
            codes.push(code);
        }
        if codes.iter().any(|c| !c.is_impact()) {
            // Ctrl-C: the adapters' process groups (and the codes they started) are killed
            // and their scratch folders removed before the exit; nothing of --out is written.
            let _ = ctrlc::set_handler(|| {
                impact_solver::interrupt::request_stop();
                impact_verification::codes::process::stop_all();
                std::process::exit(130);
            });
        }
        Ok(codes)
    }
}

/// The whole matrix, one shard of it, or the merge of shards (`impact_verification::run::shard`).
enum Split {
    Whole,
    Shard(impact_verification::run::shard::Shard),
    Merge(Vec<PathBuf>),
}

/// Every input of a verify checked before the first run: the codes found, and a baseline that
/// is missing or malformed refused now, not after the whole matrix (as `impact report --from`
/// refuses it).
fn inputs_checked(
    repo: &Repo,
    code_args: CodeArgs,
    baseline: Option<&Path>,
) -> Result<Vec<Code>, String> {
    if let Some(dir) = baseline {
        impact_verification::report::results::read(&dir.join("results.json"))
            .map_err(|e| format!("--baseline {}: {e:#}", dir.display()))?;
    }
    code_args.resolve(&repo.root)
}

#[allow(clippy::too_many_arguments)]
fn verify(
    selectors: Vec<String>,
    filter: Option<String>,
    jobs: Option<u16>,
    out: PathBuf,
    light: bool,
    report: Option<ReportOptions>,
    root: Option<PathBuf>,
    baseline: Option<PathBuf>,
    split: Split,
    code_args: CodeArgs,
) -> ExitCode {
    let repo = match repo(root) {
        Ok(r) => r,
        Err(c) => return c,
    };
    let codes = match inputs_checked(&repo, code_args, baseline.as_deref()) {
        Ok(c) => c,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let started = std::time::Instant::now();
    let jobs = jobs.map_or_else(
        || std::thread::available_parallelism().map_or(1, |n| n.get()),
        usize::from,
    );
    let opts = Options {
        selectors,
        filter,
        jobs,
        include_heavy: !light,
        progress: std::io::stderr().is_terminal(),
    };
    let outcome = match split {
        Split::Whole => runner::verify_codes(&repo, &opts, &codes),
        Split::Merge(dirs) => impact_verification::run::shard::merge(&repo, &dirs, jobs),
        Split::Shard(shard) => {
            return match impact_verification::run::shard::run_shard(&repo, &opts, shard, &out) {
                Ok((mine, all)) => {
                    println!(
                        "shard {}/{}: ran {mine} of the {all} jobs; wrote {} ({:.1} s); merge with impact verify --merge DIR...",
                        shard.index,
                        shard.count,
                        out.join(impact_verification::run::shard::SHARD_FILE).display(),
                        started.elapsed().as_secs_f64()
                    );
                    ExitCode::SUCCESS
                }
                Err(problems) => {
                    for p in problems {
                        eprintln!("error: {p}");
                    }
                    ExitCode::from(2)
                }
            };
        }
    };
    if impact_solver::interrupt::stop_requested() {
        eprintln!("interrupted: nothing written to {}", out.display());
        return ExitCode::from(130);
    }
    let outcome = match outcome {
        Ok(o) => o,
        Err(problems) => {
            for p in problems {
                eprintln!("error: {p}");
            }
            return ExitCode::from(2);
        }
    };
    for c in &outcome.matrix.cases {
        if let Some(e) = c.job_errors.get("(case.yaml)") {
            eprintln!(
                "error: {}/{} is broken (a FAIL row; the other cases ran): {e}",
                c.suite, c.case
            );
        }
    }
    print!("{}", runner::matrix_text(&outcome.matrix));
    print!("{}", runner::summary_text(&outcome.matrix));
    let wall = started.elapsed().as_secs_f64();
    if let Err(e) = runner::write_outputs(&outcome, &out)
        .and_then(|_| impact_verification::report::write_environment(&repo, &out, wall, jobs))
    {
        eprintln!("error: cannot write {}: {e}", out.display());
        return ExitCode::from(2);
    }
    println!(
        "wrote {}/results.json, junit.xml, matrix.txt ({wall:.1} s, {jobs} jobs)",
        out.display()
    );
    let _ = std::fs::remove_file(out.join("what-changed.md"));
    if let Some(dir) = baseline {
        match impact_verification::review::baseline::apply(&dir, &out) {
            Ok(changes) => println!("{}", changes.line()),
            Err(e) => {
                eprintln!("error: --baseline {}: {e:#}", dir.display());
                return ExitCode::from(2);
            }
        }
    }
    if let Some(opts) = report {
        match impact_verification::report::write_report_with(&out, &out, &opts) {
            Ok(files) => {
                for f in files {
                    println!("wrote {}", f.display());
                }
            }
            Err(e) => {
                eprintln!("error: report: {e:#}");
                return ExitCode::from(2);
            }
        }
    }
    ExitCode::from(outcome.matrix.exit_status())
}

fn simulate(
    scene: &std::path::Path,
    out: &std::path::Path,
    options: &RunOptions,
    threads: Option<usize>,
    quiet: bool,
) -> ExitCode {
    if let Some(n) = threads {
        if let Err(e) = rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build_global()
        {
            eprintln!("error: --threads {n}: {e}");
            return ExitCode::from(2);
        }
    }
    // SIGINT/SIGTERM: the loop stops at its next poll and the staging folder is removed; a
    // second signal ends the process at once (the next run removes what it left). A repeat
    // within REPEATED_SIGNAL_WINDOW is the same request delivered twice (`timeout` signals
    // the child and then its whole process group), not a second request.
    let first_signal = std::sync::OnceLock::new();
    let _ = ctrlc::set_handler(move || {
        let first = first_signal.get_or_init(std::time::Instant::now);
        if impact_solver::interrupt::stop_requested() {
            if first.elapsed() > REPEATED_SIGNAL_WINDOW {
                std::process::exit(130);
            }
            return;
        }
        impact_solver::interrupt::request_stop();
    });
    let mut say = |note: String| {
        if !quiet || note.starts_with("warning") {
            eprintln!("{note}");
        }
    };
    use impact_solver::kernels::fallback::{with_policy, Policy};
    let policy = match Policy::from_env() {
        Ok(policy) => policy,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let run = || impact_solver::output::simulate_to_dir_with(scene, out, options, &mut say);
    match with_policy(policy, run) {
        Ok(outcome) => {
            if !quiet {
                print_summary(&outcome.summary);
            }
            ExitCode::SUCCESS
        }
        Err(e @ impact_solver::Error::Interrupted { .. }) => {
            eprintln!("stopped: {e}");
            ExitCode::from(130)
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}

/// `--threads N`: an integer from 1 to `thread_count::max_threads()`.
fn parse_threads(text: &str) -> Result<usize, String> {
    use impact_solver::kernels::thread_count::{check_threads, refusal};
    match text.trim().parse::<u64>() {
        Ok(n) => check_threads("--threads", n),
        Err(_) => Err(refusal("--threads", text)),
    }
}

fn parse_memory(text: &str) -> Result<f64, String> {
    impact_solver::budget::parse_bytes(text)
        .ok_or_else(|| format!("{text:?}: expected a size such as 16G, 500M or 2.5e9 (bytes)"))
}

fn print_summary(s: &impact_solver::Summary) {
    match &s.wall {
        Some(wall) => print_wall(wall),
        None => print_plate(s),
    }
    if let Some(v) = s.final_impactor_velocity {
        println!("final impactor velocity {:>14.6e} m/s", v);
    }
    for (probe, vm) in &s.max_von_mises {
        println!("max von Mises at {probe:<6} {:>14.6e} Pa", vm);
    }
    println!(
        "energy balance error    {:>14.6e} (max)",
        s.max_energy_balance_error
    );
    if let Some(e) = s.impulse_momentum_error {
        println!("impulse-momentum error  {:>14.6e} (relative)", e);
    }
    let step = match (s.dt_min, s.dt_max) {
        (Some(lo), Some(hi)) => format!(
            "dt {:.4e} s at the start ({:.3} of stable), re-estimated every step: {lo:.4e} to {hi:.4e} s",
            s.dt, s.cfl
        ),
        _ => format!("dt {:.4e} s ({:.3} of stable)", s.dt, s.cfl),
    };
    println!(
        "{step}, {} steps, {} elements, {:.3} s wall ({:.1} ns per element-step)",
        s.n_steps, s.n_elements, s.wall_time, s.ns_per_element_step
    );
    for warning in &s.result_warnings {
        println!("warning: {warning}");
    }
}

/// A plate's answers: the impulse, the peak force, the deflection, the contact.
fn print_plate(s: &impact_solver::Summary) {
    println!("impulse                 {:>14.6e} N s", s.impulse);
    println!("peak contact force      {:>14.6e} N", s.peak_contact_force);
    println!(
        "max plate displacement  {:>14.6e} m",
        s.max_plate_displacement
    );
    println!(
        "contact duration        {:>14.6e} s ({} interval(s))",
        s.contact_duration,
        s.contact_intervals.len()
    );
}

/// A body on the rigid wall (a Taylor bar): its length, foot, release and rebound, the wall's
/// bearing force and dissipation (ALGORITHM.md 5c).
fn print_wall(w: &impact_solver::WallSummary) {
    println!(
        "final length            {:>14.6e} m ({:.4} of the initial)",
        w.final_length, w.length_ratio
    );
    println!(
        "foot radius             {:>14.6e} m ({:.4} of the initial; largest {:.6e} m)",
        w.foot_radius, w.foot_radius_ratio, w.max_foot_radius
    );
    match (w.release_time, w.rebound_velocity) {
        (Some(t), Some(v)) => {
            println!("left the wall at        {t:>14.6e} s, rebounding at {v:.6e} m/s")
        }
        _ => println!(
            "left the wall at        {:>14} (on the wall at the end)",
            "never"
        ),
    }
    println!(
        "peak bearing force      {:>14.6e} N (one step's largest, landings included: {:.6e} N)",
        w.peak_force, w.peak_step_force
    );
    println!("wall dissipation        {:>14.6e} J", w.dissipated_energy);
    if let Some(e) = w.max_equivalent_plastic_strain {
        println!("max equivalent plastic  {e:>14.6e} (-)");
    }
}
