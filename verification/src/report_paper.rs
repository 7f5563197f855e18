//! The paper-specific parts of the V&V report: Tables 1 and 2 of Dokko & Kim (2004) next to
//! the computed values, and the paragraph on which reading of the paper the runs use. Each
//! part is filled from the case whose `report:` block declares it ([`ReportSpec`]), so the
//! report names no suite.

use std::path::Path;

use crate::case::{PaperTable, ReadingPart, ReportSpec};
use crate::check_row::num;

fn rel(c: Option<f64>, p: Option<f64>) -> String {
    match (c, p) {
        (Some(c), Some(p)) if p != 0.0 => format!("{:+.1} %", 100.0 * (c / p - 1.0)),
        _ => "-".into(),
    }
}

fn short(x: Option<f64>) -> String {
    x.map_or("-".into(), |v| format!("{v:.4}"))
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
    let rows1 = [
        ("impulse", "Impulse (N s)", "impulse_Ns", 1.0),
        (
            "max_contact_load",
            "Max. contact load (kN)",
            "peak_contact_force_N",
            1e-3,
        ),
        (
            "max_plate_displacement",
            "Max. displacement (mm)",
            "max_plate_displacement_m",
            1e3,
        ),
        (
            "contact_duration",
            "Contact duration (ms)",
            "contact_duration_s",
            1e3,
        ),
        (
            "impactor_final_velocity",
            "Final impactor velocity (m/s)",
            "final_impactor_velocity_mps",
            1.0,
        ),
        (
            "max_effective_stress_point_a",
            "Max. von Mises at A (MPa)",
            "max_von_mises_Pa.A",
            1e-6,
        ),
    ];
    for (q, label, key, scale) in rows1 {
        let mut sel = std::collections::BTreeMap::new();
        sel.insert("quantity".to_string(), q.to_string());
        let p = |col: &str| crate::check::table_value(&path1, &sel, col).ok();
        let ce = metric(&t1, "elastic", key).map(|v| v * scale);
        let cp = metric(&t1, "plastic", key).map(|v| v * scale);
        let (pe, pp) = (p("elastic"), p("elasto_plastic"));
        table1.push(serde_json::json!({
            "label": label, "pe": short(pe), "ce": short(ce), "de": rel(ce, pe),
            "pp": short(pp), "cp": short(cp), "dp": rel(cp, pp),
            "pr": short(p("ratio_ep_e")), "cr": short(cp.zip(ce).map(|(a, b)| a / b)),
        }));
    }
    let t2 = find(PaperTable::PaperTable2);
    let path2 = root.join("reference-data/paper/table2.csv");
    let mut table2 = Vec::new();
    for v in ["1.25", "2.5", "5", "7.5", "10", "12.5", "15"] {
        let mut sel = std::collections::BTreeMap::new();
        sel.insert("initial_velocity_mps".to_string(), v.to_string());
        let p = |col: &str| crate::check::table_value(&path2, &sel, col).ok();
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
        table2.push(serde_json::json!({
            "v": v, "pe": short(pe), "ce": short(ce), "de": rel(ce, pe),
            "pp": short(pp), "cp": short(cp), "dp": rel(cp, pp), "id": num(id),
        }));
    }
    (table1, table2)
}
