//! Rigid-plastic bounds for a clamped beam struck at mid-span by a mass (N. Jones,
//! *Structural Impact*, Cambridge University Press: the collapse load of a clamped beam, the
//! square yield curve for the interaction of bending and membrane forces, the energy ratio),
//! in plane strain. The beam: span `L` between the clamps, width `B`, depth `h`; a mass `G`
//! at speed `v0` (kinetic energy `K = G v0^2 / 2`).
//!
//! - Plane-strain flow stress `sigma_0 = 2 sigma_y / sqrt(3)` (von Mises), fully plastic moment
//!   `M_p = sigma_0 B h^2 / 4`, static collapse load `P_c = 8 M_p / L` (hinges at both clamps
//!   and at mid-span).
//! - Square yield curve (circumscribing the exact one, so the strongest rigid-plastic
//!   response): `P / P_c = 1 + (w / h)^2` for `w <= h`, `2 w / h` beyond. The energy absorbed
//!   up to a deflection `w` is its integral, `D(w) = P_c (w + w^3 / (3 h^2))`, then
//!   `P_c (w^2 / h + h / 3)`.
//! - Energy ratio `E_r = K / U_c`, `U_c = P_c^2 / (2 k)` the elastic energy the beam stores at
//!   the collapse load (`k` the mid-span stiffness with shear, [`crate::beam`]). Rigid-plastic
//!   theory describes the response when `E_r >> 1`; below 1 no mechanism forms at all.
//!
//! The band on the maximum mid-span deflection, each edge argued:
//! - **Upper edge** (the weakest response the theory admits): bending alone at `sigma_0`
//!   (membrane forces and hardening only add resistance), every joule of `K` into the
//!   mechanism, plus the elastic deflection at collapse `P_c / k`:
//!   `w_hi = K / P_c + P_c / k`.
//! - **Lower edge** (the strongest): the circumscribing square yield curve, the flow stress
//!   hardened at the mean plastic strain of a hinge of length `2 h` at that
//!   deflection (rotation `2 w / L`, strain `theta h / 2 / (2 h) = w / (2 L)`), and only the
//!   energy that survives the momentum transfer to the whole plate (`K G / (G + m_plate)`,
//!   inelastic impact of the mass on the plate's mass: a bound, the mass set moving is at most
//!   the plate) less the elastic energy at collapse, which returns to the striker.
//!
//! Where membrane forces can act (a model that follows the deformation: `kinematics: finite`),
//! a tighter upper edge: the **inscribing** square yield curve, which lies inside the exact
//! curve of a rectangular section `M / M_0 + (N / N_0)^2 = 1` and touches it at
//! `M / M_0 = N / N_0 = 0.618` (the root of `m + m^2 = 1`; Jones, *Structural Impact*,
//! section 2.4), so the weakest rigid-plastic response with membrane forces: `0.618 D(w)`
//! absorbs all of `K` without hardening, plus the elastic deflection at collapse. A model
//! without membrane action (small strain) is bounded only by the bending edge and leaves this
//! one once the deflection is several thicknesses.

use crate::beam::ClampedBeam;

/// A clamped beam of rigid-linear-hardening material struck by a mass (SI units).
#[derive(Clone, Copy, Debug)]
pub struct BeamImpact {
    pub beam: ClampedBeam,
    /// kg/m^3
    pub density: f64,
    /// Uniaxial yield stress, Pa.
    pub yield_stress: f64,
    /// Slope of the uniaxial flow stress against the plastic strain, Pa (0: perfectly plastic).
    pub hardening_modulus: f64,
    /// Striking mass, kg.
    pub mass: f64,
    /// Impact speed, m/s.
    pub velocity: f64,
}

/// The closed-form numbers of one impact.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    /// `P_c = 8 M_p / L`, N.
    pub collapse_load: f64,
    /// `U_c = P_c^2 / (2 k)`, J.
    pub elastic_energy_at_collapse: f64,
    /// `E_r = K / U_c`, -.
    pub energy_ratio: f64,
    /// Jones's estimate: the square yield curve at `sigma_0` absorbing all of `K`, m.
    pub estimate: f64,
    /// Lower edge of the band, m.
    pub lower: f64,
    /// Upper edge of the band, m.
    pub upper: f64,
    /// Upper edge with membrane forces (the inscribing square yield curve), m.
    pub membrane_upper: f64,
}

/// The inscribing square yield curve's size relative to the circumscribing one,
/// `(sqrt(5) - 1) / 2`.
pub const INSCRIBED: f64 = 0.618_033_988_749_894_9;

impl BeamImpact {
    /// Errors: a density, yield stress, mass or velocity not finite and > 0, or a negative
    /// tangent modulus.
    pub fn new(
        beam: ClampedBeam,
        density: f64,
        yield_stress: f64,
        hardening_modulus: f64,
        mass: f64,
        velocity: f64,
    ) -> Result<Self, String> {
        if !(hardening_modulus.is_finite() && hardening_modulus >= 0.0) {
            return Err(format!(
                "hardening_modulus = {hardening_modulus}: must be a finite number >= 0"
            ));
        }
        Ok(BeamImpact {
            beam,
            density: crate::positive("density", density)?,
            yield_stress: crate::positive("yield_stress", yield_stress)?,
            hardening_modulus,
            mass: crate::positive("mass", mass)?,
            velocity: crate::positive("velocity", velocity)?,
        })
    }

    /// `P_c` at the uniaxial flow stress `flow` (Pa), N.
    fn collapse_at(&self, flow: f64) -> f64 {
        let b = &self.beam;
        let moment = 2.0 / 3f64.sqrt() * flow * b.width * b.thickness.powi(2) / 4.0;
        8.0 * moment / b.length
    }

    /// Mid-span stiffness of the elastic clamped beam (bending and shear), N/m.
    fn stiffness(&self) -> f64 {
        1.0 / (self.beam.euler_bernoulli_midspan(1.0) + self.beam.shear_midspan(1.0))
    }

    /// Kinetic energy of the striker, J.
    pub fn kinetic_energy(&self) -> f64 {
        0.5 * self.mass * self.velocity * self.velocity
    }

    /// The plate's mass, kg.
    pub fn plate_mass(&self) -> f64 {
        let b = &self.beam;
        self.density * b.length * b.width * b.thickness
    }

    /// The band and the numbers behind it.
    pub fn bounds(&self) -> Bounds {
        let pc = self.collapse_at(self.yield_stress);
        let k = self.stiffness();
        let uc = pc * pc / (2.0 * k);
        let kinetic = self.kinetic_energy();
        let h = self.beam.thickness;
        let kept = kinetic * self.mass / (self.mass + self.plate_mass()) - uc;
        let lower = bisect(|w| {
            let strain = w / (2.0 * self.beam.length);
            let flow = self.yield_stress + self.hardening_modulus * strain;
            square_yield_energy(w, h, self.collapse_at(flow)) - kept
        });
        Bounds {
            collapse_load: pc,
            elastic_energy_at_collapse: uc,
            energy_ratio: kinetic / uc,
            estimate: bisect(|w| square_yield_energy(w, h, pc) - kinetic),
            lower,
            upper: kinetic / pc + pc / k,
            membrane_upper: bisect(|w| INSCRIBED * square_yield_energy(w, h, pc) - kinetic)
                + pc / k,
        }
    }
}

/// Energy absorbed up to the deflection `w` on the square yield curve, J.
pub fn square_yield_energy(w: f64, h: f64, collapse_load: f64) -> f64 {
    if w <= h {
        collapse_load * (w + w.powi(3) / (3.0 * h * h))
    } else {
        collapse_load * (w * w / h + h / 3.0)
    }
}

/// The root of an increasing `f` on `[0, inf)`, 0 when `f(0) >= 0` (no energy left).
fn bisect(f: impl Fn(f64) -> f64) -> f64 {
    if f(0.0) >= 0.0 {
        return 0.0;
    }
    let mut hi = 1e-3;
    while f(hi) < 0.0 {
        hi *= 2.0;
    }
    let mut lo = 0.0;
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The paper's reconstructed plate (reference-data/paper/reconstruction/report.md section
    /// 3: P_c = 129 kN there) struck by 18 kg at 10 m/s.
    fn table1() -> BeamImpact {
        let beam = ClampedBeam::new(0.2, 0.179, 0.0188, 207e9, 0.3).unwrap();
        BeamImpact::new(beam, 7850.0, 176e6, 4.14e9, 18.0, 10.0).unwrap()
    }

    #[test]
    fn collapse_load_is_8_mp_over_l_and_the_energy_is_its_integral() {
        let b = table1().bounds();
        let mp = 2.0 / 3f64.sqrt() * 176e6 * 0.179 * 0.0188f64.powi(2) / 4.0;
        assert!((b.collapse_load / (8.0 * mp / 0.2) - 1.0).abs() < 1e-12);
        assert!((b.collapse_load / 128.6e3 - 1.0).abs() < 1e-3, "{b:?}");
        // the estimate absorbs exactly K on the square yield curve
        let d = square_yield_energy(b.estimate, 0.0188, b.collapse_load);
        assert!((d / 900.0 - 1.0).abs() < 1e-12);
        // continuity of the two branches at w = h
        let (h, pc) = (0.0188, 1.0);
        let left = square_yield_energy(h, h, pc);
        let right = square_yield_energy(h * (1.0 + 1e-12), h, pc);
        assert!((left - right).abs() < 1e-12);
    }

    /// The inscribing curve absorbs 0.618 of the circumscribing one's energy, so its edge
    /// lies above Jones's estimate and, with membrane forces growing like w^2, far below the
    /// bending edge once w >> h (here 18 kg at 40 m/s on the Table 1 plate: W ~ 3 h).
    #[test]
    fn the_membrane_edge_lies_between_the_estimate_and_the_bending_edge() {
        let mut t = table1();
        t.velocity = 40.0;
        let b = t.bounds();
        let m = INSCRIBED + INSCRIBED * INSCRIBED;
        assert!((m - 1.0).abs() < 1e-15);
        assert!(
            b.estimate < b.membrane_upper && b.membrane_upper < 0.6 * b.upper,
            "{b:?}"
        );
        let k = 0.5 * 18.0 * 1600.0;
        let w = b.membrane_upper - (b.upper - k / b.collapse_load);
        let d = INSCRIBED * square_yield_energy(w, 0.0188, b.collapse_load);
        assert!((d / k - 1.0).abs() < 1e-12, "{d} {k}");
    }

    #[test]
    fn the_band_brackets_the_estimate_and_a_stronger_plate_moves_it_down() {
        let t = table1();
        let b = t.bounds();
        assert!(b.lower < b.estimate && b.estimate < b.upper, "{b:?}");
        assert!(b.energy_ratio > 10.0, "{b:?}");
        let strong = BeamImpact {
            yield_stress: 2.0 * t.yield_stress,
            ..t
        };
        let s = strong.bounds();
        assert!(s.upper < b.upper && s.lower < b.lower, "{s:?}");
        // a slow impact stores its energy elastically: no mechanism, ratio below 1
        let slow = BeamImpact {
            mass: 10.0,
            velocity: 1.25,
            ..t
        };
        assert!(slow.bounds().energy_ratio < 1.0);
        assert_eq!(slow.bounds().lower, 0.0);
    }
}
