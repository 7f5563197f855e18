//! The number type the element and material kernels are written in, once: `f64` on the
//! scalar reference path (one element at a time), [`Lanes`] on the batched path ([`LANES`]
//! elements at a time, [`crate::batch`]). Every operation is one IEEE operation per lane, so
//! a kernel written once over [`Real`] does the same arithmetic in the same order on both
//! paths, and its results are the same bits.
//!
//! Writing a kernel over [`Real`]: a constant factor goes on the right (`x * 2.0`, which is
//! `2.0 * x` bit for bit: IEEE `+` and `*` are commutative), a constant on the left of `-` or
//! `/` is splatted (`R::splat(1.0) - x`), and a product chain keeps its grouping
//! (`1.5 * dk / q` is `(1.5 * dk) / q`, written `dk * 1.5 / q`, never `dk * (1.5 / q)`).

use std::ops::{Add, AddAssign, Div, Mul, Sub};

use crate::simd::{Lanes, Mask, LANES};

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
        std::array::from_fn(|l| self.0[l] > other.0[l])
    }
    #[inline(always)]
    fn select(mask: Mask, a: Lanes, b: Lanes) -> Lanes {
        let mut out = b;
        for ((o, &m), &x) in out.0.iter_mut().zip(&mask).zip(&a.0) {
            if m {
                *o = x;
            }
        }
        out
    }
    #[inline(always)]
    fn any(mask: Mask) -> bool {
        mask.iter().any(|&m| m)
    }
    #[inline(always)]
    fn on(mask: Mask, l: usize) -> bool {
        mask[l]
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
}
