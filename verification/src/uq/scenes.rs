//! A study's scenes: `scene:` or `scenes:` as declared, each read with the study's `set` and
//! every uncertain input tried on it (a key the scene does not accept is refused where the
//! input is declared), resolved to its file, label and declared mesh.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::Serialize;
use serde_saphyr::Spanned;

use crate::definition::case::Loc;
use crate::uq::declaration::{invalid, StudyFile};
use crate::uq::distribution::Input;

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

/// A declared scene before it is checked: its file, its place, label and table row.
pub(super) struct SceneDecl<'a> {
    pub(super) file: &'a Spanned<String>,
    pub(super) label: Option<&'a str>,
    pub(super) row: Option<&'a str>,
    /// `scenes[i]` or `scene`.
    pub(super) field: String,
}

/// The declared scenes: exactly one of `scene` and `scenes` (not empty).
pub(super) fn scene_decls<'a>(
    file: &'a StudyFile,
    path: &Path,
) -> Result<Vec<SceneDecl<'a>>, String> {
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

/// Where each input is declared: its own file's span, for messages about it.
pub(super) type InputPlaces = BTreeMap<String, Loc>;

/// Reads one scene, checks `set` and every input against it, and returns its declared mesh.
pub(super) fn check_scene(
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
