//! What a job produced, the neutral data the builtins and scene jobs write and the checks
//! read: here, beside the checks, so that neither jobs nor builtins depends on the other for
//! it, and no check on the run.

use std::collections::BTreeMap;
use std::sync::Arc;

use impact_solver::History;
use serde_json::Value;

/// What a job produced, or why it did not.
pub type JobResult = Result<Arc<RunData>, String>;

/// What a job produced: named scalars, histories, and the modelling for the report.
#[derive(Debug, Clone, Default)]
pub struct RunData {
    pub metrics: BTreeMap<String, f64>,
    /// Histories by name; a scene run has one named "" (its history.csv).
    pub histories: BTreeMap<String, History>,
    /// Modelling description (mesh, element, dt, contact law, ...).
    pub info: BTreeMap<String, String>,
    /// summary.json without wall times (scene runs only).
    pub summary: Option<Value>,
    /// Files kept beside the history in the run's folder (another code's scene, its input
    /// and `adapter.json`), by name.
    pub files: BTreeMap<String, Vec<u8>>,
    /// What the run cost on this machine (scene runs; never in results.json, which must not
    /// depend on the machine: `costs.json` holds it).
    pub cost: Option<Cost>,
    /// Scalars of the scene as run that the matrix's invariants need (the end of its time,
    /// `summary_invariants::END_METRICS`, s): inputs, not results, so never compared, shown or
    /// written to results.json; carried by the shards.
    pub scene_values: BTreeMap<String, f64>,
}

/// A scene run's cost: wall-clock seconds over its elements and steps.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Cost {
    /// s, the whole run (an adapter's: writing the input, the code, reading the output).
    pub wall_time_s: f64,
    pub n_elements: f64,
    pub n_steps: f64,
    /// s, the code's own time within it, as its adapter reports it (`adapter.json`
    /// `wall_time_s`); the rest is the adapter's overhead. None for impact's runs.
    #[serde(default)]
    pub code_time_s: Option<f64>,
}

impl Cost {
    /// ns per element and step.
    pub fn ns_per_element_step(&self) -> f64 {
        1e9 * self.wall_time_s / (self.n_elements * self.n_steps)
    }
}

impl RunData {
    /// A builtin's result: its metrics and its one history (the case's plots read it as "").
    pub fn with_history(metrics: BTreeMap<String, f64>, history: History) -> RunData {
        RunData {
            metrics,
            histories: BTreeMap::from([(String::new(), history)]),
            ..Default::default()
        }
    }

    pub fn history(&self) -> Option<&History> {
        self.histories.get("")
    }
}

/// Quantities of an impact that a rigid wall (I = 2 m v0, v_f = -v0) gets wrong by all of
/// themselves (issue 10): the restitution deficit `(2 m v0 - I) / (m v0)` (0 for a rigid
/// wall, 1 for a fully plastic stop), and the energy the plate takes from the impactor,
/// `m (v0^2 - v_f^2) / 2` in J (0 for a rigid wall). `v_f` is signed, positive toward the plate.
pub fn impact_discriminators(
    mass: f64,
    v0: f64,
    impulse: f64,
    v_final: f64,
) -> [(&'static str, f64); 2] {
    [
        (
            "restitution_deficit",
            (2.0 * mass * v0 - impulse) / (mass * v0),
        ),
        (
            "plate_absorbed_energy_J",
            0.5 * mass * (v0 * v0 - v_final * v_final),
        ),
    ]
}

/// Numeric leaves of a JSON value under dotted keys.
pub fn flatten(prefix: &str, v: &Value, out: &mut BTreeMap<String, f64>) {
    match v {
        Value::Number(n) => {
            if let Some(x) = n.as_f64() {
                out.insert(prefix.to_string(), x);
            }
        }
        Value::Object(m) => {
            for (k, v) in m {
                let key = if prefix.is_empty() {
                    k.clone()
                } else {
                    format!("{prefix}.{k}")
                };
                flatten(&key, v, out);
            }
        }
        _ => {}
    }
}
