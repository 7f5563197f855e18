//! The paper-specific parts of the V&V report: Tables 1 and 2 of Dokko & Kim (2004) next to
//! the computed values, and the paragraph on which reading of the paper the runs use. Each
//! part is filled from the case whose `report:` block declares it ([`ReportSpec`]), so the
//! report names no suite.

use std::path::Path;

use crate::definition::case::{PaperTable, ReadingPart, ReportSpec};
use crate::definition::check_row::num;

fn rel(c: Option<f64>, p: Option<f64>) -> String {
    match (c, p) {
        (Some(c), Some(p)) if p != 0.0 => format!("{:+.1} %", 100.0 * (c / p - 1.0)),
        _ => "-".into(),
    }
}

fn short(x: Option<f64>) -> String {
    x.map_or("-".into(), |v| format!("{v:.4}"))
}

/// Decimals of a number as the paper printed it ("2394" 0, "-1.903" 3).
fn decimals(printed: &str) -> usize {
    printed.split_once('.').map_or(0, |(_, d)| d.len())
}

/// A computed value with as many decimals as the paper's printed value beside it has, and one
/// more (the paper's last digit is rounded; ours shows where it would round).
fn like_paper(x: Option<f64>, printed: Option<&str>) -> String {
    match (x, printed) {
        (Some(v), Some(p)) => format!("{v:.*}", decimals(p) + 1),
        _ => short(x),
    }
}

/// The check of Table 1's case with this id, as the report's cells show it: its tolerance
/// and verdict (OK, FAIL, FAIL* for a declared known failure, XPASS), or that none checks
/// this cell.
fn check_cell(case: &Option<serde_json::Value>, id: Option<&str>) -> serde_json::Value {
    let found = id.and_then(|id| {
        case.as_ref()?["checks"]
            .as_array()?
            .iter()
            .find(|k| k["id"] == id)
            .and_then(|k| {
                serde_json::from_value::<crate::definition::check::CheckResult>(k.clone()).ok()
            })
    });
    match found {
        Some(k) => {
            let v = crate::definition::verdict::Verdict::of_check(&k).label();
            serde_json::json!({"tol": format!("tolerance {}", k.tolerance), "status": v,
                "class": v.replace('*', "K"), "known": k.known_failure.is_some()})
        }
        None => {
            serde_json::json!({"tol": "no check of its own", "status": "", "class": "", "known": false})
        }
    }
}

/// A case's `report:` block as results.json holds it (None when it declares none).
pub fn declared(case: &serde_json::Value) -> Option<ReportSpec> {
    serde_json::from_value(case.get("report")?.clone()).ok()
}

/// The first case in results.json whose `report:` block satisfies `wants`, with the block.
fn declaring(
    results: &serde_json::Value,
    wants: impl Fn(&ReportSpec) -> bool,
) -> Option<(&serde_json::Value, ReportSpec)> {
    results["cases"]
        .as_array()
        .into_iter()
        .flatten()
        .find_map(|c| declared(c).filter(&wants).map(|r| (c, r)))
}

/// Which reading of the paper the suites run and what the literal reading costs, from this
/// run's own results: the energy balance of the default and literal pairings (from the case
/// declaring `reading: [energy-balance]`) and the error that stops the literal
/// elasto-plastic run (from the case declaring `reading: [literal-error]`).
pub fn reading_context(results: &serde_json::Value) -> serde_json::Value {
    let case =
        |part: ReadingPart| declaring(results, |r| r.reading.contains(&part)).map(|(c, _)| c);
    let energy = case(ReadingPart::EnergyBalance);
    let balance =
        |scene: &str| energy.and_then(|c| c["metrics"][scene]["max_energy_balance_error"].as_f64());
    let literal = case(ReadingPart::LiteralError);
    let literal_error = literal
        .and_then(|c| c["modelling"]["literal-plastic"]["expected error"].as_str())
        .filter(|m| !m.is_empty());
    let not_stopped = format!(
        "the run did not stop (see {}/literal-reading-plastic-breaks)",
        literal
            .and_then(|c| c["suite"].as_str())
            .unwrap_or("its case")
    );
    serde_json::json!({
        "present": balance("literal-pairing").is_some() || literal_error.is_some(),
        "default_elastic": num(balance("elastic")),
        "default_plastic": num(balance("plastic")),
        "literal_elastic": num(balance("literal-pairing")),
        "literal_plastic_error": literal_error.map_or(not_stopped, str::to_string),
    })
}

/// Table 1's rows: (paper quantity, label, metric, scale to the paper's unit, the ids of the
/// checks of the cells: elastic, elasto-plastic, ratio).
type Table1Row = (
    &'static str,
    &'static str,
    &'static str,
    f64,
    [Option<&'static str>; 3],
);
const TABLE1_ROWS: [Table1Row; 6] = [
    (
        "impulse",
        "Impulse (N s)",
        "impulse_Ns",
        1.0,
        [None, Some("impulse-plastic"), Some("ratio-impulse")],
    ),
    (
        "max_contact_load",
        "Max. contact load (kN)",
        "peak_contact_force_N",
        1e-3,
        [
            Some("peak-force-elastic"),
            Some("peak-force-plastic"),
            Some("ratio-peak-force"),
        ],
    ),
    (
        "max_plate_displacement",
        "Max. displacement (mm)",
        "max_plate_displacement_m",
        1e3,
        [
            Some("max-displacement-elastic"),
            Some("max-displacement-plastic"),
            Some("ratio-displacement"),
        ],
    ),
    (
        "contact_duration",
        "Contact duration (ms)",
        "contact_duration_s",
        1e3,
        [
            Some("duration-elastic"),
            Some("duration-plastic"),
            Some("ratio-duration"),
        ],
    ),
    (
        "impactor_final_velocity",
        "Final impactor velocity (m/s)",
        "final_impactor_velocity_mps",
        1.0,
        [
            None,
            Some("final-velocity-plastic"),
            Some("ratio-final-velocity"),
        ],
    ),
    (
        "max_effective_stress_point_a",
        "Max. von Mises at A (MPa)",
        "max_von_mises_Pa.A",
        1e-6,
        [
            Some("stress-A-elastic"),
            Some("stress-A-plastic"),
            Some("ratio-stress-A"),
        ],
    ),
];

/// Table 1 and Table 2 rows: the paper's printed values next to the computed ones.
pub fn paper_tables(
    results: &serde_json::Value,
    root: &Path,
) -> (Vec<serde_json::Value>, Vec<serde_json::Value>) {
    let find =
        |table: PaperTable| declaring(results, |r| r.table == Some(table)).map(|(c, _)| c.clone());
    let metric = |c: &Option<serde_json::Value>, scene: &str, key: &str| {
        c.as_ref().and_then(|c| c["metrics"][scene][key].as_f64())
    };
    let t1 = find(PaperTable::PaperTable1);
    let path1 = root.join("reference-data/paper/table1.csv");
    let mut table1 = Vec::new();
    for (q, label, key, scale, ids) in TABLE1_ROWS {
        let mut sel = std::collections::BTreeMap::new();
        sel.insert("quantity".to_string(), q.to_string());
        let printed = |col: &str| crate::definition::check::table_text(&path1, &sel, col).ok();
        let (pe, pp, pr) = (
            printed("elastic"),
            printed("elasto_plastic"),
            printed("ratio_ep_e"),
        );
        let value = |p: &Option<String>| p.as_deref().and_then(|p| p.parse::<f64>().ok());
        let ce = metric(&t1, "elastic", key).map(|v| v * scale);
        let cp = metric(&t1, "plastic", key).map(|v| v * scale);
        let cr = cp.zip(ce).map(|(a, b)| a / b);
        let dash = || "-".to_string();
        table1.push(serde_json::json!({
            "label": label,
            "pe": pe.clone().unwrap_or_else(dash), "ce": like_paper(ce, pe.as_deref()), "de": rel(ce, value(&pe)),
            "pp": pp.clone().unwrap_or_else(dash), "cp": like_paper(cp, pp.as_deref()), "dp": rel(cp, value(&pp)),
            "pr": pr.clone().unwrap_or_else(dash), "cr": like_paper(cr, pr.as_deref()), "dr": rel(cr, value(&pr)),
            "ke": check_cell(&t1, ids[0]), "kp": check_cell(&t1, ids[1]), "kr": check_cell(&t1, ids[2]),
        }));
    }
    let t2 = find(PaperTable::PaperTable2);
    let path2 = root.join("reference-data/paper/table2.csv");
    let mut table2 = Vec::new();
    for v in ["1.25", "2.5", "5", "7.5", "10", "12.5", "15"] {
        let mut sel = std::collections::BTreeMap::new();
        sel.insert("initial_velocity_mps".to_string(), v.to_string());
        let p = |col: &str| crate::definition::check::table_value(&path2, &sel, col).ok();
        let printed = |col: &str| crate::definition::check::table_text(&path2, &sel, col).ok();
        let ce = metric(&t2, &format!("elastic-v{v}"), "impulse_Ns");
        let cp = metric(&t2, &format!("plastic-v{v}"), "impulse_Ns");
        let id = [format!("elastic-v{v}"), format!("plastic-v{v}")]
            .iter()
            .filter_map(|s| {
                let i = metric(&t2, s, "impulse_Ns")?;
                let m = metric(&t2, s, "momentum_change_Ns")?;
                Some((i - m).abs() / i)
            })
            .fold(None, |a: Option<f64>, b| Some(a.map_or(b, |a| a.max(b))));
        let (pe, pp) = (p("elastic_impulse_Ns"), p("ep_impulse_Ns"));
        let (tpe, tpp) = (printed("elastic_impulse_Ns"), printed("ep_impulse_Ns"));
        table2.push(serde_json::json!({
            "v": v, "pe": tpe.clone().unwrap_or_else(|| "-".into()), "ce": like_paper(ce, tpe.as_deref()), "de": rel(ce, pe),
            "pp": tpp.clone().unwrap_or_else(|| "-".into()), "cp": like_paper(cp, tpp.as_deref()), "dp": rel(cp, pp), "id": num(id),
        }));
    }
    (table1, table2)
}

#[cfg(test)]
mod tests {
    //! Table 1's cells: the paper's value as printed (the old cells printed "2394.0000" for
    //! the paper's 2394), ours to one more decimal, and each cell's check with its tolerance
    //! and verdict (a declared known failure FAIL*).
    use super::*;

    #[test]
    fn computed_values_follow_the_papers_digits() {
        assert_eq!(decimals("2394"), 0);
        assert_eq!(decimals("-1.903"), 3);
        assert_eq!(like_paper(Some(2220.2266), Some("2394")), "2220.2");
        assert_eq!(like_paper(Some(-1.82543), Some("-1.903")), "-1.8254");
        assert_eq!(like_paper(Some(0.5), None), "0.5000");
    }

    #[test]
    fn cells_show_their_checks_tolerance_and_verdict() {
        let k = |id: &str, status: &str, known: bool| {
            serde_json::json!({"id": id, "title": "t", "status": status, "computed": 1.0,
                "reference": 1.0, "error": 0.0, "error_kind": "relative", "compare": "within",
                "tolerance": "rel 1.0e-1", "tolerance_reason": "r", "reference_kind": "calibration",
                "reference_source": "s", "message": "",
                "known_failure": if known { serde_json::json!("why") } else { serde_json::json!(null) }})
        };
        let case = Some(
            serde_json::json!({"checks": [k("peak-force-plastic", "FAIL", true),
            k("peak-force-elastic", "OK", false)]}),
        );
        let star = check_cell(&case, Some("peak-force-plastic"));
        assert_eq!(star["status"], "FAIL*");
        assert_eq!(star["class"], "FAILK");
        assert_eq!(star["tol"], "tolerance rel 1.0e-1");
        assert_eq!(
            check_cell(&case, Some("peak-force-elastic"))["status"],
            "OK"
        );
        assert_eq!(check_cell(&case, None)["tol"], "no check of its own");
    }
}
