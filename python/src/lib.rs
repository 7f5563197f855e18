//! `impact._impact`: the native module of the Python package `impact` (see `python/impact/`
//! for the documented API). It runs the solver and the verification harness through their
//! own library functions, so results, files and error messages are those of the `impact`
//! command; the Python side only shapes them (dicts, numpy arrays, data frames, sweeps).
//! The GIL is released while the solver or the matrix runs.

mod errors;
mod overrides;
mod scene_keys;
mod simulate;
mod study_checks;
mod summary_keys;
mod uq;
mod verify;

use pyo3::prelude::*;

#[pymodule]
fn _impact(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("SceneError", py.get_type::<errors::SceneError>())?;
    m.add("RunError", py.get_type::<errors::RunError>())?;
    m.add("VerifyError", py.get_type::<errors::VerifyError>())?;
    m.add_function(wrap_pyfunction!(simulate::read_scene, m)?)?;
    m.add_function(wrap_pyfunction!(simulate::resolved_scene, m)?)?;
    m.add_function(wrap_pyfunction!(simulate::simulate, m)?)?;
    m.add_function(wrap_pyfunction!(verify::verify, m)?)?;
    m.add_function(wrap_pyfunction!(uq::read_study, m)?)?;
    m.add_function(wrap_pyfunction!(uq::gci, m)?)?;
    m.add_function(wrap_pyfunction!(uq::rigid_plastic, m)?)?;
    m.add_function(wrap_pyfunction!(uq::refusal, m)?)?;
    m.add_function(wrap_pyfunction!(uq::summary_keys, m)?)?;
    m.add(
        "TIMING_KEYS",
        impact_verification::jobs::TIMING_KEYS.to_vec(),
    )?;
    Ok(())
}
