//! The codes a verify run evaluates its checks on (issue 38): `impact`, this project's
//! solver, run in-process; another code through its adapter (`adapters/<name>/`, the
//! contract in `adapters/README.md`); or results computed elsewhere and read from a folder
//! (`--results-from DIR`). Each gives, per scene, what `impact simulate` gives: a history
//! and a summary, in the same names and units.

pub mod adapter;
pub mod contract;
pub mod problem;
pub mod process;
pub mod results_from;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

pub use adapter::Adapter;

/// The prefix of a run's error when the code cannot express the scene: its checks show
/// *not expressible* (N/E), never FAIL or OK.
pub const NOT_EXPRESSIBLE: &str = "not expressible: ";
/// The prefix of a run's error when results read from a folder have none for the scene.
pub const NOT_PRODUCED: &str = "not produced: ";

/// Whether a run's error says the code cannot express the scene or did not produce it.
pub fn is_not_expressible(error: &str) -> bool {
    error.starts_with(NOT_EXPRESSIBLE) || error.starts_with(NOT_PRODUCED)
}

/// A code the matrix runs its cases on.
#[derive(Debug, Clone)]
pub enum Code {
    /// This project's solver, in-process.
    Impact,
    /// Another code through its adapter.
    Adapter(Adapter),
    /// Histories and summaries someone computed, one folder per scene; with the known
    /// failures of the adapter of the same name, when there is one (`suite/case/check` ->
    /// reason).
    ResultsFrom(PathBuf, BTreeMap<String, String>),
}

impl Code {
    /// The code named on the command line: `impact`, or an adapter under `<root>/adapters/`.
    pub fn find(root: &Path, name: &str) -> Result<Code, String> {
        if name == "impact" {
            return Ok(Code::Impact);
        }
        Adapter::load(root, name).map(Code::Adapter)
    }

    /// `--results-from DIR`: refused when DIR is not a folder. Named by DIR's own name; the
    /// known failures of the adapter of that name (under `root`), if any, are its own.
    pub fn results_from(root: &Path, dir: &Path) -> Result<Code, String> {
        if !dir.is_dir() {
            return Err(format!(
                "--results-from {}: not a folder (expected DIR/<suite>/<case>/<scene>/ with history.csv and summary.json, adapters/README.md)",
                dir.display()
            ));
        }
        let expected = Adapter::load(root, &folder_name(dir))
            .map(|a| a.expected)
            .unwrap_or_default();
        Ok(Code::ResultsFrom(dir.to_path_buf(), expected))
    }

    /// The name its rows carry (for `--results-from DIR`, DIR's own name).
    pub fn name(&self) -> String {
        match self {
            Code::Impact => "impact".into(),
            Code::Adapter(a) => a.name.clone(),
            Code::ResultsFrom(dir, _) => folder_name(dir),
        }
    }

    pub fn is_impact(&self) -> bool {
        matches!(self, Code::Impact)
    }

    /// One line on what the code is, for the report.
    pub fn description(&self) -> String {
        match self {
            Code::Impact => "this project's solver (in-process)".into(),
            Code::Adapter(a) => a.description.clone(),
            Code::ResultsFrom(dir, _) => format!("results read from {}", dir.display()),
        }
    }

    /// The cases this code runs when no selector is given (`None`: all of them).
    pub fn default_cases(&self, light: bool) -> Option<Vec<String>> {
        match self {
            Code::Adapter(a) => Some(if light {
                a.light.clone()
            } else {
                a.cases.clone()
            }),
            Code::Impact | Code::ResultsFrom(..) => None,
        }
    }

    /// This code's known failures, `suite/case/check` -> reason (the cases' own
    /// `known_failure` declarations are `impact`'s).
    pub fn expected(&self) -> &BTreeMap<String, String> {
        static NONE: BTreeMap<String, String> = BTreeMap::new();
        match self {
            Code::Adapter(a) => &a.expected,
            Code::ResultsFrom(_, expected) => expected,
            Code::Impact => &NONE,
        }
    }
}

/// The name of results read from `dir`: the folder's own name.
fn folder_name(dir: &Path) -> String {
    dir.file_name()
        .map_or("results".into(), |n| n.to_string_lossy().into_owned())
}
