//! `impact-bench`: run time against error (work-precision), kernel throughput, and stress
//! tests of numerical stability. Results (CSV, SVG, Markdown) go to `--out`, and after every
//! run the page of all that folder holds, `benchmarks.md` (what the V&V report embeds).

mod common;
mod meta;
mod page;
#[cfg(test)]
mod page_tests;
mod page_work_precision;
mod pareto;
mod references;
mod stability;
mod table;
mod threads;
mod throughput;
mod work_precision;

use std::path::{Path, PathBuf};

use clap::{Parser, Subcommand};

#[derive(Parser)]
#[command(name = "impact-bench", about = "Benchmarks of the impact solver")]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// Output folder (where `impact verify --report` looks for the benchmarks).
    #[arg(long, global = true, default_value = "out/verification/benchmarks")]
    out: PathBuf,
    /// Small sizes (for CI): fewer levels, repeats and cases.
    #[arg(long, global = true)]
    quick: bool,
}

#[derive(Subcommand)]
enum Command {
    /// Error of the robust quantities against wall time, per element, mesh level and CFL.
    WorkPrecision,
    /// ns per element-step of the kernels and whole-run times, against the targets.
    Throughput,
    /// CFL sweep, critical ratio, extreme inputs: bounded or a clear error, never garbage.
    Stability,
    /// All three.
    All,
    /// The paper's plastic run on the default threads, on the team that never falls back and
    /// on one thread, idle and with the other cores busy (spinning child processes): does the
    /// team ever make a run slower? Not in `all` (it loads the machine on purpose).
    Threads,
    /// The work-precision references alone, untimed, kept in --out for a later
    /// work-precision run there by this binary (the main job runs this beside the
    /// verification matrix, then the timed benchmarks alone).
    References,
}

fn main() -> anyhow::Result<()> {
    let cli = Cli::parse();
    std::fs::create_dir_all(&cli.out)?;
    let ran = run(&cli);
    // The page also after a failure (a stability run that found a blow-up): it shows it.
    let page = page::write(&cli.out)?;
    println!("page: {}", page.display());
    ran
}

/// A benchmark: its name (meta.json, the page) and what runs it (output folder, quick).
type Benchmark = (&'static str, fn(&Path, bool) -> anyhow::Result<()>);

/// Every benchmark, in the order `all` runs them.
const BENCHMARKS: [Benchmark; 3] = [
    ("throughput", throughput::run),
    ("work-precision", work_precision::run),
    ("stability", stability::run),
];

/// Runs the benchmarks asked for and records each that finished in meta.json.
fn run(cli: &Cli) -> anyhow::Result<()> {
    let (q, out) = (cli.quick, &cli.out);
    if let Command::References = cli.command {
        return work_precision::write_references(out, q);
    }
    if let Command::Threads = cli.command {
        threads::run(out, q)?;
        return meta::record(out, "threads", q, None);
    }
    let wp_sizes = work_precision::Sizes::new(q).describe();
    let asked = match cli.command {
        Command::WorkPrecision => Some("work-precision"),
        Command::Throughput => Some("throughput"),
        Command::Stability => Some("stability"),
        Command::All | Command::References | Command::Threads => None,
    };
    for (name, bench) in BENCHMARKS {
        if asked.is_some_and(|a| a != name) {
            continue;
        }
        bench(out, q)?;
        let sizes = (name == "work-precision").then_some(wp_sizes.as_str());
        meta::record(out, name, q, sizes)?;
    }
    Ok(())
}
