//! The objective rating of a signal against a reference, ISO/TS 18571:2014 ("Road vehicles:
//! objective rating metric for non-ambiguous signals"): a corridor score, a phase score, a
//! magnitude score and a slope score, combined 0.4 / 0.2 / 0.2 / 0.2 into one rating in [0, 1]
//! with the standard's grades (excellent > 0.94, good > 0.80, fair > 0.58, poor otherwise).
//!
//! The formulas and every constant follow the standard's defaults as the TU Graz reference
//! implementation (the PyPI package `objective_rating_metrics` 1.3, `ISO18571`) computes them,
//! step for step: the same order of the shifts tried, the same dynamic time warping (steps
//! (-1, 0), (0, -1), (-1, -1) of weight 1, a Sakoe-Chiba band of ceil(0.1 n) - 1 samples, the
//! first of equal predecessors taken when tracing back), the same end treatment of the slope's
//! moving average. Tested against the values that implementation gives (the tests below).
//!
//! Both signals are sampled alike (n samples, one step apart); the standard samples at 10 kHz.
//! Every score except the slope's is a function of the sample values and their indices only,
//! and the slope score is a ratio of two derivatives taken with the same step, so the rating
//! depends on the sampling only through the number of samples.

/// Default constants of ISO/TS 18571 (its Table 1).
const CORRIDOR_EXPONENT: i32 = 2; // k_z
const PHASE_EXPONENT: i32 = 1; // k_p
const MAGNITUDE_EXPONENT: i32 = 1; // k_m
const MAGNITUDE_LIMIT: f64 = 0.5; // epsilon_m*
const SLOPE_LIMIT: f64 = 2.0; // epsilon_s*
const MAX_SHIFT_FRACTION: f64 = 0.2; // epsilon_p* = 1 - the initial minimum 0.8
const INNER_CORRIDOR: f64 = 0.05; // a_0, of the reference's largest magnitude
const OUTER_CORRIDOR: f64 = 0.5; // b_0
const DTW_BAND_FRACTION: f64 = 0.1;
const WEIGHTS: [f64; 4] = [0.4, 0.2, 0.2, 0.2]; // corridor, phase, magnitude, slope

/// The fewest samples the slope's nine-point moving average can be taken on.
pub const MIN_SAMPLES: usize = 9;

/// The four scores, the rating that combines them and the shift the phase score found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rating {
    /// Share of samples inside the corridors around the reference, in [0, 1].
    pub corridor: f64,
    /// 1 with no shift, falling linearly to 0 at a shift of 20 % of the samples.
    pub phase: f64,
    /// 1 - (L1 error after dynamic time warping, relative) / 0.5, floored at 0.
    pub magnitude: f64,
    /// 1 - (L1 error of the smoothed derivatives, relative) / 2, floored at 0.
    pub slope: f64,
    /// 0.4 corridor + 0.2 (phase + magnitude + slope).
    pub overall: f64,
    /// The shift (samples) of the comparison that correlates best with the reference:
    /// positive when the comparison lags (its samples were moved left).
    pub shift_samples: i64,
}

/// The standard's grade of an overall rating.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Grade {
    Excellent,
    Good,
    Fair,
    Poor,
}

impl Grade {
    /// ISO/TS 18571's bands: excellent R > 0.94, good 0.80 < R <= 0.94, fair 0.58 < R <= 0.80,
    /// poor R <= 0.58.
    pub fn of(overall: f64) -> Grade {
        if overall > 0.94 {
            Grade::Excellent
        } else if overall > 0.80 {
            Grade::Good
        } else if overall > 0.58 {
            Grade::Fair
        } else {
            Grade::Poor
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Grade::Excellent => "excellent",
            Grade::Good => "good",
            Grade::Fair => "fair",
            Grade::Poor => "poor",
        }
    }
}

/// Why two signals cannot be rated.
#[derive(Debug, Clone, PartialEq)]
pub enum RatingError {
    /// The two signals have different numbers of samples (resample them first).
    Lengths { reference: usize, comparison: usize },
    /// Fewer samples than [`MIN_SAMPLES`].
    TooShort(usize),
    /// A sample is NaN or infinite.
    NotFinite,
    /// The reference is zero everywhere: its corridors have no width.
    ZeroReference,
}

impl std::fmt::Display for RatingError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RatingError::Lengths {
                reference,
                comparison,
            } => write!(
                f,
                "the reference has {reference} samples and the comparison {comparison}: \
                 ISO/TS 18571 rates signals sampled alike"
            ),
            RatingError::TooShort(n) => write!(
                f,
                "{n} samples: ISO/TS 18571's slope score needs at least {MIN_SAMPLES}"
            ),
            RatingError::NotFinite => write!(f, "a sample is NaN or infinite"),
            RatingError::ZeroReference => {
                write!(
                    f,
                    "the reference is zero everywhere: its corridors have no width"
                )
            }
        }
    }
}

impl std::error::Error for RatingError {}

/// Rates `comparison` against `reference`, both sampled `dt` apart (s, or any unit: see the
/// module's notes).
pub fn rate(reference: &[f64], comparison: &[f64], dt: f64) -> Result<Rating, RatingError> {
    let n = reference.len();
    if comparison.len() != n {
        return Err(RatingError::Lengths {
            reference: n,
            comparison: comparison.len(),
        });
    }
    if n < MIN_SAMPLES {
        return Err(RatingError::TooShort(n));
    }
    if reference.iter().chain(comparison).any(|v| !v.is_finite()) {
        return Err(RatingError::NotFinite);
    }
    if reference.iter().all(|v| *v == 0.0) {
        return Err(RatingError::ZeroReference);
    }
    let corridor = corridor_score(reference, comparison);
    let shift = best_shift(reference, comparison);
    let (reference_s, comparison_s) = shifted(reference, comparison, shift);
    let phase = phase_score(n, shift);
    let magnitude = magnitude_score(reference_s, comparison_s);
    let slope = slope_score(reference_s, comparison_s, dt);
    let overall =
        WEIGHTS[0] * corridor + WEIGHTS[1] * phase + WEIGHTS[2] * magnitude + WEIGHTS[3] * slope;
    Ok(Rating {
        corridor,
        phase,
        magnitude,
        slope,
        overall,
        shift_samples: shift,
    })
}

/// The corridor score Z: each sample scores 1 inside the inner corridor (0.05 of the
/// reference's largest magnitude), 0 outside the outer one (0.5), and
/// ((b - d) / (b - a))^k_z between; Z is their mean.
fn corridor_score(reference: &[f64], comparison: &[f64]) -> f64 {
    let norm = reference.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let (inner, outer) = (INNER_CORRIDOR * norm, OUTER_CORRIDOR * norm);
    let sum: f64 = reference
        .iter()
        .zip(comparison)
        .map(|(r, c)| {
            let d = (r - c).abs();
            if d < inner {
                1.0
            } else if d > outer {
                0.0
            } else {
                ((outer - d) / (outer - inner)).powi(CORRIDOR_EXPONENT)
            }
        })
        .sum();
    sum / reference.len() as f64
}

/// The shift of the comparison (samples; positive: moved left) whose overlap with the
/// reference has the largest Pearson correlation, among shifts up to 20 % of the samples,
/// the left shift tried before the right one at each size and only a strictly larger
/// correlation taken (the smallest shift wins a tie).
fn best_shift(reference: &[f64], comparison: &[f64]) -> i64 {
    let n = reference.len();
    let largest = (n as f64 * MAX_SHIFT_FRACTION).floor() as usize;
    let mut best = pearson(reference, comparison);
    let mut shift = 0_i64;
    for k in 1..=largest.min(n - 2) {
        let left = pearson(&reference[..n - k], &comparison[k..]);
        if left > best {
            best = left;
            shift = k as i64;
        }
        let right = pearson(&reference[k..], &comparison[..n - k]);
        if right > best {
            best = right;
            shift = -(k as i64);
        }
    }
    shift
}

/// The overlapping parts of the two signals at a shift found by [`best_shift`].
fn shifted<'a>(reference: &'a [f64], comparison: &'a [f64], shift: i64) -> (&'a [f64], &'a [f64]) {
    let n = reference.len();
    let k = shift.unsigned_abs() as usize;
    if shift >= 0 {
        (&reference[..n - k], &comparison[k..])
    } else {
        (&reference[k..], &comparison[..n - k])
    }
}

/// Pearson's correlation coefficient (NaN for a constant signal, which no shift then beats).
fn pearson(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len() as f64;
    let (ma, mb) = (a.iter().sum::<f64>() / n, b.iter().sum::<f64>() / n);
    let (mut sab, mut saa, mut sbb) = (0.0, 0.0, 0.0);
    for (x, y) in a.iter().zip(b) {
        let (dx, dy) = (x - ma, y - mb);
        sab += dx * dy;
        saa += dx * dx;
        sbb += dy * dy;
    }
    (sab / (saa.sqrt() * sbb.sqrt())).clamp(-1.0, 1.0)
}

/// The phase score E_p: 1 with no shift, ((t - |shift|) / t)^k_p below the largest allowed
/// shift t (20 % of the samples), 0 at or beyond it.
fn phase_score(n: usize, shift: i64) -> f64 {
    let limit = n as f64 * MAX_SHIFT_FRACTION;
    let k = shift.unsigned_abs() as f64;
    if shift == 0 {
        1.0
    } else if k >= limit {
        0.0
    } else {
        ((limit - k) / limit).powi(PHASE_EXPONENT)
    }
}

/// The magnitude score E_M: the L1 distance of the shifted signals along their dynamic
/// time warping path, relative to the reference's L1 norm on that path.
fn magnitude_score(reference: &[f64], comparison: &[f64]) -> f64 {
    let path = warping_path(comparison, reference);
    let (mut err, mut norm) = (0.0, 0.0);
    for &(i, j) in &path {
        err += (comparison[i] - reference[j]).abs();
        norm += reference[j].abs();
    }
    let e = err / norm;
    if e == 0.0 {
        1.0
    } else if e > MAGNITUDE_LIMIT {
        0.0
    } else {
        ((MAGNITUDE_LIMIT - e) / MAGNITUDE_LIMIT).powi(MAGNITUDE_EXPONENT)
    }
}

/// The warping path of x against y (pairs (i, j), from (0, 0) to (n - 1, n - 1)) that
/// minimises the summed squared differences, within a band |i - j| <= ceil(0.1 n) - 1.
fn warping_path(x: &[f64], y: &[f64]) -> Vec<(usize, usize)> {
    let n = x.len();
    let band = ((DTW_BAND_FRACTION * n as f64).ceil() as usize).saturating_sub(1);
    let cost = Band::cumulative(x, y, band);
    let (mut i, mut j) = (n - 1, n - 1);
    let mut path = vec![(i, j)];
    // Each step lowers i + j by at least one, so the loop ends within 2n steps.
    while i > 0 || j > 0 {
        let steps = [(1, 0), (0, 1), (1, 1)];
        let mut best: Option<((usize, usize), f64)> = None;
        for (di, dj) in steps {
            if i < di || j < dj {
                continue;
            }
            let d = cost.at(i - di, j - dj);
            if d.is_finite() && best.is_none_or(|(_, b)| d < b) {
                best = Some(((i - di, j - dj), d));
            }
        }
        let Some(((pi, pj), _)) = best else { break };
        (i, j) = (pi, pj);
        path.push((i, j));
    }
    path.reverse();
    path
}

/// The cumulative cost of dynamic time warping, stored on the band |i - j| <= width.
struct Band {
    n: usize,
    width: usize,
    cells: Vec<f64>,
}

impl Band {
    /// D(i, j) = (x_i - y_j)^2 + min(D(i-1, j), D(i, j-1), D(i-1, j-1)), D(0, 0) = (x_0 - y_0)^2.
    fn cumulative(x: &[f64], y: &[f64], width: usize) -> Band {
        let n = x.len();
        let mut band = Band {
            n,
            width,
            cells: vec![f64::INFINITY; n * (2 * width + 1)],
        };
        for i in 0..n {
            for j in i.saturating_sub(width)..(i + width + 1).min(n) {
                let local = (x[i] - y[j]) * (x[i] - y[j]);
                let before = if i == 0 && j == 0 {
                    0.0
                } else {
                    let up = if i > 0 {
                        band.at(i - 1, j)
                    } else {
                        f64::INFINITY
                    };
                    let left = if j > 0 {
                        band.at(i, j - 1)
                    } else {
                        f64::INFINITY
                    };
                    let diag = if i > 0 && j > 0 {
                        band.at(i - 1, j - 1)
                    } else {
                        f64::INFINITY
                    };
                    up.min(left).min(diag)
                };
                let slot = band.slot(i, j);
                band.cells[slot] = before + local;
            }
        }
        band
    }

    fn slot(&self, i: usize, j: usize) -> usize {
        i * (2 * self.width + 1) + (j + self.width - i)
    }

    /// D(i, j), infinite outside the band.
    fn at(&self, i: usize, j: usize) -> f64 {
        if i >= self.n || j >= self.n || i.abs_diff(j) > self.width {
            f64::INFINITY
        } else {
            self.cells[self.slot(i, j)]
        }
    }
}

/// The slope score E_S: the derivatives (central differences, one-sided at the ends), each
/// smoothed by a nine-point moving average (1, 3, 5, 7 points towards the ends), compared in
/// the L1 norm relative to the reference's.
fn slope_score(reference: &[f64], comparison: &[f64], dt: f64) -> f64 {
    let (r, c) = (
        smoothed_slope(reference, dt),
        smoothed_slope(comparison, dt),
    );
    let err: f64 = r.iter().zip(&c).map(|(a, b)| (b - a).abs()).sum();
    let norm: f64 = r.iter().map(|a| a.abs()).sum();
    // A reference without slope (constant) against a comparison without slope: no error (the
    // reference implementation divides 0 by 0 there and rates NaN); against one with a
    // slope: the largest error.
    let e = match (err, norm) {
        (0.0, _) => 0.0,
        (_, 0.0) => f64::INFINITY,
        _ => err / norm,
    };
    if e <= 0.0 {
        1.0
    } else if e >= SLOPE_LIMIT {
        0.0
    } else {
        (SLOPE_LIMIT - e) / SLOPE_LIMIT
    }
}

fn smoothed_slope(f: &[f64], dt: f64) -> Vec<f64> {
    let n = f.len();
    let mut d = vec![0.0; n];
    d[0] = (f[1] - f[0]) / dt;
    d[n - 1] = (f[n - 1] - f[n - 2]) / dt;
    for i in 1..n - 1 {
        d[i] = (f[i + 1] - f[i - 1]) / (2.0 * dt);
    }
    let mut s = vec![0.0; n];
    for (k, width) in [1_usize, 3, 5, 7].into_iter().enumerate() {
        s[k] = d[..width].iter().sum::<f64>() / width as f64;
        s[n - 1 - k] = d[n - width..].iter().sum::<f64>() / width as f64;
    }
    for i in 4..n - 4 {
        s[i] = d[i - 4..=i + 4].iter().sum::<f64>() / 9.0;
    }
    s
}

#[cfg(test)]
mod tests {
    //! Against the TU Graz reference implementation (`objective_rating_metrics` 1.3,
    //! `ISO18571(...).overall_rating()`, three digits): a sine sin(20 t) on [0, 0.15) s at
    //! 10 kHz against 1.3 times itself rates 0.713 (corridor 0.478, phase 1, magnitude 0.760,
    //! slope 0.850); the sine shifted by 0.02 s against the sine shifted by 0.03 s, on the
    //! 1,400 samples they share, rates 0.815 (corridor 0.716, phase 0.643, magnitude 1,
    //! slope 1). At full precision, on a Gaussian pulse against a later, wider, lower one
    //! (below), the reference implementation's four scores and rating agree with these to
    //! 2e-16 (and so did a damped sine against a noisy, phase-shifted copy, checked once).
    use super::*;

    fn sine(n: usize, delay: f64) -> Vec<f64> {
        (0..n)
            .map(|k| (20.0 * (k as f64 * 1e-4 - delay)).sin())
            .collect()
    }

    fn three(x: f64) -> f64 {
        (x * 1000.0).round() / 1000.0
    }

    #[test]
    fn a_sine_against_one_point_three_times_itself() {
        let r = sine(1500, 0.0);
        let c: Vec<f64> = r.iter().map(|v| 1.3 * v).collect();
        let rating = rate(&r, &c, 1e-4).unwrap();
        assert_eq!(three(rating.corridor), 0.478);
        assert_eq!(rating.phase, 1.0);
        assert_eq!(three(rating.magnitude), 0.760);
        assert_eq!(three(rating.slope), 0.850);
        assert_eq!(three(rating.overall), 0.713);
        assert_eq!(Grade::of(rating.overall), Grade::Fair);
    }

    #[test]
    fn a_sine_against_itself_a_hundredth_of_a_second_later() {
        let all = sine(1500, 0.0);
        let (r, c) = (&all[..1400], &all[100..]);
        let rating = rate(r, c, 1e-4).unwrap();
        assert_eq!(three(rating.corridor), 0.716);
        assert_eq!(three(rating.phase), 0.643);
        assert_eq!(rating.magnitude, 1.0);
        assert_eq!(rating.slope, 1.0);
        assert_eq!(three(rating.overall), 0.815);
        // The comparison leads by 100 samples; with the roles swapped it lags, and rates alike.
        assert_eq!(rating.shift_samples, -100);
        assert_eq!(Grade::of(rating.overall), Grade::Good);
        let swapped = rate(c, r, 1e-4).unwrap();
        assert_eq!(swapped.shift_samples, 100);
        assert_eq!(three(swapped.overall), 0.815);
    }

    #[test]
    fn a_pulse_against_a_later_wider_lower_one_to_round_off() {
        let t = |k: usize| k as f64 * 1e-4;
        let r: Vec<f64> = (0..1500)
            .map(|k| (-((t(k) - 0.05) / 0.01).powi(2)).exp())
            .collect();
        let c: Vec<f64> = (0..1500)
            .map(|k| 0.9 * (-((t(k) - 0.056) / 0.012).powi(2)).exp())
            .collect();
        let rating = rate(&r, &c, 1e-4).unwrap();
        let published = [
            (rating.corridor, 0.8240465006447711),
            (rating.phase, 0.8),
            (rating.magnitude, 0.9604254694796721),
            (rating.slope, 0.8556755897066997),
            (rating.overall, 0.8528388120951829),
        ];
        for (ours, theirs) in published {
            assert!((ours - theirs).abs() <= 1e-14, "{ours} against {theirs}");
        }
    }

    #[test]
    fn a_signal_against_itself_is_excellent() {
        let r = sine(200, 0.003);
        let rating = rate(&r, &r, 1e-4).unwrap();
        assert_eq!(rating.overall, 1.0);
        assert_eq!(Grade::of(rating.overall), Grade::Excellent);
    }

    #[test]
    fn a_constant_signal_has_a_slope_score() {
        let flat = [2.0; 12];
        assert_eq!(rate(&flat, &flat, 1e-4).unwrap().overall, 1.0);
        let rising: Vec<f64> = (0..12).map(|k| 2.0 + 1e-3 * k as f64).collect();
        assert_eq!(rate(&flat, &rising, 1e-4).unwrap().slope, 0.0);
    }

    #[test]
    fn signals_that_cannot_be_rated_are_refused() {
        let r = sine(20, 0.0);
        assert_eq!(
            rate(&r, &r[..19], 1e-4),
            Err(RatingError::Lengths {
                reference: 20,
                comparison: 19
            })
        );
        assert_eq!(rate(&r[..8], &r[..8], 1e-4), Err(RatingError::TooShort(8)));
        assert_eq!(
            rate(&[0.0; 10], &r[..10], 1e-4),
            Err(RatingError::ZeroReference)
        );
        let mut bad = r.clone();
        bad[3] = f64::NAN;
        assert_eq!(rate(&r, &bad, 1e-4), Err(RatingError::NotFinite));
    }
}
