//! An Euler-Bernoulli clamped-clamped beam (plane strain modulus `E' = E / (1 - nu^2)`)
//! under a rectangular pulse `F` for `duration` at mid-span, by modal superposition
//! (Meirovitch, *Elements of Vibration Analysis*, ch. 7; the roots of `cos x cosh x = 1` and
//! the mode shapes as in Blevins, *Formulas for Natural Frequency and Mode Shape*, table 8-1):
//! `w(t) = sum_n F phi_n(L/2)^2 / (M_n omega_n^2) [(1 - cos omega_n t) - H(t - T)(1 - cos
//! omega_n (t - T))]` with `omega_n = x_n^2 / L^2 sqrt(E' I / (rho A))`.

use crate::beam::ClampedBeam;
use crate::positive;

/// Roots of `cos x cosh x = 1` (clamped-clamped beam), the first `n`.
pub fn clamped_roots(n: usize) -> Vec<f64> {
    (1..=n)
        .map(|k| {
            let mut x = (k as f64 + 0.5) * std::f64::consts::PI;
            for _ in 0..50 {
                // g(x) = cos x - 1/cosh x, well scaled for large x.
                let g = x.cos() - 1.0 / x.cosh();
                let dg = -x.sin() + x.tanh() / x.cosh();
                let step = g / dg;
                x -= step;
                if step.abs() < 1e-15 * x {
                    break;
                }
            }
            x
        })
        .collect()
}

/// Clamped-clamped mode shape at `xi = x / L` (stable for large roots; the integral of its
/// square over [0, 1] is 1).
pub fn clamped_mode(root: f64, xi: f64) -> f64 {
    let (s, c, sh) = (root.sin(), root.cos(), root.sinh());
    let one_minus_sigma = (-(-root).exp() - s + c) / (sh - s);
    let sigma = 1.0 - one_minus_sigma;
    let z = root * xi;
    (-z).exp() + one_minus_sigma * z.sinh() - z.cos() + sigma * z.sin()
}

/// Simpson's weighted sum `f(0) + 4 f(h) + 2 f(2h) + ... + f(1)` on `n` (even) intervals of
/// [0, 1]; times `h / 3 = 1 / (3 n)` it is the integral.
fn simpson_weighted_sum(n: usize, f: impl Fn(f64) -> f64) -> f64 {
    let mut s = 0.0;
    for i in 0..=n {
        let w = if i == 0 || i == n {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        };
        s += w * f(i as f64 / n as f64);
    }
    s
}

/// The beam's first modes: (omega rad/s, mode value at mid-span, modal mass kg).
pub struct ModalBeam {
    pub length: f64,
    /// Bending stiffness `E' I`, N m^2.
    pub ei: f64,
    modes: Vec<(f64, f64, f64)>,
}

impl ModalBeam {
    /// The first `n_modes` modes of `beam` of `density` (kg/m^3). Errors: a density not
    /// finite and > 0, no mode.
    pub fn new(beam: &ClampedBeam, density: f64, n_modes: usize) -> Result<Self, String> {
        let rho = positive("density", density)?;
        if n_modes == 0 {
            return Err("modes = 0: must be at least 1".into());
        }
        let (length, width, thickness) = (beam.length, beam.width, beam.thickness);
        let (e_mod, nu) = (beam.youngs_modulus, beam.poisson_ratio);
        let e_prime = e_mod / (1.0 - nu * nu);
        let ei = e_prime * width * thickness.powi(3) / 12.0;
        let rho_a = rho * width * thickness;
        // Modal masses by Simpson's rule on 4000 intervals.
        let modes = clamped_roots(n_modes)
            .iter()
            .map(|&r| {
                let n = 4000;
                let s = simpson_weighted_sum(n, |xi| clamped_mode(r, xi).powi(2));
                let mass = rho_a * length * s / (3.0 * n as f64);
                let omega = r * r / (length * length) * (ei / rho_a).sqrt();
                (omega, clamped_mode(r, 0.5), mass)
            })
            .collect();
        Ok(ModalBeam { length, ei, modes })
    }

    /// The first natural period, s.
    pub fn first_period_s(&self) -> f64 {
        2.0 * std::f64::consts::PI / self.modes[0].0
    }

    /// The static mid-span deflection under `force` (N), m, in closed form `F L^3 / (192 E'I)`.
    pub fn static_midspan(&self, force: f64) -> f64 {
        force * self.length.powi(3) / (192.0 * self.ei)
    }

    /// The static limit of the modal series (equals [`Self::static_midspan`] for enough modes).
    pub fn series_static_midspan(&self, force: f64) -> f64 {
        self.modes
            .iter()
            .map(|&(om, phi, mass)| force * phi * phi / (mass * om * om))
            .sum()
    }

    /// The mid-span deflection (m, downward positive) at time `t` (s) under `force` (N)
    /// applied from 0 to `duration` (s).
    pub fn midspan_deflection(&self, force: f64, duration: f64, t: f64) -> f64 {
        let mut w = 0.0;
        for &(om, phi, mass) in &self.modes {
            let amp = force * phi * phi / (mass * om * om);
            let on = 1.0 - (om * t).cos();
            let off = if t >= duration {
                1.0 - (om * (t - duration)).cos()
            } else {
                0.0
            };
            w += amp * (on - off);
        }
        w
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clamped_roots_match_the_tabulated_values() {
        let r = clamped_roots(4);
        for (a, b) in r
            .iter()
            .zip([4.730040745, 7.853204624, 10.99560784, 14.13716549])
        {
            // The table gives 10 significant digits (rounding up to 5e-9); measured 2.0e-9.
            assert!((a - b).abs() < 1e-8, "{a} vs {b}");
        }
        // Normalisation of this mode form: integral of phi^2 over [0, 1] is 1.
        for &root in &clamped_roots(30) {
            let n = 4000;
            let s = simpson_weighted_sum(n, |xi| clamped_mode(root, xi).powi(2)) / (3.0 * n as f64);
            // Measured up to 2.1e-13 (Simpson on smooth modes, round-off growing with the
            // root); 2e-12 is ~10x. A mode missing its normalisation is off by O(1).
            assert!((s - 1.0).abs() < 2e-12, "{root}: {s}");
        }
    }

    #[test]
    fn the_series_tends_to_the_static_deflection() {
        let beam = ClampedBeam::new(0.8, 0.2, 0.02, 207e9, 0.3).unwrap();
        let b = ModalBeam::new(&beam, 7850.0, 40).unwrap();
        let r = b.series_static_midspan(1e4) / b.static_midspan(1e4);
        // Truncation of the series after 40 modes: measured -9.9e-6; 1e-4 is ~10x.
        assert!((r - 1.0).abs() < 1e-4, "{r}");
        assert!(ModalBeam::new(&beam, 7850.0, 0).is_err());
        assert!(ModalBeam::new(&beam, -1.0, 40).is_err());
    }
}
