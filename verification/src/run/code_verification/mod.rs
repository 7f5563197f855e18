//! Code verification builtins (issue 15): observed order of accuracy of the three Q4
//! elements and of central differences on a manufactured solution, and the impactor's
//! update against a fixed linear spring. Each returns metrics for the checks and a small
//! history ("orders") for the report's order plots.

pub mod axisymmetric;
pub mod bar_wave;
pub mod bending_period;
pub mod collapse;
pub mod column_impact;
pub mod driver;
pub mod element_eigen;
pub mod finite_path;
pub mod hertz_line;
pub mod macneal_harder;
pub mod manufactured;
pub mod membrane;
pub mod orders;
pub mod plastic_path;
pub mod probe_point;
pub mod rate_path;
pub mod rigid_target;
pub mod space_time;
pub mod spring;
pub mod stable_step;
pub mod static_pulse;
pub mod table_path;
pub mod thick_cylinder;
pub mod thread_invariance;
pub mod viscoplastic_truss;
pub mod wall_bar;

use std::collections::BTreeMap;

use impact_solver::input::geometry::Geometry;
use serde_json::Value;

use crate::definition::run_data::RunData;

/// The builtins of this module.
pub const NAMES: [&str; 24] = [
    "mms-space",
    "mms-time",
    "impactor-spring",
    "macneal-harder-patch",
    "rigid-target",
    "plastic-strain-path",
    "element-eigenvalues",
    "plastic-bar-wave",
    "static-collapse",
    "bending-period",
    "static-pulse",
    "thick-cylinder",
    "column-impact",
    "hertz-line",
    "rate-strain-path",
    "viscoplastic-truss",
    "finite-strain-path",
    "membrane-regime",
    "axisymmetric",
    "square-stable-step",
    "table-strain-path",
    "thread-invariance",
    "probe-point",
    "wall-bar",
];

/// Runs one of [`NAMES`]; `None` if the name is not one of them.
pub fn run(name: &str, p: &BTreeMap<String, Value>) -> Option<Result<RunData, String>> {
    Some(match name {
        "mms-space" => space_time::space(p),
        "mms-time" => space_time::time(p),
        "impactor-spring" => spring::spring(p),
        "macneal-harder-patch" => macneal_harder::patch(p),
        "rigid-target" => rigid_target::rigid_target(p),
        "plastic-strain-path" => plastic_path::plastic_strain_path(p),
        "element-eigenvalues" => element_eigen::element_eigenvalues(p),
        "plastic-bar-wave" => bar_wave::plastic_bar_wave(p),
        "static-collapse" => collapse::static_collapse(p),
        "bending-period" => bending_period::bending_period(p),
        "static-pulse" => static_pulse::static_pulse(p),
        "thick-cylinder" => thick_cylinder::thick_cylinder(p),
        "column-impact" => column_impact::column_impact(p),
        "hertz-line" => hertz_line::hertz_line(p),
        "rate-strain-path" => rate_path::rate_strain_path(p),
        "viscoplastic-truss" => viscoplastic_truss::viscoplastic_truss(p),
        "finite-strain-path" => finite_path::finite_strain_path(p),
        "membrane-regime" => membrane::membrane_regime(p),
        "axisymmetric" => axisymmetric::axisymmetric(p),
        "square-stable-step" => stable_step::square_stable_step(p),
        "table-strain-path" => table_path::table_strain_path(p),
        "thread-invariance" => thread_invariance::thread_invariance(p),
        "probe-point" => probe_point::probe_point(p),
        "wall-bar" => wall_bar::wall_bar(p),
        _ => return None,
    })
}

/// Runs a builtin's scene, written as YAML `text` (`name` stands for the file in messages),
/// on the solver's own time loop with `observer`: the outcome, or the error's message.
pub(crate) fn run_scene_text(
    text: &str,
    name: &str,
    observer: &mut dyn impact_solver::Observer,
) -> Result<impact_solver::Outcome, String> {
    let scene = impact_solver::Scene::from_yaml(text, std::path::Path::new(name))
        .map_err(|e| e.to_string())?;
    impact_solver::simulate(&scene, observer).map_err(|e| e.to_string())
}

/// A builtin's result: its metrics and its one history (the case's plots read it as "").
pub(crate) fn with_history(
    metrics: BTreeMap<String, f64>,
    history: impact_solver::History,
) -> RunData {
    RunData {
        metrics,
        histories: BTreeMap::from([(String::new(), history)]),
        ..Default::default()
    }
}

/// A number parameter (or its default).
pub(crate) fn param(p: &BTreeMap<String, Value>, k: &str, default: f64) -> Result<f64, String> {
    match p.get(k) {
        None => Ok(default),
        Some(v) => v
            .as_f64()
            .ok_or_else(|| format!("param {k}: {v} is not a number")),
    }
}

/// The `geometry` parameter, `plane-strain` or `axisymmetric` (or `default`).
pub(crate) fn param_geometry(
    p: &BTreeMap<String, Value>,
    default: Geometry,
) -> Result<Geometry, String> {
    let name = match p.get("geometry") {
        None => return Ok(default),
        Some(v) => v.as_str().ok_or("param geometry: not a string")?,
    };
    [Geometry::PlaneStrain, Geometry::Axisymmetric]
        .into_iter()
        .find(|g| g.name() == name)
        .ok_or_else(|| format!("param geometry: {name:?} is not plane-strain or axisymmetric"))
}

/// A list of numbers parameter (or its default).
pub(crate) fn param_numbers(
    p: &BTreeMap<String, Value>,
    k: &str,
    default: &[f64],
) -> Result<Vec<f64>, String> {
    match p.get(k) {
        None => Ok(default.to_vec()),
        Some(Value::Array(a)) => a
            .iter()
            .map(|v| {
                v.as_f64()
                    .ok_or_else(|| format!("param {k}: {v} is not a number"))
            })
            .collect(),
        Some(v) => Err(format!("param {k}: {v} is not a list of numbers")),
    }
}

/// The elastic-plastic material of the plasticity builtins (steel with linear hardening by
/// default), SI units.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PlasticMaterial {
    /// Pa
    pub youngs_modulus: f64,
    pub poisson_ratio: f64,
    /// kg/m^3
    pub density: f64,
    /// Pa
    pub yield_stress: f64,
    /// Tangent modulus after yield in uniaxial stress, Pa
    pub tangent_modulus: f64,
}

/// The [`PlasticMaterial`] parameters (or their defaults: 200 GPa, 0.3, 7850 kg/m^3,
/// 250 MPa, 20 GPa).
pub(crate) fn plastic_material(p: &BTreeMap<String, Value>) -> Result<PlasticMaterial, String> {
    Ok(PlasticMaterial {
        youngs_modulus: param(p, "youngs_modulus", 200e9)?,
        poisson_ratio: param(p, "poisson_ratio", 0.3)?,
        density: param(p, "density", 7850.0)?,
        yield_stress: param(p, "yield_stress", 250e6)?,
        tangent_modulus: param(p, "tangent_modulus", 20e9)?,
    })
}

/// A list of positive integers parameter (or its default).
pub(crate) fn param_levels(
    p: &BTreeMap<String, Value>,
    k: &str,
    default: &[usize],
) -> Result<Vec<usize>, String> {
    match p.get(k) {
        None => Ok(default.to_vec()),
        Some(Value::Array(a)) => a
            .iter()
            .map(|v| {
                v.as_u64()
                    .filter(|&n| n > 0)
                    .map(|n| n as usize)
                    .ok_or_else(|| format!("param {k}: {v} is not a positive integer"))
            })
            .collect(),
        Some(v) => Err(format!("param {k}: {v} is not a list")),
    }
}
