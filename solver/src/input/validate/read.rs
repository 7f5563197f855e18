//! Reading a scene: YAML text parsed into the file's types (the parser's errors named by
//! [`crate::input::yaml_field`]), overrides set at its dotted paths, validated by
//! [`Validator`], and its plausibility warnings found.

use std::path::Path;

use crate::input::error::{Error, Result, SourceLocation};
use crate::input::overrides::Overrides;
use crate::input::scene::{Scene, SceneFile};
use crate::input::spans::FieldSpans;

use super::Validator;

impl Scene {
    /// Reads and validates a scene file.
    pub fn from_file(path: &Path) -> Result<Scene> {
        Scene::from_file_with(path, &Overrides::new())
    }

    /// Reads a scene file, applies `overrides` (see [`Scene::from_yaml_with`]) and validates.
    pub fn from_file_with(path: &Path, overrides: &Overrides) -> Result<Scene> {
        let text = std::fs::read_to_string(path).map_err(|source| Error::ReadScene {
            path: path.to_path_buf(),
            source,
        })?;
        Scene::from_yaml_with(&text, overrides, path)
    }

    /// Parses and validates YAML text; `source` names it in messages.
    pub fn from_yaml(text: &str, source: &Path) -> Result<Scene> {
        let file: SceneFile = parse(text, source)?;
        let mut scene = Validator::new(source).scene(file)?;
        scene.warnings = crate::input::plausibility::warnings(&scene, Some(text));
        Ok(scene)
    }

    /// Parses YAML text, sets each override at its dotted path of the scene (e.g.
    /// `load.impactor.mass`, `time.dt.cfl`) and validates the result with the same rules as
    /// a scene file. The text itself must be a valid scene; an override the rules refuse
    /// gives [`Error::Override`], naming the override and carrying the rule's message.
    pub fn from_yaml_with(text: &str, overrides: &Overrides, source: &Path) -> Result<Scene> {
        let base = Scene::from_yaml(text, source)?;
        if overrides.is_empty() {
            return Ok(base);
        }
        let tree: serde_json::Value = parse(text, source)?;
        let merged = |keys: &mut dyn Iterator<Item = (&String, &serde_json::Value)>| {
            let mut tree = tree.clone();
            for (key, value) in keys {
                crate::input::overrides::set(&mut tree, key, value)?;
            }
            let json = serde_json::to_string_pretty(&tree).map_err(|e| e.to_string())?;
            let file: SceneFile = parse(&json, source).map_err(|e| without_location(&e))?;
            Validator::new(source)
                .scene(file)
                .map_err(|e| without_location(&e))
        };
        let refused = match merged(&mut overrides.iter()) {
            Ok(scene) => return Ok(with_locations_of(scene, &base, overrides, text)),
            Err(message) => message,
        };
        // Name the first override the rules refuse on its own; else the combination.
        for (key, value) in overrides {
            if let Err(message) = merged(&mut std::iter::once((key, value))) {
                return Err(Error::Override {
                    file: source.to_path_buf(),
                    key: key.clone(),
                    value: value.to_string(),
                    message,
                });
            }
        }
        Err(Error::Override {
            file: source.to_path_buf(),
            key: overrides.keys().cloned().collect::<Vec<_>>().join(", "),
            value: "(together)".into(),
            message: refused,
        })
    }
}

/// Parses YAML text into `T`, with the parser's line and column.
fn parse<T: serde::de::DeserializeOwned>(text: &str, source: &Path) -> Result<T> {
    serde_saphyr::from_str(text).map_err(|e| {
        let (line, column) = e
            .location()
            .map(|l| (l.line(), l.column()))
            .unwrap_or((0, 0));
        let (line, column, message) = crate::input::yaml_field::describe(
            text,
            &crate::input::yaml_field::parser_words(&e.to_string()),
            line,
            column,
        );
        Error::ParseScene {
            location: SourceLocation {
                file: source.to_path_buf(),
                line,
                column,
            },
            message,
        }
    })
}

/// A message about the merged tree, whose lines and columns are not the file's.
fn without_location(e: &Error) -> String {
    match e {
        Error::ParseScene { message, .. } => message.clone(),
        Error::InvalidScene(v) => format!("{} = {}: {}", v.field, v.value, v.allowed),
        other => other.to_string(),
    }
}

/// The scene of the merged tree, pointing at the file where the file still holds the value,
/// its warnings found again on the merged values.
fn with_locations_of(mut scene: Scene, base: &Scene, overrides: &Overrides, text: &str) -> Scene {
    let dt_overridden = overrides
        .keys()
        .any(|k| k == "time" || k.starts_with("time.dt"));
    scene.time.dt_location = if dt_overridden {
        SourceLocation::file(&base.source)
    } else {
        base.time.dt_location.clone()
    };
    let keys: Vec<&str> = overrides.keys().map(String::as_str).collect();
    scene.fields = FieldSpans::relocated(&scene.fields, &base.fields, &keys, &base.source);
    scene.warnings = crate::input::plausibility::warnings(&scene, Some(text));
    scene
}
