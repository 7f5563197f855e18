//! The job loop of a verify run: the jobs of one plan, or of one plan per code, on one pool of
//! threads, largest first, each result kept under its job's index whatever the thread that
//! ran it (so the outcome does not depend on the thread count or the scheduling), a run that
//! panics kept as its failure, and each case announced, and with a [`Judge`] judged, as soon
//! as its last run has finished.

use std::collections::BTreeSet;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::OnceLock;

use indicatif::{ProgressBar, ProgressStyle};

use crate::definition::repo::Repo;
use crate::definition::run_data::JobResult;
use crate::definition::verdict::Tally;
use crate::run::case_progress::CaseProgress;
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
    let share = Share {
        plan,
        which: which.to_vec(),
        judge: None,
    };
    let mut done = run_shares(&[share], threads, progress)?;
    Ok(done.remove(0).0)
}

/// One plan's jobs `which` in a pool, and with a `judge` each of its cases' rows made as soon
/// as the case's last run has finished.
pub(super) struct Share<'a> {
    pub plan: &'a Plan<'a>,
    pub which: Vec<usize>,
    pub judge: Option<&'a Judge<'a>>,
}

/// Per share: its finished runs (index, result) and its judged cases' rows (per case of the
/// plan, for [`assemble_judged`](crate::run::case_rows::assemble_judged)).
pub(super) type ShareDone = (Vec<(usize, JobResult)>, Vec<Option<CaseResult>>);

/// Runs the shares' jobs in one pool of `threads` threads: another code's jobs first (their
/// runs take minutes where impact's take seconds, so they start while impact's fill the other
/// threads), each code's largest first; each thread takes the next job of that order when it
/// is free. Each case is announced (its verdicts with a judge) as it finishes.
pub(super) fn run_shares(
    shares: &[Share],
    threads: usize,
    progress: bool,
) -> Result<Vec<ShareDone>, String> {
    let states: Vec<ShareState> = shares.iter().map(ShareState::new).collect();
    let mut order: Vec<(usize, usize)> = shares
        .iter()
        .enumerate()
        .flat_map(|(s, share)| share.which.iter().map(move |&i| (s, i)))
        .collect();
    let impact = |s: usize| shares[s].plan.code.is_impact();
    let cost = |(s, i): (usize, usize)| shares[s].plan.jobs[i].cost();
    order.sort_by(|&a, &b| {
        (impact(a.0).cmp(&impact(b.0)))
            .then(cost(b).total_cmp(&cost(a)))
            .then(a.cmp(&b))
    });
    let bar = progress.then(|| progress_bar(order.len()));
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads.max(1))
        .build()
        .map_err(|e| format!("cannot start {threads} threads: {e}"))?;
    for state in &states {
        state
            .progress
            .idle()
            .into_iter()
            .for_each(|c| state.announce(c, &bar));
    }
    // Each thread takes the next job of `order` when it is free: largest first, as the order
    // says. (A parallel iterator over `order` split it in halves, one per thread, so one
    // thread ran the first half's large jobs one after another: CalculiX's seven runs of the
    // main job, 1967 s of work for two threads, took 1243 s, 2026-11-29.)
    let next = AtomicUsize::new(0);
    let run_next = || {
        while let Some(&(s, i)) = order.get(next.fetch_add(1, Ordering::Relaxed)) {
            states[s].run(i, &bar);
            if let Some(b) = &bar {
                b.inc(1);
            }
        }
    };
    pool.scope(|scope| {
        for _ in 0..pool.current_num_threads() {
            scope.spawn(|_| run_next());
        }
    });
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    Ok(states.into_iter().map(ShareState::finish).collect())
}

fn progress_bar(runs: usize) -> ProgressBar {
    let b = ProgressBar::new(runs as u64);
    b.set_style(
        ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {pos}/{len} runs {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    b
}

/// A share while its jobs run: each result kept under its job's index, each case's row
/// kept once its last run is in.
struct ShareState<'a> {
    share: &'a Share<'a>,
    progress: CaseProgress,
    slots: Vec<OnceLock<JobResult>>,
    judged: Vec<OnceLock<CaseResult>>,
}

impl<'a> ShareState<'a> {
    fn new(share: &'a Share<'a>) -> ShareState<'a> {
        let plan = share.plan;
        let mine: BTreeSet<usize> = share.which.iter().copied().collect();
        // Another code's cases are named with it, as in the matrix (`calculix:suite/case`).
        let prefix = if plan.code.is_impact() {
            String::new()
        } else {
            format!("{}:", plan.code.name())
        };
        let progress = CaseProgress::new(
            plan.cases
                .iter()
                .zip(&plan.case_jobs)
                .map(|(c, jobs_of)| {
                    let runs = jobs_of.values().filter_map(|j| j.as_ref().ok().copied());
                    let runs = runs.filter(|j| mine.contains(j));
                    (format!("{prefix}{}/{}", c.suite, c.name), runs.collect())
                })
                .collect(),
            plan.jobs.len(),
        );
        ShareState {
            share,
            progress,
            slots: plan.jobs.iter().map(|_| OnceLock::new()).collect(),
            judged: plan.cases.iter().map(|_| OnceLock::new()).collect(),
        }
    }

    /// Runs job `i` (a run that panics kept as its failure) and announces the cases it ends.
    fn run(&self, i: usize, bar: &Option<ProgressBar>) {
        let plan = self.share.plan;
        let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| plan.run_job(i)))
            .unwrap_or_else(|p| Err(format!("the run panicked: {}", panic_text(&*p))));
        let _ = self.slots[i].set(r);
        for c in self.progress.run_done(i) {
            self.announce(c, bar);
        }
    }

    /// A finished case: judged (its row kept) and announced above the bar.
    fn announce(&self, c: usize, bar: &Option<ProgressBar>) {
        let plan = self.share.plan;
        let row = self.share.judge.map(|j| {
            let (results, setup_error) =
                case_runs(&plan.case_jobs[c], |i| self.slots[i].get().cloned());
            case_result(
                j.repo,
                &plan.code,
                plan.cases[c],
                &results,
                setup_error,
                j.filter,
            )
        });
        let line = self
            .progress
            .line(c, row.as_ref().map(|r| Tally::of(&r.checks)).as_ref());
        if let Some(r) = row {
            let _ = self.judged[c].set(r);
        }
        match bar {
            Some(b) => b.println(line),
            None => eprintln!("{line}"),
        }
    }

    fn finish(self) -> ShareDone {
        let finished = self
            .slots
            .into_iter()
            .enumerate()
            .filter_map(|(i, s)| s.into_inner().map(|r| (i, r)))
            .collect();
        (
            finished,
            self.judged.into_iter().map(OnceLock::into_inner).collect(),
        )
    }
}

/// The text of a panic's payload (a `&str` or `String`; otherwise "no message").
fn panic_text(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "no message".into())
}
