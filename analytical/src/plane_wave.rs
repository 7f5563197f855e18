//! Plane-strain plane waves: the dilatational speed `c_P = sqrt((lambda + 2 mu) / rho)` and
//! the shear speed `c_S = sqrt(mu / rho)` (Graff, *Wave Motion in Elastic Solids*, sec. 5.1),
//! and the plane-wave problem that measures them with the solver (the harness's builtin
//! `plane-wave` and the work-precision benchmark's `wave-p`).

/// Lame's `(lambda, mu)`, Pa, of `E` (Pa) and `nu`.
fn lame(youngs_modulus: f64, poisson_ratio: f64) -> (f64, f64) {
    let (e, nu) = (youngs_modulus, poisson_ratio);
    let lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
    let mu = e / (2.0 * (1.0 + nu));
    (lambda, mu)
}

/// The plane-strain P-wave speed, m/s, of `E` (Pa), `nu` and density (kg/m^3).
pub fn p_wave_speed(youngs_modulus: f64, poisson_ratio: f64, density: f64) -> f64 {
    let (lambda, mu) = lame(youngs_modulus, poisson_ratio);
    ((lambda + 2.0 * mu) / density).sqrt()
}

/// The S-wave speed, m/s, of `E` (Pa), `nu` and density (kg/m^3).
pub fn s_wave_speed(youngs_modulus: f64, poisson_ratio: f64, density: f64) -> f64 {
    let (_, mu) = lame(youngs_modulus, poisson_ratio);
    (mu / density).sqrt()
}

/// A plane-strain plane wave through the thickness: `wave` "p" (roller ends, 1 MPa normal
/// traction step on the top surface) or "s" (slider ends, 1 MPa shear traction step), full
/// model 4 x `ny` of `element` through h = 20 mm, run for 8 us at `cfl`, probe M at
/// mid-depth. The speed comes from the momentum balance of the layer above the probe at depth
/// d: int_0^T (tau - sigma(d, t)) dt = tau d / c once the front has passed and before its
/// reflection returns, whatever the numerical dispersion of the front.
pub struct PlaneWave {
    /// The probe's stress column whose deficit gives the speed (M_syy_Pa or M_sxy_Pa), and
    /// the sign that makes the 1 MPa traction positive in it.
    column: &'static str,
    sign: f64,
    pub ny: usize,
    pub scene: impact_solver::Scene,
    /// The closed-form speed, m/s: c_P = sqrt((lambda + 2 mu)/rho) or c_S = sqrt(mu/rho).
    pub exact_mps: f64,
}

const WAVE_H: f64 = 0.02;

impl PlaneWave {
    /// Errors: a wave other than "p" or "s"; a scene the solver refuses (its message: `ny`
    /// odd or < 2, `cfl` out of (0, 1]).
    pub fn new(
        wave: &str,
        ny: usize,
        element: impact_solver::scene::ElementKind,
        cfl: f64,
    ) -> Result<Self, String> {
        let (e, nu, rho, h): (f64, f64, f64, f64) = (207e9, 0.3, 7850.0, WAVE_H);
        let (column, sign, ends, traction, exact_mps) = match wave {
            "p" => (
                "M_syy_Pa",
                -1.0,
                "roller",
                "normal: 1.0e6",
                p_wave_speed(e, nu, rho),
            ),
            "s" => (
                "M_sxy_Pa",
                1.0,
                "slider",
                "shear: 1.0e6",
                s_wave_speed(e, nu, rho),
            ),
            o => return Err(format!("wave {o:?}: expected p or s")),
        };
        let text = format!(
            "plate: {{length: 0.2, width: 0.2, thickness: {h}, ends: {ends}}}\n\
             material: {{density: {rho}, youngs_modulus: {e}, poisson_ratio: {nu}}}\n\
             mesh: {{nx: 4, ny: {ny}, element: {}, model: full}}\n\
             load: {{traction: {{{traction}, duration: 1.0}}}}\n\
             time: {{end: 8.0e-6, dt: {{cfl: {cfl}}}}}\n\
             output: {{probes: {{M: {{x: 0.1, y: 0.01}}}}}}\n",
            element.name()
        );
        let scene =
            impact_solver::Scene::from_yaml(&text, std::path::Path::new("(builtin plane-wave)"))
                .map_err(|e| e.to_string())?;
        Ok(PlaneWave {
            column,
            sign,
            ny,
            scene,
            exact_mps,
        })
    }

    /// The measured speed, m/s, from the momentum deficit of the layer above the probe:
    /// `int_0^T (tau - sigma(d, t)) dt = tau d / c` before the reflection returns.
    pub fn measured_speed(&self, history: &impact_solver::History) -> Result<f64, String> {
        // The probe (y = h/2) lies in the element row just below mid-depth; the stress of that
        // row is the force between its node rows, so the depth is its centre's.
        let (h, dy) = (WAVE_H, WAVE_H / self.ny as f64);
        let depth = h - (0.5 * h - 0.5 * dy);
        let until = 0.97 * (2.0 * h - depth) / self.exact_mps;
        let deficit = history
            .time_integral(self.column, until, |s| 1.0 - self.sign * s / 1e6)
            .ok_or_else(|| format!("no column {}", self.column))?;
        Ok(depth / deficit)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steel_wave_speeds_and_a_refused_wave() {
        // Steel, E = 207 GPa, nu = 0.3, rho = 7850 kg/m^3: c_P = 5958 m/s and c_S = 3185 m/s
        // (c_P / c_S = sqrt(2 (1 - nu) / (1 - 2 nu)) = 1.8708).
        let (cp, cs) = (
            p_wave_speed(207e9, 0.3, 7850.0),
            s_wave_speed(207e9, 0.3, 7850.0),
        );
        // The references are rounded to 1 m/s (computed 5957.96 and 3184.66); a (1 - 2 nu)
        // slipped to (1 - nu) moves c_P by ~1000 m/s.
        assert!((cp - 5958.0).abs() < 1.0, "{cp}");
        assert!((cs - 3185.0).abs() < 1.0, "{cs}");
        assert!((cp / cs - (2.0 * 0.7 / 0.4f64).sqrt()).abs() < 1e-12);
        let sri = impact_solver::scene::ElementKind::Q4Sri;
        assert!(PlaneWave::new("q", 80, sri, 0.5).is_err());
        assert!(PlaneWave::new("p", 80, sri, 1.5).is_err());
    }
}
