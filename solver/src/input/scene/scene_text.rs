//! The validated scene written back in the scene file's own format, every default written out:
//! what another code's adapter reads (`adapters/README.md`), and what a reader sees of a scene
//! after its `set` overrides and refinements. Reading the text back gives the same [`Scene`]
//! (its numbers are written in the shortest form that reads back to the same bits); only
//! where the scene came from (`source`, the fields' spans, the warnings) is not carried.

use serde_json::{json, Map, Value};

use super::scene_types::{
    ContactLawChoice, DtChoice, End, Hardening, Load, Plasticity, RateLaw, Scene,
};
use super::Enforcement;

impl Scene {
    /// The scene as the scene file's mapping (`title`, `plate`, `material`, `mesh`, `load`,
    /// `time`, `output`, `kinematics`, `geometry`), SI units, every default written out.
    pub fn to_file_value(&self) -> Value {
        let mut doc = Map::new();
        if let Some(t) = &self.title {
            doc.insert("title".into(), json!(t));
        }
        let p = &self.plate;
        doc.insert(
            "plate".into(),
            json!({"length": p.length, "width": p.width, "thickness": p.thickness, "ends": p.ends}),
        );
        doc.insert("material".into(), material_value(self));
        let m = &self.mesh;
        doc.insert(
            "mesh".into(),
            json!({"nx": m.nx, "ny": m.ny, "element": m.element.name(), "model": m.model,
                   "grading": m.grading, "hourglass": m.hourglass, "distortion": m.distortion}),
        );
        doc.insert("load".into(), load_value(&self.load));
        doc.insert("time".into(), time_value(self));
        doc.insert("output".into(), output_value(self));
        doc.insert("kinematics".into(), json!(self.kinematics.name()));
        doc.insert("geometry".into(), json!(self.geometry.name()));
        Value::Object(doc)
    }

    /// [`Scene::to_file_value`] as YAML text ([`file_text`]).
    pub fn to_yaml(&self) -> String {
        file_text(&self.to_file_value())
    }
}

/// A scene's mapping ([`Scene::to_file_value`]) as YAML text, opened by the schema line
/// editors read.
pub fn file_text(value: &Value) -> String {
    let body = serde_saphyr::to_string(value).unwrap_or_else(|e| format!("# not written: {e}\n"));
    format!(
        "# yaml-language-server: $schema=scene.schema.json\n\
         # The scene as validated and resolved by impact (every default written out).\n{body}"
    )
}

fn material_value(scene: &Scene) -> Value {
    let mat = &scene.material;
    let mut v = json!({"density": mat.density, "youngs_modulus": mat.youngs_modulus,
                       "poisson_ratio": mat.poisson_ratio});
    if let Some(p) = &mat.plasticity {
        v["plasticity"] = plasticity_value(p);
    }
    v
}

/// `plasticity:` as written: Johnson-Cook's `A + B k^n` lives in `rate.johnson_cook`, with
/// no `yield_stress` or `hardening` beside it.
fn plasticity_value(p: &Plasticity) -> Value {
    let rate = p.rate.as_ref().map(|r| rate_value(r, p));
    match (&p.hardening, rate) {
        (Hardening::Power { .. }, Some(rate)) => json!({"rate": rate}),
        (h, rate) => {
            let mut v = json!({"yield_stress": p.yield_stress, "hardening": hardening_value(h)});
            if let Some(rate) = rate {
                v["rate"] = rate;
            }
            v
        }
    }
}

fn hardening_value(h: &Hardening) -> Value {
    match h {
        Hardening::Linear { tangent_modulus } => json!({"linear": tangent_modulus}),
        Hardening::Table(rows) => {
            json!({"table": rows.iter().map(|(e, s)| json!([e, s])).collect::<Vec<_>>()})
        }
        // Only Johnson-Cook's law makes a power curve (handled by the caller).
        Hardening::Power { .. } => Value::Null,
    }
}

fn rate_value(r: &RateLaw, p: &Plasticity) -> Value {
    match r {
        RateLaw::CowperSymonds { d, q } => json!({"cowper_symonds": {"D": d, "q": q}}),
        RateLaw::JohnsonCook {
            c,
            reference_rate,
            thermal,
        } => {
            let (b, n) = match p.hardening {
                Hardening::Power {
                    coefficient,
                    exponent,
                } => (coefficient, exponent),
                _ => (0.0, 1.0),
            };
            let mut jc = json!({"A": p.yield_stress, "B": b, "n": n, "C": c,
                                "reference_rate": reference_rate});
            if let Some(t) = thermal {
                jc["m"] = json!(t.softening_exponent);
                jc["thermal"] = json!({"initial_temperature": t.initial_temperature,
                    "melting_temperature": t.melting_temperature,
                    "specific_heat": t.specific_heat, "taylor_quinney": t.taylor_quinney});
                if t.reference_temperature != t.initial_temperature {
                    jc["thermal"]["reference_temperature"] = json!(t.reference_temperature);
                }
            }
            json!({"johnson_cook": jc})
        }
    }
}

fn load_value(load: &Load) -> Value {
    match load {
        Load::Impactor(i) => {
            let law = match i.contact_law {
                ContactLawChoice::Paper { length_unit } => {
                    json!({"paper": {"length_unit": length_unit}})
                }
                ContactLawChoice::Johnson { datum_depth } => {
                    json!({"johnson": {"datum_depth": datum_depth}})
                }
            };
            json!({"impactor": {"mass": i.mass, "velocity": i.velocity,
                "nose_radius": i.nose_radius, "youngs_modulus": i.youngs_modulus,
                "poisson_ratio": i.poisson_ratio, "contact_law": law,
                "indentation_datum": i.indentation_datum, "force_node": i.force_node,
                "contact": "nodal"}})
        }
        Load::SurfaceImpactor(i) => {
            let mut surface = json!({"enforcement": i.contact.enforcement});
            if i.contact.enforcement == Enforcement::Penalty {
                surface["penalty_scale"] = json!(i.contact.penalty_scale);
            }
            json!({"impactor": {"mass": i.mass, "velocity": i.velocity,
                "nose_radius": i.nose_radius, "contact": {"surface": surface}}})
        }
        Load::Pulse(p) => json!({"pulse": {"force": p.force, "duration": p.duration}}),
        Load::Traction(t) => json!({"traction": {"normal": t.normal, "shear": t.shear,
                                                 "duration": t.duration}}),
        Load::Wall(w) => json!({"wall": {"velocity": w.velocity, "hold_face": w.hold_face,
                                         "friction": w.friction}}),
    }
}

fn time_value(scene: &Scene) -> Value {
    let t = &scene.time;
    let mut dt = match t.dt {
        DtChoice::Cfl(c) => json!({"cfl": c}),
        DtChoice::Fixed(d) => json!({"fixed": d}),
    };
    dt["estimate"] = json!(t.dt_estimate.name());
    dt["update"] = json!(t.dt_update.name());
    let mut v = match t.end {
        End::At(end) => json!({"end": end}),
        End::AfterContact { after, limit } => {
            json!({"end": {"after_contact": after}, "limit": limit})
        }
    };
    v["dt"] = dt;
    v["allow_unstable_dt"] = json!(t.allow_unstable_dt);
    v
}

fn output_value(scene: &Scene) -> Value {
    let o = &scene.output;
    let mut v = Map::new();
    if let Some(every) = o.every {
        v.insert("every".into(), json!(every));
    }
    if !o.probes.is_empty() {
        let probes: Map<String, Value> = o
            .probes
            .iter()
            .map(|(name, [x, y])| (name.clone(), json!({"x": x, "y": y})))
            .collect();
        v.insert("probes".into(), Value::Object(probes));
    }
    if let Some(every) = o.fields_every {
        v.insert("fields".into(), json!({"every": every}));
    }
    Value::Object(v)
}
