//! A static clamped-clamped beam of length `L` under a central force `F` (Timoshenko & Gere,
//! *Mechanics of Materials*; Roark, *Formulas for Stress and Strain*, table 8.1): the
//! Euler-Bernoulli mid-span deflection `F L^3 / (192 E' I)` and the shear deflection of
//! Timoshenko beam theory `F L / (4 k G A)` with `k = 5/6`, in plane strain
//! (`E' = E / (1 - nu^2)`, `I = b h^3 / 12` for width `b` and depth `h`).

use crate::{poisson, positive};

/// The beam's geometry (m) and material (Pa, -).
#[derive(Clone, Copy, Debug)]
pub struct ClampedBeam {
    pub length: f64,
    pub width: f64,
    pub thickness: f64,
    pub youngs_modulus: f64,
    pub poisson_ratio: f64,
}

impl ClampedBeam {
    /// Errors: a length, width, thickness or modulus not finite and > 0, a Poisson ratio out of
    /// (-1, 0.5).
    pub fn new(
        length: f64,
        width: f64,
        thickness: f64,
        youngs_modulus: f64,
        poisson_ratio: f64,
    ) -> Result<Self, String> {
        Ok(ClampedBeam {
            length: positive("length", length)?,
            width: positive("width", width)?,
            thickness: positive("thickness", thickness)?,
            youngs_modulus: positive("youngs_modulus", youngs_modulus)?,
            poisson_ratio: poisson(poisson_ratio)?,
        })
    }

    /// Euler-Bernoulli mid-span deflection under the central force `force` (N), m (downward
    /// positive): `F L^3 / (192 E' I)`.
    pub fn euler_bernoulli_midspan(&self, force: f64) -> f64 {
        let nu = self.poisson_ratio;
        let e_prime = self.youngs_modulus / (1.0 - nu * nu);
        let inertia = self.width * self.thickness.powi(3) / 12.0;
        force * self.length.powi(3) / (192.0 * e_prime * inertia)
    }

    /// The shear part of Timoshenko's mid-span deflection, m: `F L / (4 k G A)`, `k = 5/6`.
    pub fn shear_midspan(&self, force: f64) -> f64 {
        let mu = self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio));
        force * self.length / (4.0 * (5.0 / 6.0) * mu * self.width * self.thickness)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn deflections_scale_as_beam_theory_says_and_bad_input_is_refused() {
        let b = ClampedBeam::new(0.8, 0.2, 0.02, 207e9, 0.3).unwrap();
        let d = ClampedBeam {
            thickness: 0.04,
            ..b
        };
        // Bending goes as 1/h^3, shear as 1/h.
        let r = b.euler_bernoulli_midspan(1e4) / d.euler_bernoulli_midspan(1e4);
        // Exact ratios of products of the same inputs: round-off only (measured 0), so 1e-12.
        // A thickness power off by one (h^2 or h^4) gives 4 or 16 and fails.
        assert!((r - 8.0).abs() < 1e-12, "{r}");
        let r = b.shear_midspan(1e4) / d.shear_midspan(1e4);
        assert!((r - 2.0).abs() < 1e-12, "{r}");
        assert!(ClampedBeam::new(0.8, 0.2, -0.02, 207e9, 0.3).is_err());
        assert!(ClampedBeam::new(0.8, 0.2, 0.02, 207e9, 0.5).is_err());
    }
}
