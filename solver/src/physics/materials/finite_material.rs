//! A material under finite deformation: any small-strain model `M`, run in the unrotated
//! (Green-Naghdi) frame, with each point's kinematic memory kept beside its state
//! ([`crate::physics::kinematics`]). The formulation
//! ([`crate::physics::elements::finite_element::UpdatedLagrangian`]) computes the unrotated strain and
//! rotates the stress; this model holds the memory, passes the strain to `M` and reports the
//! Cauchy stress of a converged state.

use crate::lanes::real::Real;
use crate::lanes::simd::{Isa, Lanes};
use crate::physics::kinematics::{deformation, det, Memory, Rotation};
use crate::physics::materials::material::{ConstitutiveModel, Elastic, Response, Strain, Stress};

/// `M` under finite deformation.
#[derive(Debug, Clone)]
pub struct Finite<M>(pub M);

/// A point's batch: `M`'s states and the kinematic memory, in lanes.
#[derive(Debug, Clone, Copy, Default)]
pub struct FiniteBatch<B> {
    pub inner: B,
    pub memory: Memory<Lanes>,
}

/// One point's state: `M`'s and the kinematic memory.
#[derive(Debug, Clone, Copy, Default)]
pub struct FiniteState<S> {
    pub inner: S,
    pub memory: Memory<f64>,
}

impl<M: ConstitutiveModel> ConstitutiveModel for Finite<M> {
    type State = FiniteState<M::State>;
    type Batch = FiniteBatch<M::Batch>;
    const KEEPS_MEMORY: bool = true;

    fn state_of(batch: &Self::Batch, l: usize) -> Self::State {
        FiniteState {
            inner: M::state_of(&batch.inner, l),
            memory: batch.memory.lane(l),
        }
    }

    fn set_state(batch: &mut Self::Batch, l: usize, state: Self::State) {
        M::set_state(&mut batch.inner, l, state.inner);
        batch.memory.set_lane(l, &state.memory);
    }

    /// `M`'s update at the unrotated strain: the unrotated Kirchhoff stress, Pa, and the
    /// energy densities per reference volume, J/m^3.
    #[inline(always)]
    fn update<R: Real>(
        &self,
        strain: &[R; 4],
        batch: &mut Self::Batch,
        at: usize,
        active: R::Mask,
    ) -> Response<R> {
        self.0.update(strain, &mut batch.inner, at, active)
    }

    /// The Cauchy stress `R tau^ R^T / J` of the state (its memory holds the strain and the
    /// gradient; `strain`, the linearised one, is not used), Pa. `J = det F (1 + u_r / R)`
    /// with the ring's hoop stretch (1 in plane strain, where the factor is exact).
    fn stress(&self, _strain: &Strain, state: &Self::State) -> Stress {
        let m = &state.memory;
        let tau = self.0.stress(&m.strain, &state.inner);
        let f = deformation(&m.gradient);
        let j = det(&f) * (m.hoop + 1.0);
        Rotation::of_deformation(&f).apply(&tau).map(|x| x / j)
    }

    fn equivalent_plastic_strain(&self, state: &Self::State) -> f64 {
        self.0.equivalent_plastic_strain(&state.inner)
    }

    fn elastic(&self) -> &Elastic {
        self.0.elastic()
    }

    fn virgin_yield_stress(&self) -> Option<f64> {
        self.0.virgin_yield_stress()
    }

    #[inline(always)]
    fn virgin<R: Real>(&self, batch: &Self::Batch, at: usize) -> R::Mask {
        self.0.virgin::<R>(&batch.inner, at)
    }

    fn set_time_step(&mut self, dt: f64) {
        self.0.set_time_step(dt);
    }

    fn set_isa(&mut self, isa: Isa) {
        self.0.set_isa(isa);
    }

    fn plastic_strain_rate(&self, state: &Self::State) -> Option<f64> {
        self.0.plastic_strain_rate(&state.inner)
    }

    fn temperature(&self, state: &Self::State) -> Option<f64> {
        self.0.temperature(&state.inner)
    }

    fn memory(batch: &mut Self::Batch) -> Option<&mut Memory<Lanes>> {
        Some(&mut batch.memory)
    }
}
