//! `impact-bench`: run time against error (work-precision), kernel throughput, and stress
//! tests of numerical stability. Results (CSV, SVG, Markdown) go to `--out`.

mod common;
mod meta;
mod pareto;
mod stability;
mod throughput;
mod work_precision;

use std::path::PathBuf;

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
}

fn main() -> anyhow::Result<()> {
    let cli = Cli::parse();
    std::fs::create_dir_all(&cli.out)?;
    let (q, out) = (cli.quick, &cli.out);
    let wp_sizes = work_precision::Sizes::new(q).describe();
    match cli.command {
        Command::WorkPrecision => work_precision::run(out, q)?,
        Command::Throughput => throughput::run(out, q)?,
        Command::Stability => stability::run(out, q)?,
        Command::All => {
            throughput::run(out, q)?;
            work_precision::run(out, q)?;
            stability::run(out, q)?;
        }
    }
    let ran: &[&str] = match cli.command {
        Command::WorkPrecision => &["work-precision"],
        Command::Throughput => &["throughput"],
        Command::Stability => &["stability"],
        Command::All => &["throughput", "work-precision", "stability"],
    };
    for name in ran {
        let sizes = if *name == "work-precision" {
            Some(wp_sizes.as_str())
        } else {
            None
        };
        meta::record(out, name, q, sizes)?;
    }
    Ok(())
}
