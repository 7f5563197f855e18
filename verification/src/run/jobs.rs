//! Jobs: the scenes and builtin computations the checks read. A scene shared by several
//! checks (or several cases: identical scenes are recognised by content) runs once.

use std::collections::BTreeMap;
use std::path::Path;
use std::sync::Arc;

use impact_solver::integrator::{FieldFrame, Observer};
use impact_solver::material::FlowCurve;
use impact_solver::scene::{DtChoice, End, Load, MidSpanNode, Model, Scene};
use serde_json::Value;

use crate::definition::case::{Case, Loc, Refine, SceneSpec};

/// Summary keys that measure the machine, not the result: shown, never compared.
pub use impact_solver::summary::TIMING_KEYS;

pub use crate::definition::case::series_scene_name;
pub use crate::definition::run_data::{flatten, impact_discriminators, JobResult, RunData};

/// A unit of work.
#[derive(Debug, Clone)]
pub enum Job {
    Scene {
        scene: Box<Scene>,
        stress_bound: bool,
        /// Words the error message must contain (empty: the run must succeed).
        expect_error: Vec<String>,
    },
    Builtin {
        name: String,
        params: BTreeMap<String, Value>,
    },
}

impl Job {
    /// Content key: identical jobs of different cases run once.
    pub fn key(&self) -> String {
        match self {
            Job::Scene {
                scene,
                stress_bound,
                expect_error,
            } => {
                let mut s = (**scene).clone();
                s.source = Default::default();
                s.time.dt_location.file = Default::default();
                s.time.dt_location.line = 0;
                s.time.dt_location.column = 0;
                s.title = None;
                if expect_error.is_empty() {
                    // Where each value was written (and the warnings, which say where) is
                    // not the scene: one file read by two cases, through two relative paths,
                    // is one run (CalculiX ran the Table 1 surface scene twice, 2026-11-29).
                    // A bad input keeps them: its expected messages name the file and line.
                    s.fields = Default::default();
                    s.warnings.clear();
                }
                format!("scene {stress_bound} {expect_error:?} {s:?}")
            }
            Job::Builtin { name, params } => format!("builtin {name} {params:?}"),
        }
    }

    /// A rough cost for scheduling (largest first), element-steps.
    pub fn cost(&self) -> f64 {
        match self {
            Job::Scene { scene, .. } => {
                let n = (scene.mesh.nx * scene.mesh.ny) as f64;
                let end = match scene.time.end {
                    End::At(t) => t,
                    End::AfterContact { limit, .. } => limit.min(3e-3),
                };
                let h = (scene.plate.thickness / scene.mesh.ny as f64)
                    .min(0.5 * scene.plate.length / scene.mesh.nx as f64);
                let dt = match scene.time.dt {
                    DtChoice::Cfl(c) => c * h / 6000.0,
                    DtChoice::Fixed(d) => d,
                };
                n * end / dt
            }
            Job::Builtin { .. } => 1e5,
        }
    }

    pub fn run(&self) -> JobResult {
        match self {
            Job::Scene {
                scene,
                stress_bound,
                expect_error,
            } if !expect_error.is_empty() => {
                let _ = stress_bound;
                let mut metrics = BTreeMap::new();
                let (failed, message) =
                    match impact_solver::simulate(scene, &mut impact_solver::Quiet) {
                        Ok(_) => (0.0, String::new()),
                        Err(e) => (1.0, e.to_string()),
                    };
                metrics.insert("run_failed".to_string(), failed);
                for w in expect_error {
                    let hit = message.to_lowercase().contains(&w.to_lowercase());
                    metrics.insert(format!("error_mentions_{w}"), if hit { 1.0 } else { 0.0 });
                }
                let mut info = BTreeMap::new();
                info.insert("expected error".to_string(), message);
                Ok(Arc::new(RunData {
                    metrics,
                    info,
                    ..Default::default()
                }))
            }
            Job::Scene {
                scene,
                stress_bound,
                ..
            } => run_scene(scene, *stress_bound).map(Arc::new),
            Job::Builtin { name, params } => crate::run::builtins::run(name, params).map(Arc::new),
        }
    }
}

/// Records the largest `von Mises / flow stress(eqps)` over elements and field frames.
struct StressBound {
    flow: Option<FlowCurve>,
    yield_stress: f64,
    max_ratio: f64,
    max_eqps: f64,
}

impl Observer for StressBound {
    fn wants_fields(&self) -> bool {
        true
    }
    fn fields(&mut self, frame: FieldFrame) -> impact_solver::Result<()> {
        for (vm, k) in frame.von_mises.iter().zip(&frame.eqps) {
            let flow = self
                .flow
                .as_ref()
                .map_or(self.yield_stress, |f| f.flow_stress(*k));
            self.max_ratio = self.max_ratio.max(vm / flow);
            self.max_eqps = self.max_eqps.max(*k);
        }
        Ok(())
    }
}

fn run_scene(scene: &Scene, stress_bound: bool) -> Result<RunData, String> {
    let mut observer_bound = None;
    let outcome = if stress_bound {
        let p = scene
            .material
            .plasticity
            .as_ref()
            .ok_or("stress_bound needs a plastic material")?;
        let mut s = scene.clone();
        if s.output.fields_every.is_none() {
            s.output.fields_every = Some(2e-6);
        }
        let mut obs = StressBound {
            flow: FlowCurve::new(p.yield_stress, &p.hardening, s.material.youngs_modulus),
            yield_stress: p.yield_stress,
            max_ratio: 0.0,
            max_eqps: 0.0,
        };
        let out = impact_solver::simulate(&s, &mut obs).map_err(|e| e.to_string())?;
        observer_bound = Some((obs.max_ratio, obs.max_eqps));
        out
    } else {
        impact_solver::simulate(scene, &mut impact_solver::Quiet).map_err(|e| e.to_string())?
    };
    let mut summary = serde_json::to_value(&outcome.summary).map_err(|e| e.to_string())?;
    if let Value::Object(map) = &mut summary {
        for k in TIMING_KEYS {
            map.remove(k);
        }
    }
    let mut metrics = BTreeMap::new();
    flatten("", &summary, &mut metrics);
    let s = &outcome.summary;
    metrics.insert(
        "contact_intervals_count".into(),
        s.contact_intervals.len() as f64,
    );
    let e0 = s.initial_energy.total();
    metrics.insert("initial_total_energy_J".into(), e0);
    metrics.insert("final_total_energy_J".into(), s.final_energy.total());
    if let (Some((mass, v0)), Some(vf)) = (scene.impactor_motion(), s.final_impactor_velocity) {
        metrics.insert("momentum_change_Ns".into(), mass * (v0 - vf));
        metrics.insert("final_momentum_kgmps".into(), mass * vf);
        metrics.insert("initial_kinetic_J".into(), 0.5 * mass * v0 * v0);
        for (k, v) in impact_discriminators(mass, v0, s.impulse, vf) {
            metrics.insert(k.into(), v);
        }
    }
    for (k, v) in crate::run::rigid_plastic::metrics(scene, s.final_energy.plastic_work) {
        metrics.insert(k.into(), v);
    }
    if let Some((ratio, eqps)) = observer_bound {
        metrics.insert("stress_flow_ratio_max".into(), ratio);
        metrics.insert("eqps_max".into(), eqps);
    }
    let mut histories = BTreeMap::new();
    histories.insert(String::new(), outcome.history);
    Ok(RunData {
        metrics,
        histories,
        info: scene_info(scene, s),
        summary: Some(summary),
        files: BTreeMap::new(),
        cost: Some(crate::definition::run_data::Cost {
            wall_time_s: s.wall_time,
            n_elements: s.n_elements as f64,
            n_steps: s.n_steps as f64,
            code_time_s: None,
        }),
        scene_values: end_values(&scene.time.end),
    })
}

/// The hardening as a scene writes it: `{linear: 4.14e9}` (Pa) or
/// `{table: [[0, 2.5e8], [0.05, 3.2e8]]}` (equivalent plastic strain, flow stress Pa).
fn hardening_text(h: &impact_solver::scene::Hardening) -> String {
    use impact_solver::scene::Hardening;
    match h {
        Hardening::Linear { tangent_modulus } => format!("{{linear: {tangent_modulus:e}}}"),
        Hardening::Table(rows) => {
            let rows: Vec<String> = rows.iter().map(|(e, s)| format!("[{e}, {s:e}]")).collect();
            format!("{{table: [{}]}}", rows.join(", "))
        }
        Hardening::Power {
            coefficient,
            exponent,
        } => format!("B k^n with B = {coefficient:e} Pa, n = {exponent}"),
    }
}

/// The rate law in words (empty when rate-independent).
fn rate_text(rate: Option<&impact_solver::input::rate_law::RateLaw>) -> String {
    use impact_solver::input::rate_law::RateLaw;
    match rate {
        None => String::new(),
        Some(RateLaw::CowperSymonds { d, q }) => {
            format!(", Cowper-Symonds D = {d} 1/s, q = {q}")
        }
        Some(RateLaw::JohnsonCook {
            c,
            reference_rate,
            thermal,
        }) => {
            let heat = thermal.as_ref().map_or(String::new(), |t| {
                format!(
                    ", adiabatic heating from {} K (melting {} K, c = {} J/(kg K), beta = {}, m = {})",
                    t.initial_temperature,
                    t.melting_temperature,
                    t.specific_heat,
                    t.taylor_quinney,
                    t.softening_exponent
                )
            });
            format!(", Johnson-Cook C = {c}, reference rate {reference_rate} 1/s{heat}")
        }
    }
}

/// The modelling of a run, in words, for the report.
pub fn scene_info(scene: &Scene, s: &impact_solver::Summary) -> BTreeMap<String, String> {
    let dt = format!(
        "{:.4e} s ({:.3} of stable {:.4e} s)",
        s.dt, s.cfl, s.dt_critical
    );
    [
        ("plate", plate_text(scene)),
        ("material", material_text(scene)),
        ("mesh", mesh_text(scene)),
        ("dt", dt),
        ("contact law", s.contact_law.clone()),
        ("load", load_text(&scene.load)),
        ("end", end_text(&scene.time.end)),
    ]
    .into_iter()
    .map(|(key, text)| (key.to_string(), text))
    .collect()
}

fn plate_text(scene: &Scene) -> String {
    let p = &scene.plate;
    format!(
        "L = {} m, W = {} m, h = {} m",
        p.length, p.width, p.thickness
    )
}

fn material_text(scene: &Scene) -> String {
    let mat = &scene.material;
    let plastic = match &mat.plasticity {
        None => "elastic".to_string(),
        Some(pl) => format!(
            "von Mises, yield {:e} Pa, hardening {}{}",
            pl.yield_stress,
            hardening_text(&pl.hardening),
            rate_text(pl.rate.as_ref())
        ),
    };
    format!(
        "rho = {} kg/m3, E = {:e} Pa, nu = {}, {plastic}",
        mat.density, mat.youngs_modulus, mat.poisson_ratio
    )
}

fn mesh_text(scene: &Scene) -> String {
    let ms = &scene.mesh;
    let model = match ms.model {
        Model::Half => "half",
        Model::Full => "full",
    };
    format!(
        "{} x {} {}, {model} model, grading {}",
        ms.nx,
        ms.ny,
        ms.element.name(),
        ms.grading
    )
}

fn load_text(load: &Load) -> String {
    match load {
        Load::Pulse(pu) => format!(
            "rectangular pulse {} N for {} s on the top mid-span node",
            pu.force, pu.duration
        ),
        Load::Impactor(i) => format!(
            "rigid impactor m = {} kg, v0 = {} m/s, r = {} m, datum {}, force on {}",
            i.mass,
            i.velocity,
            i.nose_radius,
            node_name(i.indentation_datum),
            node_name(i.force_node)
        ),
        Load::SurfaceImpactor(i) => format!(
            "rigid impactor m = {} kg, v0 = {} m/s, r = {} m, in surface contact ({:?} enforcement, penalty scale {})",
            i.mass, i.velocity, i.nose_radius, i.contact.enforcement, i.contact.penalty_scale
        ),
        Load::Traction(t) => format!(
            "uniform traction on the top surface, normal {} Pa, shear {} Pa, for {} s",
            t.normal, t.shear, t.duration
        ),
        Load::Wall(w) => format!(
            "the body at {} m/s onto a rigid frictionless wall at y = 0",
            w.velocity
        ),
    }
}

/// The scene's end (s), for the stop reason's invariant (`summary_invariants::END_VALUES`).
fn end_values(end: &End) -> BTreeMap<String, f64> {
    let [at, after_contact, limit] = crate::run::summary_invariants::END_VALUES.map(String::from);
    match *end {
        End::At(t) => BTreeMap::from([(at, t)]),
        End::AfterContact { after, limit: l } => {
            BTreeMap::from([(after_contact, after), (limit, l)])
        }
    }
}

fn end_text(end: &End) -> String {
    match *end {
        End::At(t) => format!("t = {t} s"),
        End::AfterContact { after, limit } => {
            format!("{after} s after the last contact (limit {limit} s)")
        }
    }
}

fn node_name(n: MidSpanNode) -> &'static str {
    match n {
        MidSpanNode::MidPlane => "mid-plane",
        MidSpanNode::TopSurface => "top-surface",
    }
}

/// A case's scenes resolved to jobs, by scene name (series levels are `SERIES@LEVEL`); the
/// first reason a scene does not load ([`case_jobs_or_every_error`] gives them all).
pub fn case_jobs(case: &Case) -> Result<BTreeMap<String, Job>, String> {
    case_jobs_or_every_error(case).map_err(|errors| errors.into_iter().next().unwrap_or_default())
}

/// [`case_jobs`], or why each of the case's scenes does not load with its overrides, each
/// scene on its own (`impact lint`: not only the first; a series' error comes alone, after
/// its scene loaded).
pub fn case_jobs_or_every_error(case: &Case) -> Result<BTreeMap<String, Job>, Vec<String>> {
    let mut jobs = BTreeMap::new();
    let mut errors = Vec::new();
    for (name, spec) in &case.file.scenes {
        match scene_job(&case.dir, &spec.value, &case.loc(spec)) {
            Ok(job) => {
                jobs.insert(name.clone(), job);
            }
            Err(e) => errors.push(e),
        }
    }
    if !errors.is_empty() {
        return Err(errors);
    }
    add_series(case, &mut jobs).map_err(|e| vec![e])?;
    Ok(jobs)
}

/// The levels of the case's series, each a refined copy of its scene's job.
fn add_series(case: &Case, jobs: &mut BTreeMap<String, Job>) -> Result<(), String> {
    for (name, series) in &case.file.series {
        let loc = case.loc(series);
        let s = &series.value;
        let base = match jobs.get(&s.scene) {
            Some(Job::Scene {
                scene,
                stress_bound,
                ..
            }) => ((**scene).clone(), *stress_bound),
            _ => {
                return Err(format!(
                    "{loc}: series {name}: scene {:?} is not a scene of this case",
                    s.scene
                ))
            }
        };
        for level in &s.levels {
            let scene = refine(&base.0, s.refine, *level)
                .map_err(|e| format!("{loc}: series {name}: {e}"))?;
            jobs.insert(
                series_scene_name(name, *level),
                Job::Scene {
                    scene: Box::new(scene),
                    stress_bound: base.1,
                    expect_error: Vec::new(),
                },
            );
        }
    }
    Ok(())
}

fn scene_job(dir: &Path, spec: &SceneSpec, loc: &Loc) -> Result<Job, String> {
    match (&spec.file, &spec.builtin) {
        (Some(file), None) => {
            let path = dir.join(file);
            let scene = Scene::from_file_with(&path, &spec.set)
                .map_err(|e| format!("{loc}: scene: {e}"))?;
            Ok(Job::Scene {
                scene: Box::new(scene),
                stress_bound: spec.stress_bound,
                expect_error: spec.expect_error.clone(),
            })
        }
        (None, Some(name)) => {
            let known = crate::run::builtins::names();
            if !known.clone().any(|n| n == name) {
                return Err(format!(
                    "{loc}: unknown builtin {name:?} (known: {})",
                    known.collect::<Vec<_>>().join(", ")
                ));
            }
            Ok(Job::Builtin {
                name: name.clone(),
                params: spec.params.clone(),
            })
        }
        _ => Err(format!(
            "{loc}: a scene needs exactly one of `file` or `builtin`"
        )),
    }
}

/// A refined copy of a scene: `mesh` multiplies nx and ny by `level` (the step follows the
/// mesh through the CFL number), `dt` divides the step by `level`.
pub fn refine(scene: &Scene, how: Refine, level: f64) -> Result<Scene, String> {
    let mut s = scene.clone();
    match how {
        Refine::Mesh => {
            let scale = |n: usize| -> Result<usize, String> {
                let x = n as f64 * level;
                if (x - x.round()).abs() > 1e-9 || x < 1.0 {
                    Err(format!(
                        "level {level} does not give an integer element count from {n}"
                    ))
                } else {
                    Ok(x.round() as usize)
                }
            };
            s.mesh.nx = scale(s.mesh.nx)?;
            s.mesh.ny = scale(s.mesh.ny)?;
            if s.mesh.ny % 2 != 0 {
                return Err(format!("level {level} gives an odd ny"));
            }
        }
        Refine::Dt => {
            s.time.dt = match s.time.dt {
                DtChoice::Cfl(c) => DtChoice::Cfl(c / level),
                DtChoice::Fixed(d) => DtChoice::Fixed(d / level),
            }
        }
    }
    Ok(s)
}
