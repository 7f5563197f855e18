//! Where each field of a scene was written (`file:line:column`), kept with the validated
//! scene so that what is checked after validation (the time step, the plausibility warnings)
//! points at the value it names.

use std::collections::BTreeMap;
use std::path::Path;

use crate::input::error::SourceLocation;

/// The location of each field the validator read, by its dotted name
/// (`material.density`, `time.dt.cfl`), with its value when it is a number.
#[derive(Debug, Clone, Default)]
pub struct FieldSpans(BTreeMap<String, Read>);

/// One field as read: where, and its value when it is a number.
#[derive(Debug, Clone, PartialEq)]
pub struct Read {
    pub at: SourceLocation,
    pub value: Option<f64>,
    /// Whether the field's rule refuses 0 (a strictly positive quantity).
    pub positive: bool,
}

/// Where a value was written is not part of the scene: two scenes with the same values are
/// equal whatever their layout.
impl PartialEq for FieldSpans {
    fn eq(&self, _: &FieldSpans) -> bool {
        true
    }
}

impl FieldSpans {
    pub fn insert(&mut self, field: &str, at: SourceLocation, value: Option<f64>, positive: bool) {
        self.0.insert(
            field.to_string(),
            Read {
                at,
                value,
                positive,
            },
        );
    }

    /// Where `field` was written, if it was.
    pub fn get(&self, field: &str) -> Option<&SourceLocation> {
        self.0.get(field).map(|r| &r.at)
    }

    /// The value of `field` when it is a number that was written.
    pub fn value(&self, field: &str) -> Option<f64> {
        self.0.get(field)?.value
    }

    /// Where `field` was written, else the file alone.
    pub fn location(&self, field: &str, file: &Path) -> SourceLocation {
        self.get(field)
            .cloned()
            .unwrap_or_else(|| SourceLocation::file(file))
    }

    /// The fields read, in name order.
    pub fn iter(&self) -> impl Iterator<Item = (&str, &Read)> {
        self.0.iter().map(|(k, v)| (k.as_str(), v))
    }

    /// The spans of a scene merged from a file and overrides (`merged`, parsed from a text
    /// that is not the file): each field where the file (`base`) wrote it, or the file alone
    /// for a field at or under an `overridden` dotted key, or one the file does not have.
    pub fn relocated(
        merged: &FieldSpans,
        base: &FieldSpans,
        overridden: &[&str],
        file: &Path,
    ) -> FieldSpans {
        let under = |field: &str| {
            overridden.iter().any(|k| {
                field == *k
                    || field.starts_with(&format!("{k}."))
                    || k.starts_with(&format!("{field}."))
            })
        };
        FieldSpans(
            merged
                .0
                .iter()
                .map(|(k, read)| {
                    let at = match base.get(k) {
                        Some(at) if !under(k) => at.clone(),
                        _ => SourceLocation::file(file),
                    };
                    let read = Read { at, ..read.clone() };
                    (k.clone(), read)
                })
                .collect(),
        )
    }
}
