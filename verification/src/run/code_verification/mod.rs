//! Code verification builtins (issue 15): observed order of accuracy of the three Q4
//! elements and of central differences on a manufactured solution, and the impactor's
//! update against a fixed linear spring. Each returns metrics for the checks and a small
//! history ("orders") for the report's order plots.

pub mod axisymmetric;
pub mod axisymmetric_problems;
pub mod bar_wave;
pub mod bending_period;
pub mod collapse;
pub mod column_impact;
pub mod driver;
pub mod element_eigen;
pub mod finite_path;
pub mod hertz_line;
pub mod hertz_line_problem;
pub mod macneal_harder;
pub mod manufactured;
pub mod membrane;
pub mod orders;
pub mod plastic_material;
pub mod plastic_path;
pub mod plastic_path_problem;
pub mod probe_point;
pub mod rate_path;
pub mod rigid_target;
pub mod scene_text;
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
