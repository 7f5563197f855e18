//! Rate-dependent von Mises plasticity (ALGORITHM.md section 4b): Cowper-Symonds and
//! Johnson-Cook with adiabatic heating, integrated by the radial return of
//! [`crate::physics::materials::material::radial_return`] with a rate-dependent consistency condition.
//!
//! Over a step `dt` the equivalent plastic strain grows by `dk` at the rate `dk / dt`
//! (backward Euler), and the returned von Mises stress `q - 3 mu dk` must equal the dynamic
//! flow stress:
//! - Cowper-Symonds: `q - 3 mu dk = sigma_y(k + dk) (1 + x)`, `x = (dk / (D dt))^(1/q)`,
//!   solved for `x` (in which the residual is concave for linear hardening, so Newton's
//!   method from the upper end of the bracket converges monotonically);
//! - Johnson-Cook: `q - 3 mu dk = [A + B (k + dk)^n] [1 + C ln(max(dk / (rate0 dt), 1))]
//!   Theta(T)`, solved for `dk`; below the reference rate the rate factor is 1.
//!
//! Both solves are Newton iterations safeguarded by bisection ([`solve_decreasing`]) on a
//! bracket whose ends have residuals of opposite signs. The temperature is explicit: the
//! softening `Theta(T) = 1 - T*^m` uses the temperature at the start of the step, and after
//! the step `T` rises by `beta w / (rho c)` with `w` the step's plastic work density.

use crate::input::scene::{Hardening, Material as MaterialSpec};
use crate::input::scene::{RateLaw, Thermal};
use crate::lanes::real::Real;
use crate::lanes::simd::{dispatch_out_of_line, Isa, Kernel, Lanes};
use crate::lanes::transcendental::{ln, pow};
use crate::physics::materials::material::{
    radial_return, ConstitutiveModel, Elastic, FlowCurve, FlowLaw, PlasticBatch, PlasticState,
    Response, Strain, Stress, VonMises,
};

/// The Newton iteration stops when its step is below this fraction of the initial bracket
/// (the error after that step is of the order of the step squared).
pub const NEWTON_TOLERANCE: f64 = 1e-12;
/// ... or when the residual is below this fraction of the trial stress: a few roundings of
/// the stresses it is the difference of, below which its sign is noise (Pa / Pa).
pub const RESIDUAL_TOLERANCE: f64 = 1e-14;
/// Iterations at most (bisection alone reaches the tolerance in about 40).
pub const NEWTON_ITERATIONS: usize = 100;

/// The static flow curve (rate factor 1, the initial temperature), Pa.
#[derive(Debug, Clone, PartialEq)]
pub enum StaticCurve {
    /// Linear or tabulated hardening.
    Piecewise(FlowCurve),
    /// `a + b k^n` (Johnson-Cook's A, B, n).
    Power { a: f64, b: f64, n: f64 },
}

impl StaticCurve {
    /// Flow stress (Pa) and its slope (Pa) at `k` per lane.
    #[inline(always)]
    fn stress_and_slope<R: Real>(&self, k: R) -> (R, R) {
        match self {
            StaticCurve::Piecewise(c) => match c.linear() {
                Some(l) => (k * l.modulus + l.yield_stress, R::splat(l.modulus)),
                None => (
                    k.map_lanes(|v| c.flow_stress(v)),
                    k.map_lanes(|v| c.slope(v)),
                ),
            },
            &StaticCurve::Power { a, b, n } => {
                // The slope n b k^(n-1) as n (b k^n) / k: a division in place of a second
                // power (an `exp`) per Newton iteration; at k = 0 its limit.
                let hardening = pow(k, n) * b;
                let positive = k.gt(R::splat(0.0));
                let slope = R::select(positive, hardening * n / k, R::splat(slope_at_zero(b, n)));
                (hardening + a, slope)
            }
        }
    }

    /// Flow stress at `k`, Pa.
    #[inline(always)]
    fn stress<R: Real>(&self, k: R) -> R {
        match self {
            &StaticCurve::Power { a, b, n } => pow(k, n) * b + a,
            StaticCurve::Piecewise(_) => self.stress_and_slope(k).0,
        }
    }
}

/// The slope `n b k^(n-1)` of `b k^n` at `k = 0` (Pa): infinite below `n = 1`, `b` at 1, 0
/// above (and 0 for `n = 0`, a constant curve).
fn slope_at_zero(b: f64, n: f64) -> f64 {
    if n == 0.0 || n > 1.0 {
        0.0
    } else if n == 1.0 {
        b
    } else {
        f64::INFINITY
    }
}

/// Per-point state: the rate-independent model's, the last step's plastic strain rate and
/// the temperature rise.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ViscoState {
    pub plastic: PlasticState,
    /// Equivalent plastic strain rate over the last step, 1/s.
    pub rate: f64,
    /// Temperature above the initial one, K.
    pub heating: f64,
    /// The static flow stress at `plastic.eqps`, Pa, and the softening `1 - T*^m` at
    /// `heating` (-), kept so that a point that does not flow computes neither again (each a
    /// `pow` for Johnson-Cook); a static flow stress of 0 (the default) says not yet computed
    /// ([`FlowCache`]).
    pub cache: FlowCache<f64>,
}

/// A point's static flow stress (Pa) and softening (-), functions of its equivalent plastic
/// strain and temperature rise that [`ViscoPlastic::update`] would otherwise compute at every
/// step: written whenever either changes (and where unknown), so that the values read are
/// the bits a computation would give. `static_flow` not above 0 means not yet computed (every
/// state starts so; a curve whose flow stress is 0 computes it each step).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct FlowCache<R> {
    /// Pa
    pub static_flow: R,
    /// -
    pub softening: R,
}

/// [`ViscoState`]s of one point of a batch of elements, in lanes.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ViscoBatch {
    pub plastic: PlasticBatch,
    /// 1/s
    pub rate: Lanes,
    /// K
    pub heating: Lanes,
    pub cache: FlowCache<Lanes>,
}

/// Von Mises plasticity with a rate law.
#[derive(Debug, Clone, PartialEq)]
pub struct ViscoPlastic {
    pub elastic: Elastic,
    pub curve: StaticCurve,
    pub law: RateLaw,
    /// Heating per unit plastic work density, `beta / (rho c)`, K m^3/J (0 without heating).
    heating_per_work: f64,
    /// The run's time step, s (set by the time loop before the first update).
    dt: f64,
    /// The instruction set the Newton solve is compiled for (the batched kernels').
    isa: Isa,
    /// Whether the static flow stress and the softening cost a `pow` (a power curve, or
    /// heating): then each point keeps them ([`FlowCache`]).
    caches_flow: bool,
}

impl ViscoPlastic {
    /// The model of `spec`; `None` unless its plasticity has a rate law.
    pub fn new(spec: &MaterialSpec) -> Option<ViscoPlastic> {
        let p = spec.plasticity.as_ref()?;
        let law = p.rate?;
        let curve = match p.hardening {
            Hardening::Power {
                coefficient,
                exponent,
            } => StaticCurve::Power {
                a: p.yield_stress,
                b: coefficient,
                n: exponent,
            },
            _ => StaticCurve::Piecewise(FlowCurve::new(
                p.yield_stress,
                &p.hardening,
                spec.youngs_modulus,
            )?),
        };
        let caches_flow = matches!(curve, StaticCurve::Power { .. }) || law.thermal().is_some();
        Some(ViscoPlastic {
            elastic: Elastic::new(spec.youngs_modulus, spec.poisson_ratio),
            curve,
            heating_per_work: law
                .thermal()
                .map_or(0.0, |t| t.taylor_quinney / (spec.density * t.specific_heat)),
            law,
            dt: f64::NAN,
            isa: Isa::Baseline,
            caches_flow,
        })
    }

    /// The static flow stress and softening at `k` and `heating` (K).
    #[inline(always)]
    fn flow_at<R: Real>(&self, k: R, heating: R) -> FlowCache<R> {
        FlowCache {
            static_flow: self.curve.stress(k),
            softening: self.softening(heating),
        }
    }

    /// [`ViscoPlastic::flow_at`] the point's `k` and `heating` before the step: from `cache`
    /// when every lane has it, else computed, and kept where `active` (the lanes whose state
    /// the step writes, as the scalar path does). [`ConstitutiveModel::update`] writes it
    /// again where `k` or the heating moved.
    #[inline(always)]
    fn flow_before<R: Real>(
        &self,
        cache: &mut FlowCache<Lanes>,
        (at, active): (usize, R::Mask),
        k: R,
        heating: R,
    ) -> FlowCache<R> {
        if !self.caches_flow {
            return self.flow_at(k, heating);
        }
        let zero = R::splat(0.0);
        let static_flow = R::of_batch(&cache.static_flow, at);
        if !R::any(R::not(static_flow.gt(zero))) {
            return FlowCache {
                static_flow,
                softening: R::of_batch(&cache.softening, at),
            };
        }
        let known = self.flow_at(k, heating);
        R::store(&mut cache.static_flow, at, known.static_flow, active);
        R::store(&mut cache.softening, at, known.softening, active);
        known
    }

    /// Johnson-Cook's `1 - T*^m` per lane of the temperature rise `heating` (K) above the
    /// initial temperature, `T* = (T0 + heating - Tr) / (Tm - Tr)` clamped to [0, 1]; 1 without
    /// heating.
    #[inline(always)]
    fn softening<R: Real>(&self, heating: R) -> R {
        match self.law.thermal() {
            None => R::splat(1.0),
            Some(&Thermal {
                initial_temperature,
                reference_temperature,
                melting_temperature,
                softening_exponent,
                ..
            }) => {
                let range = melting_temperature - reference_temperature;
                // Above the reference temperature before any heating (a preheated shot): T*
                // starts there. Without it the rise alone, as it always was (the same bits).
                let above = initial_temperature - reference_temperature;
                let rise = if above == 0.0 {
                    heating
                } else {
                    heating + R::splat(above)
                };
                let homologous = (rise / range).map_lanes(|t| t.clamp(0.0, 1.0));
                R::splat(1.0) - pow(homologous, softening_exponent)
            }
        }
    }

    /// Cowper-Symonds' increment `dk` of the rate-dependent consistency condition (module
    /// documentation) per lane, for the arguments `a` and the law's constants `law` ([`IncrementSolve`]); 0 where the trial
    /// stress does not exceed the static flow stress. Inlined into [`IncrementSolve::run`],
    /// which runs out of line, compiled once per instruction set and exponent kind
    /// ([`dispatch_out_of_line`]).
    #[inline(always)]
    fn cowper_symonds<R: Real, P: Exponent, L: Exponent>(
        &self,
        a: &IncrementArgs<R>,
        law: CowperSymondsLaw<P, L>,
    ) -> R {
        let IncrementArgs {
            q,
            k,
            static_flow,
            three_mu,
            ..
        } = *a;
        let CowperSymondsLaw {
            d,
            exponent,
            power,
            power_less,
        } = law;
        let running = q.gt(static_flow);
        let zero = R::splat(0.0);
        let scale = d * self.dt;
        // x at which the rate factor alone reaches q: the residual is negative there.
        let mut hi = R::select(running, q / static_flow - 1.0, R::splat(1.0));
        if exponent > LARGE_EXPONENT || scale > 1.0 {
            // x^q overflows for a large q and x > 1 (inf, then NaN in the Newton step),
            // and with D dt > 1 (a unit strain a step at x = 1) Newton's start lies
            // orders of magnitude above the root. dk = D dt x^q is at most the
            // rate-independent increment without hardening, (q - static_flow) / 3 mu,
            // where the residual is <= 0: bound x there.
            let bound = ((q - static_flow) * (1.0 / (three_mu * scale))).max(0.0);
            let bound = pow(bound, 1.0 / exponent);
            hi = R::select(R::and(running, hi.gt(bound)), bound, hi);
        }
        let residual = CowperSymondsResidual {
            curve: &self.curve,
            q,
            k,
            three_mu,
            scale,
            exponent,
            power_less,
        };
        let x = solve_decreasing((zero, hi), hi, running, q * RESIDUAL_TOLERANCE, residual);
        R::select(running, power.of_lanes(x) * scale, zero)
    }

    /// Johnson-Cook's increment `dk`, as [`ViscoPlastic::cowper_symonds`] (compiled once per
    /// instruction set).
    #[inline(always)]
    fn johnson_cook<R: Real>(&self, a: &IncrementArgs<R>, law: JohnsonCookLaw) -> R {
        let IncrementArgs {
            q,
            k,
            static_flow,
            three_mu,
            softening,
            last_increment,
            ..
        } = *a;
        let JohnsonCookLaw { c, reference_rate } = law;
        let running = q.gt(static_flow);
        let zero = R::splat(0.0);
        let slow = reference_rate * self.dt;
        // The rate-independent increment with no hardening bounds dk from above.
        let hi = R::select(running, (q - static_flow) * (1.0 / three_mu), R::splat(1.0));
        let residual = JohnsonCookResidual {
            curve: &self.curve,
            q,
            k,
            three_mu,
            c,
            slow,
            softening,
        };
        // Newton starts from the last step's increment (its rate times this step) where
        // that lies inside the bracket: near the root in steady flow.
        let dk = solve_decreasing(
            (zero, hi),
            last_increment,
            running,
            q * RESIDUAL_TOLERANCE,
            residual,
        );
        R::select(running, dk, zero)
    }
}

/// The arguments of a rate law's increment, to run it out of line: `law` says which solve
/// ([`CowperSymondsLaw`], [`JohnsonCookLaw`]), and each law (and, for Cowper-Symonds, each
/// exponent kind) is its own type, so each runs in its own function. Measured 2026-11-30 (an
/// Intel Xeon with full-width AVX-512 units): with both laws and both exponent kinds in one
/// function, LLVM vectorised the values they share (the trial stress, the flow stress, the
/// lanes still running) in pieces of 2, 2 and 4 lanes for all of them, because the general
/// exponent's `pow` after the Cowper-Symonds loop would not take whole registers (of the
/// function's 43 vector divisions 24 ran on 128-bit registers, 16 on 256-bit, 3 on 512-bit).
#[derive(Clone, Copy)]
struct IncrementSolve<'a, R, L> {
    args: IncrementArgs<'a, R>,
    /// The law's constants.
    law: L,
}

/// What every law's increment reads ([`IncrementSolve`]).
#[derive(Clone, Copy)]
struct IncrementArgs<'a, R> {
    model: &'a ViscoPlastic,
    /// Trial von Mises stress, Pa.
    q: R,
    /// Equivalent plastic strain at the step's start (-).
    k: R,
    /// The static flow stress at `k` and the point's temperature, Pa.
    static_flow: R,
    /// 3 mu, Pa.
    three_mu: f64,
    /// `1 - T*^m` per lane.
    softening: R,
    /// Where Johnson-Cook's Newton starts: the last step's rate times this step (-).
    last_increment: R,
}

/// Cowper-Symonds' constants: `D` (1/s), the exponent `q` (-) and `x^q`, `x^(q - 1)` as
/// [`Exponent`]s.
#[derive(Clone, Copy)]
struct CowperSymondsLaw<P, L> {
    d: f64,
    exponent: f64,
    power: P,
    power_less: L,
}

/// Johnson-Cook's rate constants: `C` (-) and the reference rate (1/s).
#[derive(Clone, Copy)]
struct JohnsonCookLaw {
    c: f64,
    reference_rate: f64,
}

impl<R: Real, P: Exponent, L: Exponent> Kernel for IncrementSolve<'_, R, CowperSymondsLaw<P, L>> {
    type Output = R;
    #[inline(always)]
    fn run(self) -> R {
        self.args.model.cowper_symonds(&self.args, self.law)
    }
}

impl<R: Real> Kernel for IncrementSolve<'_, R, JohnsonCookLaw> {
    type Output = R;
    #[inline(always)]
    fn run(self) -> R {
        self.args.model.johnson_cook(&self.args, self.law)
    }
}

/// A residual and its slope per lane, `(f(x), f'(x))`, for [`solve_decreasing`]: a trait
/// whose method is always inlined rather than a closure, which LLVM may leave out of line,
/// compiled for the baseline instruction set (measured 2026-11-29: the Johnson-Cook residual
/// as a closure ran on SSE2 out of line, 66 % of a copper Taylor bar's run).
pub trait Residual<R: Real> {
    fn eval(&self, x: R) -> (R, R);
}

/// Cowper-Symonds' consistency condition in `x = (dk / (D dt))^(1/q)` (module documentation).
struct CowperSymondsResidual<'a, R, L> {
    curve: &'a StaticCurve,
    /// Trial von Mises stress and equivalent plastic strain at the step's start (Pa, -).
    q: R,
    k: R,
    /// 3 mu, Pa.
    three_mu: f64,
    /// D dt (-).
    scale: f64,
    exponent: f64,
    /// `x^(q - 1)`.
    power_less: L,
}

impl<R: Real, L: Exponent> Residual<R> for CowperSymondsResidual<'_, R, L> {
    #[inline(always)]
    fn eval(&self, x: R) -> (R, R) {
        // dk = D dt x^q and d dk / d x = q D dt x^(q - 1), without a division.
        let lower = self.power_less.of_lanes(x);
        let dk = lower * x * self.scale;
        let (s, h) = self.curve.stress_and_slope(self.k + dk);
        let factor = x + 1.0;
        let f = self.q - dk * self.three_mu - s * factor;
        let ddk = lower * (self.exponent * self.scale);
        (f, R::splat(0.0) - (h * factor + self.three_mu) * ddk - s)
    }
}

/// Johnson-Cook's consistency condition in `dk` (module documentation).
struct JohnsonCookResidual<'a, R> {
    curve: &'a StaticCurve,
    /// Trial von Mises stress and equivalent plastic strain at the step's start (Pa, -).
    q: R,
    k: R,
    /// 3 mu, Pa.
    three_mu: f64,
    /// The rate coefficient C (-).
    c: f64,
    /// The reference rate times the step, rate0 dt (-): below it the rate factor is 1.
    slow: f64,
    /// `1 - T*^m` per lane.
    softening: R,
}

impl<R: Real> Residual<R> for JohnsonCookResidual<'_, R> {
    #[inline(always)]
    fn eval(&self, dk: R) -> (R, R) {
        let zero = R::splat(0.0);
        let (s, h) = self.curve.stress_and_slope(self.k + dk);
        let fast = dk.gt(R::splat(self.slow));
        let log = R::select(fast, ln(dk * (1.0 / self.slow)), zero);
        let factor = log * self.c + 1.0;
        let dfactor = R::select(fast, R::splat(self.c) / dk, zero);
        let f = self.q - dk * self.three_mu - s * factor * self.softening;
        let df = R::splat(-self.three_mu) - (h * factor + s * dfactor) * self.softening;
        (f, df)
    }
}

/// Cowper-Symonds exponents above this (or `D dt > 1`) bound the Newton bracket so that `x^q`
/// stays finite and Newton starts near the root (published q lie between about 1 and 15, D dt
/// below 0.01; the common laws keep their bits and cost).
const LARGE_EXPONENT: f64 = 32.0;

/// `x^p` for a fixed exponent `p` per lane: the same operations on both paths.
trait Exponent: Copy {
    fn of_lanes<R: Real>(self, x: R) -> R;
}

/// A whole exponent (up to 32), raised by products (Cowper-Symonds' usual q = 5: three
/// products instead of a `pow` per lane): exponentiation by squaring.
#[derive(Debug, Clone, Copy)]
struct Whole(u32);

impl Exponent for Whole {
    #[inline(always)]
    fn of_lanes<R: Real>(self, x: R) -> R {
        let Whole(mut n) = self;
        let (mut base, mut out) = (x, R::splat(1.0));
        while n > 0 {
            if n & 1 == 1 {
                out = out * base;
            }
            n >>= 1;
            if n > 0 {
                base = base * base;
            }
        }
        out
    }
}

/// Any exponent: [`Whole`] when `p` is a whole number up to 32, else [`pow`] on the lanes.
#[derive(Debug, Clone, Copy)]
enum Power {
    Whole(u32),
    Real(f64),
}

impl Power {
    fn of(p: f64) -> Power {
        if p.fract() == 0.0 && (0.0..=32.0).contains(&p) {
            Power::Whole(p as u32)
        } else {
            Power::Real(p)
        }
    }
}

impl Exponent for Power {
    #[inline(always)]
    fn of_lanes<R: Real>(self, x: R) -> R {
        match self {
            Power::Real(p) => pow(x, p),
            Power::Whole(n) => Whole(n).of_lanes(x),
        }
    }
}

/// The root of a decreasing `f` on `[lo, hi]` per `running` lane (`f(lo) > 0 >= f(hi)`):
/// Newton's method from `start` where it lies inside the bracket (else from `hi`), a bisection step wherever Newton's leaves the bracket, which
/// shrinks to the sign change every iteration. A lane stops when `|f|` is at most
/// `residual_floor`, when its step is below [`NEWTON_TOLERANCE`] times its initial bracket,
/// or after [`NEWTON_ITERATIONS`]; it then keeps its value while the other lanes go on, so
/// every lane does what the scalar path does for it.
#[inline(always)]
pub fn solve_decreasing<R: Real>(
    (mut lo, mut hi): (R, R),
    start: R,
    mut running: R::Mask,
    residual_floor: R,
    residual: impl Residual<R>,
) -> R {
    let tolerance = (hi - lo) * NEWTON_TOLERANCE;
    let mut x = R::select(R::and(start.gt(lo), hi.gt(start)), start, hi);
    for _ in 0..NEWTON_ITERATIONS {
        if !R::any(running) {
            break;
        }
        let (f, df) = residual.eval(x);
        running = R::and(running, f.map_lanes(f64::abs).gt(residual_floor));
        let positive = f.gt(R::splat(0.0));
        lo = R::select(positive, x, lo);
        hi = R::select(positive, hi, x);
        let newton = x - f / df;
        let inside = R::and(newton.gt(lo), hi.gt(newton));
        let next = R::select(inside, newton, (lo + hi) * 0.5);
        let step = (next - x).map_lanes(f64::abs);
        x = R::select(running, next, x);
        running = R::and(running, step.gt(tolerance));
    }
    x
}

/// The flow law the radial return asks, at one point's temperature.
struct RateFlow<'a, R> {
    model: &'a ViscoPlastic,
    /// The static flow stress at the point's equivalent plastic strain before the step, Pa.
    static_flow: R,
    /// `1 - T*^m` per lane.
    softening: R,
    /// The last step's plastic strain rate times this step (-): where Newton starts.
    last_increment: R,
}

impl<R: Real> FlowLaw<R> for RateFlow<'_, R> {
    /// The static flow stress at the point's temperature: flow starts above it. Asked at the
    /// point's `k` before the step only (by [`radial_return`]), whose value `static_flow` holds.
    #[inline(always)]
    fn flow_stress(&self, _k: R) -> R {
        self.static_flow * self.softening
    }
    #[inline(always)]
    fn plastic_increment(&self, q: R, k: R, flow_at_k: R, three_mu: f64) -> R {
        let args = IncrementArgs {
            model: self.model,
            q,
            k,
            static_flow: flow_at_k,
            three_mu,
            softening: self.softening,
            last_increment: self.last_increment,
        };
        let isa = self.model.isa;
        match self.model.law {
            RateLaw::CowperSymonds { d, q: exponent } => {
                match (Power::of(exponent), Power::of(exponent - 1.0)) {
                    // The usual whole exponents in a function of their own, on whole registers.
                    (Power::Whole(p), Power::Whole(l)) => {
                        let law = CowperSymondsLaw {
                            d,
                            exponent,
                            power: Whole(p),
                            power_less: Whole(l),
                        };
                        dispatch_out_of_line(isa, IncrementSolve { args, law })
                    }
                    (power, power_less) => {
                        let law = CowperSymondsLaw {
                            d,
                            exponent,
                            power,
                            power_less,
                        };
                        dispatch_out_of_line(isa, IncrementSolve { args, law })
                    }
                }
            }
            RateLaw::JohnsonCook {
                c, reference_rate, ..
            } => {
                let law = JohnsonCookLaw { c, reference_rate };
                dispatch_out_of_line(isa, IncrementSolve { args, law })
            }
        }
    }
    /// `q_new dk`: the returned stress (the dynamic flow stress) on the increment, the
    /// backward-Euler dissipation.
    #[inline(always)]
    fn plastic_work(&self, _sy_old: R, _k_new: R, dk: R, q_new: R) -> R {
        q_new * dk
    }
}

impl ConstitutiveModel for ViscoPlastic {
    type State = ViscoState;
    type Batch = ViscoBatch;

    fn state_of(batch: &ViscoBatch, l: usize) -> ViscoState {
        ViscoState {
            plastic: VonMises::state_of(&batch.plastic, l),
            rate: batch.rate.0[l],
            heating: batch.heating.0[l],
            cache: FlowCache {
                static_flow: batch.cache.static_flow.0[l],
                softening: batch.cache.softening.0[l],
            },
        }
    }

    fn set_state(batch: &mut ViscoBatch, l: usize, state: ViscoState) {
        VonMises::set_state(&mut batch.plastic, l, state.plastic);
        batch.rate.0[l] = state.rate;
        batch.heating.0[l] = state.heating;
        batch.cache.static_flow.0[l] = state.cache.static_flow;
        batch.cache.softening.0[l] = state.cache.softening;
    }

    /// The radial return with [`RateFlow`], then the step's rate and heating.
    #[inline(always)]
    fn update<R: Real>(
        &self,
        strain: &[R; 4],
        batch: &mut ViscoBatch,
        at: usize,
        active: R::Mask,
    ) -> Response<R> {
        let heating = R::of_batch(&batch.heating, at);
        let k_old = R::of_batch(&batch.plastic.eqps, at);
        let known = self.flow_before(&mut batch.cache, (at, active), k_old, heating);
        let flow = RateFlow {
            model: self,
            static_flow: known.static_flow,
            softening: known.softening,
            last_increment: R::of_batch(&batch.rate, at) * self.dt,
        };
        let r = radial_return(
            &self.elastic,
            &flow,
            strain,
            &mut batch.plastic,
            (at, active),
        );
        let k_new = R::of_batch(&batch.plastic.eqps, at);
        R::store(
            &mut batch.rate,
            at,
            (k_new - k_old) * (1.0 / self.dt),
            active,
        );
        let mut heating_after = heating;
        if self.heating_per_work > 0.0 {
            heating_after = heating + r.plastic_work_density * self.heating_per_work;
            R::store(&mut batch.heating, at, heating_after, active);
        }
        if self.caches_flow {
            // k or the heating moved (a lane may flow with no work at a melted point).
            let still = R::and(
                R::not(k_new.gt(k_old)),
                R::not(r.plastic_work_density.gt(R::splat(0.0))),
            );
            let flowed = R::and(active, R::not(still));
            if R::any(flowed) {
                let after = self.flow_at(k_new, heating_after);
                R::store(&mut batch.cache.static_flow, at, after.static_flow, active);
                R::store(&mut batch.cache.softening, at, after.softening, active);
            }
        }
        r
    }

    fn stress(&self, strain: &Strain, state: &ViscoState) -> Stress {
        self.elastic
            .stress_of(&VonMises::elastic_strain(strain, &state.plastic))
    }

    fn equivalent_plastic_strain(&self, state: &ViscoState) -> f64 {
        state.plastic.eqps
    }

    fn elastic(&self) -> &Elastic {
        &self.elastic
    }

    /// The static flow stress before any plastic strain, at the initial temperature (below
    /// the unsoftened one for a preheated shot, `initial_temperature > reference_temperature`).
    fn virgin_yield_stress(&self) -> Option<f64> {
        let unsoftened = self.curve.stress(0.0);
        Some(match self.law.thermal() {
            Some(t) if t.initial_temperature != t.reference_temperature => {
                unsoftened * self.softening(0.0)
            }
            _ => unsoftened,
        })
    }

    /// As [`VonMises`]: heating only comes with plastic strain.
    #[inline(always)]
    fn virgin<R: Real>(&self, batch: &ViscoBatch, at: usize) -> R::Mask {
        R::not(R::of_batch(&batch.plastic.eqps, at).gt(R::splat(0.0)))
    }

    fn set_time_step(&mut self, dt: f64) {
        self.dt = dt;
    }

    fn set_isa(&mut self, isa: Isa) {
        self.isa = isa;
    }

    fn plastic_strain_rate(&self, state: &ViscoState) -> Option<f64> {
        Some(state.rate)
    }

    fn temperature(&self, state: &ViscoState) -> Option<f64> {
        self.law
            .thermal()
            .map(|t| t.initial_temperature + state.heating)
    }
}

#[cfg(test)]
mod tests {
    //! The rate-dependent return at one point against closed forms: the steady flow stress of
    //! constant-rate uniaxial strain (Cowper-Symonds and Johnson-Cook), the work identity, the
    //! Newton iteration's quadratic convergence, and the scalar path's bits in lanes.
    use super::*;
    use crate::input::rate_law::johnson_cook_42crmo4;
    use crate::input::scene::Plasticity;
    use crate::input::scene::{RateLaw, Thermal};
    use approx::assert_relative_eq;

    fn steel(hardening: Hardening, yield_stress: f64, law: RateLaw, dt: f64) -> ViscoPlastic {
        let mut m = ViscoPlastic::new(&MaterialSpec {
            density: 7850.0,
            youngs_modulus: 200e9,
            poisson_ratio: 0.3,
            plasticity: Some(Plasticity {
                yield_stress,
                hardening,
                rate: Some(law),
            }),
        })
        .expect("a rate-dependent material");
        m.set_time_step(dt);
        m
    }

    fn update(m: &ViscoPlastic, strain: &Strain, state: &mut ViscoState) -> Response<f64> {
        let mut batch = ViscoBatch::default();
        ViscoPlastic::set_state(&mut batch, 0, *state);
        let r = m.update(strain, &mut batch, 0, true);
        *state = ViscoPlastic::state_of(&batch, 0);
        r
    }

    /// Uniaxial strain at `rate` (1/s) for `steps` steps of `dt`: the last response, state,
    /// and the stress power's work minus the elastic energy and plastic work (J/m^3).
    fn drive(
        m: &ViscoPlastic,
        rate: f64,
        dt: f64,
        steps: usize,
    ) -> (Response<f64>, ViscoState, f64) {
        let mut state = ViscoState::default();
        let (mut work, mut plastic) = (0.0, 0.0);
        let mut last = Response::default();
        for i in 1..=steps {
            let e = rate * dt * i as f64;
            let r = update(m, &[e, 0.0, 0.0, 0.0], &mut state);
            work += 0.5 * (last.stress[0] + r.stress[0]) * rate * dt;
            plastic += r.plastic_work_density;
            last = r;
        }
        let gap = work - last.strain_energy_density - plastic;
        (last, state, gap / work)
    }

    #[test]
    fn cowper_symonds_reaches_its_steady_flow_stress() {
        let (d, q) = (40.4, 5.0);
        let law = RateLaw::CowperSymonds { d, q };
        let h = Hardening::Linear {
            tangent_modulus: 2e9,
        };
        for rate in [1.0, 10.0, 100.0] {
            let dt = 2e-4 / rate; // 0.02 % strain per step, to 5 %
            let m = steel(h.clone(), 250e6, law, dt);
            let (r, s, gap) = drive(&m, rate, dt, 250);
            // Uniaxial strain, q = 2 mu eps - 3 mu k; in steady flow q = sigma_y(k) g with a
            // constant factor g, so H k' g = 2 mu eps' - 3 mu k'.
            let (mu, hm) = (m.elastic.mu, 200e9 * 2e9 / (200e9 - 2e9));
            let flow = 250e6 + hm * s.plastic.eqps;
            let g = |kdot: f64| 1.0 + (kdot / d).powf(1.0 / q);
            let mut kdot = 2.0 / 3.0 * rate;
            for _ in 0..50 {
                kdot = 2.0 * mu * rate / (3.0 * mu + hm * g(kdot));
            }
            let q_now = super::super::material::von_mises(&r.stress);
            assert_relative_eq!(q_now, flow * g(kdot), max_relative = 1e-3);
            assert_relative_eq!(s.rate, kdot, max_relative = 1e-3);
            assert!(gap.abs() < 1e-3, "work identity {gap}");
        }
    }

    /// DynELA's 42CrMo4 with heating ([`johnson_cook_42crmo4`]: A = 806 MPa, B = 614 MPa,
    /// n = 0.168, C = 0.0089 at 1 1/s, Taylor-Quinney 0.9, c = 460 J/(kg K), m = 1.1), in
    /// [`steel`] (7850 kg/m^3), at the step `dt` (s).
    fn heated_steel(dt: f64) -> ViscoPlastic {
        let ((a, b, n), law) = johnson_cook_42crmo4();
        let power = Hardening::Power {
            coefficient: b,
            exponent: n,
        };
        steel(power, a, law, dt)
    }

    #[test]
    fn johnson_cook_reaches_its_steady_flow_stress_and_heats() {
        let (a, b, n, c, rate0) = (806e6, 614e6, 0.168, 0.0089, 1.0);
        let power = Hardening::Power {
            coefficient: b,
            exponent: n,
        };
        for rate in [1.0, 10.0, 100.0] {
            let dt = 2e-4 / rate;
            let law = RateLaw::JohnsonCook {
                c,
                reference_rate: rate0,
                thermal: None,
            };
            let m = steel(power.clone(), a, law, dt);
            let (r, s, gap) = drive(&m, rate, dt, 250);
            let k = s.plastic.eqps;
            let steady = (a + b * k.powf(n)) * (1.0 + c * (s.rate / rate0).max(1.0).ln());
            let q_now = super::super::material::von_mises(&r.stress);
            assert_relative_eq!(q_now, steady, max_relative = 1e-9);
            assert!(
                s.rate > 0.5 * rate && s.rate < 2.0 / 3.0 * rate,
                "{}",
                s.rate
            );
            assert!(gap.abs() < 1e-3, "work identity {gap}");
        }
        // Heating: the temperature rise is beta / (rho c) times the plastic work density.
        let dt = 2e-6;
        let m = heated_steel(dt);
        let mut state = ViscoState::default();
        let mut work = 0.0;
        for i in 1..=250 {
            let r = update(&m, &[100.0 * dt * i as f64, 0.0, 0.0, 0.0], &mut state);
            work += r.plastic_work_density;
        }
        assert_relative_eq!(
            state.heating,
            0.9 * work / (7850.0 * 460.0),
            max_relative = 1e-12
        );
        assert!(state.heating > 1.0, "{}", state.heating);
        assert_relative_eq!(m.temperature(&state).unwrap(), 293.15 + state.heating);
    }

    /// The kept static flow stress and softening ([`FlowCache`]) give the bits of computing
    /// them at every step: a Johnson-Cook point with heating is loaded, unloaded into reversed
    /// flow, held, and reloaded (flowing, elastic and flowing again, hot), once with the state
    /// as the model leaves it and once with its cache cleared before every step; every
    /// response and state (the cache aside) are equal to the bit. Fails for a cache not
    /// written after a step that flows (the point then flows on from its first flow stress:
    /// tried, the responses differ from step 22 on, the second step past yield).
    #[test]
    fn the_kept_flow_stress_is_the_computed_one() {
        let m = heated_steel(1e-6);
        // Strain (-): up to 1.2e-2 (three times the yield strain), down to -1.2e-2, held,
        // then up to 2e-2.
        let path = |i: usize| -> f64 {
            match i {
                0..=60 => 2e-4 * i as f64,
                61..=120 => 1.2e-2 - 4e-4 * (i - 60) as f64,
                121..=140 => -1.2e-2,
                _ => -1.2e-2 + 4e-4 * (i - 140) as f64,
            }
        };
        let (mut kept, mut cleared) = (ViscoState::default(), ViscoState::default());
        let mut flowed = 0;
        for i in 1..=220 {
            let strain = [path(i), -0.3 * path(i), 0.0, 0.5 * path(i)];
            let a = update(&m, &strain, &mut kept);
            cleared.cache = FlowCache::default();
            let b = update(&m, &strain, &mut cleared);
            assert_eq!(a, b, "step {i}");
            let without_cache = |s: &ViscoState| ViscoState {
                cache: FlowCache::default(),
                ..*s
            };
            assert_eq!(without_cache(&kept), without_cache(&cleared), "step {i}");
            flowed += usize::from(a.plastic_work_density > 0.0);
        }
        // The path flows, unloads and flows again (a path that never flows tests nothing).
        assert!(flowed > 60 && kept.heating > 0.0, "{flowed} {kept:?}");
    }

    /// A preheated point (60 K above the reference temperature, `T*_0 = 60 / 150 = 0.4`,
    /// m = 1) yields at `A (1 - 0.4)`: its elastic screen's stress and the first plastic step
    /// of a trial stress between that and A. Fails for a screen at the unsoftened A, or a
    /// softening that reads the rise alone (no yield below A at the start).
    #[test]
    fn a_preheated_point_yields_at_its_softened_stress() {
        let a = 250e6;
        let hot = |reference_temperature: f64| {
            let thermal = Thermal {
                initial_temperature: 353.15,
                reference_temperature,
                melting_temperature: 443.15,
                specific_heat: 460.0,
                taylor_quinney: 0.9,
                softening_exponent: 1.0,
            };
            let law = RateLaw::JohnsonCook {
                c: 0.0,
                reference_rate: 1.0,
                thermal: Some(thermal),
            };
            let power = Hardening::Power {
                coefficient: 0.0,
                exponent: 1.0,
            };
            steel(power, a, law, 1e-6)
        };
        let m = hot(293.15);
        // A (1 - T*_0) with T*_0 = 60 / 150 = 0.4: the same product in another order, a few
        // ulp (2.2e-16 each) apart at most.
        assert_relative_eq!(
            m.virgin_yield_stress().unwrap(),
            0.6 * a,
            max_relative = 1e-15
        );
        assert_eq!(hot(353.15).virgin_yield_stress(), Some(a));
        // Uniaxial strain whose elastic von Mises stress is 0.8 A (2 mu e = q): plastic now.
        let mu = m.elastic.mu;
        let mut state = ViscoState::default();
        let r = update(&m, &[0.8 * a / (2.0 * mu), 0.0, 0.0, 0.0], &mut state);
        assert!(state.plastic.eqps > 0.0, "{state:?}");
        let q = super::super::material::von_mises(&r.stress);
        // Measured: exactly 0.6 A (the return lands on the softened surface, the heating of
        // this step acts on the next); the bound is the Newton's own relative tolerance.
        assert_relative_eq!(q, 0.6 * a, max_relative = NEWTON_TOLERANCE);
    }

    /// Johnson-Cook's static curve `a + b k^n` and its slope `n (b k^n) / k` (the Newton
    /// iteration's derivative) against the derivative of `f64::powf` by central differences
    /// at h = 1e-6 k, and at `k = 0` the limits. Fails for a slope
    /// that keeps `a` in the quotient, forgets the division (`n b k^n`) or the factor `n`.
    #[test]
    fn the_power_curve_slope_is_the_derivative_of_its_stress() {
        for (a, b, n) in [
            (806e6, 614e6, 0.168),
            (90e6, 292e6, 0.31),
            (1e8, 1e9, 1.0),
            (1e8, 1e9, 2.5),
        ] {
            let curve = StaticCurve::Power { a, b, n };
            for k in [1e-8, 1e-4, 0.01, 0.3, 2.0] {
                let (s, slope) = curve.stress_and_slope(k);
                // The lanes' pow is within 2 + 2 |n ln k| ulp of powf (lanes/transcendental.rs):
                // at most ~8 ulp (1.8e-15) on these k and n; measured at most 1.5e-16.
                assert_relative_eq!(s, a + b * k.powf(n), max_relative = 2e-15);
                let h = 1e-6 * k;
                let numeric = b * ((k + h).powf(n) - (k - h).powf(n)) / (2.0 * h);
                // The difference quotient's round-off, eps / (n h / k) = 1.3e-9 at n = 0.168,
                // dominates its truncation (~1e-12): about 8x that bound; measured at most 1.8e-10.
                assert_relative_eq!(slope, numeric, max_relative = 1e-8);
            }
            let at_zero = curve.stress_and_slope(0.0_f64).1;
            let limit = if n < 1.0 {
                f64::INFINITY
            } else if n == 1.0 {
                b
            } else {
                0.0
            };
            assert_eq!(at_zero, limit, "n = {n}");
        }
    }

    /// The Newton iteration on one Cowper-Symonds point: the error falls quadratically
    /// (`e_{i+1} <= C e_i^2` with a bounded C) until round-off, in at most 6 iterations.
    #[test]
    fn newton_converges_quadratically() {
        let (q_tr, k, three_mu, sigma0, h) = (3.6e8, 0.01, 3.0 * 79.6e9, 1.76e8, 4.2e9);
        let (scale, p) = (40.4 * 1.36e-7, 5.0);
        let eval = |x: f64| {
            let dk = x.powf(p) * scale;
            let s = sigma0 + h * (k + dk);
            let f = q_tr - dk * three_mu - s * (1.0 + x);
            (f, -(h * (1.0 + x) + three_mu) * dk * p / x - s)
        };
        let hi = q_tr / (sigma0 + h * k) - 1.0;
        struct Eval<F>(F);
        impl<F: Fn(f64) -> (f64, f64)> Residual<f64> for Eval<F> {
            fn eval(&self, x: f64) -> (f64, f64) {
                (self.0)(x)
            }
        }
        let root = solve_decreasing((0.0, hi), hi, true, q_tr * RESIDUAL_TOLERANCE, Eval(eval));
        assert!(eval(root).0.abs() <= q_tr * 1e-14);
        // The iterates by hand (Newton from hi stays in the bracket for this concave residual).
        let mut x = hi;
        let mut errors = Vec::new();
        for _ in 0..6 {
            errors.push((x - root).abs());
            let (f, df) = eval(x);
            x -= f / df;
        }
        let resolved: Vec<&[f64]> = errors.windows(2).filter(|w| w[1] > 1e-14).collect();
        assert!(resolved.len() >= 1, "{errors:?}");
        for w in resolved {
            assert!(w[1] <= 10.0 * w[0] * w[0], "not quadratic: {errors:?}");
        }
        assert!(errors[4] < 1e-14, "{errors:?}");
    }

    #[test]
    fn a_huge_d_recovers_the_rate_independent_return() {
        // 1e100 and 1e300 (D dt > 1) ran into NaN (the bad-input suite, issue 28): Newton
        // started where D dt x^q is ~1e90 strain a step.
        for d in [1e30, 1e100, 1e300] {
            rate_independent_limit(RateLaw::CowperSymonds { d, q: 5.0 });
        }
    }

    #[test]
    fn a_huge_q_recovers_the_rate_independent_return_times_two() {
        // (rate / D)^(1/q) -> 1 for any flow: the static curve doubled (yield stress and plastic
        // modulus H = E Et / (E - Et) twice). q = 1000 and 1e4 ran into NaN (x^q overflowed in
        // the Newton step; the bad-input suite, issue 28).
        let (e, et) = (200e9, 2e9);
        let h2 = 2.0 * e * et / (e - et);
        let doubled = crate::physics::materials::material::VonMises::new(&MaterialSpec {
            density: 7850.0,
            youngs_modulus: e,
            poisson_ratio: 0.3,
            plasticity: Some(Plasticity {
                yield_stress: 500e6,
                hardening: Hardening::Linear {
                    tangent_modulus: h2 * e / (e + h2),
                },
                rate: None,
            }),
        })
        .unwrap();
        for q in [1e3, 1e4] {
            let h = Hardening::Linear {
                tangent_modulus: et,
            };
            let m = steel(h, 250e6, RateLaw::CowperSymonds { d: 40.0, q }, 1e-5);
            let (mut s, mut batch) = (ViscoState::default(), PlasticBatch::default());
            for i in 1..=100 {
                let strain = [1e-4 * i as f64, 0.0, 0.0, 0.0];
                let a = update(&m, &strain, &mut s);
                let b = doubled.update(&strain, &mut batch, 0, true);
                assert_relative_eq!(a.stress[0], b.stress[0], max_relative = 2e-3);
            }
        }
    }

    fn rate_independent_limit(law: RateLaw) {
        let h = Hardening::Linear {
            tangent_modulus: 2e9,
        };
        let dt = 1e-5;
        let m = steel(h.clone(), 250e6, law, dt);
        let ri = crate::physics::materials::material::VonMises::new(&MaterialSpec {
            density: 7850.0,
            youngs_modulus: 200e9,
            poisson_ratio: 0.3,
            plasticity: Some(Plasticity {
                yield_stress: 250e6,
                hardening: h,
                rate: None,
            }),
        })
        .unwrap();
        let (mut s, mut batch) = (ViscoState::default(), PlasticBatch::default());
        for i in 1..=100 {
            let e = [1e-4 * i as f64, 0.0, 0.0, 0.0];
            let a = update(&m, &e, &mut s);
            let b = ri.update(&e, &mut batch, 0, true);
            assert_relative_eq!(a.stress[0], b.stress[0], max_relative = 1e-6);
        }
    }
}
