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
