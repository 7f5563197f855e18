//! `mesh`, `time` and `output`: the mesh's sizes and options, the end and the time step's
//! choice, the history interval, the probes and the field output.

use crate::input::error::{shown, Result};
use crate::input::scene::{
    DtChoice, DtUpdate, End, EndFile, Kinematics, MeshFile, MeshSettings, Model, OutputFile,
    OutputSettings, Plate, TimeFile, TimeSettings, DEFAULT_HOURGLASS, DEFAULT_TIME_LIMIT,
};

use super::{Rule, Validator, CFL, CFL_UNCHECKED, NON_NEGATIVE, POSITIVE};

impl Validator<'_> {
    pub(super) fn mesh(&self, m: &MeshFile) -> Result<MeshSettings> {
        self.read_number(&m.nx, "mesh.nx", Some(m.nx.value as f64));
        self.read_number(&m.ny, "mesh.ny", Some(m.ny.value as f64));
        let nx = m.nx.value;
        if !(1..=100_000).contains(&nx) {
            return self.fail(&m.nx, "mesh.nx", nx, "must be an integer in [1, 100000]");
        }
        let ny = m.ny.value;
        if !(2..=10_000).contains(&ny) || ny % 2 != 0 {
            return self.fail(
                &m.ny,
                "mesh.ny",
                ny,
                "must be an even integer in [2, 10000] (the mid-plane must be a row of nodes)",
            );
        }
        if m.model() == Model::Full && nx % 2 != 0 {
            return self.fail(
                &m.nx,
                "mesh.nx",
                nx,
                "must be even for model: full (mid-span must be a column of nodes)",
            );
        }
        let grading = match &m.grading {
            None => 1.0,
            Some(g) => self.check(
                g,
                "mesh.grading",
                Rule {
                    allowed: "must lie in [1, 1000] (largest / smallest element length)",
                    ok: |v| (1.0..=1000.0).contains(&v),
                },
            )?,
        };
        let hourglass = match &m.hourglass {
            None => DEFAULT_HOURGLASS,
            Some(h) => self.check(
                h,
                "mesh.hourglass",
                Rule {
                    allowed: "must lie in (0, 1]",
                    ok: |v| v > 0.0 && v <= 1.0,
                },
            )?,
        };
        let distortion = match &m.distortion {
            None => 0.0,
            Some(d) => self.check(
                d,
                "mesh.distortion",
                Rule {
                    allowed: "must lie in [0, 0.4] (fraction of the local element size)",
                    ok: |v| (0.0..=0.4).contains(&v),
                },
            )?,
        };
        Ok(MeshSettings {
            nx: nx as usize,
            ny: ny as usize,
            element: m.element,
            model: m.model(),
            grading,
            hourglass,
            distortion,
        })
    }

    /// `on_wall`: the load is the rigid wall, whose bodies' elements crush (the default of
    /// `time.dt.update`, [`default_dt_update`]).
    pub(super) fn time(
        &self,
        t: &TimeFile,
        kinematics: Kinematics,
        on_wall: bool,
    ) -> Result<TimeSettings> {
        let limit = match &t.limit {
            None => DEFAULT_TIME_LIMIT,
            Some(l) => self.check(l, "time.limit", POSITIVE)?,
        };
        let end = match &t.end.value {
            EndFile::At(v) => {
                self.read_value(&t.end, "time.end", Some(*v), true);
                if !(v.is_finite() && *v > 0.0) {
                    return self.fail(&t.end, "time.end", shown(*v), POSITIVE.allowed);
                }
                End::At(*v)
            }
            EndFile::AfterContact(a) => End::AfterContact {
                after: self.check(&a.after_contact, "time.end.after_contact", NON_NEGATIVE)?,
                limit,
            },
        };
        if let Some(allow) = &t.allow_unstable_dt {
            self.read(allow, "time.allow_unstable_dt");
        }
        let allow_unstable_dt = t.allow_unstable_dt.as_ref().is_some_and(|a| a.value);
        let dt_location = self.at(&t.dt);
        let dt = match (&t.dt.value.cfl, &t.dt.value.fixed) {
            (Some(c), None) => {
                let rule = if allow_unstable_dt { CFL_UNCHECKED } else { CFL };
                DtChoice::Cfl(self.check(c, "time.dt.cfl", rule)?)
            }
            (None, Some(d)) => DtChoice::Fixed(self.check(d, "time.dt.fixed", POSITIVE)?),
            (c, _) => {
                return self.fail(
                    &t.dt,
                    "time.dt",
                    if c.is_some() { "both cfl and fixed" } else { "neither cfl nor fixed" },
                    "takes exactly one of cfl (a fraction of the stable estimate) or fixed (s), and optionally estimate: element | global",
                )
            }
        };
        let written = t.dt.value.update.as_ref();
        if let Some(update) = written {
            self.read(update, "time.dt.update");
        }
        let dt_update =
            written.map_or_else(|| default_dt_update(dt, kinematics, on_wall), |u| u.value);
        if let Some(update) = written.filter(|u| u.value == DtUpdate::EveryStep) {
            let why = match (dt, kinematics) {
                (DtChoice::Fixed(_), _) => Some("a fixed step is never re-estimated: give time.dt.cfl (a fraction of the stable estimate) with update: every-step"),
                (_, Kinematics::Small) => Some("under small kinematics the mesh keeps its shape, so its stable step is the one at the start: use update: once, or kinematics: finite"),
                _ => None,
            };
            if let Some(why) = why {
                return self.fail(update, "time.dt.update", "every-step", why);
            }
        }
        Ok(TimeSettings {
            end,
            dt,
            dt_estimate: t.dt.value.estimate,
            dt_update,
            dt_location,
            allow_unstable_dt,
        })
    }

    pub(super) fn output(&self, o: &OutputFile, plate: &Plate) -> Result<OutputSettings> {
        let every = match &o.every {
            None => None,
            Some(e) => Some(self.check(e, "output.every", POSITIVE)?),
        };
        let fields_every = match &o.fields {
            None => None,
            Some(f) => Some(self.check(&f.every, "output.fields.every", POSITIVE)?),
        };
        let mut probes = Vec::with_capacity(o.probes.len());
        for (name, p) in &o.probes {
            let valid_name = !name.is_empty()
                && name
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
            if !valid_name {
                return self.fail(
                    &p.x,
                    "output.probes",
                    format!("{name:?}"),
                    "probe names use letters, digits, '_' and '-' only",
                );
            }
            let x = p.x.value;
            let y = p.y.value;
            self.read_number(&p.x, &format!("output.probes.{name}.x"), Some(x));
            self.read_number(&p.y, &format!("output.probes.{name}.y"), Some(y));
            if !(x.is_finite() && (0.0..=plate.length).contains(&x)) {
                return self.fail(
                    &p.x,
                    &format!("output.probes.{name}.x"),
                    shown(x),
                    format!("must lie in [0, plate.length = {}] m", shown(plate.length)),
                );
            }
            if !(y.is_finite() && (0.0..=plate.thickness).contains(&y)) {
                return self.fail(
                    &p.y,
                    &format!("output.probes.{name}.y"),
                    shown(y),
                    format!(
                        "must lie in [0, plate.thickness = {}] m",
                        shown(plate.thickness)
                    ),
                );
            }
            probes.push((name.clone(), [x, y]));
        }
        Ok(OutputSettings {
            every,
            probes,
            fields_every,
        })
    }
}

/// `time.dt.update` when the scene does not say: `every-step` for a body of
/// `kinematics: finite` flying onto the rigid wall with the step given as `cfl` (its elements
/// are crushed: the Taylor bar's foot element falls to 1/30-1/50 of its stable length, so a
/// step fixed at the start must be 20-40x below the first stable one, and costs that many
/// more steps), else `once` (the paper's fixed step, and every scene that pins its bits).
pub fn default_dt_update(dt: DtChoice, kinematics: Kinematics, on_wall: bool) -> DtUpdate {
    match (dt, kinematics, on_wall) {
        (DtChoice::Cfl(_), Kinematics::Finite, true) => DtUpdate::EveryStep,
        _ => DtUpdate::Once,
    }
}
