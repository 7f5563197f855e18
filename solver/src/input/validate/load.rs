//! `load`: the impactor under its coupling (the nodal contact law or the surface coupling),
//! the prescribed pulse and traction, and the rigid wall with what it needs of the scene.

use serde_saphyr::Spanned;

use crate::input::error::{shown, Error, Result, SourceLocation};
use crate::input::scene::{
    ContactFile, ContactLawChoice, ContactLawFile, EndFile, Ends, Enforcement, Impactor,
    ImpactorFile, Load, LoadFile, MeshFile, MidSpanNode, Model, Plate, PlateFile, Pulse,
    SurfaceContact, SurfaceImpactor, TimeFile, Traction, Wall,
};

use super::{Num, Rule, Validator, LENGTH_UNIT, NON_NEGATIVE, POISSON, POSITIVE};

impl Validator<'_> {
    pub(super) fn load(&self, load: LoadFile, plate: &Plate) -> Result<Load> {
        Ok(match load {
            LoadFile::Traction(t) => {
                let finite = Rule {
                    allowed: "must be a finite number (Pa)",
                    ok: f64::is_finite,
                };
                let normal = match &t.normal {
                    Some(v) => self.check(v, "load.traction.normal", finite)?,
                    None => 0.0,
                };
                let shear = match &t.shear {
                    Some(v) => self.check(v, "load.traction.shear", finite)?,
                    None => 0.0,
                };
                if normal == 0.0 && shear == 0.0 {
                    return self.fail(
                        &t.duration,
                        "load.traction",
                        "normal = shear = 0",
                        "needs a non-zero normal or shear traction (Pa)",
                    );
                }
                Load::Traction(Traction {
                    normal,
                    shear,
                    duration: self.check(&t.duration, "load.traction.duration", POSITIVE)?,
                })
            }
            LoadFile::Pulse(p) => Load::Pulse(Pulse {
                force: self.check(&p.force, "load.pulse.force", NON_NEGATIVE)?,
                duration: self.check(&p.duration, "load.pulse.duration", POSITIVE)?,
            }),
            LoadFile::Impactor(i) => self.impactor(&i, plate)?,
            LoadFile::Wall(w) => {
                if let Some(hold) = &w.hold_face {
                    self.read(hold, "load.wall.hold_face");
                }
                Load::Wall(Wall {
                    velocity: self.check(&w.velocity, "load.wall.velocity", POSITIVE)?,
                    hold_face: w.hold_face.as_ref().is_some_and(|h| h.value),
                    friction: match &w.friction {
                        Some(mu) => self.check(mu, "load.wall.friction", NON_NEGATIVE)?,
                        None => 0.0,
                    },
                })
            }
        })
    }

    /// What the wall needs of the rest of the scene: a free body (`plate.ends: free`), the
    /// half model (the symmetry line is the bar's axis or mid-plane: the full model has no
    /// x support with free ends) and a fixed end time (the wall force may touch zero while
    /// the bar still rolls on the wall: `after_contact` could stop a run early).
    pub(super) fn wall_scene(
        &self,
        plate: &PlateFile,
        mesh: &MeshFile,
        time: &TimeFile,
    ) -> Result<()> {
        let why_free = "must be `free` with load: {wall}: the body flies onto the wall and nothing holds it (clamped, roller and slider ends would pin it in the air)";
        match &plate.ends {
            Some(e) if e.value != Ends::Free => {
                return self.fail(e, "plate.ends", ends_name(e.value), why_free)
            }
            None => {
                return self.fail(
                    &plate.length,
                    "plate.ends",
                    "clamped (the default)",
                    why_free,
                )
            }
            Some(_) => {}
        }
        if let Some(model) = mesh.model.as_ref().filter(|m| m.value == Model::Full) {
            return self.fail(
                model,
                "mesh.model",
                "full",
                "must be `half` with load: {wall}: the symmetry line is the bar's axis (axisymmetric) or mid-plane, and the full model's free ends leave x unsupported",
            );
        }
        if let EndFile::AfterContact(_) = time.end.value {
            return self.fail(
                &time.end,
                "time.end",
                "{after_contact}",
                "must be a time (s) with load: {wall}: the wall force may pass through zero while the bar is still on the wall, so after_contact could stop the run early",
            );
        }
        Ok(())
    }

    /// `load.impactor` under its coupling: the nodal one's law and nodes, or the surface
    /// one's options; the other coupling's keys are refused.
    fn impactor(&self, i: &ImpactorFile, plate: &Plate) -> Result<Load> {
        let f = |name: &str| format!("load.impactor.{name}");
        let (mass, velocity, nose_radius) = (
            self.check(&i.mass, &f("mass"), POSITIVE)?,
            self.check(&i.velocity, &f("velocity"), POSITIVE)?,
            self.check(&i.nose_radius, &f("nose_radius"), POSITIVE)?,
        );
        let surface = match &i.contact {
            Some(Spanned {
                value: ContactFile::Surface(options),
                ..
            }) => options,
            _ => {
                return Ok(Load::Impactor(Impactor {
                    mass,
                    velocity,
                    nose_radius,
                    youngs_modulus: self.required(
                        &i.youngs_modulus,
                        i,
                        "youngs_modulus",
                        "Pa",
                        POSITIVE,
                    )?,
                    poisson_ratio: self.required(
                        &i.poisson_ratio,
                        i,
                        "poisson_ratio",
                        "-",
                        POISSON,
                    )?,
                    contact_law: self.contact_law(i, plate)?,
                    indentation_datum: i
                        .indentation_datum
                        .as_ref()
                        .map_or_else(MidSpanNode::default, |d| d.value),
                    force_node: i
                        .force_node
                        .as_ref()
                        .or(i.indentation_datum.as_ref())
                        .map_or_else(MidSpanNode::default, |d| d.value),
                }))
            }
        };
        self.refuse_nodal_keys(i)?;
        let enforcement = surface
            .enforcement
            .as_ref()
            .map_or_else(Enforcement::default, |e| e.value);
        let penalty_scale = match &surface.penalty_scale {
            None => SurfaceContact::DEFAULT_PENALTY_SCALE,
            Some(v) if enforcement == Enforcement::Kinematic => {
                return self.fail(
                    v,
                    &f("contact.surface.penalty_scale"),
                    shown(v.value),
                    "is the penalty enforcement's: give `enforcement: penalty` with it, or remove it (the kinematic enforcement has no stiffness)",
                )
            }
            Some(v) => self.check(
                v,
                &f("contact.surface.penalty_scale"),
                Rule {
                    allowed: "must be a number in (0, 1] (the penalty stiffness of a node over its mass times its elements' largest eigenvalue; 1 shortens the stable step by 1/sqrt(2))",
                    ok: |x| x > 0.0 && x <= 1.0,
                },
            )?,
        };
        Ok(Load::SurfaceImpactor(SurfaceImpactor {
            mass,
            velocity,
            nose_radius,
            contact: SurfaceContact {
                enforcement,
                penalty_scale,
            },
        }))
    }

    /// A key the nodal coupling needs (`unit` for the message): missing is an error at the
    /// impactor's `mass`.
    fn required(
        &self,
        value: &Option<Num>,
        i: &ImpactorFile,
        key: &str,
        unit: &str,
        rule: Rule,
    ) -> Result<f64> {
        let field = format!("load.impactor.{key}");
        match value {
            Some(v) => self.check(v, &field, rule),
            None => self.fail(
                &i.mass,
                &field,
                "missing",
                format!("the nodal contact coupling (the default `contact: nodal`) needs the nose's {key} ({unit}); or use `contact: surface`, whose nose is rigid"),
            ),
        }
    }

    /// The surface coupling's nose is rigid and its force comes from the top surface: the
    /// nodal coupling's keys would do nothing, so they are refused.
    fn refuse_nodal_keys(&self, i: &ImpactorFile) -> Result<()> {
        let why = "belongs to the nodal coupling; with `contact: surface` the nose is rigid and its force comes from the plate's top surface: remove it";
        let given: [(&str, Option<SourceLocation>); 5] = [
            (
                "youngs_modulus",
                i.youngs_modulus.as_ref().map(|v| self.at(v)),
            ),
            (
                "poisson_ratio",
                i.poisson_ratio.as_ref().map(|v| self.at(v)),
            ),
            ("contact_law", i.contact_law.as_ref().map(|v| self.at(v))),
            (
                "indentation_datum",
                i.indentation_datum.as_ref().map(|v| self.at(v)),
            ),
            ("force_node", i.force_node.as_ref().map(|v| self.at(v))),
        ];
        match given.into_iter().find_map(|(k, at)| at.map(|at| (k, at))) {
            Some((key, at)) => Err(Error::invalid(
                at,
                format!("load.impactor.{key}"),
                "given",
                why,
            )),
            None => Ok(()),
        }
    }

    /// The nodal coupling's contact law (eq. 4 or Johnson's), required.
    fn contact_law(&self, i: &ImpactorFile, plate: &Plate) -> Result<ContactLawChoice> {
        let f = |name: &str| format!("load.impactor.{name}");
        let Some(law) = &i.contact_law else {
            return self.fail(
                &i.mass,
                &f("contact_law"),
                "missing",
                "the nodal contact coupling (the default `contact: nodal`) needs `contact_law: {paper: {length_unit: m}}` or `{johnson: {datum_depth: m}}`; or use `contact: surface`",
            );
        };
        Ok(match &law.value {
            ContactLawFile::Paper { length_unit } => ContactLawChoice::Paper {
                length_unit: self.check(
                    length_unit,
                    &f("contact_law.paper.length_unit"),
                    LENGTH_UNIT,
                )?,
            },
            ContactLawFile::Johnson { datum_depth } => {
                let depth =
                    self.check(datum_depth, &f("contact_law.johnson.datum_depth"), POSITIVE)?;
                if depth > plate.thickness {
                    return self.fail(
                        datum_depth,
                        &f("contact_law.johnson.datum_depth"),
                        shown(depth),
                        format!(
                            "must not exceed the plate thickness {} m",
                            shown(plate.thickness)
                        ),
                    );
                }
                ContactLawChoice::Johnson { datum_depth: depth }
            }
        })
    }
}

/// The name of `ends` in scenes.
fn ends_name(ends: Ends) -> &'static str {
    match ends {
        Ends::Clamped => "clamped",
        Ends::Roller => "roller",
        Ends::Slider => "slider",
        Ends::Free => "free",
    }
}
