//! A study's declaration checked whole before any run, beside the harness's reader
//! (`impact_verification::uq_study`): the seed's range, every input's key and declared values
//! on every scene (a bound the scene's rules refuse is named with the rule), and every output
//! against the numbers the scenes' summaries hold. Messages as the reader's: `file:line:col:
//! field = value: what is allowed`.
//!
//! The seed and the inputs declared in the study's own file are checked before the reader
//! (whose words for them are a parser's, "expected an integer", and a key "not settable" when
//! a value is refused); the inputs shared by a base study, and the outputs, after it.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::Deserialize;
use serde_saphyr::Spanned;

use impact_solver::error::SourceLocation as Loc;
use impact_solver::overrides::Overrides;
use impact_solver::{Error, Scene};
use impact_verification::case::parse_located;
use impact_verification::uq::distribution::{validate, Input};
use impact_verification::uq_study::{Study, StudyFile};

use crate::overrides::scene_with;
use crate::{scene_keys, summary_keys};

/// How a study file is named in parse errors (the reader's words; only read here when the
/// reader has accepted the file, or to check it before the reader, ignoring what fails).
const STUDY_FILE: (&str, &str) = ("study file", "");

/// Reads the study at `path` and checks it whole: the reader's rules and those of this module.
pub fn read(path: &Path) -> Result<Study, String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("{}: cannot read the study: {e}", path.display()))?;
    check_seed(&text, path)?;
    if let Ok(file) = parse_located::<StudyFile>(&text, path, STUDY_FILE) {
        check_own_inputs(&file, path)?;
    }
    let study = impact_verification::uq_study::parse(&text, path)?;
    let scenes: Vec<Option<Loaded>> = (study.scenes.iter())
        .map(|s| Loaded::read(&s.path, &study.set))
        .collect();
    check_inputs(&study.inputs, &scenes, &study.set)?;
    check_outputs(&study, &scenes, path)?;
    Ok(study)
}

/// A scene of the study, read and validated with the study's `set`.
struct Loaded {
    path: PathBuf,
    text: String,
    scene: Scene,
}

impl Loaded {
    /// None when it cannot be read or is refused with `set` (the reader says why).
    fn read(path: &Path, set: &Overrides) -> Option<Loaded> {
        let text = std::fs::read_to_string(path).ok()?;
        let scene = scene_with(&text, set, path).ok()?;
        Some(Loaded {
            path: path.to_path_buf(),
            text,
            scene,
        })
    }
}

/// `sampling.seed` as written, with its place.
#[derive(Deserialize)]
struct SeedOnly {
    #[serde(default)]
    sampling: Option<SamplingSeed>,
}

#[derive(Deserialize)]
struct SamplingSeed {
    #[serde(default)]
    seed: Option<Spanned<serde_json::Value>>,
}

/// The seed must be an integer from 0 to 2^64 - 1 (the reader reads it as such).
fn check_seed(text: &str, path: &Path) -> Result<(), String> {
    let Ok(SeedOnly {
        sampling: Some(SamplingSeed { seed: Some(seed) }),
    }) = serde_saphyr::from_str::<SeedOnly>(text)
    else {
        return Ok(());
    };
    if seed.value.as_u64().is_some() {
        return Ok(());
    }
    let shown = match &seed.value {
        serde_json::Value::String(s) => format!("{s:?}"),
        other => other.to_string(),
    };
    Err(format!(
        "{}: sampling.seed = {shown}: must be a non-negative integer, 0 to {} (the seed of the scrambled Sobol' or Latin hypercube design)",
        Loc::of(path, &seed),
        u64::MAX
    ))
}

/// The inputs the study's own file declares (those whose distribution the reader accepts),
/// on the scenes it declares (those that read with its `set`), before the reader.
fn check_own_inputs(file: &StudyFile, path: &Path) -> Result<(), String> {
    let set = file
        .set
        .as_ref()
        .map(|s| s.value.clone())
        .unwrap_or_default();
    let folder = path.parent().unwrap_or(Path::new("."));
    let one = file.scene.iter().map(|s| &s.value);
    let several =
        (file.scenes.iter()).flat_map(|list| list.value.iter().map(|e| &e.value.scene.value));
    let scenes: Vec<Option<Loaded>> = (one.chain(several))
        .map(|name| Loaded::read(&folder.join(name), &set))
        .collect();
    let inputs: Vec<Input> = (file.inputs.iter())
        .filter_map(|(key, spec)| validate(key, spec, path).ok())
        .collect();
    check_inputs(&inputs, &scenes, &set)
}

/// Each input's key must be a scene key, and each of its declared values one every scene
/// allows with `set` (the scenes that read with it; None: one that does not, left for the
/// reader to name).
fn check_inputs(
    inputs: &[Input],
    scenes: &[Option<Loaded>],
    set: &Overrides,
) -> Result<(), String> {
    for input in inputs {
        scene_keys::lookup(&input.key).map_err(|unknown| {
            format!(
                "{}: inputs.{}: not a scene key: {unknown}",
                input.at, input.key
            )
        })?;
        for s in scenes.iter().flatten() {
            check_values(input, s, set)?;
        }
    }
    Ok(())
}

/// The input's declared values (see [`declared_values`]), each set on the scene `s` with
/// `set`: a value the scene refuses is named with its field and the scene's rule.
fn check_values(input: &Input, s: &Loaded, set: &Overrides) -> Result<(), String> {
    for (field, value) in declared_values(input) {
        let mut with = set.clone();
        with.insert(input.key.clone(), value.into());
        if let Err(e) = scene_with(&s.text, &with, &s.path) {
            return Err(format!(
                "{}: inputs.{}.{}.{field} = {value}: {} does not allow it: {}",
                input.at,
                input.key,
                input.kind,
                s.path.display(),
                rule(e)
            ));
        }
    }
    Ok(())
}

/// The values a distribution declares that its samples reach: the bounds of a bounded one
/// (uniform, truncated), the mean of an unbounded one (whose draws the Python side checks,
/// `impact._uq._check_draws`: they depend on the design).
fn declared_values(input: &Input) -> Vec<(&'static str, f64)> {
    let d = &input.distribution;
    let bounds: Vec<_> = ["lower", "upper"]
        .into_iter()
        .filter_map(|name| Some((name, d[name].as_f64()?)))
        .collect();
    if bounds.len() == 2 {
        return bounds;
    }
    d["mean"]
        .as_f64()
        .map(|m| vec![("mean", m)])
        .unwrap_or_default()
}

/// The rule a refused value breaks, in the scene's words (`field = value: what is allowed`).
fn rule(e: Error) -> String {
    match e {
        Error::Override { message, .. } => message,
        other => other.to_string(),
    }
}

/// Every output must be a number of the summary of each scene it is read from.
fn check_outputs(study: &Study, scenes: &[Option<Loaded>], path: &Path) -> Result<(), String> {
    let places = output_places(path);
    let keys: Vec<Option<Vec<String>>> = (scenes.iter())
        .map(|s| s.as_ref().map(|s| summary_keys::numeric(&s.scene)))
        .collect();
    for output in &study.outputs {
        let (Some(Some(s)), Some(Some(allowed))) =
            (scenes.get(output.scene), keys.get(output.scene))
        else {
            continue;
        };
        if allowed.contains(&output.key) {
            continue;
        }
        let at = places
            .get(&output.key)
            .map_or_else(|| path.display().to_string(), Loc::to_string);
        return Err(format!(
            "{at}: outputs.{}: not a number of the summary of {}: an output is one of its numeric keys: {}",
            output.key,
            s.path.display(),
            allowed.join(", ")
        ));
    }
    Ok(())
}

/// Where each output is declared: in the study's file, or (when it declares none) in the
/// file of the study it is based on, and so on.
fn output_places(path: &Path) -> BTreeMap<String, Loc> {
    let Some(file) = std::fs::read_to_string(path)
        .ok()
        .and_then(|text| parse_located::<StudyFile>(&text, path, STUDY_FILE).ok())
    else {
        return BTreeMap::new();
    };
    match &file.based_on {
        Some(b) if file.outputs.is_empty() => output_places(
            &path
                .parent()
                .unwrap_or(Path::new("."))
                .join(&b.value.study.value),
        ),
        _ => (file.outputs.iter())
            .map(|(key, o)| (key.clone(), Loc::of(path, o)))
            .collect(),
    }
}
