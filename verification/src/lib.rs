//! The verification harness of the impact solver, in the order a case travels through it:
//! - [`definition`]: what a case is (YAML: requirement, scenes, checks), the lint, how a
//!   check is evaluated and what its result means;
//! - [`codes`]: the codes the checks are evaluated on (`impact`, adapters, results read
//!   from a folder);
//! - [`run`]: the jobs, the parallel runner and its matrix (results.json, JUnit), shards;
//! - [`review`]: a run against another (`impact diff`, `--baseline`) and the snapshots;
//! - [`report`]: the V&V report;
//! - [`uq`]: uncertainty studies, beside the matrix.
//!
//! The `impact` binary (`src/main.rs`) is its command line.

pub mod codes;
pub mod definition;
pub mod report;
pub mod review;
pub mod run;
pub mod uq;

// The module paths before the folders (issue 37), kept for the Python bindings, the tests
// and any other user: `impact_verification::runner` is `run::runner`, and so on.
pub use definition::run_data as data;
pub use definition::{broken, case, check, check_row, gci, lint, repo, verdict};
pub use report::bench_section as bench_report;
pub use report::case_plots as report_plots;
pub use report::evidence_section as evidence_report;
pub use report::paper_tables as report_paper;
pub use report::results as report_results;
pub use report::uq_section as uq_report;
pub use report::{html_tokens, markdown};
pub use review::{baseline, diff, diff_input, diff_moves, snapshot};
pub use run::{
    builtins, case_progress, code_verification, discriminate, history_invariants, jobs,
    rigid_plastic, runner, shard,
};
pub use uq::distribution as uq_distribution;
pub use uq::study as uq_study;

// The plots' modules before they became the crate `impact-plots` (shared with the benchmarks).
pub use impact_plots::line_plot as plot;
pub use impact_plots::style as plot_style;
