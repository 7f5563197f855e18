//! `impact verify --baseline DIR`: what changed against an earlier verify output (e.g. of the
//! main branch). Per check, `results.json` gains `baseline` {computed, status, change,
//! change_over_tolerance}; `what-changed.md` (the report's opening section) counts the checks
//! unchanged / moved within 10 % of their tolerance / moved more / with a changed status,
//! lists them sorted by movement relative to the tolerance, and overlays baseline and current
//! histories of every run whose history moved (`what-changed/*.svg`).
//!
//! The tolerance a movement is measured against is the check's allowance in the units of
//! its computed value: `max(abs, rel |reference|)`; a one-sided bound written with a zero
//! tolerance (`at_most`/`at_least` the reference itself) is measured against `|reference|`.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use serde_json::Value;

/// A movement up to this fraction of the tolerance counts as "within 10 %".
pub const SMALL_MOVE: f64 = 0.1;

/// How a check moved against the baseline.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Movement {
    StatusChanged,
    MovedMore,
    MovedWithin,
    Unchanged,
}

impl Movement {
    pub fn label(self) -> &'static str {
        match self {
            Movement::StatusChanged => "status changed",
            Movement::MovedMore => "moved more than 10 % of tol.",
            Movement::MovedWithin => "moved within 10 % of tol.",
            Movement::Unchanged => "unchanged",
        }
    }
}

/// One check against its baseline.
#[derive(Debug, Clone)]
pub struct CheckChange {
    /// suite/case/check
    pub id: String,
    pub status: String,
    pub baseline_status: Option<String>,
    pub computed: Option<f64>,
    pub baseline: Option<f64>,
    pub change: Option<f64>,
    pub change_over_tolerance: Option<f64>,
    pub movement: Movement,
}

/// The comparison of a verify output with its baseline.
#[derive(Debug, Clone, Default)]
pub struct Changes {
    pub checks: Vec<CheckChange>,
    /// Runs whose histories moved: ("suite/case/scene/file (column; its ISO/TS 18571 rating
    /// against the baseline)", largest relative change, plot).
    pub histories: Vec<(String, f64, Option<PathBuf>)>,
}

impl Changes {
    pub fn count(&self, m: Movement) -> usize {
        self.checks.iter().filter(|c| c.movement == m).count()
    }

    /// `against baseline: N unchanged, ...` for the terminal.
    pub fn line(&self) -> String {
        format!(
            "against the baseline: {} unchanged, {} moved within 10 % of their tolerance, {} moved more, {} changed status; {} run histories moved",
            self.count(Movement::Unchanged),
            self.count(Movement::MovedWithin),
            self.count(Movement::MovedMore),
            self.count(Movement::StatusChanged),
            self.histories.len()
        )
    }
}

fn read_results(dir: &Path) -> Result<Value> {
    let path = dir.join("results.json");
    let text = std::fs::read_to_string(&path).with_context(|| {
        format!(
            "{}: cannot read; --baseline names an earlier `impact verify --out` folder",
            path.display()
        )
    })?;
    serde_json::from_str(&text).with_context(|| format!("{}: not JSON", path.display()))
}

/// The allowance of a check in its computed value's units (see the module doc).
pub fn allowance(check: &Value) -> Option<f64> {
    let tol = check["tolerance"].as_str().unwrap_or("");
    let part = |name: &str| {
        tol.split(',')
            .map(str::trim)
            .find_map(|p| p.strip_prefix(name))
            .and_then(|v| v.trim().parse::<f64>().ok())
    };
    let reference = check["reference"].as_f64().map(f64::abs);
    let a = part("abs ")
        .unwrap_or(0.0)
        .max(part("rel ").unwrap_or(0.0) * reference.unwrap_or(0.0));
    if a > 0.0 {
        return Some(a);
    }
    let one_sided = matches!(check["compare"].as_str(), Some("at_most" | "at_least"));
    reference.filter(|r| one_sided && *r > 0.0)
}

fn compare_check(id: String, now: &Value, before: Option<&Value>) -> CheckChange {
    let status = now["status"].as_str().unwrap_or("").to_string();
    let computed = now["computed"].as_f64();
    let baseline_status = before.map(|b| b["status"].as_str().unwrap_or("").to_string());
    let baseline = before.and_then(|b| b["computed"].as_f64());
    let change = computed.zip(baseline).map(|(c, b)| c - b);
    let change_over_tolerance = change.zip(allowance(now)).map(|(d, a)| d.abs() / a);
    let movement = if baseline_status.as_deref() != Some(status.as_str()) {
        Movement::StatusChanged
    } else if change.is_none_or(|d| d == 0.0) && computed.is_some() == baseline.is_some() {
        Movement::Unchanged
    } else if change_over_tolerance.is_some_and(|r| r <= SMALL_MOVE) {
        Movement::MovedWithin
    } else {
        Movement::MovedMore
    };
    CheckChange {
        id,
        status,
        baseline_status,
        computed,
        baseline,
        change,
        change_over_tolerance,
        movement,
    }
}

/// Compares `out` (just written by verify) with `baseline`, adds the `baseline` entries to
/// `out/results.json` and writes `out/what-changed.md` with its plots.
pub fn apply(baseline_dir: &Path, out: &Path) -> Result<Changes> {
    let before = read_results(baseline_dir)?;
    let mut now = read_results(out)?;
    let mut changes = Changes::default();
    let cases = now["cases"]
        .as_array_mut()
        .context("results.json: no cases")?;
    for case in cases.iter_mut() {
        let (suite, name) = (
            case["suite"].as_str().unwrap_or("").to_string(),
            case["case"].as_str().unwrap_or("").to_string(),
        );
        let old_case = before["cases"]
            .as_array()
            .into_iter()
            .flatten()
            .find(|c| c["suite"] == suite.as_str() && c["case"] == name.as_str());
        for check in case["checks"].as_array_mut().into_iter().flatten() {
            let id = check["id"].as_str().unwrap_or("").to_string();
            let old = old_case.and_then(|c| {
                c["checks"]
                    .as_array()
                    .into_iter()
                    .flatten()
                    .find(|k| k["id"] == id.as_str())
            });
            let c = compare_check(format!("{suite}/{name}/{id}"), check, old);
            check["baseline"] = serde_json::json!({
                "computed": c.baseline, "status": c.baseline_status, "change": c.change,
                "change_over_tolerance": c.change_over_tolerance, "movement": c.movement.label(),
            });
            changes.checks.push(c);
        }
    }
    let text = serde_json::to_string_pretty(&now)? + "\n";
    std::fs::write(out.join("results.json"), text)?;
    changes.histories = moved_histories(baseline_dir, out)?;
    std::fs::write(
        out.join("what-changed.md"),
        page(&changes, baseline_dir, out),
    )?;
    Ok(changes)
}

/// Every `runs/**/*.csv` of `out` whose baseline twin differs, with an overlay plot of its
/// most-moved column.
fn moved_histories(baseline_dir: &Path, out: &Path) -> Result<Vec<(String, f64, Option<PathBuf>)>> {
    let mut files = Vec::new();
    collect_csv(&out.join("runs"), &mut files);
    files.sort();
    let plots = out.join("what-changed");
    let _ = std::fs::remove_dir_all(&plots);
    let mut moved = Vec::new();
    for file in files {
        let rel = file
            .strip_prefix(out.join("runs"))
            .unwrap_or(&file)
            .to_path_buf();
        let twin = baseline_dir.join("runs").join(&rel);
        if !twin.exists() {
            continue;
        }
        let Ok((columns, _, _)) = crate::review::diff::diff_csv(&twin, &file, 0.0) else {
            continue;
        };
        // The energy balance error is a residual near zero: its relative change says little,
        // so it is shown only when nothing else moved.
        let most = |skip_residual: bool| {
            columns
                .iter()
                .filter(|c| c.rel > 0.0 && !(skip_residual && c.column == "energy_balance_error"))
                .max_by(|a, b| a.rel.total_cmp(&b.rel))
        };
        let Some(worst) = most(true).or_else(|| most(false)) else {
            continue;
        };
        let name = rel.display().to_string();
        let plot = overlay(&twin, &file, &worst.column, &name, &plots).ok();
        let rated = worst.iso.as_ref().map_or_else(
            || "not rated by ISO/TS 18571 (too few samples, or a flat curve)".to_string(),
            |r| {
                format!(
                    "ISO/TS 18571 {:.3} ({}) against the baseline",
                    r.overall,
                    crate::review::iso18571::Grade::of(r.overall).name()
                )
            },
        );
        moved.push((
            format!("{name} ({}; {rated})", worst.column),
            worst.rel,
            plot,
        ));
    }
    Ok(moved)
}

fn collect_csv(dir: &Path, into: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .filter_map(|e| e.ok())
    {
        let p = e.path();
        if p.is_dir() {
            collect_csv(&p, into);
        } else if p.extension().is_some_and(|x| x == "csv") {
            into.push(p);
        }
    }
}

/// Baseline (dashed) and current of one column, as `what-changed/<name>.svg`.
fn overlay(before: &Path, now: &Path, column: &str, name: &str, dir: &Path) -> Result<PathBuf> {
    let series = |p: &Path| -> Result<Vec<(f64, f64)>> {
        let cols = crate::review::diff::history_columns(p)?;
        let t = &cols[0].1;
        let v = &cols
            .iter()
            .find(|(n, _)| n == column)
            .context("column gone")?
            .1;
        Ok(t.iter().copied().zip(v.iter().copied()).collect())
    };
    let (quantity, unit) = impact_plots::line_plot::column_axis(column);
    let svg = impact_plots::line_plot::svg_plot(
        &format!("{name}: {quantity}"),
        impact_plots::line_plot::Axis::new("time", "s"),
        impact_plots::line_plot::Axis::new(&quantity, unit),
        &[
            ("baseline".to_string(), series(before)?, true),
            ("current".to_string(), series(now)?, false),
        ],
    );
    std::fs::create_dir_all(dir)?;
    let file = dir.join(format!(
        "{}.svg",
        name.replace(['/', '.', ' '], "-").trim_end_matches("-csv")
    ));
    std::fs::write(&file, svg)?;
    Ok(file)
}

fn num(x: Option<f64>) -> String {
    x.map_or("-".into(), |v| format!("{v:.4e}"))
}

/// `what-changed.md`: counts, the table sorted by movement relative to the tolerance, and
/// the overlaid histories.
fn page(changes: &Changes, baseline_dir: &Path, out: &Path) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "Against the baseline `{}`: **{}** checks unchanged, **{}** moved within 10 % of their tolerance, **{}** moved more, **{}** changed status.\n",
        baseline_dir.display(),
        changes.count(Movement::Unchanged),
        changes.count(Movement::MovedWithin),
        changes.count(Movement::MovedMore),
        changes.count(Movement::StatusChanged)
    );
    let mut moved: Vec<&CheckChange> = changes
        .checks
        .iter()
        .filter(|c| c.movement != Movement::Unchanged)
        .collect();
    moved.sort_by(|a, b| {
        a.movement.cmp(&b.movement).then(
            b.change_over_tolerance
                .unwrap_or(f64::INFINITY)
                .total_cmp(&a.change_over_tolerance.unwrap_or(f64::INFINITY)),
        )
    });
    if moved.is_empty() {
        s.push_str("No check moved.\n");
    } else {
        s.push_str("| check | status (baseline -> now) | baseline | now | change | change / tolerance |\n|---|---|---|---|---|---|\n");
        for c in moved {
            let _ = writeln!(
                s,
                "| {} | {} -> {} | {} | {} | {} | {} |",
                c.id,
                c.baseline_status.as_deref().unwrap_or("(new)"),
                c.status,
                num(c.baseline),
                num(c.computed),
                num(c.change),
                c.change_over_tolerance
                    .map_or("-".into(), |r| format!("{:.1} %", 100.0 * r))
            );
        }
    }
    if !changes.histories.is_empty() {
        let _ = writeln!(
            s,
            "\n### Histories that moved\n\nBaseline dashed, current solid; the column that moved most (relative to its peak) of each run.\n"
        );
        for (name, rel, plot) in &changes.histories {
            let _ = writeln!(s, "- `{name}`: largest change {:.2e} of the peak", rel);
            if let Some(p) = plot {
                let link = p.strip_prefix(out).unwrap_or(p).display().to_string();
                let _ = writeln!(s, "\n  ![{name}]({link})\n");
            }
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn movement_is_measured_against_the_allowance() {
        let now = serde_json::json!({"status": "OK", "computed": 10.5, "reference": 10.0,
            "tolerance": "rel 1.0e-1", "compare": "within"});
        let before = serde_json::json!({"status": "OK", "computed": 10.45});
        let c = compare_check("s/c/k".into(), &now, Some(&before));
        // allowance 1.0, change 0.05: 5 % of the tolerance.
        assert!((c.change_over_tolerance.unwrap() - 0.05).abs() < 1e-12);
        assert_eq!(c.movement, Movement::MovedWithin);
        let before = serde_json::json!({"status": "OK", "computed": 10.0});
        let c = compare_check("s/c/k".into(), &now, Some(&before));
        assert_eq!(c.movement, Movement::MovedMore);
        let before = serde_json::json!({"status": "FAIL", "computed": 10.5});
        let c = compare_check("s/c/k".into(), &now, Some(&before));
        assert_eq!(c.movement, Movement::StatusChanged);
        let c = compare_check("s/c/k".into(), &now, Some(&now));
        assert_eq!(c.movement, Movement::Unchanged);
        // A one-sided bound with zero tolerance: against the bound.
        let bound = serde_json::json!({"status": "OK", "computed": 0.001, "reference": 0.005,
            "tolerance": "abs 0.0e0", "compare": "at_most"});
        assert_eq!(allowance(&bound), Some(0.005));
    }
}
