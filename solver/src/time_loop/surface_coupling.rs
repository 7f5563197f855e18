//! The surface coupling in the time loop (`ALGORITHM.md` section 6, steps 2 and 5 under
//! `contact: surface`): the forces of the rigid nose on the top-surface nodes at `t_n`
//! (kinematic: solved at `t_n` from the contact-free prediction; penalty: from the positions at
//! `t_n`), the impactor moved by central differences under their sum, the stable step (with
//! the penalty springs), the contact energy, and what the recorder reads.

use crate::input::scene::{Enforcement, SurfaceImpactor};
use crate::mesh::PlateMesh;
use crate::physics::contacts::impulse_ledger::ImpulseLedger;
use crate::physics::contacts::nose_contact::{
    KinematicScratch, NoseForces, NoseSurface, SurfaceNode,
};
use crate::physics::elements::element::{element_max_eigenvalue, Formulation};
use crate::physics::impactor::CentralDifferenceImpactor;
use crate::physics::materials::material::ConstitutiveModel;
use crate::time_loop::plate_model::PlateModel;

/// The nose, the impactor and the contact forces at `t_n`.
pub(crate) struct SurfaceImpact {
    pub nose: NoseSurface,
    pub body: CentralDifferenceImpactor,
    /// At `t_n`, for the modelled part.
    pub forces: NoseForces,
    enforcement: Enforcement,
    /// Symmetry factor `s`.
    s: f64,
    /// The kinematic solve's buffers: the candidates' contact-free velocities `v_{n+1/2}`
    /// (m/s) and displacements at `t_{n+1}` (m), their inverse masses (1/kg), its scratch.
    free_velocity: Vec<[f64; 2]>,
    predicted: Vec<[f64; 2]>,
    inverse_mass: Vec<[f64; 2]>,
    scratch: KinematicScratch,
    /// Kinematic enforcement: the works of the contact's impulses on the plate and the
    /// impactor (whole plate).
    work: ImpulseLedger,
    /// The largest penetration of a candidate at any `t_n` so far, m.
    pub max_penetration: f64,
}

impl SurfaceImpact {
    /// The nose over `mesh`; under the penalty enforcement with springs from `model`'s masses
    /// and element eigenvalues.
    pub fn new<F: Formulation, M: ConstitutiveModel>(
        spec: &SurfaceImpactor,
        mesh: &PlateMesh,
        model: &PlateModel<F, M>,
        density: f64,
    ) -> SurfaceImpact {
        let elastic = model.material.elastic();
        let penalty_scale = match spec.contact.enforcement {
            Enforcement::Penalty => spec.contact.penalty_scale,
            Enforcement::Kinematic => 0.0,
        };
        let nose = NoseSurface::new(mesh, spec.nose_radius, penalty_scale, &model.mass, |e| {
            element_max_eigenvalue(&model.formulation, elastic, density, e)
        });
        let k = nose.nodes.len();
        let inverse_mass = nose
            .nodes
            .iter()
            .map(|n| {
                [
                    model.inverse_mass[2 * n.node],
                    model.inverse_mass[2 * n.node + 1],
                ]
            })
            .collect();
        SurfaceImpact {
            body: CentralDifferenceImpactor::new(spec.mass, spec.velocity),
            forces: NoseForces {
                on_node: vec![[0.0; 2]; k],
                ..NoseForces::default()
            },
            enforcement: spec.contact.enforcement,
            s: mesh.symmetry_factor,
            free_velocity: vec![[0.0; 2]; k],
            predicted: vec![[0.0; 2]; k],
            inverse_mass,
            scratch: KinematicScratch::default(),
            work: ImpulseLedger::default(),
            max_penetration: 0.0,
            nose,
        }
    }

    /// The stable step `dt_plate` (s) with the penalty springs: `2 / sqrt((2 / dt_plate)^2 +
    /// max k_i / m_i)` (Weyl: a diagonal spring term raises the largest eigenvalue of
    /// `M^-1 K` by at most its largest entry).
    pub fn stable_step(&self, dt_plate: f64, mass: &[f64]) -> f64 {
        if self.enforcement == Enforcement::Kinematic {
            return dt_plate;
        }
        let omega = 2.0 / dt_plate;
        2.0 / (omega * omega + self.nose.largest_spring_eigenvalue(mass)).sqrt()
    }

    /// Step 2: the nose's forces at `t_n` as external forces, subtracted from `f_int - f_ext`.
    pub fn subtract_from(&self, f_int: &mut [f64]) {
        for (n, f) in self.nose.nodes.iter().zip(&self.forces.on_node) {
            f_int[2 * n.node] -= f[0];
            f_int[2 * n.node + 1] -= f[1];
        }
    }

    /// The force on the impactor at `t_n`, whole plate, N.
    pub fn force(&self) -> f64 {
        self.s * self.forces.total
    }

    /// The contact energy at `t_n`, whole plate, J: the penalty's stored energy, or the kinetic
    /// energy the kinematic impulses took out of the plate and the impactor.
    pub fn energy(&self) -> f64 {
        match self.enforcement {
            Enforcement::Penalty => self.s * self.forces.energy,
            Enforcement::Kinematic => self.work.dissipated(),
        }
    }

    /// Step 2 at `t_n` (`h` the velocity step, s; `u`, `v`, `f_int` the plate's `u_n`,
    /// `v_{n-1/2}` and `f_int - f_ext` without the contact): the kinematic enforcement's forces
    /// at `t_n` from the contact-free prediction, and the works of their impulses (the
    /// penalty's forces at `t_n` came with step 5). Returns `F_n` (whole plate, N).
    pub fn solve(&mut self, dt: f64, h: f64, u: &[f64], v: &[f64], f_int: &[f64]) -> f64 {
        if self.enforcement == Enforcement::Kinematic {
            for (k, n) in self.nose.nodes.iter().enumerate() {
                for d in 0..2 {
                    let dof = 2 * n.node + d;
                    let v_free = v[dof] + h * (-f_int[dof] * self.inverse_mass[k][d]);
                    self.free_velocity[k][d] = v_free;
                    self.predicted[k][d] = u[dof] + dt * v_free;
                }
            }
            self.nose.kinematic(
                &self.predicted,
                &self.inverse_mass,
                self.body.free_displacement(dt),
                self.s / self.body.mass,
                dt * h,
                &mut self.scratch,
                &mut self.forces,
            );
            self.book_impulses(h, v);
        }
        self.force()
    }

    /// The works of step `n`'s contact impulses `h f` on the candidates (their `v_{n-1/2}` in
    /// `v`; after the impulse, their contact-free velocity plus `h f / m`) and `-h F_n` on the
    /// impactor (its velocity positive down).
    fn book_impulses(&mut self, h: f64, v: &[f64]) {
        self.work.open();
        for (k, n) in self.nose.nodes.iter().enumerate() {
            for d in 0..2 {
                let impulse = h * self.forces.on_node[k][d];
                let after = self.free_velocity[k][d] + impulse * self.inverse_mass[k][d];
                self.work.book(self.s, impulse, v[2 * n.node + d], after);
            }
        }
        let before = self.body.half_step_velocity;
        let impulse = -h * self.force();
        self.work
            .book(1.0, impulse, before, before + impulse / self.body.mass);
        self.work.close();
    }

    /// Step 5: the impactor from `t_n` to `t_{n+1}` under `F_n`; under the penalty, the nose's
    /// forces at `u_{n+1}`. Returns the force known at `t_{n+1}` (whole plate, N; the
    /// kinematic enforcement's is found at the next step 2).
    pub fn advance(&mut self, (dt, h): (f64, f64), u: &[f64]) -> f64 {
        self.body.advance((dt, h), self.force());
        if self.enforcement == Enforcement::Penalty {
            self.nose
                .evaluate(u, self.body.displacement, &mut self.forces);
        }
        self.force()
    }

    /// The penetrations at `t_n` (`u` the plate's `u_n`, m): records the deepest, and returns
    /// the candidate that has crossed the nose (at or above its centre's level) with its depth
    /// below the nose's lowest point (m), if one has.
    pub fn observe(&mut self, u: &[f64]) -> Option<(SurfaceNode, f64)> {
        let depth = self.nose.depth(u, self.body.displacement);
        self.max_penetration = self.max_penetration.max(depth.deepest);
        depth.crossed.map(|(i, e)| (self.nose.nodes[i], e))
    }

    /// Indentation `delta_S + u_y(top mid-span)`, impactor displacement (m) and velocity (m/s)
    /// at `t_n`, as the nodal coupling reports them.
    pub fn motion(&self, h: f64, top_uy: f64) -> [f64; 3] {
        let d = self.body.displacement;
        [d + top_uy, d, self.body.velocity(h, self.force())]
    }

    /// The nose's force on every node of the mesh (`n_nodes` of them) at `t_n`, N, for a field
    /// frame.
    pub fn nodal_forces(&self, n_nodes: usize) -> Vec<[f64; 2]> {
        let mut f = vec![[0.0; 2]; n_nodes];
        for (n, force) in self.nose.nodes.iter().zip(&self.forces.on_node) {
            f[n.node] = *force;
        }
        f
    }

    /// Contact half-width (m, from the axis; current positions, or the predicted ones the
    /// kinematic forces hold on the nose) and nodes in contact (whole plate: the half model's
    /// nodes off the axis counted twice) at `t_n`.
    pub fn patch(&self) -> [f64; 2] {
        let on_axis = self
            .nose
            .nodes
            .iter()
            .zip(&self.forces.on_node)
            .filter(|(n, f)| n.x == self.nose.center_x && f[1] != 0.0)
            .count();
        let off_axis = self.forces.in_contact - on_axis;
        [
            self.forces.half_width,
            (on_axis as f64) + self.s * off_axis as f64,
        ]
    }
}
