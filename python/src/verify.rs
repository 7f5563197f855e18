//! `verify`: the verification matrix through the harness library (`impact_verification`),
//! returning `results.json`'s text and, with `out`, writing the files `impact verify` writes.

use std::path::PathBuf;

use pyo3::prelude::*;

use impact_verification::report::{self, ReportOptions};
use impact_verification::runner::{self, Options, Repo};

use crate::errors::VerifyError;

/// Runs the cases `selectors` (suites, case ids or suite/case; empty: all) whose checks match
/// `filter`, without the heavy ones when `light`, on `jobs` threads (None: one per core),
/// without the GIL. `root`: the repository (None: found from the current folder).
#[pyfunction]
#[pyo3(signature = (selectors, filter=None, light=false, jobs=None, out=None, report=false, root=None))]
#[allow(clippy::too_many_arguments)]
pub fn verify(
    py: Python<'_>,
    selectors: Vec<String>,
    filter: Option<String>,
    light: bool,
    jobs: Option<usize>,
    out: Option<PathBuf>,
    report: bool,
    root: Option<PathBuf>,
) -> PyResult<String> {
    let start = match root {
        Some(r) => r,
        None => std::env::current_dir()?,
    };
    let repo = Repo::find(&start).ok_or_else(|| {
        VerifyError::new_err(format!(
            "no verification/cases folder in {} or above (pass root=)",
            start.display()
        ))
    })?;
    let jobs = jobs.unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    let opts = Options {
        selectors,
        filter,
        jobs,
        include_heavy: !light,
        progress: false,
    };
    py.detach(|| {
        let started = std::time::Instant::now();
        let outcome = runner::verify(&repo, &opts).map_err(|p| p.join("\n"))?;
        if let Some(out) = &out {
            let wall = started.elapsed().as_secs_f64();
            runner::write_outputs(&outcome, out)
                .and_then(|_| report::write_environment(&repo, out, wall, jobs))
                .map_err(|e| format!("cannot write {}: {e}", out.display()))?;
            if report {
                report::write_report_with(out, out, &ReportOptions::default())
                    .map_err(|e| format!("report: {e:#}"))?;
            }
        }
        serde_json::to_string_pretty(&outcome.matrix).map_err(|e| e.to_string())
    })
    .map_err(VerifyError::new_err)
}
