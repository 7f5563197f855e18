//! Materials in plane strain (small strain): linear elastic, and von Mises plasticity with
//! isotropic hardening integrated by radial return (backward Euler), eq. (16).
//!
//! Strains are `[xx, yy, zz, gamma_xy]` (engineering shear; `zz` is 0 except in the B-bar
//! modified strain), stresses `[xx, yy, zz, xy]`, in Pa.

use crate::input::scene::{Hardening, Material as MaterialSpec};
use crate::lanes::real::{Real, THIRD};
use crate::lanes::simd::{Isa, Lanes};
use crate::physics::kinematics::Memory;

pub type Strain = [f64; 4];
pub type Stress = [f64; 4];

/// What a material returns at one integration point of [`Real::LANES`] elements (one for
/// `R = f64`).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Response<R> {
    /// Components `[xx, yy, zz, xy]`, Pa.
    pub stress: [R; 4],
    /// Elastic strain energy density, J/m^3.
    pub strain_energy_density: R,
    /// Plastic work density dissipated in this update, J/m^3.
    pub plastic_work_density: R,
}

/// What a material returns at one integration point of one element.
pub type PointResponse = Response<f64>;

/// A constitutive model with its per-point state, stored batch-major: one [`Self::Batch`]
/// holds the states of one point of [`crate::lanes::simd::LANES`] consecutive elements in lanes,
/// so the batched kernels load and store whole registers. Elastic models have zero-sized
/// states, so an elastic run allocates no plasticity state at all.
pub trait ConstitutiveModel: Sync + 'static {
    /// The state of one point.
    type State: Copy + Default + Send + Sync + std::fmt::Debug;
    /// The states of one point of a batch of elements, in lanes.
    type Batch: Copy + Default + Send + Sync + std::fmt::Debug;
    /// Lane `l`'s state.
    fn state_of(batch: &Self::Batch, l: usize) -> Self::State;
    /// Sets lane `l`'s state.
    fn set_state(batch: &mut Self::Batch, l: usize, state: Self::State);
    /// Stress for the total strain (components x lanes) at one point of `at` (an element for
    /// `R = f64`, its lane of `batch`; a batch for [`Lanes`]), updating the states in `batch`
    /// (called once per point per step) where `active` has the lane; an inactive lane's state
    /// is not written and its results are unspecified.
    fn update<R: Real>(
        &self,
        strain: &[R; 4],
        batch: &mut Self::Batch,
        at: usize,
        active: R::Mask,
    ) -> Response<R>;
    /// Stress for the total strain and a converged state, without changing it.
    fn stress(&self, strain: &Strain, state: &Self::State) -> Stress;
    /// Equivalent plastic strain of a state.
    fn equivalent_plastic_strain(&self, state: &Self::State) -> f64;
    fn elastic(&self) -> &Elastic;
    /// Whether the model keeps states: false for the elastic one, whose states are
    /// zero-sized. A model without states never yields and does no plastic work, so the
    /// kernels leave out (at compile time) what only such a model needs.
    const HAS_STATES: bool = std::mem::size_of::<Self::Batch>() > 0;
    /// The flow stress of a point that has never yielded (Pa), `None` for a material that
    /// never yields: below it in von Mises stress a virgin point is linear elastic.
    fn virgin_yield_stress(&self) -> Option<f64> {
        None
    }
    /// Per lane of `at` in `batch`: whether the point has never yielded (its response is
    /// still `D eps`).
    #[inline(always)]
    fn virgin<R: Real>(&self, _batch: &Self::Batch, _at: usize) -> R::Mask {
        R::not(R::splat(0.0).gt(R::splat(0.0)))
    }
    /// Tells a rate-dependent model the run's time step (s), before the first update.
    fn set_time_step(&mut self, _dt: f64) {}
    /// Tells the model the instruction set its batched kernels run on (a model that runs
    /// part of its update out of line compiles that part for it).
    fn set_isa(&mut self, _isa: Isa) {}
    /// A rate-dependent model's equivalent plastic strain rate over the last step (1/s);
    /// `None` for a rate-independent model.
    fn plastic_strain_rate(&self, _state: &Self::State) -> Option<f64> {
        None
    }
    /// A heating model's temperature (K); `None` for a model without temperature.
    fn temperature(&self, _state: &Self::State) -> Option<f64> {
        None
    }
    /// Whether the model keeps a finite-deformation memory per point
    /// ([`crate::physics::materials::finite_material::Finite`]); a finite-deformation formulation paired
    /// with one that does not gives the small-strain response (the linearisation about the
    /// reference configuration: stiffness matrices and stable-step bounds use it).
    const KEEPS_MEMORY: bool = false;
    /// The finite-deformation memory in a point's batch; `None` for a model without one.
    fn memory(_batch: &mut Self::Batch) -> Option<&mut Memory<Lanes>> {
        None
    }
}

/// `update(strain of lane l, element)` for each active lane `l` of `at`, one element at a
/// time (for a tabulated flow curve, whose pieces differ from lane to lane). `element` is
/// what the scalar path calls the lane: `at` itself for `f64`, `l` (lane `l` of the batch)
/// for [`Lanes`].
#[inline(always)]
fn each_lane<R: Real>(
    strain: &[R; 4],
    at: usize,
    active: R::Mask,
    mut update: impl FnMut(&Strain, usize) -> PointResponse,
) -> Response<R> {
    let mut out = Response::<R>::default();
    for l in (0..R::LANES).filter(|&l| R::on(active, l)) {
        let e = [
            strain[0].lane(l),
            strain[1].lane(l),
            strain[2].lane(l),
            strain[3].lane(l),
        ];
        let r = update(&e, if R::LANES == 1 { at } else { l });
        for c in 0..4 {
            out.stress[c].set_lane(l, r.stress[c]);
        }
        out.strain_energy_density
            .set_lane(l, r.strain_energy_density);
        out.plastic_work_density.set_lane(l, r.plastic_work_density);
    }
    out
}

/// Isotropic linear elasticity (Lame constants in Pa).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Elastic {
    pub lambda: f64,
    pub mu: f64,
}

impl Elastic {
    pub fn new(youngs_modulus: f64, poisson_ratio: f64) -> Elastic {
        let (e, nu) = (youngs_modulus, poisson_ratio);
        Elastic {
            lambda: e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)),
            mu: e / (2.0 * (1.0 + nu)),
        }
    }

    /// P-wave (constrained) modulus lambda + 2 mu, Pa.
    pub fn p_modulus(&self) -> f64 {
        self.lambda + 2.0 * self.mu
    }

    /// `D e`: stress (Pa) of the strain `e` (components x lanes).
    #[inline(always)]
    pub fn stress_of<R: Real>(&self, e: &[R; 4]) -> [R; 4] {
        let lt = (e[0] + e[1] + e[2]) * self.lambda;
        let m2 = 2.0 * self.mu;
        [
            lt + e[0] * m2,
            lt + e[1] * m2,
            lt + e[2] * m2,
            e[3] * self.mu,
        ]
    }
}

/// `s : e / 2` with engineering shear strain (J/m^3 for Pa and -).
#[inline(always)]
pub fn half_contraction<R: Real>(s: &[R; 4], e: &[R; 4]) -> R {
    (s[0] * e[0] + s[1] * e[1] + s[2] * e[2] + s[3] * e[3]) * 0.5
}

impl ConstitutiveModel for Elastic {
    type State = ();
    type Batch = ();
    fn state_of(_: &(), _: usize) {}
    fn set_state(_: &mut (), _: usize, _: ()) {}
    #[inline(always)]
    fn update<R: Real>(&self, strain: &[R; 4], _: &mut (), _: usize, _: R::Mask) -> Response<R> {
        let stress = self.stress_of(strain);
        Response {
            stress,
            strain_energy_density: half_contraction(&stress, strain),
            plastic_work_density: R::splat(0.0),
        }
    }
    fn stress(&self, strain: &Strain, _: &()) -> Stress {
        self.stress_of(strain)
    }
    fn equivalent_plastic_strain(&self, _: &()) -> f64 {
        0.0
    }
    fn elastic(&self) -> &Elastic {
        self
    }
}

/// Von Mises equivalent stress, Pa.
pub fn von_mises(s: &Stress) -> f64 {
    let (a, b, c) = (s[0] - s[1], s[1] - s[2], s[2] - s[0]);
    (0.5 * (a * a + b * b + c * c) + 3.0 * s[3] * s[3]).sqrt()
}

/// Flow stress against equivalent plastic strain: piecewise linear (one piece for linear
/// hardening), held constant beyond the last tabulated point.
#[derive(Debug, Clone, PartialEq)]
pub struct FlowCurve {
    /// Breakpoints (equivalent plastic strain, flow stress Pa), the first at (0, yield).
    points: Vec<(f64, f64)>,
    /// Slope after the last point, Pa (the plastic modulus H for linear hardening).
    tail_slope: f64,
}

impl FlowCurve {
    /// The piecewise-linear curve of `hardening`; `None` for a power law (which only the
    /// rate-dependent model, [`crate::physics::materials::rate_plasticity`], integrates).
    pub fn new(yield_stress: f64, hardening: &Hardening, youngs_modulus: f64) -> Option<FlowCurve> {
        Some(match hardening {
            Hardening::Linear { tangent_modulus } => FlowCurve {
                points: vec![(0.0, yield_stress)],
                // Uniaxial tangent E_t -> plastic modulus H = E E_t / (E - E_t).
                tail_slope: youngs_modulus * tangent_modulus / (youngs_modulus - tangent_modulus),
            },
            Hardening::Table(points) => FlowCurve {
                points: points.clone(),
                tail_slope: 0.0,
            },
            Hardening::Power { .. } => return None,
        })
    }

    /// (flow stress Pa, slope Pa to the right of `k`, next breakpoint after `k` if any).
    #[inline]
    fn piece(&self, k: f64) -> (f64, f64, Option<f64>) {
        let p = &self.points;
        if p.len() == 1 {
            // Linear hardening: one piece, no search.
            return (p[0].1 + self.tail_slope * k, self.tail_slope, None);
        }
        // Index of the last breakpoint at or before k.
        let i = p.partition_point(|&(kk, _)| kk <= k).saturating_sub(1);
        if i + 1 < p.len() {
            let (k0, s0) = p[i];
            let (k1, s1) = p[i + 1];
            let slope = (s1 - s0) / (k1 - k0);
            (s0 + slope * (k - k0), slope, Some(k1))
        } else {
            let (k0, s0) = p[i];
            (s0 + self.tail_slope * (k - k0), self.tail_slope, None)
        }
    }

    /// The curve as [`LinearHardening`], `None` for a tabulated one.
    #[inline(always)]
    pub fn linear(&self) -> Option<LinearHardening> {
        (self.points.len() == 1).then(|| LinearHardening {
            yield_stress: self.points[0].1,
            modulus: self.tail_slope,
        })
    }

    /// Flow stress at equivalent plastic strain `k`, Pa.
    pub fn flow_stress(&self, k: f64) -> f64 {
        self.piece(k).0
    }

    /// Slope of the flow curve to the right of `k`, Pa.
    pub fn slope(&self, k: f64) -> f64 {
        self.piece(k).1
    }
}

/// What the radial return needs of a flow curve, in the number type `R`.
pub trait FlowLaw<R: Real> {
    /// Flow stress at equivalent plastic strain `k`, Pa.
    fn flow_stress(&self, k: R) -> R;
    /// The increment `dk` solving `q - 3 mu dk - sigma_y(k + dk) = 0` (`q`: trial von Mises
    /// stress, Pa; `flow_at_k`: [`FlowLaw::flow_stress`] at `k`, which the caller has already
    /// computed, Pa; `three_mu`: 3 mu, Pa).
    fn plastic_increment(&self, q: R, k: R, flow_at_k: R, three_mu: f64) -> R;
    /// The plastic work density of the increment `dk` from `k_new - dk` to `k_new` (J/m^3),
    /// `sy_old` the flow stress at its start and `q_new` the returned von Mises stress (Pa):
    /// the trapezoid of the flow curve.
    #[inline(always)]
    fn plastic_work(&self, sy_old: R, k_new: R, dk: R, _q_new: R) -> R {
        (sy_old + self.flow_stress(k_new)) * 0.5 * dk
    }
}

/// Linear hardening, `sigma_y(k) = yield_stress + modulus k`: one piece, any number type.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearHardening {
    /// Initial yield stress, Pa.
    pub yield_stress: f64,
    /// Plastic modulus H, Pa.
    pub modulus: f64,
}

impl<R: Real> FlowLaw<R> for LinearHardening {
    #[inline(always)]
    fn flow_stress(&self, k: R) -> R {
        k * self.modulus + self.yield_stress
    }
    /// [`FlowCurve`]'s piece by piece solve on its one piece, in its order.
    #[inline(always)]
    fn plastic_increment(&self, q: R, k: R, _flow_at_k: R, three_mu: f64) -> R {
        let dk = R::splat(0.0);
        let sy = self.flow_stress(k + dk);
        let x = (q - dk * three_mu - sy) * (1.0 / (three_mu + self.modulus));
        dk + x
    }
}

impl FlowLaw<f64> for FlowCurve {
    #[inline(always)]
    fn flow_stress(&self, k: f64) -> f64 {
        self.piece(k).0
    }
    /// Piece by piece of the curve: each pass either returns or moves to the next piece, so
    /// the passes are at most the pieces. After a breakpoint `b` the next piece is looked up
    /// at `max(k + dk, b)`: `k + (b - k)` can round below `b` (k = 0.0021765534325648541,
    /// b = 0.01 gives 0.009999999999999998), and the lookup at `k + dk` alone found the same
    /// piece again, for ever (found by the batched-kernel test's random fields).
    fn plastic_increment(&self, q: f64, k: f64, _flow_at_k: f64, three_mu: f64) -> f64 {
        let mut dk = 0.0;
        let mut at = k;
        for _ in 0..self.points.len() {
            let (sy, h, next) = self.piece(at);
            let x = (q - three_mu * dk - sy) * (1.0 / (three_mu + h));
            match next {
                Some(b) if k + dk + x > b => {
                    dk = b - k;
                    at = (k + dk).max(b);
                }
                _ => return dk + x,
            }
        }
        // Past the last breakpoint: the tail piece (no next breakpoint) returns above, so
        // this is reached only on a curve whose pieces do not advance (not one the scene
        // reader builds); the increment to the last breakpoint is the bounded answer.
        dk
    }
}

/// Per-point state of the plastic model.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PlasticState {
    /// Plastic strain tensor `[xx, yy, zz, xy]` (tensor shear).
    pub plastic_strain: [f64; 4],
    /// Equivalent plastic strain.
    pub eqps: f64,
}

/// [`PlasticState`]s of one point of a batch of elements, in lanes.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PlasticBatch {
    /// Plastic strain tensor `[xx, yy, zz, xy]` (tensor shear).
    pub plastic_strain: [Lanes; 4],
    /// Equivalent plastic strain.
    pub eqps: Lanes,
}

/// Von Mises plasticity with isotropic hardening.
#[derive(Debug, Clone, PartialEq)]
pub struct VonMises {
    pub elastic: Elastic,
    pub flow: FlowCurve,
}

impl VonMises {
    pub(crate) fn elastic_strain(strain: &Strain, state: &PlasticState) -> Strain {
        let p = &state.plastic_strain;
        [
            strain[0] - p[0],
            strain[1] - p[1],
            strain[2] - p[2],
            strain[3] - 2.0 * p[3],
        ]
    }
}

/// Radial return from the trial deviator: the mean stress is elastic (von Mises flow is
/// deviatoric), the deviator is scaled back to the flow stress. Elastic strain energy
/// density `K tr^2 / 2 + q^2 / (6 mu)`, from the trial and returned `q` directly. The
/// trial for every lane, the return where any lane yields, selected per lane; states as
/// in [`ConstitutiveModel::update`], written back only for active lanes that yield.
#[inline(always)]
pub(crate) fn radial_return<R: Real, H: FlowLaw<R>>(
    elastic: &Elastic,
    flow: &H,
    strain: &[R; 4],
    batch: &mut PlasticBatch,
    (at, active): (usize, R::Mask),
) -> Response<R> {
    let mu = elastic.mu;
    let bulk = elastic.lambda + 2.0 / 3.0 * mu;
    let mut p = [R::splat(0.0); 4];
    for (pc, stored) in p.iter_mut().zip(&batch.plastic_strain) {
        *pc = R::of_batch(stored, at);
    }
    let k_old = R::of_batch(&batch.eqps, at);
    let e = [strain[0] - p[0], strain[1] - p[1], strain[2] - p[2]];
    let trace = e[0] + e[1] + e[2];
    let third = trace * THIRD;
    let mut dev = [
        (e[0] - third) * (2.0 * mu),
        (e[1] - third) * (2.0 * mu),
        (e[2] - third) * (2.0 * mu),
        (strain[3] - p[3] * 2.0) * mu,
    ];
    let mean = trace * bulk;
    let volumetric_energy = mean * 0.5 * trace;
    let q2 = (dev[0] * dev[0] + dev[1] * dev[1] + dev[2] * dev[2]) * 1.5 + dev[3] * 3.0 * dev[3];
    let sy_old = flow.flow_stress(k_old);
    let mut plastic_work_density = R::splat(0.0);
    let mut q2_final = q2;
    // Compare squares: most points are elastic and need no square root.
    let yields = q2.gt(sy_old * sy_old);
    if R::any(yields) {
        // (At least the smallest normal number: a lane with no deviatoric stress, which
        // does not yield, must not divide 0 by 0 below. A yielding lane has q > 0.)
        let q = q2.sqrt().max(f64::MIN_POSITIVE);
        // (q2 > sy^2 and q <= sy can both hold within an ulp: never a negative increment.)
        let dk = flow.plastic_increment(q, k_old, sy_old, 3.0 * mu).max(0.0);
        // Plastic strain increment dk * 3/2 dev/q (tensor shear). No select between the
        // yielding and the elastic values: a lane that does not yield has q <= sy
        // (sqrt(fl(sy^2)) = sy), so dk = 0, r = 0 and scale = 1 exactly, and p, dev and q2
        // come out with their elastic bits. (Written as selects, LLVM turned them into a
        // branch per lane over transposed components: ~25 % of the yielding kernel.)
        let r = dk * 1.5 / q;
        let scale = R::splat(1.0) - r * (2.0 * mu); // q_new / q = 1 - 3 mu dk / q
        for (pc, dc) in p.iter_mut().zip(&mut dev) {
            *pc += r * *dc;
            *dc = *dc * scale;
        }
        q2_final = q2 * scale * scale;
        let eqps = k_old + dk;
        let work = flow.plastic_work(sy_old, eqps, dk, q * scale);
        plastic_work_density = R::select(yields, work, plastic_work_density);
        let write = R::and(active, yields);
        for (stored, &pc) in batch.plastic_strain.iter_mut().zip(&p) {
            R::store(stored, at, pc, write);
        }
        R::store(&mut batch.eqps, at, eqps, write);
    }
    Response {
        stress: [dev[0] + mean, dev[1] + mean, dev[2] + mean, dev[3]],
        strain_energy_density: volumetric_energy + q2_final * (1.0 / (6.0 * mu)),
        plastic_work_density,
    }
}

impl ConstitutiveModel for VonMises {
    type State = PlasticState;
    type Batch = PlasticBatch;

    fn state_of(batch: &PlasticBatch, l: usize) -> PlasticState {
        PlasticState {
            plastic_strain: batch.plastic_strain.map(|x| x.0[l]),
            eqps: batch.eqps.0[l],
        }
    }

    fn set_state(batch: &mut PlasticBatch, l: usize, state: PlasticState) {
        for (stored, x) in batch.plastic_strain.iter_mut().zip(state.plastic_strain) {
            stored.0[l] = x;
        }
        batch.eqps.0[l] = state.eqps;
    }

    /// The radial return ([`radial_return`]), in lanes for linear hardening; a
    /// tabulated curve, whose pieces differ from lane to lane, runs it lane by lane.
    #[inline(always)]
    fn update<R: Real>(
        &self,
        strain: &[R; 4],
        batch: &mut PlasticBatch,
        at: usize,
        active: R::Mask,
    ) -> Response<R> {
        match self.flow.linear() {
            Some(linear) => radial_return(&self.elastic, &linear, strain, batch, (at, active)),
            // Lane `l` of the batch as the scalar path's element `l`.
            None => each_lane(strain, at, active, |e, element| {
                radial_return(&self.elastic, &self.flow, e, batch, (element, true))
            }),
        }
    }

    fn stress(&self, strain: &Strain, state: &PlasticState) -> Stress {
        self.elastic.stress_of(&Self::elastic_strain(strain, state))
    }

    fn equivalent_plastic_strain(&self, state: &PlasticState) -> f64 {
        state.eqps
    }

    fn elastic(&self) -> &Elastic {
        &self.elastic
    }

    fn virgin_yield_stress(&self) -> Option<f64> {
        Some(self.flow.flow_stress(0.0))
    }

    /// The plastic strain only moves with the equivalent plastic strain (`dk > 0`), so a
    /// point with `eqps == 0` (it is never negative) still has zero plastic strain.
    #[inline(always)]
    fn virgin<R: Real>(&self, batch: &PlasticBatch, at: usize) -> R::Mask {
        R::not(R::of_batch(&batch.eqps, at).gt(R::splat(0.0)))
    }
}

impl VonMises {
    /// The rate-independent model of `spec`; `None` without plasticity or with a rate law
    /// (that is [`crate::physics::materials::rate_plasticity::ViscoPlastic`]'s).
    pub fn new(spec: &MaterialSpec) -> Option<VonMises> {
        let p = spec.plasticity.as_ref().filter(|p| p.rate.is_none())?;
        Some(VonMises {
            elastic: Elastic::new(spec.youngs_modulus, spec.poisson_ratio),
            flow: FlowCurve::new(p.yield_stress, &p.hardening, spec.youngs_modulus)?,
        })
    }
}

/// Steel with a 176 MPa yield stress and 1 GPa linear hardening: the plastic material of the
/// solver's unit tests.
#[cfg(test)]
pub(crate) fn test_von_mises() -> VonMises {
    von_mises_steel(
        207e9,
        176e6,
        Hardening::Linear {
            tangent_modulus: 1e9,
        },
    )
}

/// Von Mises steel (7850 kg/m^3, nu = 0.3) of Young's modulus `youngs_modulus` and yield
/// stress `yield_stress` (Pa) with `hardening`.
#[cfg(test)]
fn von_mises_steel(youngs_modulus: f64, yield_stress: f64, hardening: Hardening) -> VonMises {
    VonMises::new(&MaterialSpec {
        density: 7850.0,
        youngs_modulus,
        poisson_ratio: 0.3,
        plasticity: Some(crate::input::scene::Plasticity {
            yield_stress,
            hardening,
            rate: None,
        }),
    })
    .expect("a material with plasticity")
}

#[cfg(test)]
mod tests {
    //! Radial return against closed forms: uniaxial strain (plane strain, eps_xx only)
    //! loading with linear hardening, and the tabulated curve.
    use super::*;
    use approx::assert_relative_eq;

    /// One point's update (lane 0 of a batch).
    fn update(m: &VonMises, strain: &Strain, state: &mut PlasticState) -> PointResponse {
        let mut batch = PlasticBatch::default();
        VonMises::set_state(&mut batch, 0, *state);
        let r = m.update(strain, &mut batch, 0, true);
        *state = VonMises::state_of(&batch, 0);
        r
    }

    fn steel(hardening: Hardening) -> VonMises {
        von_mises_steel(200e9, 250e6, hardening)
    }

    /// Uniaxial strain eps_xx = e (all other strains 0). Closed form: elastic until
    /// e_y = sigma_y / (2 mu); after that, with plastic modulus H, the axial stress is
    /// sigma_xx = K e + (4/3) [mu e_y + mu H/(3 mu + H) (e - e_y)] ... derived below.
    #[test]
    fn radial_return_matches_the_uniaxial_strain_closed_form() {
        let et = 2.0e9;
        let m = steel(Hardening::Linear {
            tangent_modulus: et,
        });
        let (lam, mu) = (m.elastic.lambda, m.elastic.mu);
        let bulk = lam + 2.0 * mu / 3.0;
        let h = 200e9 * et / (200e9 - et);
        let sy = 250e6;
        // Deviatoric axial part s_xx = (2/3) q with q the von Mises stress; elastically
        // q = 2 mu e. Yield at e_y = sy / (2 mu). After yield, d q = 2 mu * 3 mu H / ... :
        // q = sy + H k and 2 mu (e - e_y) = (q - sy) + 3 mu k  =>  k = 2 mu (e - e_y) / (3 mu + H)
        let e_y = sy / (2.0 * mu);
        let mut state = PlasticState::default();
        let steps = 400;
        let e_max = 10.0 * e_y;
        for i in 1..=steps {
            let e = e_max * i as f64 / steps as f64;
            let r = update(&m, &[e, 0.0, 0.0, 0.0], &mut state);
            let (q, k) = if e <= e_y {
                (2.0 * mu * e, 0.0)
            } else {
                let k = 2.0 * mu * (e - e_y) / (3.0 * mu + h);
                (sy + h * k, k)
            };
            let sxx = bulk * e + 2.0 / 3.0 * q;
            let syy = bulk * e - q / 3.0;
            assert_relative_eq!(r.stress[0], sxx, max_relative = 1e-12);
            assert_relative_eq!(r.stress[1], syy, max_relative = 1e-12);
            assert_relative_eq!(r.stress[2], syy, max_relative = 1e-12);
            assert_relative_eq!(state.eqps, k, epsilon = 1e-15);
            assert_relative_eq!(von_mises(&r.stress), q, max_relative = 1e-12);
        }
    }

    #[test]
    fn tabulated_curve_is_followed_across_breakpoints_and_held_beyond_the_last() {
        let m = steel(Hardening::Table(vec![
            (0.0, 250e6),
            (0.01, 300e6),
            (0.02, 310e6),
        ]));
        let mu = m.elastic.mu;
        let mut state = PlasticState::default();
        // One big step far beyond the table: the return must end on the flat tail.
        let e = 0.1;
        let r = update(&m, &[e, 0.0, 0.0, 0.0], &mut state);
        assert_relative_eq!(von_mises(&r.stress), 310e6, max_relative = 1e-12);
        // Consistency: 2 mu e = q + 3 mu k (uniaxial strain, deviatoric part).
        assert_relative_eq!(
            2.0 * mu * e,
            310e6 + 3.0 * mu * state.eqps,
            max_relative = 1e-12
        );
        // Inside the first segment.
        let mut s2 = PlasticState::default();
        let e2 = 250e6 / (2.0 * mu) + 0.004;
        let r2 = update(&m, &[e2, 0.0, 0.0, 0.0], &mut s2);
        let h = 5e9;
        let k = 2.0 * mu * 0.004 / (3.0 * mu + h);
        assert_relative_eq!(s2.eqps, k, max_relative = 1e-12);
        assert_relative_eq!(von_mises(&r2.stress), 250e6 + h * k, max_relative = 1e-12);
    }

    /// A return that starts where `k + (b - k)` rounds below the breakpoint `b` (the values
    /// the batched-kernel test's random fields met: k = 0.0021765534325648541, b = 0.01)
    /// ends, on the piece after `b`, and satisfies the consistency condition there. (Before
    /// the fix the lookup found the piece ending at `b` again and looped for ever.)
    #[test]
    fn a_return_across_a_breakpoint_that_rounds_short_ends() {
        let k = 0.0021765534325648541;
        assert!(k + (0.01 - k) < 0.01, "the rounding this test needs");
        let curve = FlowCurve::new(
            320e6,
            &Hardening::Table(vec![(0.0, 320e6), (0.01, 400e6), (0.05, 450e6)]),
            207e9,
        )
        .unwrap();
        let three_mu = 3.0 * 207e9 / 2.6;
        let q = 340e6 + three_mu * 0.02;
        let dk = curve.plastic_increment(q, k, curve.flow_stress(k), three_mu);
        assert!(k + dk > 0.01 && k + dk < 0.05, "{dk}");
        // q - 3 mu dk = flow(k + dk): relative 1e-12, ~1e4 round-offs of the O(1e8) terms.
        let residual = q - three_mu * dk - curve.flow_stress(k + dk);
        assert!(residual.abs() < 1e-12 * q, "{residual}");
    }

    #[test]
    fn elastic_unloading_after_yield_keeps_the_plastic_strain() {
        let m = steel(Hardening::Linear {
            tangent_modulus: 1e9,
        });
        let mut state = PlasticState::default();
        update(&m, &[0.01, 0.0, 0.0, 0.0], &mut state);
        let k = state.eqps;
        let r = update(&m, &[0.0099, 0.0, 0.0, 0.0], &mut state);
        assert_eq!(state.eqps, k);
        assert_eq!(r.plastic_work_density, 0.0);
    }
}
