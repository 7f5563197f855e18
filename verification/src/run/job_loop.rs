//! The job loop of a verify run: the plan's jobs on a pool of threads, largest first, each
//! result kept under its job's index whatever the thread that ran it (so the outcome does not
//! depend on the thread count or the scheduling), a run that panics kept as its failure, and
//! each case announced, and with a [`Judge`] judged, as soon as its last run has finished.

use std::collections::BTreeSet;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::OnceLock;

use indicatif::{ProgressBar, ProgressStyle};

use crate::definition::repo::Repo;
use crate::definition::run_data::JobResult;
use crate::definition::verdict::Tally;
use crate::run::case_rows::{case_result, case_runs};
use crate::run::matrix::CaseResult;
use crate::run::plan::Plan;

/// What judges a case as soon as its runs are done: where its references live and which of
/// its checks to evaluate.
pub struct Judge<'a> {
    pub repo: &'a Repo,
    pub filter: &'a Option<String>,
}

/// Runs the jobs `which` on `threads` threads, largest first; each result is returned with
/// its index, whatever the thread that ran it. Each case whose runs are all among `which`
/// is announced as it finishes (without verdicts: a shard's cases are judged at the merge).
pub fn execute(
    plan: &Plan,
    which: &[usize],
    threads: usize,
    progress: bool,
) -> Result<Vec<(usize, JobResult)>, String> {
    run_jobs(plan, which, threads, progress, None).map(|(finished, _)| finished)
}

/// [`execute`], and with a `judge` each case's row is made as soon as its last run has
/// finished, announced with its verdicts and returned (per case of the plan) for
/// [`assemble_judged`](crate::run::case_rows::assemble_judged).
pub(super) fn run_jobs(
    plan: &Plan,
    which: &[usize],
    threads: usize,
    progress: bool,
    judge: Option<&Judge>,
) -> Result<(Vec<(usize, JobResult)>, Vec<Option<CaseResult>>), String> {
    let jobs = &plan.jobs;
    let mut order = which.to_vec();
    order.sort_by(|&a, &b| jobs[b].cost().total_cmp(&jobs[a].cost()).then(a.cmp(&b)));
    let bar = progress.then(|| {
        let b = ProgressBar::new(order.len() as u64);
        b.set_style(
            ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {pos}/{len} runs {msg}")
                .unwrap_or_else(|_| ProgressStyle::default_bar())
                .progress_chars("=> "),
        );
        b
    });
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads.max(1))
        .build()
        .map_err(|e| format!("cannot start {threads} threads: {e}"))?;
    let mine: BTreeSet<usize> = which.iter().copied().collect();
    let case_progress = crate::run::case_progress::CaseProgress::new(
        plan.cases
            .iter()
            .zip(&plan.case_jobs)
            .map(|(c, jobs_of)| {
                let runs = jobs_of.values().filter_map(|j| j.as_ref().ok().copied());
                let runs = runs.filter(|j| mine.contains(j));
                (format!("{}/{}", c.suite, c.name), runs.collect())
            })
            .collect(),
        jobs.len(),
    );
    let slots: Vec<OnceLock<JobResult>> = jobs.iter().map(|_| OnceLock::new()).collect();
    let judged: Vec<OnceLock<CaseResult>> = plan.cases.iter().map(|_| OnceLock::new()).collect();
    // A finished case: judged (its row kept) and announced above the bar.
    let announce = |c: usize| {
        let row = judge.map(|j| {
            let (results, setup_error) = case_runs(&plan.case_jobs[c], |i| slots[i].get().cloned());
            case_result(
                j.repo,
                &plan.code,
                plan.cases[c],
                &results,
                setup_error,
                j.filter,
            )
        });
        let line = case_progress.line(c, row.as_ref().map(|r| Tally::of(&r.checks)).as_ref());
        if let Some(r) = row {
            let _ = judged[c].set(r);
        }
        match &bar {
            Some(b) => b.println(line),
            None => eprintln!("{line}"),
        }
    };
    case_progress.idle().into_iter().for_each(announce);
    // Each thread takes the next job of `order` when it is free: largest first, as the order
    // says. (A parallel iterator over `order` split it in halves, one per thread, so one
    // thread ran the first half's large jobs one after another: CalculiX's seven runs of the
    // main job, 1967 s of work for two threads, took 1243 s, 2026-11-29.)
    let next = AtomicUsize::new(0);
    let run_next = || {
        while let Some(&i) = order.get(next.fetch_add(1, Ordering::Relaxed)) {
            let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| plan.run_job(i)))
                .unwrap_or_else(|p| Err(format!("the run panicked: {}", panic_text(&*p))));
            let _ = slots[i].set(r);
            case_progress.run_done(i).into_iter().for_each(announce);
            if let Some(b) = &bar {
                b.inc(1);
            }
        }
    };
    pool.scope(|s| {
        for _ in 0..pool.current_num_threads() {
            s.spawn(|_| run_next());
        }
    });
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let finished = slots
        .into_iter()
        .enumerate()
        .filter_map(|(i, s)| s.into_inner().map(|r| (i, r)))
        .collect();
    Ok((
        finished,
        judged.into_iter().map(OnceLock::into_inner).collect(),
    ))
}

/// The text of a panic's payload (a `&str` or `String`; otherwise "no message").
fn panic_text(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "no message".into())
}
