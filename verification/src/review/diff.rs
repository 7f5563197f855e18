//! `impact diff RUN_A RUN_B`: what changed between two `impact simulate` output folders.
//! Every `summary.json` key (nested keys dotted, list items indexed) and, per `history.csv`
//! column, the largest absolute difference on A's time grid (B interpolated linearly onto
//! it, over the times both runs cover) and that difference relative to the column's peak
//! magnitude in A. A difference is "beyond" when its relative size exceeds `--tol`; the
//! wall-clock keys are shown but never compared (they differ on every run). What cannot be
//! compared is refused ([`crate::review::diff_input`]: NaN, a time that does not increase, a summary
//! that is no object) and so are two runs without a common time window; the closing summary
//! lists the moves physical first ([`crate::review::diff_moves`]). Each column also carries
//! the field's rating of B against A, ISO/TS 18571 ([`rating_of`]), beside the max-norm error.

use std::fmt::Write as _;
use std::path::Path;

use anyhow::{bail, Result};
use serde_json::Value;

use crate::definition::check::interpolate;
pub use crate::review::diff_input::history_columns;
use crate::review::diff_input::{check_comparable, read_summary};
use crate::review::diff_moves::Move;
use crate::review::iso18571::{Grade, Rating};

/// Summary keys that measure the machine, not the result: shown, never compared.
use impact_solver::summary::is_timing_key;

/// How one compared quantity came out.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// Bit-identical.
    Same,
    /// Differs, relative difference at most the tolerance.
    Within,
    /// Differs by more than the tolerance, or present in one run only, or a text changed.
    Beyond,
    /// A wall-clock key: shown, not compared.
    Timing,
}

impl Verdict {
    pub fn label(self) -> &'static str {
        match self {
            Verdict::Same => "same",
            Verdict::Within => "within",
            Verdict::Beyond => "BEYOND",
            Verdict::Timing => "timing",
        }
    }
}

/// One `summary.json` key in both runs.
#[derive(Debug, Clone)]
pub struct KeyDiff {
    /// Dotted key, e.g. `final_energy_J.plastic_work_J` or `contact_intervals_s[0][1]`.
    pub key: String,
    /// The values as JSON text (`-` when absent).
    pub a: String,
    pub b: String,
    /// |a - b| for numbers, in the key's unit.
    pub abs: Option<f64>,
    /// |a - b| / max(|a|, |b|) for numbers.
    pub rel: Option<f64>,
    pub verdict: Verdict,
}

/// One `history.csv` column in both runs.
#[derive(Debug, Clone)]
pub struct ColumnDiff {
    /// Column name, carrying its unit.
    pub column: String,
    /// Largest |a(t) - b(t)| on the common grid, in the column's unit (NaN when one run lacks it).
    pub max_abs: f64,
    /// Time of that largest difference, s.
    pub at_time: f64,
    /// `max_abs` over the column's peak |a| (0 when both are 0).
    pub rel: f64,
    pub verdict: Verdict,
    /// B rated against A by ISO/TS 18571 on the common window ([`rating_of`]); None where
    /// the standard cannot rate them (A zero throughout, fewer than 9 rows, one run only).
    pub iso: Option<Rating>,
}

/// The comparison of two runs.
#[derive(Debug, Clone)]
pub struct RunDiff {
    pub tol: f64,
    pub keys: Vec<KeyDiff>,
    pub columns: Vec<ColumnDiff>,
    /// The compared time window [start, end], s, and the number of grid points in it.
    pub window: (f64, f64, usize),
    /// A's and B's time spans, s.
    pub spans: ((f64, f64), (f64, f64)),
}

impl RunDiff {
    /// Keys and columns beyond the tolerance.
    pub fn n_beyond(&self) -> usize {
        self.keys
            .iter()
            .map(|k| k.verdict)
            .chain(self.columns.iter().map(|c| c.verdict))
            .filter(|v| *v == Verdict::Beyond)
            .count()
    }

    /// The table printed by `impact diff`, then one closing line.
    pub fn text(&self) -> String {
        let mut s = String::new();
        let w = self
            .keys
            .iter()
            .map(|k| k.key.len())
            .chain(self.columns.iter().map(|c| c.column.len()))
            .max()
            .unwrap_or(10)
            .max(10);
        let _ = writeln!(
            s,
            "summary.json{:pad$}  {:>16}  {:>16}  {:>10}  {:>10}  verdict",
            "",
            "A",
            "B",
            "|A - B|",
            "relative",
            pad = w - 12
        );
        for k in &self.keys {
            let _ = writeln!(
                s,
                "{:w$}  {:>16}  {:>16}  {:>10}  {:>10}  {}",
                k.key,
                clip(&k.a, 16),
                clip(&k.b, 16),
                k.abs.map_or("-".into(), |x| format!("{x:.3e}")),
                k.rel.map_or("-".into(), |x| format!("{x:.3e}")),
                k.verdict.label()
            );
        }
        let (t0, t1, n) = self.window;
        let ((a0, a1), (b0, b1)) = self.spans;
        let _ = writeln!(
            s,
            "\nhistory.csv on A's grid, {n} rows in [{t0:.6e}, {t1:.6e}] s (A covers [{a0:.6e}, {a1:.6e}], B [{b0:.6e}, {b1:.6e}])"
        );
        let _ = writeln!(
            s,
            "{:w$}  {:>10}  {:>12}  {:>10}  {:>15}  verdict",
            "column", "max |A - B|", "at time_s", "rel. peak", "ISO 18571"
        );
        for c in &self.columns {
            let iso = c.iso.map_or("-".to_string(), |r| {
                format!("{:.3} {}", r.overall, Grade::of(r.overall).name())
            });
            let _ = writeln!(
                s,
                "{:w$}  {:>11.3e}  {:>12.6e}  {:>10.3e}  {:>15}  {}",
                c.column,
                c.max_abs,
                c.at_time,
                c.rel,
                iso,
                c.verdict.label()
            );
        }
        s.push_str(&crate::review::diff_moves::listing(&self.moves()));
        let _ = writeln!(s, "{}", self.closing_line());
        s
    }

    /// `diff: ... beyond --tol ...` with the largest physical move
    /// ([`crate::review::diff_moves::headline`]).
    pub fn closing_line(&self) -> String {
        let n_keys = self
            .keys
            .iter()
            .filter(|k| k.verdict != Verdict::Timing)
            .count();
        format!(
            "diff: {n_keys} summary keys, {} history columns; {} beyond --tol {}; {}",
            self.columns.len(),
            self.n_beyond(),
            self.tol,
            crate::review::diff_moves::headline(&self.moves())
        )
    }

    /// What differs (within or beyond the tolerance), in the closing summary's order.
    pub fn moves(&self) -> Vec<Move> {
        let moved = |v: Verdict| matches!(v, Verdict::Within | Verdict::Beyond);
        let keys = self.keys.iter().filter(|k| moved(k.verdict)).map(|k| {
            let rel = k.rel.unwrap_or(f64::INFINITY);
            Move::new(
                &k.key,
                rel,
                k.verdict.label(),
                format!("{} -> {}", k.a, k.b),
            )
        });
        let columns = self
            .columns
            .iter()
            .filter(|c| moved(c.verdict))
            .map(|c| Move::new(&c.column, c.rel, c.verdict.label(), String::new()));
        crate::review::diff_moves::sorted(keys.chain(columns).collect())
    }
}

fn clip(s: &str, n: usize) -> String {
    if s.chars().count() <= n {
        s.to_string()
    } else {
        let head: String = s.chars().take(n - 1).collect();
        format!("{head}~")
    }
}

/// Compares two `impact simulate` output folders (`summary.json` and `history.csv` in each).
pub fn diff_runs(a: &Path, b: &Path, tol: f64) -> Result<RunDiff> {
    if !(tol >= 0.0 && tol.is_finite()) {
        bail!("--tol = {tol}: must be a finite number >= 0 (a relative difference)");
    }
    let keys = diff_summaries(&read_summary(a)?, &read_summary(b)?, tol);
    let (columns, window, spans) = diff_histories(a, b, tol)?;
    Ok(RunDiff {
        tol,
        keys,
        columns,
        window,
        spans,
    })
}

/// Flattens a JSON value into (dotted key, leaf value) pairs in document order.
fn flatten(prefix: &str, v: &Value, out: &mut Vec<(String, Value)>) {
    match v {
        Value::Object(map) => {
            for (k, x) in map {
                let key = if prefix.is_empty() {
                    k.clone()
                } else {
                    format!("{prefix}.{k}")
                };
                flatten(&key, x, out);
            }
        }
        Value::Array(items) if !items.is_empty() => {
            for (i, x) in items.iter().enumerate() {
                flatten(&format!("{prefix}[{i}]"), x, out);
            }
        }
        _ => out.push((prefix.to_string(), v.clone())),
    }
}

fn diff_summaries(a: &Value, b: &Value, tol: f64) -> Vec<KeyDiff> {
    let (mut fa, mut fb) = (Vec::new(), Vec::new());
    flatten("", a, &mut fa);
    flatten("", b, &mut fb);
    let mut keys: Vec<String> = fa.iter().map(|(k, _)| k.clone()).collect();
    for (k, _) in &fb {
        if !keys.contains(k) {
            keys.push(k.clone());
        }
    }
    let find = |f: &[(String, Value)], k: &str| f.iter().find(|(x, _)| x == k).map(|p| p.1.clone());
    keys.into_iter()
        .map(|key| {
            let (va, vb) = (find(&fa, &key), find(&fb, &key));
            let timing = is_timing_key(&key);
            key_diff(key, va, vb, tol, timing)
        })
        .collect()
}

/// A summary value as printed: integers whole, other numbers to 10 significant digits.
fn shown(v: &Value) -> String {
    match v {
        Value::Number(n) if n.is_f64() => format!("{:.9e}", n.as_f64().unwrap_or(f64::NAN)),
        other => other.to_string(),
    }
}

fn key_diff(key: String, a: Option<Value>, b: Option<Value>, tol: f64, timing: bool) -> KeyDiff {
    let text = |v: &Option<Value>| v.as_ref().map_or("-".to_string(), shown);
    let (ta, tb) = (text(&a), text(&b));
    let numbers = a
        .as_ref()
        .and_then(Value::as_f64)
        .zip(b.as_ref().and_then(Value::as_f64));
    let (abs, rel) = match numbers {
        Some((x, y)) => {
            let abs = (x - y).abs();
            let scale = x.abs().max(y.abs());
            (Some(abs), Some(if abs == 0.0 { 0.0 } else { abs / scale }))
        }
        None => (None, None),
    };
    let verdict = if timing {
        Verdict::Timing
    } else if a == b {
        Verdict::Same
    } else if rel.is_some_and(|r| r <= tol) {
        Verdict::Within
    } else {
        Verdict::Beyond
    };
    KeyDiff {
        key,
        a: ta,
        b: tb,
        abs,
        rel,
        verdict,
    }
}

/// Column comparisons, the compared window (start s, end s, rows) and both time spans, s.
pub type Histories = (Vec<ColumnDiff>, (f64, f64, usize), ((f64, f64), (f64, f64)));

fn diff_histories(a: &Path, b: &Path, tol: f64) -> Result<Histories> {
    diff_csv(&a.join("history.csv"), &b.join("history.csv"), tol)
}

/// Compares two history CSV files (`time_s` first) column by column on A's time grid:
/// the columns, the compared window [start, end, rows] and the two time spans, s.
pub fn diff_csv(a: &Path, b: &Path, tol: f64) -> Result<Histories> {
    let (ha, hb) = (history_columns(a)?, history_columns(b)?);
    check_comparable(a, &ha)?;
    check_comparable(b, &hb)?;
    let (ta, tb) = (&ha[0].1, &hb[0].1);
    let span = |t: &[f64]| (t[0], t[t.len() - 1]);
    let (sa, sb) = (span(ta), span(tb));
    let (t0, t1) = (sa.0.max(sb.0), sa.1.min(sb.1));
    let grid: Vec<usize> = (0..ta.len())
        .filter(|&i| ta[i] >= t0 && ta[i] <= t1)
        .collect();
    check_window(a, b, (sa, sb), &grid)?;
    let mut columns = Vec::new();
    for (name, va) in ha.iter().skip(1) {
        let Some((_, vb)) = hb.iter().find(|(n, _)| n == name) else {
            columns.push(missing(name));
            continue;
        };
        columns.push(column_diff(name, ta, va, tb, vb, &grid, tol));
    }
    for (name, _) in hb.iter().skip(1) {
        if !ha.iter().any(|(n, _)| n == name) {
            columns.push(missing(name));
        }
    }
    Ok((columns, (t0, t1, grid.len()), (sa, sb)))
}

/// Refuses two histories that share no time window (or share one instant only while either
/// spans more), or whose common window holds no row of A's grid.
fn check_window(a: &Path, b: &Path, spans: ((f64, f64), (f64, f64)), grid: &[usize]) -> Result<()> {
    let ((a0, a1), (b0, b1)) = spans;
    let (t0, t1) = (a0.max(b0), a1.min(b1));
    let spans_text = format!(
        "A ({}) covers [{a0:.6e}, {a1:.6e}] s, B ({}) [{b0:.6e}, {b1:.6e}] s",
        a.display(),
        b.display()
    );
    if t0 > t1 || (t0 == t1 && (a0 < a1 || b0 < b1)) {
        bail!("no common time window to compare: {spans_text}");
    }
    if grid.is_empty() {
        bail!("no row of A lies in the common time window [{t0:.6e}, {t1:.6e}] s, nothing to compare: {spans_text}");
    }
    Ok(())
}

fn missing(name: &str) -> ColumnDiff {
    ColumnDiff {
        column: format!("{name} (in one run only)"),
        max_abs: f64::NAN,
        at_time: f64::NAN,
        rel: f64::INFINITY,
        verdict: Verdict::Beyond,
        iso: None,
    }
}

fn column_diff(
    name: &str,
    ta: &[f64],
    va: &[f64],
    tb: &[f64],
    vb: &[f64],
    grid: &[usize],
    tol: f64,
) -> ColumnDiff {
    let same_grid = ta == tb;
    let b_at = |t: f64, i: usize| {
        if same_grid {
            vb[i]
        } else {
            interpolate(tb, vb, t)
        }
    };
    let (mut max_abs, mut at_time, mut peak) = (0.0_f64, f64::NAN, 0.0_f64);
    for &i in grid {
        let y = b_at(ta[i], i);
        let d = (va[i] - y).abs();
        peak = peak.max(va[i].abs());
        if d > max_abs || at_time.is_nan() {
            max_abs = d;
            at_time = ta[i];
        }
    }
    let rel = if max_abs == 0.0 { 0.0 } else { max_abs / peak };
    let verdict = if max_abs == 0.0 && !grid.is_empty() {
        Verdict::Same
    } else if rel <= tol {
        Verdict::Within
    } else {
        Verdict::Beyond
    };
    ColumnDiff {
        column: name.to_string(),
        max_abs,
        at_time,
        rel,
        verdict,
        iso: rating_of(ta, va, tb, vb, grid),
    }
}

/// B rated against A by ISO/TS 18571 on A's rows within the window both cover (see
/// [`rating_of`]); None where the standard cannot rate the pair. For histories compared
/// outside `impact diff` (another code's, a reference curve) that may start and end apart.
pub fn rating_in_common_window(ta: &[f64], va: &[f64], tb: &[f64], vb: &[f64]) -> Option<Rating> {
    let (lo, hi) = (ta.first()?.max(*tb.first()?), ta.last()?.min(*tb.last()?));
    let grid: Vec<usize> = (0..ta.len())
        .filter(|&i| ta[i] >= lo && ta[i] <= hi)
        .collect();
    rating_of(ta, va, tb, vb, &grid)
}

/// B's column rated against A's by ISO/TS 18571 ([`crate::review::iso18571`]): both
/// interpolated linearly onto as many equally spaced times as A has rows in the common
/// window, from its first to its last. The standard samples a crash pulse of ~150 ms at
/// 10 kHz; an impact history lasts microseconds to milliseconds and is written at the run's
/// output step, and the rating depends on the sampling only through the number of samples,
/// so A's own row count is the sampling kept. None where the standard cannot rate the pair.
pub fn rating_of(ta: &[f64], va: &[f64], tb: &[f64], vb: &[f64], grid: &[usize]) -> Option<Rating> {
    let (&first, &last) = (grid.first()?, grid.last()?);
    let n = grid.len();
    if n < crate::review::iso18571::MIN_SAMPLES {
        return None;
    }
    let (t0, t1) = (ta[first], ta[last]);
    let dt = (t1 - t0) / (n - 1) as f64;
    let times: Vec<f64> = (0..n).map(|k| t0 + dt * k as f64).collect();
    let a: Vec<f64> = times.iter().map(|&t| interpolate(ta, va, t)).collect();
    let b: Vec<f64> = times.iter().map(|&t| interpolate(tb, vb, t)).collect();
    crate::review::iso18571::rate(&a, &b, dt).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_changed_number_is_beyond_a_tight_tolerance_and_within_a_loose_one() {
        let a = serde_json::json!({"impulse_Ns": 100.0, "wall_time_s": 1.0, "e": {"k": 1.0}});
        let b = serde_json::json!({"impulse_Ns": 101.0, "wall_time_s": 9.0, "e": {"k": 1.0}});
        let d = diff_summaries(&a, &b, 1e-3);
        let key = |d: &[KeyDiff], k: &str| d.iter().find(|x| x.key == k).unwrap().clone();
        assert_eq!(key(&d, "impulse_Ns").verdict, Verdict::Beyond);
        assert!((key(&d, "impulse_Ns").rel.unwrap() - 1.0 / 101.0).abs() < 1e-15);
        assert_eq!(key(&d, "wall_time_s").verdict, Verdict::Timing);
        assert_eq!(key(&d, "e.k").verdict, Verdict::Same);
        let d = diff_summaries(&a, &b, 0.02);
        assert_eq!(key(&d, "impulse_Ns").verdict, Verdict::Within);
    }

    #[test]
    fn a_key_in_one_run_only_or_a_changed_text_is_beyond() {
        let a = serde_json::json!({"element": "q4-sri", "x": [1.0, 2.0]});
        let b = serde_json::json!({"element": "q4-full", "x": [1.0]});
        let d = diff_summaries(&a, &b, 1.0);
        let v: Vec<_> = d.iter().map(|k| (k.key.as_str(), k.verdict)).collect();
        assert_eq!(
            v,
            [
                ("element", Verdict::Beyond),
                ("x[0]", Verdict::Same),
                ("x[1]", Verdict::Beyond)
            ]
        );
    }

    #[test]
    fn a_column_on_another_grid_is_interpolated() {
        // B is the same straight line sampled twice as densely: no difference.
        let ta = [0.0, 1.0, 2.0];
        let va = [0.0, 2.0, 4.0];
        let tb = [0.0, 0.5, 1.0, 1.5, 2.0];
        let vb = [0.0, 1.0, 2.0, 3.0, 4.0];
        let c = column_diff("y", &ta, &va, &tb, &vb, &[0, 1, 2], 0.0);
        assert_eq!((c.max_abs, c.verdict), (0.0, Verdict::Same));
        // Shifted by 0.4 at t = 1: relative to the peak 4.
        let vb = [0.0, 1.0, 2.4, 3.0, 4.0];
        let c = column_diff("y", &ta, &va, &tb, &vb, &[0, 1, 2], 0.05);
        assert!((c.max_abs - 0.4).abs() < 1e-12 && c.at_time == 1.0);
        assert!((c.rel - 0.1).abs() < 1e-12);
        assert_eq!(c.verdict, Verdict::Beyond);
    }
}
