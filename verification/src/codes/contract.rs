//! The files of the adapter contract (`adapters/README.md`) read back into what a check
//! reads ([`RunData`]): `history.csv` (a `time_s` column, then any of `impact simulate`'s
//! columns), `summary.json` (an object of its keys; numbers under dotted names as the
//! solver's own summary gives them) and, when present, `adapter.json` (the code, its version,
//! the input it ran, times and the substitutions it made; its times go to the run's cost,
//! never to what results.json holds). A missing or malformed file is one message naming the
//! file, and for the history its line and column.

use std::collections::BTreeMap;
use std::path::Path;

use impact_solver::Scene;
use serde_json::Value;

use crate::definition::history_csv::read_history;
use crate::definition::run_data::RunData;

/// The run written in `dir` for `scene` (the derived impact quantities of a checked run,
/// e.g. `momentum_change_Ns`, are computed from the summary as for `impact`'s own runs).
pub fn read_run(dir: &Path, scene: Option<&Scene>) -> Result<RunData, String> {
    let history = read_history(&dir.join("history.csv"))?;
    let summary = read_json(&dir.join("summary.json"))?;
    if !summary.is_object() {
        return Err(format!(
            "{}: expected a JSON object of summary keys",
            dir.join("summary.json").display()
        ));
    }
    let mut metrics = BTreeMap::new();
    crate::definition::run_data::flatten("", &summary, &mut metrics);
    if let Some(scene) = scene {
        derived_metrics(scene, &mut metrics);
    }
    let (info, cost) = read_adapter_record(dir, &summary)?;
    Ok(RunData {
        metrics,
        histories: BTreeMap::from([(String::new(), history)]),
        info,
        summary: Some(summary),
        files: BTreeMap::new(),
        cost,
        scene_values: BTreeMap::new(),
    })
}

/// What `dir/adapter.json` records, when present: the code, its version, its substitutions and
/// the input it ran (`info`), and the run's cost (its counts from the file, else from
/// `summary`, where impact writes them).
pub fn read_adapter_record(
    dir: &Path,
    summary: &Value,
) -> Result<
    (
        BTreeMap<String, String>,
        Option<crate::definition::run_data::Cost>,
    ),
    String,
> {
    let mut info = BTreeMap::new();
    let mut cost = None;
    let adapter = dir.join("adapter.json");
    if adapter.exists() {
        let a = read_json(&adapter)?;
        // The counts from adapter.json, else from the summary (where impact writes them).
        let number = |k: &str| {
            a.get(k)
                .and_then(Value::as_f64)
                .or_else(|| summary.get(k).and_then(Value::as_f64))
        };
        if let (Some(wall_time_s), Some(n_elements), Some(n_steps)) = (
            number("wall_time_s"),
            number("n_elements"),
            number("n_steps"),
        ) {
            cost = Some(crate::definition::run_data::Cost {
                wall_time_s,
                n_elements,
                n_steps,
                code_time_s: None,
            });
        }
        for key in ["code", "version", "substitutions", "input"] {
            if let Some(v) = a.get(key) {
                info.insert(key.to_string(), text_of(v));
            }
        }
    }
    Ok((info, cost))
}

/// A JSON value as one line: strings bare, lists joined by "; ".
fn text_of(v: &Value) -> String {
    match v {
        Value::String(s) => s.clone(),
        Value::Array(items) => items.iter().map(text_of).collect::<Vec<_>>().join("; "),
        other => other.to_string(),
    }
}

/// The impactor's momentum change, final momentum, initial kinetic energy and the
/// discriminators of a rigid wall, from the summary's `impulse_Ns` and
/// `final_impactor_velocity_mps` and the scene's mass and speed (as `impact`'s runs give them).
fn derived_metrics(scene: &Scene, metrics: &mut BTreeMap<String, f64>) {
    let Some((mass, v0)) = scene.impactor_motion() else {
        return;
    };
    metrics.insert("initial_kinetic_J".into(), 0.5 * mass * v0 * v0);
    let Some(&vf) = metrics.get("final_impactor_velocity_mps") else {
        return;
    };
    metrics.insert("momentum_change_Ns".into(), mass * (v0 - vf));
    metrics.insert("final_momentum_kgmps".into(), mass * vf);
    if let Some(&impulse) = metrics.get("impulse_Ns") {
        for (k, v) in crate::definition::run_data::impact_discriminators(mass, v0, impulse, vf) {
            metrics.insert(k.into(), v);
        }
    }
}

fn read_json(path: &Path) -> Result<Value, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))
}
