//! The V&V report (`impact report`): index.html and report.md from a verify output folder,
//! its sections (the paper's tables, each case's plots, the evidence, what changed, the
//! benchmarks' and the UQ study's pages, the validation against measurements) and the Markdown and HTML they are made of.

pub mod bench_section;
pub mod case_plots;
pub mod changes_section;
pub mod codes_section;
pub mod evidence_section;
pub mod file_name;
pub mod html_tokens;
pub mod markdown;
pub mod page;
pub mod paper_tables;
pub mod results;
pub mod uq_section;
pub mod validation_section;

pub use page::{
    environment, write_environment, write_report, write_report_with, ReportOptions,
    RECONSTRUCTION_PAGE,
};
