//! The stable time step `dt_crit = 2 / omega_max` (eq. 15), from one of two estimates of
//! `omega_max^2`, the largest eigenvalue of `M^-1 K`:
//!
//! - `element`: the largest element eigenvalue with lumped mass, a rigorous upper bound of
//!   the global one (so a step below the true critical one; 15-16 % below on uniform meshes).
//! - `global`: power iteration on `M^-1/2 K M^-1/2` (elastic stiffness, hourglass included)
//!   plus the contact spring at the loaded node, at its stiffest force the impactor's energy
//!   can reach. The Rayleigh quotient approaches the largest eigenvalue from below, so the
//!   step is multiplied by [`GLOBAL_SAFETY`].

use crate::kernels::stiffness::LinearKernel;
use crate::mesh::Mesh;
use crate::physics::contacts::contact::LineContactLaw;
use crate::physics::elements::element::{element_max_eigenvalue, scatter_add, Formulation};
use crate::physics::elements::geometry::PointGeometry;
use crate::physics::materials::material::Elastic;

pub use crate::input::scene::Estimate;

/// Power iterations at most (each is one stiffness product over the mesh).
const MAX_ITERATIONS: usize = 2000;
/// Converged when the Rayleigh quotient moved less than this (relative) over
/// [`CHECK_EVERY`] iterations.
const TOLERANCE: f64 = 1e-7;
const CHECK_EVERY: usize = 20;

/// Factor on the global step. The Rayleigh quotient is below the largest eigenvalue by the
/// weight left in the modes just under it (a cluster on a fine uniform mesh): stopping when
/// it moves by 1e-7 per 20 iterations leaves it within ~1 % of the top of the spectrum on
/// the meshes of the stability benchmark; 0.98 on the step covers 4 % on the eigenvalue.
pub const GLOBAL_SAFETY: f64 = 0.98;

/// A spring to ground on one degree of freedom (the contact at the loaded node).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spring {
    pub dof: usize,
    /// N/m, for the modelled part of the plate (divided by the symmetry factor).
    pub stiffness: f64,
}

/// `2 / sqrt(max_e lambda_e)`, s.
pub fn element_bound<F: Formulation>(formulation: &F, elastic: &Elastic, density: f64) -> f64 {
    let lambda_max = (0..formulation.n_elements())
        .map(|e| element_max_eigenvalue(formulation, elastic, density, e))
        .fold(0.0, f64::max);
    2.0 / lambda_max.sqrt()
}

/// `S = sum_a |grad N_a|^2` (1/m^2) at the centroid of the element with node coordinates
/// `c` (m): what [`deformed_ratio`] compares.
pub fn centroid_spread(c: &[[f64; 2]; 4]) -> f64 {
    let g = PointGeometry::at(&c.map(|p| [p[0] - c[0][0], p[1] - c[0][1]]), [0.0, 0.0]);
    (0..4)
        .map(|a| g.dndx[a] * g.dndx[a] + g.dndy[a] * g.dndy[a])
        .sum()
}

/// [`centroid_spread`] of every element of `mesh` as it was made (the reference of
/// [`deformed_ratio`], computed once per run).
pub fn reference_spreads(mesh: &Mesh) -> Vec<f64> {
    (0..mesh.elements.len())
        .map(|e| centroid_spread(&mesh.element_coords(e)))
        .collect()
}

/// How far deformation has shortened the stable step, for finite deformation: the smallest
/// over the elements of `sqrt(S_ref / S_cur)` ([`centroid_spread`] on the reference,
/// `reference` from [`reference_spreads`], and on the current (`u`, m) configuration), and that
/// element. An element's highest frequency is `omega^2 ~ (lambda + 2 mu) S_cur / rho_0` (the
/// forces `w_ref tau : grad_x N` with a Kirchhoff modulus and the reference mass), so its step
/// scales by this ratio: by the stretch of a side compressed alone, 1 for a rigid motion.
pub fn deformed_ratio(mesh: &Mesh, reference: &[f64], u: &[f64]) -> (f64, usize) {
    let mut smallest = (f64::INFINITY, 0);
    for (e, nodes) in mesh.elements.iter().enumerate() {
        let made = mesh.element_coords(e);
        let current = std::array::from_fn(|a| {
            let n = nodes[a] as usize;
            [made[a][0] + u[2 * n], made[a][1] + u[2 * n + 1]]
        });
        let ratio = (reference[e] / centroid_spread(&current)).sqrt();
        if ratio < smallest.0 {
            smallest = (ratio, e);
        }
    }
    smallest
}

/// The largest stiffness `dF/d alpha` (N/m, whole width) of the contact law up to the force
/// at which its stored energy equals `energy` (J, the impactor's initial kinetic energy: no
/// larger force can be reached while energy is conserved), or up to 0.999 of the law's
/// maximum when that energy is beyond what the law can store.
pub fn contact_stiffness_bound(law: &LineContactLaw, energy: f64) -> f64 {
    let max_force = law.max_force_per_width() * law.width;
    let (mut lo, mut hi) = (0.0, 0.999 * max_force);
    if law.energy(hi) > energy {
        // Bisection: energy(F) increases with F on the physical branch.
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if law.energy(mid) > energy {
                hi = mid;
            } else {
                lo = mid;
            }
        }
    }
    // alpha' falls with P on the branch, so the stiffness W / alpha' is largest at `hi`.
    law.width / law.alpha_slope(hi / law.width)
}

/// `2 / sqrt(lambda)` with `lambda` the power-iteration estimate of the largest eigenvalue of
/// `M^-1 K` (+ `spring`), times [`GLOBAL_SAFETY`], s. `inverse_mass`: 1/mass per dof, 0 on
/// constrained dofs (they do not move).
pub fn global_estimate<F: Formulation>(
    formulation: &F,
    elastic: &Elastic,
    inverse_mass: &[f64],
    spring: Option<Spring>,
) -> f64 {
    let kernel = LinearKernel::new(formulation, elastic);
    let n = inverse_mass.len();
    let scale: Vec<f64> = inverse_mass.iter().map(|m| m.sqrt()).collect();
    // A deterministic start with weight in every mode (xorshift), zero on fixed dofs.
    let mut seed = 0x9E37_79B9_7F4A_7C15_u64;
    let mut x: Vec<f64> = scale
        .iter()
        .map(|&s| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            let r = (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
            if s > 0.0 {
                r
            } else {
                0.0
            }
        })
        .collect();
    let (mut z, mut f) = (vec![0.0; n], vec![0.0; n]);
    let (mut lambda, mut checked) = (0.0, 0.0);
    for iteration in 1..=MAX_ITERATIONS {
        let norm = x.iter().map(|v| v * v).sum::<f64>().sqrt();
        for d in 0..n {
            x[d] /= norm;
            z[d] = scale[d] * x[d];
        }
        f.fill(0.0);
        for e in 0..formulation.n_elements() {
            let nodes = formulation.nodes(e);
            let (fe, _) = kernel.element(formulation, e, &z);
            scatter_add(nodes, &fe, &mut f);
        }
        if let Some(s) = spring {
            f[s.dof] += s.stiffness * z[s.dof];
        }
        lambda = 0.0;
        for d in 0..n {
            x[d] = scale[d] * f[d];
            lambda += z[d] * f[d];
        }
        if iteration % CHECK_EVERY == 0 {
            if (lambda - checked).abs() <= TOLERANCE * lambda {
                break;
            }
            checked = lambda;
        }
    }
    GLOBAL_SAFETY * 2.0 / lambda.sqrt()
}

#[cfg(test)]
mod tests {
    //! Reference: the dense eigenvalues of `M^-1/2 K M^-1/2` (nalgebra) on a small mesh; the
    //! element bound must lie above the global eigenvalue, the estimate just below it.
    use super::*;
    use crate::physics::elements::element::SelectiveQ4;
    use crate::time_loop::plate_model::PlateModel;

    #[test]
    fn power_iteration_finds_the_largest_eigenvalue_below_the_element_bound() {
        for grading in [1.0, 3.0] {
            let mesh = crate::mesh::test_plate_mesh(10, 3, grading);
            let f = SelectiveQ4::new(&mesh.mesh, 0.2).unwrap();
            let elastic = Elastic::new(207e9, 0.3);
            let density = 7850.0;
            let model = PlateModel::new(
                SelectiveQ4::new(&mesh.mesh, 0.2).unwrap(),
                elastic,
                &mesh,
                density,
            );
            let inverse_mass = model.inverse_mass;
            // Dense operator, column by column.
            let n = inverse_mass.len();
            let kernel = LinearKernel::new(&f, &elastic);
            let a = nalgebra::DMatrix::<f64>::from_fn(n, n, |i, j| {
                let mut unit = vec![0.0; n];
                unit[j] = 1.0;
                let mut col = vec![0.0; n];
                for e in 0..f.n_elements() {
                    let (fe, _) = kernel.element(&f, e, &unit);
                    scatter_add(f.nodes(e), &fe, &mut col);
                }
                inverse_mass[i].sqrt() * col[i] * inverse_mass[j].sqrt()
            });
            let a = 0.5 * (&a + a.transpose());
            let exact = 2.0 / a.symmetric_eigenvalues().max().sqrt();
            let global = global_estimate(&f, &elastic, &inverse_mass, None);
            let bound = element_bound(&f, &elastic, density);
            assert!(bound < exact, "element bound {bound:e} vs exact {exact:e}");
            // The estimate carries the safety factor and converged to 1e-3 of the step.
            let ratio = global / exact;
            assert!(
                ratio <= GLOBAL_SAFETY * 1.001 && ratio >= GLOBAL_SAFETY * 0.999,
                "grading {grading}: global / exact = {ratio}"
            );
            // A contact spring stiffer than the plate lowers the step.
            let spring = Spring {
                dof: 2 * mesh.top + 1,
                stiffness: 1e12,
            };
            let with_spring = global_estimate(&f, &elastic, &inverse_mass, Some(spring));
            assert!(with_spring < 0.9 * global, "{with_spring:e} vs {global:e}");
        }
    }
}
