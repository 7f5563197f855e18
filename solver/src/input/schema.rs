//! The scene's JSON Schema, generated from the scene file's own types ([`SceneFile`] and its
//! parts derive [`schemars::JsonSchema`]; `end:` and `contact:`, read by hand-written
//! visitors, describe by hand what those accept), and the Markdown scene reference rendered
//! from it. Editors read the schema through the YAML language server's modeline, the first
//! line of a scene file: `# yaml-language-server: $schema=<relative path to`
//! [`SCHEMA_PATH`]`>`.
//!
//! The schema is JSON Schema draft 7 (what the YAML language server reads). `deny_unknown_fields`
//! is `additionalProperties: false`, each field's documentation its `description` (with its
//! unit and default), `default` the value an absent key takes. Quoted numbers and booleans,
//! which the reader takes with a warning (`crate::input::plausibility`), are left out: an
//! editor marks them as the solver warns. `impact schema` writes both files ([`write_files`]);
//! a test fails when the committed ones differ from what these functions make.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use schemars::generate::SchemaSettings;
use serde_json::{Map, Value};

use crate::input::scene::SceneFile;

/// The schema's file, relative to the repository root.
pub const SCHEMA_PATH: &str = "solver/scene.schema.json";
/// The Markdown scene reference's file, relative to the repository root.
pub const REFERENCE_PATH: &str = "docs/scene-reference.md";

/// The scene's JSON Schema (draft 7), as a JSON value.
pub fn scene_schema() -> Value {
    let generator = SchemaSettings::draft07().into_generator();
    let mut schema = Value::from(generator.into_root_schema_for::<SceneFile>());
    if let Some(root) = schema.as_object_mut() {
        root.insert(
            "$comment".into(),
            Value::from(format!(
                "Generated from the scene's types (solver/src/input/scene/) by `impact schema`; do not edit. Reference: {REFERENCE_PATH}."
            )),
        );
    }
    tidy(&mut schema);
    describe_variant_keys(&mut schema);
    schema
}

/// Descriptions as an editor shows them (a doc comment's lines joined, its paragraphs kept,
/// rustdoc's link brackets left out), and no `default: null` (an absent optional key is
/// none: the description says so).
fn tidy(value: &mut Value) {
    match value {
        Value::Object(map) => {
            if map.get("default").is_some_and(Value::is_null) {
                map.remove("default");
            }
            if let Some(Value::String(text)) = map.get_mut("description") {
                let paragraphs: Vec<String> = text
                    .split("\n\n")
                    .map(|p| p.split_whitespace().collect::<Vec<_>>().join(" "))
                    .collect();
                *text = paragraphs
                    .join("\n\n")
                    .replace("[`", "`")
                    .replace("`]", "`");
            }
            map.values_mut().for_each(tidy);
        }
        Value::Array(items) => items.iter_mut().for_each(tidy),
        _ => {}
    }
}

/// [`scene_schema`] as pretty JSON with a trailing newline; keys in sorted order (the same
/// text on every run).
pub fn scene_schema_json() -> String {
    let mut text = serde_json::to_string_pretty(&scene_schema()).expect("a JSON value prints");
    text.push('\n');
    text
}

/// Writes [`SCHEMA_PATH`] and [`REFERENCE_PATH`] under `repo_root`; returns their paths.
pub fn write_files(repo_root: &Path) -> std::io::Result<Vec<PathBuf>> {
    let files = [
        (repo_root.join(SCHEMA_PATH), scene_schema_json()),
        (repo_root.join(REFERENCE_PATH), scene_reference_markdown()),
    ];
    let mut written = Vec::new();
    for (path, text) in files {
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent)?;
        }
        // Written beside, then renamed over: an interrupted write leaves the old file whole.
        let staged = path.with_extension("partial");
        std::fs::write(&staged, text)?;
        std::fs::rename(&staged, &path)?;
        written.push(path);
    }
    Ok(written)
}

/// An externally tagged enum's variant is an object of one key whose documentation is the
/// variant's: it is given to the key too, so that every property carries its description.
fn describe_variant_keys(value: &mut Value) {
    match value {
        Value::Object(map) => {
            let description = map.get("description").cloned();
            if let (Some(description), Some(Value::Object(properties))) =
                (description, map.get_mut("properties"))
            {
                if properties.len() == 1 {
                    for property in properties.values_mut() {
                        if let Value::Object(p) = property {
                            p.entry("description").or_insert(description.clone());
                        }
                    }
                }
            }
            map.values_mut().for_each(describe_variant_keys);
        }
        Value::Array(items) => items.iter_mut().for_each(describe_variant_keys),
        _ => {}
    }
}

/// The Markdown scene reference: a table per object of the scene (its keys as dotted paths,
/// their type or allowed values, default and description), rendered from [`scene_schema`].
pub fn scene_reference_markdown() -> String {
    let schema = scene_schema();
    let reference = Reference::of(&schema);
    let mut tables = Vec::new();
    reference.object("", &schema, &mut tables);
    let mut out = String::new();
    out.push_str("# Scene reference\n\n");
    out.push_str(
        "<!-- Generated from the scene's types (solver/src/input/scene/) by `impact schema`; do not edit. -->\n\n",
    );
    let _ = writeln!(
        out,
        "Every key of a scene file, object by object, in SI units. Editors that read the YAML \
         language server's modeline check and complete scene files against the JSON Schema \
         `{SCHEMA_PATH}`: a scene file's first line is \
         `# yaml-language-server: $schema=<relative path to {SCHEMA_PATH}>`.\n"
    );
    let _ = writeln!(
        out,
        "A key is required where its default says so; `—` is no default (the key is optional \
         and absent means none). `A | B` are the words allowed; \"one key of\" is a mapping \
         with exactly one of the keys listed.\n"
    );
    for table in tables {
        let title = if table.path.is_empty() {
            "The scene".to_string()
        } else {
            format!("`{}`", table.path)
        };
        let _ = writeln!(out, "## {title}\n");
        if !table.description.is_empty() {
            let _ = writeln!(out, "{}\n", table.description);
        }
        out.push_str("| key | type / allowed values | default | description |\n");
        out.push_str("| --- | --- | --- | --- |\n");
        for row in table.rows {
            let _ = writeln!(
                out,
                "| `{}` | {} | {} | {} |",
                row.key,
                cell(&row.kind),
                cell(&row.default),
                cell(&row.description)
            );
        }
        out.push('\n');
    }
    out.truncate(out.trim_end().len());
    out.push('\n');
    out
}

/// One object's table.
struct Table {
    path: String,
    description: String,
    rows: Vec<Row>,
}

struct Row {
    key: String,
    kind: String,
    default: String,
    description: String,
}

/// A Markdown table cell: one line, `|` escaped.
fn cell(text: &str) -> String {
    text.split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .replace('|', "\\|")
}

fn join(path: &str, key: &str) -> String {
    if path.is_empty() {
        key.to_string()
    } else {
        format!("{path}.{key}")
    }
}

/// The schema's definitions, to resolve `$ref`.
struct Reference<'a> {
    definitions: Option<&'a Map<String, Value>>,
}

impl<'a> Reference<'a> {
    fn of(root: &'a Value) -> Reference<'a> {
        Reference {
            definitions: root.get("definitions").and_then(Value::as_object),
        }
    }

    /// `schema` with its `$ref` (or a lone `allOf: [$ref]`) followed, and an optional value's
    /// `null` alternative left out.
    fn resolve(&self, schema: &'a Value) -> &'a Value {
        if let Some(target) = schema.get("$ref").and_then(Value::as_str) {
            let name = target.rsplit('/').next().unwrap_or(target);
            if let Some(found) = self.definitions.and_then(|d| d.get(name)) {
                return self.resolve(found);
            }
        }
        for key in ["allOf", "anyOf", "oneOf"] {
            if let Some(Value::Array(items)) = schema.get(key) {
                let not_null: Vec<&Value> = items.iter().filter(|s| !is_null(s)).collect();
                if not_null.len() == 1 && (key == "allOf" || not_null.len() < items.len()) {
                    return self.resolve(not_null[0]);
                }
            }
        }
        schema
    }

    /// The alternatives of `schema` (its `oneOf` or `anyOf`, `null` left out), if it has some.
    fn alternatives(&self, schema: &'a Value) -> Option<Vec<&'a Value>> {
        let schema = self.resolve(schema);
        ["oneOf", "anyOf"].iter().find_map(|key| {
            schema.get(*key).and_then(Value::as_array).map(|items| {
                items
                    .iter()
                    .filter(|s| !is_null(s))
                    .map(|s| self.resolve(s))
                    .collect()
            })
        })
    }

    /// The table of the object `schema` at `path`, then the tables of its keys' objects.
    fn object(&self, path: &str, schema: &'a Value, tables: &mut Vec<Table>) {
        let schema = self.resolve(schema);
        let Some(properties) = self.properties(schema) else {
            return;
        };
        let required: Vec<&str> = schema
            .get("required")
            .and_then(Value::as_array)
            .map(|r| r.iter().filter_map(Value::as_str).collect())
            .unwrap_or_default();
        // A choice of one-key mappings (an externally tagged enum): give exactly one key.
        let choice = schema.get("properties").is_none()
            && self.alternatives(schema).is_some_and(|alternatives| {
                alternatives.iter().all(|a| {
                    a.get("properties")
                        .and_then(Value::as_object)
                        .is_some_and(|p| p.len() == 1)
                })
            });
        let mut rows = Vec::new();
        for (key, property) in &properties {
            let resolved = self.resolve(property);
            let default = match property.get("default").or(resolved.get("default")) {
                _ if choice => "one key of these".to_string(),
                Some(Value::Null) | None if required.contains(&key.as_str()) => {
                    "required".to_string()
                }
                Some(Value::Null) | None => "—".to_string(),
                Some(value) => format!("`{}`", shown(value)),
            };
            rows.push(Row {
                key: join(path, key),
                kind: self.kind(property),
                default,
                description: description(property)
                    .or(description(resolved))
                    .unwrap_or_default(),
            });
        }
        tables.push(Table {
            path: path.to_string(),
            description: if path.is_empty() {
                description(schema).unwrap_or_default()
            } else {
                String::new()
            },
            rows,
        });
        for (key, property) in properties {
            self.children(&join(path, &key), property, tables);
        }
    }

    /// The keys of an object schema, or of a choice of one-key objects (an externally
    /// tagged enum: `load`, `hardening`, `rate`, `contact_law`, `{surface: ...}`) and of the
    /// object alternatives of a choice (`time.end: {after_contact}`).
    fn properties(&self, schema: &'a Value) -> Option<Vec<(String, &'a Value)>> {
        if let Some(Value::Object(p)) = schema.get("properties") {
            return Some(p.iter().map(|(k, v)| (k.clone(), v)).collect());
        }
        let mut keys = Vec::new();
        for alternative in self.alternatives(schema)? {
            if let Some(Value::Object(p)) = alternative.get("properties") {
                keys.extend(p.iter().map(|(k, v)| (k.clone(), v)));
            }
        }
        (!keys.is_empty()).then_some(keys)
    }

    /// The tables under a key: its object, its map's values (`NAME`), its choice's objects.
    fn children(&self, path: &str, property: &'a Value, tables: &mut Vec<Table>) {
        let schema = self.resolve(property);
        if let Some(Value::Object(_)) = schema.get("additionalProperties") {
            let values = &schema["additionalProperties"];
            self.object(&format!("{path}.NAME"), values, tables);
        } else if self.properties(schema).is_some() {
            self.object(path, schema, tables);
        }
    }

    /// A key's type or allowed values, in words.
    fn kind(&self, property: &'a Value) -> String {
        let schema = self.resolve(property);
        if let Some(words) = words(schema) {
            return words;
        }
        if let Some(alternatives) = self.alternatives(schema) {
            if alternatives.iter().all(|a| words(a).is_some()) {
                let all: Vec<String> = alternatives.iter().filter_map(|a| words(a)).collect();
                return all.join(" | ");
            }
            let tagged = alternatives.iter().all(|a| {
                a.get("properties")
                    .and_then(Value::as_object)
                    .is_some_and(|p| p.len() == 1)
                    && a.get("required").is_some()
            });
            if tagged {
                let keys: Vec<String> = alternatives
                    .iter()
                    .filter_map(|a| a["properties"].as_object())
                    .flat_map(|p| p.keys().map(|k| format!("`{k}`")))
                    .collect();
                return format!("one key of {}", keys.join(", "));
            }
            let kinds: Vec<String> = alternatives.iter().map(|a| self.kind(a)).collect();
            return kinds.join(" or ");
        }
        match schema.get("type") {
            Some(Value::String(t)) if t == "object" => {
                if schema
                    .get("additionalProperties")
                    .is_some_and(Value::is_object)
                {
                    "mapping of NAME to mapping".to_string()
                } else {
                    "mapping".to_string()
                }
            }
            Some(Value::String(t)) if t == "array" => match schema.get("items") {
                Some(Value::Array(items)) => {
                    let each: Vec<String> = items.iter().map(|i| self.kind(i)).collect();
                    format!("list of [{}]", each.join(", "))
                }
                _ => self.plain_kind(schema),
            },
            Some(Value::Array(types)) => types
                .iter()
                .filter_map(Value::as_str)
                .filter(|t| *t != "null")
                .collect::<Vec<_>>()
                .join(" or "),
            _ => self.plain_kind(schema),
        }
    }

    /// A type without alternatives or words: its JSON type, a fixed-length list as
    /// `[number, number]`.
    fn plain_kind(&self, schema: &'a Value) -> String {
        match schema.get("type") {
            Some(Value::String(t)) if t == "array" => {
                let n = schema
                    .get("minItems")
                    .filter(|n| schema.get("maxItems") == Some(*n));
                match (n.and_then(Value::as_u64), schema.get("items")) {
                    (Some(n), Some(items)) if items.is_object() => {
                        let each = vec![self.kind(items); n as usize];
                        format!("[{}]", each.join(", "))
                    }
                    (None, Some(items)) if items.is_object() => {
                        format!("list of {}", self.kind(items))
                    }
                    _ => "list".to_string(),
                }
            }
            Some(Value::String(t)) => t.clone(),
            _ => "any".to_string(),
        }
    }
}

/// The words a schema allows (`const` or `enum`), as `` `a` | `b` ``.
fn words(schema: &Value) -> Option<String> {
    if let Some(value) = schema.get("const") {
        return Some(format!("`{}`", shown(value)));
    }
    let values = schema.get("enum")?.as_array()?;
    let words: Vec<String> = values
        .iter()
        .filter(|v| !v.is_null())
        .map(|v| format!("`{}`", shown(v)))
        .collect();
    Some(words.join(" | "))
}

fn is_null(schema: &Value) -> bool {
    schema.get("type").and_then(Value::as_str) == Some("null")
}

fn description(schema: &Value) -> Option<String> {
    schema
        .get("description")
        .and_then(Value::as_str)
        .map(str::to_string)
}

/// A JSON value as written in a scene: a string without quotes.
fn shown(value: &Value) -> String {
    match value {
        Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}
