//! Natural frequencies of a Timoshenko beam (rotary inertia and shear deformation; Timoshenko,
//! *Vibration Problems in Engineering*; Huang 1961, J. Appl. Mech. 28, "The effect of rotatory
//! inertia and of shear deformation on the frequency and normal mode equations of uniform beams
//! with simple end conditions"), in plane strain (`E' = E / (1 - nu^2)` in bending, `G` in
//! shear, shear coefficient `k`), found here from the general solution of the two equations
//!
//! `k G A (w'' - phi') + rho A omega^2 w = 0`,
//! `E' I phi'' + k G A (w' - phi) + rho I omega^2 phi = 0`.
//!
//! With `w, phi ~ e^(lambda x)`, `mu = lambda^2` solves `a mu^2 + b mu + c = 0`,
//! `a = k G A E' I`, `b = rho omega^2 (k G A I + A E' I)`, `c = rho A omega^2 (rho I omega^2 - k G A)`:
//! below the cut-off `rho I omega^2 < k G A` one root `alpha^2 > 0` and one `-beta^2 < 0`, so
//! `w = C1 cosh(alpha x) + C2 sinh(alpha x) + C3 cos(beta x) + C4 sin(beta x)` and, from the
//! first equation (`phi' = w'' + q w`, `q = rho omega^2 / (k G)`),
//! `phi = (alpha^2 + q)/alpha (C1 sinh + C2 cosh) + (q - beta^2)/beta (C3 sin - C4 cos)`.
//! The end conditions make a 4 x 4 determinant whose roots in omega are the frequencies.

use crate::beam::ClampedBeam;
use crate::positive;

/// End conditions of both ends.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ends {
    /// `w = 0`, `phi = 0`
    Clamped,
    /// `w = 0`, `phi' = 0` (no moment)
    Pinned,
}

/// A uniform Timoshenko beam per unit width (the width cancels).
#[derive(Clone, Copy, Debug)]
pub struct TimoshenkoBeam {
    pub length: f64,
    /// Bending stiffness `E' I` per unit width, N m
    pub ei: f64,
    /// Shear stiffness `k G A` per unit width, N/m
    pub kga: f64,
    /// `rho A` per unit width, kg/m^2
    pub rho_a: f64,
    /// `rho I` per unit width, kg
    pub rho_i: f64,
}

impl TimoshenkoBeam {
    /// The plane-strain beam of `beam` with `density` (kg/m^3) and shear coefficient
    /// `shear_coefficient` (5/6 for a rectangle). Errors: a density or coefficient not finite
    /// and > 0.
    pub fn new(beam: &ClampedBeam, density: f64, shear_coefficient: f64) -> Result<Self, String> {
        let rho = positive("density", density)?;
        let k = positive("shear_coefficient", shear_coefficient)?;
        let (e, nu, h) = (beam.youngs_modulus, beam.poisson_ratio, beam.thickness);
        let inertia = h.powi(3) / 12.0;
        Ok(TimoshenkoBeam {
            length: beam.length,
            ei: e / (1.0 - nu * nu) * inertia,
            kga: k * e / (2.0 * (1.0 + nu)) * h,
            rho_a: rho * h,
            rho_i: rho * inertia,
        })
    }

    /// `(alpha, beta)` at `omega` (rad/s), 1/m; None above the cut-off.
    fn wavenumbers(&self, omega: f64) -> Option<(f64, f64)> {
        let w2 = omega * omega;
        let a = self.kga * self.ei;
        let b = w2 * (self.kga * self.rho_i + self.rho_a * self.ei);
        let c = self.rho_a * w2 * (self.rho_i * w2 - self.kga);
        if c >= 0.0 {
            return None;
        }
        let disc = (b * b - 4.0 * a * c).sqrt();
        let alpha2 = (-b + disc) / (2.0 * a);
        let beta2 = (b + disc) / (2.0 * a);
        Some((alpha2.sqrt(), beta2.sqrt()))
    }

    /// The end-condition determinant at `omega` (its roots are the natural frequencies).
    fn determinant(&self, ends: Ends, omega: f64) -> Option<f64> {
        let (al, be) = self.wavenumbers(omega)?;
        let q = self.rho_a * omega * omega / self.kga;
        let (ga, gb) = ((al * al + q) / al, (q - be * be) / be);
        // Rows: the two conditions at x, for the bases cosh, sinh, cos, sin of w.
        let rows = |x: f64| -> [[f64; 4]; 2] {
            let (ch, sh, c, s) = (
                (al * x).cosh(),
                (al * x).sinh(),
                (be * x).cos(),
                (be * x).sin(),
            );
            let w = [ch, sh, c, s];
            match ends {
                Ends::Clamped => [w, [ga * sh, ga * ch, gb * s, -gb * c]],
                // phi' = w'' + q w
                Ends::Pinned => [
                    w,
                    [
                        (al * al + q) * ch,
                        (al * al + q) * sh,
                        gb * be * c,
                        gb * be * s,
                    ],
                ],
            }
        };
        let [r0, r1] = rows(0.0);
        let [r2, r3] = rows(self.length);
        Some(det4([r0, r1, r2, r3]))
    }

    /// The lowest natural frequency with `ends`, rad/s: the first sign change of the
    /// determinant on a 0.1 % grid from 10 % of `omega_guess` (e.g. Euler-Bernoulli's), then
    /// bisection to 1e-13 relative.
    pub fn first_omega(&self, ends: Ends, omega_guess: f64) -> Result<f64, String> {
        let mut lo = 0.1 * omega_guess;
        let mut d_lo = self.determinant(ends, lo).ok_or("above the cut-off")?;
        while lo < 3.0 * omega_guess {
            let hi = lo * 1.001;
            let d_hi = self.determinant(ends, hi).ok_or("above the cut-off")?;
            if d_lo.signum() != d_hi.signum() {
                let (mut a, mut b, mut da) = (lo, hi, d_lo);
                while (b - a) > 1e-13 * b {
                    let m = 0.5 * (a + b);
                    let dm = self.determinant(ends, m).ok_or("above the cut-off")?;
                    if dm.signum() == da.signum() {
                        (a, da) = (m, dm);
                    } else {
                        b = m;
                    }
                }
                return Ok(0.5 * (a + b));
            }
            (lo, d_lo) = (hi, d_hi);
        }
        Err(format!("no root below 3 x {omega_guess} rad/s"))
    }
}

/// Determinant of a 4 x 4 matrix (Laplace expansion along the first row).
fn det4(m: [[f64; 4]; 4]) -> f64 {
    let det3 = |r: [[f64; 3]; 3]| {
        r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1])
            - r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0])
            + r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0])
    };
    (0..4)
        .map(|j| {
            let minor = [1, 2, 3].map(|i| {
                let mut row = [0.0; 3];
                let mut k = 0;
                for (c, &v) in m[i].iter().enumerate() {
                    if c != j {
                        row[k] = v;
                        k += 1;
                    }
                }
                row
            });
            let sign = if j % 2 == 0 { 1.0 } else { -1.0 };
            sign * m[0][j] * det3(minor)
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn beam(thickness: f64) -> (ClampedBeam, TimoshenkoBeam) {
        let b = ClampedBeam::new(0.2, 1.0, thickness, 207e9, 0.3).unwrap();
        (b, TimoshenkoBeam::new(&b, 7850.0, 5.0 / 6.0).unwrap())
    }

    /// Pinned-pinned has a closed form: with `w = W sin(k x)`, `phi = P cos(k x)`,
    /// `k = pi / L`, `(k G A k^2 - rho A w^2)(E'I k^2 + k G A - rho I w^2) = (k G A k)^2`; the
    /// determinant's first root must match its lower root (checks the general solution and
    /// the root finder). Measured up to 1.2e-11 (h = 5 mm); 1e-10 is ~10x.
    #[test]
    fn pinned_pinned_matches_its_closed_form() {
        for h in [0.005, 0.02, 0.05] {
            let (_, t) = beam(h);
            let k = std::f64::consts::PI / t.length;
            // A w4 + B w2 + C = 0 in w2 = omega^2.
            let a = t.rho_a * t.rho_i;
            let b = -(t.rho_a * (t.ei * k * k + t.kga) + t.rho_i * t.kga * k * k);
            let c = t.kga * k * k * t.ei * k * k;
            let w2 = (-b - (b * b - 4.0 * a * c).sqrt()) / (2.0 * a);
            let eb = k * k * (t.ei / t.rho_a).sqrt();
            let found = t.first_omega(Ends::Pinned, eb).unwrap();
            assert!(
                (found / w2.sqrt() - 1.0).abs() < 1e-10,
                "{h}: {found} vs {}",
                w2.sqrt()
            );
        }
    }

    /// Clamped-clamped tends to Euler-Bernoulli's 4.730040745^2 / L^2 sqrt(E'I / rho A) as the
    /// beam gets slender (shear and rotary inertia corrections ~ (h/L)^2), and lies below it
    /// (the band at L/h = 10 brackets the measured gap, printed by the case).
    #[test]
    fn clamped_clamped_tends_to_euler_bernoulli() {
        let x1 = 4.730_040_744_862_704_f64;
        let mut gaps = Vec::new();
        for h in [0.02, 0.002, 0.0002] {
            let (_, t) = beam(h);
            let eb = x1 * x1 / (t.length * t.length) * (t.ei / t.rho_a).sqrt();
            let gap = t.first_omega(Ends::Clamped, eb).unwrap() / eb - 1.0;
            assert!(gap < 0.0, "{h}: {gap}");
            if h == 0.02 {
                assert!((-0.08..-0.05).contains(&gap), "{gap}");
            }
            gaps.push(gap);
        }
        // The correction is ~19 (h/L)^2: measured -7.58e-6 at L/h = 5000, under 1e-5.
        let last_gap = gaps[2];
        assert!(last_gap.abs() < 1e-5, "{last_gap}");
        // ... and it falls as (h/L)^2 in the slender range: a 10x thinner beam, a 100x smaller
        // gap (measured 99.88; 1.2 % is ~10x its distance from 100). A constant bias (a wrong
        // Euler-Bernoulli root, a root-finder offset: 1e-6 gives 88) or a correction of
        // another order in h/L (10 for O(h/L)) fails it; the band above catches a wrong
        // coefficient.
        let ratio = gaps[1] / gaps[2];
        assert!((ratio / 100.0 - 1.0).abs() < 0.012, "{ratio}");
    }
}
