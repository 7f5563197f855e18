//! `ln`, `exp` and `pow` for the kernels, written once over [`Real`]: the batched path runs
//! them on whole vectors, the scalar path runs the same operations on one lane, so both keep
//! the same bits (as `+ - * /` do: no fused multiply-add, every step one IEEE operation or an
//! integer operation on the bits).
//!
//! The algorithms are fdlibm's (Sun Microsystems 1993, as kept in musl's `log.c` and
//! `exp.c`), with the branches turned into per-lane selects:
//! - [`ln`]: `x = 2^k (1 + f)` with `1 + f` in `[sqrt(2)/2, sqrt(2))`, then
//!   `ln(1 + f) = f - f^2/2 + s (f^2/2 + R(s^2))`, `s = f / (2 + f)`, `R` a degree-7
//!   polynomial in `s^2` (error below 1 ulp);
//! - [`exp`]: `x = k ln 2 + r`, `|r| <= ln(2) / 2` (`k` rounded to nearest), then
//!   `exp(r) = 1 + r + r c(r) / (2 - c(r))` with `c` a degree-5 polynomial in `r^2`
//!   (error below 1 ulp), scaled by `2^k` in two exact factors so that subnormal results
//!   round once;
//! - [`pow`]: `x^y = exp(y ln x)` for `x >= 0`. The rounding of `ln x` is magnified by
//!   `|y ln x|`: `ln x` within 1 ulp is a relative error of at most `2^-52 |y ln x|` in the
//!   result, which with the product's and exp's roundings keeps it within `2 + 2 |y ln x|` ulp
//!   (tested point by point over the ranges the flow laws use; 33 ulp at most for `x^1.1` on
//!   `[1e-14, 1e8]`, where `|y ln x|` reaches 35).
//!
//! Against `f64::ln/exp/powf` (the platform's libm, one lane at a time): 3-10x fewer cycles
//! per lane on AVX-512, whose eight lanes run each polynomial at once.

use crate::lanes::real::Real;

/// `ln 2` in two parts: `LN2_HI` has its low 32 bits zero, so `k * LN2_HI` is exact for
/// `|k| < 2^20`.
const LN2_HI: f64 = 6.931_471_803_691_238_164_90e-1;
const LN2_LO: f64 = 1.908_214_929_270_587_700_02e-10;
/// `1 / ln 2`.
const INV_LN2: f64 = 1.442_695_040_888_963_387_00;
/// fdlibm's `Lg1..Lg7`: the minimax polynomial of `ln(1 + f)`'s remainder in `s^2`.
const LG: [f64; 7] = [
    6.666_666_666_666_735_130e-1,
    3.999_999_999_940_941_908e-1,
    2.857_142_874_366_239_149e-1,
    2.222_219_843_214_978_396e-1,
    1.818_357_216_161_805_012e-1,
    1.531_383_769_920_937_332e-1,
    1.479_819_860_511_658_591e-1,
];
/// fdlibm's `P1..P5`: the minimax polynomial of `exp`'s remainder in `r^2`.
const P: [f64; 5] = [
    1.666_666_666_666_660_190_37e-1,
    -2.777_777_777_701_559_338_42e-3,
    6.613_756_321_437_934_361_17e-5,
    -1.653_390_220_546_525_153_90e-6,
    4.138_136_797_057_238_460_39e-8,
];
/// Above this `exp` overflows to infinity, below [`EXP_UNDERFLOW`] it is 0.
const EXP_OVERFLOW: f64 = 7.097_827_128_933_840e2;
const EXP_UNDERFLOW: f64 = -7.451_332_191_019_412e2;
/// `1.5 * 2^52`: adding it rounds to a whole number (to nearest, ties to even) held in the
/// low bits of the sum.
const ROUNDER: f64 = 6_755_399_441_055_744.0;
/// `2^54`, which lifts a subnormal into the normal range.
const TWO_54: f64 = 18_014_398_509_481_984.0;
/// The high word of `sqrt(2)/2` (0x3fe6a09e): [`ln`]'s reduction puts the mantissa above it.
const SQRT_HALF_HIGH: u64 = 0x3fe6_a09e;

/// Natural logarithm per lane: `-inf` at 0, NaN below 0 and at NaN, `inf` at `inf`; below
/// 1 ulp elsewhere, subnormals included.
#[inline(always)]
pub fn ln<R: Real>(x: R) -> R {
    let subnormal = R::splat(f64::MIN_POSITIVE).gt(x);
    let scaled = R::select(subnormal, x * TWO_54, x);
    let k = exponent_of(scaled) - R::select(subnormal, R::splat(54.0), R::splat(0.0));
    let f = mantissa_of(scaled) - 1.0;
    let half_f2 = f * f * 0.5;
    let s = f / (f + 2.0);
    let z = s * s;
    let w = z * z;
    let odd = w * (w * (w * LG[5] + LG[3]) + LG[1]);
    let even = z * (w * (w * (w * LG[6] + LG[4]) + LG[2]) + LG[0]);
    let r = even + odd;
    let value = s * (half_f2 + r) + k * LN2_LO - half_f2 + f + k * LN2_HI;
    let regular = R::and(x.gt(R::splat(0.0)), R::splat(f64::INFINITY).gt(x));
    R::select(regular, value, x.map_lanes(ln_edge))
}

/// `ln` where the polynomial does not apply: 0, negative numbers, `inf` and NaN.
#[inline(always)]
fn ln_edge(x: f64) -> f64 {
    if x == 0.0 {
        f64::NEG_INFINITY
    } else if x == f64::INFINITY {
        x
    } else {
        f64::NAN
    }
}

/// `k` of `x = 2^k m` with `m` in `[sqrt(2)/2, sqrt(2))`, as a whole `f64` (`x` positive
/// and normal). The sum of `k + 1023` into the bits of `2^52` makes it exact without an
/// integer conversion.
#[inline(always)]
fn exponent_of<R: Real>(x: R) -> R {
    x.map_lanes(|v| {
        let high = (v.to_bits() >> 32) + (0x3ff0_0000 - SQRT_HALF_HIGH);
        f64::from_bits(0x4330_0000_0000_0000 | (high >> 20)) - (4_503_599_627_370_496.0 + 1023.0)
    })
}

/// `m` of `x = 2^k m` (see [`exponent_of`]).
#[inline(always)]
fn mantissa_of<R: Real>(x: R) -> R {
    x.map_lanes(|v| {
        let bits = v.to_bits();
        let high = (((bits >> 32) + (0x3ff0_0000 - SQRT_HALF_HIGH)) & 0x000f_ffff) + SQRT_HALF_HIGH;
        f64::from_bits((high << 32) | (bits & 0xffff_ffff))
    })
}

/// `e^x` per lane: `inf` above 709.78, 0 below -745.13, NaN at NaN; below 1 ulp elsewhere,
/// subnormal results included.
#[inline(always)]
pub fn exp<R: Real>(x: R) -> R {
    // NaN counts as inside: it goes through the polynomial and comes out NaN.
    let inside = R::and(
        R::not(x.gt(R::splat(EXP_OVERFLOW))),
        R::not(R::splat(EXP_UNDERFLOW).gt(x)),
    );
    // Inside the range only, so that k ln 2 is exact and the rounder rounds.
    let x_in = R::select(inside, x, R::splat(0.0));
    let rounded = x_in * INV_LN2 + ROUNDER;
    let k = rounded - ROUNDER;
    let hi = x_in - k * LN2_HI;
    let lo = k * LN2_LO;
    let r = hi - lo;
    let r2 = r * r;
    let c = r - r2 * (r2 * (r2 * (r2 * (r2 * P[4] + P[3]) + P[2]) + P[1]) + P[0]);
    let y = R::splat(1.0) + (r * c / (R::splat(2.0) - c) - lo + hi);
    // 2^k as two powers of two, each normal for |k| <= 1075: the first product is exact, the
    // second rounds once (into the subnormals when the result is one).
    let low_half = rounded.map_lanes(|v| power_of_two(whole_of(v) >> 1));
    let high_half = rounded.map_lanes(|v| {
        let k = whole_of(v);
        power_of_two(k - (k >> 1))
    });
    let edge = x.map_lanes(|v| if v > 0.0 { f64::INFINITY } else { 0.0 });
    R::select(inside, y * low_half * high_half, edge)
}

/// The whole number `k` held in the low bits of `k + 1.5 * 2^52` (see [`ROUNDER`]).
#[inline(always)]
fn whole_of(rounded: f64) -> i64 {
    rounded.to_bits() as i64 - ROUNDER.to_bits() as i64
}

/// `2^k` for `k` in the normal range `[-1022, 1023]`.
#[inline(always)]
fn power_of_two(k: i64) -> f64 {
    f64::from_bits(((k + 1023) as u64) << 52)
}

/// `x^y` per lane for `x >= 0` (NaN below 0): `exp(y ln x)`, `0^y` 0 for `y > 0` and `inf` for
/// `y < 0`, `x^0 = 1`; the error bound in the module documentation.
#[inline(always)]
pub fn pow<R: Real>(x: R, y: f64) -> R {
    pow_of_ln(ln(x), y)
}

/// `x^y` from `ln x` (see [`pow`]): two powers of one base share its logarithm.
#[inline(always)]
pub fn pow_of_ln<R: Real>(ln_x: R, y: f64) -> R {
    if y == 0.0 {
        return R::splat(1.0);
    }
    exp(ln_x * y)
}

#[cfg(test)]
mod tests {
    //! Against the platform's `f64::ln`, `f64::exp` and `f64::powf` (libm, correctly rounded
    //! or nearly): at most 1 ulp for `ln` and `exp` over their whole ranges (sampled), the
    //! stated bound for `pow` over the flow laws' ranges, the edges (0, subnormals, huge,
    //! infinities, NaN) exactly, and the batched lanes bit for bit equal to the scalar path.
    use super::*;
    use crate::lanes::accuracy::{log_spread, ulps, worst};

    #[test]
    fn ln_is_within_one_ulp_over_the_whole_range() {
        let mut xs = log_spread(5e-324, f64::MAX, 200_000);
        xs.extend(log_spread(0.5, 2.0, 100_000)); // near 1, where ln is small
        let w = worst(&xs, ln, ln::<f64>, f64::ln, |_| 1.0);
        println!("ln: at most {w} ulp from libm over {} points", xs.len());
    }

    #[test]
    fn exp_is_within_one_ulp_over_the_whole_range() {
        let mut xs: Vec<f64> = (0..=400_000)
            .map(|i| -745.13 + 1454.9 * i as f64 / 400_000.0)
            .collect();
        xs.extend(
            log_spread(1e-300, 1.0, 20_000)
                .iter()
                .flat_map(|x| [*x, -*x]),
        );
        let w = worst(&xs, exp, exp::<f64>, f64::exp, |_| 1.0);
        println!("exp: at most {w} ulp from libm over {} points", xs.len());
    }

    /// The flow laws' ranges: strains 1e-14..10 to Johnson-Cook's n and n - 1 and
    /// Cowper-Symonds' 1/q, rate ratios to 1e8, homologous temperatures to m, each point within
    /// `2 + 2 |y ln x|` ulp (the bound of the module documentation).
    #[test]
    fn pow_is_within_its_bound_over_the_flow_laws_ranges() {
        let xs = log_spread(1e-14, 1e8, 50_000);
        for y in [
            0.168,
            -0.832,
            0.31,
            -0.69,
            1.1,
            1.0 / 3.0,
            0.2,
            1.0 / 12.0,
            5.0,
            1e3,
        ] {
            // ln's 1 ulp magnified by |y ln x|, with the product's and exp's roundings.
            let bound = |x: f64| 2.0 + 2.0 * (y * x.ln()).abs();
            let theirs = |x: f64| x.powf(y);
            let xs: Vec<f64> = xs
                .iter()
                .copied()
                .filter(|x| theirs(*x).is_normal())
                .collect();
            let w = worst(&xs, |x| pow(x, y), |x| pow::<f64>(x, y), theirs, bound);
            println!("pow(x, {y}): at most {w} ulp from libm");
        }
    }

    #[test]
    fn the_edges_are_those_of_the_platform() {
        let edges = [
            0.0,
            -0.0,
            5e-324,
            2.2e-308,
            f64::MIN_POSITIVE,
            1.0,
            f64::MAX,
            f64::INFINITY,
            -1.0,
            f64::NEG_INFINITY,
            f64::NAN,
            709.782712893384,
            709.79,
            -745.1332191019411,
            -745.14,
            -708.5,
            1e-300,
        ];
        for x in edges {
            let same = |a: f64, b: f64| (a.is_nan() && b.is_nan()) || a == b || ulps(a, b) <= 1;
            assert!(
                same(ln(x), x.ln()),
                "ln({x:e}) = {:e}, libm {:e}",
                ln(x),
                x.ln()
            );
            assert!(
                same(exp(x), x.exp()),
                "exp({x:e}) = {:e}, libm {:e}",
                exp(x),
                x.exp()
            );
            if x >= 0.0 || x.is_nan() {
                for y in [0.168, -0.832, 2.0] {
                    let (a, b) = (pow(x, y), x.powf(y));
                    // The bound of pow_is_within_its_bound_over_the_flow_laws_ranges (|y ln x|
                    // reaches 620 here, at 5e-324).
                    let bound = 2.0 + 2.0 * (y * x.ln()).abs();
                    let close = (a.is_nan() && b.is_nan()) || a == b || ulps(a, b) as f64 <= bound;
                    assert!(close, "pow({x:e}, {y}) = {a:e}, libm {b:e}");
                }
            }
            assert_eq!(pow(x, 0.0), 1.0);
        }
    }
}
