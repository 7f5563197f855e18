//! Snapshot text of a case: its checks' statuses and computed values, the summaries of the
//! scenes named in its `snapshot:` block and their histories at fixed times. Numbers carry a
//! fixed number of significant digits (never decimal places: values span 1e-9 m to 1e9 Pa),
//! and values at round-off level print as zero, so that harmless round-off cannot flicker.
//! Wall-clock times are never included.

use std::collections::BTreeMap;
use std::fmt::Write;

use crate::definition::check::interpolate;
use crate::definition::run_data::JobResult;
use crate::run::matrix::CaseResult;

/// Below this magnitude a metric is round-off (relative errors and residuals of exact
/// properties, code-to-code differences ~1e-11): printed as 0. No physical metric of these
/// cases is that small (the smallest are indentations ~1e-6 m and time steps ~1e-8 s).
pub const METRIC_FLOOR: f64 = 1e-9;
/// History values below this fraction of the column's largest magnitude print as 0.
pub const HISTORY_FLOOR: f64 = 1e-9;

/// `x` with `digits` significant digits, e.g. `3.58878e2`; `0` for zero; `nan`, `inf`.
pub fn sig(x: f64, digits: usize) -> String {
    if x == 0.0 {
        return "0".into();
    }
    if !x.is_finite() {
        return format!("{x}");
    }
    format!("{:.*e}", digits.saturating_sub(1), x)
}

fn floored(x: f64, floor: f64, digits: usize) -> String {
    if x.abs() < floor {
        "0".into()
    } else {
        sig(x, digits)
    }
}

/// The snapshot text of one case.
pub fn case_text(
    case: &CaseResult,
    spec: Option<&crate::definition::case::SnapshotSpec>,
    data: &BTreeMap<String, JobResult>,
) -> String {
    let digits = spec.and_then(|s| s.digits).unwrap_or(6);
    let mut out = String::new();
    let _ = writeln!(
        out,
        "case {} ({}/{}), {} significant digits",
        case.id, case.suite, case.case, digits
    );
    let _ = writeln!(out, "checks:");
    for k in &case.checks {
        let _ = writeln!(
            out,
            "  {:<5} {} computed {} reference {}",
            k.status.name(),
            k.id,
            k.computed
                .map_or("-".into(), |v| floored(v, METRIC_FLOOR, digits)),
            k.reference
                .map_or("-".into(), |v| floored(v, METRIC_FLOOR, digits)),
        );
    }
    let Some(spec) = spec else { return out };
    for scene in &spec.scenes {
        let _ = writeln!(out, "scene {scene}:");
        let d = match data.get(scene) {
            None => {
                let _ = writeln!(out, "  (no such scene)");
                continue;
            }
            Some(Err(e)) => {
                let _ = writeln!(out, "  error: {e}");
                continue;
            }
            Some(Ok(d)) => d,
        };
        let _ = writeln!(out, "  metrics:");
        for (k, v) in &d.metrics {
            let _ = writeln!(out, "    {k}: {}", floored(*v, METRIC_FLOOR, digits));
        }
        let Some(h) = d.history() else { continue };
        let Some(t) = h.column("time_s") else {
            continue;
        };
        let cols: Vec<(&String, Vec<f64>)> = spec
            .columns
            .iter()
            .filter_map(|c| h.column(c).map(|v| (c, v)))
            .collect();
        if cols.is_empty() || spec.times.is_empty() {
            continue;
        }
        let names: Vec<&str> = cols.iter().map(|c| c.0.as_str()).collect();
        let _ = writeln!(
            out,
            "  history at fixed times (time_s, {}):",
            names.join(", ")
        );
        let last = t.last().copied().unwrap_or(0.0);
        for &time in &spec.times {
            if time > last * (1.0 + 1e-12) {
                continue;
            }
            let mut row = vec![sig(time, digits)];
            for (_, v) in &cols {
                let peak = v.iter().fold(0.0f64, |a, b| a.max(b.abs()));
                row.push(floored(
                    interpolate(&t, v, time),
                    HISTORY_FLOOR * peak,
                    digits,
                ));
            }
            let _ = writeln!(out, "    {}", row.join("  "));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn significant_digits_not_decimals() {
        assert_eq!(sig(358.878378924, 6), "3.58878e2");
        assert_eq!(sig(-1.654004953e-3, 6), "-1.65400e-3");
        assert_eq!(sig(2.26e9, 3), "2.26e9");
        assert_eq!(sig(0.0, 6), "0");
        assert_eq!(floored(1e-16, METRIC_FLOOR, 6), "0");
    }
}
