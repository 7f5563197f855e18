//! The plate model a run steps: the formulation over the mesh, the material and its states
//! per point, the lumped masses, and the kernels' shortcuts (element stiffness matrices, the
//! elastic screen) and assembly buffers; built once by [`crate::time_loop::model`].

use crate::kernels::assembly::Assembly;
use crate::kernels::elastic_screen::ElasticScreen;
use crate::kernels::stiffness::LinearKernel;
use crate::lanes::heap;
use crate::lanes::simd::{KernelPath, LANES};
use crate::mesh::PlateMesh;
use crate::physics::elements::element::{gather, lumped_masses, Formulation};
use crate::physics::materials::material::{ConstitutiveModel, Elastic, Stress};
use crate::time_loop::stable_step::{self, Spring};

/// The plate model: formulation, material, per-point states, masses.
pub struct PlateModel<F: Formulation, M: ConstitutiveModel> {
    pub formulation: F,
    pub material: M,
    /// The material states, batch-major: `POINTS` batches (one per point) per batch of
    /// [`LANES`] elements (zero-sized for elastic models); [`PlateModel::state`] reads one.
    pub states: Vec<M::Batch>,
    /// Lumped nodal mass, kg.
    pub mass: Vec<f64>,
    /// 1/mass per dof, 0 on constrained dofs.
    pub inverse_mass: Vec<f64>,
    /// Precomputed element stiffness, used instead of the stress path when the material is
    /// linear elastic (see [`PlateModel::with_linear_kernel`]).
    pub linear: Option<LinearKernel>,
    /// For a plastic material: elements that never yielded and stay elastic by `K_e u_e`
    /// (see [`PlateModel::with_elastic_screen`]).
    pub screen: Option<ElasticScreen>,
    /// Chunked (optionally multithreaded) assembly buffers.
    pub assembly: Assembly,
    /// Batched kernels (the default) or the scalar reference.
    pub kernel_path: KernelPath,
}

impl<F: Formulation, M: ConstitutiveModel> PlateModel<F, M> {
    pub fn new(formulation: F, mut material: M, mesh: &PlateMesh, density: f64) -> Self {
        material.set_isa(KernelPath::fastest().isa());
        let n = formulation.n_elements();
        let mass = lumped_masses(&formulation, mesh.mesh.n_nodes(), density);
        let inverse_mass = (0..2 * mass.len())
            .map(|d| {
                if mesh.fixed_dofs[d] {
                    0.0
                } else {
                    1.0 / mass[d / 2]
                }
            })
            .collect();
        // Elastic materials have no states and a cheap kernel.
        let assembly = Assembly::for_mesh(
            formulation.connectivity(),
            mesh.mesh.n_nodes(),
            M::HAS_STATES,
        );
        PlateModel {
            states: vec![M::Batch::default(); n.div_ceil(LANES) * F::POINTS],
            formulation,
            material,
            mass,
            inverse_mass,
            linear: None,
            screen: None,
            assembly,
            kernel_path: KernelPath::fastest(),
        }
    }

    /// Heap bytes the model holds: geometry, states, masses, stiffness matrices, screen and
    /// assembly buffers (not the time loop's nodal vectors).
    pub fn heap_bytes(&self) -> usize {
        self.formulation.heap_bytes()
            + heap::vec_bytes(&self.states)
            + heap::vec_bytes(&self.mass)
            + heap::vec_bytes(&self.inverse_mass)
            + self.linear.as_ref().map_or(0, LinearKernel::heap_bytes)
            + self.screen.as_ref().map_or(0, ElasticScreen::heap_bytes)
            + self.assembly.heap_bytes()
    }

    /// Runs the element kernels on `path` (the scalar reference or a batched instruction set).
    pub fn with_kernel_path(mut self, path: KernelPath) -> Self {
        self.kernel_path = path;
        self.material.set_isa(path.isa());
        self
    }

    /// Switches the internal forces to precomputed element stiffness matrices. Only valid
    /// for a linear elastic material (the caller's guarantee: `M = Elastic`).
    pub fn with_linear_kernel(mut self, elastic: &Elastic) -> Self {
        self.linear = Some(LinearKernel::new(&self.formulation, elastic));
        self
    }

    /// Lets elements that never yielded respond by `K_e u_e` while they certainly stay
    /// elastic (no effect for a material that never yields).
    pub fn with_elastic_screen(mut self) -> Self {
        self.screen = ElasticScreen::new(&self.formulation, &self.material);
        self
    }

    /// The critical time step 2 / omega_max from the element eigenvalue bound (eq. 15), s.
    pub fn critical_time_step(&self, density: f64) -> f64 {
        stable_step::element_bound(&self.formulation, self.material.elastic(), density)
    }

    /// The critical time step from the global estimate of omega_max (power iteration, the
    /// contact `spring` included, times the safety factor), s.
    pub fn global_time_step(&self, spring: Option<Spring>) -> f64 {
        stable_step::global_estimate(
            &self.formulation,
            self.material.elastic(),
            &self.inverse_mass,
            spring,
        )
    }

    /// The material state of integration point `p` of element `e`.
    pub fn state(&self, e: usize, p: usize) -> M::State {
        M::state_of(&self.states[e / LANES * F::POINTS + p], e % LANES)
    }

    /// Stress at integration point `p` of element `e` for displacements `u`.
    pub fn point_stress(&self, e: usize, p: usize, u: &[f64]) -> Stress {
        let ue = gather(self.formulation.nodes(e), u);
        let strain = self.formulation.strains(e, &ue)[p];
        self.material.stress(&strain, &self.state(e, p))
    }

    /// The highest temperature over the points (K); `None` for a material without one.
    pub fn max_temperature(&self) -> Option<f64> {
        let n = self.formulation.n_elements();
        (0..n)
            .flat_map(|e| (0..F::POINTS).map(move |p| (e, p)))
            .filter_map(|(e, p)| self.material.temperature(&self.state(e, p)))
            .reduce(f64::max)
    }

    /// The weighted mean over element `e`'s points of `value` (for field output); `None`
    /// where the material has no such value.
    pub fn element_mean(&self, e: usize, value: impl Fn(&M::State) -> Option<f64>) -> Option<f64> {
        let w = self.formulation.weights(e);
        let total: f64 = w[..F::POINTS].iter().sum();
        let mut mean = 0.0;
        for (p, &wp) in w.iter().enumerate().take(F::POINTS) {
            mean += wp / total * value(&self.state(e, p))?;
        }
        Some(mean)
    }

    /// Element-average stress and equivalent plastic strain (for field output).
    pub fn element_average(&self, e: usize, u: &[f64]) -> (Stress, f64) {
        let w = self.formulation.weights(e);
        let total: f64 = w[..F::POINTS].iter().sum();
        let mut s = [0.0; 4];
        let mut k = 0.0;
        for (p, &wp) in w.iter().enumerate().take(F::POINTS) {
            let sp = self.point_stress(e, p, u);
            for c in 0..4 {
                s[c] += wp / total * sp[c];
            }
            k += wp / total * self.material.equivalent_plastic_strain(&self.state(e, p));
        }
        (s, k)
    }
}
