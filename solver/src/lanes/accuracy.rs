//! What the lanes' functions are tested with ([`super::transcendental`], [`super::cube_root`]):
//! the distance in ulp from the platform's libm, point by point within a bound, the batched
//! lanes checked bit for bit against the scalar path on the way.

use crate::lanes::simd::{Lanes, LANES};

/// The distance in units in the last place between two finite numbers of one sign.
pub(crate) fn ulps(a: f64, b: f64) -> u64 {
    (a.to_bits() as i64 - b.to_bits() as i64).unsigned_abs()
}

/// `n` numbers spread over `[lo, hi]` in the logarithm (both > 0), with their neighbours.
pub(crate) fn log_spread(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    let (a, b) = (lo.ln(), hi.ln());
    (0..=n)
        .map(|i| (a + (b - a) * i as f64 / n as f64).exp())
        .flat_map(|x| {
            [
                x,
                f64::from_bits(x.to_bits() + 1),
                f64::from_bits(x.to_bits() - 1),
            ]
        })
        .filter(|x| *x >= lo && *x <= hi)
        .collect()
}

/// Largest ulp distance of `ours` from `theirs` over `xs`, each point within `bound(x)`
/// ulp, and the batched lanes checked bit for bit against the scalar path on the way.
pub(crate) fn worst(
    xs: &[f64],
    ours: impl Fn(Lanes) -> Lanes,
    scalar: impl Fn(f64) -> f64,
    theirs: impl Fn(f64) -> f64,
    bound: impl Fn(f64) -> f64,
) -> u64 {
    let mut worst = 0;
    for chunk in xs.chunks(LANES) {
        let mut lanes = Lanes::splat(1.0);
        lanes.0[..chunk.len()].copy_from_slice(chunk);
        let batched = ours(lanes);
        for (l, &x) in chunk.iter().enumerate() {
            let one = scalar(x);
            assert_eq!(batched.0[l].to_bits(), one.to_bits(), "lane {l} at {x:e}");
            let off = ulps(one, theirs(x));
            assert!(off as f64 <= bound(x), "{off} ulp at {x:e}");
            worst = worst.max(off);
        }
    }
    worst
}
