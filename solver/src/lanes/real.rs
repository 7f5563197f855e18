//! The number type the element and material kernels are written in, once: `f64` on the
//! scalar reference path (one element at a time), [`Lanes`] on the batched path ([`LANES`]
//! elements at a time, [`crate::kernels::batch`]). Every operation is one IEEE operation per lane, so
//! a kernel written once over [`Real`] does the same arithmetic in the same order on both
//! paths, and its results are the same bits.
//!
//! Writing a kernel over [`Real`]: a constant factor goes on the right (`x * 2.0`, which is
//! `2.0 * x` bit for bit: IEEE `+` and `*` are commutative), a constant on the left of `-` or
//! `/` is splatted (`R::splat(1.0) - x`), and a product chain keeps its grouping
//! (`1.5 * dk / q` is `(1.5 * dk) / q`, written `dk * 1.5 / q`, never `dk * (1.5 / q)`).
//!
//! Divisions by a constant are written as products with its reciprocal (`x * THIRD`, `x *
//! (1.0 / (6.0 * mu))`), on both paths alike: a vector division costs ~16 cycles of a divider
//! that does one at a time, a product one cycle of two multipliers, and the result differs
//! from the quotient by at most one rounding (relative 1.1e-16). Only `dk * 1.5 / q` (one per
//! yielding point) and the square root remain on the divider.

use std::ops::{Add, AddAssign, Div, Mul, Sub};

use crate::lanes::simd::{each_lane, Lanes, Mask, LANES};

/// 1/3, rounded once: the kernels multiply by it where the formula divides by 3 (see the
/// module documentation).
pub const THIRD: f64 = 1.0 / 3.0;

/// A number of the kernels: one value per lane, [`Real::LANES`] lanes.
pub trait Real:
    Copy
    + Default
    + std::fmt::Debug
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Add<f64, Output = Self>
    + Sub<f64, Output = Self>
    + Mul<f64, Output = Self>
    + Div<f64, Output = Self>
    + AddAssign
{
    /// One `bool` per lane.
    type Mask: Copy;
    /// Elements a value holds: 1 for `f64`, [`LANES`] for [`Lanes`].
    const LANES: usize;
    /// `x` in every lane.
    fn splat(x: f64) -> Self;
    fn sqrt(self) -> Self;
    /// `f64::max` with `x` per lane.
    fn max(self, x: f64) -> Self;
    /// `self > other` per lane.
    fn gt(self, other: Self) -> Self::Mask;
    /// Per lane: `a` where `mask`, else `b`.
    fn select(mask: Self::Mask, a: Self, b: Self) -> Self;
    /// Whether any lane of `mask` is set.
    fn any(mask: Self::Mask) -> bool;
    /// Per lane: `a and b`.
    fn and(a: Self::Mask, b: Self::Mask) -> Self::Mask;
    /// Per lane: `not m`.
    fn not(m: Self::Mask) -> Self::Mask;
    /// Writes `value` at `at` (see [`Real::of_batch`]) into `stored` where `mask` is set.
    fn store(stored: &mut Lanes, at: usize, value: Self, mask: Self::Mask);
    /// Lane `l` of `mask`.
    fn on(mask: Self::Mask, l: usize) -> bool;
    /// Lane `l`'s value.
    fn lane(self, l: usize) -> f64;
    /// Sets lane `l` to `x`.
    fn set_lane(&mut self, l: usize, x: f64);
    /// The value at `at` of a quantity stored per batch of [`LANES`] elements: `at` is an
    /// element for `f64` (its lane of its batch), a batch for [`Lanes`] (the whole batch).
    fn of_batch(stored: &Lanes, at: usize) -> Self;
    /// The batch that holds `at` (an element for `f64`, a batch for [`Lanes`]).
    fn batch_of(at: usize) -> usize;
    /// `f` of each lane: a scalar function (`f64::ln`, `f64::powf`, a table look-up) applied
    /// lane by lane, so both paths call the same scalar code and get the same bits.
    fn map_lanes(self, f: impl Fn(f64) -> f64) -> Self;
}

impl Real for f64 {
    type Mask = bool;
    const LANES: usize = 1;
    #[inline(always)]
    fn splat(x: f64) -> f64 {
        x
    }
    #[inline(always)]
    fn sqrt(self) -> f64 {
        f64::sqrt(self)
    }
    #[inline(always)]
    fn max(self, x: f64) -> f64 {
        f64::max(self, x)
    }
    #[inline(always)]
    fn gt(self, other: f64) -> bool {
        self > other
    }
    #[inline(always)]
    fn select(mask: bool, a: f64, b: f64) -> f64 {
        if mask {
            a
        } else {
            b
        }
    }
    #[inline(always)]
    fn any(mask: bool) -> bool {
        mask
    }
    #[inline(always)]
    fn and(a: bool, b: bool) -> bool {
        a && b
    }
    #[inline(always)]
    fn not(m: bool) -> bool {
        !m
    }
    #[inline(always)]
    fn store(stored: &mut Lanes, e: usize, value: f64, mask: bool) {
        if mask {
            stored.0[e % LANES] = value;
        }
    }
    #[inline(always)]
    fn on(mask: bool, _: usize) -> bool {
        mask
    }
    #[inline(always)]
    fn lane(self, _: usize) -> f64 {
        self
    }
    #[inline(always)]
    fn set_lane(&mut self, _: usize, x: f64) {
        *self = x;
    }
    #[inline(always)]
    fn of_batch(stored: &Lanes, e: usize) -> f64 {
        stored.0[e % LANES]
    }
    #[inline(always)]
    fn batch_of(e: usize) -> usize {
        e / LANES
    }
    #[inline(always)]
    fn map_lanes(self, f: impl Fn(f64) -> f64) -> f64 {
        f(self)
    }
}

impl Real for Lanes {
    type Mask = Mask;
    const LANES: usize = LANES;
    #[inline(always)]
    fn splat(x: f64) -> Lanes {
        Lanes::splat(x)
    }
    #[inline(always)]
    fn sqrt(self) -> Lanes {
        self.map(f64::sqrt)
    }
    #[inline(always)]
    fn max(self, x: f64) -> Lanes {
        self.map(|v| v.max(x))
    }
    #[inline(always)]
    fn gt(self, other: Lanes) -> Mask {
        Mask(each_lane(|l| if self.0[l] > other.0[l] { !0 } else { 0 }))
    }
    #[inline(always)]
    fn select(mask: Mask, a: Lanes, b: Lanes) -> Lanes {
        // Bitwise, so that it compiles to one blend.
        Lanes(each_lane(|l| {
            let (a, b, m) = (a.0[l].to_bits(), b.0[l].to_bits(), mask.0[l]);
            f64::from_bits((a & m) | (b & !m))
        }))
    }
    #[inline(always)]
    fn any(mask: Mask) -> bool {
        mask.0.iter().fold(0, |x, y| x | y) != 0
    }
    #[inline(always)]
    fn and(a: Mask, b: Mask) -> Mask {
        Mask(each_lane(|l| a.0[l] & b.0[l]))
    }
    #[inline(always)]
    fn not(m: Mask) -> Mask {
        Mask(each_lane(|l| !m.0[l]))
    }
    #[inline(always)]
    fn store(stored: &mut Lanes, _: usize, value: Lanes, mask: Mask) {
        *stored = Lanes::select(mask, value, *stored);
    }
    #[inline(always)]
    fn on(mask: Mask, l: usize) -> bool {
        mask.on(l)
    }
    #[inline(always)]
    fn lane(self, l: usize) -> f64 {
        self.0[l]
    }
    #[inline(always)]
    fn set_lane(&mut self, l: usize, x: f64) {
        self.0[l] = x;
    }
    #[inline(always)]
    fn of_batch(stored: &Lanes, _: usize) -> Lanes {
        *stored
    }
    #[inline(always)]
    fn batch_of(b: usize) -> usize {
        b
    }
    #[inline(always)]
    fn map_lanes(self, f: impl Fn(f64) -> f64) -> Lanes {
        self.map(f)
    }
}
