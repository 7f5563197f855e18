//! The `axisymmetric` builtin's problems for another code (`crate::codes::problem`): the
//! ring's patch test off and on the axis, the solid disk's uniform expansion and Lame's
//! thick-walled cylinder on 4, 8, 16 and 32 elements through the wall, each the section of
//! `super::axisymmetric` about its axis, in the contract's `(r, z)` form; their metrics from the
//! code's fields by the builtin's own rules. The plastic limit pressure is `impact`'s
//! quasi-static push (`super::collapse`): not produced by another code.

use std::collections::BTreeMap;

use serde_json::Value;

use super::axisymmetric::{
    expansion_error, expansion_setup, lame_error, lame_setup, patch_field, patch_metrics, DISK,
    LAME,
};
use super::driver::distorted_patch;
use super::space_time::element;
use crate::codes::problem::{by_node, Fields, Problem};
use crate::definition::run_data::RunData;

type Params = BTreeMap<String, Value>;

/// Young's modulus (Pa) and Poisson's ratio of the builtin.
const ELASTIC: (f64, f64) = (200e9, 0.3);
/// The patch's axis off and on its edge, m.
const PATCH_AXES: [(&str, f64); 2] = [("patch", 0.03), ("patch-on-axis", 0.02)];
/// Lame's meshes: elements through the wall.
const LAME_NR: [usize; 4] = [4, 8, 16, 32];

/// The problems, labelled, in the order [`from_fields`] reads them.
pub fn problems(p: &Params) -> Result<Vec<(&'static str, Problem)>, String> {
    let kind = element(p)?.name();
    let mut out = Vec::new();
    let patch = distorted_patch();
    for (label, axis) in PATCH_AXES {
        let u = patch_field(&patch, axis);
        let all = by_node(u.into_iter().enumerate());
        out.push((
            label,
            Problem::about_axis(kind, ELASTIC, (&patch, axis), all, Vec::new()),
        ));
    }
    let (disk, prescribed) = expansion_setup()?;
    let disk_problem = Problem::about_axis(
        kind,
        ELASTIC,
        (&disk.mesh, DISK.0),
        by_node(prescribed),
        Vec::new(),
    );
    out.push(("expansion", disk_problem));
    for (nr, label) in LAME_NR
        .into_iter()
        .zip(["lame-4", "lame-8", "lame-16", "lame-32"])
    {
        let (wall, prescribed, loads) = lame_setup(nr)?;
        let loads = by_node(loads);
        let problem = Problem::about_axis(
            kind,
            ELASTIC,
            (&wall.mesh, LAME.1),
            by_node(prescribed),
            loads,
        );
        out.push((label, problem));
    }
    Ok(out)
}

/// The builtin's metrics (but the limit pressure's) from the code's fields of [`problems`].
pub fn from_fields(_: &Params, fields: &[Fields]) -> Result<RunData, String> {
    let [patch, on_axis, expansion, lame @ ..] = fields else {
        return Err(format!(
            "axisymmetric: {} fields for its 7 problems",
            fields.len()
        ));
    };
    if lame.len() != LAME_NR.len() {
        return Err(format!(
            "axisymmetric: {} fields for its 7 problems",
            fields.len()
        ));
    }
    let mut m = BTreeMap::new();
    for (prefix, f) in [("patch", patch), ("patch_on_axis", on_axis)] {
        let (_, forces, stresses) = f.on_section();
        let (force, stress) = patch_metrics(forces.as_deref(), stresses.into_iter());
        if let Some(force) = force {
            m.insert(format!("{prefix}_free_node_force_rel"), force);
        }
        m.insert(format!("{prefix}_stress_max_rel_error"), stress);
    }
    let (disk, _) = expansion_setup()?;
    m.insert(
        "expansion_max_rel_error".into(),
        expansion_error(&disk, &expansion.on_section().0),
    );
    let mut errors = Vec::new();
    for (nr, f) in LAME_NR.into_iter().zip(lame) {
        let (wall, _, _) = lame_setup(nr)?;
        let error = lame_error(&wall, &f.on_section().0);
        m.insert(format!("lame_error_nr{nr}"), error);
        errors.push(error);
    }
    m.insert("lame_order".into(), (errors[2] / errors[3]).log2());
    Ok(RunData {
        metrics: m,
        ..Default::default()
    })
}
