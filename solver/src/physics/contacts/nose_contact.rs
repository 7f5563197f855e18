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
    /// y of the top surface (`h`), m: the nose's lowest point before the impactor moves.
    pub top: f64,
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
    /// `e`'s largest eigenvalue, (rad/s)^2, asked once per top-row element a candidate holds
    /// and only when `penalty_scale > 0` (the kinematic enforcement has no springs: 0); `mass`
    /// the nodal masses, kg.
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
        // Each top-row element's eigenvalue, computed when a candidate first needs it.
        let mut eigenvalues: Vec<Option<f64>> = vec![None; mesh.nx];
        let mut nodes = Vec::new();
        for i in 0..=mesh.nx {
            let node = first + i;
            let [x, y] = mesh.mesh.coords[node];
            if (x - center_x).abs() > 1.1 * radius {
                continue;
            }
            // The top-row elements holding node (i, ny): i - 1 and i.
            let mut lambda_i: f64 = 0.0;
            if penalty_scale > 0.0 {
                for e in [i.wrapping_sub(1), i].into_iter().filter(|&e| e < mesh.nx) {
                    let l = *eigenvalues[e].get_or_insert_with(|| lambda(top_row + e));
                    lambda_i = lambda_i.max(l);
                }
            }
            nodes.push(SurfaceNode {
                node,
                x,
                y,
                stiffness: penalty_scale * mass[node] * lambda_i,
            });
        }
        let top = mesh.mesh.coords[first][1];
        NoseSurface {
            center_x,
            top,
            radius,
            nodes,
        }
    }

    /// Node `n`'s penetration `g = R - |d|` (m) at displacement `u` (m) with the impactor
    /// moved down by `delta` (m), with `d` (node minus nose centre, m) and `|d|`. Written as
    /// `g = (2 e R - e^2 - d_x^2) / (R + |d|)`, `e = (y - h) + u_y + delta` the node's depth below
    /// the nose's lowest point, so that no difference of two numbers near `R` is taken: the
    /// round-off is that of `e` and `d_x`, not of `R`.
    #[inline]
    pub fn gap(&self, n: &SurfaceNode, u: [f64; 2], delta: f64) -> (f64, [f64; 2], f64) {
        let r = self.radius;
        let dx = (n.x - self.center_x) + u[0];
        let e = (n.y - self.top) + u[1] + delta;
        let dy = e - r;
        let distance = (dx * dx + dy * dy).sqrt();
        let g = (2.0 * e * r - e * e - dx * dx) / (r + distance);
        (g, [dx, dy], distance)
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
        out.on_node.clear();
        out.total = 0.0;
        out.energy = 0.0;
        out.in_contact = 0;
        out.half_width = 0.0;
        for n in &self.nodes {
            let (g, [dx, dy], distance) = self.gap(n, [u[2 * n.node], u[2 * n.node + 1]], delta);
            // A node at or above the centre's level has crossed the nose (the run stops on it,
            // `deepest`): its radial normal would pull it up, so it takes nothing.
            if g <= 0.0 || distance == 0.0 || dy >= 0.0 {
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

/// How deep the plate's top surface is in the nose at one instant.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Depth {
    /// The largest penetration `g` of a candidate, m (0 when none penetrates).
    pub deepest: f64,
    /// The first candidate (its index in [`NoseSurface::nodes`]) at or above the nose's
    /// centre (`e >= R`), with its depth `e` below the nose's lowest point, m: the plate's
    /// surface has crossed the nose (the cylinder's contact no longer holds it).
    pub crossed: Option<(usize, f64)>,
}

impl NoseSurface {
    /// The penetrations at displacement `u` (m) with the impactor moved down by `delta` (m).
    pub fn depth(&self, u: &[f64], delta: f64) -> Depth {
        let mut depth = Depth::default();
        for (i, n) in self.nodes.iter().enumerate() {
            let (g, [_, dy], _) = self.gap(n, [u[2 * n.node], u[2 * n.node + 1]], delta);
            depth.deepest = depth.deepest.max(g);
            if dy >= 0.0 && depth.crossed.is_none() {
                depth.crossed = Some((i, dy + self.radius));
            }
        }
        depth
    }
}

/// Reused buffers of [`NoseSurface::kinematic`] (no allocation after the first step).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct KinematicScratch {
    /// Predicted penetration, m.
    g: Vec<f64>,
    /// Unit outward normal at the predicted position.
    normal: Vec<[f64; 2]>,
    /// `n . M^-1 n`, 1/kg (0 for a node that cannot move along n).
    mobility: Vec<f64>,
    active: Vec<bool>,
}

/// The most active-set passes of the kinematic solve (each pass changes the set or ends it;
/// the set is monotone in the recoil sum, so a handful suffice; the bound only guards).
const MAX_ACTIVE_SET_PASSES: usize = 64;

impl NoseSurface {
    /// Kinematic enforcement (predictor-corrector, as Taylor and Flanagan's PRONTO 2D and
    /// Abaqus/Explicit's kinematic contact pairs): the forces `lambda_i n_i` at `t_n` that put
    /// back on the nose's surface every node the contact-free step would push into it, the
    /// impactor's recoil included. With `g_i` the predicted penetration at `t_{n+1}`, `n_i`
    /// the outward normal there, `w_i = n_i . M_i^-1 n_i` and `a_i = n_i,y`, the linearised
    /// conditions `g_i = c [w_i lambda_i + r a_i sum_j a_j lambda_j]` (`c = dt h`: a force at
    /// `t_n` moves a node by `c f / m` at `t_{n+1}`; `r = s / m_impactor`) on the active set,
    /// `lambda_i = 0` off it, `lambda >= 0`: the matrix is diagonal plus rank one, so with
    /// `S = sum a_j lambda_j` every `lambda_i = (g_i / c - r a_i S) / w_i` and `S` solves one
    /// scalar equation (Sherman-Morrison); a node is active when its `lambda_i > 0`.
    ///
    /// `predicted[i]`: candidate `i`'s displacement at `t_{n+1}` without contact, m;
    /// `inverse_mass[i]`: its `(1/m_x, 1/m_y)` (0 on a fixed dof), 1/kg; `delta`: the
    /// impactor's predicted displacement, m.
    #[allow(clippy::too_many_arguments)]
    pub fn kinematic(
        &self,
        predicted: &[[f64; 2]],
        inverse_mass: &[[f64; 2]],
        delta: f64,
        recoil: f64,
        c: f64,
        scratch: &mut KinematicScratch,
        out: &mut NoseForces,
    ) {
        self.predict(predicted, inverse_mass, delta, scratch);
        let KinematicScratch {
            g,
            normal,
            mobility,
            active,
        } = scratch;
        let mut sum = 0.0;
        for _ in 0..MAX_ACTIVE_SET_PASSES {
            let (mut num, mut den) = (0.0, 1.0);
            for i in 0..g.len() {
                if active[i] {
                    let a = normal[i][1];
                    num += a * g[i] / (c * mobility[i]);
                    den += recoil * a * a / mobility[i];
                }
            }
            sum = num / den;
            let mut changed = false;
            for i in 0..g.len() {
                let now = mobility[i] > 0.0 && g[i] / c - recoil * normal[i][1] * sum > 0.0;
                changed |= now != active[i];
                active[i] = now;
            }
            if !changed {
                break;
            }
        }
        out.on_node.clear();
        (out.total, out.energy, out.in_contact, out.half_width) = (0.0, 0.0, 0, 0.0);
        for (i, node) in self.nodes.iter().enumerate() {
            if !active[i] {
                out.on_node.push([0.0, 0.0]);
                continue;
            }
            let lambda = (g[i] / c - recoil * normal[i][1] * sum) / mobility[i];
            let f = [lambda * normal[i][0], lambda * normal[i][1]];
            out.on_node.push(f);
            out.total -= f[1];
            out.in_contact += 1;
            let dx = (node.x - self.center_x) + predicted[i][0];
            out.half_width = out.half_width.max(dx.abs());
        }
    }

    /// The predicted penetrations, normals and mobilities; the nodes that penetrate start
    /// active.
    fn predict(
        &self,
        predicted: &[[f64; 2]],
        inverse_mass: &[[f64; 2]],
        delta: f64,
        scratch: &mut KinematicScratch,
    ) {
        scratch.g.clear();
        scratch.normal.clear();
        scratch.mobility.clear();
        scratch.active.clear();
        for (i, n) in self.nodes.iter().enumerate() {
            let (g, [dx, dy], distance) = self.gap(n, predicted[i], delta);
            let normal = if distance > 0.0 {
                [dx / distance, dy / distance]
            } else {
                [0.0, -1.0]
            };
            let [im_x, im_y] = inverse_mass[i];
            // A node at or above the centre's level (a crossing, `deepest`) is not held: its
            // normal would pull it up.
            let mobility = if normal[1] < 0.0 {
                im_x * normal[0] * normal[0] + im_y * normal[1] * normal[1]
            } else {
                0.0
            };
            scratch.g.push(g);
            scratch.normal.push(normal);
            scratch.mobility.push(mobility);
            scratch.active.push(g > 0.0 && mobility > 0.0);
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
            top: 0.0,
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
    fn the_depth_is_the_deepest_penetration_and_a_node_past_the_centre_has_crossed() {
        // delta = 0.3: node 0 is 0.3 deep, node 1 0.07805 (above): the deepest is node 0's.
        // Bounds 1e-15: the round-off of gaps of order 1 (a wrong node, or the radial gap
        // taken for the depth below the lowest point, misses by 0.2 or more).
        let d = nose().depth(&[0.0; 4], 0.3);
        assert!((d.deepest - 0.3).abs() < 1e-15, "{d:?}");
        assert_eq!(d.crossed, None);
        // Nobody touches: the deepest is 0, not a negative gap.
        assert_eq!(nose().depth(&[0.0, -0.5, 0.0, -0.5], 0.1).deepest, 0.0);
        // delta = 1.2: node 0 is 1.2 below the nose's lowest point, above its centre
        // (R = 1): crossed, with its depth; node 1 (e = 1.2 too) is not the first.
        let d = nose().depth(&[0.0; 4], 1.2);
        let (node, e) = d.crossed.expect("crossed");
        assert!(node == 0 && (e - 1.2).abs() < 1e-15, "{d:?}");
        // A node past the centre takes no force: its radial normal would pull it up.
        let mut out = NoseForces::default();
        nose().evaluate(&[0.0; 4], 1.2, &mut out);
        assert!(out.on_node.iter().all(|f| f[1] <= 0.0), "{:?}", out.on_node);
        assert!(out.total >= 0.0);
    }

    #[test]
    fn the_spring_eigenvalue_is_the_largest_stiffness_over_mass() {
        assert_eq!(nose().largest_spring_eigenvalue(&[2.0, 2.0]), 10.0);
    }

    #[test]
    fn the_kinematic_forces_put_the_predicted_nodes_on_the_surface() {
        // Node 0 predicted 0.1 into the nose (straight below its axis), node 1 outside; a
        // 1 kg node, c = 0.01 s^2, a light impactor (recoil r = 0.5 /kg): lambda solves
        // g = c (lambda / m + r a^2 lambda) with a = -1: lambda = 0.1 / (0.01 * 1.5).
        let mut out = NoseForces::default();
        let mut scratch = KinematicScratch::default();
        let predicted = [[0.0, -0.0], [0.0, 0.0]];
        let im = [[1.0, 1.0], [1.0, 1.0]];
        nose().kinematic(&predicted, &im, 0.1, 0.5, 0.01, &mut scratch, &mut out);
        assert_eq!(out.in_contact, 1);
        let lambda = 0.1 / (0.01 * 1.5);
        assert!(
            (out.on_node[0][1] + lambda).abs() < 1e-9 * lambda,
            "{:?}",
            out.on_node
        );
        assert_eq!(out.on_node[1], [0.0, 0.0]);
        // The node moves down by c lambda / m, the nose up by c r lambda: the gap closes.
        let closed = 0.01 * lambda + 0.01 * 0.5 * lambda;
        assert!((closed - 0.1).abs() < 1e-12);
        // A node that cannot move along its normal (u_y fixed under the axis) takes nothing.
        let fixed = [[1.0, 0.0], [1.0, 1.0]];
        nose().kinematic(&predicted, &fixed, 0.1, 0.5, 0.01, &mut scratch, &mut out);
        assert_eq!(out.in_contact, 0);
        assert_eq!(out.total, 0.0);
    }
}
