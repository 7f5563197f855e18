//! The cube root of a ratio near 1, written once over [`Real`] like [`super::transcendental`]:
//! F-bar's factor `(J_bar / J)^(1/3)` in the axisymmetric `q4-sri` element under finite
//! deformation, where the element's volume change over a point's stays within a few per cent
//! of 1 (plastic flow keeps the volume; the points of one element differ by their elastic
//! dilatations).
//!
//! On `[3/4, 4/3]`: `z = x^(-1/3)` from the cubic Taylor polynomial of `(1 + t)^(-1/3)`
//! (`t = x - 1`, relative error at most 1.5e-3 there), three Newton steps on `x z^3 = 1`,
//! `z <- z + z (1 - x z^3) / 3` (no division; quadratic: 1.5e-3, 4.6e-6, 4.3e-11, then the
//! rounding), and `x^(1/3) = x z^2`. Outside the interval (and at 0, below 0, at `inf`) the
//! lanes take [`pow`]`(x, 1/3)`, computed only when a lane needs it. Every step one IEEE
//! operation, so the scalar path and the lanes keep the same bits.

use crate::lanes::real::{Real, THIRD};
use crate::lanes::transcendental::pow;

/// The interval of the polynomial start and the three Newton steps.
const LOW: f64 = 0.75;
const HIGH: f64 = 4.0 / 3.0;

/// The Taylor coefficients of `(1 + t)^(-1/3)` after the constant: `-1/3`, `2/9`, `-14/81`.
const C1: f64 = -1.0 / 3.0;
const C2: f64 = 2.0 / 9.0;
const C3: f64 = -14.0 / 81.0;

/// `x^(1/3)` per lane: within 5 ulp of libm's `cbrt` on `[3/4, 4/3]` (sampled), [`pow`]'s bound
/// elsewhere (NaN below 0 and at NaN, 0 at 0, `inf` at `inf`).
#[inline(always)]
pub fn cube_root<R: Real>(x: R) -> R {
    let one = R::splat(1.0);
    // NaN counts as near: it goes through the steps and comes out NaN.
    let near = R::and(R::not(R::splat(LOW).gt(x)), R::not(x.gt(R::splat(HIGH))));
    let x_near = R::select(near, x, one);
    let t = x_near - 1.0;
    let mut z = one + t * (R::splat(C1) + t * (R::splat(C2) + t * C3));
    for _ in 0..3 {
        z = z + z * (one - x_near * (z * z * z)) * THIRD;
    }
    let root = x_near * (z * z);
    if R::any(R::not(near)) {
        R::select(near, root, pow(x, THIRD))
    } else {
        root
    }
}

#[cfg(test)]
mod tests {
    //! Against the platform's `f64::cbrt` (libm): within 10 ulp on `[3/4, 4/3]` (sampled
    //! densely, and at its ends and their neighbours; measured 5, the roundings of `x z^3` and
    //! of the two products after the steps), `pow`'s bound outside it, the edges (0, `inf`,
    //! NaN, below 0) as `pow`'s; the lanes bit for bit the scalar path, with lanes inside and
    //! outside the interval in one vector (`lanes::accuracy`, as `transcendental`'s tests). Wrong models each fails (tried): a Newton step too
    //! few, a sign slip in the cubic Taylor coefficient (819 ulp), the fallback not taken
    //! outside the interval (the steps diverge).
    use super::*;
    use crate::lanes::accuracy::worst;

    /// Measured 5: the roundings of `x z^3` and of the two products after the steps.
    const NEAR_ONE_ULP: f64 = 10.0;

    /// pow(x, 1/3)'s bound, `2 + 2 |ln x| / 3` ulp (`transcendental`'s module documentation).
    fn pow_bound(x: f64) -> f64 {
        2.0 + 2.0 * (x.ln() / 3.0).abs()
    }

    #[test]
    fn within_ten_ulp_near_one() {
        let mut xs: Vec<f64> = (0..=400_000)
            .map(|i| LOW + (HIGH - LOW) * i as f64 / 400_000.0)
            .collect();
        for edge in [LOW, HIGH, 1.0] {
            xs.extend([
                edge,
                f64::from_bits(edge.to_bits() + 1),
                f64::from_bits(edge.to_bits() - 1),
            ]);
        }
        let w = worst(&xs, cube_root, cube_root::<f64>, f64::cbrt, |_| {
            NEAR_ONE_ULP
        });
        println!("cube_root: at most {w} ulp from libm on [3/4, 4/3]");
    }

    #[test]
    fn outside_the_interval_it_is_pow() {
        // Mixed vectors: every eighth number outside, the rest inside.
        let xs: Vec<f64> = (0..4000)
            .map(|i| {
                if i % 8 == 3 {
                    1e-6 * (1.0 + i as f64)
                } else {
                    0.8 + 1e-4 * i as f64
                }
            })
            .chain([10.0, 0.5, 1e300, 5e-324])
            .collect();
        let near = |x: f64| (LOW..=HIGH).contains(&x);
        let bound = |x: f64| if near(x) { NEAR_ONE_ULP } else { pow_bound(x) };
        worst(&xs, cube_root, cube_root::<f64>, f64::cbrt, bound);
        for x in [10.0, 0.5, 1e-3, 27.0] {
            assert_eq!(cube_root(x), pow(x, THIRD), "{x}");
        }
        assert!(cube_root(f64::NAN).is_nan() && cube_root(-1.0).is_nan());
        assert_eq!(cube_root(0.0), 0.0);
        assert_eq!(cube_root(f64::INFINITY), f64::INFINITY);
    }
}
