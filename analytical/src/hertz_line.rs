//! The paper's line-contact law (Dokko & Kim 2004, eq. (4)) as printed, in whatever
//! consistent unit system its arguments are given: indentation
//! `alpha = P c (1 - ln(P r c / l^2))` with `c = (1 - nu_s^2)/(pi E) + 1/(pi E)` (the
//! paper's `chi_s + chi_p`, `chi_p = 1/(pi E)` kept as printed), `P` the force per width, `r`
//! the nose radius and `l` the hidden length unit of the logarithm (see
//! `reference-data/paper/README.md`). Its maximum force per width is `P* = l^2 / (r c)`,
//! where `d alpha / d P` vanishes.

/// The compliance `c` of eq. (4), 1/modulus units: `(1 - nu_s^2)/(pi E) + 1/(pi E)`.
pub fn compliance(youngs_modulus: f64, poisson_ratio: f64) -> f64 {
    let (e, nu_s) = (youngs_modulus, poisson_ratio);
    let pi = std::f64::consts::PI;
    (1.0 - nu_s * nu_s) / (pi * e) + 1.0 / (pi * e)
}

/// Eq. (4): the indentation for force per width `p`, moduli `e`, Poisson ratio `nu_s`, radius
/// `r` and hidden length `l`, all in one consistent unit system.
pub fn paper_alpha(p: f64, e: f64, nu_s: f64, r: f64, l: f64) -> f64 {
    let c = compliance(e, nu_s);
    p * c * (1.0 - (p * r * c / (l * l)).ln())
}

/// The law's maximum force per width `P* = l^2 / (r c)` (force per length of the system).
pub fn paper_max_force_per_width(e: f64, nu_s: f64, r: f64, l: f64) -> f64 {
    l * l / (r * compliance(e, nu_s))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_indentation_is_stationary_at_the_maximum_force() {
        // Against the derivative of eq. (4) (its zero defines P*), by central differences.
        let (e, nu, r, l) = (207e3, 0.3, 10.0, 1.0);
        let p = paper_max_force_per_width(e, nu, r, l);
        let h = 1e-6 * p;
        let slope = (paper_alpha(p + h, e, nu, r, l) - paper_alpha(p - h, e, nu, r, l)) / (2.0 * h);
        // Measured 6.9e-11 of the compliance (central-difference truncation and round-off);
        // 1e-9 is ~10x that, so a P* that is not the stationary point of eq. (4) shows.
        assert!(slope.abs() < 1e-9 * compliance(e, nu), "{slope}");
        assert!(paper_alpha(0.5 * p, e, nu, r, l) < paper_alpha(p, e, nu, r, l));
    }
}
