//! The `table-strain-path` builtin: a tabulated flow curve (`hardening: {table: ...}`, read
//! from a scene's YAML as a user writes it) in the loop, against the piecewise-linear closed
//! form. A square block (distorted 4 x 4 mesh) is driven at a constant rate through
//! plane-strain uniaxial strain by its boundary (`u = t L x`, `L_xx = rate`), the interior
//! nodes free (the field is linear and uniform in time, so they carry no body force), as in
//! `rate-strain-path`; the solver's plate model computes the internal forces (element strains,
//! the radial return of `VonMises` on the scene's `FlowCurve`, assembly), central differences at
//! 0.8 of the stable step, until the equivalent plastic strain is past the table's last row.
//!
//! Closed form (written here from the table, not from the solver's material code):
//! - the flow stress at equivalent plastic strain `k` is the linear interpolation of the rows
//!   around `k`, and the last row's stress beyond it (flat, as the README documents);
//! - in plastic flow the von Mises stress equals the flow stress at the current `k`;
//! - uniaxial strain with plastic strain `k (1, -1/2, -1/2)`: `q = 2 mu eps - 3 mu k`, so on
//!   segment `i` (rows `(k_i, s_i)`, slope `H_i`): `k = (2 mu eps - s_i + H_i k_i) / (3 mu + H_i)`.
//!
//! Wrong models it must tell (`model_hardening` gives the solver another curve than the
//! closed form's, unit test below): the first segment's slope everywhere (a linear curve), and
//! a lookup one segment off (evaluated on the run's own path).

use std::collections::BTreeMap;

use impact_solver::element::Formulation;
use impact_solver::integrator::PlateModel;
use impact_solver::material::{von_mises, ConstitutiveModel, Elastic, VonMises};
use impact_solver::mesh::PlateMesh;
use impact_solver::model::AnyFormulation;
use impact_solver::scene::{Hardening, Material};
use serde_json::Value;

use super::driver::mapped_mesh;
use super::space_time::element;
use crate::definition::run_data::RunData;
use crate::run::builtin_params::param;

type Params = BTreeMap<String, Value>;

/// The default table: (equivalent plastic strain, flow stress Pa), three segments of slopes
/// 5, 2 and 0.33 GPa, flat after 6 %.
const TABLE: [[f64; 2]; 4] = [[0.0, 250e6], [0.01, 300e6], [0.03, 340e6], [0.06, 350e6]];

/// The scene the material is read from, as a user writes it (steel; the plate, mesh and load
/// are only there to make a valid scene: the block below is the builtin's own).
fn scene_text(table: &[[f64; 2]]) -> String {
    let rows: Vec<String> = table
        .iter()
        .map(|r| format!("[{:e}, {:e}]", r[0], r[1]))
        .collect();
    format!(
        "plate: {{length: 0.2, width: 0.2, thickness: 0.02}}\n\
         material:\n  density: 7850.0\n  youngs_modulus: 200.0e9\n  poisson_ratio: 0.3\n  \
         plasticity:\n    yield_stress: {:e}\n    hardening: {{table: [{}]}}\n\
         mesh: {{nx: 20, ny: 4}}\n\
         load: {{pulse: {{force: 1.0e3, duration: 1.0e-5}}}}\n\
         time: {{end: 1.0e-5, dt: {{cfl: 0.8}}}}\n",
        table[0][1],
        rows.join(", ")
    )
}

/// The table's flow stress at `k` (Pa): linear between rows, the last row's beyond it.
pub(crate) fn table_flow(table: &[[f64; 2]], k: f64) -> f64 {
    let last = table[table.len() - 1];
    if k >= last[0] {
        return last[1];
    }
    let i = (0..table.len() - 1)
        .rev()
        .find(|&i| table[i][0] <= k)
        .unwrap_or(0);
    let (a, b) = (table[i], table[i + 1]);
    a[1] + (b[1] - a[1]) * (k - a[0]) / (b[0] - a[0])
}

/// The closed-form equivalent plastic strain at axial strain `eps` of uniaxial strain (0 while
/// elastic), shear modulus `mu` Pa.
fn closed_form_eqps(table: &[[f64; 2]], mu: f64, eps: f64) -> f64 {
    let q_trial = 2.0 * mu * eps;
    if q_trial <= table[0][1] {
        return 0.0;
    }
    for i in 0..table.len() {
        let (k0, s0) = (table[i][0], table[i][1]);
        let h = table.get(i + 1).map_or(0.0, |b| (b[1] - s0) / (b[0] - k0));
        let k = (q_trial - s0 + h * k0) / (3.0 * mu + h);
        if table.get(i + 1).is_none_or(|b| k <= b[0]) {
            return k;
        }
    }
    unreachable!("the last segment has no end")
}

/// Per sampled step: axial strain (-), von Mises stress and eqps of every point (Pa, -).
struct Run {
    rows: Vec<(f64, Vec<(f64, f64)>)>,
}

fn march<F: Formulation>(
    mesh: &PlateMesh,
    f: F,
    (rate, end): (f64, f64),
    mat: VonMises,
    rho: f64,
) -> Run {
    let mut model = PlateModel::new(f, mat, mesh, rho);
    let dt = 0.8 * model.critical_time_step(rho);
    let steps = (end / dt).ceil() as usize;
    let coords = &mesh.mesh.coords;
    let ndof = 2 * coords.len();
    let mut u = vec![0.0; ndof];
    let mut v: Vec<f64> = coords.iter().flat_map(|&x| [rate * x[0], 0.0]).collect();
    let mut f_int = vec![0.0; ndof];
    let mut rows = Vec::new();
    let every = (steps / 400).max(1);
    let points: Vec<(usize, usize)> = (0..model.formulation.n_elements())
        .flat_map(|e| (0..F::POINTS).map(move |p| (e, p)))
        .collect();
    for n in 0..=steps {
        let t = n as f64 * dt;
        model.internal_forces(&u, &mut f_int);
        if n % every == 0 || n == steps {
            let at = points
                .iter()
                .map(|&(e, p)| {
                    let k = model.material.equivalent_plastic_strain(&model.state(e, p));
                    (von_mises(&model.point_stress(e, p, &u)), k)
                })
                .collect();
            rows.push((rate * t, at));
        }
        if n == steps {
            break;
        }
        let half = if n == 0 { 0.5 } else { 1.0 };
        for d in 0..ndof {
            if mesh.fixed_dofs[d] {
                u[d] = if d % 2 == 0 {
                    (t + dt) * rate * coords[d / 2][0]
                } else {
                    0.0
                };
                continue;
            }
            v[d] -= half * dt * f_int[d] * model.inverse_mass[d];
            u[d] += dt * v[d];
        }
    }
    Run { rows }
}

/// The table of param `table` (rows `[eqps, Pa]`) or [`TABLE`].
fn table(p: &Params) -> Result<Vec<[f64; 2]>, String> {
    let Some(v) = p.get("table") else {
        return Ok(TABLE.to_vec());
    };
    serde_json::from_value(v.clone()).map_err(|e| format!("param table: {v}: {e}"))
}

/// The material the solver is given: the scene's (read from [`scene_text`]), or with
/// `model_hardening: first-slope` the negative control, the first segment's slope everywhere.
fn model_material(p: &Params, table: &[[f64; 2]]) -> Result<Material, String> {
    let text = scene_text(table);
    let scene = impact_solver::Scene::from_yaml(&text, std::path::Path::new("table-strain-path"))
        .map_err(|e| e.to_string())?;
    let mut material = scene.material.clone();
    match p.get("model_hardening").and_then(Value::as_str) {
        None => {}
        Some("first-slope") => {
            let h = (table[1][1] - table[0][1]) / (table[1][0] - table[0][0]);
            let e = material.youngs_modulus;
            if let Some(pl) = material.plasticity.as_mut() {
                pl.hardening = Hardening::Linear {
                    tangent_modulus: e * h / (e + h),
                };
            }
        }
        Some(other) => {
            return Err(format!(
                "param model_hardening: {other}, expected first-slope"
            ))
        }
    }
    Ok(material)
}

pub fn table_strain_path(p: &Params) -> Result<RunData, String> {
    let table = table(p)?;
    let material = model_material(p, &table)?;
    let mu = material.youngs_modulus / (2.0 * (1.0 + material.poisson_ratio));
    let k_end = param(p, "eqps_over_last_row", 1.5)? * table[table.len() - 1][0];
    // The axial strain at which the eqps reaches k_end (flat tail: q = s_last).
    let strain = (table[table.len() - 1][1] + 3.0 * mu * k_end) / (2.0 * mu);
    let rate = param(p, "rate", 100.0)?;
    let mesh = mapped_mesh(0.01, 0.01, 4, 4, 0.1)?;
    let any = AnyFormulation::new(
        element(p)?,
        &mesh.mesh,
        1.0,
        0.05,
        &Elastic::new(material.youngs_modulus, material.poisson_ratio),
    )
    .map_err(|e| e.to_string())?;
    let mat = VonMises::new(&material).ok_or("table-strain-path: not a plastic material")?;
    let rho = material.density;
    let run = impact_solver::with_formulation!(any, f => march(&mesh, f, (rate, strain / rate), mat, rho));
    let (mut flow_err, mut eqps_err, mut k_max) = (0.0f64, 0.0f64, 0.0f64);
    let mut segments = std::collections::BTreeSet::new();
    // `time_s` holds the axial strain (-), the plots' x axis; point 0 of element 0.
    let columns = [
        "time_s",
        "von_mises_Pa",
        "eqps",
        "table_flow_stress_Pa",
        "closed_form_eqps",
    ];
    let mut values = Vec::new();
    for (eps, at) in &run.rows {
        let k_exact = closed_form_eqps(&table, mu, *eps);
        for &(q, k) in at {
            if k > 0.0 {
                flow_err = flow_err.max((q - table_flow(&table, k)).abs());
                segments.insert(table.iter().filter(|r| r[0] <= k).count());
            }
            eqps_err = eqps_err.max((k - k_exact).abs());
            k_max = k_max.max(k);
        }
        let (q0, k0) = at[0];
        values.extend([*eps, q0, k0, table_flow(&table, k0), k_exact]);
    }
    let sigma_y = table[0][1];
    let m = BTreeMap::from([
        (
            "flow_stress_error_over_yield".to_string(),
            flow_err / sigma_y,
        ),
        ("eqps_error".to_string(), eqps_err),
        ("eqps_max".to_string(), k_max),
        ("eqps_last_row".to_string(), table[table.len() - 1][0]),
        ("segments_visited".to_string(), segments.len() as f64),
    ]);
    let history = impact_solver::History {
        columns: columns.iter().map(|c| c.to_string()).collect(),
        values,
    };
    Ok(RunData::with_history(m, history))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn metrics(extra: &[(&str, Value)]) -> BTreeMap<String, f64> {
        let mut p = Params::new();
        for (k, v) in extra {
            p.insert(k.to_string(), v.clone());
        }
        table_strain_path(&p).unwrap().metrics
    }

    /// The closed forms by hand on the default table, and the negative controls: the solver
    /// given the first segment's slope everywhere misses the table's flow stress by 1.37 of
    /// the yield stress (measured; the case's tolerance is 1.5e-13) and the eqps by 1.5e-3,
    /// and a lookup one segment off, evaluated on eqps from 0 to 6 %, by 0.133 of it.
    #[test]
    fn wrong_flow_curves_fail_the_checks() {
        let t = TABLE.to_vec();
        assert_eq!(table_flow(&t, 0.02), 320e6);
        assert_eq!(table_flow(&t, 0.1), 350e6);
        assert_eq!(table_flow(&t, 0.0), 250e6);
        let right = metrics(&[]);
        assert!(right["flow_stress_error_over_yield"] < 1e-13, "{right:?}");
        assert!(right["eqps_error"] < 1e-13, "{right:?}");
        assert_eq!(right["segments_visited"], 4.0);
        let first = metrics(&[("model_hardening", Value::from("first-slope"))]);
        assert!(first["flow_stress_error_over_yield"] > 1.0, "{first:?}");
        assert!(first["eqps_error"] > 1e-3, "{first:?}");
        // One segment off: rows i+1, i+2 used on segment i (the last one's tail flat).
        let off = |k: f64| {
            let i = t.iter().filter(|r| r[0] <= k).count() - 1;
            match (t.get(i + 1), t.get(i + 2)) {
                (Some(a), Some(b)) => a[1] + (b[1] - a[1]) * (k - a[0]) / (b[0] - a[0]),
                _ => t[t.len() - 1][1],
            }
        };
        let miss = (0..=60)
            .map(|j| 0.001 * j as f64)
            .map(|k| (off(k) - table_flow(&t, k)).abs() / 250e6)
            .fold(0.0, f64::max);
        assert!(miss > 0.1, "{miss}");
    }
}
