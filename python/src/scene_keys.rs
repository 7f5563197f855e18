//! The scene's keys as its JSON Schema gives them (`impact_solver::input::schema`, the file
//! `solver/scene.schema.json`): the schema of a dotted key, the keys allowed where a dotted key
//! names none, and whether a word (`contact: surface`) is the short form of a map keyed by it
//! (`contact: {surface: ~}`).

use std::sync::OnceLock;

use serde_json::Value;

fn schema() -> &'static Value {
    static SCHEMA: OnceLock<Value> = OnceLock::new();
    SCHEMA.get_or_init(impact_solver::input::schema::scene_schema)
}

/// The forms a schema node allows: its `$ref` resolved, its `anyOf`, `oneOf` and `allOf`
/// flattened.
fn forms(node: &'static Value) -> Vec<&'static Value> {
    let mut out = Vec::new();
    collect_forms(node, &mut out);
    out
}

fn collect_forms(node: &'static Value, out: &mut Vec<&'static Value>) {
    if let Some(target) = node
        .get("$ref")
        .and_then(Value::as_str)
        .and_then(|r| r.strip_prefix("#/definitions/"))
        .and_then(|name| schema()["definitions"].get(name))
    {
        return collect_forms(target, out);
    }
    let mut combined = false;
    for key in ["anyOf", "oneOf", "allOf"] {
        for inner in node
            .get(key)
            .and_then(Value::as_array)
            .into_iter()
            .flatten()
        {
            combined = true;
            collect_forms(inner, out);
        }
    }
    if !combined || node.get("properties").is_some() {
        out.push(node);
    }
}

/// The schema of the value at `part` inside any of the forms `of`: its own property, or the
/// schema every key of a free map takes (`output.probes.NAME`).
fn child(of: &[&'static Value], part: &str) -> Vec<&'static Value> {
    of.iter()
        .filter_map(|form| {
            let named = form.get("properties").and_then(|p| p.get(part));
            named.or_else(|| form.get("additionalProperties").filter(|a| a.is_object()))
        })
        .flat_map(forms)
        .collect()
}

/// The keys the forms `of` name (sorted, each once).
fn keys_of(of: &[&'static Value]) -> Vec<String> {
    let mut keys: Vec<String> = of
        .iter()
        .filter_map(|form| form.get("properties").and_then(Value::as_object))
        .flat_map(|p| p.keys().cloned())
        .collect();
    keys.sort();
    keys.dedup();
    keys
}

/// A dotted key that names no value of the scene: the part the schema does not know, where,
/// and the keys it allows there.
pub struct Unknown {
    /// The dotted key up to the unknown part (empty: the scene's top level).
    pub parent: String,
    pub part: String,
    pub allowed: Vec<String>,
}

impl std::fmt::Display for Unknown {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let parent = if self.parent.is_empty() {
            "the scene".to_string()
        } else {
            format!("`{}`", self.parent)
        };
        if self.allowed.is_empty() {
            write!(
                f,
                "{parent} holds a value, no keys: `{}` is not a scene key",
                self.part
            )
        } else {
            write!(
                f,
                "{parent} has no key `{}`; its keys: {}",
                self.part,
                self.allowed.join(", ")
            )
        }
    }
}

/// The forms of the value at the dotted `key`, or where the schema stops knowing it.
pub fn lookup(key: &str) -> Result<Vec<&'static Value>, Unknown> {
    let mut at = forms(schema());
    let mut parent = String::new();
    for part in key.split('.') {
        let next = child(&at, part);
        if next.is_empty() {
            return Err(Unknown {
                parent,
                part: part.to_string(),
                allowed: keys_of(&at),
            });
        }
        if !parent.is_empty() {
            parent.push('.');
        }
        parent.push_str(part);
        at = next;
    }
    Ok(at)
}

/// Whether the word `word` at the dotted `key` is the short form of the map `{word: ~}`: the
/// schema takes both the word and a map whose key `word` may be null (its options' defaults),
/// as `load.impactor.contact` takes `surface` and `{surface: ~}`.
pub fn word_is_short_for_map(key: &str, word: &str) -> bool {
    let Ok(at) = lookup(key) else {
        return false;
    };
    let names_word = |form: &&Value| {
        let listed = form.get("enum").and_then(Value::as_array);
        listed.is_some_and(|e| e.iter().any(|w| w == word))
            || form.get("const").is_some_and(|w| w == word)
    };
    let null_allowed = |forms: Vec<&Value>| {
        forms
            .iter()
            .any(|f| f.get("type").is_some_and(|t| t == "null"))
    };
    at.iter().any(names_word) && null_allowed(child(&at, word))
}

/// The description the schema gives the value at the dotted `key` (its forms and default).
pub fn description(key: &str) -> Option<String> {
    let mut node = schema();
    let mut at = forms(node);
    for part in key.split('.') {
        let found = at
            .iter()
            .find_map(|f| f.get("properties").and_then(|p| p.get(part)))?;
        node = found;
        at = forms(found);
    }
    node.get("description")
        .and_then(Value::as_str)
        .map(str::to_string)
}
