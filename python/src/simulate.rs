//! `simulate`: one scene, from its YAML text, through the solver's own run and output code.

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use numpy::PyArray1;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use impact_solver::kernels::fallback;
use impact_solver::overrides::Overrides;
use impact_solver::{output, Outcome, Scene};

use crate::errors::to_py;

/// Reads a scene file's text (the CLI's message when it cannot).
#[pyfunction]
pub fn read_scene(path: PathBuf) -> PyResult<String> {
    std::fs::read_to_string(&path)
        .map_err(|source| to_py(impact_solver::Error::ReadScene { path, source }))
}

/// A finished run: `summary.json`'s text and the history's columns in file order.
type NativeRun<'py> = (String, Vec<String>, Vec<Bound<'py, PyArray1<f64>>>);

/// Parses `text` (`source` names it in messages), sets `overrides` (a JSON object of dotted
/// scene keys, see `Scene::from_yaml_with`), validates, passes each plausibility warning's
/// text to `warn` (before the run, also when it is then refused), runs it without the GIL on
/// `threads` threads (None: the global pool, one thread per core) and, with `out`, writes the
/// CLI's files there.
#[pyfunction]
#[pyo3(signature = (text, source, out=None, threads=None, overrides=None, warn=None))]
pub fn simulate<'py>(
    py: Python<'py>,
    text: &str,
    source: PathBuf,
    out: Option<PathBuf>,
    threads: Option<Bound<'py, PyAny>>,
    overrides: Option<&str>,
    warn: Option<Bound<'py, PyAny>>,
) -> PyResult<NativeRun<'py>> {
    let overrides: Overrides = match overrides {
        Some(json) => serde_json::from_str(json)
            .map_err(|e| PyValueError::new_err(format!("overrides: {e}")))?,
        None => Overrides::new(),
    };
    let threads = threads.map(|t| thread_count(&t)).transpose()?;
    let policy = fallback::Policy::from_env().map_err(PyValueError::new_err)?;
    let scene = Scene::from_yaml_with(text, &overrides, &source).map_err(to_py)?;
    if let Some(warn) = &warn {
        for w in &scene.warnings {
            warn.call1((w.to_string(),))?;
        }
    }
    let signals = Arc::new(PythonSignals::default());
    let outcome = py.detach(|| {
        let run = || fallback::with_policy(policy, || run(&scene, out.as_deref(), &signals));
        match threads {
            Some(n) => impact_solver::workers::with_threads(n, run),
            None => run(),
        }
    });
    let outcome = outcome.map_err(|e| signals.raised_take().unwrap_or_else(|| to_py(e)))?;
    let summary = serde_json::to_string_pretty(&outcome.summary)
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    let history = &outcome.history;
    let arrays = (0..history.columns.len())
        .map(|c| {
            let column: Vec<f64> = history
                .values
                .iter()
                .skip(c)
                .step_by(history.columns.len())
                .copied()
                .collect();
            PyArray1::from_vec(py, column)
        })
        .collect();
    Ok((summary, history.columns.clone(), arrays))
}

/// `threads=` as a thread count: an integer from 1 to `thread_count::max_threads()`, else a
/// ValueError naming `threads`, the value and what is allowed (also for integers beyond 64
/// bits and negative ones, which pyo3 alone would report as an OverflowError).
fn thread_count(threads: &Bound<'_, PyAny>) -> PyResult<usize> {
    use impact_solver::kernels::thread_count::{check_threads, refusal};
    let checked = match threads.extract::<u64>() {
        Ok(n) => check_threads("threads", n),
        Err(_) => Err(refusal("threads", &threads.repr()?.to_string())),
    };
    checked.map_err(PyValueError::new_err)
}

/// Ctrl-C from Python: the time loop polls [`PythonSignals::check`] every `POLL_EVERY` steps;
/// it takes the GIL for the check (the run holds none) and lets Python run its signal handlers
/// (`PyErr_CheckSignals`: SIGINT raises KeyboardInterrupt). A raised exception stops the run
/// and is kept, to be raised in place of the solver's own "interrupted" error.
#[derive(Default)]
struct PythonSignals {
    raised: Mutex<Option<PyErr>>,
}

impl PythonSignals {
    /// Whether a Python signal handler raised (the run must stop).
    fn check(&self) -> bool {
        Python::attach(|py| match py.check_signals() {
            Ok(()) => false,
            Err(e) => {
                if let Ok(mut slot) = self.raised.lock() {
                    *slot = Some(e);
                }
                true
            }
        })
    }

    fn raised_take(&self) -> Option<PyErr> {
        self.raised.lock().ok()?.take()
    }
}

impl impact_solver::Observer for &PythonSignals {
    fn stop_requested(&self) -> bool {
        self.check()
    }
}

fn run(
    scene: &Scene,
    out: Option<&Path>,
    signals: &Arc<PythonSignals>,
) -> impact_solver::Result<Outcome> {
    match out {
        Some(dir) => {
            // Run.history is returned: hold it in memory as well as writing history.csv.
            let hook = Arc::clone(signals);
            let options = output::RunOptions {
                keep_history: true,
                stop: Some(output::StopHook(Arc::new(move || hook.check()))),
                ..Default::default()
            };
            output::simulate_scene_to_dir_with(scene, dir, &options, &mut |_| {})
        }
        None => impact_solver::simulate(scene, &mut &**signals),
    }
}
