//! The report's validation section (issue 40, section 4): every check against a measurement
//! (reference kind `experiment`) with its V&V 20 row (`crate::definition::validation`), the
//! area metric per case and quantity, and a plain statement of what the model predicts within
//! its uncertainty and what it misses, with the reasons the cases give.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

use serde_json::Value;

/// One comparison, read back from results.json.
struct Comparison {
    check: String,
    quantity: String,
    v: Value,
    known: Option<String>,
}

fn f(v: &Value, key: &str) -> f64 {
    v[key].as_f64().unwrap_or(f64::NAN)
}

/// Whether the comparison ran and `|E| <= k u_val`.
fn covered(r: &Comparison) -> bool {
    !r.v.is_null() && f(&r.v, "comparison_error").abs() <= f(&r.v, "k") * f(&r.v, "u_val")
}

/// The quantity a check compares: its id without the shot (`final-length-wg73-cu-6` ->
/// `final-length`), so that rows group by what was measured.
fn quantity(check: &str, shot_free: &[&str]) -> String {
    shot_free
        .iter()
        .find(|q| check.starts_with(*q))
        .map_or_else(|| check.to_string(), |q| q.to_string())
}

fn comparisons(case: &Value) -> Vec<Comparison> {
    const QUANTITIES: [&str; 4] = [
        "final-length",
        "foot-radius",
        "undeformed-length",
        "profile",
    ];
    case["checks"]
        .as_array()
        .into_iter()
        .flatten()
        .filter(|k| k["reference_kind"] == "experiment")
        .map(|k| Comparison {
            check: k["id"].as_str().unwrap_or("").to_string(),
            quantity: quantity(k["id"].as_str().unwrap_or(""), &QUANTITIES),
            v: k["vv20_budget"].clone(),
            known: k["known_failure"].as_str().map(str::to_string),
        })
        .collect()
}

/// The rows of one case: D, S, E (also over D), the three uncertainties, u_val, |E| / u_val,
/// whether 2 u_val covers E, the area metric.
fn table(rows: &[Comparison]) -> String {
    let mut s = String::from(
        "| comparison | measured D | predicted S | E = S - D | E / D | u_num | u_input | u_D | u_val | \\|E\\| / u_val | within k u_val | area metric |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let v = &r.v;
        if v.is_null() {
            let _ = writeln!(
                s,
                "| {} | - | - | - | - | - | - | - | - | - | the run failed | - |",
                r.check
            );
            continue;
        }
        let (e, d, u) = (f(v, "comparison_error"), f(v, "measurement"), f(v, "u_val"));
        let _ = writeln!(
            s,
            "| {} | {:.4e} | {:.4e} | {:+.3e} | {} | {:.2e} | {:.2e} | {:.2e} | {:.2e} | {:.2} | {} | {:.2e} |",
            r.check,
            d,
            f(v, "simulation"),
            e,
            percent_of(e, d),
            f(v, "u_num"),
            f(v, "u_input"),
            f(v, "u_d"),
            u,
            e.abs() / u,
            if covered(r) { "yes" } else { "**no**" },
            f(v, "area"),
        );
    }
    s
}

/// `e / d` in per cent, "-" when `d` is 0 (a gap measured against none: a profile).
fn percent_of(e: f64, d: f64) -> String {
    if d == 0.0 {
        "-".to_string()
    } else {
        format!("{:+.2} %", 100.0 * e / d)
    }
}

/// Per quantity: the comparisons covered, the mean |E| / D and the mean area metric over D
/// (the area metric pooled over the shots, each relative to its measurement; "-" for a
/// quantity measured against 0, a profile's gap).
fn summary(rows: &[&Comparison]) -> String {
    let mut per: BTreeMap<&str, Vec<&Comparison>> = BTreeMap::new();
    for r in rows.iter().copied().filter(|r| !r.v.is_null()) {
        per.entry(r.quantity.as_str()).or_default().push(r);
    }
    let mut s = String::from(
        "\n| quantity | comparisons | within 2 u_val | mean \\|E\\| / D | mean area metric / D |\n|---|---|---|---|---|\n",
    );
    for (q, rs) in &per {
        let n = rs.len() as f64;
        let covered = rs.iter().filter(|r| covered(r)).count();
        let rel = |key: &str| {
            let sum: f64 = rs
                .iter()
                .map(|r| (f(&r.v, key) / f(&r.v, "measurement")).abs())
                .sum();
            format!("{:.2} %", 100.0 * sum / n)
        };
        let against_zero = rs.iter().any(|r| f(&r.v, "measurement") == 0.0);
        let (mean_e, mean_area) = if against_zero {
            ("-".to_string(), "-".to_string())
        } else {
            (rel("comparison_error"), rel("area"))
        };
        let _ = writeln!(
            s,
            "| {q} | {} | {covered} | {} | {} |",
            rs.len(),
            mean_e,
            mean_area,
        );
    }
    s
}

/// Every case's comparisons pooled per measurement table (`measurement_file`: one table per
/// material), each with the count of its rows compared and left out and the quantity table of
/// [`summary`]: a material's shots over its cases read as one set. Empty when no row names its
/// table.
fn by_material(all: &[Comparison], left: &[&Value]) -> String {
    let mut per: BTreeMap<&str, (Vec<&Comparison>, usize)> = BTreeMap::new();
    for r in all {
        if let Some(file) = r.v["measurement_file"].as_str() {
            per.entry(file).or_default().0.push(r);
        }
    }
    for r in left {
        if let Some(file) = r["file"].as_str() {
            per.entry(file).or_default().1 += 1;
        }
    }
    let mut s = String::new();
    for (file, (rows, left_out)) in &per {
        let shots: std::collections::BTreeSet<&str> = rows
            .iter()
            .filter_map(|r| r.v["measurement_row"].as_str())
            .collect();
        let _ =
            write!(
            s,
            "\n**`{file}`**, every case that reads it: rows compared {}, not compared {left_out} \
             (each case lists its own with why; a comparison whose run failed is counted \
             under its case only).\n{}",
            shots.len(),
            if rows.is_empty() { String::new() } else { summary(rows) }
        );
    }
    if s.is_empty() {
        return s;
    }
    format!("## Pooled per material\n{s}\n")
}

/// The columns of a row left out that the report shows (header, label), where its table has them.
const SHOWN: [(&str, &str); 6] = [
    ("source", "source"),
    ("initial_temperature_K", "T0 (K)"),
    ("impact_speed_m_s", "speed (m/s)"),
    ("initial_length_m", "L0 (m)"),
    ("final_length_m", "measured Lf (m)"),
    ("foot_diameter_m", "measured Dm (m)"),
];

/// The case's rows of measurement tables it does not compare.
fn left_out_of(case: &Value) -> Vec<&Value> {
    case["not_compared"]
        .as_array()
        .into_iter()
        .flatten()
        .collect()
}

/// The rows left out, a table per reason (in the order the case declares them).
fn left_out(rows: &[&Value]) -> String {
    let mut groups: Vec<(&str, Vec<&Value>)> = Vec::new();
    for r in rows {
        let why = r["why"].as_str().unwrap_or("");
        match groups.iter_mut().find(|(w, _)| *w == why) {
            Some((_, g)) => g.push(r),
            None => groups.push((why, vec![r])),
        }
    }
    let mut s = String::new();
    for (why, group) in groups {
        let shown: Vec<(&str, &str)> = SHOWN
            .into_iter()
            .filter(|(h, _)| {
                group
                    .iter()
                    .any(|r| r["cells"][h].as_str().is_some_and(|c| !c.is_empty()))
            })
            .collect();
        let key = group[0]["key"].as_str().unwrap_or("row");
        let _ = writeln!(
            s,
            "\n**Not compared** ({} rows of `{}`): {why}\n",
            group.len(),
            group[0]["file"].as_str().unwrap_or("")
        );
        let labels: Vec<&str> = shown.iter().map(|(_, l)| *l).collect();
        let _ = writeln!(s, "| {key} | {} |", labels.join(" | "));
        let _ = writeln!(s, "|---|{}", "---|".repeat(shown.len()));
        for r in group {
            let cells: Vec<&str> = shown
                .iter()
                .map(|(h, _)| {
                    r["cells"][h]
                        .as_str()
                        .filter(|c| !c.is_empty())
                        .unwrap_or("-")
                })
                .collect();
            let _ = writeln!(
                s,
                "| {} | {} |",
                r["row"].as_str().unwrap_or(""),
                cells.join(" | ")
            );
        }
    }
    s
}

/// What the model predicts within its uncertainty and what it misses, with the cases' reasons.
fn statement(rows: &[Comparison]) -> String {
    let within: Vec<&str> = rows
        .iter()
        .filter(|r| covered(r))
        .map(|r| r.check.as_str())
        .collect();
    let mut s = String::new();
    let _ = writeln!(
        s,
        "\n**Within the validation uncertainty** ({} of {}): {}.",
        within.len(),
        rows.len(),
        if within.is_empty() {
            "none".to_string()
        } else {
            within.join(", ")
        }
    );
    let missed: Vec<&Comparison> = rows.iter().filter(|r| !covered(r)).collect();
    if missed.is_empty() {
        s.push_str("\n**Missed:** none.\n");
    } else {
        s.push_str("\n**Missed** (a model error the uncertainties do not cover):\n\n");
        for r in missed {
            let why = r
                .known
                .as_deref()
                .unwrap_or("no reason declared: an unexpected failure");
            let _ = writeln!(s, "- `{}`: {why}", r.check);
        }
    }
    s
}

/// Every case's comparisons, in the cases' order.
fn every_comparison(results: &Value) -> Vec<Comparison> {
    results["cases"]
        .as_array()
        .into_iter()
        .flatten()
        .flat_map(comparisons)
        .collect()
}

/// The section as Markdown (headings from level 3); `None` when no check is against a
/// measurement.
pub fn markdown(results: &Value) -> Option<String> {
    let all = every_comparison(results);
    let cases = results["cases"].as_array().into_iter().flatten();
    let left: Vec<&Value> = cases.clone().flat_map(left_out_of).collect();
    let mut s = by_material(&all, &left);
    for c in cases {
        let rows = comparisons(c);
        let left = left_out_of(c);
        if rows.is_empty() && left.is_empty() {
            continue;
        }
        let _ = writeln!(
            s,
            "## {}/{}\n\n{}\n\n{}\n",
            c["suite"].as_str().unwrap_or(""),
            c["case"].as_str().unwrap_or(""),
            c["title"].as_str().unwrap_or(""),
            c["problem"].as_str().unwrap_or("").trim()
        );
        if !rows.is_empty() {
            s.push_str(&table(&rows));
            s.push_str(&summary(&rows.iter().collect::<Vec<_>>()));
            s.push_str(&statement(&rows));
        }
        s.push_str(&left_out(&left));
    }
    (!s.is_empty()).then(|| {
        format!(
            "Comparisons with **measurements** of physical tests (reference kind `experiment`), by \
             ASME V&V 20-2009: the comparison error `E = S - D`, the validation uncertainty \
             `u_val = sqrt(u_num^2 + u_input^2 + u_D^2)` (standard uncertainties: `u_num` by \
             Richardson at first order from a mesh 2x coarser, `u_input` by the \
             sensitivity-coefficient method with each input moved by its standard uncertainty, \
             `u_D` the measurement's), and the verdict `|E| <= 2 u_val`. The area metric \
             (Ferson, Oberkampf and Ginzburg 2008) is the area between the cumulative \
             distributions of the prediction `N(S, u_num^2 + u_input^2)` and the measurement \
             `N(D, u_D^2)`, in the quantity's unit. The models' constants were fitted to other \
             tests, never to these: this is validation, not calibration. The rows of a measurement \
             table that a case does not compare are listed under it with why (a run the \
             solver cannot finish, no constants fitted to other tests, a comparison that \
             could not fail).\n\n{s}"
        )
    })
}

/// The section for the report templates: `{present, html, md}`.
pub fn context(results: &Value, out: &Path) -> Value {
    let Some(text) = markdown(results) else {
        return serde_json::json!({"present": false, "md": "", "html": "", "count": 0, "covered": 0});
    };
    let all = every_comparison(results);
    let covered = all.iter().filter(|r| covered(r)).count();
    let e = crate::report::markdown::embed(
        &text,
        &crate::report::markdown::Embed {
            base: out,
            top_level: 3,
            anchor_prefix: "validation-",
            out,
            copy_to: "",
            section_title: None,
        },
    );
    serde_json::json!({"present": true, "md": e.md, "html": e.html, "count": all.len(), "covered": covered})
}

#[cfg(test)]
mod tests {
    //! The validation section recomputes its verdicts and summaries from the rows it is given.
    use super::*;

    fn case(rows: &[(&str, f64, f64, f64, Option<&str>)]) -> Value {
        let checks: Vec<Value> = rows
            .iter()
            .map(|(id, s, d, u, known)| {
                serde_json::json!({"id": id, "reference_kind": "experiment", "known_failure": known,
                    "vv20_budget": {"simulation": s, "measurement": d, "comparison_error": s - d,
                        "u_num": 0.0, "u_input": 0.0, "u_d": u, "u_val": u, "k": 2.0,
                        "area": (s - d).abs()}})
            })
            .collect();
        serde_json::json!({"cases": [{"suite": "s", "case": "c", "title": "t",
            "problem": "p", "checks": checks}]})
    }

    #[test]
    fn rows_within_two_u_val_are_covered_and_the_others_missed_with_their_reason() {
        let r = case(&[
            ("final-length-a", 10.1, 10.0, 0.1, None),
            ("final-length-b", 10.5, 10.0, 0.1, Some("too long")),
        ]);
        let md = markdown(&r).unwrap();
        assert!(
            md.contains("**Within the validation uncertainty** (1 of 2): final-length-a."),
            "{md}"
        );
        assert!(md.contains("- `final-length-b`: too long"), "{md}");
        // mean |E| / D over the two shots: (1 % + 5 %) / 2
        assert!(md.contains("| final-length | 2 | 1 | 3.00 % |"), "{md}");
    }

    #[test]
    fn comparisons_of_one_table_pool_over_their_cases() {
        let row = |id: &str, s: f64, d: f64, file: Option<&str>| {
            serde_json::json!({"id": id, "reference_kind": "experiment",
                "vv20_budget": {"simulation": s, "measurement": d, "comparison_error": s - d,
                    "u_num": 0.0, "u_input": 0.0, "u_d": 0.1, "u_val": 0.1, "k": 2.0,
                    "area": (s - d).abs(), "measurement_file": file}})
        };
        let case = |name: &str, checks: Vec<Value>| serde_json::json!({"suite": "s", "case": name, "title": "t", "problem": "p", "checks": checks});
        let r = serde_json::json!({"cases": [
            case("a", vec![row("final-length-1", 10.1, 10.0, Some("cu.csv"))]),
            case("b", vec![row("final-length-2", 10.5, 10.0, Some("cu.csv")),
                           row("final-length-3", 10.2, 10.0, Some("al.csv"))]),
            case("c", vec![row("final-length-4", 10.0, 10.0, None)]),
        ]});
        let md = markdown(&r).unwrap();
        let pooled = &md[md.find("## Pooled per material").unwrap()..md.find("## s/a").unwrap()];
        // cu.csv over cases a and b: 1 % and 5 %, one of two within 2 u_val
        assert!(pooled.contains("**`cu.csv`**"), "{pooled}");
        assert!(
            pooled.contains("| final-length | 2 | 1 | 3.00 % |"),
            "{pooled}"
        );
        assert!(
            pooled.contains("| final-length | 1 | 1 | 2.00 % |"),
            "{pooled}"
        );
        assert!(
            !pooled.contains("| final-length | 1 | 1 | 0.00 % |"),
            "a row without a table pools nowhere: {pooled}"
        );
    }

    #[test]
    fn a_profile_s_gap_measured_against_zero_has_no_relative_error() {
        // The gap of an outline (D = 0, S = 0.1 mm, u_val 0.15 mm): covered, no E / D.
        let r = case(&[("profile-a", 1.0e-4, 0.0, 1.5e-4, None)]);
        let md = markdown(&r).unwrap();
        assert!(
            md.contains("| profile-a | 0.0000e0 | 1.0000e-4 | +1.000e-4 | - |"),
            "{md}"
        );
        assert!(md.contains("| profile | 1 | 1 | - | - |"), "{md}");
        assert!(!md.contains("inf"), "{md}");
    }

    #[test]
    fn rows_left_out_are_counted_per_table_and_listed_with_why() {
        let left = |row: &str, file: &str, why: &str| {
            serde_json::json!({"file": file, "key": "shot_id", "row": row, "why": why,
                "cells": {"shot_id": row, "impact_speed_m_s": "478", "final_length_m": "0.01",
                    "foot_diameter_m": "", "unshown": "x"}})
        };
        let mut r = case(&[("final-length-a", 10.1, 10.0, 0.1, None)]);
        r["cases"][0]["checks"][0]["vv20_budget"]["measurement_file"] = "al.csv".into();
        r["cases"][0]["checks"][0]["vv20_budget"]["measurement_row"] = "a".into();
        r["cases"][0]["not_compared"] = serde_json::json!([
            left("b", "al.csv", "inverts"),
            left("c", "al.csv", "inverts"),
            left("d", "etp.csv", "no constants"),
        ]);
        let md = markdown(&r).unwrap();
        assert!(
            md.contains("**`al.csv`**, every case that reads it: rows compared 1, not compared 2"),
            "{md}"
        );
        assert!(
            md.contains("**`etp.csv`**, every case that reads it: rows compared 0, not compared 1"),
            "{md}"
        );
        assert!(
            md.contains("**Not compared** (2 rows of `al.csv`): inverts"),
            "{md}"
        );
        assert!(
            md.contains("| shot_id | speed (m/s) | measured Lf (m) |"),
            "{md}"
        );
        assert!(md.contains("| b | 478 | 0.01 |"), "{md}");
        assert!(
            md.contains("**Not compared** (1 rows of `etp.csv`): no constants"),
            "{md}"
        );
        assert!(!md.contains("unshown"), "{md}");
        // A case with rows left out and no comparison still has its section.
        let only = serde_json::json!({"cases": [{"suite": "s", "case": "e", "title": "t",
            "problem": "p", "checks": [], "not_compared": [left("d", "etp.csv", "no constants")]}]});
        let md = markdown(&only).unwrap();
        assert!(
            md.contains("## s/e") && md.contains("| d | 478 | 0.01 |"),
            "{md}"
        );
    }

    #[test]
    fn no_comparison_with_a_measurement_gives_no_section() {
        let r =
            serde_json::json!({"cases": [{"checks": [{"id": "x", "reference_kind": "paper"}]}]});
        assert!(markdown(&r).is_none());
    }
}
