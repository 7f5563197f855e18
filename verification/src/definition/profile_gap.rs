//! The measure `profile_gap: {file}`: how far a Taylor bar's final outline lies from a
//! digitised profile of the recovered specimen (`reference-data/experiments/taylor/profiles/`,
//! columns `z_m`, the height above the impact face, and `radius_m`).
//!
//! The run's outline is the summary's `wall.final_outline` (the side's nodes at the end,
//! bottom to top: height above the impact face's centre and distance from the axis,
//! `solver/ALGORITHM.md` section 5c). At each digitised point `(z_i, r_i)` whose height the
//! bar reaches, the model's radius `r(z_i)` is read on the outline by linear interpolation
//! between the two side nodes whose heights bracket `z_i`, the highest such pair (near the
//! foot the side folds onto the anvil, and a height can be met twice; the digitised outline
//! is the silhouette, the outer of the two); the gap is `|r(z_i) - r_i|`. The measure is the
//! largest gap, m. Points above the bar's top are left out (the final length has its own
//! check), and so are points below the side's lowest node (the foot's rim lifted off the
//! anvil as the bar rebounds: the outline does not reach the face there); a profile with no
//! point the outline reaches is an error. Unsigned: a signed "largest in size" flips sign when
//! an input moves the worst point from a bulge to a waist, and the budget's sensitivity
//! `S_i - S` then measures the flip (2x the gap), not the input.

use serde::Deserialize;
use serde_json::Value;
use std::path::Path;

use crate::definition::measure_error::MeasureError;

/// `profile_gap: {file}` of a measure.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProfileGapFile {
    /// The digitised profile (CSV with `z_m` and `radius_m`), from the repository's root.
    pub file: String,
}

/// The largest gap (m) between the outline of `summary` and the profile in `path`.
pub fn profile_gap(summary: &Value, path: &Path) -> Result<f64, MeasureError> {
    let (heights, radii) = final_outline(summary)?;
    let (z, r) = crate::definition::csv_columns::read_csv_pair(path, "z_m", "radius_m")?;
    let points: Vec<(f64, f64)> = z.into_iter().zip(r).collect();
    let top = heights.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let gaps: Vec<f64> = points
        .iter()
        .filter(|(z, _)| *z <= top)
        .filter_map(|&(z, r)| radius_at(&heights, &radii, z).map(|m| (m - r).abs()))
        .collect();
    if gaps.is_empty() {
        return Err(MeasureError::Invalid(format!(
            "{}: no digitised point within the outline's heights (top {top:e} m)",
            path.display()
        )));
    }
    Ok(gaps.into_iter().fold(0.0, f64::max))
}

/// The summary's `wall.final_outline`: heights and radii, m.
fn final_outline(summary: &Value) -> Result<(Vec<f64>, Vec<f64>), MeasureError> {
    let outline = summary
        .get("wall")
        .and_then(|w| w.get("final_outline"))
        .ok_or_else(|| {
            MeasureError::NotProduced(
                "no metric \"wall.final_outline\" (the summary has no final outline)".into(),
            )
        })?;
    let numbers = |key: &str| -> Result<Vec<f64>, String> {
        outline
            .get(key)
            .and_then(Value::as_array)
            .and_then(|a| a.iter().map(Value::as_f64).collect::<Option<Vec<f64>>>())
            .ok_or_else(|| format!("wall.final_outline.{key}: not an array of numbers"))
    };
    let (h, r) = (numbers("height_m")?, numbers("radius_m")?);
    if h.len() != r.len() || h.len() < 2 {
        return Err(MeasureError::Invalid(format!(
            "wall.final_outline: {} heights and {} radii (at least 2 of each, as many)",
            h.len(),
            r.len()
        )));
    }
    Ok((h, r))
}

/// The model's radius at height `z` (m): on the highest segment of the outline whose ends
/// bracket `z`, linearly; `None` when no segment does.
fn radius_at(heights: &[f64], radii: &[f64], z: f64) -> Option<f64> {
    (0..heights.len() - 1).rev().find_map(|k| {
        let (h0, h1) = (heights[k], heights[k + 1]);
        let (lo, hi) = (h0.min(h1), h0.max(h1));
        if !(lo <= z && z <= hi) {
            return None;
        }
        if hi == lo {
            return Some(radii[k].max(radii[k + 1]));
        }
        Some(radii[k] + (radii[k + 1] - radii[k]) * (z - h0) / (h1 - h0))
    })
}

#[cfg(test)]
mod tests {
    //! A made-up outline (a foot folded under at the bottom, a straight taper above) against
    //! made-up profiles; the wrong readings the measure must not make: the fold's inner radius
    //! taken at the foot, the points above the bar counted.
    use super::*;

    /// Side nodes: the bottom one rolled under (height 0.5 mm, radius 5 mm), the next at the
    /// face's edge (height 0, radius 6 mm), then a taper to 4 mm at 10 mm and a straight rear
    /// to 20 mm.
    fn summary() -> Value {
        serde_json::json!({"wall": {"final_outline": {
            "height_m": [0.5e-3, 0.0, 10.0e-3, 20.0e-3],
            "radius_m": [5.0e-3, 6.0e-3, 4.0e-3, 4.0e-3],
        }}})
    }

    /// The profile written to a file of its own under the system's temporary folder.
    fn profile(points: &[(f64, f64)]) -> std::path::PathBuf {
        static COUNT: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
        let k = COUNT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let mut text = String::from("z_m,radius_m,printed_z_mm,printed_radius_mm\n");
        for (z, r) in points {
            text += &format!("{z},{r},{},{}\n", z * 1e3, r * 1e3);
        }
        let path = std::env::temp_dir().join(format!("profile-gap-{}-{k}.csv", std::process::id()));
        std::fs::write(&path, text).unwrap();
        path
    }

    /// Bound of the gaps' checks, m: the gaps are differences of millimetre radii (one ulp
    /// about 1e-18 m) through one interpolation, a few ulp; the wrong readings they must tell
    /// apart miss by 1e-4 m and more (the fold's 5.5 mm against the silhouette's 5.95 mm).
    const ROUND_OFF: f64 = 1e-15;

    #[test]
    fn the_gap_is_read_on_the_silhouette() {
        // At 0.25 mm the fold meets the height twice: the silhouette is the taper (5.95 mm), not
        // the folded node's segment (5.5 mm). A profile 0.1 mm inside the taper everywhere:
        // the model is 0.1 mm wider.
        let inside = profile(&[(0.25e-3, 5.85e-3), (5.0e-3, 4.9e-3), (15.0e-3, 3.9e-3)]);
        let gap = profile_gap(&summary(), &inside).unwrap();
        assert!((gap - 1.0e-4).abs() < ROUND_OFF, "{gap}");
        // One point 0.3 mm outside, one 0.2 mm inside, the rest on the outline: 0.3 mm.
        let outside = profile(&[(0.25e-3, 5.95e-3), (5.0e-3, 5.3e-3), (15.0e-3, 3.8e-3)]);
        let gap = profile_gap(&summary(), &outside).unwrap();
        assert!((gap - 3.0e-4).abs() < ROUND_OFF, "{gap}");
    }

    #[test]
    fn points_above_the_bar_are_left_out_and_none_is_an_error() {
        let longer = profile(&[(5.0e-3, 5.0e-3), (25.0e-3, 3.0e-3)]);
        assert!((profile_gap(&summary(), &longer).unwrap() - 0.0).abs() < ROUND_OFF);
        let above = profile(&[(25.0e-3, 3.0e-3)]);
        let e = profile_gap(&summary(), &above).unwrap_err();
        assert!(
            !e.is_not_produced() && e.to_string().contains("no digitised point"),
            "{e}"
        );
        // Below the outline's lowest node (a rim lifted to 0.5 mm while the face's centre
        // sits at 0): left out, not read off the fold.
        let mut lifted = summary();
        lifted["wall"]["final_outline"]["height_m"] =
            serde_json::json!([0.6e-3, 0.5e-3, 10.0e-3, 20.0e-3]);
        let face = profile(&[(0.1e-3, 9.0e-3), (15.0e-3, 4.1e-3)]);
        assert!((profile_gap(&lifted, &face).unwrap() - 1.0e-4).abs() < ROUND_OFF);
        let e = profile_gap(&serde_json::json!({"wall": {}}), &longer).unwrap_err();
        // Another code's summary without the outline: not produced (N/E on its row), not FAIL.
        assert!(
            e.is_not_produced() && e.to_string().starts_with("no metric"),
            "{e}"
        );
    }
}
