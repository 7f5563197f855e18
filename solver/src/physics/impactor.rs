//! The rigid impactor, eqs. (1), (19), (20): with the contact force varying linearly over a
//! step, its velocity and displacement are updated exactly.

/// Impactor state: displacement `delta_S` (m) and velocity (m/s), positive toward the plate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidImpactor {
    /// kg
    pub mass: f64,
    pub displacement: f64,
    pub velocity: f64,
}

impl RigidImpactor {
    pub fn new(mass: f64, velocity: f64) -> RigidImpactor {
        RigidImpactor {
            mass,
            displacement: 0.0,
            velocity,
        }
    }

    /// Displacement at the end of a step of `dt` (s) if the force (N) went from `f0` to `f1`
    /// linearly: eq. (20).
    #[inline]
    pub fn displacement_after(&self, dt: f64, f0: f64, f1: f64) -> f64 {
        self.displacement + self.velocity * dt - (2.0 * f0 + f1) * dt * dt / (6.0 * self.mass)
    }

    /// Advances one step of `dt` with the force going linearly from `f0` to `f1`: eqs. (19)-(20).
    #[inline]
    pub fn advance(&mut self, dt: f64, f0: f64, f1: f64) {
        self.displacement = self.displacement_after(dt, f0, f1);
        self.velocity -= (f0 + f1) * dt / (2.0 * self.mass);
    }

    /// Kinetic energy, J.
    pub fn kinetic_energy(&self) -> f64 {
        0.5 * self.mass * self.velocity * self.velocity
    }
}

#[cfg(test)]
mod tests {
    //! Against the closed-form motion under a constant and a linearly varying force.
    use super::*;

    #[test]
    fn constant_force_motion_is_exact() {
        let (m, v0, f, dt) = (18.0, 10.0, 1.5e5, 1e-7);
        let mut imp = RigidImpactor::new(m, v0);
        let n = 1000;
        for _ in 0..n {
            imp.advance(dt, f, f);
        }
        let t = n as f64 * dt;
        assert!((imp.velocity - (v0 - f / m * t)).abs() < 1e-12 * v0);
        let x = v0 * t - 0.5 * f / m * t * t;
        assert!((imp.displacement - x).abs() < 1e-12 * x);
    }

    #[test]
    fn linear_force_motion_is_exact() {
        // F(t) = k t: v = v0 - k t^2 / (2m), x = v0 t - k t^3 / (6m).
        let (m, v0, k, dt) = (10.0, 5.0, 3e9, 1e-7);
        let mut imp = RigidImpactor::new(m, v0);
        let n = 2000;
        for i in 0..n {
            imp.advance(dt, k * i as f64 * dt, k * (i + 1) as f64 * dt);
        }
        let t = n as f64 * dt;
        let v = v0 - k * t * t / (2.0 * m);
        let x = v0 * t - k * t * t * t / (6.0 * m);
        assert!(
            (imp.velocity - v).abs() < 1e-12 * v0,
            "{} vs {v}",
            imp.velocity
        );
        assert!((imp.displacement - x).abs() < 1e-12 * x.abs());
    }
}
