//! Prescribed loads: a fixed pattern of nodal forces scaled by a rectangular time function.
//! - `pulse`: a point force on the top mid-span node (the paper's 86.5 kN verification case);
//! - `traction`: a uniform normal and/or shear traction on the whole top surface (plane
//!   P and S waves), lumped to the top nodes by their tributary lengths.
//!
//! The external work on the whole plate is `s sum_n (g_n + g_{n+1})/2 (P . (u_{n+1} - u_n))`
//! with `P` the nodal pattern of the modelled part, `g` the magnitude and `s` the symmetry
//! factor (trapezoidal rule, as for the internal work).

use crate::input::scene::{Load, Plate};
use crate::mesh::PlateMesh;

#[derive(Debug, Clone, PartialEq)]
pub struct PrescribedLoad {
    /// (dof, nodal force per unit magnitude) on the modelled part.
    pattern: Vec<(usize, f64)>,
    /// Magnitude while the load acts: the total force on the whole plate it reports, N
    /// (the normal force for a traction).
    magnitude: f64,
    /// s
    duration: f64,
    symmetry_factor: f64,
}

impl PrescribedLoad {
    /// The prescribed load of a scene, if it has one (an impactor and the wall have none).
    pub fn from_scene(load: &Load, plate: &Plate, mesh: &PlateMesh) -> Option<PrescribedLoad> {
        let s = mesh.symmetry_factor;
        match load {
            Load::Impactor(_) | Load::SurfaceImpactor(_) | Load::Wall(_) => None,
            Load::Pulse(p) => Some(PrescribedLoad {
                pattern: vec![(2 * mesh.top + 1, -1.0 / s)],
                magnitude: p.force,
                duration: p.duration,
                symmetry_factor: s,
            }),
            Load::Traction(t) => {
                // Total normal force on the whole plate (N) is the reported magnitude; with
                // a shear-only traction the magnitude is the total shear force.
                let area = plate.length * plate.width;
                let (magnitude, normal, shear) = if t.normal != 0.0 {
                    (t.normal * area, 1.0, t.shear / t.normal)
                } else {
                    (t.shear * area, 0.0, 1.0)
                };
                let pattern = mesh
                    .top_nodes_with_tributary_length()
                    .into_iter()
                    .flat_map(|(node, length)| {
                        let share = length * plate.width / area; // of the whole-plate force
                        [(2 * node, shear * share), (2 * node + 1, -normal * share)]
                    })
                    .filter(|&(_, f)| f != 0.0)
                    .collect();
                Some(PrescribedLoad {
                    pattern,
                    magnitude,
                    duration: t.duration,
                    symmetry_factor: s,
                })
            }
        }
    }

    /// The load's magnitude at `t` (rectangular: on for `0 <= t < duration`), N.
    pub fn magnitude_at(&self, t: f64) -> f64 {
        if (0.0..self.duration).contains(&t) {
            self.magnitude
        } else {
            0.0
        }
    }

    /// Subtracts the nodal forces at magnitude `g` from `f_int` (which then holds
    /// `f_int - f_ext`).
    pub fn subtract_from(&self, g: f64, f_int: &mut [f64]) {
        for &(dof, p) in &self.pattern {
            f_int[dof] -= g * p;
        }
    }

    /// `P . u`: the generalised displacement the load works on, m.
    pub fn projection(&self, u: &[f64]) -> f64 {
        self.pattern.iter().map(|&(dof, p)| p * u[dof]).sum()
    }

    /// Work on the whole plate over a step (J), from the magnitudes at its ends and the
    /// projections before and after.
    pub fn work(&self, g0: f64, g1: f64, projection_before: f64, projection_after: f64) -> f64 {
        self.symmetry_factor * 0.5 * (g0 + g1) * (projection_after - projection_before)
    }
}
