//! The `square-stable-step` builtin: the closed-form critical time step of one square
//! bilinear element with lumped mass in plane strain, the reference of the case
//! patch/stable-step (which reads the solver's `dt_critical_s` of a scene of square elements).
//!
//! Closed form (written here from the element, not from the solver's code): the largest
//! eigenvalue of `M^-1 K` of a square element of side `h` (m) is that of its uniform
//! dilatation mode `u_a = x_a` (nodes at `(+-h/2, +-h/2)`): strain `exx = eyy = 1`, so
//! `u^T K u = h^2 [2 (lambda + 2 mu) + 2 lambda] = 4 h^2 (lambda + mu)` per unit width and
//! `u^T M u = (rho h^2 / 4) 4 (h^2 / 2) = rho h^4 / 2`, hence
//! `omega_max^2 = 8 (lambda + mu) / (rho h^2)` and
//! `dt_crit = 2 / omega_max = h sqrt(rho / (2 (lambda + mu)))` (s). The same for 2 x 2 Gauss,
//! B-bar and one point (the mode is linear, every rule integrates it exactly; one-point
//! hourglass control acts only on the hourglass modes, whose eigenvalue
//! `2 kappa (lambda + 2 mu) / (rho h^2)` is far below).
//!
//! The wrong models it reports (metrics `dt_wrong_*_s`), each a slip a developer makes when
//! writing the estimate from the wave speed: `h / (c_d sqrt 2)` with the dilatational speed
//! `c_d = sqrt((lambda + 2 mu) / rho)` (the modulus of one-dimensional strain instead of
//! `2 (lambda + mu)`), the same with `E` in place of the P-wave modulus, and `h / c_d`
//! (the sqrt(2) of the two-dimensional element missing).

use std::collections::BTreeMap;

use serde_json::Value;

use crate::definition::run_data::RunData;
use crate::run::builtin_params::param;

/// The closed form and the wrong models, s: (`dt_closed_form_s`, the wrong models by name).
fn steps(
    youngs_modulus: f64,
    poisson_ratio: f64,
    density: f64,
    h: f64,
) -> [(&'static str, f64); 4] {
    let (e, nu) = (youngs_modulus, poisson_ratio);
    let lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
    let mu = e / (2.0 * (1.0 + nu));
    let c_d = ((lambda + 2.0 * mu) / density).sqrt();
    let c_e = (e / density).sqrt();
    [
        (
            "dt_closed_form_s",
            h * (density / (2.0 * (lambda + mu))).sqrt(),
        ),
        ("dt_wrong_p_wave_s", h / (c_d * 2f64.sqrt())),
        ("dt_wrong_youngs_s", h / (c_e * 2f64.sqrt())),
        ("dt_wrong_no_sqrt2_s", h / c_d),
    ]
}

/// Parameters: `youngs_modulus` (Pa, default 200e9), `poisson_ratio` (0.3), `density`
/// (kg/m^3, 7850), `side` (m, 0.01).
pub fn square_stable_step(p: &BTreeMap<String, Value>) -> Result<RunData, String> {
    let h = param(p, "side", 0.01)?;
    let metrics = steps(
        param(p, "youngs_modulus", 200e9)?,
        param(p, "poisson_ratio", 0.3)?,
        param(p, "density", 7850.0)?,
        h,
    )
    .into_iter()
    .map(|(k, v)| (k.to_string(), v))
    .collect();
    Ok(RunData {
        metrics,
        ..Default::default()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The closed form is the largest eigenvalue of an independently assembled square
    /// element (2 x 2 Gauss, lumped mass) to round-off, and each wrong model misses it by far
    /// more than the case's tolerance (5e-15): -15.5 %, -1.9 %, +19.5 % for steel.
    #[test]
    fn closed_form_is_the_element_eigenvalue_and_the_wrong_models_miss_it() {
        let (e, nu, rho, h) = (200e9, 0.3, 7850.0, 0.01);
        let s = steps(e, nu, rho, h);
        let lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
        let mu = e / (2.0 * (1.0 + nu));
        // 2 x 2 Gauss stiffness of the square, unit width.
        let mut k = nalgebra::SMatrix::<f64, 8, 8>::zeros();
        let sign = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];
        let g = 1.0 / 3f64.sqrt();
        for (xi, eta) in [(-g, -g), (g, -g), (g, g), (-g, g)] {
            let mut b = nalgebra::SMatrix::<f64, 3, 8>::zeros();
            for a in 0..4 {
                let dx = 0.25 * sign[a][0] * (1.0 + eta * sign[a][1]) * 2.0 / h;
                let dy = 0.25 * sign[a][1] * (1.0 + xi * sign[a][0]) * 2.0 / h;
                b[(0, 2 * a)] = dx;
                b[(1, 2 * a + 1)] = dy;
                b[(2, 2 * a)] = dy;
                b[(2, 2 * a + 1)] = dx;
            }
            let d = nalgebra::Matrix3::new(
                lambda + 2.0 * mu,
                lambda,
                0.0,
                lambda,
                lambda + 2.0 * mu,
                0.0,
                0.0,
                0.0,
                mu,
            );
            k += b.transpose() * d * b * (h * h / 4.0);
        }
        let m = rho * h * h / 4.0;
        let omega2 = nalgebra::SymmetricEigen::new(k / m).eigenvalues.max();
        let dt = 2.0 / omega2.sqrt();
        assert!((dt / s[0].1 - 1.0).abs() < 1e-14, "{dt} vs {}", s[0].1);
        let misses: Vec<f64> = s[1..].iter().map(|w| w.1 / s[0].1 - 1.0).collect();
        for (want, got) in [-0.155, -0.019, 0.195].iter().zip(&misses) {
            assert!((want - got).abs() < 1e-3, "{misses:?}");
        }
    }
}
