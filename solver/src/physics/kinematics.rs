//! Finite-deformation kinematics of a point (updated Lagrangian, Green-Naghdi rate), written
//! once over [`Real`] like every kernel, and the point's memory between steps.
//!
//! Notation (in-plane, 2 x 2): `G = du/dX` the displacement gradient on the reference
//! configuration, `F = I + G` the deformation gradient, `F = R U` its polar decomposition.
//! Gradients are stored row-major, `[dux/dX, dux/dY, duy/dX, duy/dY]`.
//!
//! One step from `G_n` to `G_{n+1}` (`ALGORITHM.md` section 3c):
//! - the rate of deformation over the step on the mid-step configuration,
//!   `d dt = sym(dG F_mid^-1)`, `F_mid = I + (G_n + G_{n+1}) / 2`, `dG = G_{n+1} - G_n`
//!   (Hughes & Winget 1980's midpoint rule: second-order accurate, and a rigid rotation gives
//!   `sym(dG F_mid^-1) = 0` exactly: for rotations `R_n`, `R_{n+1}`,
//!   `(R_{n+1} - R_n)(R_{n+1} + R_n)^-1 = tan(dtheta / 2) [[0, -1], [1, 0]]` is skew);
//! - the increment in the unrotated frame, `R_mid^T d dt R_mid` (`R_mid` the rotation of
//!   `F_mid`), added to the point's unrotated strain `e^`: the Green-Naghdi rate of the
//!   Kirchhoff stress, `tau^ = R^T tau R` evolving with `R^T d R` (Dienes 1979; Simo & Hughes
//!   1998, section 8.3.2);
//! - the material's stress for `e^` (its total-strain form: radial return, rate laws and all,
//!   unchanged, since isotropic elasticity commutes with the rotation), rotated to the
//!   current frame by `R_{n+1}`: `tau = R tau^ R^T`.
//!
//! Why Green-Naghdi (not Jaumann): in homogeneous simple shear the Jaumann rate's shear
//! stress oscillates (`sigma_xy = mu sin(gamma)`: it falls after `gamma = pi / 2`, Dienes
//! 1979), the Green-Naghdi rate's grows monotonically; the rotation comes from `F` itself, so
//! a rigid rotation of any size maps the stress exactly, whatever the step; and the
//! material sees a strain in a frame that does not rotate, so every model of
//! [`crate::physics::materials::material`] runs as it is. The Jaumann rate's appeal, a rotation from
//! the spin that needs no polar decomposition, is worth nothing here: in 2D the polar
//! rotation costs one square root.
//!
//! The stress is Kirchhoff's, `tau = J sigma`: its stress power per reference volume is
//! `tau : d`, so the material's energy densities per reference volume, times the reference
//! weights, close the energy balance; the yield condition reads `tau` (Simo & Hughes 1998,
//! Box 9.1), which differs from the Cauchy stress by the elastic volume change (`J - 1` about
//! `p / K`, 1e-3 at yield for steel).

use crate::lanes::real::Real;
use crate::lanes::simd::Lanes;

/// A displacement gradient `du/dX`, row-major `[xX, xY, yX, yY]` (dimensionless).
pub type Gradient<R> = [R; 4];

/// What a point of a finite-deformation model remembers between steps (in lanes for a
/// batch, `f64` for one point).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Memory<R> {
    /// `G_n`, the displacement gradient of the last step.
    pub gradient: Gradient<R>,
    /// The unrotated strain `e^` `[xx, yy, zz, gamma_xy]` (engineering shear).
    pub strain: [R; 4],
    /// The hoop displacement gradient `u_r / R` of the last step in the axisymmetric
    /// geometry (`F_theta theta - 1`, dimensionless); zero in plane strain, where it is never
    /// read or written ([`Memory::at`] and [`Memory::store`] leave it out).
    pub hoop: R,
}

impl Memory<Lanes> {
    /// Lane `l`.
    pub fn lane(&self, l: usize) -> Memory<f64> {
        Memory {
            gradient: self.gradient.map(|x| x.0[l]),
            strain: self.strain.map(|x| x.0[l]),
            hoop: self.hoop.0[l],
        }
    }

    /// Sets lane `l`.
    pub fn set_lane(&mut self, l: usize, m: &Memory<f64>) {
        for c in 0..4 {
            self.gradient[c].0[l] = m.gradient[c];
            self.strain[c].0[l] = m.strain[c];
        }
        self.hoop.0[l] = m.hoop;
    }

    /// The memory at `at` ([`Real::of_batch`]), its `hoop` left at zero (the plane
    /// geometry's: [`Memory::hoop_at`] reads the ring's).
    #[inline(always)]
    pub fn at<R: Real>(&self, at: usize) -> Memory<R> {
        Memory {
            gradient: four(|c| R::of_batch(&self.gradient[c], at)),
            strain: four(|c| R::of_batch(&self.strain[c], at)),
            hoop: R::splat(0.0),
        }
    }

    /// The hoop gradient at `at`.
    #[inline(always)]
    pub fn hoop_at<R: Real>(&self, at: usize) -> R {
        R::of_batch(&self.hoop, at)
    }

    /// Writes the hoop gradient `hoop` at `at` where `active` has the lane.
    #[inline(always)]
    pub fn store_hoop<R: Real>(&mut self, at: usize, hoop: R, active: R::Mask) {
        R::store(&mut self.hoop, at, hoop, active);
    }

    /// Writes `m` at `at` where `active` has the lane.
    #[inline(always)]
    pub fn store<R: Real>(&mut self, at: usize, m: &Memory<R>, active: R::Mask) {
        for c in 0..4 {
            R::store(&mut self.gradient[c], at, m.gradient[c], active);
            R::store(&mut self.strain[c], at, m.strain[c], active);
        }
    }
}

/// `[f(0), f(1), f(2), f(3)]`, written out (LLVM may leave `std::array::from_fn` and
/// `array::map` out of line in a kernel: see `crate::lanes::simd::each_lane`).
#[inline(always)]
pub fn four<T>(f: impl Fn(usize) -> T) -> [T; 4] {
    [f(0), f(1), f(2), f(3)]
}

/// `F = I + G`.
#[inline(always)]
pub fn deformation<R: Real>(g: &Gradient<R>) -> [R; 4] {
    [g[0] + 1.0, g[1], g[2], g[3] + 1.0]
}

/// `det F` of a 2 x 2 `F`.
#[inline(always)]
pub fn det<R: Real>(f: &[R; 4]) -> R {
    f[0] * f[3] - f[1] * f[2]
}

/// `F^-1` (row-major) of a 2 x 2 `F` from `1 / det F`.
#[inline(always)]
pub fn inverse_with<R: Real>(f: &[R; 4], inv_det: R) -> [R; 4] {
    let zero = R::splat(0.0);
    [
        f[3] * inv_det,
        zero - f[1] * inv_det,
        zero - f[2] * inv_det,
        f[0] * inv_det,
    ]
}

/// The polar decomposition's rotation `R = [[c, -s], [s, c]]` of a 2 x 2 `F` with `det F > 0`
/// (`c = a / n`, `s = b / n`, `a = F_xx + F_yy`, `b = F_yx - F_xy`, `n^2 = a^2 + b^2`), held by
/// the products `c^2`, `s^2`, `c s`: all that rotating a symmetric tensor takes, so it needs
/// `1 / n^2` and no square root.
#[derive(Debug, Clone, Copy)]
pub struct Rotation<R> {
    cc: R,
    ss: R,
    cs: R,
}

/// `(a, b, n^2)` of `F` ([`Rotation`]).
#[inline(always)]
pub fn polar_terms<R: Real>(f: &[R; 4]) -> (R, R, R) {
    let (a, b) = (f[0] + f[3], f[2] - f[1]);
    (a, b, a * a + b * b)
}

impl<R: Real> Rotation<R> {
    /// From [`polar_terms`] `a`, `b` and `1 / n^2`.
    #[inline(always)]
    pub fn of(a: R, b: R, inv_n2: R) -> Rotation<R> {
        Rotation {
            cc: a * a * inv_n2,
            ss: b * b * inv_n2,
            cs: a * b * inv_n2,
        }
    }

    /// The rotation of `F` (one division).
    #[inline(always)]
    pub fn of_deformation(f: &[R; 4]) -> Rotation<R> {
        let (a, b, n2) = polar_terms(f);
        Rotation::of(a, b, R::splat(1.0) / n2)
    }

    /// `R t R^T` of a symmetric tensor `[xx, yy, zz, xy]` (tensor shear; `zz` unchanged).
    #[inline(always)]
    pub fn apply(&self, t: &[R; 4]) -> [R; 4] {
        rotate(t, self.cc, self.ss, self.cs)
    }

    /// `R^T t R`.
    #[inline(always)]
    pub fn apply_transposed(&self, t: &[R; 4]) -> [R; 4] {
        rotate(t, self.cc, self.ss, R::splat(0.0) - self.cs)
    }
}

/// `R t R^T` for `R = [[c, -s], [s, c]]` given `c^2`, `s^2`, `c s`.
#[inline(always)]
fn rotate<R: Real>(t: &[R; 4], cc: R, ss: R, cs: R) -> [R; 4] {
    let shear = cs * t[3] * 2.0;
    [
        cc * t[0] + ss * t[1] - shear,
        ss * t[0] + cc * t[1] + shear,
        t[2],
        cs * (t[0] - t[1]) + (cc - ss) * t[3],
    ]
}

/// One step's kinematics of a point.
#[derive(Debug, Clone, Copy)]
pub struct Step<R> {
    /// The unrotated strain after the step, `[xx, yy, zz, gamma_xy]`.
    pub strain: [R; 4],
    /// `R_{n+1}`.
    pub rotation: Rotation<R>,
    /// `F_{n+1}^-1` (row-major).
    pub inverse: [R; 4],
}

/// The step from the point's `memory` (`G_n`, `e^_n`) to the gradient `g` (`G_{n+1}`): the
/// unrotated strain after it, the rotation at its end and `F_{n+1}^-1` (module
/// documentation). One division gives the four reciprocals it needs (`det` and `n^2` of
/// `F_mid` and of `F_{n+1}`, each O(1)): `1 / x = r y z w` with `r = 1 / (x y z w)`.
#[inline(always)]
pub fn step<R: Real>(memory: &Memory<R>, g: &Gradient<R>) -> Step<R> {
    let p = &memory.gradient;
    let dg = four(|c| g[c] - p[c]);
    let mid = four(|c| (g[c] + p[c]) * 0.5);
    let (f_mid, f) = (deformation(&mid), deformation(g));
    let (det_mid, det_end) = (det(&f_mid), det(&f));
    let (a_mid, b_mid, n2_mid) = polar_terms(&f_mid);
    let (a, b, n2) = polar_terms(&f);
    let (mid_pair, end_pair) = (det_mid * n2_mid, det_end * n2);
    let r = R::splat(1.0) / (mid_pair * end_pair);
    let (r_mid, r_end) = (r * end_pair, r * mid_pair);
    let inv = inverse_with(&f_mid, r_mid * n2_mid);
    // L dt = dG F_mid^-1, its symmetric part (tensor shear).
    let l_xx = dg[0] * inv[0] + dg[1] * inv[2];
    let l_xy = dg[0] * inv[1] + dg[1] * inv[3];
    let l_yx = dg[2] * inv[0] + dg[3] * inv[2];
    let l_yy = dg[2] * inv[1] + dg[3] * inv[3];
    let d = [l_xx, l_yy, R::splat(0.0), (l_xy + l_yx) * 0.5];
    let dr = Rotation::of(a_mid, b_mid, r_mid * det_mid).apply_transposed(&d);
    let e = &memory.strain;
    Step {
        strain: [e[0] + dr[0], e[1] + dr[1], e[2], e[3] + dr[3] * 2.0],
        rotation: Rotation::of(a, b, r_end * det_end),
        inverse: inverse_with(&f, r_end * n2),
    }
}

/// The unrotated hoop strain after a step of the hoop gradient from `before` to `after`
/// (`u_r / R`, dimensionless), from the one `e_zz` before it: the same midpoint rule as
/// [`step`], `d_theta theta dt = dF / F_mid` with `F = 1 + u_r / R`. The hoop direction is a
/// principal direction that never rotates, so this is the Green-Naghdi increment too.
#[inline(always)]
pub fn hoop_strain<R: Real>(e_zz: R, before: R, after: R) -> R {
    let f_mid = (before + after) * 0.5 + 1.0;
    e_zz + (after - before) / f_mid
}

/// First Piola-Kirchhoff stress `P = tau F^-T` (row-major `[xX, xY, yX, yY]`, Pa) of a
/// symmetric Kirchhoff stress `[xx, yy, zz, xy]` and `F^-1`: the nodal forces are
/// `w_ref P dN/dX`.
#[inline(always)]
pub fn piola<R: Real>(tau: &[R; 4], inv: &[R; 4]) -> [R; 4] {
    [
        tau[0] * inv[0] + tau[3] * inv[1],
        tau[0] * inv[2] + tau[3] * inv[3],
        tau[3] * inv[0] + tau[1] * inv[1],
        tau[3] * inv[2] + tau[1] * inv[3],
    ]
}

#[cfg(test)]
mod tests {
    //! The step's identities: a rigid rotation of any size adds no strain (to round-off) and
    //! its rotation is the applied one; a stretch without rotation integrates to the
    //! logarithmic strain at second order; the polar rotation of a simple shear against the
    //! closed form `tan(theta) = -gamma / 2`. Wrong models each test fails: the increment on
    //! `F_{n+1}^-1` instead of `F_mid^-1` (a rotation then leaves a symmetric part of order
    //! `dtheta^2` per step, ~3e-6 here, and the stretch is first order); the increment not
    //! rotated into the unrotated frame (the stored strain turns with the body); a sign slip in
    //! `s = F_yx - F_xy` (the rotation goes the other way: `c s` changes sign).
    use super::*;

    fn rotation(theta: f64) -> Gradient<f64> {
        let (s, c) = theta.sin_cos();
        [c - 1.0, -s, s, c - 1.0]
    }

    #[test]
    fn a_rigid_rotation_adds_no_strain_and_is_recovered() {
        let strain0 = [1e-3, -2e-3, 5e-4, 3e-3];
        let mut m = Memory {
            gradient: [0.0; 4],
            strain: strain0,
            hoop: 0.0,
        };
        let steps = 1000;
        for k in 1..=steps {
            // 1.7 rad in all: past 90 degrees.
            let g = rotation(1.7 * k as f64 / steps as f64);
            let s = step(&m, &g);
            m = Memory {
                gradient: g,
                strain: s.strain,
                hoop: 0.0,
            };
            let theta = 1.7 * k as f64 / steps as f64;
            let r = s.rotation.apply(&[1.0, 0.0, 0.0, 0.0]);
            let (sn, c) = theta.sin_cos();
            // R e_x e_x R^T = [c^2, s^2, 0, c s]. Bound 1e-15: ~10x the measured 1.1e-16
            // (one rounding of products of O(1) terms).
            assert!(
                (r[0] - c * c).abs() < 1e-15 && (r[3] - c * sn).abs() < 1e-15,
                "{r:?}"
            );
        }
        // Bound 5e-16 on the 1e-3 strains after the 1000 steps: ~10x the measured 4.4e-17
        // (round-off of the increments' sums; the symmetric part of a rotation increment is
        // zero to round-off).
        for c in 0..4 {
            assert!((m.strain[c] - strain0[c]).abs() < 5e-16, "{m:?}");
        }
    }

    #[test]
    fn a_stretch_integrates_to_the_logarithmic_strain_at_second_order() {
        let error = |steps: usize| {
            let mut m = Memory::<f64>::default();
            for k in 1..=steps {
                let g = [0.5 * k as f64 / steps as f64, 0.0, 0.0, 0.0];
                let s = step(&m, &g);
                m = Memory {
                    gradient: g,
                    strain: s.strain,
                    hoop: 0.0,
                };
            }
            (m.strain[0] - 1.5f64.ln()).abs()
        };
        let (coarse, fine) = (error(50), error(100));
        let order = (coarse / fine).log2();
        // Measured 1.99997 (error 2.3e-6 at 50 steps, far above round-off); bound 1e-3,
        // ~40x its distance from 2, as the next term of the midpoint rule's error moves it; a
        // first-order increment gives 1.
        assert!((order - 2.0).abs() < 1e-3, "{coarse:e} {fine:e} {order}");
    }

    #[test]
    fn the_polar_rotation_of_simple_shear() {
        for gamma in [0.1, 1.0, 10.0] {
            let r = Rotation::of_deformation(&deformation(&[0.0, gamma, 0.0, 0.0]));
            let (s, c) = (-gamma / 2.0f64).atan().sin_cos();
            let e = r.apply(&[1.0, 0.0, 0.0, 0.0]);
            // Bound 1e-15: ~10x the measured 1.1e-16.
            assert!(
                (e[0] - c * c).abs() < 1e-15 && (e[1] - s * s).abs() < 1e-15,
                "{e:?}"
            );
            assert!((e[3] - c * s).abs() < 1e-15, "{e:?}");
        }
    }

    #[test]
    fn rotation_maps_a_tensor_as_r_t_r_transposed() {
        let t = [3.0, -1.0, 0.5, 2.0];
        let (s, c) = 0.3f64.sin_cos();
        let r = nalgebra::Matrix2::new(c, -s, s, c);
        let m = nalgebra::Matrix2::new(t[0], t[3], t[3], t[1]);
        let e = r * m * r.transpose();
        let got = Rotation::of(c, s, 1.0).apply(&t);
        // Bound 5e-15 on components of size 3: ~10x the measured 4.4e-16 (nalgebra sums the
        // products in another order).
        for (x, y) in [
            (got[0], e[(0, 0)]),
            (got[1], e[(1, 1)]),
            (got[3], e[(0, 1)]),
        ] {
            assert!((x - y).abs() < 5e-15);
        }
        assert_eq!(got[2], 0.5);
    }
}
