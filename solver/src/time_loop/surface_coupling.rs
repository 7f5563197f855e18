//! The surface coupling in the time loop (`ALGORITHM.md` section 6, steps 2 and 5 under
//! `contact: surface`): the penalty forces of the rigid nose on the top-surface nodes at `t_n`,
//! the impactor moved by central differences under their sum, the stable step with the
//! penalty springs, and what the recorder reads.

use crate::input::scene::SurfaceImpactor;
use crate::mesh::PlateMesh;
use crate::physics::element::{element_max_eigenvalue, Formulation};
use crate::physics::impactor::CentralDifferenceImpactor;
use crate::physics::material::ConstitutiveModel;
use crate::physics::nose_contact::{NoseForces, NoseSurface};
use crate::time_loop::integrator::PlateModel;

/// The nose, the impactor and the contact forces at `t_n`.
pub(crate) struct SurfaceImpact {
    pub nose: NoseSurface,
    pub body: CentralDifferenceImpactor,
    /// At `t_n`, for the modelled part.
    pub forces: NoseForces,
    /// Symmetry factor `s`.
    s: f64,
}

impl SurfaceImpact {
    /// The nose over `mesh` with penalty springs from `model`'s masses and element eigenvalues.
    pub fn new<F: Formulation, M: ConstitutiveModel>(
        spec: &SurfaceImpactor,
        mesh: &PlateMesh,
        model: &PlateModel<F, M>,
        density: f64,
    ) -> SurfaceImpact {
        let elastic = model.material.elastic();
        let nose = NoseSurface::new(
            mesh,
            spec.nose_radius,
            spec.contact.penalty_scale,
            &model.mass,
            |e| element_max_eigenvalue(&model.formulation, elastic, density, e),
        );
        let forces = NoseForces {
            on_node: Vec::with_capacity(nose.nodes.len()),
            ..NoseForces::default()
        };
        SurfaceImpact {
            nose,
            body: CentralDifferenceImpactor::new(spec.mass, spec.velocity),
            forces,
            s: mesh.symmetry_factor,
        }
    }

    /// The stable step `dt_plate` (s) with the penalty springs: `2 / sqrt((2 / dt_plate)^2 +
    /// max k_i / m_i)` (Weyl: a diagonal spring term raises the largest eigenvalue of
    /// `M^-1 K` by at most its largest entry).
    pub fn stable_step(&self, dt_plate: f64, mass: &[f64]) -> f64 {
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

    /// Penalty energy at `t_n`, whole plate, J.
    pub fn energy(&self) -> f64 {
        self.s * self.forces.energy
    }

    /// Step 5: the impactor from `t_n` to `t_{n+1}` under `F_n`, then the nose's forces at
    /// `u_{n+1}`; returns `F_{n+1}` (whole plate, N).
    pub fn advance(&mut self, dt: f64, u: &[f64]) -> f64 {
        self.body.advance(dt, self.force());
        self.nose
            .evaluate(u, self.body.displacement, &mut self.forces);
        self.force()
    }

    /// Indentation `delta_S + u_y(top mid-span)`, impactor displacement (m) and velocity (m/s)
    /// at `t_n`, as the nodal coupling reports them.
    pub fn motion(&self, dt: f64, top_uy: f64) -> [f64; 3] {
        let d = self.body.displacement;
        [d + top_uy, d, self.body.velocity(dt, self.force())]
    }

    /// Contact half-width (m, current positions, from the axis) and nodes in contact (whole
    /// plate: the half model's nodes off the axis counted twice) at `t_n`.
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
