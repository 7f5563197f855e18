//! The rigid impactor, eqs. (1), (19), (20): with the contact force varying linearly over a
//! step, its velocity and displacement are updated exactly (the nodal coupling); under the
//! surface coupling it takes the plate's central differences ([`CentralDifferenceImpactor`]).

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

/// The impactor of the surface coupling, integrated by the plate's central differences (eqs.
/// 8-12 for one rigid body on y): `v_{n+1/2} = v_{n-1/2} - dt F_n / m` (the first step
/// `v_{1/2} = v_0 - dt F_0 / (2 m)`), `delta_{n+1} = delta_n + dt v_{n+1/2}`. The momentum it
/// loses is exactly `dt (F_0/2 + F_1 + ... + F_{N-1} + F_N/2)`, the trapezoidal impulse, when
/// its velocity at `t_N` is read as `v_{N-1/2} - dt F_N / (2 m)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CentralDifferenceImpactor {
    /// kg
    pub mass: f64,
    /// `delta_n`, m, positive toward the plate.
    pub displacement: f64,
    /// `v_{n-1/2}` (`v_0` before the first step), m/s, positive toward the plate.
    pub half_step_velocity: f64,
    started: bool,
}

impl CentralDifferenceImpactor {
    pub fn new(mass: f64, velocity: f64) -> CentralDifferenceImpactor {
        CentralDifferenceImpactor {
            mass,
            displacement: 0.0,
            half_step_velocity: velocity,
            started: false,
        }
    }

    /// The velocity at `t_n` under the force `F_n` (N), m/s: the mean of `v_{n-1/2}` and
    /// `v_{n+1/2}` for the velocity step `h` (s; the step itself when steps are equal).
    pub fn velocity(&self, h: f64, force: f64) -> f64 {
        if self.started {
            self.half_step_velocity - 0.5 * h * force / self.mass
        } else {
            self.half_step_velocity
        }
    }

    /// The displacement at `t_{n+1}` if no force acted at `t_n`, m.
    pub fn free_displacement(&self, dt: f64) -> f64 {
        self.displacement + dt * self.half_step_velocity
    }

    /// From `t_n` to `t_{n+1}` (`dt` s) under `F_n` (N), with the velocity step `h` (s:
    /// `dt / 2` at the first step, `dt` when steps are equal).
    pub fn advance(&mut self, (dt, h): (f64, f64), force: f64) {
        self.half_step_velocity -= h * force / self.mass;
        self.displacement += dt * self.half_step_velocity;
        self.started = true;
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

    #[test]
    fn central_differences_lose_the_trapezoidal_impulse() {
        // Forces F_n = 1, 2, 3, 4 N at t_0..t_3 with dt = 0.5 s, m = 2 kg, v_0 = 10 m/s: the
        // velocity at t_3 is v_0 - dt (F_0/2 + F_1 + F_2 + F_3/2) / m = 10 - 0.5 * 7.5 / 2.
        let (dt, m) = (0.5, 2.0);
        let mut body = CentralDifferenceImpactor::new(m, 10.0);
        assert_eq!(body.velocity(dt, 0.0), 10.0);
        let mut x = 0.0;
        for (n, f) in [1.0, 2.0, 3.0].into_iter().enumerate() {
            let v_half = if n == 0 {
                10.0 - 0.25 * f / m
            } else {
                body.half_step_velocity - dt * f / m
            };
            x += dt * v_half;
            body.advance((dt, if n == 0 { 0.5 * dt } else { dt }), f);
            assert_eq!(body.half_step_velocity, v_half);
            assert_eq!(body.displacement, x);
        }
        assert!((body.velocity(dt, 4.0) - (10.0 - 0.5 * 7.5 / 2.0)).abs() < 1e-14);
    }
}
