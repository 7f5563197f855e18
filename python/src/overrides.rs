//! Overrides from Python (a JSON object of dotted scene keys) set on a scene, with one step
//! before the solver's own (`impact_solver::overrides::set`): a dotted key that goes through a
//! word of the scene that is the short form of a map keyed by it (`contact: surface`, short
//! for `contact: {surface: ~}`, the schema's forms) turns the word into that map, so that
//! `load.impactor.contact.surface.enforcement` can be set on a scene that writes `contact:
//! surface`. A key that goes through any other word is refused with the forms the scene
//! allows there and how to write the override.

use std::collections::BTreeSet;
use std::path::Path;

use pyo3::exceptions::PyValueError;
use pyo3::PyResult;
use serde_json::{Map, Value};

use impact_solver::overrides::{set, Overrides};
use impact_solver::{Error, Scene};

use crate::scene_keys;

/// The overrides' JSON text (None: none) as the solver's map.
pub fn parse(json: Option<&str>) -> PyResult<Overrides> {
    match json {
        Some(json) => {
            serde_json::from_str(json).map_err(|e| PyValueError::new_err(format!("overrides: {e}")))
        }
        None => Ok(Overrides::new()),
    }
}

/// The scene `text` (named `source`) with `overrides` set and validated, words that are the
/// short form of a map turned into it first (see the module's documentation); a refusal
/// names the overrides as given.
pub fn scene_with(
    text: &str,
    overrides: &Overrides,
    source: &Path,
) -> impact_solver::Result<Scene> {
    let (set, expanded) = through_words(text, overrides, source)?;
    Scene::from_yaml_with(text, &set, source).map_err(|e| match e {
        Error::Override {
            file,
            key,
            value,
            message,
        } if expanded.contains(&key) => {
            let (key, value) = as_given(overrides, &key).unwrap_or((key, value));
            Error::Override {
                file,
                key,
                value,
                message,
            }
        }
        other => other,
    })
}

/// The overrides as given under the word turned into a map at `at`: the key and its value,
/// or the keys and `(together)` (the solver's words for several keys refused together).
fn as_given(overrides: &Overrides, at: &str) -> Option<(String, String)> {
    let under: Vec<_> = (overrides.iter())
        .filter(|(k, _)| k.starts_with(&format!("{at}.")))
        .collect();
    match under.as_slice() {
        [] => None,
        [(key, value)] => Some((key.to_string(), value.to_string())),
        several => Some((
            several
                .iter()
                .map(|(k, _)| k.as_str())
                .collect::<Vec<_>>()
                .join(", "),
            "(together)".into(),
        )),
    }
}

/// The overrides with every key that goes through a word of the scene rewritten: the word's
/// key set to its map with those keys set in it; and the keys of the words so turned. The
/// same overrides when no key meets a word (or the scene does not parse: the solver then says
/// why).
fn through_words(
    text: &str,
    overrides: &Overrides,
    source: &Path,
) -> impact_solver::Result<(Overrides, BTreeSet<String>)> {
    let mut expanded = BTreeSet::new();
    let mut tree = match serde_saphyr::from_str::<Value>(text) {
        Ok(tree) if !overrides.is_empty() => tree,
        _ => return Ok((overrides.clone(), expanded)),
    };
    for (key, value) in overrides {
        if let Some((at, word)) = word_on_the_way(&tree, key) {
            let next = key[at.len() + 1..].split('.').next().unwrap_or_default();
            if next != word || !scene_keys::word_is_short_for_map(&at, &word) {
                return Err(Error::Override {
                    file: source.to_path_buf(),
                    key: key.clone(),
                    value: value.to_string(),
                    message: how_to_write(&at, &word, key, value),
                });
            }
            if let Some(node) = node_mut(&mut tree, &at) {
                *node = single(&word, Value::Null);
            }
            expanded.insert(at);
        }
        // As the solver sets it; a key it refuses is left for it to name.
        let _ = set(&mut tree, key, value);
    }
    let under = |key: &str| expanded.iter().any(|p| key.starts_with(&format!("{p}.")));
    let mut out: Overrides = (overrides.iter())
        .filter(|(k, _)| !under(k))
        .map(|(k, v)| (k.clone(), v.clone()))
        .collect();
    for at in &expanded {
        let node = node_mut(&mut tree, at)
            .map(|n| n.clone())
            .unwrap_or(Value::Null);
        out.insert(at.clone(), node);
    }
    Ok((out, expanded))
}

/// The first proper prefix of the dotted `key` whose value in `tree` is a word (a string),
/// with the word.
fn word_on_the_way(tree: &Value, key: &str) -> Option<(String, String)> {
    let parts: Vec<&str> = key.split('.').collect();
    let mut node = tree;
    for (i, part) in parts[..parts.len() - 1].iter().enumerate() {
        node = node.as_object()?.get(*part)?;
        if let Value::String(word) = node {
            return Some((parts[..=i].join("."), word.clone()));
        }
    }
    None
}

fn node_mut<'a>(tree: &'a mut Value, key: &str) -> Option<&'a mut Value> {
    key.split('.')
        .try_fold(tree, |node, part| node.as_object_mut()?.get_mut(part))
}

/// The refusal of `key` (= `value`) inside the word `word` at `at`: the forms the schema
/// gives `at`, and the override that sets it whole.
fn how_to_write(at: &str, word: &str, key: &str, value: &Value) -> String {
    let rest: Vec<&str> = key[at.len() + 1..].split('.').collect();
    let whole = (rest.iter().rev()).fold(value.clone(), |inner, part| single(part, inner));
    let forms = scene_keys::description(at)
        .map(|d| format!(" ({at}: {d})"))
        .unwrap_or_default();
    format!(
        "`{at}` is the word `{word}` in this scene, which holds no keys: to set `{key}`, set `{at}` whole, e.g. {}{forms}",
        single(at, whole)
    )
}

/// The map `{key: value}`.
fn single(key: &str, value: Value) -> Value {
    Value::Object(Map::from_iter([(key.to_string(), value)]))
}
