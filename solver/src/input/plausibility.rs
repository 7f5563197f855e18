//! Plausibility warnings: inputs a scene accepts that look wrong. A warning never stops a run
//! (each value may be meant); it names the field, where it is written, its value and why it
//! looks wrong. `impact simulate` prints them on stderr before the run, `summary.json` keeps
//! them (`warnings`), the Python package raises them as `impact.SceneWarning`.
//!
//! - **Units.** Scenes are in SI units; the usual slip is another unit system, above all the
//!   millimetre-tonne-second one of many FE codes (lengths in mm, density in t/mm^3 = 7.85e-9
//!   for steel, moduli and stresses in MPa). Each threshold is one no solid plate of this model
//!   crosses in SI, and the same value in that other unit does (see each rule).
//! - **Options that do nothing here** (`mesh.hourglass` without `q4-1pt`, `time.limit` with a
//!   fixed end, `after_contact` without an impactor, ...).
//! - **Output that swamps the run**: a history row or a VTK frame every step, field output of
//!   more than [`FIELD_BYTES_WARNING`], more than [`MANY_STEPS`] steps.
//! - **Quoted numbers and string booleans** in a scene file: read as the number (or boolean),
//!   with a warning. They are not refused because PyYAML (YAML 1.1) loads `207.0e9` from our
//!   own scene files as the string `'207.0e9'`, so dict scenes carry such strings; for the
//!   same reason dict scenes (source `<dict>`) get no quote warning.

use std::fmt;

use crate::input::error::{shown, SourceLocation};
use crate::input::estimate::budget::{Estimate, MANY_STEPS};
use crate::input::estimate::measures::{bytes, count, p_wave_speed};
use crate::input::scene::{
    DtChoice, DtUpdate, ElementKind, End, Geometry, Kinematics, Load, Scene,
};

// Kept at their paths before the scene's types and the measures had their files.
pub use crate::input::estimate::measures::{extreme_fields, extreme_inputs, EXTREME};
pub use crate::input::scene::Warning;

/// Plate length and width above this (m) look like millimetres: every plate of 10 mm or more
/// given in mm crosses it, and a clamped plate of more than 10 m struck by a line nose is no
/// scene this plane-strain model is for.
pub const PLATE_SPAN_MAX: f64 = 10.0;
/// Plate thickness above this (m) looks like millimetres (any plate of 1 mm or more in mm).
pub const PLATE_THICKNESS_MAX: f64 = 1.0;
/// Nose radius above this (m) looks like millimetres (any nose of 1 mm or more in mm); the
/// surface-contact scenes use up to 0.5 m.
pub const NOSE_RADIUS_MAX: f64 = 1.0;
/// Densities (kg/m^3) between aerogel (~1) and far beyond osmium (22 590); steel in t/mm^3
/// is 7.85e-9, in g/cm^3 7.85 (caught by the wave speed below).
pub const DENSITY_RANGE: (f64, f64) = (1.0, 1.0e5);
/// Young's moduli (Pa) from soft rubber (~1e6) to diamond (1.2e12); steel in MPa is 2.07e5,
/// in GPa 207.
pub const MODULUS_RANGE: (f64, f64) = (1.0e6, 1.2e12);
/// P-wave speeds (m/s) of solids, from soft rubber (~20) to diamond (~18 000): outside, the
/// density and the modulus are in units that do not match.
pub const WAVE_SPEED_RANGE: (f64, f64) = (20.0, 2.0e4);
/// Yield stresses (Pa) below this (0.1 MPa, below any metal's or polymer's) look like MPa.
pub const YIELD_STRESS_MIN: f64 = 1.0e5;
/// Impactor speeds, and a body's speed onto the rigid wall (m/s), above this are no
/// low-velocity impact (no equation of state, no erosion here; published Taylor shots reach
/// about 600 m/s); 10 m/s in mm/s is 10 000.
pub const VELOCITY_MAX: f64 = 1.0e3;
/// Initial temperatures (K) below this look like degrees Celsius (20 C is 293.15 K); the
/// coldest Taylor tests are at liquid nitrogen's 77 K.
pub const TEMPERATURE_MIN: f64 = 70.0;
/// VTK field output beyond this many bytes is announced with its size.
pub const FIELD_BYTES_WARNING: f64 = 1.0e9;
/// A step fixed for the run below this fraction of the stable one is announced with its cost
/// (a fixed step is an estimate's fraction of the stable one; the shipped scenes' smallest
/// fixed fractions are the pinned Taylor bars' 0.01 and 0.02).
pub const SMALL_STEP_FRACTION: f64 = 0.05;
/// The estimated stable step is within this factor of the solver's own (budget.rs); a history
/// or field interval below the estimate over it is below the step whatever the solver finds.
const STEP_ESTIMATE_FACTOR: f64 = 1.5;

/// The warnings of a validated scene; `text` is the scene's YAML text (for quoted values).
pub fn warnings(scene: &Scene, text: Option<&str>) -> Vec<Warning> {
    let mut w = Finder {
        scene,
        found: Vec::new(),
    };
    w.units();
    w.johnson_cook();
    w.options();
    w.output();
    if let Some(text) = text {
        if scene.source.as_os_str() != "<dict>" {
            w.quoted(text);
        }
    }
    w.extremes();
    w.small_fixed_step();
    w.found
}

struct Finder<'a> {
    scene: &'a Scene,
    found: Vec<Warning>,
}

impl Finder<'_> {
    fn warn(&mut self, field: &str, value: impl fmt::Display, message: String) {
        self.found.push(Warning {
            location: self.scene.fields.location(field, &self.scene.source),
            field: field.to_string(),
            value: value.to_string(),
            message,
        });
    }

    fn warned(&self, field: &str) -> bool {
        self.found.iter().any(|w| w.field == field)
    }

    fn given(&self, field: &str) -> bool {
        self.scene.fields.get(field).is_some()
    }

    fn units(&mut self) {
        let s = self.scene;
        let p = s.plate;
        for (field, x, max) in [
            ("plate.length", p.length, PLATE_SPAN_MAX),
            ("plate.width", p.width, PLATE_SPAN_MAX),
            ("plate.thickness", p.thickness, PLATE_THICKNESS_MAX),
        ] {
            if x > max {
                self.warn(field, shown(x), format!(
                    "a plate of {} m is unusual: lengths are in metres, and above {max} m this looks like millimetres (200 mm is 0.2)",
                    shown(x)
                ));
            }
        }
        let m = &s.material;
        let (lo, hi) = DENSITY_RANGE;
        if m.density < lo {
            self.warn("material.density", shown(m.density), format!(
                "below {lo} kg/m^3, lighter than any solid (aerogels are about 1): density is in kg/m^3 (steel is 7850; 7.85e-9 is steel in t/mm^3)"
            ));
        } else if m.density > hi {
            self.warn("material.density", shown(m.density), format!(
                "above {} kg/m^3, denser than any solid (osmium is 22 590): density is in kg/m^3 (steel is 7850)",
                shown(hi)
            ));
        }
        self.modulus("material.youngs_modulus", m.youngs_modulus);
        if let Some(i) = s.impactor() {
            self.modulus("load.impactor.youngs_modulus", i.youngs_modulus);
        }
        let c = p_wave_speed(m);
        let (slow, fast) = WAVE_SPEED_RANGE;
        let material_warned =
            self.warned("material.density") || self.warned("material.youngs_modulus");
        if !material_warned && !(slow..=fast).contains(&c) {
            self.warn("material.density", shown(m.density), format!(
                "with youngs_modulus = {} Pa and poisson_ratio = {} the P-wave speed is {c:.3e} m/s, outside that of any solid (about {slow} m/s for soft rubber to 18 000 m/s for diamond): density and youngs_modulus look like different units (steel: 7850 kg/m^3 and 2.07e11 Pa)",
                shown(m.youngs_modulus), m.poisson_ratio
            ));
        }
        if let Some(pl) = &m.plasticity {
            let field = if self.given("material.plasticity.yield_stress") {
                "material.plasticity.yield_stress"
            } else {
                "material.plasticity.rate.johnson_cook.A"
            };
            if pl.yield_stress < YIELD_STRESS_MIN {
                self.warn(field, shown(pl.yield_stress), format!(
                    "below {} Pa (0.1 MPa), under any metal's or polymer's yield stress: stresses are in Pa (250 MPa is 2.5e8)",
                    shown(YIELD_STRESS_MIN)
                ));
            } else if pl.yield_stress > m.youngs_modulus {
                self.warn(field, shown(pl.yield_stress), format!(
                    "above youngs_modulus = {} Pa: the plate would yield only past a strain of 1; the two look like different units",
                    shown(m.youngs_modulus)
                ));
            }
        }
        let speed = match (s.impactor_motion(), s.wall()) {
            (Some((_, v)), _) => Some(("load.impactor.velocity", v)),
            (None, Some(w)) => Some(("load.wall.velocity", w.velocity)),
            (None, None) => None,
        };
        if let Some((field, v)) = speed {
            if v > VELOCITY_MAX {
                self.warn(field, shown(v), format!(
                    "above {} m/s: this solver is for low-velocity impact (no equation of state, no erosion); velocities are in m/s (10 m/s is not 10000 mm/s)",
                    shown(VELOCITY_MAX)
                ));
            }
        }
        if let Some(i) = s.impactor() {
            // The explicit coupling (eq. 21) of an impactor of mass m with a contact of
            // stiffness k is stable for dt < 2 sqrt(m / k); a line contact is at most about as
            // stiff as the plate under it, k ~ E W (its log factor makes it softer), so below
            // m = E W dt^2 / 4 the impactor bounces within a step.
            let dt = Estimate::of(s).dt;
            let bound = m.youngs_modulus * p.width * dt * dt / 4.0;
            let runs =
                crate::input::estimate::time_step::check_steps(s, dt).is_ok() && bound.is_finite();
            if runs && i.mass < bound && !self.warned("load.impactor.mass") {
                self.warn("load.impactor.mass", shown(i.mass), format!(
                    "below E W dt^2 / 4 = {bound:.3e} kg (youngs_modulus, plate.width and the time step of about {dt:.2e} s): the explicit contact coupling (eq. 21) is not stable for so light an impactor against a contact as stiff as the plate, it bounces within a step; the run's results will not be physical"
                ));
            }
        }
        let radius = match &s.load {
            Load::Impactor(i) => Some(i.nose_radius),
            Load::SurfaceImpactor(i) => Some(i.nose_radius),
            Load::Pulse(_) | Load::Traction(_) | Load::Wall(_) => None,
        };
        if let Some(r) = radius.filter(|r| *r > NOSE_RADIUS_MAX) {
            self.warn("load.impactor.nose_radius", shown(r), format!(
                "a nose radius above {NOSE_RADIUS_MAX} m is unusual: lengths are in metres, and this looks like millimetres (10 mm is 0.01)"
            ));
        }
    }

    fn modulus(&mut self, field: &str, e: f64) {
        let (lo, hi) = MODULUS_RANGE;
        if e < lo {
            self.warn(field, shown(e), format!(
                "below {} Pa, softer than soft rubber: moduli are in Pa (steel is 2.07e11; 2.07e5 is steel in MPa, 207 in GPa)",
                shown(lo)
            ));
        } else if e > hi {
            self.warn(
                field,
                shown(e),
                format!(
                    "above {} Pa, stiffer than diamond: moduli are in Pa (steel is 2.07e11)",
                    shown(hi)
                ),
            );
        }
    }

    /// Options given that do nothing in this scene.
    fn options(&mut self) {
        let s = self.scene;
        if s.mesh.element != ElementKind::Q4OnePoint {
            if let Some(h) = self.value("mesh.hourglass") {
                self.warn("mesh.hourglass", shown(h), format!(
                    "does nothing with element: {} (hourglass control is q4-1pt's): remove it, or use element: q4-1pt",
                    s.mesh.element.name()
                ));
            }
        }
        let limit = self.value("time.limit");
        match s.time.end {
            End::At(end) => {
                if let Some(l) = limit {
                    self.warn("time.limit", shown(l), format!(
                        "does nothing with time.end = {} s (a fixed end): time.limit bounds only time.end: {{after_contact: s}}",
                        shown(end)
                    ));
                }
            }
            End::AfterContact { after, limit } => {
                if s.impactor_motion().is_none() {
                    self.warn("time.end.after_contact", shown(after), format!(
                        "does nothing without an impactor (a pulse or traction load has no contact that ends): the run goes on to time.limit = {} s; give time.end in seconds",
                        shown(limit)
                    ));
                } else if after >= limit {
                    self.warn("time.end.after_contact", shown(after), format!(
                        "is not shorter than time.limit = {} s: the run always stops at time.limit, never after the contact",
                        shown(limit)
                    ));
                }
            }
        }
        if let (true, DtChoice::Cfl(c)) = (s.time.allow_unstable_dt, s.time.dt) {
            if c <= 1.0 {
                self.warn("time.allow_unstable_dt", "true", format!(
                    "does nothing with time.dt.cfl = {c} (at most the stable step): it only lets a cfl above 1 or a fixed step above the stable one run"
                ));
            }
        }
        if let Load::Pulse(p) = &s.load {
            if p.force == 0.0 {
                self.warn(
                    "load.pulse.force",
                    "0",
                    "the plate is never loaded: the run computes a plate at rest".into(),
                );
            } else if s.geometry == Geometry::Axisymmetric {
                self.warn("load.pulse.force", shown(p.force), "in the axisymmetric geometry the pulse is a force on the axis node: a true 3-D point load, whose stress under it has no mesh limit; the energy balance error grows as the mesh is refined (measured 9.9e-3 at 10 x 2 and 2.4e-2 at 40 x 8 on a 1 kN pulse, 1.0e-3 in plane strain) and a large force punches the axis element through; for a load spread over the plate use an impactor with contact: surface".into());
            }
        }
    }

    /// A step fixed for the run far below the stable one: it costs the inverse of its fraction
    /// in steps and buys no accuracy a mesh could show (central differences' error at the
    /// stable step is far below the mesh's). Not for a `cfl` with `update: once` written out:
    /// a step kept fixed on purpose (the bit-pinned Taylor bars, the fixed-step reference of
    /// the adaptive step's case).
    fn small_fixed_step(&mut self) {
        let s = self.scene;
        if s.time.dt_update != DtUpdate::Once || self.given("time.dt.update") {
            return;
        }
        let (field, value, fraction) = match s.time.dt {
            DtChoice::Cfl(c) => ("time.dt.cfl", c, c),
            DtChoice::Fixed(d) => ("time.dt.fixed", d, d / Estimate::of(s).stable_dt),
        };
        if fraction >= SMALL_STEP_FRACTION || self.warned(field) {
            return; // an extreme value has its own warning
        }
        let advice = if s.kinematics == Kinematics::Finite {
            "if elements crush, time.dt: {cfl: 0.8, update: every-step} lets the step follow the deformed mesh instead (the 42CrMo4 Taylor bar: 4809 steps against 92 639 at a fixed cfl 0.01)"
        } else {
            "under small kinematics the mesh keeps its shape, so a step near the stable one (cfl 0.8) is as stable and as accurate"
        };
        self.warn(field, shown(value), format!(
            "the step stays about {} of the stable one for the whole run, about {}x the steps of cfl 0.8 (write update: once to keep it so on purpose): {advice}",
            shown(fraction),
            shown((0.8 / fraction).round())
        ));
    }

    /// Output that swamps the run, and runs of very many steps.
    fn output(&mut self) {
        let s = self.scene;
        let e = Estimate::of(s);
        if crate::input::estimate::time_step::check_steps(s, e.dt).is_err() {
            return; // no run: the time step's refusal says why
        }
        // Below this the interval is below the step whatever the solver's own estimate.
        let step = match s.time.dt {
            DtChoice::Fixed(d) => d,
            DtChoice::Cfl(_) => e.dt / STEP_ESTIMATE_FACTOR,
        };
        if let Some(every) = s.output.every.filter(|x| *x < step) {
            self.warn("output.every", shown(every), format!(
                "below the time step (about {:.2e} s): the history gets a row every step ({} rows); raise output.every, or leave it out for every step on purpose",
                e.dt, count(e.history_rows)
            ));
        }
        if let Some(every) = s.output.fields_every {
            if every < step {
                self.warn("output.fields.every", shown(every), format!(
                    "below the time step (about {:.2e} s): a VTK field frame every step, about {} frames, about {} on disk; raise output.fields.every",
                    e.dt, count(e.field_frames), bytes(e.field_bytes)
                ));
            } else if e.field_bytes > FIELD_BYTES_WARNING {
                self.warn("output.fields.every", shown(every), format!(
                    "about {} VTK field frames of {} elements, about {} on disk; raise output.fields.every if that is not meant",
                    count(e.field_frames), count(e.elements), bytes(e.field_bytes)
                ));
            }
        }
        if e.steps > MANY_STEPS {
            let (field, end) = match s.time.end {
                End::At(t) => ("time.end", t),
                End::AfterContact { limit, .. } => ("time.limit", limit),
            };
            self.warn(field, shown(end), format!(
                "about {} time steps of {:.2e} s (more than {}): this run may take hours; shorten time.end or coarsen the mesh if that is not meant",
                count(e.steps), e.dt, count(MANY_STEPS)
            ));
        }
    }

    /// A number written in quotes, a boolean written other than `true`/`false`.
    fn quoted(&mut self, text: &str) {
        let lines: Vec<&str> = text.lines().collect();
        let mut found = Vec::new();
        for (field, read) in self.scene.fields.iter() {
            let Some(token) = token_at(&lines, &read.at) else {
                continue;
            };
            if field == "time.allow_unstable_dt" {
                if token != "true" && token != "false" {
                    let meant = self.scene.time.allow_unstable_dt;
                    found.push((
                        field.to_string(),
                        token.clone(),
                        format!("written `{token}`, read as {meant}: write true or false"),
                    ));
                }
            } else if let (Some(x), true) = (read.value, token.starts_with(['"', '\''])) {
                found.push((field.to_string(), token.clone(), format!(
                    "a number in quotes, read as {}: write numbers without quotes (a quoted number is often a unit slip or a template's text)",
                    shown(x)
                )));
            }
        }
        for (field, token, message) in found {
            self.warn(&field, token, message);
        }
    }

    /// Johnson-Cook's inputs that do nothing or look like Celsius.
    fn johnson_cook(&mut self) {
        const JC: &str = "material.plasticity.rate.johnson_cook";
        let thermal = self.scene.rate_law().and_then(|r| r.thermal()).copied();
        if thermal.is_none() && self.given(&format!("{JC}.m")) {
            let m = self.value(&format!("{JC}.m")).unwrap_or(f64::NAN);
            self.warn(&format!("{JC}.m"), shown(m), format!(
                "m does nothing without {JC}.thermal: the thermal softening needs a temperature, which only the heating block gives (add thermal: {{initial_temperature, melting_temperature, specific_heat, taylor_quinney}}, or remove m)"
            ));
        }
        if let Some(t) = thermal.filter(|t| t.initial_temperature < TEMPERATURE_MIN) {
            self.warn(&format!("{JC}.thermal.initial_temperature"), shown(t.initial_temperature), format!(
                "below {TEMPERATURE_MIN} K: temperatures are in kelvin, and this looks like degrees Celsius (20 C is 293.15 K); then melting_temperature {} is likely Celsius too (add 273.15 to both)",
                shown(t.melting_temperature)
            ));
        }
        let reference = format!("{JC}.thermal.reference_temperature");
        if let Some(t) = thermal.filter(|t| t.reference_temperature < TEMPERATURE_MIN) {
            if self.given(&reference) {
                self.warn(&reference, shown(t.reference_temperature), format!(
                    "below {TEMPERATURE_MIN} K: temperatures are in kelvin, and this looks like degrees Celsius (20 C is 293.15 K)"
                ));
            }
        }
    }

    /// Any other number beyond [`EXTREME`] in magnitude.
    fn extremes(&mut self) {
        let (tiny, huge) = EXTREME;
        let extreme: Vec<(String, f64)> = extreme_fields(self.scene)
            .into_iter()
            .filter(|(field, _)| !self.warned(field))
            .collect();
        for (field, x) in extreme {
            self.warn(&field, shown(x), format!(
                "beyond any physical value of this problem in SI units ({} to {} in magnitude): a typo? The arithmetic may overflow",
                shown(tiny), shown(huge)
            ));
        }
    }

    fn value(&self, field: &str) -> Option<f64> {
        self.scene.fields.value(field)
    }
}

/// The scalar written at `at` (1-based line and column) as it reads in the text: a quoted
/// string with its quotes, else up to the next `,`, `}`, `]` or comment.
fn token_at(lines: &[&str], at: &SourceLocation) -> Option<String> {
    let line = lines.get((at.line as usize).checked_sub(1)?)?;
    let rest: String = line
        .chars()
        .skip((at.column as usize).checked_sub(1)?)
        .collect();
    let first = rest.chars().next()?;
    if first == '"' || first == '\'' {
        let close = rest[1..].find(first).map_or(rest.len(), |i| i + 2);
        return Some(rest[..close].to_string());
    }
    let end = rest.find([',', '}', ']', '#']).unwrap_or(rest.len());
    Some(rest[..end].trim().to_string())
}

#[cfg(test)]
mod tests {
    //! The rules on the example scene: it warns nothing as written (nor does any scene of the
    //! repository but the rigid target of a code-verification case, whose density is 1e15 on
    //! purpose); each slip warns once, naming the field where the file writes it.
    use super::*;
    use std::path::Path;

    const EXAMPLE: &str = include_str!("../../../verification/scenes/example-elastic.yaml");

    fn warned(edit: impl Fn(&str) -> String, source: &str) -> Vec<String> {
        warnings_of(&edit(EXAMPLE), source)
    }

    /// The warnings of scene `text` read from a file named `source`.
    fn warnings_of(text: &str, source: &str) -> Vec<String> {
        let scene = Scene::from_yaml(text, Path::new(source)).expect("a valid scene");
        scene.warnings.iter().map(ToString::to_string).collect()
    }

    fn one(edit: impl Fn(&str) -> String) -> String {
        let w = warned(edit, "s.yaml");
        assert_eq!(w.len(), 1, "{w:?}");
        w[0].clone()
    }

    #[test]
    fn the_repository_scenes_warn_nothing() {
        assert_eq!(warned(|s| s.to_string(), "s.yaml"), Vec::<String>::new());
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../verification/scenes");
        let mut files = vec![];
        for dir in [root.clone(), root.join("paper-table2")] {
            for e in std::fs::read_dir(dir).unwrap().filter_map(|e| e.ok()) {
                if e.path().extension().is_some_and(|x| x == "yaml") {
                    files.push(e.path());
                }
            }
        }
        assert!(files.len() > 20);
        for f in files {
            let scene = Scene::from_file(&f).unwrap();
            assert!(
                scene.warnings.is_empty(),
                "{}: {:?}",
                f.display(),
                scene.warnings
            );
        }
    }

    /// Issue 39: a step fixed far below the stable one warns with its cost (`cfl` 0.01 on the
    /// example, a fixed step 1/100 of its stable one); `cfl` 0.05 (the bound), `update: once`
    /// written out, and re-estimation on a finite body do not.
    #[test]
    fn a_fixed_step_far_below_the_stable_one_warns() {
        let cfl = |c: &str| format!("  dt: {{{c}}}");
        let to = |c: &'static str| move |s: &str| s.replace(&cfl("cfl: 0.8"), &cfl(c));
        let w = one(to("cfl: 0.01"));
        assert!(w.contains("time.dt.cfl = 0.01: the step stays about 0.01 of the stable one for the whole run, about 80x the steps"), "{w}");
        assert!(w.contains("under small kinematics"), "{w}");
        let fixed = Scene::from_yaml(EXAMPLE, Path::new("s.yaml")).unwrap();
        let stable = Estimate::of(&fixed).stable_dt;
        let w = one(|s| {
            s.replace(
                &cfl("cfl: 0.8"),
                &cfl(&format!("fixed: {:e}", stable / 100.0)),
            )
        });
        assert!(
            w.contains("time.dt.fixed = ") && w.contains("about 0.01 of the stable one"),
            "{w}"
        );
        for quiet in [to("cfl: 0.05"), to("cfl: 0.01, update: once")] {
            assert_eq!(warned(quiet, "s.yaml"), Vec::<String>::new());
        }
    }

    #[test]
    fn units_that_look_wrong_warn_at_their_value() {
        // Steel in t/mm^3: and its step of 1e-13 s makes 2.5e10 steps.
        let w = warned(
            |s| s.replace("density: 7850.0", "density: 7.85e-9"),
            "s.yaml",
        );
        assert!(
            w[0].starts_with("s.yaml:5:12: material.density = 7.85e-9: below 1 kg/m^3"),
            "{w:?}"
        );
        assert!(w[1].contains("this run may take hours"), "{w:?}");
        // Steel's modulus in MPa, the step then 1e-4 s: the history's every 1e-6 s is below it.
        let w = warned(
            |s| s.replacen("youngs_modulus: 207.0e9", "youngs_modulus: 2.07e5", 1),
            "s.yaml",
        );
        assert!(
            w[0].starts_with("s.yaml:6:19: material.youngs_modulus = 207000: below 1e6 Pa"),
            "{w:?}"
        );
        assert!(
            w.len() == 2 && w[1].contains("output.every = 1e-6: below the time step"),
            "{w:?}"
        );
        // 7.85 (g/cm^3) is a density some solid could have: the wave speed tells.
        let w = one(|s| s.replace("density: 7850.0", "density: 7.85"));
        assert!(w.contains("P-wave speed is 1.884e5 m/s"), "{w}");
        let w = warned(
            |s| {
                s.replace(
                    "{length: 0.200, width: 0.200, thickness: 0.020}",
                    "{length: 200, width: 200, thickness: 20}",
                )
                .replace("x: 0.100", "x: 100")
            },
            "s.yaml",
        );
        assert!(
            w[0].starts_with("s.yaml:3:17: plate.length = 200: a plate of 200 m"),
            "{w:?}"
        );
        assert!(
            w.iter().any(|x| x.contains("plate.thickness = 20")),
            "{w:?}"
        );
        let w = one(|s| s.replace("velocity: 10.0", "velocity: 10000"));
        assert!(
            w.contains("load.impactor.velocity = 10000: above 1000 m/s"),
            "{w}"
        );
        let w = one(|s| s.replace("mass: 18.0", "mass: 1.0e-6"));
        assert!(
            w.contains("load.impactor.mass = 1e-6: below E W dt^2 / 4"),
            "{w}"
        );
    }

    #[test]
    fn options_that_do_nothing_warn() {
        let w = one(|s| s.replace("element: q4-sri,", "element: q4-sri, hourglass: 0.1,"));
        assert!(
            w.contains("mesh.hourglass = 0.1: does nothing with element: q4-sri"),
            "{w}"
        );
        let w = one(|s| s.replace("  dt: {cfl: 0.8}", "  dt: {cfl: 0.8}\n  limit: 0.01"));
        assert!(
            w.contains("time.limit = 0.01: does nothing with time.end = 0.003 s"),
            "{w}"
        );
        let w = one(|s| {
            s.replace(
                "  dt: {cfl: 0.8}",
                "  dt: {cfl: 0.8}\n  allow_unstable_dt: true",
            )
        });
        assert!(
            w.contains("time.allow_unstable_dt = true: does nothing"),
            "{w}"
        );
        let w = one(|s| s.replace("fields: {every: 1.0e-4}", "fields: {every: 1.0e-12}"));
        assert!(w.contains("a VTK field frame every step, about"), "{w}");
    }

    /// Issue 40's slips on the Johnson-Cook scene of the code-to-code gate and the Taylor bar:
    /// `m` without `thermal` (ignored), temperatures in Celsius (a bar 273 K colder, its flow
    /// stress far too high), a bar at 5000 m/s; each warns once, naming its field.
    #[test]
    fn johnson_cook_inputs_that_do_nothing_or_look_like_celsius_warn() {
        const JC: &str =
            include_str!("../../../scripts/ci-scenes/impact-plastic-johnson-cook.yaml");
        const TAYLOR: &str = include_str!("../../../verification/scenes/taylor-bar.yaml");
        let read = |text: String| warnings_of(&text, "s.yaml");
        assert!(read(JC.to_string()).is_empty());
        let thermal = JC.lines().find(|l| l.contains("thermal:")).unwrap();
        let w = read(JC.replace(thermal, ""));
        assert_eq!(w.len(), 1, "{w:?}");
        assert!(
            w[0].contains("johnson_cook.m = 1.1: m does nothing without"),
            "{w:?}"
        );
        let w = read(JC.replace(
            "initial_temperature: 293.15, melting_temperature: 1813.15",
            "initial_temperature: 20.0, melting_temperature: 1540.0",
        ));
        assert_eq!(w.len(), 1, "{w:?}");
        assert!(
            w[0].contains("initial_temperature = 20: below 70 K")
                && w[0].contains("melting_temperature 1540"),
            "{w:?}"
        );
        let w = read(TAYLOR.replace("velocity: 227.0", "velocity: 5000.0"));
        assert_eq!(w.len(), 1, "{w:?}");
        assert!(
            w[0].contains("load.wall.velocity = 5000: above 1000 m/s"),
            "{w:?}"
        );
    }

    /// Issue 40: a pulse in the axisymmetric geometry is a point force on the axis (its
    /// energy error grows under refinement, a large one punches the axis element through):
    /// warned once on load.pulse.force; the same pulse in plane strain warns nothing.
    #[test]
    fn a_pulse_on_the_axis_of_a_ring_warns() {
        const AXIS: &str = include_str!("../../../scripts/ci-scenes/axisym-pulse-full.yaml");
        let read = |text: &str| warnings_of(text, "s.yaml");
        let w = read(AXIS);
        assert_eq!(w.len(), 1, "{w:?}");
        assert!(
            w[0].contains("load.pulse.force") && w[0].contains("a true 3-D point load"),
            "{w:?}"
        );
        assert!(read(&AXIS.replace("geometry: axisymmetric", "")).is_empty());
    }

    #[test]
    fn quoted_numbers_warn_in_a_file_not_in_a_dict_scene() {
        let quoted = |s: &str| s.replace("density: 7850.0", "density: \"7850.0\"");
        let w = warned(quoted, "s.yaml");
        assert_eq!(w.len(), 1, "{w:?}");
        assert!(
            w[0].starts_with(
                "s.yaml:5:12: material.density = \"7850.0\": a number in quotes, read as 7850"
            ),
            "{w:?}"
        );
        assert!(warned(quoted, "<dict>").is_empty());
        let w = one(|s| {
            s.replace(
                "  dt: {cfl: 0.8}",
                "  dt: {cfl: 1.0}\n  allow_unstable_dt: \"no\"",
            )
        });
        assert!(w.contains("written `\"no\"`, read as false"), "{w}");
    }
}
