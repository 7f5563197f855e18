//! `impact verify`: select cases, run their jobs in parallel (each job is single-threaded
//! and independent, results are keyed by job, so the outcome does not depend on the thread
//! count or the scheduling), evaluate the checks, print the matrix, write results.json,
//! JUnit XML and the run data the report reads. The steps stand beside this file, their items
//! re-exported here: the [`plan`](crate::run::plan), the [`job_loop`](crate::run::job_loop),
//! the [`case_rows`](crate::run::case_rows) of the [`matrix`](crate::run::matrix) and the
//! [`matrix_files`](crate::run::matrix_files) it is written to.

pub use crate::definition::check_row::num;
pub use crate::definition::repo::Repo;
pub use crate::run::case_rows::assemble;
pub use crate::run::job_loop::{execute, Judge};
pub use crate::run::matrix::{CaseResult, Counts, Matrix, Outcome, SeriesData};
pub use crate::run::matrix_files::{
    junit_xml, matrix_text, summary_text, total_line, write_outputs,
};
pub use crate::run::plan::{load, plan, Loaded, Options, Plan};

use crate::definition::run_data::JobResult;
use crate::run::{case_rows, job_loop};

/// Runs the selected cases, announcing each as it finishes with its checks' verdicts, then
/// the total. Errors: cases that do not load or do not lint.
pub fn verify(repo: &Repo, opts: &Options) -> Result<Outcome, Vec<String>> {
    let started = std::time::Instant::now();
    let loaded = load(repo)?;
    let plan = plan(&loaded, opts)?;
    let all: Vec<usize> = (0..plan.jobs.len()).collect();
    let judge = Judge {
        repo,
        filter: &opts.filter,
    };
    let (finished, judged) =
        job_loop::run_jobs(&plan, &all, opts.jobs, opts.progress, Some(&judge))
            .map_err(|e| vec![e])?;
    let mut slots: Vec<Option<JobResult>> = vec![None; plan.jobs.len()];
    for (i, r) in finished {
        slots[i] = Some(r);
    }
    let outcome = case_rows::assemble_judged(repo, &plan, slots, &opts.filter, judged);
    eprintln!(
        "{}",
        total_line(&outcome.matrix, started.elapsed().as_secs_f64())
    );
    Ok(outcome)
}
