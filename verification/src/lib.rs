//! The verification harness of the impact solver: cases (YAML) with requirements, scenes and
//! checks; the lint; the parallel runner and its matrix, results.json and JUnit output; the
//! V&V report. The `impact` binary (`src/main.rs`) is its command line.

pub mod baseline;
pub mod bench_report;
pub mod broken;
pub mod builtins;
pub mod case;
pub mod case_progress;
pub mod check;
pub mod check_row;
pub mod code_verification;
pub mod data;
pub mod diff;
pub mod diff_input;
pub mod diff_moves;
pub mod discriminate;
pub mod evidence_report;
pub mod gci;
pub mod history_invariants;
pub mod html_tokens;
pub mod jobs;
pub mod lint;
pub mod markdown;
pub mod repo;
pub mod report;
pub mod report_paper;
pub mod report_plots;
pub mod report_results;
pub mod rigid_plastic;
pub mod runner;
pub mod shard;
pub mod snapshot;
pub mod uq_distribution;
pub mod uq_report;
pub mod uq_study;
pub mod verdict;

// The plots' modules before they became the crate `impact-plots` (shared with the benchmarks).
pub use impact_plots::line_plot as plot;
pub use impact_plots::style as plot_style;
