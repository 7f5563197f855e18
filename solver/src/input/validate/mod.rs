//! Validation: the scene file's types ([`crate::input::scene::SceneFile`]) checked value by
//! value against their rules ([`Rule`]) into the validated [`Scene`], each field's location
//! noted ([`FieldSpans`]). Reading ([`read`]: [`Scene::from_file`], [`Scene::from_yaml`] and
//! their overrides), the materials ([`material`]), the loads ([`load`]), the mesh, time and
//! output ([`settings`]) and the geometry ([`geometry`]) each have their file.

use std::cell::RefCell;
use std::path::Path;

use serde_saphyr::Spanned;

use crate::input::error::{shown, Error, Result, SourceLocation};
use crate::input::scene::{Ends, Load, Plate, Scene, SceneFile};
use crate::input::spans::FieldSpans;

pub mod geometry;
mod load;
mod material;
pub mod read;
mod settings;

type Num = Spanned<f64>;

pub(super) struct Validator<'a> {
    source: &'a Path,
    /// Where each field read so far was written.
    spans: RefCell<FieldSpans>,
}

/// A validation rule: what a value must satisfy, in words.
#[derive(Clone, Copy)]
pub(super) struct Rule {
    pub(super) allowed: &'static str,
    pub(super) ok: fn(f64) -> bool,
}

pub(super) const POSITIVE: Rule = Rule {
    allowed: "must be a finite number > 0",
    ok: |v| v.is_finite() && v > 0.0,
};
pub(super) const NON_NEGATIVE: Rule = Rule {
    allowed: "must be a finite number >= 0",
    ok: |v| v.is_finite() && v >= 0.0,
};
const POISSON: Rule = Rule {
    allowed: "must lie in (-1, 0.5) (exclusive)",
    ok: |v| v > -1.0 && v < 0.5,
};
/// Eq. (4)'s hidden length: the unit of length the paper's law is read in. Any unit of
/// length anyone means lies between a micrometre and a kilometre; beyond 1.3e154 m its square
/// overflows and the law's constants become inf (a run that stopped with NaN energies).
const LENGTH_UNIT: Rule = Rule {
    allowed: "must lie in [1e-6, 1e3] m (the unit of length eq. (4) is read in: 1 for metres, 0.001 for millimetres)",
    ok: |v| (1e-6..=1e3).contains(&v),
};
const CFL: Rule = Rule {
    allowed: "must lie in (0, 1] (fraction of the stable step)",
    ok: |v| v > 0.0 && v <= 1.0,
};
const CFL_UNCHECKED: Rule = Rule {
    allowed: "must be a finite number > 0",
    ok: |v| v.is_finite() && v > 0.0,
};

impl<'a> Validator<'a> {
    fn new(source: &'a Path) -> Validator<'a> {
        Validator {
            source,
            spans: RefCell::new(FieldSpans::default()),
        }
    }

    fn at<T>(&self, spanned: &Spanned<T>) -> SourceLocation {
        SourceLocation::of(self.source, spanned)
    }

    /// Notes where `field` was written (and its value, when a number).
    fn read<T>(&self, spanned: &Spanned<T>, field: &str) {
        self.read_number(spanned, field, None);
    }

    fn read_number<T>(&self, spanned: &Spanned<T>, field: &str, value: Option<f64>) {
        self.read_value(spanned, field, value, false);
    }

    fn read_value<T>(&self, spanned: &Spanned<T>, field: &str, value: Option<f64>, positive: bool) {
        self.spans
            .borrow_mut()
            .insert(field, self.at(spanned), value, positive);
    }

    pub(super) fn check(&self, value: &Num, field: &str, rule: Rule) -> Result<f64> {
        self.read_value(value, field, Some(value.value), !(rule.ok)(0.0));
        if (rule.ok)(value.value) {
            Ok(value.value)
        } else {
            Err(Error::invalid(
                self.at(value),
                field,
                shown(value.value),
                rule.allowed,
            ))
        }
    }

    pub(super) fn fail<T, U>(
        &self,
        at: &Spanned<T>,
        field: &str,
        value: impl std::fmt::Display,
        allowed: impl Into<String>,
    ) -> Result<U> {
        Err(Error::invalid(self.at(at), field, value, allowed))
    }

    fn scene(&self, file: SceneFile) -> Result<Scene> {
        let plate = Plate {
            length: self.check(&file.plate.length, "plate.length", POSITIVE)?,
            width: self.check(&file.plate.width, "plate.width", POSITIVE)?,
            thickness: self.check(&file.plate.thickness, "plate.thickness", POSITIVE)?,
            ends: file
                .plate
                .ends
                .as_ref()
                .map_or_else(Ends::default, |e| e.value),
        };
        let material = self.material(file.material)?;
        let mesh = self.mesh(&file.mesh)?;
        let load = self.load(file.load, &plate)?;
        let on_wall = matches!(load, Load::Wall(_));
        let time = self.time(&file.time, file.kinematics, on_wall)?;
        if on_wall {
            self.wall_scene(&file.plate, &file.mesh, &file.time)?;
        }
        let output = self.output(&file.output, &plate)?;
        let choices = geometry::Choices {
            model: mesh.model,
            load: &load,
            estimate: time.dt_estimate,
        };
        let geometry = geometry::validated(file.geometry.as_ref(), self.source, choices)?;
        Ok(Scene {
            source: self.source.to_path_buf(),
            title: file.title,
            plate,
            material,
            mesh,
            load,
            time,
            output,
            fields: self.spans.take(),
            warnings: Vec::new(),
            kinematics: file.kinematics,
            geometry,
        })
    }
}
