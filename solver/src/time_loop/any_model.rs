//! A built model of any element x material behind one object type ([`AnyModel`]), for the
//! callers that only evaluate its internal forces: the kernel benchmarks (`impact-bench
//! throughput`, the criterion bench), the bit tests of the batched kernels, the memory test.
//! Its generic code is compiled once, in this crate, where the time loop compiles the same
//! instances anyway. A caller with its own [`UseModel`] compiles every element x material x
//! kinematics x geometry x instruction set combination again in its own crate (measured
//! 2026-11-29 on 2 cores: rebuilding the batched-kernel bit test and the benchmarks'
//! `throughput.rs` took 51.6 s with their own, 4.6 s through this).

use crate::input::error::Result;
use crate::input::scene::Scene;
use crate::lanes::simd::KernelPath;
use crate::mesh::PlateMesh;
use crate::physics::elements::element::{ElementEnergy, Formulation};
use crate::physics::materials::material::ConstitutiveModel;
use crate::time_loop::internal_forces::is_compiled_here;
use crate::time_loop::model::{build_on, Kernel, UseModel};
use crate::time_loop::plate_model::PlateModel;

/// What a caller may do with a built model without knowing its element and material types.
pub trait AnyModel {
    /// Internal forces `f` (N) of displacements `u` (m), updating the material states; the
    /// elements' energies of the call ([`PlateModel::internal_forces`]).
    fn internal_forces(&mut self, u: &[f64], f: &mut [f64]) -> ElementEnergy;
    /// Tells a rate-dependent material the run's time step (s).
    fn set_time_step(&mut self, dt: f64);
    /// The critical time step from the element eigenvalue bound (eq. 15) at `density`
    /// (kg/m^3), s.
    fn critical_time_step(&self, density: f64) -> f64;
    fn n_elements(&self) -> usize;
    /// Integration points per element.
    fn points_per_element(&self) -> usize;
    /// The material state of point `p` of element `e`, as `{:?}` prints it (each f64 in its
    /// shortest round-trip form: equal strings are equal bits).
    fn state_debug(&self, e: usize, p: usize) -> String;
    /// Heap bytes of the whole model and of its geometry alone ([`PlateModel::heap_bytes`]).
    fn heap_bytes(&self) -> (usize, usize);
    /// Whether its internal forces run the function compiled for its (formulation, material)
    /// pair in this crate (`time_loop::internal_forces`), the code `impact` runs, rather than
    /// a copy compiled in the caller's crate.
    fn forces_compiled_here(&self) -> bool;
}

impl<F: Formulation, M: ConstitutiveModel> AnyModel for PlateModel<F, M> {
    fn internal_forces(&mut self, u: &[f64], f: &mut [f64]) -> ElementEnergy {
        PlateModel::internal_forces(self, u, f)
    }
    fn set_time_step(&mut self, dt: f64) {
        self.material.set_time_step(dt);
    }
    fn critical_time_step(&self, density: f64) -> f64 {
        PlateModel::critical_time_step(self, density)
    }
    fn n_elements(&self) -> usize {
        self.formulation.n_elements()
    }
    fn points_per_element(&self) -> usize {
        F::POINTS
    }
    fn state_debug(&self, e: usize, p: usize) -> String {
        format!("{:?}", self.state(e, p))
    }
    fn heap_bytes(&self) -> (usize, usize) {
        (PlateModel::heap_bytes(self), self.formulation.heap_bytes())
    }
    fn forces_compiled_here(&self) -> bool {
        is_compiled_here::<F, M>()
    }
}

/// Boxes whatever model the factory built.
struct Boxed;

impl UseModel for Boxed {
    type Output = Box<dyn AnyModel>;
    fn use_model<F: Formulation, M: ConstitutiveModel>(
        self,
        model: PlateModel<F, M>,
    ) -> Box<dyn AnyModel> {
        Box::new(model)
    }
}

/// The model of `scene` on `mesh` with `kernel`, its element kernels on `path`
/// ([`build_on`]), behind [`AnyModel`].
pub fn build_any(
    scene: &Scene,
    mesh: &PlateMesh,
    kernel: Kernel,
    path: KernelPath,
) -> Result<Box<dyn AnyModel>> {
    build_on(scene, mesh, kernel, path, Boxed)
}
