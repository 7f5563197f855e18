//! An uncertainty study's declaration (issue 27, section 1): a scene, its uncertain inputs as
//! distributions with their source, the sampling, the outputs and their references. Read and
//! validated here like every other input (messages `file:line:col: field = value: what is
//! allowed`); the Python package samples, runs and analyses it (`impact.uq`).
//!
//! ```yaml
//! title: Table 1, elasto-plastic row
//! scene: ../scenes/paper-plastic.yaml            # relative to this file
//! set: {mesh.nx: 20, mesh.ny: 4}                # optional: fixed overrides of every run
//! inputs:                                         # dotted scene keys, as overrides
//!   material.youngs_modulus: {normal: {mean: 207.0e9, std: 6.21e9}, source: "..."}
//!   material.plasticity.yield_stress: {lognormal: {mean: 176.0e6, cov: 0.07}, source: "..."}
//!   plate.width: {uniform: {lower: 0.178, upper: 0.180}, source: "..."}
//!   plate.thickness: {truncated: {normal: {mean: 0.0188, std: 2.0e-4}, lower: 0.0182, upper: 0.0194}, source: "..."}
//! sampling: {method: sobol, seed: 27, sizes: [16, 32, 64]}   # or lhs; sizes: base samples N, doubling
//! convergence: {mean: 0.002, std: 0.05, total_index: 0.05}   # allowed change from N/2 to N
//! mesh_levels: [0.25, 0.5, 1.0]                  # u_num: the GCI on the declared mesh (last level 1)
//! outputs:
//!   impulse_Ns: {table: {file: reference-data/paper/table1.csv, row: impulse, column: elasto_plastic}, kind: calibration}
//!   max_plate_displacement_m: {table: {...}, scale: -1.0e-3, kind: calibration}   # reference x scale = SI
//! ```

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use serde_saphyr::Spanned;

use crate::case::{parse_located, Loc};
use crate::uq_distribution::{Input, InputFile};

#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Sampling {
    pub method: String,
    pub seed: u64,
    pub sizes: Vec<usize>,
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

#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct TableRef {
    pub file: String,
    pub row: String,
    pub column: String,
}

/// An output (a summary key, dotted for nested ones) and its reference.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct OutputFile {
    #[serde(default)]
    pub table: Option<TableRef>,
    #[serde(default)]
    pub scale: Option<f64>,
    /// calibration | paper | none
    #[serde(default)]
    pub kind: Option<String>,
    #[serde(default)]
    pub label: Option<String>,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StudyFile {
    pub title: String,
    pub scene: Spanned<String>,
    /// Fixed overrides of the scene for every run (e.g. a coarse mesh for CI).
    #[serde(default)]
    pub set: Option<Spanned<impact_solver::overrides::Overrides>>,
    pub inputs: BTreeMap<String, Spanned<InputFile>>,
    pub sampling: Spanned<Sampling>,
    pub convergence: Spanned<Convergence>,
    pub mesh_levels: Spanned<Vec<f64>>,
    pub outputs: BTreeMap<String, Spanned<OutputFile>>,
}

/// A validated study, as the Python package reads it (JSON).
#[derive(Debug, Clone, Serialize)]
pub struct Study {
    pub title: String,
    /// The scene file, resolved against the study's folder.
    pub scene: PathBuf,
    pub set: impact_solver::overrides::Overrides,
    pub inputs: Vec<Input>,
    pub sampling: Sampling,
    pub convergence: Convergence,
    pub mesh_levels: Vec<f64>,
    pub outputs: BTreeMap<String, OutputFile>,
}

/// `loc: field = value: allowed`.
fn invalid(loc: &Loc, field: &str, value: impl std::fmt::Display, allowed: &str) -> String {
    format!("{loc}: {field} = {value}: {allowed}")
}

/// Reads and validates a study file.
pub fn read(path: &Path) -> Result<Study, String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("{}: cannot read the study: {e}", path.display()))?;
    parse(&text, path)
}

/// Parses and validates a study's YAML text; `path` names it and resolves its scene.
pub fn parse(text: &str, path: &Path) -> Result<Study, String> {
    let file: StudyFile = parse_located(
        text,
        path,
        (
            "study file",
            "every study needs title, scene, inputs, sampling, convergence, mesh_levels and outputs",
        ),
    )
    .map_err(|e| e.to_string())?;
    let scene_loc = Loc::of(path, &file.scene);
    let scene = path
        .parent()
        .unwrap_or(Path::new("."))
        .join(&file.scene.value);
    let scene_text = std::fs::read_to_string(&scene).map_err(|e| {
        invalid(
            &scene_loc,
            "scene",
            scene.display(),
            &format!("cannot read it: {e}"),
        )
    })?;
    let mut inputs = Vec::new();
    for (key, spec) in &file.inputs {
        inputs.push(crate::uq_distribution::validate(key, spec, path)?);
    }
    if inputs.is_empty() {
        return Err(format!(
            "{}: inputs: the study declares no uncertain input",
            path.display()
        ));
    }
    let set = file
        .set
        .as_ref()
        .map(|s| s.value.clone())
        .unwrap_or_default();
    if let Some(s) = &file.set {
        impact_solver::scene::Scene::from_yaml_with(&scene_text, &set, &scene)
            .map_err(|e| format!("{}: set: {e}", Loc::of(path, s)))?;
    }
    check_overrides(&inputs, &file.inputs, &scene_text, &scene, &set, path)?;
    check_sampling(&file.sampling, path)?;
    check_convergence(&file.convergence, path)?;
    check_levels(&file.mesh_levels, path)?;
    for (key, o) in &file.outputs {
        let kind = o.value.kind.as_deref().unwrap_or("none");
        if !matches!(kind, "calibration" | "paper" | "none") {
            let loc = Loc::of(path, o);
            return Err(invalid(
                &loc,
                &format!("outputs.{key}.kind"),
                kind,
                "must be calibration, paper or none",
            ));
        }
    }
    Ok(Study {
        title: file.title,
        scene,
        set,
        inputs,
        sampling: file.sampling.value,
        convergence: file.convergence.value,
        mesh_levels: file.mesh_levels.value,
        outputs: file
            .outputs
            .into_iter()
            .map(|(k, v)| (k, v.value))
            .collect(),
    })
}

/// Every input's key must be a scene key the scene's rules accept at the distribution's
/// centre (its mean or mid-range).
fn check_overrides(
    inputs: &[Input],
    specs: &BTreeMap<String, Spanned<InputFile>>,
    scene_text: &str,
    scene: &Path,
    fixed: &impact_solver::overrides::Overrides,
    path: &Path,
) -> Result<(), String> {
    for input in inputs {
        let centre = crate::uq_distribution::centre(&input.distribution);
        let mut set = fixed.clone();
        set.insert(input.key.clone(), serde_json::json!(centre));
        if let Err(e) = impact_solver::scene::Scene::from_yaml_with(scene_text, &set, scene) {
            let loc = Loc::of(path, &specs[&input.key]);
            return Err(format!(
                "{loc}: inputs.{}: not a settable scene key at {centre:e}: {e}",
                input.key
            ));
        }
    }
    Ok(())
}

fn check_sampling(s: &Spanned<Sampling>, path: &Path) -> Result<(), String> {
    let loc = Loc::of(path, s);
    let v = &s.value;
    if !matches!(v.method.as_str(), "sobol" | "lhs") {
        return Err(invalid(
            &loc,
            "sampling.method",
            &v.method,
            "must be sobol (scrambled Sobol', Saltelli's design) or lhs (Latin hypercube)",
        ));
    }
    let doubling = v.sizes.windows(2).all(|w| w[1] == 2 * w[0]);
    if v.sizes.is_empty() || !v.sizes[0].is_power_of_two() || v.sizes[0] < 4 || !doubling {
        return Err(invalid(
            &loc,
            "sampling.sizes",
            format!("{:?}", v.sizes),
            "must be powers of two >= 4, each twice the one before (nested Sobol' designs)",
        ));
    }
    Ok(())
}

fn check_convergence(c: &Spanned<Convergence>, path: &Path) -> Result<(), String> {
    let loc = Loc::of(path, c);
    for (name, x) in [
        ("mean", c.value.mean),
        ("std", c.value.std),
        ("total_index", c.value.total_index),
    ] {
        if !(x.is_finite() && x > 0.0) {
            return Err(invalid(
                &loc,
                &format!("convergence.{name}"),
                x,
                "must be a finite number > 0",
            ));
        }
    }
    Ok(())
}

fn check_levels(l: &Spanned<Vec<f64>>, path: &Path) -> Result<(), String> {
    let loc = Loc::of(path, l);
    let v = &l.value;
    let ratio_ok = v.windows(2).all(|w| (w[1] / w[0] - 2.0).abs() < 1e-12);
    if v.len() < 3 || v.last() != Some(&1.0) || !ratio_ok {
        return Err(invalid(&loc, "mesh_levels", format!("{v:?}"), "must be at least three levels, each twice the one before, ending at 1 (the declared mesh)"));
    }
    Ok(())
}
