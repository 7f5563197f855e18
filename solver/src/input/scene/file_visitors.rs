//! The two scene keys read by hand-written visitors, for errors in plain words (an untagged
//! enum would say "did not match any variant"): `load.impactor.contact` ([`ContactFile`]) and
//! `time.end` ([`EndFile`]).

use std::borrow::Cow;

use schemars::{json_schema, JsonSchema, Schema, SchemaGenerator};
use serde::Deserialize;

use super::scene_file::{AfterContactFile, ContactFile, EndFile, SurfaceFile};

/// What [`ContactVisitor`] accepts: the word `nodal` or `surface`, or the mapping
/// `{surface: {...}}` of exactly that key (its value the options, `~` for none).
impl JsonSchema for ContactFile {
    fn schema_name() -> Cow<'static, str> {
        "ContactFile".into()
    }

    fn json_schema(generator: &mut SchemaGenerator) -> Schema {
        let mut options = generator.subschema_for::<Option<SurfaceFile>>();
        options.insert(
            "description".into(),
            "The rigid nose in contact with the plate's top surface, with its options (`~`: the defaults).".into(),
        );
        json_schema!({
            "description": "How the nose meets the plate: `nodal`, `surface` or `{surface: {enforcement, penalty_scale}}`.",
            "oneOf": [
                {
                    "type": "string",
                    "enum": ["nodal", "surface"],
                    "description": "`nodal`: the paper's contact law at one node; `surface`: the rigid nose in contact with the plate's top surface, with the default options.",
                },
                {
                    "type": "object",
                    "description": "The surface coupling with its options.",
                    "properties": {"surface": options},
                    "required": ["surface"],
                    "additionalProperties": false,
                },
            ],
        })
    }
}

/// What [`EndVisitor`] accepts: a number of seconds, or the mapping `{after_contact: s}`
/// ([`AfterContactFile`]). (A number in quotes reads as the number with a warning, as
/// everywhere in a scene; the schema leaves it out.)
impl JsonSchema for EndFile {
    fn schema_name() -> Cow<'static, str> {
        "EndFile".into()
    }

    fn json_schema(generator: &mut SchemaGenerator) -> Schema {
        let after_contact = generator.subschema_for::<AfterContactFile>();
        json_schema!({
            "description": "When the run ends: a time, s, or `{after_contact: s}`.",
            "oneOf": [
                {"type": "number", "description": "End time, s; > 0."},
                after_contact,
            ],
        })
    }
}

impl<'de> Deserialize<'de> for ContactFile {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        d.deserialize_any(ContactVisitor)
    }
}

/// Reads `nodal`, `surface` or `{surface: {...}}` with plain-word errors.
struct ContactVisitor;

impl<'de> serde::de::Visitor<'de> for ContactVisitor {
    type Value = ContactFile;
    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("`nodal`, `surface` or `{surface: {enforcement: penalty, penalty_scale: ...}}`")
    }
    fn visit_str<E: serde::de::Error>(self, v: &str) -> std::result::Result<ContactFile, E> {
        match v {
            "nodal" => Ok(ContactFile::Nodal),
            "surface" => Ok(ContactFile::Surface(SurfaceFile::default())),
            other => Err(E::custom(format!(
                "unknown contact `{other}`, expected `nodal`, `surface` or `{{surface: {{enforcement: kinematic | penalty, penalty_scale: ...}}}}` (penalty_scale only with enforcement: penalty)"
            ))),
        }
    }
    fn visit_map<A: serde::de::MapAccess<'de>>(
        self,
        mut map: A,
    ) -> std::result::Result<ContactFile, A::Error> {
        use serde::de::Error as _;
        let Some(key) = map.next_key::<String>()? else {
            return Err(A::Error::custom(
                "expected `{surface: {enforcement: kinematic | penalty, penalty_scale: ...}}` (penalty_scale only with enforcement: penalty)",
            ));
        };
        if key == "nodal" {
            return Err(A::Error::custom(
                "`nodal` takes no settings: write `contact: nodal` (its law is load.impactor.contact_law)",
            ));
        }
        if key != "surface" {
            return Err(A::Error::custom(format!(
                "unknown contact `{key}`, expected `nodal` or `surface: {{enforcement: kinematic | penalty, penalty_scale: ...}}` (penalty_scale only with enforcement: penalty)"
            )));
        }
        let options: Option<SurfaceFile> = map.next_value()?;
        if let Some(extra) = map.next_key::<String>()? {
            return Err(A::Error::custom(format!(
                "`{extra}` next to `surface`: give one contact"
            )));
        }
        Ok(ContactFile::Surface(options.unwrap_or_default()))
    }
}

impl<'de> Deserialize<'de> for EndFile {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        d.deserialize_any(EndVisitor)
    }
}

/// Reads `end:` with plain-word errors (an untagged enum would say "did not match any
/// variant").
struct EndVisitor;

impl<'de> serde::de::Visitor<'de> for EndVisitor {
    type Value = EndFile;
    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a number of seconds or {after_contact: seconds}")
    }
    fn visit_f64<E: serde::de::Error>(self, v: f64) -> std::result::Result<EndFile, E> {
        Ok(EndFile::At(v))
    }
    fn visit_i64<E: serde::de::Error>(self, v: i64) -> std::result::Result<EndFile, E> {
        Ok(EndFile::At(v as f64))
    }
    fn visit_u64<E: serde::de::Error>(self, v: u64) -> std::result::Result<EndFile, E> {
        Ok(EndFile::At(v as f64))
    }
    fn visit_str<E: serde::de::Error>(self, v: &str) -> std::result::Result<EndFile, E> {
        match v.trim().parse::<f64>() {
            // `inf`/`nan` in quotes are words here, as YAML's .inf/.nan are (refused by name).
            Ok(x) if x.is_finite() => Ok(EndFile::At(x)),
            _ => Err(E::custom(format!(
                "`{v}` is not a number: expected a number of seconds or {{after_contact: seconds}}"
            ))),
        }
    }
    fn visit_bool<E: serde::de::Error>(self, v: bool) -> std::result::Result<EndFile, E> {
        Err(E::custom(format!(
            "`{v}` is not a number: expected a number of seconds or {{after_contact: seconds}}"
        )))
    }
    fn visit_unit<E: serde::de::Error>(self) -> std::result::Result<EndFile, E> {
        Err(E::custom(
            "no value: expected a number of seconds or {after_contact: seconds}",
        ))
    }
    fn visit_none<E: serde::de::Error>(self) -> std::result::Result<EndFile, E> {
        self.visit_unit()
    }
    fn visit_seq<A: serde::de::SeqAccess<'de>>(
        self,
        _: A,
    ) -> std::result::Result<EndFile, A::Error> {
        Err(serde::de::Error::custom(
            "a list: expected a number of seconds or {after_contact: seconds}",
        ))
    }
    fn visit_map<A: serde::de::MapAccess<'de>>(
        self,
        map: A,
    ) -> std::result::Result<EndFile, A::Error> {
        let a = AfterContactFile::deserialize(serde::de::value::MapAccessDeserializer::new(map))?;
        Ok(EndFile::AfterContact(a))
    }
}
