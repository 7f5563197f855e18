//! An uncertainty study as its file declares it (the file's form is described in
//! [`super::study`]): the keys and their types, read with the place of each value, before any
//! of them is checked; and the form of the messages that refuse one.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};
use serde_saphyr::Spanned;

use crate::definition::case::Loc;
use crate::uq::distribution::InputFile;

/// How a study file is named in parse errors, and the keys it must have.
pub(super) const STUDY_FILE: (&str, &str) = (
    "study file",
    "every study needs title, inputs, sampling, convergence, mesh_levels and outputs (and a scene or scenes, unless based_on gives them)",
);

#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Sampling {
    pub method: String,
    pub seed: u64,
    pub sizes: Vec<usize>,
    /// Optional: the sampled runs on this mesh level (one of `mesh_levels` below 1) instead of
    /// the declared mesh, a cheaper model of the spread; `S` and `u_num` stay on the declared
    /// mesh, and the first size's `A` and `B` points are run on both meshes to measure how the
    /// spread moves between them.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mesh: Option<f64>,
}

#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Convergence {
    /// Largest change of the mean from N/2 to N, relative to the mean.
    pub mean: f64,
    /// Largest change of the standard deviation, relative to it.
    pub std: f64,
    /// Largest change of a total-order index, absolute.
    pub total_index: f64,
}

/// A cell of a reference table as declared: the row (the first column's printed text) is
/// given by each scene in a study of several scenes.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TableRefFile {
    pub file: String,
    #[serde(default)]
    pub row: Option<String>,
    pub column: String,
}

/// An output (a summary key, dotted for nested ones) and its reference, as declared.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputFile {
    #[serde(default)]
    pub table: Option<TableRefFile>,
    #[serde(default)]
    pub scale: Option<f64>,
    /// calibration | paper | none
    #[serde(default)]
    pub kind: Option<String>,
    #[serde(default)]
    pub label: Option<String>,
}

/// One entry of `scenes:`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneEntryFile {
    pub scene: Spanned<String>,
    /// The scene's name in the report (default: the file's stem).
    #[serde(default)]
    pub label: Option<String>,
    /// The row of the outputs' reference tables that belongs to this scene.
    #[serde(default)]
    pub row: Option<String>,
}

/// `based_on:` another study whose inputs (less `except`) and outputs this one shares.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BasedOn {
    pub study: Spanned<String>,
    #[serde(default)]
    pub except: Vec<Spanned<String>>,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StudyFile {
    pub title: String,
    #[serde(default)]
    pub scene: Option<Spanned<String>>,
    #[serde(default)]
    pub scenes: Option<Spanned<Vec<Spanned<SceneEntryFile>>>>,
    /// Fixed overrides of the scene for every run (e.g. a coarse mesh for CI).
    #[serde(default)]
    pub set: Option<Spanned<impact_solver::overrides::Overrides>>,
    #[serde(default)]
    pub based_on: Option<Spanned<BasedOn>>,
    #[serde(default)]
    pub inputs: BTreeMap<String, Spanned<InputFile>>,
    pub sampling: Spanned<Sampling>,
    pub convergence: Spanned<Convergence>,
    pub mesh_levels: Spanned<Vec<f64>>,
    /// Optional with `based_on` (then the base's).
    #[serde(default)]
    pub outputs: BTreeMap<String, Spanned<OutputFile>>,
}

/// `loc: field = value: allowed`.
pub(super) fn invalid(
    loc: &Loc,
    field: &str,
    value: impl std::fmt::Display,
    allowed: &str,
) -> String {
    format!("{loc}: {field} = {value}: {allowed}")
}
