//! Evaluating one check: the measured value, the reference value, the tolerance, the status.

use std::collections::BTreeMap;
use std::path::Path;

use impact_solver::History;
use serde::{Deserialize, Serialize};

use crate::definition::case::{
    series_scene_name, CheckFile, Compare, MeasureFile, Norm, Reduce, ReferenceFile, Refine,
    SeriesSpec,
};
use crate::definition::csv_columns::read_csv_columns;
use crate::definition::measure_error::MeasureError;
use crate::definition::run_data::JobResult;
use crate::definition::validation::{ValidationFile, ValidationRow};

#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
pub enum Status {
    #[serde(rename = "OK")]
    Ok,
    #[serde(rename = "FAIL")]
    Fail,
    #[serde(rename = "SKIP")]
    Skip,
    /// Another code cannot express what the check measures (a feature it lacks, a kernel of
    /// `impact` itself), or did not produce it: neither OK nor FAIL (issue 38).
    #[serde(rename = "N/E")]
    NotExpressible,
}

impl Status {
    pub fn name(self) -> &'static str {
        match self {
            Status::Ok => "OK",
            Status::Fail => "FAIL",
            Status::Skip => "SKIP",
            Status::NotExpressible => "N/E",
        }
    }
}

/// Whether a check's error is divided by |reference| (results.json: "relative", "absolute").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ErrorKind {
    Relative,
    Absolute,
}

/// The outcome of one check, as printed in the matrix and written to results.json (and read
/// back from it by the report).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CheckResult {
    pub id: String,
    pub title: String,
    pub status: Status,
    pub computed: Option<f64>,
    pub reference: Option<f64>,
    /// `computed - reference`, divided by |reference| when the tolerance is relative.
    pub error: Option<f64>,
    pub error_kind: ErrorKind,
    pub compare: Compare,
    /// The tolerance as written (e.g. "rel 5.0e-2, abs 1.0e-9, floor 1.0e-12").
    pub tolerance: String,
    pub tolerance_reason: String,
    pub reference_kind: String,
    pub reference_source: String,
    /// Why it failed or was skipped (empty for OK).
    pub message: String,
    pub known_failure: Option<String>,
    /// The V&V 20 budget of a check against a measurement (reference kind `experiment`).
    #[serde(
        default,
        rename = "vv20_budget",
        skip_serializing_if = "Option::is_none"
    )]
    pub validation: Option<ValidationRow>,
    /// The run did not write what the check reads ([`MeasureError::NotProduced`]): another
    /// code's row shows it *not produced* (N/E), not FAIL. Not written to results.json.
    #[serde(skip)]
    pub not_produced: bool,
}

/// What a check can read: the results of its case's jobs and where reference files live.
pub struct Context<'a> {
    pub results: &'a BTreeMap<String, JobResult>,
    pub series: &'a BTreeMap<String, SeriesSpec>,
    pub root: &'a Path,
    /// Used when a measure names no scene and the case has exactly one.
    pub default_scene: Option<&'a str>,
}

fn fmt_tol(t: &crate::definition::case::ToleranceFile) -> String {
    let mut parts = Vec::new();
    if let Some(r) = t.relative {
        parts.push(format!("rel {r:.1e}"));
    }
    if let Some(a) = t.absolute {
        parts.push(format!("abs {a:.1e}"));
    }
    if let Some(f) = t.floor {
        parts.push(format!("floor {f:.1e}"));
    }
    if parts.is_empty() {
        "exact".into()
    } else {
        parts.join(", ")
    }
}

pub fn evaluate(check: &CheckFile, ctx: &Context) -> CheckResult {
    let tol = check
        .tolerance
        .as_ref()
        .map(|t| t.value.clone())
        .unwrap_or_default();
    let reference = check
        .reference
        .as_ref()
        .map(|r| r.value.clone())
        .unwrap_or_default();
    let mut result = CheckResult {
        id: check.id.clone(),
        title: check.title.clone(),
        status: Status::Fail,
        computed: None,
        reference: None,
        error: None,
        error_kind: if tol.relative.is_some() {
            ErrorKind::Relative
        } else {
            ErrorKind::Absolute
        },
        compare: check.compare,
        tolerance: fmt_tol(&tol),
        tolerance_reason: tol.reason.clone().unwrap_or_default(),
        reference_kind: reference.kind.map_or("(none)", |k| k.name()).to_string(),
        reference_source: reference.source.clone().unwrap_or_default(),
        message: String::new(),
        known_failure: check.known_failure.clone(),
        validation: None,
        not_produced: false,
    };
    if let Some(skip) = &check.skip {
        if skip.value.is_skip() {
            result.status = Status::Skip;
            result.message = skip
                .value
                .reason()
                .unwrap_or("(no reason given)")
                .to_string();
            return result;
        }
    }
    if let Some(p) = &reference.pending {
        result.status = Status::Skip;
        result.message = format!("reference pending: {p}");
        return result;
    }
    let measure = &check.measure.value;
    let ref_history = match &reference.history {
        Some(h) => match reference_history(h, ctx) {
            Ok(v) => Some(v),
            Err(e) => {
                return not_evaluated(result, e.prefixed("reference: "));
            }
        },
        None => None,
    };
    let computed = match measure_value(measure, ctx, ref_history.as_ref()) {
        Ok(v) => v,
        Err(e) => {
            // The bound or reference value still shows (a failed run printed "<= -"), when
            // it does not come from the run itself.
            result.reference = run_free_reference(&reference, measure, ctx);
            return not_evaluated(result, e);
        }
    };
    result.computed = Some(computed);
    let reference_value = if measure.error.is_some() {
        Ok(reference.value.unwrap_or(0.0))
    } else {
        reference_value(&reference, measure, ctx)
    };
    let r = match reference_value {
        Ok(v) => v,
        Err(e) => return not_evaluated(result, e.prefixed("reference: ")),
    };
    result.reference = Some(r);
    if let Some(v) = &check.validation {
        return validated(
            result,
            &v.value,
            (computed, r),
            (measure, reference.table.as_ref()),
            ctx,
        );
    }
    judged(result, &tol, (computed, r), check.compare)
}

/// A FAIL without a value: `e`'s message, and whether it is *not produced*.
fn not_evaluated(mut result: CheckResult, e: MeasureError) -> CheckResult {
    result.not_produced = e.is_not_produced();
    result.message = e.to_string();
    result
}

/// The verdict of `computed` against reference `r` within tolerance `tol`, by `compare`.
fn judged(
    mut result: CheckResult,
    tol: &crate::definition::case::ToleranceFile,
    (computed, r): (f64, f64),
    compare: Compare,
) -> CheckResult {
    let floor = tol.floor.unwrap_or(0.0);
    let allowance = tol
        .absolute
        .unwrap_or(0.0)
        .max(tol.relative.unwrap_or(0.0) * r.abs());
    let diff = computed - r;
    result.error = Some(if tol.relative.is_some() && r != 0.0 {
        diff / r.abs()
    } else {
        diff
    });
    if !computed.is_finite() {
        result.message = "the computed value is not finite".into();
        return result;
    }
    let zero = computed.abs() < floor && r.abs() < floor;
    let pass = zero
        || match compare {
            Compare::Within => diff.abs() <= allowance,
            Compare::AtMost => diff <= allowance,
            Compare::AtLeast => -diff <= allowance,
        };
    if pass {
        result.status = Status::Ok;
    } else {
        result.message = match compare {
            Compare::Within => format!(
                "|computed - reference| = {:.3e} exceeds {:.3e}",
                diff.abs(),
                allowance
            ),
            Compare::AtMost => format!("computed exceeds reference + {allowance:.3e}"),
            Compare::AtLeast => format!("computed is below reference - {allowance:.3e}"),
        };
    }
    result
}

/// The verdict of a comparison with a measurement: `|S - D| <= k u_val` with the budget of
/// [`ValidationRow`], whose parts come from the same measure on the case's other scenes.
fn validated(
    mut result: CheckResult,
    spec: &ValidationFile,
    (simulation, measurement): (f64, f64),
    (measure, table): (&MeasureFile, Option<&crate::definition::case::TableRef>),
    ctx: &Context,
) -> CheckResult {
    let on = |scene: &str| {
        let mut m = measure.clone();
        m.scene = Some(scene.to_string());
        measure_value(&m, ctx, None).map_err(|e| e.prefixed(&format!("scene {scene}: ")))
    };
    let parts = on(&spec.numerical.scene).and_then(|coarse| {
        let inputs = spec
            .input
            .iter()
            .map(|(name, d)| Ok((name.clone(), on(&d.scene)?)))
            .collect::<Result<Vec<_>, MeasureError>>()?;
        Ok(ValidationRow::new(
            spec,
            (simulation, measurement),
            coarse,
            inputs,
        )?)
    });
    let parts = parts.map(|row| ValidationRow {
        measurement_file: table.map(|t| t.file.clone()),
        measurement_row: table.and_then(|t| match t.row.values().collect::<Vec<_>>()[..] {
            [one] => Some(one.clone()),
            _ => None,
        }),
        ..row
    });
    let row = match parts {
        Ok(row) => row,
        Err(e) => return not_evaluated(result, e.prefixed("validation budget: ")),
    };
    result.error_kind = ErrorKind::Absolute;
    result.error = Some(row.comparison_error);
    result.tolerance = format!("k u_val = {:.3e}", row.k * row.u_val);
    result.tolerance_reason = format!(
        "V&V 20: u_val = {:.3e} (u_num {:.3e}, u_input {:.3e}, u_D {:.3e}), k = {}",
        row.u_val, row.u_num, row.u_input, row.u_d, row.k
    );
    if row.covered() {
        result.status = Status::Ok;
    } else {
        result.message = format!(
            "|E| = {:.3e} exceeds k u_val = {:.3e}: a model error the uncertainties do not cover",
            row.comparison_error.abs(),
            row.k * row.u_val
        );
    }
    result.validation = Some(row);
    result
}

fn scene_name<'a>(m: &'a MeasureFile, ctx: &'a Context) -> Result<&'a str, MeasureError> {
    m.scene
        .as_deref()
        .or(ctx.default_scene)
        .ok_or_else(|| "the measure names no scene and the case has not exactly one".into())
}

fn job<'a>(
    name: &str,
    ctx: &'a Context,
) -> Result<&'a crate::definition::run_data::RunData, MeasureError> {
    match ctx.results.get(name) {
        None => Err(format!("no scene {name:?} in this case").into()),
        Some(Err(e)) => Err(format!("scene {name} failed: {e}").into()),
        Some(Ok(d)) => Ok(d),
    }
}

fn column(h: &History, name: &str) -> Result<(Vec<f64>, Vec<f64>), MeasureError> {
    let t = h
        .column("time_s")
        .ok_or("the history has no time_s column")?;
    let v = h.column(name).ok_or_else(|| {
        MeasureError::NotProduced(format!(
            "no history column {name:?} (have: {})",
            h.columns.join(", ")
        ))
    })?;
    Ok((t, v))
}

/// Linear interpolation of (t, v) at time `x` (clamped to the ends).
pub fn interpolate(t: &[f64], v: &[f64], x: f64) -> f64 {
    if t.is_empty() {
        return f64::NAN;
    }
    if x <= t[0] {
        return v[0];
    }
    let i = t.partition_point(|&s| s <= x);
    if i >= t.len() {
        return v[t.len() - 1];
    }
    let (t0, t1) = (t[i - 1], t[i]);
    if t1 == t0 {
        return v[i];
    }
    v[i - 1] + (v[i] - v[i - 1]) * (x - t0) / (t1 - t0)
}

pub fn measure_value(
    m: &MeasureFile,
    ctx: &Context,
    ref_history: Option<&(Vec<f64>, Vec<f64>)>,
) -> Result<f64, MeasureError> {
    if m.selector_count() != 1 {
        return Err(crate::definition::case::ONE_SELECTOR.into());
    }
    let mut value = if let Some(name) = &m.metric {
        let d = job(scene_name(m, ctx)?, ctx)?;
        *d.metrics.get(name).ok_or_else(|| {
            MeasureError::NotProduced(format!(
                "no metric {name:?} (have: {})",
                d.metrics.keys().cloned().collect::<Vec<_>>().join(", ")
            ))
        })?
    } else if let Some(at) = &m.at {
        let d = job(scene_name(m, ctx)?, ctx)?;
        let (t, v) = column(history_of(d)?, &at.column)?;
        interpolate(&t, &v, at.time)
    } else if let Some(x) = &m.extreme {
        let d = job(scene_name(m, ctx)?, ctx)?;
        let (t, v) = column(history_of(d)?, &x.column)?;
        let w = x.window.unwrap_or([f64::NEG_INFINITY, f64::INFINITY]);
        let sel: Vec<f64> = t
            .iter()
            .zip(&v)
            .filter(|(t, _)| **t >= w[0] && **t <= w[1])
            .map(|(_, v)| *v)
            .collect();
        if sel.is_empty() {
            return Err("no history rows in the window".into());
        }
        match x.reduce {
            Reduce::Max => sel.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            Reduce::Min => sel.iter().copied().fold(f64::INFINITY, f64::min),
            Reduce::AbsMax => sel
                .iter()
                .copied()
                .fold(0.0, |a: f64, b| if b.abs() > a.abs() { b } else { a }),
            Reduce::Mean => sel.iter().sum::<f64>() / sel.len() as f64,
        }
    } else if let Some(e) = &m.error {
        let d = job(scene_name(m, ctx)?, ctx)?;
        let (t, v) = column(history_of(d)?, &e.column)?;
        let (rt, rv) = ref_history.ok_or("an error measure needs a reference history")?;
        let w = e.window.unwrap_or([f64::NEG_INFINITY, f64::INFINITY]);
        let pts: Vec<(f64, f64)> = rt
            .iter()
            .zip(rv)
            .filter(|(tr, _)| **tr >= w[0] && **tr <= w[1])
            .map(|(tr, r)| (interpolate(&t, &v, *tr) - r, *r))
            .collect();
        if pts.is_empty() {
            return Err("no reference rows in the window".into());
        }
        let scale = pts.iter().map(|p| p.1.abs()).fold(0.0, f64::max);
        if scale == 0.0 {
            return Err("the reference history is zero in the window".into());
        }
        let norm = match e.norm {
            Norm::Linf => pts.iter().map(|p| p.0.abs()).fold(0.0, f64::max),
            Norm::L2 => (pts.iter().map(|p| p.0 * p.0).sum::<f64>() / pts.len() as f64).sqrt(),
        };
        norm / scale
    } else if let Some(r) = &m.ratio {
        if r.len() != 2 {
            return Err("ratio needs [numerator, denominator]".into());
        }
        let a = measure_value(&inherit(&r[0], m), ctx, ref_history)?;
        let b = measure_value(&inherit(&r[1], m), ctx, ref_history)?;
        a / b
    } else if let Some(b) = &m.band {
        let [v, lo, hi] = b.as_slice() else {
            return Err("band needs [value, lower, upper]".into());
        };
        let at = |x: &MeasureFile| measure_value(&inherit(x, m), ctx, ref_history);
        let (v, lo, hi) = (at(v)?, at(lo)?, at(hi)?);
        if !(hi > lo) {
            return Err(format!("band: upper {hi:e} is not above lower {lo:e}").into());
        }
        (v - lo) / (hi - lo)
    } else if let Some(q) = &m.order {
        series_order(q, ctx)?.finest_order()
    } else if let Some(q) = &m.gci {
        series_order(q, ctx)?
            .gci
            .ok_or("a gci needs the formal order: gci: {series, metric, formal}")?
            .value
    } else if let Some(q) = &m.change {
        series_change(q, ctx)?
    } else if let Some(p) = &m.profile_gap {
        let d = job(scene_name(m, ctx)?, ctx)?;
        let summary = d
            .summary
            .as_ref()
            .ok_or_else(|| MeasureError::NotProduced("the scene has no summary".into()))?;
        crate::definition::profile_gap::profile_gap(summary, &ctx.root.join(&p.file))?
    } else {
        unreachable!()
    };
    if let Some(s) = m.scale {
        value *= s;
    }
    if m.abs {
        value = value.abs();
    }
    Ok(value)
}

/// The run's history, or *not produced*.
fn history_of(d: &crate::definition::run_data::RunData) -> Result<&History, MeasureError> {
    d.history()
        .ok_or_else(|| MeasureError::NotProduced("the scene has no history".into()))
}

fn inherit(inner: &MeasureFile, outer: &MeasureFile) -> MeasureFile {
    let mut m = inner.clone();
    if m.scene.is_none() {
        m.scene = outer.scene.clone();
    }
    m
}

/// The metric of each level of a series, coarse to fine.
pub fn series_values(
    series: &str,
    metric: &str,
    ctx: &Context,
) -> Result<(Vec<f64>, Vec<f64>, Refine), MeasureError> {
    let s = ctx
        .series
        .get(series)
        .ok_or_else(|| format!("no series {series:?} in this case"))?;
    let mut values = Vec::new();
    for level in &s.levels {
        let d = job(&series_scene_name(series, *level), ctx)?;
        values.push(
            *d.metrics
                .get(metric)
                .ok_or_else(|| MeasureError::NotProduced(format!("no metric {metric:?}")))?,
        );
    }
    Ok((s.levels.clone(), values, s.refine))
}

/// The series assessed by the GCI rule of [`crate::definition::gci`] (every triplet's order, monotone
/// convergence, the safety factor); `Err` with the evidence when it is not asymptotic.
pub fn series_order(
    q: &crate::definition::case::SeriesQuantity,
    ctx: &Context,
) -> Result<crate::definition::gci::Assessment, MeasureError> {
    let (levels, f, _) = series_values(&q.series, &q.metric, ctx)?;
    if levels.len() < 3 {
        return Err("an order needs at least three levels".into());
    }
    let r = levels[1] / levels[0];
    if levels
        .windows(2)
        .any(|w| ((w[1] / w[0]) / r - 1.0).abs() > 1e-9)
    {
        return Err("the levels must have a constant refinement ratio".into());
    }
    Ok(crate::definition::gci::assess(&f, r, q.formal)?)
}

/// Relative change from the first to the last level: `|f_first - f_last| / |f_last|`.
pub fn series_change(
    q: &crate::definition::case::SeriesQuantity,
    ctx: &Context,
) -> Result<f64, MeasureError> {
    let (_, f, _) = series_values(&q.series, &q.metric, ctx)?;
    match (f.first(), f.last()) {
        (Some(first), Some(last)) if f.len() >= 2 => Ok(((first - last) / last).abs()),
        _ => Err("a change needs at least two levels".into()),
    }
}

/// The reference when it does not come from the run (a literal, a table cell, a JSON
/// value): what a check whose measure failed still shows.
fn run_free_reference(r: &ReferenceFile, measure: &MeasureFile, ctx: &Context) -> Option<f64> {
    if r.metric.is_some() || measure.error.is_some() {
        return None;
    }
    reference_value(r, measure, ctx).ok()
}

fn reference_value(
    r: &ReferenceFile,
    measure: &MeasureFile,
    ctx: &Context,
) -> Result<f64, MeasureError> {
    let sources = [
        r.value.is_some(),
        r.table.is_some(),
        r.metric.is_some(),
        r.json.is_some(),
    ];
    if sources.iter().filter(|&&b| b).count() != 1 {
        return Err("a reference needs exactly one of value, table, metric, json".into());
    }
    let v = if let Some(v) = r.value {
        v
    } else if let Some(t) = &r.table {
        table_value(&ctx.root.join(&t.file), &t.row, &t.column)?
    } else if let Some(m) = &r.metric {
        measure_value(&inherit(m, measure), ctx, None)?
    } else if let Some(j) = &r.json {
        let path = ctx.root.join(&j.file);
        let text =
            std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        let value: serde_json::Value =
            serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
        let mut cur = &value;
        for part in j.key.split('.') {
            cur = cur
                .get(part)
                .ok_or_else(|| format!("{}: no key {:?}", path.display(), j.key))?;
        }
        cur.as_f64()
            .ok_or_else(|| format!("{}: {:?} is not a number", path.display(), j.key))?
    } else {
        unreachable!()
    };
    Ok(v * r.scale.unwrap_or(1.0))
}

/// A cell of a CSV table: the row whose columns match `row` (printed strings), `column`.
pub fn table_value(
    path: &Path,
    row: &BTreeMap<String, String>,
    column: &str,
) -> Result<f64, String> {
    let cell = table_text(path, row, column)?;
    cell.trim()
        .parse::<f64>()
        .map_err(|_| format!("{}: {cell:?} is not a number", path.display()))
}

/// A CSV table's cell as written (the digits the source printed).
pub fn table_text(
    path: &Path,
    row: &BTreeMap<String, String>,
    column: &str,
) -> Result<String, String> {
    let mut rd = csv::Reader::from_path(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let headers = rd
        .headers()
        .map_err(|e| format!("{}: {e}", path.display()))?
        .clone();
    let idx = |name: &str| {
        headers
            .iter()
            .position(|h| h == name)
            .ok_or_else(|| format!("{}: no column {name:?}", path.display()))
    };
    let col = idx(column)?;
    let keys: Vec<(usize, &String)> = row
        .iter()
        .map(|(k, v)| idx(k).map(|i| (i, v)))
        .collect::<Result<_, _>>()?;
    for rec in rd.records() {
        let rec = rec.map_err(|e| format!("{}: {e}", path.display()))?;
        if keys.iter().all(|(i, v)| rec.get(*i) == Some(v.as_str())) {
            return Ok(rec.get(col).unwrap_or("").trim().to_string());
        }
    }
    Err(format!("{}: no row with {row:?}", path.display()))
}

/// A reference history: a CSV file (time_s + column) or a scene's / builtin's history.
pub fn reference_history(
    h: &crate::definition::case::HistoryRef,
    ctx: &Context,
) -> Result<(Vec<f64>, Vec<f64>), MeasureError> {
    match (&h.file, &h.scene) {
        (Some(f), None) => Ok(read_csv_columns(&ctx.root.join(f), &h.column)?),
        (None, Some(s)) => {
            let d = job(s, ctx)?;
            let hist = d
                .histories
                .get(&h.column)
                .or_else(|| d.history())
                .ok_or_else(|| MeasureError::NotProduced(format!("scene {s} has no history")))?;
            let name = if hist.columns.iter().any(|c| c == &h.column) {
                h.column.as_str()
            } else {
                "value"
            };
            column(hist, name)
        }
        _ => Err("a reference history needs exactly one of file or scene".into()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interpolation_is_linear_and_clamped() {
        let t = [0.0, 1.0, 2.0];
        let v = [0.0, 10.0, 0.0];
        assert_eq!(interpolate(&t, &v, 0.5), 5.0);
        assert_eq!(interpolate(&t, &v, 1.5), 5.0);
        assert_eq!(interpolate(&t, &v, -1.0), 0.0);
        assert_eq!(interpolate(&t, &v, 3.0), 0.0);
    }

    /// A bound check whose run failed still shows its bound (the report printed "<= -").
    #[test]
    fn a_failed_measure_keeps_its_literal_bound() {
        let check: CheckFile = serde_saphyr::from_str(
            "id: balance\ntitle: t\ncompare: at_most\nmeasure: {scene: gone, metric: max_energy_balance_error}\n\
             reference: {kind: acceptance, value: 1.0e-4, source: s}\ntolerance: {absolute: 0.0, reason: r}\n",
        )
        .unwrap();
        let (results, series) = (BTreeMap::new(), BTreeMap::new());
        let ctx = Context {
            results: &results,
            series: &series,
            root: Path::new("."),
            default_scene: None,
        };
        let r = evaluate(&check, &ctx);
        assert_eq!(r.status, Status::Fail);
        assert_eq!((r.computed, r.reference), (None, Some(1.0e-4)));
        assert_eq!(
            crate::definition::check_row::CheckRow::of(&r).reference,
            "<= 1.000000e-4"
        );
    }

    /// *Not produced* is a type, not words: a key or column the run did not write (a summary
    /// without the metric, a history without the column) marks the row; a scene that failed, a
    /// reference file without the key or a message that merely quotes "no metric" does not.
    #[test]
    fn what_the_run_did_not_write_is_marked_not_produced() {
        let check = |measure: &str, reference: &str| -> CheckFile {
            serde_saphyr::from_str(&format!(
                "id: k\ntitle: t\nmeasure: {measure}\nreference: {reference}\n\
                 tolerance: {{absolute: 1.0, reason: r}}\n"
            ))
            .unwrap()
        };
        let mut run = crate::definition::run_data::RunData::default();
        run.metrics.insert("peak_contact_force_N".into(), 1.0);
        let mut results = BTreeMap::new();
        results.insert("plate".to_string(), Ok(std::sync::Arc::new(run)));
        results.insert(
            "gone".to_string(),
            Err("no metric words in a crash".to_string()),
        );
        let series = BTreeMap::new();
        let ctx = Context {
            results: &results,
            series: &series,
            root: Path::new("/nonexistent"),
            default_scene: None,
        };
        let literal = "{kind: analytical, value: 1.0, source: s}";
        let marked = |m: &str, r: &str| {
            let r = evaluate(&check(m, r), &ctx);
            assert_eq!(r.status, Status::Fail, "{}", r.message);
            r.not_produced
        };
        assert!(marked("{scene: plate, metric: impulse_Ns}", literal));
        assert!(marked(
            "{scene: plate, at: {column: mid_uy_m, time: 0.0}}",
            literal
        ));
        let from_run = "{kind: analytical, metric: {scene: plate, metric: impulse_Ns}, source: s}";
        assert!(marked(
            "{scene: plate, metric: peak_contact_force_N}",
            from_run
        ));
        assert!(!marked("{scene: gone, metric: impulse_Ns}", literal));
        assert!(!marked("{scene: absent, metric: impulse_Ns}", literal));
        let json = "{kind: analytical, json: {file: no.json, key: impulse_Ns}, source: s}";
        assert!(!marked(
            "{scene: plate, metric: peak_contact_force_N}",
            json
        ));
    }
}
