//! Overrides of a scene: values set at the scene's own dotted YAML paths (`load.impactor.mass`,
//! `time.dt.cfl`, `mesh.element`) on the YAML tree BEFORE the scene is validated, so an
//! override obeys every rule a scene file does and there is one scene language.

use std::collections::BTreeMap;

use serde_json::{Map, Value};

/// Overrides by dotted YAML path of the scene, e.g. `{"time.dt.cfl": 0.5}`.
pub type Overrides = BTreeMap<String, Value>;

/// Maps of the scene whose single key chooses a variant (`time.dt: {cfl | fixed}`,
/// `load: {impactor | pulse | traction}`, ...): setting one key replaces the others.
const ONE_OF: [&str; 5] = [
    "load",
    "load.impactor.contact_law",
    "material.plasticity.hardening",
    "time.dt",
    "time.end",
];

/// Keys beside the variant of a one-of map (`time.dt: {cfl | fixed, estimate, update}`): kept when
/// the variant changes, and setting one keeps the variant.
const BESIDE_THE_VARIANT: [(&str, &str); 2] = [("time.dt", "estimate"), ("time.dt", "update")];

/// Sets `value` at the dotted `key` of the YAML `tree`, creating the maps on the way
/// (the scene's parser then refuses keys it does not know). A word on the way that the key
/// goes on through by its own name (`contact: surface` and the key
/// `load.impactor.contact.surface.enforcement`) is the short form of the map keyed by it
/// (`contact: {surface: ~}`, the schema's forms) and becomes that map.
pub fn set(tree: &mut Value, key: &str, value: &Value) -> Result<(), String> {
    if key.is_empty() || key.split('.').any(str::is_empty) {
        return Err("an override key is a dotted path of the scene, e.g. time.dt.cfl".into());
    }
    let parts: Vec<&str> = key.split('.').collect();
    let mut node = tree;
    let mut path = String::new();
    for (i, part) in parts.iter().copied().enumerate() {
        let one_of = ONE_OF.contains(&path.as_str());
        if node.as_str() == Some(part) && i + 1 < parts.len() {
            *node = Value::Object(Map::from_iter([(part.to_string(), Value::Null)]));
        }
        // An absent node (null), or a plain value where a variant is chosen (`time.end: 0.003`
        // when `time.end.after_contact` is set), becomes an empty map; another plain value
        // where the key goes on is refused (no copy of the tree is made on the way).
        if !(node.is_null() || node.is_object() || one_of) {
            return Err(how_to_write(&path, node, &parts, value));
        }
        if !node.is_object() {
            *node = Value::Object(Map::new());
        }
        let Value::Object(map) = node else {
            return Err(format!("`{path}` could not be opened as a map"));
        };
        if one_of && !map.contains_key(part) {
            let beside = |k: &str| BESIDE_THE_VARIANT.contains(&(path.as_str(), k));
            if !beside(part) {
                map.retain(|k, _| beside(k));
            }
        }
        if !path.is_empty() {
            path.push('.');
        }
        path.push_str(part);
        node = map
            .entry(part.to_string())
            .or_insert(Value::Object(Map::new()));
    }
    *node = value.clone();
    Ok(())
}

/// The refusal of `parts` (= `value`) inside the plain value `held` at `path`: the override
/// that sets `path` whole.
fn how_to_write(path: &str, held: &Value, parts: &[&str], value: &Value) -> String {
    let depth = if path.is_empty() {
        0
    } else {
        path.split('.').count()
    };
    let whole =
        (parts[depth..].iter().rev()).fold(value.clone(), |inner, part| json_map(part, inner));
    format!(
        "`{path}` is {held} in this scene, which holds no keys: to set `{}`, set `{path}` whole, e.g. `{path}: {whole}`",
        parts.join(".")
    )
}

fn json_map(key: &str, value: Value) -> Value {
    Value::Object(Map::from_iter([(key.to_string(), value)]))
}

#[cfg(test)]
mod tests {
    //! Checks the tree edits against hand-written expected trees.
    use super::*;
    use serde_json::json;

    #[test]
    fn sets_creates_and_replaces_variants() {
        let mut t = json!({"time": {"end": 0.003, "dt": {"fixed": 1e-8}}, "mesh": {"nx": 4}});
        set(&mut t, "time.dt.cfl", &json!(0.5)).unwrap();
        set(&mut t, "time.end.after_contact", &json!(2e-4)).unwrap();
        set(&mut t, "mesh.nx", &json!(8)).unwrap();
        set(&mut t, "output.every", &json!(1e-6)).unwrap();
        assert_eq!(
            t,
            json!({"time": {"end": {"after_contact": 2e-4}, "dt": {"cfl": 0.5}},
                   "mesh": {"nx": 8}, "output": {"every": 1e-6}})
        );
        assert!(set(&mut t, "mesh.nx.more", &json!(1)).is_err());
        assert!(set(&mut t, "mesh..nx", &json!(1)).is_err());
    }

    /// A word the key goes on through by its name becomes its map; through another word the
    /// refusal says how to set the whole key.
    #[test]
    fn a_word_that_is_short_for_its_map_opens() {
        let mut t = json!({"load": {"impactor": {"contact": "surface", "mass": 1.0}}});
        let key = "load.impactor.contact.surface.enforcement";
        set(&mut t, key, &json!("penalty")).unwrap();
        assert_eq!(
            t["load"]["impactor"]["contact"],
            json!({"surface": {"enforcement": "penalty"}})
        );
        let mut t = json!({"load": {"impactor": {"contact": "nodal"}}});
        let e = set(&mut t, key, &json!("penalty")).unwrap_err();
        assert!(
            e.contains("`load.impactor.contact` is \"nodal\" in this scene")
                && e.contains(r#"`load.impactor.contact: {"surface":{"enforcement":"penalty"}}`"#),
            "{e}"
        );
        // The word itself can still be replaced.
        set(&mut t, "load.impactor.contact", &json!("surface")).unwrap();
        assert_eq!(t["load"]["impactor"]["contact"], json!("surface"));
    }
}
