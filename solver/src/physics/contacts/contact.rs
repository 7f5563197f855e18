//! The Hertz line-contact law (eq. 4) with its hidden length made explicit, and the solve of
//! eq. (21) for the contact force at the end of a step.
//!
//! Every variant has the form `alpha(P) = P (a - b ln P)` with `P = F / W` the force per unit
//! width (N/m), `alpha` the indentation (m), `b > 0`. `alpha` rises from 0 to its maximum at
//! `P* = exp(a/b - 1)` and falls after it: beyond `P*` the law has no physical root.

use crate::input::scene::{ContactLawChoice, Impactor, Material};

/// `alpha(P) = P (a - b ln P)` in SI units (P in N/m, alpha in m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineContactLaw {
    /// m^2/N
    pub a: f64,
    /// m^2/N
    pub b: f64,
    /// Plate width W, m (converts total force to force per unit width).
    pub width: f64,
}

/// `(1 - nu^2) / (pi E)`, m^2/N.
fn compliance(youngs_modulus: f64, poisson_ratio: f64) -> f64 {
    (1.0 - poisson_ratio * poisson_ratio) / (std::f64::consts::PI * youngs_modulus)
}

impl LineContactLaw {
    /// The law a scene asks for, between its impactor and its plate material.
    pub fn new(impactor: &Impactor, plate: &Material, width: f64) -> LineContactLaw {
        let r = impactor.nose_radius;
        let chi_s = compliance(impactor.youngs_modulus, impactor.poisson_ratio);
        let (a, b) = match impactor.contact_law {
            ContactLawChoice::Paper { length_unit } => {
                // Eq. (4) as printed: chi_p = 1 / (pi E), no (1 - nu^2).
                let c = chi_s + 1.0 / (std::f64::consts::PI * plate.youngs_modulus);
                (c * (1.0 + (length_unit * length_unit / (r * c)).ln()), c)
            }
            ContactLawChoice::Johnson { datum_depth } => {
                let nu = plate.poisson_ratio;
                let chi_p = compliance(plate.youngs_modulus, nu);
                // Hertz half-width a_H^2 = 4 P r / (pi E*), pi E* = 1 / (chi_s + chi_p).
                let ln_ah2_over_p = (4.0 * r * (chi_s + chi_p)).ln();
                let impactor_part = chi_s * (2.0 * (4.0 * r).ln() - ln_ah2_over_p - 1.0);
                let plate_part =
                    chi_p * (2.0 * (2.0 * datum_depth).ln() - ln_ah2_over_p - nu / (1.0 - nu));
                (impactor_part + plate_part, chi_s + chi_p)
            }
        };
        LineContactLaw { a, b, width }
    }

    /// Indentation for a force per unit width `p` >= 0, m.
    #[inline]
    pub fn alpha(&self, p: f64) -> f64 {
        if p <= 0.0 {
            0.0
        } else {
            p * (self.a - self.b * p.ln())
        }
    }

    /// d alpha / dP, m^2/N (infinite at P = 0).
    #[inline]
    pub fn alpha_slope(&self, p: f64) -> f64 {
        self.a - self.b - self.b * p.ln()
    }

    /// Force per unit width at the law's maximum, N/m.
    pub fn max_force_per_width(&self) -> f64 {
        (self.a / self.b - 1.0).exp()
    }

    /// Largest indentation the law can give, m.
    pub fn max_indentation(&self) -> f64 {
        self.alpha(self.max_force_per_width())
    }

    /// Stored contact energy `W int_0^alpha P d alpha = W (P alpha / 2 - b P^2 / 4)` for a
    /// total force `force` (N), J.
    pub fn energy(&self, force: f64) -> f64 {
        if force <= 0.0 {
            return 0.0;
        }
        let p = force / self.width;
        self.width * (0.5 * p * self.alpha(p) - 0.25 * self.b * p * p)
    }

    /// Total force (N) for an indentation `alpha` (m) on the physical branch; `None` beyond
    /// the law's maximum.
    pub fn force_for(&self, alpha: f64) -> Option<f64> {
        solve_monotone(self, 0.0, alpha)
    }
}

/// Why eq. (21) has no root.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BeyondMaximum {
    /// The indentation the step asks for, m.
    pub required: f64,
    /// The largest the law can give (plus the impactor's own response), m.
    pub available: f64,
    /// Force at the law's maximum, N (whole width).
    pub max_force: f64,
}

/// Solves eq. (21), `alpha(F/W) + F dt^2/(6m) = alpha_free`, for the total force `F >= 0`.
///
/// `alpha_free = delta_S + v dt - F_n dt^2/(3m) - delta_C` is the indentation the step
/// gives with no new force. `alpha_free <= 0` is the exact zero branch (the bodies separate).
pub fn solve_contact_force(
    law: &LineContactLaw,
    compliance_of_impactor: f64,
    alpha_free: f64,
) -> Result<f64, BeyondMaximum> {
    if alpha_free <= 0.0 {
        return Ok(0.0);
    }
    let g = ImpactorCoupledLaw {
        law,
        extra: compliance_of_impactor,
    };
    solve_monotone(&g, 0.0, alpha_free).ok_or_else(|| {
        let max_force = law.max_force_per_width() * law.width;
        BeyondMaximum {
            required: alpha_free,
            available: g.value(max_force),
            max_force,
        }
    })
}

/// A function of the total force that increases from 0 on `[0, upper]`.
trait MonotoneInForce {
    fn value(&self, force: f64) -> f64;
    fn slope(&self, force: f64) -> f64;
    fn upper(&self) -> f64;
}

impl MonotoneInForce for LineContactLaw {
    fn value(&self, f: f64) -> f64 {
        self.alpha(f / self.width)
    }
    fn slope(&self, f: f64) -> f64 {
        self.alpha_slope(f / self.width) / self.width
    }
    fn upper(&self) -> f64 {
        self.max_force_per_width() * self.width
    }
}

/// The law plus the impactor's own linear response `F dt^2 / (6m)` of eq. (21).
struct ImpactorCoupledLaw<'a> {
    law: &'a LineContactLaw,
    /// dt^2 / (6 m), m/N
    extra: f64,
}

impl MonotoneInForce for ImpactorCoupledLaw<'_> {
    fn value(&self, f: f64) -> f64 {
        self.law.value(f) + self.extra * f
    }
    fn slope(&self, f: f64) -> f64 {
        self.law.slope(f) + self.extra
    }
    fn upper(&self) -> f64 {
        self.law.upper()
    }
}

/// Maximum iterations of the safeguarded Newton solve (bisection alone needs < 1100 to
/// exhaust a double-precision bracket; Newton usually takes < 10).
const MAX_ITERATIONS: usize = 200;

/// Root of `g(F) = target` on `[lo, g.upper()]` by Newton's method safeguarded with
/// bisection (rtsafe). `None` when the target is beyond `g(upper)`.
fn solve_monotone(g: &impl MonotoneInForce, lo: f64, target: f64) -> Option<f64> {
    if target <= 0.0 {
        return Some(0.0);
    }
    let upper = g.upper();
    let at_upper = g.value(upper) - target;
    if at_upper < 0.0 {
        return None;
    }
    if at_upper == 0.0 {
        return Some(upper);
    }
    let (mut lo, mut hi) = (lo, upper);
    // Start from the linearisation around the secant through (0, 0) and (upper, g(upper)).
    let mut f = (target / (at_upper + target) * upper).clamp(lo, hi);
    for _ in 0..MAX_ITERATIONS {
        let r = g.value(f) - target;
        if r == 0.0 {
            return Some(f);
        }
        if r < 0.0 {
            lo = f;
        } else {
            hi = f;
        }
        let slope = g.slope(f);
        let newton = f - r / slope;
        let next = if slope.is_finite() && slope > 0.0 && newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if (next - f).abs() <= 4.0 * f64::EPSILON * next.abs() || hi - lo <= f64::EPSILON * hi {
            return Some(next);
        }
        f = next;
    }
    Some(f)
}

#[cfg(test)]
mod tests {
    //! Against closed forms: the law inverted and re-evaluated, its maximum, unit
    //! consistency of the hidden length, and the analytic slope against finite differences.
    use super::*;
    use crate::input::scene::{ContactLawChoice, MidSpanNode};

    fn impactor(contact_law: ContactLawChoice) -> Impactor {
        Impactor {
            mass: 18.0,
            velocity: 10.0,
            nose_radius: 0.01,
            youngs_modulus: 207e9,
            poisson_ratio: 0.3,
            contact_law,
            indentation_datum: MidSpanNode::MidPlane,
            force_node: MidSpanNode::MidPlane,
        }
    }

    fn plate() -> Material {
        Material {
            density: 7850.0,
            youngs_modulus: 207e9,
            poisson_ratio: 0.3,
            plasticity: None,
        }
    }

    fn laws() -> Vec<LineContactLaw> {
        [
            ContactLawChoice::Paper { length_unit: 1.0 },
            ContactLawChoice::Paper { length_unit: 1e-3 },
            ContactLawChoice::Johnson { datum_depth: 0.01 },
        ]
        .into_iter()
        .map(|c| LineContactLaw::new(&impactor(c), &plate(), 0.2))
        .collect()
    }

    #[test]
    fn force_to_indentation_round_trip_is_exact_to_1e_12() {
        for law in laws() {
            let fmax = law.max_force_per_width() * law.width;
            for frac in [1e-12, 1e-8, 1e-4, 0.01, 0.1, 0.5, 0.9] {
                let f = frac * fmax;
                let alpha = law.alpha(f / law.width);
                let back = law.force_for(alpha).unwrap();
                assert!(
                    ((back - f) / f).abs() < 1e-12,
                    "{law:?}: f = {f:e}, back = {back:e}"
                );
            }
        }
    }

    /// Near the maximum alpha is flat, so F(alpha) is ill-conditioned: the round trip can
    /// only be as good as the condition number `kappa = alpha / (P alpha')` times the
    /// round-off of evaluating alpha (cancellation in `a - b ln P`, about `a/b` ulps).
    #[test]
    fn round_trip_near_the_maximum_is_as_good_as_its_conditioning_allows() {
        for law in laws() {
            let pmax = law.max_force_per_width();
            for frac in [0.99, 0.999] {
                let p = frac * pmax;
                let kappa = law.alpha(p) / (p * law.alpha_slope(p));
                let bound = 4.0 * f64::EPSILON * kappa * (law.a / law.b).abs().max(1.0);
                let back = law.force_for(law.alpha(p)).unwrap() / law.width;
                assert!(
                    ((back - p) / p).abs() < bound,
                    "{frac}: {:e} vs bound {bound:e}",
                    (back - p) / p
                );
            }
        }
    }

    #[test]
    fn zero_branch_and_tiny_forces_do_not_fail() {
        for law in laws() {
            assert_eq!(solve_contact_force(&law, 1e-12, 0.0), Ok(0.0));
            assert_eq!(solve_contact_force(&law, 1e-12, -1e-3), Ok(0.0));
            let f = solve_contact_force(&law, 1e-12, 1e-300).unwrap();
            assert!(f >= 0.0 && f < 1e-280, "{f:e}");
        }
    }

    #[test]
    fn beyond_the_maximum_is_reported_not_solved() {
        for law in laws() {
            let too_deep = 1.01 * law.max_indentation();
            assert_eq!(law.force_for(too_deep), None);
            let err = solve_contact_force(&law, 0.0, too_deep).unwrap_err();
            assert!(err.available < err.required);
        }
    }

    #[test]
    fn maximum_of_the_paper_law_is_at_p_r_c_equal_l_squared() {
        let law = &laws()[1];
        let c = law.b;
        let p_star = 1e-6 / (0.01 * c);
        assert!((law.max_force_per_width() / p_star - 1.0).abs() < 1e-12);
        assert!(law.alpha_slope(p_star).abs() < 1e-12 * law.a.abs().max(law.b));
    }

    #[test]
    fn analytic_slope_matches_central_differences() {
        for law in laws() {
            let pmax = law.max_force_per_width();
            for frac in [1e-6, 1e-3, 0.1, 0.5] {
                let p = frac * pmax;
                let h = 1e-6 * p;
                let fd = (law.alpha(p + h) - law.alpha(p - h)) / (2.0 * h);
                assert!((fd / law.alpha_slope(p) - 1.0).abs() < 1e-7, "{frac}");
            }
        }
    }

    #[test]
    fn paper_law_in_metres_and_millimetres_agree_once_the_length_is_fixed() {
        // The same physical law (hidden length 1 mm) evaluated with all lengths in mm
        // (forces in N, moduli in N/mm^2, P in N/mm, l = 1 mm) gives alpha in mm equal to
        // 1000 x the SI alpha.
        let si = &laws()[1];
        let (e_mm, r_mm, l_mm) = (207e9 * 1e-6, 10.0, 1.0);
        let c_mm =
            (1.0 - 0.09) / (std::f64::consts::PI * e_mm) + 1.0 / (std::f64::consts::PI * e_mm);
        for p_si in [1e4, 1e6, 1e7] {
            let p_mm = p_si * 1e-3;
            let alpha_mm = p_mm * c_mm * (1.0 - (p_mm * r_mm * c_mm / (l_mm * l_mm)).ln());
            assert!((alpha_mm / (1000.0 * si.alpha(p_si)) - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn stored_energy_is_the_integral_of_force_over_indentation() {
        for law in laws() {
            let fmax = 0.8 * law.max_force_per_width() * law.width;
            let n = 200_000;
            let mut work = 0.0;
            let mut prev = (0.0, 0.0);
            for i in 1..=n {
                let f = fmax * (i as f64 / n as f64).powi(2);
                let alpha = law.alpha(f / law.width);
                work += 0.5 * (f + prev.0) * (alpha - prev.1);
                prev = (f, alpha);
            }
            assert!((work / law.energy(fmax) - 1.0).abs() < 1e-6);
        }
    }
}
