//! `impact verify` says what is happening: a line for each case as soon as its last run has
//! finished (the runs are shared between cases and run largest first in parallel, so cases
//! finish out of order), with its checks' verdicts when they can be judged (`4 OK, 1 FAIL*`),
//! its run count and the time since the start; then one total line.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use crate::definition::verdict::Tally;

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

    /// The cases that wait on no run (skipped, or their runs could not be made): finished
    /// from the start.
    pub fn idle(&self) -> Vec<usize> {
        (0..self.runs.len())
            .filter(|&c| self.runs[c] == 0)
            .collect()
    }

    /// Run `job` has finished: the cases whose last run it was.
    pub fn run_done(&self, job: usize) -> Vec<usize> {
        self.users[job]
            .iter()
            .copied()
            .filter(|&c| self.remaining[c].fetch_sub(1, Ordering::SeqCst) == 1)
            .collect()
    }

    /// The line of finished case `c`: `finished suite/case: 4 OK, 1 FAIL* (3 runs, 12.3 s)`,
    /// without the verdicts when its checks are judged elsewhere (a shard).
    pub fn line(&self, c: usize, verdicts: Option<&Tally>) -> String {
        let runs = self.runs[c];
        format!(
            "finished {}{} ({runs} run{}, {:.1} s)",
            self.names[c],
            verdicts
                .map(|t| format!(": {}", t.short()))
                .unwrap_or_default(),
            if runs == 1 { "" } else { "s" },
            self.started.elapsed().as_secs_f64()
        )
    }
}
