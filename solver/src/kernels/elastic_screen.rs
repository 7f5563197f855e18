//! Elastic points at elastic cost in a plastic scene. An element none of whose points has
//! yielded responds with `K_e u_e` (eq. 13) as long as every point stays below the initial
//! yield stress; the screen proves that from the element's elastic strain energy, which the
//! stiffness product gives for 8 more flops, and otherwise leaves the element to the plastic
//! stress path (eqs. 14, 16).
//!
//! The bound: for the linear-elastic response the element strain energy is
//! `W = sum_p w_p (K tr_p^2 / 2 + q_p^2 / (6 mu))` (bulk modulus `K`, von Mises stress `q_p`,
//! weights `w_p`; every term >= 0; B-bar and one-point elements alike, hourglass energy
//! apart), so `q_p^2 <= 6 mu W / w_p` at every point. When `W < SAFETY w_min sigma_y^2 /
//! (6 mu)`, every `q_p^2 < sigma_y^2`: the radial return would take its elastic branch at
//! every point and leave the state unchanged, and `K_e u_e` is its force up to round-off.

use std::sync::atomic::{AtomicU8, Ordering};

use crate::kernels::assembly::CHUNK;
use crate::kernels::stiffness::LinearKernel;
use crate::lanes::heap::vec_bytes;
use crate::lanes::real::Real;
use crate::lanes::simd::{Lanes, LANES};
use crate::physics::elements::element::{ElementEnergy, ElementVector, Energy, Formulation};
use crate::physics::elements::geometry::Vector;
use crate::physics::materials::material::ConstitutiveModel;

/// Fraction of the bound an element may reach on the fast path. `W` from the stiffness
/// product (with node 0's translation removed, so no rigid motion cancels) is exact to
/// ~1e-13 relative (64 products of one sign-definite quadratic form); a margin of 1e-3 is
/// 10^10 times that and costs nothing measurable (elements that close to yield are few).
const SAFETY: f64 = 0.999;

/// Stiffness matrices and, per element, the strain energy below which it is certainly elastic.
pub struct ElasticScreen {
    kernel: LinearKernel,
    /// Per batch of [`LANES`] elements, in lanes: `SAFETY w_min sigma_y^2 / (6 mu)`, J (0 in
    /// the missing lanes of a partial batch: nothing is below it).
    limit: Vec<Lanes>,
    /// Per chunk of [`CHUNK`] elements: calls left before the screen is tried on the whole
    /// chunk again ([`ElasticScreen::try_whole`]).
    skips: Vec<Skips>,
}

/// A chunk's skips, alone in its cache line (chunks next to each other may be run by
/// different threads: no line written by both).
#[repr(align(64))]
struct Skips(AtomicU8);

/// Calls a chunk skips the whole-chunk screen after it failed there (an element above the
/// bound, a yielded point): the failed try's products are redone by the stress path.
const SKIPS_AFTER_A_FAILURE: u8 = 8;

impl ElasticScreen {
    /// The screen of `formulation` for `material`, `None` when the material never yields.
    pub fn new<F: Formulation, M: ConstitutiveModel>(
        formulation: &F,
        material: &M,
    ) -> Option<ElasticScreen> {
        let yield_stress = material.virgin_yield_stress()?;
        let elastic = material.elastic();
        let per_weight = SAFETY * yield_stress * yield_stress / (6.0 * elastic.mu);
        let mut limit = vec![Lanes::splat(0.0); formulation.n_elements().div_ceil(LANES)];
        for e in 0..formulation.n_elements() {
            let w = formulation.weights::<f64>(e);
            let w_min = w[..F::POINTS].iter().copied().fold(f64::INFINITY, f64::min);
            limit[e / LANES].0[e % LANES] = per_weight * w_min;
        }
        Some(ElasticScreen {
            kernel: LinearKernel::new(formulation, elastic),
            limit,
            skips: (0..formulation.n_elements().div_ceil(CHUNK))
                .map(|_| Skips(AtomicU8::new(0)))
                .collect(),
        })
    }

    /// Heap bytes of the matrices, the limits and the chunks' skips.
    pub fn heap_bytes(&self) -> usize {
        self.kernel.heap_bytes() + vec_bytes(&self.limit) + vec_bytes(&self.skips)
    }

    /// Runs `whole` (the screen on the whole chunk that starts at element `first`: `None`
    /// when it fails) unless the chunk failed there within the last
    /// [`SKIPS_AFTER_A_FAILURE`] calls. Which path a chunk takes changes no bit (the screen
    /// gives the same forces either way), so this is no source of nondeterminism; a chunk is
    /// only ever run by one thread at a time.
    #[inline]
    pub fn try_whole<T>(&self, first: usize, whole: impl FnOnce() -> Option<T>) -> Option<T> {
        let skips = &self.skips[first / CHUNK].0;
        let left = skips.load(Ordering::Relaxed);
        if left > 0 {
            skips.store(left - 1, Ordering::Relaxed);
            return None;
        }
        let result = whole();
        if result.is_none() {
            skips.store(SKIPS_AFTER_A_FAILURE, Ordering::Relaxed);
        }
        result
    }

    /// `K_e u_e` of `at` (an element, or a batch in lanes) at its displacements `ue` (m):
    /// forces, energies, and the lanes certainly below yield at every point if they have
    /// never yielded (the caller's part: those lanes may take the forces; the others run the
    /// plastic stress path).
    #[inline(always)]
    pub fn product<F: Formulation, R: Real>(
        &self,
        formulation: &F,
        at: usize,
        ue: &Vector<R>,
    ) -> (Vector<R>, Energy<R>, R::Mask) {
        let (f, energy) = self.kernel.product(formulation, at, ue);
        (f, energy, self.below(at, &energy))
    }

    /// [`ElasticScreen::product`] in the form the stress path's kernel inlines
    /// ([`LinearKernel::screen_product`]; the same bits).
    #[inline(always)]
    pub fn product_in_stress_path<F: Formulation, R: Real>(
        &self,
        formulation: &F,
        at: usize,
        ue: &Vector<R>,
    ) -> (Vector<R>, Energy<R>, R::Mask) {
        let (f, energy) = self.kernel.screen_product(formulation, at, ue);
        (f, energy, self.below(at, &energy))
    }

    /// The lanes of `at` whose strain energy is below the bound.
    #[inline(always)]
    fn below<R: Real>(&self, at: usize, energy: &Energy<R>) -> R::Mask {
        R::of_batch(&self.limit[R::batch_of(at)], at).gt(energy.strain)
    }

    /// Forces and energies of element `e` at its displacements `ue` (m) by `K_e u_e` when
    /// every point of it (its lane of `batches`, one per point) is virgin and certainly stays
    /// elastic; `None` otherwise (the caller runs the plastic stress path).
    #[inline(always)]
    pub fn element<F: Formulation, M: ConstitutiveModel>(
        &self,
        formulation: &F,
        material: &M,
        e: usize,
        ue: &ElementVector,
        batches: &[M::Batch],
    ) -> Option<(ElementVector, ElementEnergy)> {
        if !batches.iter().all(|b| material.virgin::<f64>(b, e)) {
            return None;
        }
        let (f, energy, below) = self.product(formulation, e, ue);
        below.then_some((f, energy))
    }
}

#[cfg(test)]
mod tests {
    //! Reference: the plastic stress path (`element_response` with von Mises). Below the
    //! screen's bound both give the same forces to round-off and leave the states virgin;
    //! near yield the screen must refuse every element the stress path lets yield.
    use super::*;
    use crate::mesh::Mesh;
    use crate::physics::elements::element::{
        element_response, gather, FullQ4, OnePointQ4, SelectiveQ4,
    };
    use crate::physics::materials::material::{
        test_von_mises, Elastic, PlasticBatch, PlasticState, VonMises,
    };

    /// Element `e`'s point `states` in its lane of batches.
    fn in_batches(states: &[PlasticState], e: usize) -> Vec<PlasticBatch> {
        states
            .iter()
            .map(|&s| {
                let mut batch = PlasticBatch::default();
                VonMises::set_state(&mut batch, e % LANES, s);
                batch
            })
            .collect()
    }

    fn check<F: Formulation>(make: impl Fn(&Mesh) -> F) {
        let mesh = crate::mesh::test_plate_mesh(12, 4, 3.0);
        let material = test_von_mises();
        let formulation = make(&mesh.mesh);
        let screen = ElasticScreen::new(&formulation, &material).unwrap();
        let (mut fast, mut refused_yielding) = (0, 0);
        // Non-smooth fields with a large rigid translation, from far below yield to far above.
        for amplitude in [1e-7, 1e-6, 3e-6, 1e-5, 3e-5, 1e-4] {
            let u: Vec<f64> = (0..2 * mesh.mesh.n_nodes())
                .map(|i| 1e-3 + amplitude * ((i as f64 * 0.7).sin() + 0.3 * (i as f64 * 2.3).cos()))
                .collect();
            for e in 0..formulation.n_elements() {
                let ue = gather(formulation.nodes(e), &u);
                let mut states = [PlasticState::default(); 4];
                let (f_ref, en_ref) =
                    element_response(&formulation, &material, e, &ue, &mut states[..F::POINTS]);
                let yielded = states.iter().any(|s| s.eqps > 0.0);
                let batches = in_batches(&states[..F::POINTS], e);
                match screen.element(&formulation, &material, e, &ue, &batches) {
                    Some((f, en)) => {
                        assert!(!yielded, "element {e} at {amplitude}: screened but yields");
                        let scale = f_ref.iter().fold(0.0f64, |m, x| m.max(x.abs()));
                        for (a, b) in f.iter().zip(&f_ref) {
                            assert!((a - b).abs() <= 1e-9 * scale, "{a:e} vs {b:e}");
                        }
                        assert!((en.strain - en_ref.strain).abs() <= 1e-9 * en_ref.strain);
                        fast += 1;
                    }
                    None if yielded => refused_yielding += 1,
                    // Far below yield the screen must pay: every element takes it.
                    None => assert!(amplitude > 1e-7, "element {e} refused far below yield"),
                }
            }
        }
        // The sweep crosses yield: some elements take each branch.
        assert!(
            fast > 0 && refused_yielding > 0,
            "{fast} {refused_yielding}"
        );
        // A yielded element is never screened, even when it is elastic again.
        let mut states = [PlasticState::default(); 4];
        states[0].eqps = 1e-9;
        let batches = in_batches(&states[..F::POINTS], 0);
        assert!(screen
            .element(&formulation, &material, 0, &[0.0; 8], &batches)
            .is_none());
    }

    #[test]
    fn screened_elements_equal_the_plastic_stress_path_and_never_yield() {
        check(|m| FullQ4::new(m, 0.2).unwrap());
        check(|m| SelectiveQ4::new(m, 0.2).unwrap());
        check(|m| OnePointQ4::new(m, 0.2, 0.05, Elastic::new(207e9, 0.3).p_modulus()).unwrap());
    }

    #[test]
    fn an_elastic_material_has_no_screen() {
        let mesh = crate::mesh::test_plate_mesh(4, 2, 1.0);
        let f = SelectiveQ4::new(&mesh.mesh, 0.2).unwrap();
        assert!(ElasticScreen::new(&f, &Elastic::new(207e9, 0.3)).is_none());
    }
}
