//! `impact`: the command-line front of the solver and of the verification matrix.

use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

#[derive(Parser)]
#[command(name = "impact", version, about = "Explicit impact solver (Dokko & Kim 2004) and its verification")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run one scene: writes history.csv, summary.json (and VTK fields if asked) to --out.
    Simulate {
        /// Scene file (YAML, SI units; see README "Scene reference").
        scene: PathBuf,
        /// Output folder (created; earlier outputs of the same names are replaced).
        #[arg(long)]
        out: PathBuf,
        /// No progress bar and no summary on the terminal.
        #[arg(long)]
        quiet: bool,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Simulate { scene, out, quiet } => {
            let progress = !quiet && std::io::stderr().is_terminal();
            match impact_solver::output::simulate_to_dir(&scene, &out, progress) {
                Ok(outcome) => {
                    if !quiet {
                        print_summary(&outcome.summary);
                    }
                    ExitCode::SUCCESS
                }
                Err(e) => {
                    eprintln!("error: {e}");
                    ExitCode::from(2)
                }
            }
        }
    }
}

fn print_summary(s: &impact_solver::Summary) {
    println!("impulse                 {:>14.6e} N s", s.impulse);
    println!("peak contact force      {:>14.6e} N", s.peak_contact_force);
    println!("max plate displacement  {:>14.6e} m", s.max_plate_displacement);
    println!("contact duration        {:>14.6e} s ({} interval(s))", s.contact_duration, s.contact_intervals.len());
    if let Some(v) = s.final_impactor_velocity {
        println!("final impactor velocity {:>14.6e} m/s", v);
    }
    for (probe, vm) in &s.max_von_mises {
        println!("max von Mises at {probe:<6} {:>14.6e} Pa", vm);
    }
    println!("energy balance error    {:>14.6e} (max)", s.max_energy_balance_error);
    if let Some(e) = s.impulse_momentum_error {
        println!("impulse-momentum error  {:>14.6e} (relative)", e);
    }
    println!(
        "dt {:.4e} s ({:.3} of stable), {} steps, {} elements, {:.3} s wall ({:.1} ns per element-step)",
        s.dt, s.cfl, s.n_steps, s.n_elements, s.wall_time, s.ns_per_element_step
    );
}
