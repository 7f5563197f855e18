//! The matrix written out: its one-line total, the table of checks and the per-suite summary
//! (matrix.txt, and the terminal), JUnit XML, results.json, and each run's history.csv and
//! summary.json under runs/ for the report.

use std::collections::BTreeMap;
use std::path::Path;

use crate::definition::check::Status;
use crate::definition::verdict::{Tally, Verdict};
use crate::run::matrix::{Matrix, Outcome};

/// The one-line total: `verify: 2 cases, 5 checks: 4 OK, 1 FAIL* (exit 0, 3.2 s)`.
pub fn total_line(m: &Matrix, seconds: f64) -> String {
    let t = m.tally();
    let n_checks = t.total();
    let mut line = format!(
        "verify: {} case{}, {n_checks} check{}: {}",
        m.cases.len(),
        if m.cases.len() == 1 { "" } else { "s" },
        if n_checks == 1 { "" } else { "s" },
        t.short(),
    );
    for c in &m.codes {
        let t = Tally::of(c.cases.iter().flat_map(|r| r.checks.iter()));
        let n = c.cases.len();
        let s = if n == 1 { "" } else { "s" };
        line.push_str(&format!("; {}: {n} case{s}, {}", c.code, t.short()));
    }
    line + &format!(" (exit {}, {seconds:.1} s)", m.exit_status())
}

/// The matrix as text: one row per check (with the code first when other codes ran).
pub fn matrix_text(m: &Matrix) -> String {
    let mut rows = vec![[
        "code".to_string(),
        "suite".to_string(),
        "case".into(),
        "check".into(),
        "status".into(),
        "computed".into(),
        "reference".into(),
        "error (one-sided: margin)".into(),
        "tolerance".into(),
    ]];
    for (c, k) in m.all_codes_checks() {
        let row = crate::definition::check_row::CheckRow::of(k);
        rows.push([
            c.code.clone(),
            c.suite.clone(),
            c.case.clone(),
            k.id.clone(),
            row.verdict.label().to_string(),
            row.computed,
            row.reference,
            row.error,
            row.tolerance,
        ]);
    }
    let mut widths = [0usize; 9];
    for r in &rows {
        for (w, s) in widths.iter_mut().zip(r) {
            *w = (*w).max(s.chars().count());
        }
    }
    // The code column only when another code ran (impact's own matrix.txt is as it was).
    let first = usize::from(m.codes.is_empty());
    let mut out = String::new();
    for r in &rows {
        let line: Vec<String> = r[first..]
            .iter()
            .zip(&widths[first..])
            .map(|(s, &w)| format!("{s:<w$}"))
            .collect();
        out.push_str(line.join("  ").trim_end());
        out.push('\n');
    }
    out
}

/// Per-suite counts (known failures and unexpected passes apart), the total line, and the
/// list of non-OK checks with their messages.
pub fn summary_text(m: &Matrix) -> String {
    let mut per: BTreeMap<String, Tally> = BTreeMap::new();
    for (c, k) in m.all_codes_checks() {
        let name = format!("{}{}", c.code_prefix(), c.suite);
        per.entry(name).or_default().add(Verdict::of_check(k));
    }
    // The N/E column only when another code ran (impact's own matrix.txt is as it was).
    let with_ne = !m.codes.is_empty();
    let w = per
        .keys()
        .map(|k| k.chars().count())
        .max()
        .unwrap_or(0)
        .max(20);
    let row = |name: &str, t: &Tally| {
        let ne = if with_ne {
            format!(" {:>5}", t.not_expressible)
        } else {
            String::new()
        };
        format!(
            "{name:<w$} {:>4} {:>6} {:>5} {:>6} {:>5}{ne}\n",
            t.ok, t.known_fail, t.fail, t.xpass, t.skip
        )
    };
    let mut out = format!("\n{:<w$}  OK  FAIL*  FAIL  XPASS  SKIP", "suite");
    out.push_str(if with_ne { "    N/E\n" } else { "\n" });
    for (s, t) in &per {
        out.push_str(&row(s, t));
    }
    let total = m.tally_all();
    out.push_str(&row("total", &total));
    out.push_str(&format!(
        "matrix: {} ({} unexpected: {})\n",
        total.line(),
        total.unexpected(),
        if total.unexpected() == 0 {
            "exit 0"
        } else {
            "exit 1"
        }
    ));
    let notes: Vec<String> = m
        .all_codes_checks()
        .filter(|(_, k)| Verdict::of_check(k) != Verdict::Ok)
        .map(|(c, k)| {
            let v = Verdict::of_check(k);
            let known = k
                .known_failure
                .as_ref()
                .map(|r| format!(" [known: {r}]"))
                .unwrap_or_default();
            let message = if v == Verdict::UnexpectedPass {
                "passes, but is declared a known failure: remove the declaration or explain".into()
            } else {
                k.message.clone()
            };
            let code = c.code_prefix();
            format!(
                "  {} {code}{}/{}/{}: {message}{known}",
                v.label(),
                c.suite,
                c.case,
                k.id
            )
        })
        .collect();
    if !notes.is_empty() {
        out.push_str("\nnot OK:\n");
        out.push_str(&notes.join("\n"));
        out.push('\n');
    }
    out
}

/// JUnit XML: one test suite per case, one test case per check.
pub fn junit_xml(m: &Matrix) -> Result<String, String> {
    use quick_junit::{NonSuccessKind, Report, TestCase, TestCaseStatus, TestSuite};
    let mut report = Report::new("impact-verify");
    let other = m.codes.iter().flat_map(|code| code.cases.iter());
    for c in m.cases.iter().chain(other) {
        let prefix = c.code_prefix();
        let mut suite = TestSuite::new(format!("{prefix}{}/{}", c.suite, c.case));
        for k in &c.checks {
            let row = crate::definition::check_row::CheckRow::of(k);
            let detail = format!(
                "computed {} reference {} ({}) error {} tolerance {} ({})",
                row.computed,
                row.reference,
                k.reference_kind,
                row.error,
                k.tolerance,
                k.tolerance_reason
            );
            let status = match k.status {
                Status::Ok if k.known_failure.is_some() => {
                    let mut s = TestCaseStatus::non_success(NonSuccessKind::Failure);
                    s.set_message("XPASS: passes, but is declared a known failure");
                    s.set_description(detail.clone());
                    s
                }
                Status::Ok => TestCaseStatus::success(),
                Status::Fail => {
                    let mut s = TestCaseStatus::non_success(NonSuccessKind::Failure);
                    s.set_message(k.message.clone());
                    s.set_description(detail.clone());
                    s
                }
                Status::Skip | Status::NotExpressible => {
                    let mut s = TestCaseStatus::skipped();
                    s.set_message(format!("{}: {}", k.status.name(), k.message));
                    s
                }
            };
            let mut tc = TestCase::new(k.id.clone(), status);
            tc.set_classname(format!(
                "{}{}.{}",
                prefix.replace(':', "."),
                c.suite,
                c.case
            ));
            tc.set_system_out(detail);
            suite.add_test_case(tc);
        }
        report.add_test_suite(suite);
    }
    report.to_string().map_err(|e| e.to_string())
}

/// Writes results.json, junit.xml, matrix.txt and runs/<suite>/<case>/<scene>/ into `out`.
pub fn write_outputs(outcome: &Outcome, out: &Path) -> std::io::Result<()> {
    std::fs::create_dir_all(out)?;
    let json = serde_json::to_string_pretty(&outcome.matrix).map_err(std::io::Error::other)?;
    std::fs::write(out.join("results.json"), json + "\n")?;
    std::fs::write(
        out.join("junit.xml"),
        junit_xml(&outcome.matrix).map_err(std::io::Error::other)?,
    )?;
    std::fs::write(
        out.join("matrix.txt"),
        matrix_text(&outcome.matrix) + &summary_text(&outcome.matrix),
    )?;
    let runs = out.join("runs");
    if runs.exists() {
        std::fs::remove_dir_all(&runs)?;
    }
    write_runs(&outcome.data, &runs)?;
    let codes = out.join("codes");
    if codes.exists() {
        std::fs::remove_dir_all(&codes)?;
    }
    for (code, data) in &outcome.code_data {
        write_runs(data, &codes.join(code).join("runs"))?;
    }
    write_costs(outcome, &out.join(COSTS_FILE))
}

/// The machine-dependent file of each scene run's cost (results.json holds none).
pub const COSTS_FILE: &str = "costs.json";

/// `costs.json`: per code, case and scene, the run's wall time, elements, steps and ns per
/// element-step (every code's runs on this machine, for the report's cost table).
fn write_costs(outcome: &Outcome, path: &Path) -> std::io::Result<()> {
    let impact = ("impact".to_string(), &outcome.data);
    let all = std::iter::once(impact).chain(outcome.code_data.iter().map(|(c, d)| (c.clone(), d)));
    let mut rows = Vec::new();
    for (code, data) in all {
        for ((suite, case), results) in data {
            for (scene, r) in results {
                let Some(cost) = r.as_ref().ok().and_then(|d| d.cost) else {
                    continue;
                };
                rows.push(serde_json::json!({
                    "code": code, "suite": suite, "case": case, "scene": scene,
                    "wall_time_s": cost.wall_time_s, "n_elements": cost.n_elements,
                    "n_steps": cost.n_steps, "ns_per_element_step": cost.ns_per_element_step(),
                    "code_time_s": cost.code_time_s,
                }));
            }
        }
    }
    let text = serde_json::to_string_pretty(&rows).map_err(std::io::Error::other)?;
    std::fs::write(path, text + "\n")
}

type RunsByCase =
    BTreeMap<(String, String), BTreeMap<String, crate::definition::run_data::JobResult>>;

/// Each run's history.csv, summary.json and kept files under `runs/<suite>/<case>/<scene>/`.
fn write_runs(data: &RunsByCase, runs: &Path) -> std::io::Result<()> {
    for ((suite, case), results) in data {
        for (scene, r) in results {
            let Ok(d) = r else { continue };
            let dir = runs.join(suite).join(case).join(scene);
            std::fs::create_dir_all(&dir)?;
            for (name, h) in &d.histories {
                let file = if name.is_empty() {
                    "history.csv".to_string()
                } else {
                    format!("{name}.csv")
                };
                impact_solver::output::write_history(h, &dir.join(file))
                    .map_err(std::io::Error::other)?;
            }
            if let Some(s) = &d.summary {
                let text = serde_json::to_string_pretty(s).map_err(std::io::Error::other)?;
                std::fs::write(dir.join("summary.json"), text + "\n")?;
            }
            for (name, bytes) in &d.files {
                std::fs::write(dir.join(name), bytes)?;
            }
        }
    }
    Ok(())
}
