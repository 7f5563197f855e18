//! The `plastic-strain-path` builtin as a problem for another code (issue 38,
//! `crate::codes::problem`, a [`STATIC_PATH`](crate::codes::problem::STATIC_PATH)): the same
//! block, material and boundary, followed through the same cycle statically. At the load
//! factors `sin(pi t_n / T)`, `t_n = n T / N`, `n = 1 .. N` (`N` the finest level's step count)
//! the boundary nodes sit at `u = eps_max sin(pi t_n / T) x`, the interior nodes are free and
//! unloaded: the homogeneous field is an equilibrium without the dynamic run's body force. Along
//! this path the deviatoric strain keeps one direction, so a radial return with linear hardening
//! is exact whatever the increment: a code that is right meets the closed form at every factor
//! to its round-off (and its printing).
//!
//! The metrics are the dynamic run's finest-level ones read from the code's fields at each
//! factor; point 0's history is the first point of the first element in the code's own order
//! (the field is homogeneous). The orders in dt have no counterpart in a static path: *not
//! produced*.

use std::collections::BTreeMap;

use serde_json::Value;

use super::plastic_path::{path_run, row, setup, uniaxial};
use super::space_time::element;
use crate::codes::problem::{held, Fields, Problem, ProblemPlasticity};
use crate::definition::run_data::RunData;

type Params = BTreeMap<String, Value>;

/// The path as one problem: the boundary's displacements at `eps_max`, scaled by each factor.
pub fn problems(p: &Params) -> Result<Vec<(&'static str, Problem)>, String> {
    let (path, mesh, levels) = setup(p)?;
    let steps = levels[levels.len() - 1];
    let coords = &mesh.mesh.coords;
    let boundary = held(&mesh.fixed_dofs, |d| {
        uniaxial(d, coords[d / 2][0], path.eps_max)
    });
    let factors = (1..=steps)
        .map(|n| path.strain(path.time(n, steps)) / path.eps_max)
        .collect();
    let plasticity = ProblemPlasticity {
        yield_stress: path.model.0,
        tangent_modulus: path.model.1,
    };
    let problem = Problem::plane_strain(
        element(p)?.name(),
        1.0,
        (path.youngs_modulus, path.poisson_ratio),
        &mesh.mesh,
        boundary,
        Vec::new(),
    );
    Ok(vec![("", problem.along_path(plasticity, factors))])
}

/// The builtin's finest-level metrics from the code's fields at each load factor of
/// [`problems`] (the equivalent plastic strain's too when the code gives it).
pub fn from_fields(p: &Params, fields: &[Fields]) -> Result<RunData, String> {
    let (path, _, levels) = setup(p)?;
    let steps = levels[levels.len() - 1];
    if fields.len() != steps {
        return Err(format!(
            "plastic-strain-path: {} fields for the path's {steps} load factors",
            fields.len()
        ));
    }
    let rows: Vec<_> = (fields.iter().enumerate())
        .map(|(k, f)| row(&path, path.time(k + 1, steps), f))
        .collect();
    let mut run = path_run(&path, &rows, BTreeMap::new());
    if fields.iter().any(|f| f.point_eqps.is_none()) {
        for key in ["eqps_error_finest", "yield_onset_strain", "final_eqps"] {
            run.metrics.remove(key);
        }
    }
    Ok(run)
}
