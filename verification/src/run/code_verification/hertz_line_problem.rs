//! The `hertz-line` builtin as a problem for another code (issue 38, `crate::codes::problem`,
//! a [`STATIC_CONTACT`](crate::codes::problem::STATIC_CONTACT)): the builtin's block (its
//! mesh, supports and material, from its own scene) with the rigid cylinder of radius `R`
//! touching the top surface on the axis, pressed statically down by `indentation` (m; 35 um
//! by default, which on the 20 mm block gives about the dynamic run's peak force, P near
//! 2e6 N/m). The code's contact force on each top node is its internal force there; the metrics are
//! the builtin's own ([`super::hertz_line::measure`]) from those forces, so Hertz's `p0` and
//! `a` are taken at the code's total force, as at the dynamic run's frame. A held node carries
//! its reaction, not a contact force: the top row's held node (the clamped end, 43 or more
//! half-widths from the contact) counts as out of contact.

use std::collections::BTreeMap;

use impact_solver::mesh::PlateMesh;
use impact_solver::Scene;
use serde_json::Value;

use super::hertz_line::{measure, scene, Block, RADIUS, WIDTH};
use crate::codes::problem::{held, Fields, Problem, ProblemIndenter};
use crate::definition::run_data::RunData;
use crate::run::builtin_params::param;

type Params = BTreeMap<String, Value>;

/// The builtin's block: its scene's mesh and the element it runs.
fn block_mesh(p: &Params) -> Result<(Block, PlateMesh, &'static str), String> {
    let block = Block::of(p)?;
    let text = scene(block.n, block.size, block.model_modulus, block.elastic.1);
    let scene = Scene::from_yaml(&text, std::path::Path::new("(builtin hertz-line)"))
        .map_err(|e| e.to_string())?;
    Ok((
        block,
        PlateMesh::of_scene(&scene),
        scene.mesh.element.name(),
    ))
}

/// The block pressed by the cylinder, as one problem.
pub fn problems(p: &Params) -> Result<Vec<(&'static str, Problem)>, String> {
    let (block, mesh, element) = block_mesh(p)?;
    let indentation = param(p, "indentation", 3.5e-5)?;
    let modulus = (block.model_modulus, block.elastic.1);
    let problem = Problem::plane_strain(
        element,
        WIDTH,
        modulus,
        &mesh.mesh,
        held(&mesh.fixed_dofs, |_| 0.0),
        vec![],
    );
    let indenter = ProblemIndenter {
        radius: RADIUS,
        touch: mesh.mesh.coords[mesh.top],
        displacement: [0.0, -indentation],
        surface_nodes: (mesh.top_nodes_with_tributary_length().iter())
            .map(|(node, _)| *node)
            .collect(),
    };
    Ok(vec![("", problem.pressed_by(indenter))])
}

/// The builtin's metrics from the code's nodal forces on the top surface (the held nodes'
/// reactions left out).
pub fn from_fields(p: &Params, fields: &[Fields]) -> Result<RunData, String> {
    let (block, mesh, _) = block_mesh(p)?;
    let [fields] = fields else {
        return Err(format!(
            "hertz-line: {} fields for its one problem",
            fields.len()
        ));
    };
    let Some(forces) = &fields.nodal_forces else {
        return Ok(RunData::default()); // every metric not produced
    };
    let contact: Vec<[f64; 2]> = (forces.iter().enumerate())
        .map(|(node, &f)| {
            if mesh.fixed_dofs[2 * node + 1] {
                [0.0; 2]
            } else {
                f
            }
        })
        .collect();
    Ok(RunData {
        metrics: measure(&contact, block.n, block.size, block.e_star()),
        ..Default::default()
    })
}

#[cfg(test)]
mod tests {
    //! The problem form against the builtin: the problem is the builtin's block and cylinder,
    //! and the evaluation of a code's nodal forces is the builtin's own measure (impact's
    //! contact forces at the peak frame, written as another code writes them, give its
    //! metrics bit for bit); a code whose axis node carries 10 % more force is seen.
    use super::super::hertz_line::peak_run;
    use super::*;

    fn params() -> Params {
        Params::from([
            ("n".to_string(), Value::from(88)),
            ("size".to_string(), Value::from(0.02)),
        ])
    }

    #[test]
    fn the_problem_is_the_builtins_block_pressed_on_its_axis() {
        let [(_, problem)] = &problems(&params()).unwrap()[..] else {
            panic!("one problem")
        };
        let (_, mesh, _) = block_mesh(&params()).unwrap();
        let json = serde_json::to_value(problem).unwrap();
        assert_eq!(json["problem"], "static contact");
        let ind = problem.indenter.as_ref().unwrap();
        assert_eq!(ind.touch, [0.02, 0.02]); // the top node on the axis (the half model's x = L/2)
        assert_eq!((ind.radius, ind.displacement), (0.02, [0.0, -3.5e-5]));
        assert_eq!(ind.surface_nodes, (88 * 89..89 * 89).collect::<Vec<_>>());
        let held = mesh.fixed_dofs.iter().filter(|f| **f).count();
        assert_eq!(problem.prescribed_m.len(), held);
        assert_eq!(problem.element, "q4-sri");
    }

    #[test]
    fn own_contact_forces_give_the_builtin_metrics() {
        let block = Block::of(&params()).unwrap();
        let (frame, _) = peak_run(&block).unwrap();
        let forces = frame.contact_force.clone().unwrap();
        let own = measure(&forces, block.n, block.size, block.e_star());
        let fields = |forces: Vec<[f64; 2]>| Fields {
            displacements: vec![[0.0; 2]; forces.len()],
            nodal_forces: Some(forces),
            point_stresses: vec![vec![[0.0; 4]]; 88 * 88],
            point_eqps: None,
        };
        let from = from_fields(&params(), &[fields(forces.clone())]).unwrap();
        assert_eq!(from.metrics.len(), own.len());
        for (k, v) in &from.metrics {
            assert_eq!(v.to_bits(), own[k].to_bits(), "{k}: {v} {}", own[k]);
        }
        let mut more = forces;
        more[88 * 89 + 88][1] *= 1.1; // the top node on the axis
        let moved = from_fields(&params(), &[fields(more)]).unwrap().metrics;
        let rel = moved["axis_pressure_Pa"] / own["axis_pressure_Pa"] - 1.0;
        assert!(rel > 0.09, "{rel}");
    }
}
