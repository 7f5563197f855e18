//! The `static-collapse` builtin: the clamped plate's collapse load under a slowly ramped
//! central load, against plane-strain limit analysis. The solver's plate model (element
//! strains, the radial return of `VonMises` with perfect plasticity, assembly, lumped masses)
//! on the solver's clamped half-model mesh, marched by central differences with light
//! mass-proportional damping while the load rises linearly (quasi-static: the ramp lasts
//! tens of first periods).
//!
//! The load is a uniform pressure over a central patch of width `c` on the top surface (a
//! single node would punch locally: a point force on a perfectly plastic continuum has no
//! limit of its own). Reference (upper bound = lower bound for the beam mechanism, the
//! derivation in the case's README): hinges at both clamps and at mid-span, each half of span
//! `a = L/2` rotating by theta, the patch load doing `P theta (a - c/4)` of work against
//! `4 M_p theta`, so `P_c = 4 M_p / (a - c/4)` per unit width, with the plane-strain fully
//! plastic moment `M_p = sigma_0 h^2 / 4`, `sigma_0 = 2/sqrt(3) sigma_y`.
//!
//! Measured: the load at which the tangent slope of the load-deflection curve (mid-span,
//! mid-plane node) falls below `slope_fraction` of its elastic slope; the largest load
//! applied when it never does (a material that never yields).

use std::collections::BTreeMap;

use impact_analytical::beam::ClampedBeam;
use impact_analytical::modal_beam::ModalBeam;
use impact_solver::element::Formulation;
use impact_solver::integrator::PlateModel;
use impact_solver::material::{Elastic, VonMises};
use impact_solver::mesh::PlateMesh;
use impact_solver::model::AnyFormulation;
use impact_solver::scene::{Hardening, Material, Plasticity};
use impact_solver::History;
use serde_json::Value;

use super::plastic_material::{plastic_material, PlasticMaterial};
use super::space_time::element;
use crate::definition::run_data::RunData;
use crate::run::builtin_params::param;

type Params = BTreeMap<String, Value>;

/// The plate, the load and the march, SI units (per metre of width).
#[derive(Debug, Clone, Copy)]
struct Plate {
    material: PlasticMaterial,
    /// Clamp to clamp, m
    length: f64,
    /// m
    thickness: f64,
    /// Width of the loaded central patch, m
    patch: f64,
    /// Largest punch displacement, as a multiple of the elastic (Timoshenko) deflection at
    /// the limit load
    overdrive: f64,
    /// Duration of the push in first (Euler-Bernoulli) periods
    ramp_periods: f64,
}

impl Plate {
    /// Plane-strain limit load per unit width, N/m: `4 M_p / (a - c/2)`.
    fn limit_load(&self) -> f64 {
        let sigma_0 = 2.0 / 3f64.sqrt() * self.material.yield_stress;
        let m_p = sigma_0 * self.thickness * self.thickness / 4.0;
        4.0 * m_p / (0.5 * self.length - 0.5 * self.patch)
    }
    /// Timoshenko beam stiffness per unit width (central load), N/m per m.
    fn timoshenko_slope(&self) -> f64 {
        let beam = self.beam().expect("a valid beam");
        1.0 / (beam.euler_bernoulli_midspan(1.0) + beam.shear_midspan(1.0))
    }
    fn beam(&self) -> Result<ClampedBeam, String> {
        let m = &self.material;
        ClampedBeam::new(
            self.length,
            1.0,
            self.thickness,
            m.youngs_modulus,
            m.poisson_ratio,
        )
    }
}

/// The solver's clamped half-model mesh, `nx` x `ny`.
fn half_mesh(plate: &Plate, nx: usize, ny: usize) -> Result<PlateMesh, String> {
    let text = format!(
        "plate: {{length: {}, width: 1.0, thickness: {}}}\n\
         material: {{density: 1.0, youngs_modulus: 1.0, poisson_ratio: 0.3}}\n\
         mesh: {{nx: {nx}, ny: {ny}, model: half}}\n\
         load: {{pulse: {{force: 1.0, duration: 1.0}}}}\n\
         time: {{end: 1.0, dt: {{cfl: 0.5}}}}\n",
        plate.length, plate.thickness
    );
    let scene = impact_solver::Scene::from_yaml(&text, std::path::Path::new("(static-collapse)"))
        .map_err(|e| e.to_string())?;
    Ok(PlateMesh::new(&scene.plate, &scene.mesh))
}

/// The y dofs of the top nodes on the punch `|x - L/2| <= c/2` (the half model's part).
fn punch_dofs(plate: &Plate, mesh: &PlateMesh) -> Vec<usize> {
    let from = 0.5 * (plate.length - plate.patch) - 1e-9 * plate.length;
    let first = mesh.ny * (mesh.nx + 1);
    (first..=first + mesh.nx)
        .filter(|&n| mesh.mesh.coords[n][0] >= from)
        .map(|n| 2 * n + 1)
        .collect()
}

/// A prescribed displacement `U(t) c_d` on `dofs` (dof, component `c_d` of the unit
/// direction), `U` rising to `total` (m) over `duration` (s) at constant speed after a
/// half-cosine start over the first tenth (little vibration excited).
pub(super) struct Push {
    pub dofs: Vec<(usize, f64)>,
    pub total: f64,
    pub duration: f64,
}

impl Push {
    fn displacement(&self, t: f64) -> f64 {
        let rise = 0.1 * self.duration;
        let speed = self.total / (self.duration - 0.5 * rise);
        if t < rise {
            let w = std::f64::consts::PI / rise;
            speed * (0.5 * t - 0.5 * (w * t).sin() / w)
        } else {
            speed * (t.min(self.duration) - 0.5 * rise)
        }
    }
}

/// The solver's plate model on `mesh` (its fixed dofs held) marched by central differences
/// at 0.9 of the stable step while `push` moves its dofs: rows (time s, the reaction
/// `sum_d c_d f_int_d` (N per metre of width on the modelled part, work-conjugate to U), U m).
pub(super) fn march<F: Formulation>(
    mesh: &PlateMesh,
    f: F,
    material: VonMises,
    density: f64,
    push: &Push,
) -> Vec<[f64; 3]> {
    let mut model = PlateModel::new(f, material, mesh, density);
    let dt = 0.9 * model.critical_time_step(density);
    let steps = (push.duration / dt).ceil() as usize;
    let ndof = 2 * mesh.mesh.n_nodes();
    let (mut u, mut v, mut f_int) = (vec![0.0; ndof], vec![0.0; ndof], vec![0.0; ndof]);
    let every = (steps / 2000).max(1);
    let mut rows = Vec::with_capacity(steps / every + 2);
    for n in 0..=steps {
        let t = n as f64 * dt;
        model.internal_forces(&u, &mut f_int);
        if n % every == 0 {
            let reaction: f64 = push.dofs.iter().map(|&(d, c)| c * f_int[d]).sum();
            rows.push([t, reaction, push.displacement(t)]);
        }
        let half = if n == 0 { 0.5 } else { 1.0 };
        for d in 0..ndof {
            v[d] -= half * dt * f_int[d] * model.inverse_mass[d];
            u[d] += dt * v[d];
        }
        let now = push.displacement(t + dt);
        for &(d, c) in &push.dofs {
            u[d] = c * now;
        }
    }
    rows
}

/// Mean reaction over the last fifth of the push (the plateau of perfect plasticity).
pub(super) fn plateau(rows: &[[f64; 3]]) -> f64 {
    let last = rows[rows.len() - 1][2];
    let tail: Vec<f64> = rows
        .iter()
        .filter(|r| r[2] >= 0.8 * last)
        .map(|r| r[1])
        .collect();
    tail.iter().sum::<f64>() / tail.len() as f64
}

fn model_material(plate: &Plate, p: &Params) -> Result<VonMises, String> {
    let m = &plate.material;
    VonMises::new(&Material {
        density: m.density,
        youngs_modulus: param(p, "model_youngs_modulus", m.youngs_modulus)?,
        poisson_ratio: m.poisson_ratio,
        plasticity: Some(Plasticity {
            yield_stress: param(p, "model_yield_stress", m.yield_stress)?,
            hardening: Hardening::Linear {
                tangent_modulus: m.tangent_modulus,
            },
            rate: None,
        }),
    })
    .ok_or_else(|| "static-collapse: not a plastic material".to_string())
}

/// One plate's push: its rows (the punch force on the whole plate) and plateau over its
/// limit load.
fn push(plate: &Plate, nx: usize, ny: usize, p: &Params) -> Result<(Vec<[f64; 3]>, f64), String> {
    let mesh = half_mesh(plate, nx, ny)?;
    let elastic = Elastic::new(
        param(p, "model_youngs_modulus", plate.material.youngs_modulus)?,
        plate.material.poisson_ratio,
    );
    let any = AnyFormulation::new(element(p)?, &mesh.mesh, 1.0, 0.05, &elastic)
        .map_err(|e| e.to_string())?;
    let rho = plate.material.density;
    let modal = ModalBeam::new(&plate.beam()?, rho, 1)?;
    // Downward: the punch force (positive down) is -sum f_int, doubled for the whole plate.
    let push = Push {
        dofs: punch_dofs(plate, &mesh)
            .into_iter()
            .map(|d| (d, -1.0))
            .collect(),
        total: plate.overdrive * plate.limit_load() / plate.timoshenko_slope(),
        duration: plate.ramp_periods * modal.first_period_s(),
    };
    let vm = model_material(plate, p)?;
    let mut rows = impact_solver::with_formulation!(any, f => march(&mesh, f, vm, rho, &push));
    for r in &mut rows {
        r[1] *= 2.0;
    }
    let ratio = plateau(&rows) / plate.limit_load();
    Ok((rows, ratio))
}

fn history(rows: &[[f64; 3]]) -> History {
    History {
        columns: vec![
            "time_s".into(),
            "load_N_per_m".into(),
            "deflection_m".into(),
        ],
        values: rows.iter().flat_map(|r| r.iter().copied()).collect(),
    }
}

/// The plate (`thickness`, `nx` x `ny`) and the same plate half as thick (`2 nx` x `ny`: the
/// same elements per thickness), each pushed to `overdrive` times its elastic deflection at
/// its limit load; their plateaus over `P_c` and the linear extrapolation to `h/L -> 0`
/// (where beam theory is the 2-D solution's limit).
pub fn static_collapse(p: &Params) -> Result<RunData, String> {
    let mut material = plastic_material(p)?;
    material.tangent_modulus = param(p, "tangent_modulus", 0.0)?;
    let thick = Plate {
        material,
        length: param(p, "length", 0.2)?,
        thickness: param(p, "thickness", 0.02)?,
        patch: param(p, "patch", 0.01)?,
        overdrive: param(p, "overdrive", 10.0)?,
        ramp_periods: param(p, "ramp_periods", 10.0)?,
    };
    thick.beam()?;
    let thin = Plate {
        thickness: 0.5 * thick.thickness,
        ..thick
    };
    let nx = param(p, "nx", 40.0)? as usize;
    let ny = param(p, "ny", 8.0)? as usize;
    let (rows_thick, r_thick) = push(&thick, nx, ny, p)?;
    let (rows_thin, r_thin) = push(&thin, 2 * nx, ny, p)?;
    let mut m = BTreeMap::new();
    m.insert("limit_load_closed_form_N_per_m".into(), thick.limit_load());
    m.insert("plateau_N_per_m".into(), r_thick * thick.limit_load());
    m.insert("plateau_over_limit".into(), r_thick);
    m.insert("plateau_over_limit_half_thickness".into(), r_thin);
    m.insert(
        "plateau_over_limit_extrapolated".into(),
        2.0 * r_thin - r_thick,
    );
    m.insert(
        "gap_ratio_thick_over_thin".into(),
        (r_thick - 1.0) / (r_thin - 1.0),
    );
    Ok(RunData {
        histories: BTreeMap::from([
            (String::new(), history(&rows_thick)),
            ("half-thickness".into(), history(&rows_thin)),
        ]),
        metrics: m,
        ..Default::default()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The builtin's metrics with the parameters of `params` (a JSON object).
    fn metrics(params: Value) -> BTreeMap<String, f64> {
        let p: Params = serde_json::from_value(params).expect("an object");
        static_collapse(&p).unwrap().metrics
    }

    /// Negative controls for the case's checks: a material that never yields has no plateau
    /// (the force keeps rising: 9.2 x P_c at the end of the push); the plane-stress flow
    /// stress (sigma_0 = sigma_y, the 2/sqrt(3) of plane strain forgotten) moves the
    /// extrapolated collapse load to 0.85 P_c, outside the 5 % band.
    #[test]
    fn wrong_models_fail_the_checks() {
        let right = metrics(serde_json::json!({}));
        assert!(
            (right["plateau_over_limit_extrapolated"] - 1.0).abs() < 0.05,
            "{right:?}"
        );
        let never = metrics(serde_json::json!({"model_yield_stress": 1e12}));
        assert!(never["plateau_over_limit"] > 5.0, "{never:?}");
        let plane_stress =
            metrics(serde_json::json!({"model_yield_stress": 250e6 * 3f64.sqrt() / 2.0}));
        assert!(
            plane_stress["plateau_over_limit_extrapolated"] < 0.9,
            "{plane_stress:?}"
        );
    }
}
