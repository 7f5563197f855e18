//! The parameters a case gives a builtin (`params:` of a `builtin:` scene), each read with
//! its default: numbers, strings, lists, the geometry and the element kind.

use std::collections::BTreeMap;

use impact_solver::input::geometry::Geometry;
use impact_solver::scene::ElementKind;
use serde_json::Value;

/// A builtin's parameters by name.
pub(super) type Params = BTreeMap<String, Value>;

/// A number parameter (or its default).
pub(super) fn param(p: &Params, k: &str, default: f64) -> Result<f64, String> {
    match p.get(k) {
        None => Ok(default),
        Some(v) => v
            .as_f64()
            .ok_or_else(|| format!("param {k}: {v} is not a number")),
    }
}

/// A string parameter (or its default).
pub(super) fn param_str<'a>(p: &'a Params, k: &str, default: &'a str) -> Result<&'a str, String> {
    match p.get(k) {
        None => Ok(default),
        Some(v) => v
            .as_str()
            .ok_or_else(|| format!("param {k}: {v} is not a string")),
    }
}

/// A list of numbers parameter (or its default).
pub(super) fn param_numbers(p: &Params, k: &str, default: &[f64]) -> Result<Vec<f64>, String> {
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

/// A list of positive integers parameter (or its default).
pub(super) fn param_levels(p: &Params, k: &str, default: &[usize]) -> Result<Vec<usize>, String> {
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

/// The `geometry` parameter, `plane-strain` or `axisymmetric` (or `default`).
pub(super) fn param_geometry(p: &Params, default: Geometry) -> Result<Geometry, String> {
    let name = match p.get("geometry") {
        None => return Ok(default),
        Some(v) => v.as_str().ok_or("param geometry: not a string")?,
    };
    [Geometry::PlaneStrain, Geometry::Axisymmetric]
        .into_iter()
        .find(|g| g.name() == name)
        .ok_or_else(|| format!("param geometry: {name:?} is not plane-strain or axisymmetric"))
}

/// The element kind a parameter names (`q4-sri`, ...).
pub(super) fn element_kind(name: &str) -> Result<ElementKind, String> {
    name.parse().map_err(|e| format!("param element: {e}"))
}
