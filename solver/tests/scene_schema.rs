//! The scene's JSON Schema and its Markdown reference against the repository:
//! - the committed `solver/scene.schema.json` and `docs/scene-reference.md` are what the
//!   scene's types make now (else: run `impact schema` to update them);
//! - every property of the schema has a description, and every number its unit;
//! - every scene file of the repository starts with the YAML language server's modeline
//!   naming it by a relative path that resolves;
//! - every scene reads back, bit for bit, from the text `Scene::to_yaml` writes of it.
//! That every scene file, and every such text, validates against the schema is judged by the
//! reference implementation of JSON Schema, in Python (python/tests/test_scene_schema.py): the
//! Rust crate `jsonschema` and what it pulled in took 100 s of the gate's compile (measured
//! 2026-11-30).

use std::path::{Path, PathBuf};

use impact_solver::input::schema::{
    scene_reference_markdown, scene_schema, scene_schema_json, REFERENCE_PATH, SCHEMA_PATH,
};
use serde_json::Value;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .canonicalize()
        .expect("the repository root")
}

/// The modeline of a scene file in `dir`: the schema by its path relative to `dir`.
fn modeline_prefix() -> &'static str {
    "# yaml-language-server: $schema="
}

fn yaml_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let mut entries: Vec<PathBuf> = entries.flatten().map(|e| e.path()).collect();
    entries.sort();
    for p in entries {
        let name = p.file_name().unwrap_or_default().to_string_lossy();
        if p.is_dir() {
            if !(name.starts_with('.') || name == "target" || name == "node_modules") {
                yaml_files(&p, out);
            }
        } else if name.ends_with(".yaml") || name.ends_with(".yml") {
            out.push(p);
        }
    }
}

/// A YAML file's document as JSON.
fn document(path: &Path) -> Option<Value> {
    let text = std::fs::read_to_string(path).ok()?;
    serde_saphyr::from_str::<Value>(&text).ok()
}

/// The repository's scene files (relative paths): the YAML files whose document is a mapping
/// with `plate`, `material` and `load` (case.yaml files are cases; the
/// uncertainty-quantification declarations and the bad-input list are not scenes).
fn scene_files() -> Vec<String> {
    let root = root();
    let mut files = Vec::new();
    yaml_files(&root, &mut files);
    files
        .into_iter()
        .filter(|p| p.file_name().is_some_and(|n| n != "case.yaml"))
        .filter_map(|p| {
            let doc = document(&p)?;
            let map = doc.as_object()?;
            let scene = ["plate", "material", "load"]
                .iter()
                .all(|k| map.contains_key(*k));
            let rel = p
                .strip_prefix(&root)
                .ok()?
                .to_string_lossy()
                .replace('\\', "/");
            scene.then_some(rel)
        })
        .collect()
}

#[test]
fn the_committed_schema_and_reference_are_up_to_date() {
    let root = root();
    for (path, made) in [
        (SCHEMA_PATH, scene_schema_json()),
        (REFERENCE_PATH, scene_reference_markdown()),
    ] {
        let committed = std::fs::read_to_string(root.join(path)).unwrap_or_default();
        assert!(
            committed == made,
            "{path} is not what the scene's types make: run `impact schema` to update it (or `cargo test -p impact-solver --release --test scene_schema -- --ignored`)"
        );
    }
    assert_eq!(scene_schema_json(), scene_schema_json(), "deterministic");
}

/// Every `properties` entry of `schema`, with its dotted path.
fn properties<'a>(path: &str, schema: &'a Value, out: &mut Vec<(String, &'a Value)>) {
    match schema {
        Value::Object(map) => {
            if let Some(Value::Object(props)) = map.get("properties") {
                for (key, p) in props {
                    out.push((format!("{path}.{key}"), p));
                }
            }
            for (key, value) in map {
                properties(&format!("{path}/{key}"), value, out);
            }
        }
        Value::Array(items) => {
            for (i, value) in items.iter().enumerate() {
                properties(&format!("{path}/{i}"), value, out);
            }
        }
        _ => {}
    }
}

/// The SI units a number's description names (`(-)`: none), each written after `, `, ` ` or
/// `(` and before `;`, `,`, `.` or `)`.
const UNITS: [&str; 11] = [
    "m", "m/s", "kg", "kg/m^3", "s", "Pa", "N", "K", "1/s", "J/(kg K)", "-",
];

fn names_a_unit(description: &str) -> bool {
    UNITS.iter().any(|u| {
        [", ", " ", "("].iter().any(|before| {
            [";", ",", ".", ")"]
                .iter()
                .any(|after| description.contains(&format!("{before}{u}{after}")))
        })
    })
}

#[test]
fn every_property_has_a_description_and_every_number_its_unit() {
    let schema = scene_schema();
    let mut all = Vec::new();
    properties("", &schema, &mut all);
    assert!(all.len() > 60, "only {} properties", all.len());
    let definitions = schema["definitions"].as_object().unwrap();
    let resolve = |p: &Value| -> Value {
        let target = p
            .get("$ref")
            .or_else(|| p.get("allOf").and_then(|a| a[0].get("$ref")));
        match target.and_then(Value::as_str) {
            Some(r) => definitions[r.rsplit('/').next().unwrap()].clone(),
            None => p.clone(),
        }
    };
    let mut missing = Vec::new();
    let mut unitless = Vec::new();
    for (path, p) in &all {
        let Some(description) = p.get("description").and_then(Value::as_str) else {
            missing.push(path.clone());
            continue;
        };
        let target = resolve(p);
        let number = |t: &Value| {
            let types = match t.get("type") {
                Some(Value::String(s)) => vec![s.as_str()],
                Some(Value::Array(a)) => a.iter().filter_map(Value::as_str).collect(),
                _ => Vec::new(),
            };
            types.contains(&"number") || types.contains(&"integer")
        };
        if number(&target) && !names_a_unit(description) {
            unitless.push(format!("{path}: {description}"));
        }
    }
    assert!(
        missing.is_empty(),
        "properties without a description: {missing:#?}"
    );
    assert!(unitless.is_empty(), "numbers without a unit: {unitless:#?}");
}

#[test]
fn every_scene_file_starts_with_the_schema_modeline() {
    let root = root();
    let schema = root
        .join(SCHEMA_PATH)
        .canonicalize()
        .expect("the schema file");
    let mut wrong = Vec::new();
    for rel in scene_files() {
        let path = root.join(&rel);
        let text = std::fs::read_to_string(&path).unwrap();
        let first = text.lines().next().unwrap_or_default();
        let Some(target) = first.strip_prefix(modeline_prefix()) else {
            wrong.push(format!(
                "{rel}: the first line is not the modeline: {first:?}"
            ));
            continue;
        };
        let resolved = path.parent().unwrap().join(target.trim()).canonicalize();
        if resolved.as_ref().ok() != Some(&schema) {
            wrong.push(format!("{rel}: {target} does not resolve to {SCHEMA_PATH}"));
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

/// Writes the two files (what `impact schema` does): `cargo test -p impact-solver --release
/// --test scene_schema -- --ignored`.
#[test]
#[ignore = "writes solver/scene.schema.json and docs/scene-reference.md"]
fn write_files() {
    let written =
        impact_solver::input::schema::write_files(&root()).expect("the files are written");
    assert_eq!(written.len(), 2);
}

/// What a scene is, without where it came from (the file, the fields' spans, the warnings).
fn without_origin(
    mut s: impact_solver::Scene,
    like: &impact_solver::Scene,
) -> impact_solver::Scene {
    s.source = Default::default();
    s.fields = Default::default();
    s.warnings.clear();
    s.time.dt_location = like.time.dt_location.clone();
    s
}

/// `Scene::to_yaml` (what another code's adapter reads, `adapters/README.md`) reads back to
/// the same scene, bit for bit, for every scene file of the repository that the reader
/// accepts (the text's validation against the schema: python/tests/test_scene_schema.py).
/// Fails for a key written under a wrong name, a default left out that differs from the
/// reader's, or a number printed short of its bits.
#[test]
fn every_scene_reads_back_from_its_resolved_text() {
    let root = root();
    let mut read_back = 0;
    let mut wrong = Vec::new();
    for path in scene_files() {
        let Ok(scene) = impact_solver::Scene::from_file(&root.join(&path)) else {
            continue; // the bad-input bases and the refused examples
        };
        let text = scene.to_yaml();
        match impact_solver::Scene::from_yaml(&text, Path::new("resolved.yaml")) {
            Ok(again)
                if without_origin(again.clone(), &scene)
                    == without_origin(scene.clone(), &scene) =>
            {
                read_back += 1
            }
            Ok(_) => wrong.push(format!("{path}: reads back to another scene:\n{text}")),
            Err(e) => wrong.push(format!("{path}: refused on reading back: {e}\n{text}")),
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n\n"));
    assert!(read_back > 60, "only {read_back} scenes read back");
}
