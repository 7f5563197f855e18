//! The native side of `impact.uq`: a study's declaration read and validated by the harness
//! (`impact_verification::uq_study`), the project's GCI rule (`impact_verification::gci`) and
//! the rigid-plastic numbers of a scene (`impact_verification::rigid_plastic`), so that the
//! Python package reuses them instead of writing them again.

use std::path::PathBuf;

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use impact_solver::overrides::Overrides;
use impact_solver::Scene;

use crate::errors::{to_py, SceneError};

/// The validated study as JSON text (each scene with its declared mesh, `mesh: {nx, ny}`).
/// A study the rules refuse raises SceneError with `file:line:col: field = value: allowed`.
#[pyfunction]
pub fn read_study(path: PathBuf) -> PyResult<String> {
    let study = impact_verification::uq_study::read(&path).map_err(SceneError::new_err)?;
    serde_json::to_string(&study).map_err(|e| PyValueError::new_err(e.to_string()))
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
    let overrides: Overrides = match overrides {
        Some(json) => serde_json::from_str(json)
            .map_err(|e| PyValueError::new_err(format!("overrides: {e}")))?,
        None => Overrides::new(),
    };
    let scene = Scene::from_yaml_with(text, &overrides, &source).map_err(to_py)?;
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
