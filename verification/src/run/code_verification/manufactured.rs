//! A manufactured solution (Roache 2002, "Code verification by the method of manufactured
//! solutions", J. Fluids Eng. 124:4-10; Oberkampf & Roy 2010, ch. 6) for plane-strain linear
//! elastodynamics on the rectangle [0, L] x [0, H], vanishing on its whole boundary:
//!
//!   u_x = A sin(pi x / L) sin(pi y / H) cos(w t)
//!   u_y = B sin(2 pi x / L) sin(pi y / H) cos(w t)
//!
//! It satisfies `rho u'' = div sigma + b` with the body force
//!   b = rho u'' - div sigma,  div sigma = ((l + 2m) u_x,xx + m u_x,yy + (l + m) u_y,xy,
//!                                         m u_y,xx + (l + 2m) u_y,yy + (l + m) u_x,xy)
//! (Lame constants l, m from E and nu written here, not taken from the solver's material code).
//! Both components, shear and dilatation are nonzero, so no term of the element can be wrong
//! unnoticed; the field is smooth, so the formal orders apply (2 in space for the bilinear
//! quad in displacement, 2 in time for central differences).

use std::f64::consts::PI;

/// The manufactured field and its data, SI units.
#[derive(Debug, Clone, Copy)]
pub struct Manufactured {
    /// Domain, m.
    pub length: f64,
    pub height: f64,
    /// Amplitudes, m.
    pub amp_x: f64,
    pub amp_y: f64,
    /// Angular frequency, rad/s.
    pub omega: f64,
    /// kg/m^3
    pub density: f64,
    /// Lame constants, Pa.
    lambda: f64,
    mu: f64,
}

impl Manufactured {
    /// Checked constructor: positive sizes, density, modulus, frequency; nu in (-1, 0.5).
    pub fn new(
        length: f64,
        height: f64,
        youngs_modulus: f64,
        poisson_ratio: f64,
        density: f64,
        omega: f64,
    ) -> Result<Self, String> {
        let positive = [
            ("length", length),
            ("height", height),
            ("youngs_modulus", youngs_modulus),
            ("density", density),
            ("omega", omega),
        ];
        for (name, v) in positive {
            if !(v.is_finite() && v > 0.0) {
                return Err(format!("manufactured solution: {name} = {v}: must be > 0"));
            }
        }
        if !(poisson_ratio > -1.0 && poisson_ratio < 0.5) {
            return Err(format!(
                "manufactured solution: poisson_ratio = {poisson_ratio}: must lie in (-1, 0.5)"
            ));
        }
        let (e, nu) = (youngs_modulus, poisson_ratio);
        Ok(Manufactured {
            length,
            height,
            amp_x: 1.0e-5 * length,
            amp_y: 0.5e-5 * length,
            omega,
            density,
            lambda: e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)),
            mu: e / (2.0 * (1.0 + nu)),
        })
    }

    /// Spatial shape (without the time factor) and its second derivatives:
    /// `[u_x, u_y]`, `[u_x,xx, u_x,yy, u_x,xy]`, `[u_y,xx, u_y,yy, u_y,xy]`.
    fn shape(&self, x: [f64; 2]) -> ([f64; 2], [f64; 3], [f64; 3]) {
        let (kx, ky) = (PI / self.length, PI / self.height);
        let (s1, c1) = (kx * x[0]).sin_cos();
        let (s2, c2) = (2.0 * kx * x[0]).sin_cos();
        let (sy, cy) = (ky * x[1]).sin_cos();
        let (a, b) = (self.amp_x, self.amp_y);
        let u = [a * s1 * sy, b * s2 * sy];
        let dux = [
            -a * kx * kx * s1 * sy,
            -a * ky * ky * s1 * sy,
            a * kx * ky * c1 * cy,
        ];
        let duy = [
            -b * 4.0 * kx * kx * s2 * sy,
            -b * ky * ky * s2 * sy,
            b * 2.0 * kx * ky * c2 * cy,
        ];
        (u, dux, duy)
    }

    /// Displacement at `x` (m) and time `t` (s), m.
    pub fn displacement(&self, x: [f64; 2], t: f64) -> [f64; 2] {
        let g = (self.omega * t).cos();
        let (u, _, _) = self.shape(x);
        [u[0] * g, u[1] * g]
    }

    /// Velocity, m/s.
    pub fn velocity(&self, x: [f64; 2], t: f64) -> [f64; 2] {
        let g = -self.omega * (self.omega * t).sin();
        let (u, _, _) = self.shape(x);
        [u[0] * g, u[1] * g]
    }

    /// Body force per volume `rho u'' - div sigma`, N/m^3.
    pub fn body_force(&self, x: [f64; 2], t: f64) -> [f64; 2] {
        let g = (self.omega * t).cos();
        let (u, dux, duy) = self.shape(x);
        let (l, m) = (self.lambda, self.mu);
        let div = [
            (l + 2.0 * m) * dux[0] + m * dux[1] + (l + m) * duy[2],
            m * duy[0] + (l + 2.0 * m) * duy[1] + (l + m) * dux[2],
        ];
        let acc = -self.omega * self.omega;
        [
            (self.density * acc * u[0] - div[0]) * g,
            (self.density * acc * u[1] - div[1]) * g,
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The body force balances the equation of motion: checked with finite differences of
    /// the displacement (stress from the strain by Hooke's law written out here).
    #[test]
    fn body_force_balances_the_equation_of_motion() {
        let (e, nu, rho) = (207e9, 0.3, 7850.0);
        let m = Manufactured::new(0.2, 0.05, e, nu, rho, 1e5).unwrap();
        let lam = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
        let mu = e / (2.0 * (1.0 + nu));
        let stress = |x: [f64; 2], t: f64| {
            let h = 1e-6;
            let d = |dx: f64, dy: f64| m.displacement([x[0] + dx, x[1] + dy], t);
            let (xp, xm, yp, ym) = (d(h, 0.0), d(-h, 0.0), d(0.0, h), d(0.0, -h));
            let exx = (xp[0] - xm[0]) / (2.0 * h);
            let eyy = (yp[1] - ym[1]) / (2.0 * h);
            let gxy = (yp[0] - ym[0] + xp[1] - xm[1]) / (2.0 * h);
            [
                lam * (exx + eyy) + 2.0 * mu * exx,
                lam * (exx + eyy) + 2.0 * mu * eyy,
                mu * gxy,
            ]
        };
        let (x, t, h, dt) = ([0.063, 0.017], 2.3e-5, 1e-4, 1e-8);
        let sxp = stress([x[0] + h, x[1]], t);
        let sxm = stress([x[0] - h, x[1]], t);
        let syp = stress([x[0], x[1] + h], t);
        let sym = stress([x[0], x[1] - h], t);
        let div = [
            (sxp[0] - sxm[0] + syp[2] - sym[2]) / (2.0 * h),
            (sxp[2] - sxm[2] + syp[1] - sym[1]) / (2.0 * h),
        ];
        let (up, u0, um) = (
            m.displacement(x, t + dt),
            m.displacement(x, t),
            m.displacement(x, t - dt),
        );
        let b = m.body_force(x, t);
        for c in 0..2 {
            let acc = (up[c] - 2.0 * u0[c] + um[c]) / (dt * dt);
            let residual = rho * acc - div[c] - b[c];
            assert!(
                residual.abs() < 1e-3 * b[c].abs(),
                "{c}: {residual} vs {}",
                b[c]
            );
        }
    }

    #[test]
    fn bad_data_is_refused() {
        assert!(Manufactured::new(0.2, 0.05, 207e9, 0.5, 7850.0, 1e5).is_err());
        assert!(Manufactured::new(0.2, -0.05, 207e9, 0.3, 7850.0, 1e5).is_err());
    }
}
