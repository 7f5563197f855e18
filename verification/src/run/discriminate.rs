//! Discriminating power (issue 10, section 1): every evidence check of a case (reference kind
//! paper, calibration, invariant, acceptance, independent code, other codes, other code or experiment) re-evaluated on the results of trivial or
//! wrong models declared in the case's `wrong_models`: a rigid wall (closed form), another
//! scene read in place of one (the elastic plate in the elasto-plastic row), or the case's
//! scenes re-run with overrides (the plate with E x 0.5 and x 2). A check that a trivial
//! model passes cannot tell a plate from no plate; the report shows the table.

use std::collections::BTreeMap;
use std::sync::Arc;

use serde::Serialize;

use crate::definition::case::{Case, CheckFile, RefKind, WrongModelSpec};
use crate::definition::check::{self, Context, Status};
use crate::definition::run_data::{JobResult, RunData};

/// The reference kinds whose checks the table covers (analytical: the physics bounds of
/// issue 27, e.g. the rigid-plastic band, whose wrong models must fail; independent code:
/// the Python FE's run of the unmodified scene, which a wrong model's run must miss).
pub const KINDS: [RefKind; 9] = [
    RefKind::Analytical,
    RefKind::IndependentCode,
    RefKind::Paper,
    RefKind::Calibration,
    RefKind::Invariant,
    RefKind::Acceptance,
    RefKind::OtherCodes,
    RefKind::OtherCode,
    RefKind::Experiment,
];

/// One wrong model's value for one check.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ModelValue {
    pub model: String,
    /// None: the model has no value for this measure (e.g. a rigid wall's peak force).
    pub value: Option<f64>,
    /// "passes", "fails", "same as ours" (the model does not change what the check reads)
    /// or "n/a" (no finite value).
    pub verdict: &'static str,
}

/// One row of the discriminating-power table.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Row {
    pub check: String,
    pub kind: String,
    pub tolerance: String,
    pub computed: Option<f64>,
    pub reference: Option<f64>,
    pub models: Vec<ModelValue>,
}

/// The name of a wrong model's run of `scene`.
pub fn run_name(scene: &str, model: &str) -> String {
    format!("{scene}~{model}")
}

/// The runs the case's `set` models need: `SCENE~MODEL` for each of their scenes, the
/// scene's file with its own overrides and the model's on top (as one set of overrides).
/// Heavy models only with `include_heavy`.
pub fn jobs(
    case: &Case,
    base: &BTreeMap<String, crate::run::jobs::Job>,
    include_heavy: bool,
) -> Result<BTreeMap<String, crate::run::jobs::Job>, String> {
    let mut out = BTreeMap::new();
    for (model, spec) in &case.file.wrong_models {
        let loc = case.loc(spec);
        let spec = &spec.value;
        if spec.set.is_empty() || (spec.heavy && !include_heavy) {
            continue;
        }
        for scene in &spec.scenes {
            let (Some(s), Some(crate::run::jobs::Job::Scene { stress_bound, .. })) =
                (case.file.scenes.get(scene), base.get(scene))
            else {
                return Err(format!(
                    "{loc}: wrong model {model}: {scene:?} is not a scene of this case"
                ));
            };
            let file =
                s.value.file.as_ref().ok_or_else(|| {
                    format!("{loc}: wrong model {model}: scene {scene} has no file")
                })?;
            let mut set = s.value.set.clone();
            set.extend(spec.set.clone());
            let run = impact_solver::scene::Scene::from_file_with(&case.dir.join(file), &set)
                .map_err(|e| format!("{loc}: wrong model {model}: {e}"))?;
            out.insert(
                run_name(scene, model),
                crate::run::jobs::Job::Scene {
                    scene: Box::new(run),
                    stress_bound: *stress_bound,
                    expect_error: Vec::new(),
                },
            );
        }
    }
    Ok(out)
}

/// What a rigid wall gives in place of an impact run: I = 2 m v0, v_f = -v0, nothing in the
/// plate. Scenes without an impactor have no rigid-wall counterpart (None).
fn rigid_wall(d: &RunData) -> Option<RunData> {
    let m = &d.metrics;
    let kinetic = *m.get("initial_kinetic_J")?;
    let momentum = m.get("momentum_change_Ns")? + m.get("final_momentum_kgmps")?; // m v0
    let v0 = 2.0 * kinetic / momentum;
    let mass = momentum / v0;
    let mut r = BTreeMap::new();
    for (k, v) in crate::run::jobs::impact_discriminators(mass, v0, 2.0 * momentum, -v0) {
        r.insert(k.to_string(), v);
    }
    for (k, v) in [
        ("impulse_Ns", 2.0 * momentum),
        ("momentum_change_Ns", 2.0 * momentum),
        ("final_impactor_velocity_mps", -v0),
        ("final_momentum_kgmps", -momentum),
        ("initial_kinetic_J", kinetic),
        ("initial_total_energy_J", kinetic),
        ("max_plate_displacement_m", 0.0),
        ("max_energy_balance_error", 0.0),
        ("impulse_momentum_error", 0.0),
        ("final_energy_J.plastic_work", 0.0),
    ] {
        r.insert(k.to_string(), v);
    }
    for k in m.keys().filter(|k| k.starts_with("max_von_mises_Pa.")) {
        r.insert(k.clone(), 0.0);
    }
    // closed forms of the scene's plate and impactor, not results of the run
    for k in crate::run::rigid_plastic::SCENE_KEYS {
        if let Some(v) = m.get(k) {
            r.insert(k.to_string(), *v);
        }
    }
    Some(RunData {
        metrics: r,
        ..Default::default()
    })
}

/// The results the checks read under a wrong model.
fn model_results(
    model: &str,
    spec: &WrongModelSpec,
    results: &BTreeMap<String, JobResult>,
) -> BTreeMap<String, JobResult> {
    let mut out = results.clone();
    if spec.rigid_wall {
        for (name, r) in results {
            let wall = r.as_ref().ok().and_then(|d| rigid_wall(d));
            out.insert(
                name.clone(),
                wall.map(Arc::new)
                    .ok_or_else(|| "no rigid-wall counterpart".to_string()),
            );
        }
    }
    for (scene, by) in &spec.replace {
        if let Some(r) = results.get(by) {
            out.insert(scene.clone(), r.clone());
        }
    }
    for scene in &spec.scenes {
        let r = results
            .get(&run_name(scene, model))
            .cloned()
            .unwrap_or_else(|| Err("not run (heavy wrong model: full matrix only)".into()));
        out.insert(scene.clone(), r);
    }
    out
}

/// The table rows of one case: each evidence check under each wrong model.
pub fn rows(case: &Case, checks: &[&CheckFile], ctx: &Context) -> Vec<Row> {
    if case.file.wrong_models.is_empty() {
        return Vec::new();
    }
    let per_model: Vec<(String, BTreeMap<String, JobResult>)> = case
        .file
        .wrong_models
        .iter()
        .map(|(name, spec)| (name.clone(), model_results(name, &spec.value, ctx.results)))
        .collect();
    let mut rows = Vec::new();
    for k in checks {
        let base = check::evaluate(k, ctx);
        if !KINDS.iter().any(|kind| kind.name() == base.reference_kind) {
            continue;
        }
        let models = per_model
            .iter()
            .map(|(name, results)| {
                let c = Context {
                    results,
                    series: ctx.series,
                    root: ctx.root,
                    default_scene: ctx.default_scene,
                };
                let mut r = check::evaluate(k, &c);
                let finite = r.computed.filter(|v| v.is_finite());
                // Against a measurement the wrong model meets our budget (k u_val of the right
                // model): its own would measure its coarse and input scenes against ours.
                if let (Some(row), Some(v)) = (&base.validation, finite) {
                    let covered = (v - row.measurement).abs() <= row.k * row.u_val;
                    r.status = if covered { Status::Ok } else { Status::Fail };
                }
                let verdict = match (r.status, finite) {
                    // the model does not change what this check reads (e.g. the elastic
                    // plate in the elasto-plastic row, for an elastic-row check)
                    (_, Some(v)) if Some(v) == base.computed => "same as ours",
                    (Status::Ok, _) => "passes",
                    (Status::Fail, Some(_)) => "fails",
                    _ => "n/a",
                };
                ModelValue {
                    model: name.clone(),
                    value: finite,
                    verdict,
                }
            })
            .collect();
        rows.push(Row {
            check: k.id.clone(),
            kind: base.reference_kind,
            tolerance: base.tolerance,
            computed: base.computed,
            reference: base.reference,
            models,
        });
    }
    rows
}

/// The titles of a case's wrong models, by name.
pub fn titles(case: &Case) -> BTreeMap<String, String> {
    case.file
        .wrong_models
        .iter()
        .map(|(k, v)| (k.clone(), v.value.title.clone()))
        .collect()
}
