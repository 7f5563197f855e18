//! The two scene keys read by hand-written visitors, for errors in plain words (an untagged
//! enum would say "did not match any variant"): `load.impactor.contact` ([`ContactFile`]) and
//! `time.end` ([`EndFile`]).

use serde::Deserialize;

use super::scene_file::{AfterContactFile, ContactFile, EndFile, SurfaceFile};

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
        f.write_str("`nodal`, `surface` or `{surface: {penalty_scale: ...}}`")
    }
    fn visit_str<E: serde::de::Error>(self, v: &str) -> std::result::Result<ContactFile, E> {
        match v {
            "nodal" => Ok(ContactFile::Nodal),
            "surface" => Ok(ContactFile::Surface(SurfaceFile::default())),
            other => Err(E::custom(format!(
                "unknown contact `{other}`, expected `nodal`, `surface` or `{{surface: {{penalty_scale: ...}}}}`"
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
                "expected `{surface: {penalty_scale: ...}}`",
            ));
        };
        if key != "surface" {
            return Err(A::Error::custom(format!(
                "unknown contact `{key}`, expected `surface: {{penalty_scale: ...}}`"
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
