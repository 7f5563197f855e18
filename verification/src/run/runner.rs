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
pub use crate::run::plan::{load, plan, plan_for, Loaded, Options, Plan};

use crate::codes::Code;
use crate::definition::run_data::JobResult;
use crate::run::matrix::CodeMatrix;
use crate::run::{case_rows, job_loop};

/// Runs the selected cases, announcing each as it finishes with its checks' verdicts, then
/// the total. Errors: cases that do not load or do not lint.
pub fn verify(repo: &Repo, opts: &Options) -> Result<Outcome, Vec<String>> {
    verify_codes(repo, opts, &[Code::Impact])
}

/// [`verify`] on each of `codes` (issue 38): the same cases' checks, references and
/// tolerances evaluated on each code's results, every code's jobs in one pool (another code's
/// first, [`job_loop::run_shares`]); `impact`'s rows are the matrix's own (none when it is not
/// among the codes), the others' rows follow code by code.
pub fn verify_codes(repo: &Repo, opts: &Options, codes: &[Code]) -> Result<Outcome, Vec<String>> {
    let started = std::time::Instant::now();
    let loaded = load(repo)?;
    let mut plans = Vec::new();
    for code in codes {
        if codes.len() > 1 {
            eprintln!("== {}: {}", code.name(), code.description());
        }
        plans.push(plan_for(&loaded, opts, code.clone())?);
    }
    let mut outcome = None;
    let mut others = Vec::new();
    for (code, o) in codes.iter().zip(run_plans(repo, &plans, opts)?) {
        match code {
            Code::Impact => outcome = Some(o),
            _ => others.push((code, o)),
        }
    }
    let mut outcome = outcome.unwrap_or_else(|| Outcome {
        matrix: Matrix {
            counts: Counts::default(),
            cases: Vec::new(),
            codes: Vec::new(),
        },
        data: Default::default(),
        code_data: Vec::new(),
    });
    for (code, o) in others {
        outcome.matrix.codes.push(CodeMatrix {
            code: code.name(),
            description: code.description(),
            counts: o.matrix.counts,
            cases: o.matrix.cases,
        });
        outcome.code_data.push((code.name(), o.data));
    }
    eprintln!(
        "{}",
        total_line(&outcome.matrix, started.elapsed().as_secs_f64())
    );
    Ok(outcome)
}

/// The plans' jobs run in one pool and each plan's cases judged.
fn run_plans(repo: &Repo, plans: &[Plan], opts: &Options) -> Result<Vec<Outcome>, Vec<String>> {
    let judge = Judge {
        repo,
        filter: &opts.filter,
    };
    let shares: Vec<job_loop::Share> = plans
        .iter()
        .map(|plan| job_loop::Share {
            plan,
            which: (0..plan.jobs.len()).collect(),
            judge: Some(&judge),
        })
        .collect();
    let done = job_loop::run_shares(&shares, opts.jobs, opts.progress).map_err(|e| vec![e])?;
    Ok(plans
        .iter()
        .zip(done)
        .map(|(plan, (finished, judged))| {
            let mut slots: Vec<Option<JobResult>> = vec![None; plan.jobs.len()];
            for (i, r) in finished {
                slots[i] = Some(r);
            }
            case_rows::assemble_judged(repo, plan, slots, &opts.filter, judged)
        })
        .collect())
}
