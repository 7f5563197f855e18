//! `impact verify` says what is happening: a line for each case as soon as its last run has
//! finished (the runs are shared between cases and run largest first in parallel, so cases
//! finish out of order), with its run count and the time since the start.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use indicatif::ProgressBar;

/// Which cases wait on which runs.
pub struct CaseProgress {
    names: Vec<String>,
    runs: Vec<usize>,
    remaining: Vec<AtomicUsize>,
    /// Per run: the cases that use it.
    users: Vec<Vec<usize>>,
    started: Instant,
}

impl CaseProgress {
    /// `cases`: (suite/case, the indices of the runs it uses); `n_runs` runs in all.
    pub fn new(cases: Vec<(String, Vec<usize>)>, n_runs: usize) -> CaseProgress {
        let mut users = vec![Vec::new(); n_runs];
        let mut runs = Vec::new();
        let mut remaining = Vec::new();
        let mut names = Vec::new();
        for (c, (name, mut jobs)) in cases.into_iter().enumerate() {
            jobs.sort_unstable();
            jobs.dedup();
            for &j in &jobs {
                users[j].push(c);
            }
            names.push(name);
            runs.push(jobs.len());
            remaining.push(AtomicUsize::new(jobs.len()));
        }
        CaseProgress {
            names,
            runs,
            remaining,
            users,
            started: Instant::now(),
        }
    }

    /// Run `job` has finished: prints the cases it completes (above the bar, if any).
    pub fn run_done(&self, job: usize, bar: Option<&ProgressBar>) {
        for &c in &self.users[job] {
            if self.remaining[c].fetch_sub(1, Ordering::SeqCst) == 1 {
                let line = format!(
                    "finished {} ({} run{}, {:.1} s)",
                    self.names[c],
                    self.runs[c],
                    if self.runs[c] == 1 { "" } else { "s" },
                    self.started.elapsed().as_secs_f64()
                );
                match bar {
                    Some(b) => b.println(line),
                    None => eprintln!("{line}"),
                }
            }
        }
    }
}
