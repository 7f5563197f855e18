//! The report's codes side by side (issue 38), when `impact verify --code NAME` or
//! `--results-from DIR` ran other codes: each code's counts, its checks by reference kind,
//! its cost per element-step on the same scenes as `impact` (`costs.json`), per case the
//! checks of every code in one table and each history of the case's plots drawn for every
//! code over the reference, rated against `impact`'s by ISO/TS 18571; then, per other code,
//! "NAME against the matrix": what it passes and fails, each check with its reference, in a
//! form a user of that code can cite.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

use impact_plots::line_plot::{column_axis, svg_plot, Axis, Series};
use serde_json::Value;

use crate::definition::history_csv::read_history;
use crate::review::iso18571::Grade;

/// The section's context: `present` (another code ran), its Markdown and HTML.
pub fn context(results: &Value, from: &Path, root: &Path, out: &Path) -> Value {
    let codes = results["codes"].as_array().cloned().unwrap_or_default();
    if codes.is_empty() {
        return serde_json::json!({"present": false, "md": "", "html": ""});
    }
    let text = markdown(results, &codes, (from, root), out);
    let e = crate::report::markdown::embed(
        &text,
        &crate::report::markdown::Embed {
            base: out,
            top_level: 3,
            anchor_prefix: "codes-",
            out,
            copy_to: "",
            section_title: None,
        },
    );
    serde_json::json!({"present": true, "md": e.md, "html": e.html})
}

fn markdown(results: &Value, codes: &[Value], (from, root): (&Path, &Path), out: &Path) -> String {
    let mut s = String::new();
    s.push_str(&glance(results, codes));
    s.push_str(&kinds(codes));
    s.push_str(&costs(from));
    let dirs = (from, root);
    let impact = cases_of(results);
    for code in codes {
        for case in code["cases"].as_array().into_iter().flatten() {
            s.push_str(&side_by_side(
                case,
                impact.get(&key(case)).copied(),
                codes,
                dirs,
                out,
            ));
        }
    }
    for code in codes {
        s.push_str(&against_the_matrix(code));
    }
    s
}

fn key(case: &Value) -> (String, String) {
    let f = |k: &str| case[k].as_str().unwrap_or("").to_string();
    (f("suite"), f("case"))
}

fn cases_of(results: &Value) -> BTreeMap<(String, String), &Value> {
    results["cases"]
        .as_array()
        .into_iter()
        .flatten()
        .map(|c| (key(c), c))
        .collect()
}

/// The verdict of a check row as the matrix prints it.
/// Why a check is not OK on a code: its known failure's reason (the code's `expected`), else
/// the check's message; empty when OK.
fn why(k: &Value) -> String {
    if label(k) == "OK" {
        return String::new();
    }
    match k["known_failure"].as_str() {
        Some(reason) => format!("known: {reason}"),
        None => k["message"].as_str().unwrap_or("").to_string(),
    }
    .replace('|', "\\|")
}

fn label(k: &Value) -> String {
    let row: Result<crate::definition::check::CheckResult, _> = serde_json::from_value(k.clone());
    row.map(|r| {
        crate::definition::verdict::Verdict::of_check(&r)
            .label()
            .to_string()
    })
    .unwrap_or_else(|_| "?".into())
}

fn num(v: &Value) -> String {
    v.as_f64().map_or("-".into(), |x| format!("{x:.4e}"))
}

fn glance(results: &Value, codes: &[Value]) -> String {
    let mut s = String::from(
        "The same cases' checks, references and tolerances evaluated on each code's results. \
         N/E: the code cannot express what the check measures (a feature it lacks, a kernel of \
         impact itself) or did not write it; never counted as OK or FAIL.\n\n\
         | code | what it is | cases | OK | FAIL* | FAIL | XPASS | SKIP | N/E |\n|---|---|---|---|---|---|---|---|---|\n",
    );
    let impact = results["cases"].as_array().cloned().unwrap_or_default();
    let rows = std::iter::once((
        "impact".to_string(),
        "this project's solver".to_string(),
        impact,
    ))
    .chain(codes.iter().map(|c| {
        let name = c["code"].as_str().unwrap_or("?").to_string();
        let what = c["description"].as_str().unwrap_or("").to_string();
        (
            name,
            what,
            c["cases"].as_array().cloned().unwrap_or_default(),
        )
    }));
    for (name, what, cases) in rows {
        let mut n: BTreeMap<String, usize> = BTreeMap::new();
        for k in cases
            .iter()
            .flat_map(|c| c["checks"].as_array().cloned().unwrap_or_default())
        {
            *n.entry(label(&k)).or_default() += 1;
        }
        let g = |l: &str| n.get(l).copied().unwrap_or(0);
        let _ = writeln!(
            s,
            "| {name} | {what} | {} | {} | {} | {} | {} | {} | {} |",
            cases.len(),
            g("OK"),
            g("FAIL*"),
            g("FAIL"),
            g("XPASS"),
            g("SKIP"),
            g("N/E")
        );
    }
    s + "\n"
}

fn kinds(codes: &[Value]) -> String {
    let mut s = String::from("### Checks by reference kind, per code\n\n");
    for code in codes {
        let name = code["code"].as_str().unwrap_or("?");
        let mut per: BTreeMap<String, BTreeMap<String, usize>> = BTreeMap::new();
        for c in code["cases"].as_array().into_iter().flatten() {
            for k in c["checks"].as_array().into_iter().flatten() {
                let kind = k["reference_kind"].as_str().unwrap_or("").to_string();
                *per.entry(kind).or_default().entry(label(k)).or_default() += 1;
            }
        }
        let _ = write!(
            s,
            "**{name}**\n\n| reference kind | OK | FAIL* | FAIL | N/E |\n|---|---|---|---|---|\n"
        );
        for (kind, n) in &per {
            let g = |l: &str| n.get(l).copied().unwrap_or(0);
            let _ = writeln!(
                s,
                "| {kind} | {} | {} | {} | {} |",
                g("OK"),
                g("FAIL*"),
                g("FAIL"),
                g("N/E")
            );
        }
        s.push('\n');
    }
    s
}

/// The cost table from `costs.json`: the scenes another code ran, with impact's cost on the
/// same scene where it ran it too.
fn costs(from: &Path) -> String {
    let rows: Vec<Value> = std::fs::read_to_string(from.join(crate::run::matrix_files::COSTS_FILE))
        .ok()
        .and_then(|t| serde_json::from_str(&t).ok())
        .unwrap_or_default();
    let at = |r: &Value| {
        ["suite", "case", "scene"]
            .map(|k| r[k].as_str().unwrap_or("").to_string())
            .join("/")
    };
    let impact: BTreeMap<String, &Value> = rows
        .iter()
        .filter(|r| r["code"] == "impact")
        .map(|r| (at(r), r))
        .collect();
    let mut s = String::from(
        "### Cost per element-step on the same scenes\n\nWall-clock time on this machine \
         (`costs.json`; another code's time is its whole adapter run: writing its input, the \
         code, reading its output) over elements times steps; each code's own element count and \
         step. The adapter's overhead is the whole run's time less the code's own (as its \
         adapter reports it).\n\n| scene | code | elements | steps | wall s | adapter overhead | ns per element-step | impact, ns per element-step |\n|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows.iter().filter(|r| r["code"] != "impact") {
        let mine = impact.get(&at(r)).map_or("-".into(), |i| {
            format!(
                "{:.1}",
                i["ns_per_element_step"].as_f64().unwrap_or(f64::NAN)
            )
        });
        let wall = r["wall_time_s"].as_f64().unwrap_or(f64::NAN);
        let overhead = r["code_time_s"]
            .as_f64()
            .map_or("-".into(), |c| format!("{:.1} %", 100.0 * (wall - c) / c));
        let _ = writeln!(
            s,
            "| {} | {} | {:.0} | {:.0} | {wall:.2} | {overhead} | {:.1} | {mine} |",
            at(r),
            r["code"].as_str().unwrap_or(""),
            r["n_elements"].as_f64().unwrap_or(f64::NAN),
            r["n_steps"].as_f64().unwrap_or(f64::NAN),
            r["ns_per_element_step"].as_f64().unwrap_or(f64::NAN)
        );
    }
    s + "\n"
}

/// One case: every code's rows of its checks in one table, then its plots for every code.
fn side_by_side(
    case: &Value,
    impact: Option<&Value>,
    codes: &[Value],
    dirs: (&Path, &Path),
    out: &Path,
) -> String {
    let code = case["code"].as_str().unwrap_or("?");
    let (suite, name) = key(case);
    let mut s = format!(
        "### {suite}/{name} on {code}: {}\n\n| check | reference | tolerance | impact | {code} | {code}: error | {code}: why |\n|---|---|---|---|---|---|---|\n",
        case["title"].as_str().unwrap_or("")
    );
    let theirs = |id: &str, c: &Value| -> Option<Value> {
        c["checks"]
            .as_array()?
            .iter()
            .find(|k| k["id"] == id)
            .cloned()
    };
    for k in case["checks"].as_array().into_iter().flatten() {
        let id = k["id"].as_str().unwrap_or("");
        let mine = impact
            .and_then(|c| theirs(id, c))
            .map_or("not run".into(), |m| {
                format!("{} {}", num(&m["computed"]), label(&m))
            });
        let _ = writeln!(
            s,
            "| {id} | {} ({}) | {} | {mine} | {} {} | {} | {} |",
            num(&k["reference"]),
            k["reference_kind"].as_str().unwrap_or(""),
            k["tolerance"].as_str().unwrap_or(""),
            num(&k["computed"]),
            label(k),
            num(&k["error"]),
            why(k),
        );
    }
    s.push('\n');
    s.push_str(&plots(case, codes, dirs, out));
    s
}

/// The case's `plots:` histories for impact and every other code over the reference files,
/// with the ISO/TS 18571 rating of each code's history against impact's.
fn plots(case: &Value, codes: &[Value], (from, root): (&Path, &Path), out: &Path) -> String {
    let (suite, name) = key(case);
    let mut s = String::new();
    let run_dirs: Vec<(String, std::path::PathBuf)> =
        std::iter::once(("impact".to_string(), from.join("runs")))
            .chain(codes.iter().filter_map(|c| {
                let n = c["code"].as_str()?.to_string();
                Some((n.clone(), from.join("codes").join(&n).join("runs")))
            }))
            .collect();
    for (i, p) in case["plots"].as_array().into_iter().flatten().enumerate() {
        let Some(column) = p["column"].as_str() else {
            continue;
        };
        let scale = p["scale"].as_f64().unwrap_or(1.0);
        for scene in p["scenes"]
            .as_array()
            .into_iter()
            .flatten()
            .filter_map(Value::as_str)
        {
            let mut series: Vec<Series> = Vec::new();
            let mut histories = Vec::new();
            for (code, dir) in &run_dirs {
                let file = dir.join(&suite).join(&name).join(scene).join("history.csv");
                let Ok(h) = read_history(&file) else { continue };
                let (Some(t), Some(v)) = (h.column("time_s"), h.column(column)) else {
                    continue;
                };
                series.push((
                    code.clone(),
                    t.iter().zip(&v).map(|(t, v)| (*t, v * scale)).collect(),
                    false,
                ));
                histories.push((code.clone(), t, v));
            }
            for r in p["references"]
                .as_array()
                .into_iter()
                .flatten()
                .filter_map(Value::as_str)
            {
                if let Ok((t, v)) =
                    crate::definition::csv_columns::read_csv_columns(&root.join(r), column)
                {
                    series.push((
                        format!("reference {r}"),
                        t.iter().zip(&v).map(|(t, v)| (*t, v * scale)).collect(),
                        true,
                    ));
                }
            }
            if histories.len() < 2 {
                continue;
            }
            let title = format!("{suite}/{name}, {scene}: {column}, every code");
            let (label, unit) = column_axis(column);
            let unit = p["unit"].as_str().unwrap_or(unit);
            let svg = svg_plot(
                &title,
                Axis::new("time", "s"),
                Axis::new(&label, unit),
                &series,
            );
            let file = format!(
                "plots/codes-{}-{}-{i}-{scene}.svg",
                crate::report::file_name::slug(&suite),
                crate::report::file_name::slug(&name)
            );
            if std::fs::write(out.join(&file), &svg).is_ok() {
                let _ = writeln!(s, "![{title}]({file})\n");
            }
            s.push_str(&ratings(column, &histories));
        }
    }
    s
}

/// ISO/TS 18571 of each other code's history against impact's (the first).
fn ratings(column: &str, histories: &[(String, Vec<f64>, Vec<f64>)]) -> String {
    let Some((_, ta, va)) = histories.iter().find(|h| h.0 == "impact") else {
        return String::new();
    };
    let mut s = format!("| {column} against impact's | ISO/TS 18571 | grade | corridor | phase | magnitude | slope |\n|---|---|---|---|---|---|---|\n");
    for (code, tb, vb) in histories.iter().filter(|h| h.0 != "impact") {
        match crate::review::diff::rating_in_common_window(ta, va, tb, vb) {
            Some(r) => {
                let _ = writeln!(
                    s,
                    "| {code} | {:.3} | {} | {:.3} | {:.3} | {:.3} | {:.3} |",
                    r.overall,
                    Grade::of(r.overall).name(),
                    r.corridor,
                    r.phase,
                    r.magnitude,
                    r.slope
                );
            }
            None => {
                let _ = writeln!(
                    s,
                    "| {code} | not rated (too few common samples or a flat history) | | | | | |"
                );
            }
        }
    }
    s + "\n"
}

/// "NAME against the matrix": each case the code ran, what it passes and fails, with the
/// reference and its source.
fn against_the_matrix(code: &Value) -> String {
    let name = code["code"].as_str().unwrap_or("?");
    let mut s = format!(
        "### {name} against the matrix\n\n{}: every check of the cases it ran, with the \
         reference it is held to and that reference's source; the tolerances are the matrix's, \
         each with its reason in the case's own section; why a check is not OK (the code's known \
         failure with its evidence, what it did not produce or cannot express).\n\n| case | check | status | computed | reference | source | why |\n|---|---|---|---|---|---|---|\n",
        code["description"].as_str().unwrap_or("")
    );
    for c in code["cases"].as_array().into_iter().flatten() {
        let (suite, case) = key(c);
        for k in c["checks"].as_array().into_iter().flatten() {
            let _ = writeln!(
                s,
                "| {suite}/{case} | {} | {} | {} | {} ({}) | {} | {} |",
                k["id"].as_str().unwrap_or(""),
                label(k),
                num(&k["computed"]),
                num(&k["reference"]),
                k["reference_kind"].as_str().unwrap_or(""),
                k["reference_source"]
                    .as_str()
                    .unwrap_or("")
                    .replace('|', "\\|"),
                why(k),
            );
        }
    }
    s + "\n"
}

#[cfg(test)]
mod tests {
    //! "NAME against the matrix" says why each check is not OK: a known failure of the code
    //! its reason from the code's `expected`, another status the check's message, an OK
    //! nothing.
    use super::*;
    use crate::definition::case::Compare;
    use crate::definition::check::Status;
    use crate::definition::check_row::tests::check;

    #[test]
    fn a_code_s_known_failure_shows_its_reason_and_an_n_e_its_message() {
        let mut not_expressible = check(Status::NotExpressible, false, Compare::Within);
        not_expressible.message = "not produced by fake: no metric".into();
        let rows = [
            check(Status::Fail, true, Compare::Within),
            not_expressible,
            check(Status::Ok, false, Compare::Within),
        ];
        let code = serde_json::json!({"code": "fake", "description": "d",
            "cases": [{"suite": "s", "case": "c", "checks": rows}]});
        let md = against_the_matrix(&code);
        let lines: Vec<&str> = md.lines().filter(|l| l.starts_with("| s/c |")).collect();
        assert!(
            lines[0].contains("| FAIL* |") && lines[0].ends_with("| known: why |"),
            "{md}"
        );
        assert!(
            lines[1].ends_with("| not produced by fake: no metric |"),
            "{md}"
        );
        assert!(
            lines[2].contains("| OK |") && lines[2].ends_with("|  |"),
            "{md}"
        );
    }
}
