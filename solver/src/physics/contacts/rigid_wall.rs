//! The rigid, frictionless planar wall `y = 0` (`load: {wall}`, `ALGORITHM.md` section 5c),
//! enforced kinematically as explicit codes do (LS-DYNA's `*RIGIDWALL_PLANAR`, Abaqus/Explicit's
//! kinematic contact): at step 2 of `t_n`, every node whose contact-free prediction
//! `y_{n+1} = Y + u_n + dt v_free` would cross the wall gets the upward force
//! `R_n = m (v_wall - v_free) / h` that makes `v_{n+1/2} = v_wall = -(Y + u_n) / dt`, so it
//! lands on the wall at `t_{n+1}` (and, once there, stays with zero normal velocity); a node
//! whose prediction stays above the wall gets no force (unilateral: it leaves). Only `u_y` is
//! touched (frictionless). Any node may reach the wall. With `hold_face` the nodes of the impact
//! face (`Y = 0`) get that force at every step whatever their prediction, so they never leave
//! (the boundary `u_y = 0` of DynELA's and Abaqus' Taylor decks).
//!
//! Coulomb friction (`friction` = mu > 0; 0, the default, touches nothing): a held node's
//! tangential force is the one that stops its tangential motion in this step,
//! `T_stick = -m v_x,free / h`, limited to `mu max(R_i, 0)` in size (stick below the limit, slip
//! at it). Impulses, not rates: a landing node's tangential impulse is at most mu times the
//! normal impulse that stops it. Its work joins `W_n` (the friction's dissipation is in the
//! wall's).
//!
//! The wall takes kinetic energy out (a perfectly inelastic impact of each node that lands): its
//! impulse `h R_n` at step `n` changes the node's velocity from `v_{n-1/2}` to `v_{n+1/2}`, and
//! so its kinetic energy by `W_n = h R_n (v_{n-1/2} + v_{n+1/2}) / 2` (exactly: the half-step
//! kinetic energies differ by the impulse times the mean of the velocities before and after).
//! The wall's dissipation `D = -s sum W` (J, LS-DYNA's "rigidwall energy") is the kinetic energy
//! it removed; a node resting on the wall (`v = 0` before and after) costs nothing, as a rigid
//! wall that does not move does no work. At `t_n` it holds the `W_k` of the steps before and
//! the share of `W_n` in section 7's kinetic energy at `t_n` ([`ImpulseLedger`]: none at
//! `t_0`). Forces N and energies J of
//! the modelled part times the symmetry factor `s` (whole ring in the axisymmetric geometry,
//! whole `plate.width` in plane strain).
//!
//! The wall's force splits in two: `R_i = m (v_wall - v_{n-1/2}) / h + f_i`. The first term
//! stops the momentum the node brings (a landing node's `m v / h`: the one-step impulse of a
//! kinematic stop, which grows as `1 / dt`); the second is the body's own force on the node
//! (`f_int - f_ext`), which the wall bears. Their sum over the held nodes, the bearing force
//! `B_n = s sum f_i`, is the pressure of the body on the wall; it converges as the step falls,
//! and the wall's `peak_force_N` is its largest value.

use crate::mesh::PlateMesh;
use crate::physics::contacts::impulse_ledger::ImpulseLedger;

/// Height (m) below which a node counts as touching the wall, over the body's thickness: a
/// landed node sits at `Y + u_y = 0` up to the round-off of that sum (~1e-16 of the
/// thickness), far below this.
const TOUCH_FRACTION: f64 = 1e-9;

/// Growth of the side's radius over the initial one (-) from which a section of the bar counts
/// as deformed ([`RigidWall::undeformed_length`]): 0.5 %, 0.02 mm on a 7.6 mm bar (what an
/// outline or a micrometer resolves), 20x the radial strain of the elastic ringing a copper
/// bar keeps (`nu sigma_y / E`, about 2.5e-4).
pub const DEFORMED_GROWTH: f64 = 0.005;

/// The wall and its forces at `t_n`.
#[derive(Debug, Clone)]
pub struct RigidWall {
    /// Reference position of each node, m.
    reference: Vec<[f64; 2]>,
    /// The half model's symmetry line (the axis in the axisymmetric geometry), m.
    axis_x: f64,
    /// A node lower than this touches the wall, m.
    touch: f64,
    /// Symmetry factor `s`.
    s: f64,
    /// `R_n` on each node's `u_y`, N (modelled part), `>= 0`.
    force: Vec<f64>,
    /// The works `W_k` of the wall's impulses, whole body.
    work: ImpulseLedger,
    /// Whether each node has touched the wall (the foot).
    touched: Vec<bool>,
    /// The bottom and top axis nodes (the bar's length on the axis is their distance).
    axis_nodes: [usize; 2],
    /// Whether the impact face's nodes are held on the wall (never leave it).
    hold_face: bool,
    /// Coulomb's coefficient `mu` (-), 0 without friction.
    friction: f64,
    /// The tangential force on each node's `u_x`, N (modelled part); 0 without friction.
    tangential: Vec<f64>,
    /// The bearing force `B_n` of step `n`, whole body, N.
    bearing: f64,
    /// The largest `B_n` so far, N.
    max_bearing: f64,
    /// The largest foot radius so far, m.
    max_foot: f64,
    /// The side's nodes (the reference's outer surface, farthest from the axis), bottom to top.
    side: Vec<usize>,
    /// The side's reference distance from the axis (the bar's initial radius), m.
    radius0: f64,
}

/// What the wall reports at `t_n` (the history's wall columns, section 5c), SI units; all 0
/// before the first step.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct WallReading {
    /// The largest current distance from the axis of a node that has touched the wall, m.
    pub foot_radius: f64,
    /// The distance between the bottom and the top axis nodes (the bar's length), m.
    pub bar_length: f64,
    /// The largest current distance from the axis of a node touching the wall now, m.
    pub contact_radius: f64,
    /// The bearing force `B_n`: the body's own force on the wall through the nodes it holds,
    /// N (whole body).
    pub bearing_force: f64,
    /// The length of the bar's rear part whose side stays within [`DEFORMED_GROWTH`] of its
    /// initial radius ([`RigidWall::undeformed_length`], Taylor's `X`), m.
    pub undeformed_length: f64,
}

impl WallReading {
    /// The history's wall columns, in this order.
    pub const COLUMNS: [&'static str; 5] = [
        "foot_radius_m",
        "bar_length_m",
        "contact_radius_m",
        "bearing_force_N",
        "undeformed_length_m",
    ];

    /// The values of [`WallReading::COLUMNS`].
    pub fn values(&self) -> [f64; 5] {
        [
            self.foot_radius,
            self.bar_length,
            self.contact_radius,
            self.bearing_force,
            self.undeformed_length,
        ]
    }
}

/// What the wall reports at the end of a run (SI units).
#[derive(Debug, Clone, PartialEq)]
pub struct WallTotals {
    /// When the body left the wall for good, s (`None`: still on it at the end).
    pub release_time: Option<f64>,
    /// The bar's length on the axis at the end ([`WallReading::bar_length`]), m.
    pub length: f64,
    /// [`WallReading::foot_radius`] at the end, m.
    pub foot_radius: f64,
    /// [`WallReading::undeformed_length`] at the end, m.
    pub undeformed_length: f64,
    /// The side's outline at the end ([`RigidWall::outline`]): `[height, radius]` per side
    /// node, bottom to top, m.
    pub outline: Vec<[f64; 2]>,
    /// The largest [`WallReading::foot_radius`] of the run, m.
    pub max_foot_radius: f64,
    /// The largest [`WallReading::bearing_force`] of the run, N.
    pub peak_bearing_force: f64,
    /// The body's mean velocity away from the wall at the end (`v_{n+1/2}`, positive away),
    /// m/s, once it has left the wall for good (`None` while on it).
    pub rebound_velocity: Option<f64>,
    /// The kinetic energy the wall took out, J.
    pub dissipated: f64,
    /// The largest equivalent plastic strain over the points at the end (plastic only).
    pub max_plastic_strain: Option<f64>,
}

impl RigidWall {
    /// The wall under `mesh` (`thickness` m); `hold_face` keeps the face's nodes on it;
    /// `friction` is Coulomb's `mu` (-).
    pub fn new(mesh: &PlateMesh, thickness: f64, (hold_face, friction): (bool, f64)) -> RigidWall {
        let n = mesh.mesh.n_nodes();
        let coords = &mesh.mesh.coords;
        let outer = coords.iter().map(|c| c[0]).fold(f64::INFINITY, f64::min);
        let mut side: Vec<usize> = (0..n).filter(|&k| coords[k][0] == outer).collect();
        side.sort_by(|&a, &b| coords[a][1].total_cmp(&coords[b][1]));
        RigidWall {
            reference: mesh.mesh.coords.clone(),
            axis_x: mesh.mid_span_x(),
            touch: TOUCH_FRACTION * thickness,
            s: mesh.symmetry_factor,
            force: vec![0.0; n],
            work: ImpulseLedger::default(),
            touched: vec![false; n],
            axis_nodes: [mesh.bottom, mesh.top],
            hold_face,
            friction,
            tangential: vec![0.0; n],
            bearing: 0.0,
            max_bearing: 0.0,
            max_foot: 0.0,
            side,
            radius0: mesh.mid_span_x() - outer,
        }
    }

    /// The initial velocity `-velocity` (m/s, toward the wall) on every free `u_y`.
    pub fn launch(&self, velocity: f64, inverse_mass: &[f64], v: &mut [f64]) {
        for node in 0..self.reference.len() {
            if inverse_mass[2 * node + 1] != 0.0 {
                v[2 * node + 1] = -velocity;
            }
        }
    }

    /// The kinetic energy of `v` (m/s) on the nodal masses `mass` (kg), whole body, J.
    pub fn kinetic_energy(&self, mass: &[f64], v: &[f64]) -> f64 {
        let twice: f64 = (0..mass.len())
            .map(|n| mass[n] * (v[2 * n] * v[2 * n] + v[2 * n + 1] * v[2 * n + 1]))
            .sum();
        0.5 * self.s * twice
    }

    /// Step 2 at `t_n` (`dt` s; `h` the velocity step, s; `u`, `v`, `f_int` the body's `u_n`,
    /// `v_{n-1/2}` and `f_int - f_ext` without the wall; `mass` kg, `inverse_mass` per dof
    /// 1/kg): the wall's forces `R_n` and their work `W_n`. Returns their sum, whole body, N.
    pub fn solve(
        &mut self,
        (dt, h): (f64, f64),
        (u, v, f_int): (&[f64], &[f64], &[f64]),
        mass: &[f64],
        inverse_mass: &[f64],
    ) -> f64 {
        self.work.open();
        let (mut total, mut bearing) = (0.0, 0.0);
        for (node, &[_, y0]) in self.reference.iter().enumerate() {
            let dof = 2 * node + 1;
            self.force[node] = 0.0;
            self.tangential[node] = 0.0;
            if inverse_mass[dof] == 0.0 {
                continue;
            }
            let height = y0 + u[dof];
            let v_free = v[dof] - h * f_int[dof] * inverse_mass[dof];
            if height + dt * v_free < 0.0 || (self.hold_face && y0 == 0.0) {
                let v_wall = -height / dt;
                self.force[node] = mass[node] * (v_wall - v_free) / h;
                total += self.force[node];
                self.work.book(self.s, h * self.force[node], v[dof], v_wall);
                bearing += f_int[dof];
                if self.friction > 0.0 && inverse_mass[dof - 1] != 0.0 {
                    let limit = self.friction * self.force[node].max(0.0);
                    let (t, after) = coulomb(limit, h, (v[dof - 1], f_int[dof - 1]), mass[node]);
                    self.tangential[node] = t;
                    self.work.book(self.s, h * t, v[dof - 1], after);
                }
            }
        }
        self.work.close();
        self.bearing = self.s * bearing;
        self.max_bearing = self.max_bearing.max(self.bearing);
        self.s * total
    }

    /// Step 2: the wall's forces at `t_n` as external forces, subtracted from `f_int - f_ext`.
    pub fn subtract_from(&self, f_int: &mut [f64]) {
        for (node, &r) in self.force.iter().enumerate() {
            f_int[2 * node + 1] -= r;
        }
        if self.friction > 0.0 {
            for (node, &t) in self.tangential.iter().enumerate() {
                f_int[2 * node] -= t;
            }
        }
    }

    /// The kinetic energy the wall has taken out up to `t_n` (its dissipation), whole body, J.
    pub fn energy(&self) -> f64 {
        self.work.dissipated()
    }

    /// The wall's reading at `u` (m): marks the nodes touching the wall (`y <= 1e-9 h`) as
    /// the foot, and measures the foot, the contact and the bar (section 5c).
    pub fn observe(&mut self, u: &[f64]) -> WallReading {
        let (mut contact, mut foot): (f64, f64) = (0.0, 0.0);
        for (node, &[_, y0]) in self.reference.iter().enumerate() {
            let radius = self.radius(node, u);
            if y0 + u[2 * node + 1] <= self.touch {
                self.touched[node] = true;
                contact = contact.max(radius);
            }
            if self.touched[node] {
                foot = foot.max(radius);
            }
        }
        self.max_foot = self.max_foot.max(foot);
        let [bottom, top] = self.axis_nodes;
        WallReading {
            foot_radius: foot,
            bar_length: self.height(top, u) - self.height(bottom, u),
            contact_radius: contact,
            bearing_force: self.bearing,
            undeformed_length: self.undeformed_length(u),
        }
    }

    /// Taylor's undeformed length `X` at `u` (m): from the top of the side down to the highest
    /// point where the side's current distance from the axis reaches `(1 + g) r_0`
    /// ([`DEFORMED_GROWTH`] `g`, `r_0` the initial radius), interpolated linearly between the
    /// side's nodes, along the current heights; the whole side's height when no node reaches
    /// it, 0 when the top one does (section 5c).
    pub fn undeformed_length(&self, u: &[f64]) -> f64 {
        let threshold = (1.0 + DEFORMED_GROWTH) * self.radius0;
        let (Some(&bottom), Some(&top)) = (self.side.first(), self.side.last()) else {
            return 0.0;
        };
        let mut above = top;
        for &node in self.side.iter().rev() {
            let r = self.radius(node, u);
            if r >= threshold {
                if node == top {
                    return 0.0;
                }
                let (z, z_above) = (self.height(node, u), self.height(above, u));
                let t = (r - threshold) / (r - self.radius(above, u));
                return self.height(top, u) - (z + t * (z_above - z));
            }
            above = node;
        }
        self.height(top, u) - self.height(bottom, u)
    }

    /// The side's outline at `u` (m), the side's nodes bottom to top: each one's height above
    /// the bottom axis node (the impact face's centre) and distance from the axis, as a
    /// digitised Taylor profile gives them (section 5c).
    pub fn outline(&self, u: &[f64]) -> Vec<[f64; 2]> {
        let face = self.height(self.axis_nodes[0], u);
        self.side
            .iter()
            .map(|&node| [self.height(node, u) - face, self.radius(node, u)])
            .collect()
    }

    /// The largest foot radius and bearing force so far (m, N).
    pub fn maxima(&self) -> (f64, f64) {
        (self.max_foot, self.max_bearing)
    }

    /// The current distance of `node` from the axis at `u` (the half-width in plane strain), m.
    fn radius(&self, node: usize, u: &[f64]) -> f64 {
        self.axis_x - (self.reference[node][0] + u[2 * node])
    }

    /// The current height of `node` at `u`, m.
    fn height(&self, node: usize, u: &[f64]) -> f64 {
        self.reference[node][1] + u[2 * node + 1]
    }

    /// The body's mean velocity along +y (away from the wall) of `v` (m/s) on `mass` (kg).
    pub fn mean_velocity(mass: &[f64], v: &[f64]) -> f64 {
        let momentum: f64 = (0..mass.len()).map(|n| mass[n] * v[2 * n + 1]).sum();
        momentum / mass.iter().sum::<f64>()
    }
}

/// Coulomb friction on a held node with normal force limit `limit = mu max(R_i, 0)` (N): the
/// tangential force `T = clamp(-m v_free / h, -limit, limit)` (N) that stops the node's
/// tangential motion in the step or slips at the limit (`v`, `f` its `v_x,n-1/2` m/s and
/// `f_int - f_ext` on `u_x` N, `m` kg, `h` s), and the velocity `v_x,n+1/2` it leaves (m/s).
fn coulomb(limit: f64, h: f64, (v, f): (f64, f64), m: f64) -> (f64, f64) {
    let v_free = v - h * f / m;
    let t = (-m * v_free / h).clamp(-limit, limit);
    (t, v_free + h * t / m)
}

#[cfg(test)]
mod tests {
    //! The wall on a column of masses: one node stopped, one landing mid-step; the dissipation
    //! against the kinetic energy it removes (closed form: all of it, `m V^2 / 2`).
    use super::*;

    /// A one-element mesh 1 m x 1 m: nodes 0, 1 on the bottom (y = 0), 2, 3 on top.
    fn wall() -> RigidWall {
        let plate = crate::input::scene::Plate {
            length: 2.0,
            width: 1.0,
            thickness: 1.0,
            ends: crate::input::scene::Ends::Free,
        };
        let settings = crate::input::scene::MeshSettings {
            nx: 1,
            ny: 2,
            element: crate::input::scene::ElementKind::Q4Sri,
            model: crate::input::scene::Model::Half,
            grading: 1.0,
            hourglass: 0.05,
            distortion: 0.0,
        };
        RigidWall::new(&PlateMesh::new(&plate, &settings), 1.0, (false, 0.0))
    }

    /// Free masses (no internal force) at `V` onto the wall, `steps` steps of `dt`; returns the
    /// dissipation and the kinetic energy left (mean velocities), J, whole body.
    fn fall(height_of_top: f64, steps: usize) -> (f64, f64, f64) {
        let mut w = wall();
        let n = w.reference.len();
        let (dt, velocity) = (0.1, 1.0);
        let mass = vec![2.0; n];
        let inverse_mass: Vec<f64> = (0..2 * n).map(|_| 0.5).collect();
        let mut u = vec![0.0; 2 * n];
        // Lift the top row so that it lands in the middle of a step.
        for r in w.reference.iter_mut().filter(|r| r[1] > 0.0) {
            r[1] = height_of_top;
        }
        let mut v = vec![0.0; 2 * n];
        w.launch(velocity, &inverse_mass, &mut v);
        let initial = w.kinetic_energy(&mass, &v);
        let f_int = vec![0.0; 2 * n];
        let mut old = v.clone();
        for step in 0..steps {
            let h = if step == 0 { 0.5 * dt } else { dt };
            let mut f = f_int.clone();
            w.solve((dt, h), (&u, &v, &f), &mass, &inverse_mass);
            w.subtract_from(&mut f);
            old.copy_from_slice(&v);
            for d in 0..2 * n {
                v[d] -= h * f[d] * inverse_mass[d];
            }
            for d in 0..2 * n {
                u[d] += dt * v[d];
            }
        }
        let mean: Vec<f64> = old.iter().zip(&v).map(|(a, b)| 0.5 * (a + b)).collect();
        (initial, w.energy(), w.kinetic_energy(&mass, &mean))
    }

    #[test]
    fn the_wall_takes_all_the_kinetic_energy_of_free_masses() {
        // The bottom row stops at t_0; the top row lands after 0.35 s (between steps 3 and 4).
        let (initial, dissipated, left) = fall(0.35, 12);
        // Round-off bounds (energies of order 10 J here): every node landed, so the kinetic
        // energy left is that of velocities cancelled to a rounding, and the dissipation is
        // the initial energy to a few roundings; a wall that let a node through, or stopped
        // it twice, misses by a node's 1 J.
        assert!(left.abs() < 1e-15, "left {left}");
        assert!(
            (dissipated - initial).abs() < 1e-14 * initial,
            "{dissipated} vs {initial}"
        );
        // Mid-flight the balance closes too (the top row not yet landed).
        let (initial, dissipated, left) = fall(0.35, 3);
        assert!((dissipated + left - initial).abs() < 1e-14 * initial);
        // And at the step of the top row's landing (step 3: from -1 to -0.5 m/s), read with
        // the mean velocity: booking half of that step's work instead misses by
        // m (0.5 m/s)^2 / 8 per node (6.25e-2 J here).
        let (initial, dissipated, left) = fall(0.35, 4);
        assert!(
            (dissipated + left - initial).abs() < 1e-14 * initial,
            "{dissipated} + {left} against {initial}"
        );
    }

    #[test]
    fn a_node_above_the_wall_with_no_push_gets_no_force() {
        let mut w = wall();
        let n = w.reference.len();
        let (mass, inverse_mass) = (vec![1.0; n], vec![1.0; 2 * n]);
        let (u, f) = (vec![0.0; 2 * n], vec![0.0; 2 * n]);
        // Moving up from the wall: unilateral, no pull.
        let v: Vec<f64> = (0..2 * n)
            .map(|d| if d % 2 == 1 { 1.0 } else { 0.0 })
            .collect();
        assert_eq!(w.solve((0.1, 0.1), (&u, &v, &f), &mass, &inverse_mass), 0.0);
    }

    #[test]
    fn a_held_face_is_pulled_back_and_only_the_face() {
        // The same upward motion with hold_face: the face's nodes (Y = 0) are held (the wall
        // pulls each back by m v / h), the rows above still leave freely.
        let mut w = wall();
        w.hold_face = true;
        let n = w.reference.len();
        let (mass, inverse_mass) = (vec![1.0; n], vec![1.0; 2 * n]);
        let (u, mut f) = (vec![0.0; 2 * n], vec![0.0; 2 * n]);
        let v: Vec<f64> = (0..2 * n)
            .map(|d| if d % 2 == 1 { 1.0 } else { 0.0 })
            .collect();
        let face = w.reference.iter().filter(|r| r[1] == 0.0).count();
        let total = w.solve((0.1, 0.1), (&u, &v, &f), &mass, &inverse_mass);
        assert_eq!(total, -(face as f64) * 1.0 / 0.1 * w.s);
        w.subtract_from(&mut f);
        for (node, r) in w.reference.iter().enumerate() {
            let held = if r[1] == 0.0 { 1.0 / 0.1 } else { 0.0 };
            assert_eq!(f[2 * node + 1], held, "node {node}");
        }
    }

    #[test]
    fn taylor_s_undeformed_length_is_read_from_the_top_of_the_side() {
        // The one-element bar: side nodes (x = 0, radius 1 m) at heights 0, 0.5 and 1 m.
        let w = wall();
        let n = w.reference.len();
        let side_at = |u: &mut Vec<f64>, y: f64, grow: f64| {
            let k = (0..n)
                .find(|&k| w.reference[k] == [0.0, y])
                .expect("a side node");
            u[2 * k] = -grow;
        };
        // A rigid drop of 0.1 m: nothing grew, the whole side (1 m) is undeformed.
        let mut u: Vec<f64> = (0..2 * n).map(|d| -0.1 * (d % 2) as f64).collect();
        assert_eq!(w.undeformed_length(&u), 1.0);
        // The foot grown 2 %: 1.005 is reached 3/4 of the way up to the middle node (0.375 m).
        side_at(&mut u, 0.0, 0.02);
        // Bound 1e-13 m: `r - 1.005 r_0` cancels two digits (1.02 - 1.005), so the crossing
        // carries some 1e-14 of relative round-off (measured 2.8e-15 m here); a crossing taken
        // at the node instead of interpolated misses by 0.275 m.
        let close = |x: f64, want: f64| (x - want).abs() < 1e-13;
        assert!(
            close(w.undeformed_length(&u), 0.625),
            "{}",
            w.undeformed_length(&u)
        );
        // A bulge at the middle (1 %) above the foot: the highest crossing counts, halfway
        // between the middle and the top (0.25 m); scanning from the foot up would stop at 0.625.
        side_at(&mut u, 0.5, 0.01);
        assert!(close(w.undeformed_length(&u), 0.25));
        // 0.4 % is within the growth that counts as undeformed: the crossing lies between the
        // foot (2 %) and the middle (0.4 %), 15/16 of the way up (0.53125 m from the top).
        side_at(&mut u, 0.5, 0.004);
        assert!(close(w.undeformed_length(&u), 0.53125));
        // The top grown too: no undeformed part.
        side_at(&mut u, 1.0, 0.01);
        assert_eq!(w.undeformed_length(&u), 0.0);
    }

    #[test]
    fn a_pressed_block_slides_to_rest_at_coulomb_s_deceleration() {
        // Closed form: a mass m pressed on the wall by F with tangential speed v0 decelerates
        // at mu F / m and stops at t_s = m v0 / (mu F), having lost its kinetic energy m v0^2 / 2
        // to the wall. Masses 2 kg, F = 4 N, mu = 0.25: 0.5 m/s^2, v0 = 1 m/s stops at t = 2 s
        // (20 steps of 0.1 s); the rows above the wall are lifted out of reach.
        let mut w = wall();
        w.friction = 0.25;
        let n = w.reference.len();
        for r in w.reference.iter_mut().filter(|r| r[1] > 0.0) {
            r[1] = 1.0e3;
        }
        let (m, push, v0, h) = (2.0, 4.0, 1.0, 0.1);
        let face: Vec<usize> = (0..n).filter(|&k| w.reference[k][1] == 0.0).collect();
        let (mass, inverse_mass) = (vec![m; n], vec![1.0 / m; 2 * n]);
        let (u, mut v) = (vec![0.0; 2 * n], vec![0.0; 2 * n]);
        for &k in &face {
            v[2 * k] = v0;
        }
        let mut speeds = Vec::new();
        for _ in 0..30 {
            let mut f = vec![0.0; 2 * n];
            for &k in &face {
                f[2 * k + 1] = push;
            }
            w.solve((h, h), (&u, &v, &f), &mass, &inverse_mass);
            w.subtract_from(&mut f);
            for d in 0..2 * n {
                v[d] -= h * f[d] * inverse_mass[d];
            }
            speeds.push(v[2 * face[0]]);
        }
        for (step, &s) in speeds.iter().enumerate() {
            let closed = (v0 - 0.25 * push / m * h * (step + 1) as f64).max(0.0);
            assert!(
                (s - closed).abs() < 1e-14,
                "step {step}: {s} against {closed}"
            );
        }
        // The wall took the tangential kinetic energy, s m v0^2 / 2 per face node (the normal
        // direction is at rest: no work).
        let lost = w.s * face.len() as f64 * 0.5 * m * v0 * v0;
        w.solve((h, h), (&u, &v, &vec![0.0; 2 * n]), &mass, &inverse_mass);
        assert!(
            (w.energy() - lost).abs() < 1e-12 * lost,
            "{} against {lost}",
            w.energy()
        );
        // Frictionless, the same block keeps its speed.
        let mut frictionless = wall();
        let f = vec![0.0; 2 * n];
        let mut v = vec![0.0; 2 * n];
        v[2 * face[0]] = v0;
        frictionless.solve((h, h), (&u, &v, &f), &mass, &inverse_mass);
        assert!(frictionless.tangential.iter().all(|&t| t == 0.0));
    }
}
