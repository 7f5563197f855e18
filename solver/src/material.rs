//! Materials in plane strain (small strain): linear elastic, and von Mises plasticity with
//! isotropic hardening integrated by radial return (backward Euler), eq. (16).
//!
//! Strains are `[xx, yy, zz, gamma_xy]` (engineering shear; `zz` is 0 except in the B-bar
//! modified strain), stresses `[xx, yy, zz, xy]`, in Pa.

use crate::scene::{Hardening, Material as MaterialSpec};
use crate::simd::{Lanes, Mask, LANES};

pub type Strain = [f64; 4];
pub type Stress = [f64; 4];

/// What a material returns at one integration point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointResponse {
    pub stress: Stress,
    /// Elastic strain energy density, J/m^3.
    pub strain_energy_density: f64,
    /// Plastic work density dissipated in this update, J/m^3.
    pub plastic_work_density: f64,
}

/// A constitutive model with its per-point state. Elastic models have a zero-sized state, so
/// an elastic run allocates no plasticity state at all.
pub trait ConstitutiveModel: Sync {
    type State: Copy + Default + Send + Sync + std::fmt::Debug;
    /// Stress for the total strain, updating the state (called once per point per step).
    fn update(&self, strain: &Strain, state: &mut Self::State) -> PointResponse;
    /// [`ConstitutiveModel::update`] at one point of [`LANES`] elements (strain components x
    /// lanes): lane `l`'s state is `states[first + l * stride]` when `active[l]`; an inactive
    /// lane's state is neither read nor written and its results are unspecified. Bit-identical
    /// to `update` lane by lane (the default runs it lane by lane).
    #[inline(always)]
    fn update_lanes(
        &self,
        strain: &[Lanes; 4],
        states: &mut [Self::State],
        first: usize,
        stride: usize,
        active: &Mask,
    ) -> LaneResponse {
        update_each_lane(self, strain, states, first, stride, active)
    }
    /// Stress for the total strain and a converged state, without changing it.
    fn stress(&self, strain: &Strain, state: &Self::State) -> Stress;
    /// Equivalent plastic strain of a state.
    fn equivalent_plastic_strain(&self, state: &Self::State) -> f64;
    fn elastic(&self) -> &Elastic;
    /// The flow stress of a point that has never yielded (Pa), `None` for a material that
    /// never yields: below it in von Mises stress a virgin point is linear elastic.
    fn virgin_yield_stress(&self) -> Option<f64> {
        None
    }
    /// Whether a point in `state` has never yielded (its response is still `D eps`).
    #[inline(always)]
    fn is_virgin(&self, _state: &Self::State) -> bool {
        true
    }
}

/// What a material returns at one integration point of [`LANES`] elements.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct LaneResponse {
    /// Components `[xx, yy, zz, xy]` x lanes, Pa.
    pub stress: [Lanes; 4],
    /// J/m^3
    pub strain_energy_density: Lanes,
    /// J/m^3
    pub plastic_work_density: Lanes,
}

/// The lane-by-lane fallback of [`ConstitutiveModel::update_lanes`] (scalar `update` per lane).
#[inline(always)]
pub fn update_each_lane<M: ConstitutiveModel + ?Sized>(
    material: &M,
    strain: &[Lanes; 4],
    states: &mut [M::State],
    first: usize,
    stride: usize,
    active: &Mask,
) -> LaneResponse {
    let mut out = LaneResponse::default();
    for l in (0..LANES).filter(|&l| active[l]) {
        let e = [
            strain[0].0[l],
            strain[1].0[l],
            strain[2].0[l],
            strain[3].0[l],
        ];
        let r = material.update(&e, &mut states[first + l * stride]);
        for c in 0..4 {
            out.stress[c].0[l] = r.stress[c];
        }
        out.strain_energy_density.0[l] = r.strain_energy_density;
        out.plastic_work_density.0[l] = r.plastic_work_density;
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

    #[inline(always)]
    pub fn stress_of(&self, e: &Strain) -> Stress {
        let lt = self.lambda * (e[0] + e[1] + e[2]);
        let m2 = 2.0 * self.mu;
        [
            lt + m2 * e[0],
            lt + m2 * e[1],
            lt + m2 * e[2],
            self.mu * e[3],
        ]
    }
}

/// `s : e / 2` with engineering shear strain.
#[inline(always)]
pub fn half_contraction(s: &Stress, e: &Strain) -> f64 {
    0.5 * (s[0] * e[0] + s[1] * e[1] + s[2] * e[2] + s[3] * e[3])
}

impl ConstitutiveModel for Elastic {
    type State = ();
    #[inline(always)]
    fn update(&self, strain: &Strain, _: &mut ()) -> PointResponse {
        let stress = self.stress_of(strain);
        PointResponse {
            stress,
            strain_energy_density: half_contraction(&stress, strain),
            plastic_work_density: 0.0,
        }
    }
    /// `stress_of` and `half_contraction` in lanes, in their order.
    #[inline(always)]
    fn update_lanes(
        &self,
        e: &[Lanes; 4],
        _: &mut [()],
        _: usize,
        _: usize,
        _: &Mask,
    ) -> LaneResponse {
        let lt = self.lambda * (e[0] + e[1] + e[2]);
        let m2 = 2.0 * self.mu;
        let s = [
            lt + m2 * e[0],
            lt + m2 * e[1],
            lt + m2 * e[2],
            self.mu * e[3],
        ];
        LaneResponse {
            stress: s,
            strain_energy_density: 0.5 * (s[0] * e[0] + s[1] * e[1] + s[2] * e[2] + s[3] * e[3]),
            plastic_work_density: Lanes::splat(0.0),
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
    pub fn new(yield_stress: f64, hardening: &Hardening, youngs_modulus: f64) -> FlowCurve {
        match hardening {
            Hardening::Linear { tangent_modulus } => FlowCurve {
                points: vec![(0.0, yield_stress)],
                // Uniaxial tangent E_t -> plastic modulus H = E E_t / (E - E_t).
                tail_slope: youngs_modulus * tangent_modulus / (youngs_modulus - tangent_modulus),
            },
            Hardening::Table(points) => FlowCurve {
                points: points.clone(),
                tail_slope: 0.0,
            },
        }
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

    /// `(initial yield stress Pa, plastic modulus Pa)` of a linear-hardening curve, `None` for
    /// a tabulated one.
    #[inline(always)]
    pub fn linear(&self) -> Option<(f64, f64)> {
        (self.points.len() == 1).then(|| (self.points[0].1, self.tail_slope))
    }

    /// Flow stress at equivalent plastic strain `k`, Pa.
    pub fn flow_stress(&self, k: f64) -> f64 {
        self.piece(k).0
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

/// Von Mises plasticity with isotropic hardening.
#[derive(Debug, Clone, PartialEq)]
pub struct VonMises {
    pub elastic: Elastic,
    pub flow: FlowCurve,
}

impl VonMises {
    fn elastic_strain(strain: &Strain, state: &PlasticState) -> Strain {
        let p = &state.plastic_strain;
        [
            strain[0] - p[0],
            strain[1] - p[1],
            strain[2] - p[2],
            strain[3] - 2.0 * p[3],
        ]
    }

    /// Solves `q - 3 mu dk - sigma_y(k + dk) = 0` piece by piece of the flow curve.
    fn plastic_increment(&self, q: f64, k: f64) -> f64 {
        let three_mu = 3.0 * self.elastic.mu;
        let mut dk = 0.0;
        loop {
            let (sy, h, next) = self.flow.piece(k + dk);
            let x = (q - three_mu * dk - sy) / (three_mu + h);
            match next {
                Some(b) if k + dk + x > b => dk = b - k,
                _ => return dk + x,
            }
        }
    }
}

impl ConstitutiveModel for VonMises {
    type State = PlasticState;

    /// Radial return from the trial deviator: the mean stress is elastic (von Mises flow is
    /// deviatoric), the deviator is scaled back to the flow stress. Elastic strain energy
    /// density `K tr^2 / 2 + q^2 / (6 mu)`, from the trial and returned `q` directly.
    #[inline(always)]
    fn update(&self, strain: &Strain, state: &mut PlasticState) -> PointResponse {
        let mu = self.elastic.mu;
        let bulk = self.elastic.lambda + 2.0 / 3.0 * mu;
        let p = &state.plastic_strain;
        let e = [strain[0] - p[0], strain[1] - p[1], strain[2] - p[2]];
        let trace = e[0] + e[1] + e[2];
        let third = trace / 3.0;
        let mut dev = [
            2.0 * mu * (e[0] - third),
            2.0 * mu * (e[1] - third),
            2.0 * mu * (e[2] - third),
            mu * (strain[3] - 2.0 * p[3]),
        ];
        let mean = bulk * trace;
        let volumetric_energy = 0.5 * mean * trace;
        let q2 =
            1.5 * (dev[0] * dev[0] + dev[1] * dev[1] + dev[2] * dev[2]) + 3.0 * dev[3] * dev[3];
        let k_old = state.eqps;
        let sy_old = self.flow.flow_stress(k_old);
        let mut plastic_work_density = 0.0;
        let mut q2_final = q2;
        // Compare squares: most points are elastic and need no square root.
        if q2 > sy_old * sy_old {
            let q = q2.sqrt();
            // (q2 > sy^2 and q <= sy can both hold within an ulp: never a negative increment.)
            let dk = self.plastic_increment(q, k_old).max(0.0);
            // Plastic strain increment dk * 3/2 dev/q (tensor shear).
            let r = 1.5 * dk / q;
            for (pk, d) in state.plastic_strain.iter_mut().zip(dev) {
                *pk += r * d;
            }
            let scale = 1.0 - 2.0 * mu * r; // q_new / q = 1 - 3 mu dk / q
            for d in &mut dev {
                *d *= scale;
            }
            q2_final = q2 * scale * scale;
            state.eqps = k_old + dk;
            plastic_work_density = 0.5 * (sy_old + self.flow.flow_stress(state.eqps)) * dk;
        }
        PointResponse {
            stress: [dev[0] + mean, dev[1] + mean, dev[2] + mean, dev[3]],
            strain_energy_density: volumetric_energy + q2_final / (6.0 * mu),
            plastic_work_density,
        }
    }

    /// The radial return of `update` in lanes (linear hardening; a tabulated curve runs
    /// `update` lane by lane): the trial for every lane, the return where any lane yields,
    /// selected per lane, and the state written back only for active lanes that yield. Every
    /// expression is `update`'s (and `plastic_increment`'s first piece) in the same order.
    #[inline(always)]
    fn update_lanes(
        &self,
        strain: &[Lanes; 4],
        states: &mut [PlasticState],
        first: usize,
        stride: usize,
        active: &Mask,
    ) -> LaneResponse {
        let Some((yield_stress, h)) = self.flow.linear() else {
            return update_each_lane(self, strain, states, first, stride, active);
        };
        let mu = self.elastic.mu;
        let bulk = self.elastic.lambda + 2.0 / 3.0 * mu;
        let (mut p, mut k_old) = ([Lanes::splat(0.0); 4], Lanes::splat(0.0));
        for l in (0..LANES).filter(|&l| active[l]) {
            let s = &states[first + l * stride];
            for c in 0..4 {
                p[c].0[l] = s.plastic_strain[c];
            }
            k_old.0[l] = s.eqps;
        }
        let e = [strain[0] - p[0], strain[1] - p[1], strain[2] - p[2]];
        let trace = e[0] + e[1] + e[2];
        let third = trace / 3.0;
        let mut dev = [
            2.0 * mu * (e[0] - third),
            2.0 * mu * (e[1] - third),
            2.0 * mu * (e[2] - third),
            mu * (strain[3] - 2.0 * p[3]),
        ];
        let mean = bulk * trace;
        let volumetric_energy = 0.5 * mean * trace;
        let q2 =
            1.5 * (dev[0] * dev[0] + dev[1] * dev[1] + dev[2] * dev[2]) + 3.0 * dev[3] * dev[3];
        let sy_old = yield_stress + h * k_old;
        let yields = q2.gt(sy_old * sy_old);
        let mut q2_final = q2;
        let mut plastic_work_density = Lanes::splat(0.0);
        if yields.iter().any(|&y| y) {
            let three_mu = 3.0 * mu;
            let q = q2.sqrt();
            // plastic_increment(q, k_old): its first (and only) piece, from dk = 0.
            let dk0 = 0.0;
            let sy = yield_stress + h * (k_old + dk0);
            let x = (q - three_mu * dk0 - sy) / (three_mu + h);
            let dk = (dk0 + x).max(0.0);
            let r = 1.5 * dk / q;
            let scale = 1.0 - 2.0 * mu * r;
            let eqps = k_old + dk;
            for c in 0..4 {
                p[c] = Lanes::select(&yields, p[c] + r * dev[c], p[c]);
                dev[c] = Lanes::select(&yields, dev[c] * scale, dev[c]);
            }
            q2_final = Lanes::select(&yields, q2 * scale * scale, q2);
            let work = 0.5 * (sy_old + (yield_stress + h * eqps)) * dk;
            plastic_work_density = Lanes::select(&yields, work, plastic_work_density);
            for l in (0..LANES).filter(|&l| active[l] && yields[l]) {
                states[first + l * stride] = PlasticState {
                    plastic_strain: [p[0].0[l], p[1].0[l], p[2].0[l], p[3].0[l]],
                    eqps: eqps.0[l],
                };
            }
        }
        LaneResponse {
            stress: [dev[0] + mean, dev[1] + mean, dev[2] + mean, dev[3]],
            strain_energy_density: volumetric_energy + q2_final / (6.0 * mu),
            plastic_work_density,
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
    /// point with `eqps == 0` still has zero plastic strain.
    #[inline(always)]
    fn is_virgin(&self, state: &PlasticState) -> bool {
        state.eqps == 0.0
    }
}

impl VonMises {
    pub fn new(spec: &MaterialSpec) -> Option<VonMises> {
        let p = spec.plasticity.as_ref()?;
        Some(VonMises {
            elastic: Elastic::new(spec.youngs_modulus, spec.poisson_ratio),
            flow: FlowCurve::new(p.yield_stress, &p.hardening, spec.youngs_modulus),
        })
    }
}

#[cfg(test)]
mod tests {
    //! Radial return against closed forms: uniaxial strain (plane strain, eps_xx only)
    //! loading with linear hardening, and the tabulated curve.
    use super::*;
    use approx::assert_relative_eq;

    fn steel(hardening: Hardening) -> VonMises {
        VonMises::new(&MaterialSpec {
            density: 7850.0,
            youngs_modulus: 200e9,
            poisson_ratio: 0.3,
            plasticity: Some(crate::scene::Plasticity {
                yield_stress: 250e6,
                hardening,
            }),
        })
        .unwrap()
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
            let r = m.update(&[e, 0.0, 0.0, 0.0], &mut state);
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
        let r = m.update(&[e, 0.0, 0.0, 0.0], &mut state);
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
        let r2 = m.update(&[e2, 0.0, 0.0, 0.0], &mut s2);
        let h = 5e9;
        let k = 2.0 * mu * 0.004 / (3.0 * mu + h);
        assert_relative_eq!(s2.eqps, k, max_relative = 1e-12);
        assert_relative_eq!(von_mises(&r2.stress), 250e6 + h * k, max_relative = 1e-12);
    }

    #[test]
    fn elastic_unloading_after_yield_keeps_the_plastic_strain() {
        let m = steel(Hardening::Linear {
            tangent_modulus: 1e9,
        });
        let mut state = PlasticState::default();
        m.update(&[0.01, 0.0, 0.0, 0.0], &mut state);
        let k = state.eqps;
        let r = m.update(&[0.0099, 0.0, 0.0, 0.0], &mut state);
        assert_eq!(state.eqps, k);
        assert_eq!(r.plastic_work_density, 0.0);
    }
}
