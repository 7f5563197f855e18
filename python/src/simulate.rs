//! `simulate`: one scene, from its YAML text, through the solver's own run and output code.

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use numpy::PyArray1;
use pyo3::exceptions::{PyKeyboardInterrupt, PyValueError};
use pyo3::prelude::*;

use impact_solver::kernels::fallback;
use impact_solver::{output, Outcome, Scene};

use crate::errors::to_py;
use crate::overrides::{self, scene_with};

/// Reads a scene file's text (the CLI's message when it cannot).
#[pyfunction]
pub fn read_scene(path: PathBuf) -> PyResult<String> {
    std::fs::read_to_string(&path)
        .map_err(|source| to_py(impact_solver::Error::ReadScene { path, source }))
}

/// The scene file at `path` as the text `Scene::to_yaml` writes of it (every key with its
/// value, the defaults written out: what another code's adapter reads, `adapters/README.md`);
/// the CLI's message when the file is refused. The scene schema's test validates these texts.
#[pyfunction]
pub fn resolved_scene(path: PathBuf) -> PyResult<String> {
    Scene::from_file(&path).map(|s| s.to_yaml()).map_err(to_py)
}

/// A finished run: `summary.json`'s text and the history's columns in file order.
type NativeRun<'py> = (String, Vec<String>, Vec<Bound<'py, PyArray1<f64>>>);

/// Parses `text` (`source` names it in messages), sets `overrides` (a JSON object of dotted
/// scene keys, see `Scene::from_yaml_with` and `crate::overrides`), validates, passes each
/// plausibility warning's text to `warn` (before the run, also when it is then refused), runs
/// it without the GIL on `threads` threads (None: the global pool, one thread per core) and,
/// with `out`, writes the CLI's files there. `stop`: an object with `is_set()` (a
/// `threading.Event`), polled with the signals: once set, the run stops with
/// KeyboardInterrupt (how a sweep stops its runs on other threads, where Python's signal
/// handlers do not run).
#[pyfunction]
#[pyo3(signature = (text, source, out=None, threads=None, overrides=None, warn=None, stop=None))]
#[allow(clippy::too_many_arguments)]
pub fn simulate<'py>(
    py: Python<'py>,
    text: &str,
    source: PathBuf,
    out: Option<PathBuf>,
    threads: Option<Bound<'py, PyAny>>,
    overrides: Option<&str>,
    warn: Option<Bound<'py, PyAny>>,
    stop: Option<Bound<'py, PyAny>>,
) -> PyResult<NativeRun<'py>> {
    let overrides = overrides::parse(overrides)?;
    let threads = threads.map(|t| thread_count(&t)).transpose()?;
    let policy = fallback::Policy::from_env().map_err(PyValueError::new_err)?;
    let scene = scene_with(text, &overrides, &source).map_err(to_py)?;
    if let Some(warn) = &warn {
        for w in &scene.warnings {
            warn.call1((w.to_string(),))?;
        }
    }
    let signals = Arc::new(PythonSignals {
        raised: Mutex::new(None),
        stop: stop.map(Bound::unbind),
    });
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
/// (`PyErr_CheckSignals`: SIGINT raises KeyboardInterrupt; on the main thread only), then looks
/// at the caller's `stop` event (set: KeyboardInterrupt, on any thread). A raised exception
/// stops the run and is kept, to be raised in place of the solver's own "interrupted" error.
struct PythonSignals {
    raised: Mutex<Option<PyErr>>,
    stop: Option<Py<PyAny>>,
}

impl PythonSignals {
    /// Whether a Python signal handler raised or `stop` is set (the run must stop).
    fn check(&self) -> bool {
        Python::attach(|py| {
            let raised = py.check_signals().err().or_else(|| self.stopped(py));
            let Some(e) = raised else {
                return false;
            };
            if let Ok(mut slot) = self.raised.lock() {
                *slot = Some(e);
            }
            true
        })
    }

    /// KeyboardInterrupt when the `stop` event is set.
    fn stopped(&self, py: Python<'_>) -> Option<PyErr> {
        let set = self.stop.as_ref()?.bind(py).call_method0("is_set").ok()?;
        set.is_truthy().unwrap_or(false).then(|| {
            PyKeyboardInterrupt::new_err("stopped: the sweep this run belongs to was interrupted")
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
