//! Surface contact of the rigid nose (`load.impactor.contact: surface`, `ALGORITHM.md`
//! section 5b): a rigid cylinder of radius `R`, its axis at mid-span, moving along y only, in
//! frictionless penalty contact with the plate's top-surface nodes (node-to-rigid-surface, the
//! nodes slaves of the analytical surface, as Abaqus/Explicit's analytical rigid surfaces and
//! LS-DYNA's rigid-wall contacts).
//!
//! A node at `p` (current position) with `d = p - c`, `c = (x_c, h + R - delta_S)` the nose's
//! centre, penetrates by `g = R - |d|`; where `g > 0` the nose pushes it along `n = d / |d|`
//! with the force `k_i g n` and stores `k_i g^2 / 2`. The impactor takes the sum of the
//! reactions. The penalty stiffness of node `i` is `k_i = s m_i lambda_i` (`s` the
//! `penalty_scale`, `m_i` its lumped mass, `lambda_i` the largest element eigenvalue of the
//! top-row elements that hold it): a spring that adds at most `s lambda_i` to the largest
//! eigenvalue of `M^-1 K` (Weyl), so the stable step shrinks by at most `1/sqrt(1 + s)`.

use crate::mesh::PlateMesh;

/// A top-surface node the nose can reach.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceNode {
    pub node: usize,
    /// Reference position, m.
    pub x: f64,
    pub y: f64,
    /// Penalty stiffness, N/m, for the modelled part of the plate.
    pub stiffness: f64,
}

/// The rigid nose and the nodes it can touch.
#[derive(Debug, Clone, PartialEq)]
pub struct NoseSurface {
    /// The nose's axis, m.
    pub center_x: f64,
    /// y of the axis before the impactor moves (`h + R`), m.
    pub center_y0: f64,
    /// m
    pub radius: f64,
    pub nodes: Vec<SurfaceNode>,
}

/// The contact state at one instant, for the modelled part of the plate.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct NoseForces {
    /// Force of the nose on each of [`NoseSurface::nodes`], N (x, y).
    pub on_node: Vec<[f64; 2]>,
    /// Downward force of the nose on the plate (the impactor's reaction), N.
    pub total: f64,
    /// Penalty energy `sum k g^2 / 2`, J.
    pub energy: f64,
    /// Nodes with `g > 0`.
    pub in_contact: usize,
    /// Largest `|x - x_c|` of a node in contact (current positions), m.
    pub half_width: f64,
}

impl NoseSurface {
    /// The nose over the top-surface nodes within `1.1 R` of its axis (a node farther away
    /// would have to move sideways by `0.1 R` to touch: small strain). `lambda(e)` is element
    /// `e`'s largest eigenvalue, (rad/s)^2; `mass` the nodal masses, kg.
    pub fn new(
        mesh: &PlateMesh,
        radius: f64,
        penalty_scale: f64,
        mass: &[f64],
        lambda: impl Fn(usize) -> f64,
    ) -> NoseSurface {
        let center_x = 0.5 * mesh.length;
        let top_row = (mesh.ny - 1) * mesh.nx;
        let first = mesh.ny * (mesh.nx + 1);
        let nodes = (0..=mesh.nx)
            .filter_map(|i| {
                let node = first + i;
                let [x, y] = mesh.mesh.coords[node];
                if (x - center_x).abs() > 1.1 * radius {
                    return None;
                }
                // The top-row elements holding node (i, ny): i - 1 and i.
                let mut lambda_i: f64 = 0.0;
                for e in [i.wrapping_sub(1), i] {
                    if e < mesh.nx {
                        lambda_i = lambda_i.max(lambda(top_row + e));
                    }
                }
                Some(SurfaceNode {
                    node,
                    x,
                    y,
                    stiffness: penalty_scale * mass[node] * lambda_i,
                })
            })
            .collect();
        let top = mesh.mesh.coords[first][1];
        NoseSurface {
            center_x,
            center_y0: top + radius,
            radius,
            nodes,
        }
    }

    /// The largest `k_i / m_i` of the nodes, (rad/s)^2: what the penalty adds at most to the
    /// largest eigenvalue of `M^-1 K`.
    pub fn largest_spring_eigenvalue(&self, mass: &[f64]) -> f64 {
        self.nodes
            .iter()
            .map(|n| n.stiffness / mass[n.node])
            .fold(0.0, f64::max)
    }

    /// The contact forces at displacements `u` (m, 2 per node) with the impactor moved down by
    /// `delta` (m), into `out` (its buffers reused: no allocation after the first call).
    pub fn evaluate(&self, u: &[f64], delta: f64, out: &mut NoseForces) {
        let (cx, cy) = (self.center_x, self.center_y0 - delta);
        out.on_node.clear();
        out.total = 0.0;
        out.energy = 0.0;
        out.in_contact = 0;
        out.half_width = 0.0;
        for n in &self.nodes {
            let px = n.x + u[2 * n.node];
            let py = n.y + u[2 * n.node + 1];
            let (dx, dy) = (px - cx, py - cy);
            let distance = (dx * dx + dy * dy).sqrt();
            let g = self.radius - distance;
            if g <= 0.0 || distance == 0.0 {
                out.on_node.push([0.0, 0.0]);
                continue;
            }
            let f = n.stiffness * g / distance;
            let force = [f * dx, f * dy];
            out.on_node.push(force);
            out.total -= force[1];
            out.energy += 0.5 * n.stiffness * g * g;
            out.in_contact += 1;
            out.half_width = out.half_width.max(dx.abs());
        }
    }
}

#[cfg(test)]
mod tests {
    //! Against hand-computed geometry: a node pushed below the nose by a known depth takes
    //! `k g` along the radius, a node outside takes nothing, the energy is `k g^2 / 2`.
    use super::*;

    fn nose() -> NoseSurface {
        NoseSurface {
            center_x: 0.0,
            center_y0: 1.0,
            radius: 1.0,
            nodes: vec![
                SurfaceNode {
                    node: 0,
                    x: 0.0,
                    y: 0.0,
                    stiffness: 10.0,
                },
                SurfaceNode {
                    node: 1,
                    x: 0.6,
                    y: 0.0,
                    stiffness: 20.0,
                },
            ],
        }
    }

    #[test]
    fn penetrating_nodes_are_pushed_along_the_radius() {
        let mut out = NoseForces::default();
        // delta = 0.1: node 0 penetrates by 0.1 straight down; node 1 at distance
        // sqrt(0.36 + 0.81) = 1.0817 > 1: free.
        nose().evaluate(&[0.0; 4], 0.1, &mut out);
        assert_eq!(out.in_contact, 1);
        assert!((out.on_node[0][1] + 1.0).abs() < 1e-12, "{:?}", out.on_node);
        assert_eq!(out.on_node[1], [0.0, 0.0]);
        assert!((out.total - 1.0).abs() < 1e-12);
        assert!((out.energy - 0.05).abs() < 1e-12);
        // delta = 0.3: node 1 at distance sqrt(0.36 + 0.49) = 0.92195, g = 0.07805, along
        // (0.6, -0.7) / 0.92195.
        nose().evaluate(&[0.0; 4], 0.3, &mut out);
        let (d, g) = (0.85_f64.sqrt(), 1.0 - 0.85_f64.sqrt());
        assert_eq!(out.in_contact, 2);
        assert!((out.on_node[1][0] - 20.0 * g * 0.6 / d).abs() < 1e-12);
        assert!((out.on_node[1][1] + 20.0 * g * 0.7 / d).abs() < 1e-12);
        assert!((out.total - (10.0 * 0.3 + 20.0 * g * 0.7 / d)).abs() < 1e-12);
        assert!((out.half_width - 0.6).abs() < 1e-15);
        assert!((out.energy - (5.0 * 0.09 + 10.0 * g * g)).abs() < 1e-12);
    }

    #[test]
    fn the_spring_eigenvalue_is_the_largest_stiffness_over_mass() {
        assert_eq!(nose().largest_spring_eigenvalue(&[2.0, 2.0]), 10.0);
    }
}
