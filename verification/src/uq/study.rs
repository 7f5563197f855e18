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
//! #   optional mesh: 0.5: the sampled runs on that mesh level, S and u_num on the declared mesh
//! convergence: {mean: 0.002, std: 0.05, total_index: 0.05}   # allowed change from N/2 to N
//! mesh_levels: [0.25, 0.5, 1.0]                  # u_num: the GCI on the declared mesh (last level 1)
//! outputs:
//!   impulse_Ns: {table: {file: reference-data/paper/table1.csv, row: impulse, column: elasto_plastic}, kind: calibration}
//!   max_plate_displacement_m: {table: {...}, scale: -1.0e-3, kind: calibration}   # reference x scale = SI
//! ```
//!
//! Several scenes that share the inputs (Table 2's velocities) take `scenes:` instead of
//! `scene:`, each with its label and its row of the outputs' tables (the tables then give no
//! `row`); every output is then compared once per scene, all from one design of the inputs:
//!
//! ```yaml
//! scenes:
//!   - {scene: ../scenes/paper-table2/v01.25-plastic.yaml, label: "1.25 m/s", row: "1.25"}
//!   - {scene: ../scenes/paper-table2/v02.50-plastic.yaml, label: "2.5 m/s", row: "2.5"}
//! outputs:
//!   impulse_Ns: {table: {file: reference-data/paper/table2.csv, column: ep_impulse_Ns}, kind: calibration}
//! ```
//!
//! A study based on another, `based_on: {study: other.yaml, except: [keys]}`, takes that
//! study's inputs (validated where they are declared, that study's own base's included) less
//! the keys named, plus any `inputs:` of its own that it does not repeat; and its outputs when
//! it declares none. A chain of bases that comes back to a study is refused.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use serde_saphyr::Spanned;

use crate::definition::case::{parse_located, Loc};

/// How a study file is named in parse errors, and the keys it must have.
const STUDY_FILE: (&str, &str) = (
    "study file",
    "every study needs title, inputs, sampling, convergence, mesh_levels and outputs (and a scene or scenes, unless based_on gives them)",
);
use crate::uq::distribution::{Input, InputFile};

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

/// A cell of a reference table (file relative to the repository, row by its first column).
#[derive(Debug, Clone, Serialize)]
pub struct TableRef {
    pub file: String,
    pub row: String,
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

/// One compared quantity: an output of one scene, with its reference cell.
#[derive(Debug, Clone, Serialize)]
pub struct Output {
    /// Unique in the study: the key, and `key [scene label]` in a study of several scenes.
    pub id: String,
    /// The summary key (dotted for nested ones).
    pub key: String,
    /// Index into `Study::scenes`.
    pub scene: usize,
    pub table: Option<TableRef>,
    pub scale: Option<f64>,
    /// calibration | paper | none
    pub kind: String,
    pub label: String,
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

/// The declared mesh of a scene (with the study's `set`), which the mesh levels scale.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct MeshSize {
    pub nx: usize,
    pub ny: usize,
}

/// A scene of the study, resolved against the study's folder.
#[derive(Debug, Clone, Serialize)]
pub struct StudyScene {
    pub path: PathBuf,
    pub label: String,
    pub mesh: MeshSize,
}

/// A validated study, as the Python package reads it (JSON).
#[derive(Debug, Clone, Serialize)]
pub struct Study {
    pub title: String,
    /// One or more scenes, sampled with the same design of the inputs.
    pub scenes: Vec<StudyScene>,
    pub set: impact_solver::overrides::Overrides,
    pub inputs: Vec<Input>,
    pub sampling: Sampling,
    pub convergence: Convergence,
    pub mesh_levels: Vec<f64>,
    /// Per scene (in order) the declared outputs (by key).
    pub outputs: Vec<Output>,
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

/// A declared scene before it is checked: its file, its place, label and table row.
struct SceneDecl<'a> {
    file: &'a Spanned<String>,
    label: Option<&'a str>,
    row: Option<&'a str>,
    /// `scenes[i]` or `scene`.
    field: String,
}

/// The declared scenes: exactly one of `scene` and `scenes` (not empty).
fn scene_decls<'a>(file: &'a StudyFile, path: &Path) -> Result<Vec<SceneDecl<'a>>, String> {
    match (&file.scene, &file.scenes) {
        (Some(s), None) => Ok(vec![SceneDecl {
            file: s,
            label: None,
            row: None,
            field: "scene".into(),
        }]),
        (None, Some(list)) if !list.value.is_empty() => Ok(list
            .value
            .iter()
            .enumerate()
            .map(|(i, e)| SceneDecl {
                file: &e.value.scene,
                label: e.value.label.as_deref(),
                row: e.value.row.as_deref(),
                field: format!("scenes[{i}]"),
            })
            .collect()),
        (None, Some(list)) => Err(invalid(
            &Loc::of(path, list),
            "scenes",
            "[]",
            "must name at least one scene",
        )),
        (Some(_), Some(list)) => Err(format!(
            "{}: scenes: give either scene (one) or scenes (several), not both",
            Loc::of(path, list)
        )),
        (None, None) => Err(format!(
            "{}: scene: missing: a study names its scene (scene: FILE) or its scenes (scenes: [...])",
            path.display()
        )),
    }
}

/// Parses and validates a study's YAML text; `path` names it and resolves its scenes.
pub fn parse(text: &str, path: &Path) -> Result<Study, String> {
    let file: StudyFile = parse_located(text, path, STUDY_FILE).map_err(|e| e.to_string())?;
    let decls = scene_decls(&file, path)?;
    let set = file
        .set
        .as_ref()
        .map(|s| s.value.clone())
        .unwrap_or_default();
    let shared = shared(&file, path, &mut vec![canonical(path)])?;
    if shared.inputs.is_empty() {
        return Err(format!(
            "{}: inputs: the study declares no uncertain input",
            path.display()
        ));
    }
    if shared.outputs.is_empty() {
        return Err(format!(
            "{}: outputs: the study compares no output",
            path.display()
        ));
    }
    let places: InputPlaces = (shared.inputs.iter())
        .map(|(k, (_, l))| (k.clone(), l.clone()))
        .collect();
    let inputs: Vec<Input> = shared.inputs.into_values().map(|(i, _)| i).collect();
    let mut scenes = Vec::new();
    for d in &decls {
        scenes.push(check_scene(d, &file, &set, &inputs, &places, path)?);
    }
    check_sampling(&file.sampling, path)?;
    check_convergence(&file.convergence, path)?;
    check_levels(&file.mesh_levels, path)?;
    check_sampling_mesh(&file.sampling, &file.mesh_levels.value, path)?;
    let declared = (&shared.outputs, shared.outputs_file.as_path());
    let several = file.scenes.is_some();
    let outputs = outputs(declared, several, &decls, &scenes, path)?;
    Ok(Study {
        title: file.title,
        scenes,
        set,
        inputs,
        sampling: file.sampling.value,
        convergence: file.convergence.value,
        mesh_levels: file.mesh_levels.value,
        outputs,
    })
}

/// Where each input is declared: its own file's span, for messages about it.
type InputPlaces = BTreeMap<String, Loc>;

/// What a study shares with those based on it: its inputs (each with where it is declared)
/// and its outputs with the file that declares them.
struct Shared {
    inputs: BTreeMap<String, (Input, Loc)>,
    outputs: BTreeMap<String, Spanned<OutputFile>>,
    outputs_file: PathBuf,
}

fn canonical(path: &Path) -> PathBuf {
    path.canonicalize().unwrap_or_else(|_| path.to_path_buf())
}

/// The inputs and outputs of the study `file` (read from `path`): its base's (less
/// `except`, recursively) and its own. `chain`: the studies on the way here, to refuse a loop.
fn shared(file: &StudyFile, path: &Path, chain: &mut Vec<PathBuf>) -> Result<Shared, String> {
    let mut inputs = BTreeMap::new();
    let mut base_outputs = None;
    if let Some(b) = &file.based_on {
        let (decl, other) = base_study(b, path, chain)?;
        chain.push(canonical(&other));
        let base = shared(&decl, &other, chain)?;
        inputs = base.inputs;
        for key in &b.value.except {
            if inputs.remove(&key.value).is_none() {
                return Err(invalid(
                    &Loc::of(path, key),
                    "based_on.except",
                    &key.value,
                    &format!("is not an input of {}", other.display()),
                ));
            }
        }
        base_outputs = Some((base.outputs, base.outputs_file));
    }
    for (key, spec) in &file.inputs {
        let loc = Loc::of(path, spec);
        if inputs.contains_key(key) {
            return Err(format!(
                "{loc}: inputs.{key}: also an input of based_on.study: name it in based_on.except to declare it here"
            ));
        }
        let input = crate::uq::distribution::validate(key, spec, path)?;
        inputs.insert(key.clone(), (input, loc));
    }
    let (outputs, outputs_file) = match base_outputs {
        Some(base) if file.outputs.is_empty() => base,
        _ => (file.outputs.clone(), path.to_path_buf()),
    };
    Ok(Shared {
        inputs,
        outputs,
        outputs_file,
    })
}

/// The study `based_on.study`, read and parsed (its file's path beside it); a study already
/// on the chain of bases is refused.
fn base_study(
    b: &Spanned<BasedOn>,
    path: &Path,
    chain: &[PathBuf],
) -> Result<(StudyFile, PathBuf), String> {
    let loc = Loc::of(path, &b.value.study);
    let other = path
        .parent()
        .unwrap_or(Path::new("."))
        .join(&b.value.study.value);
    let text = std::fs::read_to_string(&other).map_err(|e| {
        invalid(
            &loc,
            "based_on.study",
            other.display(),
            &format!("cannot read it: {e}"),
        )
    })?;
    if chain.contains(&canonical(&other)) {
        return Err(invalid(
            &loc,
            "based_on.study",
            other.display(),
            "is already on this chain of bases (a study cannot be based on itself)",
        ));
    }
    parse_located(&text, &other, STUDY_FILE)
        .map(|decl| (decl, other))
        .map_err(|e| e.to_string())
}

/// Reads one scene, checks `set` and every input against it, and returns its declared mesh.
fn check_scene(
    d: &SceneDecl,
    file: &StudyFile,
    set: &impact_solver::overrides::Overrides,
    inputs: &[Input],
    places: &InputPlaces,
    path: &Path,
) -> Result<StudyScene, String> {
    let scene_loc = Loc::of(path, d.file);
    let scene = path.parent().unwrap_or(Path::new(".")).join(&d.file.value);
    let text = std::fs::read_to_string(&scene).map_err(|e| {
        invalid(
            &scene_loc,
            &d.field,
            scene.display(),
            &format!("cannot read it: {e}"),
        )
    })?;
    let parsed =
        impact_solver::scene::Scene::from_yaml_with(&text, set, &scene).map_err(
            |e| match &file.set {
                Some(s) => format!("{}: set: {e}", Loc::of(path, s)),
                None => format!("{scene_loc}: {}: {e}", d.field),
            },
        )?;
    check_overrides(inputs, places, &text, &scene, set)?;
    let label = d.label.map(str::to_string).unwrap_or_else(|| {
        scene
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default()
    });
    Ok(StudyScene {
        path: scene,
        label,
        mesh: MeshSize {
            nx: parsed.mesh.nx,
            ny: parsed.mesh.ny,
        },
    })
}

/// Every input's key must be a scene key the scene's rules accept at the distribution's
/// centre (its mean or mid-range); the message names where the input is declared.
fn check_overrides(
    inputs: &[Input],
    places: &InputPlaces,
    scene_text: &str,
    scene: &Path,
    fixed: &impact_solver::overrides::Overrides,
) -> Result<(), String> {
    for input in inputs {
        let centre = crate::uq::distribution::centre(&input.distribution);
        let mut set = fixed.clone();
        set.insert(input.key.clone(), serde_json::json!(centre));
        if let Err(e) = impact_solver::scene::Scene::from_yaml_with(scene_text, &set, scene) {
            let loc = &places[&input.key];
            return Err(format!(
                "{loc}: inputs.{}: not a settable scene key at {centre:e}: {e}",
                input.key
            ));
        }
    }
    Ok(())
}

/// The outputs per scene, each table reference resolved to its row and checked in its file.
/// `declared`: the outputs and the file that declares them (the study's, or its base's);
/// `path`: the study's file.
fn outputs(
    declared: (&BTreeMap<String, Spanned<OutputFile>>, &Path),
    several: bool,
    decls: &[SceneDecl],
    scenes: &[StudyScene],
    path: &Path,
) -> Result<Vec<Output>, String> {
    let (declared, from) = declared;
    let mut out = Vec::new();
    for (i, (d, s)) in decls.iter().zip(scenes).enumerate() {
        for (key, o) in declared {
            let loc = Loc::of(from, o);
            let kind = o.value.kind.as_deref().unwrap_or("none");
            if !matches!(kind, "calibration" | "paper" | "none") {
                let field = format!("outputs.{key}.kind");
                return Err(invalid(
                    &loc,
                    &field,
                    kind,
                    "must be calibration, paper or none",
                ));
            }
            let table = match &o.value.table {
                Some(t) => Some(table_ref(t, key, d, &loc, several, path)?),
                None => None,
            };
            let label = o.value.label.clone().unwrap_or_else(|| key.clone());
            let (id, label) = if several {
                (
                    format!("{key} [{}]", s.label),
                    format!("{label}, {}", s.label),
                )
            } else {
                (key.clone(), label)
            };
            out.push(Output {
                id,
                key: key.clone(),
                scene: i,
                table,
                scale: o.value.scale,
                kind: kind.to_string(),
                label,
            });
        }
    }
    Ok(out)
}

/// The table cell of one output of one scene: its row from the output (one scene) or from
/// the scene (several), and the cell must hold a number.
fn table_ref(
    t: &TableRefFile,
    key: &str,
    d: &SceneDecl,
    loc: &Loc,
    several: bool,
    path: &Path,
) -> Result<TableRef, String> {
    // the row and where it is written (on the output, or on the scene of a study of several)
    let (row, at) = match (several, &t.row, d.row) {
        (false, Some(r), _) => (r.clone(), format!("{loc}: outputs.{key}.table.row")),
        (false, None, _) => {
            return Err(format!("{loc}: outputs.{key}.table.row: missing: the row of {} (its first column's text)", t.file))
        }
        (true, Some(r), _) => {
            return Err(invalid(loc, &format!("outputs.{key}.table.row"), r, "must be left out in a study of several scenes: each scene gives its row (scenes[i].row)"))
        }
        (true, None, Some(r)) => (r.to_string(), format!("{}: {}.row", Loc::of(path, d.file), d.field)),
        (true, None, None) => {
            let at = Loc::of(path, d.file);
            return Err(format!("{at}: {}.row: missing: the row of {} for this scene (outputs.{key} has a table)", d.field, t.file));
        }
    };
    let Some(root) = path.canonicalize().ok().and_then(|p| {
        p.ancestors()
            .find(|a| a.join("reference-data").is_dir())
            .map(Path::to_path_buf)
    }) else {
        return Err(format!(
            "{loc}: outputs.{key}.table.file: no folder reference-data above the study"
        ));
    };
    let csv = root.join(&t.file);
    let first = first_column(&csv).map_err(|e| format!("{loc}: outputs.{key}.table: {e}"))?;
    let at_row = BTreeMap::from([(first, row.clone())]);
    crate::definition::check::table_value(&csv, &at_row, &t.column)
        .map_err(|e| format!("{at} = {row} (outputs.{key}): {e}"))?;
    Ok(TableRef {
        file: t.file.clone(),
        row,
        column: t.column.clone(),
    })
}

/// The name of a CSV file's first column.
fn first_column(path: &Path) -> Result<String, String> {
    let mut rd = csv::Reader::from_path(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let headers = rd
        .headers()
        .map_err(|e| format!("{}: {e}", path.display()))?;
    headers
        .get(0)
        .map(str::to_string)
        .ok_or_else(|| format!("{}: no columns", path.display()))
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

/// `sampling.mesh`, when given, is one of the mesh levels below the declared mesh.
fn check_sampling_mesh(s: &Spanned<Sampling>, levels: &[f64], path: &Path) -> Result<(), String> {
    match s.value.mesh {
        Some(m) if !(m < 1.0 && levels.contains(&m)) => Err(invalid(
            &Loc::of(path, s),
            "sampling.mesh",
            m,
            &format!("must be one of the mesh levels below 1 ({levels:?})"),
        )),
        _ => Ok(()),
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    fn repo() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
    }

    /// A folder for test studies with `reference-data` beside them (a link to the repo's).
    fn folder(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("uq-study-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        std::os::unix::fs::symlink(repo().join("reference-data"), dir.join("reference-data"))
            .unwrap();
        dir
    }

    fn scene(name: &str) -> String {
        repo()
            .join("verification/scenes")
            .join(name)
            .display()
            .to_string()
    }

    const TAIL: &str = "sampling: {method: sobol, seed: 1, sizes: [4, 8]}\n\
        convergence: {mean: 0.01, std: 0.1, total_index: 0.1}\n\
        mesh_levels: [0.25, 0.5, 1.0]\n";

    const WIDTH: &str =
        "inputs:\n  plate.width: {uniform: {lower: 0.178, upper: 0.180}, source: s}\n";

    fn two_scenes(row_a: &str, table_row: &str) -> String {
        format!(
            "title: t\nscenes:\n  - {{scene: {}, label: slow, row: {row_a}}}\n  - {{scene: {}, row: \"15\"}}\n{WIDTH}{TAIL}\
             outputs:\n  impulse_Ns: {{table: {{file: reference-data/paper/table2.csv, {table_row}column: ep_impulse_Ns}}, kind: calibration}}\n",
            scene("paper-table2/v01.25-plastic.yaml"),
            scene("paper-table2/v15.00-plastic.yaml"),
        )
    }

    fn parse_in(dir: &Path, name: &str, text: &str) -> Result<Study, String> {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        read(&path)
    }

    #[test]
    fn the_shipped_studies_read_and_share_their_inputs() {
        let uq = repo().join("verification/uq");
        let plastic = read(&uq.join("paper-plastic.yaml")).unwrap();
        let keys = |s: &Study| s.inputs.iter().map(|i| i.key.clone()).collect::<Vec<_>>();
        let elastic = read(&uq.join("paper-elastic.yaml")).unwrap();
        let ci = read(&uq.join("ci-coarse.yaml")).unwrap();
        assert_eq!(keys(&ci), keys(&plastic));
        assert_eq!(ci.outputs.len(), plastic.outputs.len());
        let no_plasticity: Vec<_> = keys(&plastic)
            .into_iter()
            .filter(|k| !k.starts_with("material.plasticity"))
            .collect();
        assert_eq!(keys(&elastic), no_plasticity);
        // each shared input keeps its distribution and where it is declared
        let e = &elastic.inputs[0];
        let p = plastic.inputs.iter().find(|i| i.key == e.key).unwrap();
        assert_eq!((&e.distribution, &e.at), (&p.distribution, &p.at));
        assert!(e.at.contains("paper-plastic.yaml:"), "{}", e.at);
        let surface = read(&uq.join("paper-elastic-surface.yaml")).unwrap();
        assert!(!keys(&surface).iter().any(|k| k.contains("contact_law")));
        assert_eq!(surface.outputs.len(), elastic.outputs.len());
        assert_eq!(surface.outputs[0].table.as_ref().unwrap().column, "elastic");
        for (name, column) in [
            ("table2-plastic", "ep_impulse_Ns"),
            ("table2-elastic", "elastic_impulse_Ns"),
        ] {
            let t2 = read(&uq.join(format!("{name}.yaml"))).unwrap();
            assert_eq!(t2.scenes.len(), 7);
            assert!(!keys(&t2)
                .iter()
                .any(|k| k.ends_with("mass") || k.ends_with("velocity")));
            let rows: Vec<_> = t2
                .outputs
                .iter()
                .map(|o| o.table.as_ref().unwrap().row.clone())
                .collect();
            assert_eq!(rows, ["1.25", "2.5", "5", "7.5", "10", "12.5", "15"]);
            assert!(t2
                .outputs
                .iter()
                .all(|o| o.table.as_ref().unwrap().column == column));
            assert_eq!(t2.outputs[6].id, "impulse_Ns [15 m/s]");
            assert_eq!(t2.outputs[6].scene, 6);
        }
    }

    #[test]
    fn several_scenes_give_one_output_per_scene_with_its_row() {
        let dir = folder("several");
        let s = parse_in(&dir, "s.yaml", &two_scenes("\"1.25\"", "")).unwrap();
        assert_eq!(s.scenes[0].label, "slow");
        assert_eq!(s.scenes[1].label, "v15.00-plastic");
        assert_eq!((s.scenes[1].mesh.nx, s.scenes[1].mesh.ny), (80, 16));
        let ids: Vec<_> = s.outputs.iter().map(|o| (o.id.as_str(), o.scene)).collect();
        assert_eq!(
            ids,
            [("impulse_Ns [slow]", 0), ("impulse_Ns [v15.00-plastic]", 1)]
        );
        assert_eq!(s.outputs[1].table.as_ref().unwrap().row, "15");
    }

    #[test]
    fn a_bad_declaration_of_scenes_names_its_place() {
        let dir = folder("bad-scenes");
        let cases = [
            // a row the table does not have: the output's place and the file
            (
                two_scenes("\"3\"", ""),
                "s.yaml:3:13: scenes[0].row = 3 (outputs.impulse_Ns): ",
                "table2.csv: no row",
            ),
            // a row on the output of a study of several scenes
            (
                two_scenes("\"1.25\"", "row: \"1.25\", "),
                "s.yaml:11:15: outputs.impulse_Ns.table.row = 1.25",
                "each scene gives its row",
            ),
            // a scene without its row
            (
                two_scenes("\"1.25\"", "").replace(", row: \"15\"", ""),
                "s.yaml:4:13: scenes[1].row: missing",
                "table2.csv",
            ),
            // both forms
            (
                format!("title: t\nscene: {}\n", scene("paper-plastic.yaml"))
                    + &two_scenes("\"1.25\"", "")[9..],
                "s.yaml:4:3: scenes: give either",
                "",
            ),
            // an empty list
            (
                format!("title: t\nscenes: []\n{WIDTH}{TAIL}outputs: {{impulse_Ns: {{}}}}\n"),
                "s.yaml:2:9: scenes = []",
                "",
            ),
        ];
        for (text, want, also) in cases {
            let e = parse_in(&dir, "s.yaml", &text).unwrap_err();
            let e = e.replace(&format!("{}/", dir.display()), "");
            assert!(
                e.starts_with(want) && e.contains(also),
                "{e}\nwanted {want} ... {also}"
            );
        }
    }

    #[test]
    fn based_on_shares_inputs_and_refuses_what_it_cannot_share() {
        let dir = folder("based-on");
        let base = format!(
            "title: base\nscene: {}\ninputs:\n  plate.width: {{uniform: {{lower: 0.178, upper: 0.180}}, source: s}}\n  \
             plate.thickness: {{uniform: {{lower: 0.018, upper: 0.019}}, source: s}}\n{TAIL}outputs: {{impulse_Ns: {{}}}}\n",
            scene("paper-plastic.yaml")
        );
        std::fs::write(dir.join("base.yaml"), base).unwrap();
        let head = format!("title: t\nscene: {}\n", scene("paper-plastic.yaml"));
        let ok = parse_in(
            &dir,
            "a.yaml",
            &format!("{head}based_on: {{study: base.yaml, except: [plate.thickness]}}\n{TAIL}"),
        )
        .unwrap();
        assert_eq!(ok.inputs.len(), 1);
        assert_eq!(ok.outputs[0].id, "impulse_Ns");
        assert!(
            ok.inputs[0].at.ends_with("base.yaml:4:16"),
            "{}",
            ok.inputs[0].at
        );
        let cases = [
            (
                format!("{head}based_on: {{study: base.yaml, except: [plate.length]}}\n{TAIL}"),
                "a.yaml:3:39: based_on.except = plate.length: is not an input of",
            ),
            (
                format!("{head}based_on: {{study: base.yaml}}\n{WIDTH}{TAIL}"),
                "a.yaml:5:16: inputs.plate.width: also an input of based_on.study",
            ),
            (
                format!("{head}based_on: {{study: a.yaml}}\n{TAIL}"),
                "a.yaml:3:19: based_on.study = ",
            ),
            (
                format!("{head}based_on: {{study: missing.yaml}}\n{TAIL}"),
                "a.yaml:3:19: based_on.study = ",
            ),
        ];
        for (text, want) in cases {
            let e = parse_in(&dir, "a.yaml", &text).unwrap_err();
            let e = e.replace(&format!("{}/", dir.display()), "");
            assert!(e.starts_with(want), "{e}\nwanted {want}");
        }
        let e = parse_in(
            &dir,
            "a.yaml",
            &format!("{head}based_on: {{study: a.yaml}}\n{TAIL}"),
        )
        .unwrap_err();
        assert!(e.contains("already on this chain"), "{e}");
    }

    #[test]
    fn the_sampling_mesh_is_a_coarser_declared_level() {
        let dir = folder("sampling-mesh");
        let study = |mesh: &str| {
            format!(
                "title: t\nscene: {}\n{WIDTH}sampling: {{method: sobol, seed: 1, sizes: [4, 8]{mesh}}}\n\
                 convergence: {{mean: 0.01, std: 0.1, total_index: 0.1}}\nmesh_levels: [0.25, 0.5, 1.0]\n\
                 outputs: {{impulse_Ns: {{}}}}\n",
                scene("paper-plastic.yaml")
            )
        };
        let ok = parse_in(&dir, "m.yaml", &study(", mesh: 0.5")).unwrap();
        assert_eq!(ok.sampling.mesh, Some(0.5));
        assert_eq!(
            parse_in(&dir, "m.yaml", &study("")).unwrap().sampling.mesh,
            None
        );
        for bad in [", mesh: 0.3", ", mesh: 1.0"] {
            let e = parse_in(&dir, "m.yaml", &study(bad)).unwrap_err();
            let e = e.replace(&format!("{}/", dir.display()), "");
            assert!(
                e.starts_with("m.yaml:5:11: sampling.mesh = ") && e.contains("below 1"),
                "{e}"
            );
        }
    }
}
