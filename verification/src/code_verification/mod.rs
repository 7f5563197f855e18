//! Code verification builtins (issue 15): observed order of accuracy of the three Q4
//! elements and of central differences on a manufactured solution, and the impactor's
//! update against a fixed linear spring. Each returns metrics for the checks and a small
//! history ("orders") for the report's order plots.

pub mod driver;
pub mod element_eigen;
pub mod macneal_harder;
pub mod manufactured;
pub mod orders;
pub mod plastic_path;
pub mod rigid_target;
pub mod space_time;
pub mod spring;

use std::collections::BTreeMap;

use serde_json::Value;

use crate::data::RunData;

/// The builtins of this module.
pub const NAMES: [&str; 7] = [
    "mms-space",
    "mms-time",
    "impactor-spring",
    "macneal-harder-patch",
    "rigid-target",
    "plastic-strain-path",
    "element-eigenvalues",
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
        _ => return None,
    })
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
