//! The `rigid-target` builtin: the reference for an impactor on a fixed rigid target through
//! a line-contact law, `m alpha'' = -F(alpha)`, `alpha(0) = 0`, `alpha'(0) = v0`.
//!
//! Independent of the solver: the law is written here from its formulas
//! (`reference-data/paper/contact-law.md`: eq. (4) as printed with its hidden length `l`, and
//! Johnson's two line-contact terms), not taken from `impact_solver::contact`; it is inverted
//! here by the Illinois method, not by the solver's Newton. Then
//! - the peak force and the largest indentation come from the energy identity
//!   `W (P alpha(P) - int_0^P alpha dp) = m v0^2 / 2` (P force per width; the integral by
//!   Simpson's rule in `p = P s^2`), solved by bisection: no time integration at all;
//! - the contact duration and rebound velocity from classical Runge-Kutta (4th order) with
//!   about 200 000 steps over the contact.
//!
//! The Runge-Kutta peak force agrees with the energy identity (`rk4_peak_rel_diff`).

use std::collections::BTreeMap;

use serde_json::Value;

use crate::definition::run_data::RunData;
use crate::run::builtin_params::param;

/// Indentation (m) as a function of the force per unit width (N/m).
type Law = Box<dyn Fn(f64) -> f64>;

/// The law a parameter set names, written from its formulas (SI units).
fn law_from(p: &BTreeMap<String, Value>) -> Result<Law, String> {
    let pi = std::f64::consts::PI;
    let r = param(p, "nose_radius", 0.01)?;
    let (e_s, nu_s) = (
        param(p, "impactor_youngs_modulus", 207e9)?,
        param(p, "impactor_poisson_ratio", 0.3)?,
    );
    let (e, nu) = (
        param(p, "youngs_modulus", 207e9)?,
        param(p, "poisson_ratio", 0.3)?,
    );
    let chi_s = (1.0 - nu_s * nu_s) / (pi * e_s);
    match p.get("law").and_then(Value::as_str).unwrap_or("paper") {
        "paper" => {
            // Eq. (4) as printed: alpha = P c (1 - ln(P r c / l^2)), c = chi_s + 1/(pi E).
            let l = param(p, "length_unit", 1.0e-3)?;
            let c = chi_s + 1.0 / (pi * e);
            Ok(Box::new(move |q: f64| {
                q * c * (1.0 - (q * r * c / (l * l)).ln())
            }))
        }
        "johnson" => {
            // Cylinder compression plus the approach of the plate point at depth d, with the
            // Hertz half-width a = sqrt(4 P r / (pi E*)).
            let d = param(p, "datum_depth", 0.01)?;
            let chi_p = (1.0 - nu * nu) / (pi * e);
            let e_star = 1.0 / ((1.0 - nu_s * nu_s) / e_s + (1.0 - nu * nu) / e);
            Ok(Box::new(move |q: f64| {
                let a = (4.0 * q * r / (pi * e_star)).sqrt();
                chi_s * q * (2.0 * (4.0 * r / a).ln() - 1.0)
                    + chi_p * q * (2.0 * (2.0 * d / a).ln() - nu / (1.0 - nu))
            }))
        }
        o => Err(format!("param law: {o:?} is not paper or johnson")),
    }
}

/// What the reference gives for one impact.
#[derive(Debug, Clone, Copy)]
pub struct Impact {
    /// N (whole width)
    pub peak_force: f64,
    /// m
    pub max_indentation: f64,
    /// s
    pub duration: f64,
    /// m/s, away from the target
    pub rebound_velocity: f64,
    /// Runge-Kutta peak force against the energy identity's, relative
    pub rk4_peak_rel_diff: f64,
}

/// The force per width (N/m) at the top of the law's physical branch (golden-section search
/// on ln P for the maximum of alpha).
fn branch_top(alpha: &dyn Fn(f64) -> f64) -> f64 {
    let (mut lo, mut hi) = (0.0f64, 45.0f64); // ln P from 1 to 3.5e19 N/m
    let g = 0.5 * (5.0f64.sqrt() - 1.0);
    for _ in 0..200 {
        let (x1, x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
        if alpha(x1.exp()) < alpha(x2.exp()) {
            lo = x1;
        } else {
            hi = x2;
        }
    }
    (0.5 * (lo + hi)).exp()
}

/// The force per width for an indentation on the physical branch `[0, top]` (Illinois
/// regula falsi); `top` when `target` is at or beyond the law's maximum.
fn invert(alpha: &dyn Fn(f64) -> f64, top: f64, target: f64) -> f64 {
    if target <= 0.0 {
        return 0.0;
    }
    let (mut lo, mut hi) = ((0.0, -target), (top, alpha(top) - target));
    if hi.1 <= 0.0 {
        return top;
    }
    let mut side = 0i8;
    for _ in 0..200 {
        let x = (lo.0 * hi.1 - hi.0 * lo.1) / (hi.1 - lo.1);
        let fx = alpha(x) - target;
        if fx == 0.0 || hi.0 - lo.0 <= 4.0 * f64::EPSILON * hi.0 {
            return x;
        }
        if fx > 0.0 {
            hi = (x, fx);
            if side == 1 {
                lo.1 *= 0.5;
            }
            side = 1;
        } else {
            lo = (x, fx);
            if side == -1 {
                hi.1 *= 0.5;
            }
            side = -1;
        }
    }
    0.5 * (lo.0 + hi.0)
}

/// `int_0^q alpha(p) dp` by Simpson's rule in `p = q s^2` (smooth in s), m N/m.
fn alpha_integral(alpha: &dyn Fn(f64) -> f64, q: f64) -> f64 {
    let n = 4000;
    let h = 1.0 / n as f64;
    let f = |s: f64| {
        if s > 0.0 {
            alpha(q * s * s) * 2.0 * q * s
        } else {
            0.0
        }
    };
    let mut sum = f(0.0) + f(1.0);
    for i in 1..n {
        sum += f(i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    sum * h / 3.0
}

/// The impact of `mass` (kg) at `v0` (m/s) on a rigid target through `alpha(P)` over a
/// width `width` (m).
pub fn impact(
    alpha: &dyn Fn(f64) -> f64,
    width: f64,
    mass: f64,
    v0: f64,
) -> Result<Impact, String> {
    let top = branch_top(alpha);
    let kinetic = 0.5 * mass * v0 * v0;
    let stored = |q: f64| width * (q * alpha(q) - alpha_integral(alpha, q));
    if stored(top) <= kinetic {
        return Err(format!(
            "the law stores at most {:.4e} J, less than the impactor's {kinetic:.4e} J",
            stored(top)
        ));
    }
    // Energy identity by bisection (stored energy increases on the physical branch).
    let (mut lo, mut hi) = (0.0, top);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if stored(mid) < kinetic {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let p_peak = 0.5 * (lo + hi);
    let (duration, rebound, rk4_peak) = runge_kutta(alpha, top, width, mass, v0)?;
    Ok(Impact {
        peak_force: p_peak * width,
        max_indentation: alpha(p_peak),
        duration,
        rebound_velocity: rebound,
        rk4_peak_rel_diff: rk4_peak / (p_peak * width) - 1.0,
    })
}

/// Contact duration (s), rebound velocity (m/s) and peak force (N) by Runge-Kutta; the step
/// is refined until the contact spans at least 1e5 steps.
fn runge_kutta(
    alpha: &dyn Fn(f64) -> f64,
    top: f64,
    width: f64,
    mass: f64,
    v0: f64,
) -> Result<(f64, f64, f64), String> {
    let acc = |a: f64| -invert(alpha, top, a) * width / mass;
    // First guess: a linear spring through the law at 1 % of its top.
    let k = 0.01 * top * width / alpha(0.01 * top);
    let mut h = std::f64::consts::PI * (mass / k).sqrt() / 200_000.0;
    for _ in 0..20 {
        let (mut a, mut v, mut t, mut a_max) = (0.0f64, v0, 0.0, 0.0f64);
        let mut ended = None;
        for _ in 0..2_000_000 {
            let k1 = (v, acc(a));
            let k2 = (v + 0.5 * h * k1.1, acc(a + 0.5 * h * k1.0));
            let k3 = (v + 0.5 * h * k2.1, acc(a + 0.5 * h * k2.0));
            let k4 = (v + h * k3.1, acc(a + h * k3.0));
            let a_new = a + h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
            let v_new = v + h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
            if a_new <= 0.0 && t > 0.0 {
                // Linear interpolation of the crossing: O(h^2) with h ~ T / 2e5.
                ended = Some((t + h * a / (a - a_new), v_new));
                break;
            }
            (a, v, t) = (a_new, v_new, t + h);
            a_max = a_max.max(a);
        }
        match ended {
            Some((duration, v_end)) if duration / h > 1.0e5 => {
                return Ok((duration, -v_end, invert(alpha, top, a_max) * width))
            }
            Some((duration, _)) => h = duration / 200_000.0,
            None => h *= 10.0,
        }
    }
    Err("rigid-target: the Runge-Kutta step did not settle".into())
}

pub fn rigid_target(p: &BTreeMap<String, Value>) -> Result<RunData, String> {
    let law = law_from(p)?;
    let (mass, v0, width) = (
        param(p, "mass", 18.0)?,
        param(p, "velocity", 10.0)?,
        param(p, "width", 0.2)?,
    );
    let r = impact(&law, width, mass, v0)?;
    let mut m = BTreeMap::new();
    m.insert("contact_duration_s".into(), r.duration);
    m.insert("max_indentation_m".into(), r.max_indentation);
    m.insert("peak_force_N".into(), r.peak_force);
    m.insert("rebound_velocity_mps".into(), r.rebound_velocity);
    m.insert("rk4_peak_rel_diff".into(), r.rk4_peak_rel_diff);
    Ok(RunData {
        metrics: m,
        ..Default::default()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params(law: &str, v: f64) -> BTreeMap<String, Value> {
        let mut p = BTreeMap::new();
        p.insert("law".into(), Value::from(law));
        p.insert("velocity".into(), Value::from(v));
        p
    }

    /// The reference agrees with the solver's own law at the tabulated points of
    /// contact-law.md (alpha in um at P = 1e6 N/m), and its two routes agree.
    #[test]
    fn law_matches_the_tabulated_values_and_routes_agree() {
        let paper = law_from(&params("paper", 3.0)).unwrap();
        let johnson = law_from(&params("johnson", 10.0)).unwrap();
        assert!((paper(1e6) * 1e6 - 13.298).abs() < 1e-3);
        assert!((johnson(1e6) * 1e6 - 22.837).abs() < 1e-3);
        let r = impact(&paper, 0.2, 18.0, 3.0).unwrap();
        assert!(r.rk4_peak_rel_diff.abs() < 1e-9, "{r:?}");
        assert!((r.rebound_velocity / 3.0 - 1.0).abs() < 1e-9, "{r:?}");
    }

    /// A plausible wrong law moves the reference by far more than the case's tolerances
    /// (1e-5 relative on the peak force, 1.25e-7 s on the duration): the constant doubled
    /// (compliance halved) and the exponent of P changed by 0.05.
    #[test]
    fn a_wrong_law_moves_peak_and_duration_beyond_the_tolerances() {
        let law = law_from(&params("johnson", 10.0)).unwrap();
        let right = impact(&law, 0.2, 18.0, 10.0).unwrap();
        let stiff = impact(&|q| 0.5 * law(q), 0.2, 18.0, 10.0).unwrap();
        let exponent = impact(&|q| law(q) * (q / 1e6).powf(0.05), 0.2, 18.0, 10.0).unwrap();
        for wrong in [stiff, exponent] {
            assert!(
                (wrong.peak_force / right.peak_force - 1.0).abs() > 1e-2,
                "{wrong:?}"
            );
            assert!((wrong.duration - right.duration).abs() > 1e-6, "{wrong:?}");
        }
    }
}
