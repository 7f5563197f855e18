//! The native side of `impact.uq`: a study's declaration read and validated by the harness
//! (`impact_verification::uq_study`) and checked whole before any run (`crate::study_checks`),
//! the project's GCI rule (`impact_verification::gci`), the rigid-plastic numbers of a scene
//! (`impact_verification::rigid_plastic`), a scene's rule for a value and its summary's numeric
//! keys, so that the Python package reuses them instead of writing them again.

use std::path::PathBuf;

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use impact_solver::Error;

use crate::errors::{to_py, SceneError};
use crate::overrides::{self, scene_with};

/// The validated study as JSON text (each scene with its declared mesh, `mesh: {nx, ny}`).
/// A study the rules refuse raises SceneError with `file:line:col: field = value: allowed`.
#[pyfunction]
pub fn read_study(path: PathBuf) -> PyResult<String> {
    let study = crate::study_checks::read(&path).map_err(SceneError::new_err)?;
    serde_json::to_string(&study).map_err(|e| PyValueError::new_err(e.to_string()))
}

/// None when the scene `text` takes `overrides` (JSON text); else the rule they break, in the
/// scene's words (`field = value: what is allowed`; the whole message when it is not about an
/// override). Nothing runs.
#[pyfunction]
#[pyo3(signature = (text, source, overrides=None))]
pub fn refusal(text: &str, source: PathBuf, overrides: Option<&str>) -> PyResult<Option<String>> {
    let overrides = overrides::parse(overrides)?;
    Ok(match scene_with(text, &overrides, &source) {
        Ok(_) => None,
        Err(Error::Override { message, .. }) => Some(message),
        Err(other) => Some(other.to_string()),
    })
}

/// The keys of the summary of a run of the scene `text` with `overrides` that hold numbers
/// (nested ones dotted, `max_von_mises_Pa.A`), known before the run: what a study's outputs
/// may name.
#[pyfunction]
#[pyo3(signature = (text, source, overrides=None))]
pub fn summary_keys(text: &str, source: PathBuf, overrides: Option<&str>) -> PyResult<Vec<String>> {
    let overrides = overrides::parse(overrides)?;
    let scene = scene_with(text, &overrides, &source).map_err(to_py)?;
    Ok(crate::summary_keys::numeric(&scene))
}

/// The project's GCI rule on `values` (coarse to fine, refinement ratio `ratio`, formal order
/// `formal`): `(gci_relative, safety_factor, order_used, triplet_orders)`; a series that is
/// not asymptotic raises ValueError with the evidence.
#[pyfunction]
pub fn gci(values: Vec<f64>, ratio: f64, formal: f64) -> PyResult<(f64, f64, f64, Vec<f64>)> {
    let a = impact_verification::gci::assess(&values, ratio, Some(formal))
        .map_err(PyValueError::new_err)?;
    let g = a.gci.expect("formal order given");
    Ok((g.value, g.safety_factor, g.order_used, a.orders))
}

/// The rigid-plastic numbers (`rigid_plastic_*` metrics, JSON text) of the scene `text` with
/// `overrides` and a run's final plastic work (J); None when the scene is no elasto-plastic
/// clamped plate struck by an impactor.
#[pyfunction]
#[pyo3(signature = (text, source, plastic_work, overrides=None))]
pub fn rigid_plastic(
    text: &str,
    source: PathBuf,
    plastic_work: f64,
    overrides: Option<&str>,
) -> PyResult<Option<String>> {
    let overrides = overrides::parse(overrides)?;
    let scene = scene_with(text, &overrides, &source).map_err(to_py)?;
    let m = impact_verification::rigid_plastic::metrics(&scene, plastic_work);
    if m.is_empty() {
        return Ok(None);
    }
    let map: serde_json::Map<String, serde_json::Value> = m
        .into_iter()
        .map(|(k, v)| (k.to_string(), v.into()))
        .collect();
    Ok(Some(serde_json::Value::Object(map).to_string()))
}
