//! The internal forces of the plate model (eq. 13 assembled from the element kernels),
//! compiled once, in this crate, for every formulation and material.
//!
//! Rust compiles a generic function in each crate that uses it, so the batched kernels were
//! compiled anew into every binary (the solver's, the benchmarks', the Python module's), and
//! LLVM's vectoriser did not always make the same code of them: measured 2026-11-25, the same
//! q4-sri all-yielding kernel ran 30.6 ns per element-step in one binary and 34.5 ns in
//! another, q4-full 65.8 and 28.6 ns (same bits). Here each (formulation, material) pair has
//! one non-generic function, and the generic [`PlateModel::internal_forces`] finds its pair by
//! type (a comparison of type ids that the compiler resolves) and calls it: every binary runs
//! the code compiled here, so the benchmarks time what `impact` runs. A pair not listed stops
//! with an internal error naming it: a fallback to the generic body compiled that body again
//! in every crate that computes forces, for every pair it uses, though it never ran
//! (measured 2026-11-30: 9 % of the verification crate's code before optimisation).

use std::any::{Any, TypeId};

use crate::kernels::assembly::{each_element, ScatterChunk};
use crate::kernels::batch;
use crate::lanes::simd::{dispatch, KernelPath};
use crate::physics::elements::axisymmetric::Axisymmetric;
use crate::physics::elements::element::{
    gather, response, ElementEnergy, Formulation, FullQ4, OnePointQ4, SelectiveQ4,
};
use crate::physics::elements::finite_element::UpdatedLagrangian;
use crate::physics::materials::finite_material::Finite;
use crate::physics::materials::material::{ConstitutiveModel, Elastic, VonMises};
use crate::physics::materials::rate_plasticity::ViscoPlastic;
use crate::time_loop::plate_model::PlateModel;

impl<F: Formulation, M: ConstitutiveModel> PlateModel<F, M> {
    /// Internal forces at `u` into `f` (overwritten), updating the material states.
    ///
    /// The crate's own unit tests (`cfg(test)`) run the generic body directly: the lookup names
    /// every pair's function, so one call compiled all 36 pairs into the unit tests' binary
    /// once more (measured 2026-11-30: that build took 209 s of the gate's compile, 58 s
    /// without). The function of each pair is that same body; the integration tests, which
    /// link this crate as `impact` does, run it and check that every model the factory builds
    /// has one (`AnyModel::forces_compiled_here`, in `tests/batched_kernels.rs`).
    pub fn internal_forces(&mut self, u: &[f64], f: &mut [f64]) -> ElementEnergy {
        #[cfg(not(test))]
        let energy = compiled_here(self, u, f).unwrap_or_else(not_compiled_here::<F, M>);
        #[cfg(test)]
        let energy = self.forces_here(u, f);
        energy
    }

    /// The generic body of [`PlateModel::internal_forces`]: compiled into each pair's function
    /// below, and where this crate's unit tests call it.
    #[inline(always)]
    fn forces_here(&mut self, u: &[f64], f: &mut [f64]) -> ElementEnergy {
        let PlateModel {
            formulation,
            material,
            states,
            linear,
            screen,
            assembly,
            kernel_path,
            ..
        } = self;
        let (formulation, material, path) = (&*formulation, &*material, *kernel_path);
        let screen = screen.as_ref();
        let nodes = |e: usize| formulation.nodes(e);
        match (linear, path) {
            (Some(k), KernelPath::Scalar) => assembly.assemble(
                states,
                F::POINTS,
                |elements, forces, states, scatter| {
                    let chunk = (elements, forces, states, scatter);
                    each_element(chunk, F::POINTS, nodes, |e, _| k.element(formulation, e, u))
                },
                f,
            ),
            (Some(k), KernelPath::Batched(isa)) => assembly.assemble(
                states,
                F::POINTS,
                |elements, forces, _, scatter| {
                    let chunk = batch::LinearChunk {
                        kernel: k,
                        formulation,
                        u,
                        elements,
                        forces,
                        scatter,
                    };
                    dispatch(isa, chunk)
                },
                f,
            ),
            (None, KernelPath::Scalar) => assembly.assemble(
                states,
                F::POINTS,
                |elements, forces, states, scatter| {
                    let chunk = (elements, forces, states, scatter);
                    each_element(chunk, F::POINTS, nodes, |e, states| {
                        let ue = gather(formulation.nodes(e), u);
                        screen
                            .and_then(|s| s.element(formulation, material, e, &ue, states))
                            .unwrap_or_else(|| {
                                response(formulation, material, e, &ue, (states, true))
                            })
                    })
                },
                f,
            ),
            (None, KernelPath::Batched(isa)) => assembly.assemble(
                states,
                F::POINTS,
                |elements, forces, states, scatter| {
                    // A chunk that never yielded and stays elastic: its screen alone.
                    if let Some(screen) = screen {
                        let whole = batch::ScreenedChunk {
                            screen,
                            formulation,
                            material,
                            u,
                            elements: elements.clone(),
                            forces: &mut *forces,
                            states: &*states,
                            scatter,
                        };
                        let first = elements.start;
                        if let Some(energy) = screen.try_whole(first, || dispatch(isa, whole)) {
                            return energy;
                        }
                    }
                    let chunk = batch::StressPathChunk {
                        formulation,
                        material,
                        screen,
                        rows: scatter.rows(),
                        u,
                        elements: elements.clone(),
                        forces,
                        states,
                    };
                    // Scattered by a kernel of its own: compiled into the stress path's (as
                    // the stiffness product's is), the paper plastic run took 1.04 s instead
                    // of 0.72 s on one thread (2026-11-25).
                    let energy = dispatch(isa, chunk);
                    let forces = &*forces;
                    dispatch(
                        isa,
                        ScatterChunk {
                            scatter,
                            elements,
                            forces,
                            nodes,
                        },
                    );
                    energy
                },
                f,
            ),
        }
    }
}

/// A model whose pair has no function here. Every pair the factory builds has one
/// (`tests/batched_kernels.rs`), so this is a programming error, never a user's.
#[cfg_attr(test, allow(dead_code))]
#[cold]
#[inline(never)]
fn not_compiled_here<F: Formulation, M: ConstitutiveModel>() -> ElementEnergy {
    panic!(
        "internal error: no internal-forces function is compiled in the solver crate for {}: \
         add the pair to `compiled!` in solver/src/time_loop/internal_forces.rs",
        std::any::type_name::<PlateModel<F, M>>()
    )
}

/// One non-generic function per (formulation, material) pair, and the lookup by type.
macro_rules! compiled {
    ($($name:ident: $f:ty, $m:ty;)*) => {
        $(
            #[cfg_attr(test, allow(dead_code))]
            #[inline(never)]
            fn $name(model: &mut PlateModel<$f, $m>, u: &[f64], f: &mut [f64]) -> ElementEnergy {
                model.forces_here(u, f)
            }
        )*

        /// The internal forces by the function compiled here for `model`'s pair, if any.
        #[cfg_attr(test, allow(dead_code))]
        #[inline(always)]
        fn compiled_here<F: Formulation, M: ConstitutiveModel>(
            model: &mut PlateModel<F, M>,
            u: &[f64],
            f: &mut [f64],
        ) -> Option<ElementEnergy> {
            let model: &mut dyn Any = model;
            $(
                if let Some(model) = model.downcast_mut::<PlateModel<$f, $m>>() {
                    return Some($name(model, u, f));
                }
            )*
            None
        }

        /// Whether `PlateModel<F, M>` has its function compiled here (type ids compared;
        /// nothing is called, so nothing more is compiled where this is used).
        pub(crate) fn is_compiled_here<F: Formulation, M: ConstitutiveModel>() -> bool {
            let pair = TypeId::of::<PlateModel<F, M>>();
            [$(TypeId::of::<PlateModel<$f, $m>>()),*].contains(&pair)
        }
    };
}

compiled! {
    full_elastic: FullQ4, Elastic;
    full_plastic: FullQ4, VonMises;
    selective_elastic: SelectiveQ4, Elastic;
    selective_plastic: SelectiveQ4, VonMises;
    one_point_elastic: OnePointQ4, Elastic;
    one_point_plastic: OnePointQ4, VonMises;
    full_rate: FullQ4, ViscoPlastic;
    selective_rate: SelectiveQ4, ViscoPlastic;
    one_point_rate: OnePointQ4, ViscoPlastic;
    finite_full_elastic: UpdatedLagrangian<FullQ4>, Finite<Elastic>;
    finite_full_plastic: UpdatedLagrangian<FullQ4>, Finite<VonMises>;
    finite_full_rate: UpdatedLagrangian<FullQ4>, Finite<ViscoPlastic>;
    finite_selective_elastic: UpdatedLagrangian<SelectiveQ4>, Finite<Elastic>;
    finite_selective_plastic: UpdatedLagrangian<SelectiveQ4>, Finite<VonMises>;
    finite_selective_rate: UpdatedLagrangian<SelectiveQ4>, Finite<ViscoPlastic>;
    finite_one_point_elastic: UpdatedLagrangian<OnePointQ4>, Finite<Elastic>;
    finite_one_point_plastic: UpdatedLagrangian<OnePointQ4>, Finite<VonMises>;
    finite_one_point_rate: UpdatedLagrangian<OnePointQ4>, Finite<ViscoPlastic>;
    ring_full_elastic: Axisymmetric<FullQ4>, Elastic;
    ring_full_plastic: Axisymmetric<FullQ4>, VonMises;
    ring_full_rate: Axisymmetric<FullQ4>, ViscoPlastic;
    ring_selective_elastic: Axisymmetric<SelectiveQ4>, Elastic;
    ring_selective_plastic: Axisymmetric<SelectiveQ4>, VonMises;
    ring_selective_rate: Axisymmetric<SelectiveQ4>, ViscoPlastic;
    ring_one_point_elastic: Axisymmetric<OnePointQ4>, Elastic;
    ring_one_point_plastic: Axisymmetric<OnePointQ4>, VonMises;
    ring_one_point_rate: Axisymmetric<OnePointQ4>, ViscoPlastic;
    finite_ring_full_elastic: UpdatedLagrangian<Axisymmetric<FullQ4>>, Finite<Elastic>;
    finite_ring_full_plastic: UpdatedLagrangian<Axisymmetric<FullQ4>>, Finite<VonMises>;
    finite_ring_full_rate: UpdatedLagrangian<Axisymmetric<FullQ4>>, Finite<ViscoPlastic>;
    finite_ring_selective_elastic: UpdatedLagrangian<Axisymmetric<SelectiveQ4>>, Finite<Elastic>;
    finite_ring_selective_plastic: UpdatedLagrangian<Axisymmetric<SelectiveQ4>>, Finite<VonMises>;
    finite_ring_selective_rate: UpdatedLagrangian<Axisymmetric<SelectiveQ4>>, Finite<ViscoPlastic>;
    finite_ring_one_point_elastic: UpdatedLagrangian<Axisymmetric<OnePointQ4>>, Finite<Elastic>;
    finite_ring_one_point_plastic: UpdatedLagrangian<Axisymmetric<OnePointQ4>>, Finite<VonMises>;
    finite_ring_one_point_rate: UpdatedLagrangian<Axisymmetric<OnePointQ4>>, Finite<ViscoPlastic>;
}
