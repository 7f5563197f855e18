//! The plots of one case in the report: the histories its `plots:` ask for (references
//! overlaid, axes named for the quantity with engineering units, curves that sit on zero on
//! their own scale), then one convergence plot per series metric its checks use (axes named
//! for the refined quantity, element size or time step; no observed order for changes at
//! round-off level).

use std::path::Path;

use impact_plots::line_plot::{
    column_axis, quantity_of, svg_panels, svg_plot, svg_plot_framed, Axis, Frame, Series,
};

/// A change smaller than this fraction of the values is round-off (about 1e4 machine
/// epsilons): no order can be read from it.
const ROUND_OFF: f64 = 1e-12;

/// The y axis of a round-off plot, log10 of the relative change: from below machine epsilon
/// (2.2e-16, log10 -15.7; an exact zero change is drawn there) to four decades above the
/// round-off level, so that round-off sits in its band at the bottom and does not fill the axis.
const ROUND_OFF_AXIS: (f64, f64) = (-17.0, -8.0);

/// The two finest triplets' observed orders agree when they differ by at most this fraction
/// of the finest one: then the series shows an order (coarser triplets may still be
/// pre-asymptotic, as the rigid target's 2.39, 1.93, 1.94). Looser than the GCI's 10 % band
/// around a formal order (crate::definition::gci), since here no formal order is known; the series the
/// report showed "p = 0.68 (triplets 0.08, 0.68)" for differ by 88 %.
pub const ORDER_AGREEMENT: f64 = 0.2;

/// (title, svg) of each plot of the case `c` (a case of results.json), its histories read
/// from `runs/<suite>/<case>/`, references from the repository `root`.
pub fn case_plots(c: &serde_json::Value, runs: &Path, root: &Path) -> Vec<(String, String)> {
    let suite = c["suite"].as_str().unwrap_or("");
    let case = c["case"].as_str().unwrap_or("");
    let dir = runs.join(suite).join(case);
    let mut out = Vec::new();
    for p in c["plots"].as_array().into_iter().flatten() {
        if p["series"].as_array().is_some_and(|s| !s.is_empty()) {
            out.extend(series_values_plot(p, &c["series"]));
        } else {
            out.extend(history_plots(p, &dir, root));
        }
    }
    for (name, sd) in c["series"].as_object().into_iter().flatten() {
        out.extend(convergence_plots(name, sd));
    }
    out
}

/// The ISO/TS 18571 rating of each history a case's `plots:` draw against each reference
/// file drawn with it (the independent Python FE's, another code's published curve): one
/// line each, "scene column against reference: 0.998 (excellent; corridor, phase,
/// magnitude, slope)", the reference as the standard's reference curve.
pub fn reference_ratings(c: &serde_json::Value, runs: &Path, root: &Path) -> Vec<String> {
    let dir = runs
        .join(c["suite"].as_str().unwrap_or(""))
        .join(c["case"].as_str().unwrap_or(""));
    let mut out = Vec::new();
    for p in c["plots"].as_array().into_iter().flatten() {
        let Some(col) = p["column"].as_str() else {
            continue;
        };
        for r in strings(&p["references"]) {
            let path = match r.strip_prefix("reference-data/") {
                Some(_) => root.join(r),
                None => dir.join(r).join("history.csv"),
            };
            let Ok((ta, va)) = crate::definition::csv_columns::read_csv_columns(&path, col) else {
                continue;
            };
            for s in strings(&p["scenes"]) {
                let run = dir.join(s).join("history.csv");
                let Ok((tb, vb)) = crate::definition::csv_columns::read_csv_columns(&run, col)
                else {
                    continue;
                };
                let rated = crate::review::diff::rating_in_common_window(&ta, &va, &tb, &vb)
                    .map_or_else(
                        || "not rated (too few common samples, or a flat curve)".to_string(),
                        |x| {
                            format!(
                            "{:.3} ({}; corridor {:.3}, phase {:.3}, magnitude {:.3}, slope {:.3})",
                            x.overall,
                            crate::review::iso18571::Grade::of(x.overall).name(),
                            x.corridor,
                            x.phase,
                            x.magnitude,
                            x.slope
                        )
                        },
                    );
                out.push(format!("{s} {col} against {r}: ISO/TS 18571 {rated}"));
            }
        }
    }
    out
}

fn strings(v: &serde_json::Value) -> Vec<&str> {
    v.as_array()
        .into_iter()
        .flatten()
        .filter_map(|s| s.as_str())
        .collect()
}

/// The y axis of a plot of `columns`: their common unit suffix (`_N`, `_J`, ... : SI values,
/// engineering ticks), else the plot's own `unit` and `scale` (dimensionless ticks, the unit
/// in the axis name). (name, unit, scale).
fn y_axis(columns: &[&str], p: &serde_json::Value) -> (String, &'static str, f64) {
    let units: Vec<&'static str> = columns.iter().map(|c| column_axis(c).1).collect();
    let unit = units[0];
    let name = if columns.len() == 1 {
        column_axis(columns[0]).0
    } else {
        quantity_of(unit).to_string()
    };
    if !unit.is_empty() && units.iter().all(|u| *u == unit) {
        return (name, unit, 1.0);
    }
    let scale = p["scale"].as_f64().unwrap_or(1.0);
    match p["unit"].as_str() {
        Some(u) if !u.is_empty() && u != "-" => (format!("{name} ({u})"), "", scale),
        _ => (name, "", scale),
    }
}

/// The plot(s) of one `plots:` entry: one `column` of several scenes (and references), or
/// several `columns` of each scene.
fn history_plots(p: &serde_json::Value, dir: &Path, root: &Path) -> Vec<(String, String)> {
    let title = p["title"].as_str().unwrap_or("");
    let scenes = strings(&p["scenes"]);
    let x = match p["x_label"].as_str() {
        Some(l) => Axis::new(l, ""),
        None => Axis::new("time", "s"),
    };
    let load = |path: &Path, col: &str, scale: f64| {
        crate::definition::csv_columns::read_csv_columns(path, col)
            .map(|(t, v)| t.iter().zip(&v).map(|(t, v)| (*t, v * scale)).collect())
    };
    if let Some(col) = p["column"].as_str() {
        let (name, unit, scale) = y_axis(&[col], p);
        let mut series: Vec<Series> = Vec::new();
        for s in &scenes {
            if let Ok(d) = load(&dir.join(s).join("history.csv"), col, scale) {
                series.push((s.to_string(), d, false));
            }
        }
        for r in strings(&p["references"]) {
            let (path, label) = match r.strip_prefix("reference-data/") {
                Some(rest) => (root.join(r), rest.trim_end_matches("/history.csv")),
                None => (dir.join(r).join("history.csv"), r),
            };
            if let Ok(d) = load(&path, col, scale) {
                series.push((format!("ref: {label}"), d, true));
            }
        }
        return svg_panels(title, x, Axis::new(&name, unit), &series);
    }
    let columns = strings(&p["columns"]);
    if columns.is_empty() {
        return Vec::new();
    }
    let (name, unit, scale) = y_axis(&columns, p);
    let mut out = Vec::new();
    for s in &scenes {
        let series: Vec<Series> = columns
            .iter()
            .filter_map(|col| {
                let d = load(&dir.join(s).join("history.csv"), col, scale).ok()?;
                Some((column_axis(col).0, d, false))
            })
            .collect();
        for (t, svg) in svg_panels(title, x, Axis::new(&name, unit), &series) {
            out.push((format!("{t} ({s})"), svg));
        }
    }
    out
}

/// A `plots:` entry with `series` and `metric`: that metric of each mesh series against
/// log10 of the element size over the coarsest one (0 at the coarsest level, negative finer),
/// the series side by side.
fn series_values_plot(p: &serde_json::Value, all: &serde_json::Value) -> Option<(String, String)> {
    let title = p["title"].as_str().unwrap_or("");
    let metric = p["metric"].as_str()?;
    let (label, unit) = column_axis(metric);
    let mut series: Vec<Series> = Vec::new();
    for name in strings(&p["series"]) {
        let sd = &all[name];
        let levels: Vec<f64> = sd["levels"]
            .as_array()?
            .iter()
            .filter_map(|x| x.as_f64())
            .collect();
        let values = sd["metrics"][metric].as_array()?;
        let pts = log_relative_sizes(&levels)
            .into_iter()
            .zip(values)
            .filter_map(|(x, v)| Some((x, v.as_f64()?)))
            .collect();
        series.push((name.to_string(), pts, false));
    }
    let x = Axis::new("log10 (element size / coarsest element size)", "");
    Some((
        title.to_string(),
        svg_plot(title, x, Axis::new(&label, unit), &series),
    ))
}

/// log10 of each level's element size (or step) over the coarsest level's: 0 at the coarsest,
/// negative finer. The levels are refinement factors of the scene's mesh (1 = the scene's
/// own), which need not be the coarsest.
fn log_relative_sizes(levels: &[f64]) -> Vec<f64> {
    let coarsest = levels.iter().copied().fold(f64::INFINITY, f64::min);
    levels.iter().map(|l| (coarsest / l).log10()).collect()
}

/// The x axis of a convergence plot: log10 of the refined size over the coarsest one.
fn refinement_axis(refine: &str) -> &'static str {
    if refine == "dt" {
        "log10 (time step / coarsest time step)"
    } else {
        "log10 (element size / coarsest element size)"
    }
}

/// The largest change between consecutive levels as a fraction of the largest value, when it
/// is at round-off level (else None).
pub fn round_off_change(f: &[f64]) -> Option<f64> {
    let size = f.iter().map(|v| v.abs()).fold(0.0, f64::max);
    let change = f
        .windows(2)
        .map(|w| (w[1] - w[0]).abs())
        .fold(0.0, f64::max);
    let rel = if size > 0.0 { change / size } else { 0.0 };
    (rel <= ROUND_OFF).then_some(rel)
}

/// The observed order a series shows, from its triplets' orders (coarse to fine; the series
/// monotone, as crate::definition::gci::assess demands): the finest triplet's, when there are at least
/// two triplets and the two finest agree within [`ORDER_AGREEMENT`] (a single triplet fits
/// any three values exactly, so it shows nothing). Else why not, in words for the title.
pub fn shown_order(orders: &[f64]) -> Result<f64, String> {
    let listed: Vec<String> = orders.iter().map(|p| format!("{p:.2}")).collect();
    let listed = listed.join(", ");
    let Some(&finest) = orders.last() else {
        return Err("no observed order: no triplet".into());
    };
    if orders.len() < 2 {
        return Err(format!(
            "no observed order: one triplet only ({listed}), two that agree are needed"
        ));
    }
    let off = (orders[orders.len() - 2] - finest).abs();
    if !(finest > 0.0 && off <= ORDER_AGREEMENT * finest) {
        return Err(format!(
            "no observed order: triplets {listed}, the two finest differ by more than {:.0} %",
            100.0 * ORDER_AGREEMENT
        ));
    }
    Ok(finest)
}

/// The plot of a series whose changes are at round-off level: log10 of each level's change
/// against the finest level, relative to the finest value, on a fixed axis with the
/// round-off band shaded (an exact zero drawn at machine epsilon).
fn round_off_plot(title: String, x: Axis, log_h: &[f64], f: &[f64]) -> (String, String) {
    let finest = f[f.len() - 1];
    let pts: Vec<(f64, f64)> = log_h
        .iter()
        .zip(f)
        .take(f.len() - 1)
        .map(|(h, v)| {
            let rel = ((v - finest) / finest).abs().max(f64::EPSILON);
            (*h, rel.log10())
        })
        .collect();
    let frame = Frame {
        y_range: Some(ROUND_OFF_AXIS),
        band: Some((
            ROUND_OFF_AXIS.0,
            ROUND_OFF.log10(),
            format!("round-off (change below {ROUND_OFF:.0e} of the value)"),
        )),
    };
    let y = Axis::new("log10 |f / f_finest - 1|", "");
    let svg = svg_plot_framed(&title, x, y, &[("runs".into(), pts, false)], &frame);
    (title, svg)
}

/// One plot per metric of the series `name`: log10 |f - f_extrapolated| against log10 of the
/// refined size with the observed order's slope; the values themselves when the order cannot
/// be read (not asymptotic, or changes at round-off level).
fn convergence_plots(name: &str, sd: &serde_json::Value) -> Vec<(String, String)> {
    let floats = |v: &serde_json::Value| -> Vec<f64> {
        v.as_array()
            .into_iter()
            .flatten()
            .filter_map(|x| x.as_f64())
            .collect()
    };
    let levels = floats(&sd["levels"]);
    let x_name = refinement_axis(sd["refine"].as_str().unwrap_or("mesh"));
    let mut out = Vec::new();
    for (metric, vals) in sd["metrics"].as_object().into_iter().flatten() {
        let f = floats(vals);
        let n = f.len();
        if n < 3 || levels.len() != n {
            continue;
        }
        let (label, unit) = column_axis(metric);
        let log_h = log_relative_sizes(&levels);
        let x = Axis::new(x_name, "");
        // The values themselves, when no order can be read from them.
        let values_plot = |title: String| {
            let pts: Vec<(f64, f64)> = log_h.iter().copied().zip(f.iter().copied()).collect();
            let svg = svg_plot(
                &title,
                x,
                Axis::new(&label, unit),
                &[("runs".into(), pts, false)],
            );
            (title, svg)
        };
        if let Some(rel) = round_off_change(&f) {
            let title = format!("{name}: {label} changes only at round-off level (largest change {rel:.1e} of the value): no order");
            out.push(round_off_plot(title, x, &log_h, &f));
            continue;
        }
        let r = levels[n - 1] / levels[n - 2];
        let Ok(assessed) = crate::definition::gci::assess(&f, r, None) else {
            out.push(values_plot(format!(
                "{name}: {label}, not in the asymptotic range (no order)"
            )));
            continue;
        };
        let p = match shown_order(&assessed.orders) {
            Ok(p) => p,
            Err(why) => {
                out.push(values_plot(format!("{name}: {label}, {why}")));
                continue;
            }
        };
        let all: Vec<String> = assessed.orders.iter().map(|p| format!("{p:.2}")).collect();
        let title = format!(
            "{name}: {label}, observed order p = {p:.2} (triplets coarse to fine: {}; the two finest within {:.0} %)",
            all.join(", "),
            100.0 * ORDER_AGREEMENT
        );
        let f_ext = f[n - 1] + (f[n - 1] - f[n - 2]) / (r.powf(p) - 1.0);
        let pts: Vec<(f64, f64)> = log_h
            .iter()
            .zip(&f)
            .map(|(h, v)| (*h, (v - f_ext).abs().log10()))
            .filter(|q| q.1.is_finite())
            .collect();
        let Some(&(hx, hy)) = pts.last() else {
            continue;
        };
        let fit: Vec<(f64, f64)> = pts.iter().map(|q| (q.0, hy + p * (q.0 - hx))).collect();
        let y = Axis::new("log10 |f - f_extrapolated|", "");
        let series = [
            ("runs".into(), pts, false),
            (format!("slope p = {p:.2}"), fit, true),
        ];
        out.push((title.clone(), svg_plot(&title, x, y, &series)));
    }
    out
}

#[cfg(test)]
mod tests {
    //! Convergence plots: no observed order for changes at round-off level (the old titles
    //! printed p = -3.72 for them; now drawn on a fixed axis with the round-off band), none
    //! from triplets that disagree (the old titles printed the finest triplet's), and dt
    //! studies are named for the time step.
    use super::*;

    #[test]
    fn round_off_changes_get_no_order() {
        let flat = [1.0, 1.0 + 2e-16, 1.0 - 1e-16, 1.0 + 3e-16];
        assert!(round_off_change(&flat).is_some());
        assert!(round_off_change(&[1.0, 1.1, 1.12]).is_none());
        let sd = serde_json::json!({"refine": "dt", "levels": [1.0, 2.0, 4.0, 8.0],
            "metrics": {"impulse_Ns": flat}});
        let plots = convergence_plots("dt-elastic", &sd);
        assert_eq!(plots.len(), 1);
        assert!(
            plots[0].0.contains("changes only at round-off level"),
            "{}",
            plots[0].0
        );
        assert!(!plots[0].0.contains("order p ="), "{}", plots[0].0);
        // Drawn on the fixed round-off axis with its band, not zoomed into the noise.
        assert!(plots[0]
            .1
            .contains("round-off (change below 1e-12 of the value)"));
        assert!(plots[0].1.contains("log10 |f / f_finest - 1|"));
        assert!(plots[0]
            .1
            .contains("log10 (time step / coarsest time step)"));
        assert!(!plots[0].1.contains("h_base"));
    }

    #[test]
    fn an_order_is_printed_only_when_the_triplets_agree() {
        // The report printed "p = 0.68 (triplets 0.08, 0.68)": the finest triplet alone.
        let e = shown_order(&[0.08, 0.68]).unwrap_err();
        assert_eq!(
            e,
            "no observed order: triplets 0.08, 0.68, the two finest differ by more than 20 %"
        );
        assert!(shown_order(&[1.28])
            .unwrap_err()
            .contains("one triplet only (1.28)"));
        assert_eq!(shown_order(&[1.97, 1.97, 1.98]), Ok(1.98));
        // A pre-asymptotic coarsest triplet (the rigid target's): the two finest agree.
        assert_eq!(shown_order(&[2.39, 1.93, 1.94]), Ok(1.94));
        assert!(shown_order(&[1.94, 0.9, 1.94]).is_err());
        // 2.39 against 1.94: 23 % off, no order; 2.2 against 1.94: 13 %, the order.
        assert!(shown_order(&[2.39, 1.94]).is_err());
        assert_eq!(shown_order(&[2.2, 1.94]), Ok(1.94));
        // A series with the triplets 0.08 and 0.68 gets the values plot and no order.
        let r: f64 = 2.0;
        let (p1, p2) = (0.08, 0.68);
        let d1 = 1.0;
        let d2 = d1 / r.powf(p1);
        let d3 = d2 / r.powf(p2);
        let f = [0.0, d1, d1 + d2, d1 + d2 + d3];
        let sd = serde_json::json!({"refine": "mesh", "levels": [1.0, 2.0, 4.0, 8.0],
            "metrics": {"impulse_Ns": f}});
        let plots = convergence_plots("mesh", &sd);
        assert!(
            plots[0]
                .0
                .contains("no observed order: triplets 0.08, 0.68"),
            "{}",
            plots[0].0
        );
    }

    #[test]
    fn sizes_are_relative_to_the_coarsest_level_not_the_scene_mesh() {
        let x = log_relative_sizes(&[0.5, 1.0, 2.0, 4.0]);
        assert_eq!(x[0], 0.0);
        assert!(x.iter().all(|&v| v <= 0.0), "{x:?}");
        assert!((x[3] + 8f64.log10()).abs() < 1e-15, "{x:?}");
    }

    #[test]
    fn a_converging_series_shows_its_order_against_element_size() {
        // f = 1 + h^2: order 2.
        let f: Vec<f64> = [1.0, 2.0, 4.0, 8.0]
            .iter()
            .map(|l: &f64| 1.0 + 0.1 / (l * l))
            .collect();
        let sd = serde_json::json!({"refine": "mesh", "levels": [1.0, 2.0, 4.0, 8.0],
            "metrics": {"max_plate_displacement_m": f}});
        let plots = convergence_plots("mesh", &sd);
        assert!(
            plots[0]
                .0
                .contains("max plate displacement, observed order p = 2.00 (triplets coarse to fine: 2.00, 2.00; the two finest within 20 %)"),
            "{}",
            plots[0].0
        );
        assert!(plots[0]
            .1
            .contains("log10 (element size / coarsest element size)"));
    }
}
