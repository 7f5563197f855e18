//! The `plastic-strain-path` builtin: plasticity in the loop. A square block (distorted mesh)
//! of von Mises material with linear isotropic hardening is driven through a homogeneous
//! plane-strain uniaxial-strain path `eps_xx(t) = eps_max sin(pi t / T)` (loading beyond
//! yield, unloading with reverse yielding) by its boundary: every boundary node moves as
//! `u = eps(t) x`, the interior nodes are free and carry the body force that makes the
//! homogeneous field an exact solution, `rho eps''(t) x`, lumped like the mass
//! (`m_a eps''(t) x_a`). The solver's plate model computes the internal forces (element
//! strains, the radial return of `VonMises`, assembly); the march is the central-difference
//! update of ALGORITHM.md section 6 with the boundary prescribed.
//!
//! The reference is the closed-form stress path of uniaxial strain with linear isotropic
//! hardening, written here from E, nu, sigma_y and E_t (not from the solver's material code):
//! with the plastic strain `eps_p (1, -1/2, -1/2)`, `q = |2 mu eps - 3 mu eps_p|`,
//! - loading: elastic up to `eps_y = sigma_y / (2 mu)`, then
//!   `eps_p = (eps - eps_y) 2 mu / (3 mu + H)`, `H = E E_t / (E - E_t)`, kappa = eps_p;
//! - unloading from `eps_max` (plastic strain `e1`, flow stress `s1 = sigma_y + H e1`):
//!   elastic down to `eps_r = 1.5 e1 - s1 / (2 mu)`, then reverse yielding with
//!   `eps_p = (sigma_y + 2 H e1 + 2 mu eps) / (3 mu + H)`, kappa = 2 e1 - eps_p;
//! - stresses `s_xx = (lambda + 2 mu) eps - 2 mu eps_p`, `s_yy = s_zz = lambda eps + mu eps_p`,
//!   `s_xy = 0`.
//!
//! The only discretisation error is the interior nodes' central-difference motion
//! (O(dt^2)): the stress error must fall at order 2 in dt.

use std::collections::BTreeMap;

use impact_solver::element::Formulation;
use impact_solver::integrator::PlateModel;
use impact_solver::material::{ConstitutiveModel, Elastic, Stress, VonMises};
use impact_solver::mesh::PlateMesh;
use impact_solver::model::AnyFormulation;
use impact_solver::scene::{Hardening, Material, Plasticity};
use impact_solver::History;
use serde_json::Value;

use super::driver::mapped_mesh;
use super::orders::{largest_step, pair_orders};
use super::plastic_material::plastic_material;
use super::space_time::element;
use crate::codes::problem::Fields;
use crate::definition::run_data::RunData;
use crate::run::builtin_params::{param, param_levels};

type Params = BTreeMap<String, Value>;

/// The material and the path, SI units.
#[derive(Debug, Clone, Copy)]
pub(super) struct Path {
    pub(super) youngs_modulus: f64,
    pub(super) poisson_ratio: f64,
    pub(super) yield_stress: f64,
    tangent_modulus: f64,
    density: f64,
    /// Largest axial strain (-)
    pub(super) eps_max: f64,
    /// Duration of the load-unload cycle, s
    pub(super) period: f64,
    /// The solver's material: yield stress and tangent modulus, Pa (the closed form's unless
    /// a negative control sets `model_yield_stress` / `model_tangent_modulus`).
    pub(super) model: (f64, f64),
}

impl Path {
    fn lame(&self) -> (f64, f64) {
        let (e, nu) = (self.youngs_modulus, self.poisson_ratio);
        (
            e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)),
            e / (2.0 * (1.0 + nu)),
        )
    }
    fn plastic_modulus(&self) -> f64 {
        let (e, et) = (self.youngs_modulus, self.tangent_modulus);
        e * et / (e - et)
    }
    /// Yield strain of uniaxial strain, `sigma_y / (2 mu)`.
    pub(super) fn yield_strain(&self) -> f64 {
        self.yield_stress / (2.0 * self.lame().1)
    }
    /// The time of step `n` of `steps` over the cycle, `n T / steps`, s.
    pub(super) fn time(&self, n: usize, steps: usize) -> f64 {
        n as f64 * (self.period / steps as f64)
    }
    pub(super) fn strain(&self, t: f64) -> f64 {
        self.eps_max * (std::f64::consts::PI * t / self.period).sin()
    }
    fn strain_acceleration(&self, t: f64) -> f64 {
        let w = std::f64::consts::PI / self.period;
        -w * w * self.strain(t)
    }
    fn strain_rate(&self, t: f64) -> f64 {
        let w = std::f64::consts::PI / self.period;
        w * self.eps_max * (w * t).cos()
    }
    /// Closed form at time t: (stress [xx, yy, zz, xy], equivalent plastic strain).
    pub(super) fn exact(&self, t: f64) -> (Stress, f64) {
        let (lambda, mu) = self.lame();
        let h = self.plastic_modulus();
        let (eps, ey) = (self.strain(t), self.yield_strain());
        let slope = 2.0 * mu / (3.0 * mu + h);
        let (eps_p, kappa) = if t <= 0.5 * self.period {
            let ep = ((eps - ey) * slope).max(0.0);
            (ep, ep)
        } else {
            let e1 = ((self.eps_max - ey) * slope).max(0.0);
            let s1 = self.yield_stress + h * e1;
            if eps >= 1.5 * e1 - s1 / (2.0 * mu) {
                (e1, e1)
            } else {
                let ep = (self.yield_stress + 2.0 * h * e1 + 2.0 * mu * eps) / (3.0 * mu + h);
                (ep, 2.0 * e1 - ep)
            }
        };
        let lateral = lambda * eps + mu * eps_p;
        (
            [
                (lambda + 2.0 * mu) * eps - 2.0 * mu * eps_p,
                lateral,
                lateral,
                0.0,
            ],
            kappa,
        )
    }
    fn material(&self) -> VonMises {
        VonMises::new(&Material {
            density: self.density,
            youngs_modulus: self.youngs_modulus,
            poisson_ratio: self.poisson_ratio,
            plasticity: Some(Plasticity {
                yield_stress: self.model.0,
                hardening: Hardening::Linear {
                    tangent_modulus: self.model.1,
                },
                rate: None,
            }),
        })
        .expect("a plastic material")
    }
}

/// One run: the fields at every step (`t = n dt`, `n = 0 .. steps`), as another code writes
/// them (`crate::codes::problem`), and the stable step, s.
struct Run {
    fields: Vec<Fields>,
    dt_critical: f64,
}

impl Run {
    /// The rows of its steps ([`row`]).
    fn rows(&self, path: &Path) -> Vec<[f64; 6]> {
        let steps = self.fields.len() - 1;
        let rows = self.fields.iter().enumerate();
        rows.map(|(n, f)| row(path, path.time(n, steps), f))
            .collect()
    }
}

/// The model's fields at displacements `u` (m) with internal forces `f_int` (N).
fn step_fields<F: Formulation>(
    model: &PlateModel<F, VonMises>,
    u: &[f64],
    f_int: &[f64],
) -> Fields {
    let pairs = |v: &[f64]| v.chunks(2).map(|c| [c[0], c[1]]).collect();
    let elements = 0..model.formulation.n_elements();
    let points = |e: usize| (0..F::POINTS).map(move |p| (e, p));
    Fields {
        displacements: pairs(u),
        nodal_forces: Some(pairs(f_int)),
        point_stresses: (elements.clone())
            .map(|e| {
                points(e)
                    .map(|(e, p)| model.point_stress(e, p, u))
                    .collect()
            })
            .collect(),
        point_eqps: Some(
            elements
                .map(|e| {
                    (points(e))
                        .map(|(e, p)| model.material.equivalent_plastic_strain(&model.state(e, p)))
                        .collect()
                })
                .collect(),
        ),
    }
}

fn march<F: Formulation>(path: &Path, mesh: &PlateMesh, f: F, steps: usize) -> Run {
    let mut model = PlateModel::new(f, path.material(), mesh, path.density);
    let dt_critical = model.critical_time_step(path.density);
    let dt = path.period / steps as f64;
    let x: Vec<f64> = mesh.mesh.coords.iter().map(|c| c[0]).collect();
    let ndof = 2 * x.len();
    let mut u = vec![0.0; ndof];
    let mut v: Vec<f64> = (0..ndof)
        .map(|d| uniaxial(d, x[d / 2], path.strain_rate(0.0)))
        .collect();
    let mut f_int = vec![0.0; ndof];
    let mut fields = Vec::with_capacity(steps + 1);
    for n in 0..=steps {
        let t = path.time(n, steps);
        model.internal_forces(&u, &mut f_int);
        fields.push(step_fields(&model, &u, &f_int));
        if n == steps {
            break;
        }
        let t_next = t + dt;
        let acc = path.strain_acceleration(t);
        let half = if n == 0 { 0.5 } else { 1.0 };
        for d in 0..ndof {
            if mesh.fixed_dofs[d] {
                u[d] = uniaxial(d, x[d / 2], path.strain(t_next));
                continue;
            }
            let body = uniaxial(d, x[d / 2], acc);
            v[d] += half * dt * (body - f_int[d] * model.inverse_mass[d]);
            u[d] += dt * v[d];
        }
    }
    Run {
        fields,
        dt_critical,
    }
}

/// Component `d` (a global dof, `2 node + axis`) of the field `a x e_x` at a node of abscissa
/// `x` (m): the homogeneous uniaxial field of the path, for `a` a strain, a strain rate or a
/// strain acceleration.
pub(super) fn uniaxial(d: usize, x: f64, a: f64) -> f64 {
    if d % 2 == 0 {
        a * x
    } else {
        0.0
    }
}

/// The path marched in `steps` steps on the case's element.
fn run(path: &Path, mesh: &PlateMesh, p: &Params, steps: usize) -> Result<Run, String> {
    let kind = element(p)?;
    let elastic = Elastic::new(path.youngs_modulus, path.poisson_ratio);
    let any =
        AnyFormulation::new(kind, &mesh.mesh, 1.0, 0.05, &elastic).map_err(|e| e.to_string())?;
    let r = impact_solver::with_formulation!(any, f => march(path, mesh, f, steps));
    let dt = path.period / steps as f64;
    if dt > r.dt_critical {
        return Err(format!(
            "plastic-strain-path: dt {dt:.3e} s above the stable step {:.3e} s",
            r.dt_critical
        ));
    }
    Ok(r)
}

/// The row of the step at time `t` (s) from its `fields`: the time, the prescribed strain,
/// the largest stress error over the points and components (/ sigma_y), the largest eqps
/// error (/ eps_y; 0 without eqps), and the first point of the first element's s_xx (Pa) and
/// eqps (NaN without).
pub(super) fn row(path: &Path, t: f64, fields: &Fields) -> [f64; 6] {
    let (sy, ey) = (path.yield_stress, path.yield_strain());
    let (exact, kappa) = path.exact(t);
    let stress_error = (fields.point_stresses.iter().flatten())
        .flat_map(|s| (0..4).map(move |c| (s[c] - exact[c]).abs() / sy))
        .fold(0.0f64, f64::max);
    let eqps = fields.point_eqps.as_ref();
    let eqps_error = (eqps.into_iter().flatten().flatten())
        .map(|k| (k - kappa).abs() / ey)
        .fold(0.0f64, f64::max);
    let s0 = fields.point_stresses[0][0][0];
    let k0 = eqps.map_or(f64::NAN, |e| e[0][0]);
    [t, path.strain(t), stress_error, eqps_error, s0, k0]
}

/// First row (loading half) with plastic strain at point 0, its strain (-).
fn onset_strain(rows: &[[f64; 6]]) -> Option<f64> {
    rows.iter().find(|r| r[5] > 0.0).map(|r| r[1])
}

/// Secant slope d sigma_xx / d eps of point 0 between the loading rows nearest to
/// `2 eps_y` and `4 eps_y`, Pa.
fn loading_slope(rows: &[[f64; 6]], ey: f64) -> f64 {
    let loading = &rows[..rows.len() / 2];
    let nearest = |target: f64| {
        loading
            .iter()
            .min_by(|a, b| (a[1] - target).abs().total_cmp(&(b[1] - target).abs()))
            .expect("rows")
    };
    let (a, b) = (nearest(2.0 * ey), nearest(4.0 * ey));
    (b[4] - a[4]) / (b[1] - a[1])
}

/// The case's path, its mesh (a distorted `n x n` block) and the step counts of its levels.
pub(super) fn setup(p: &Params) -> Result<(Path, PlateMesh, Vec<usize>), String> {
    let mat = plastic_material(p)?;
    let mut path = Path {
        youngs_modulus: mat.youngs_modulus,
        poisson_ratio: mat.poisson_ratio,
        yield_stress: mat.yield_stress,
        tangent_modulus: mat.tangent_modulus,
        density: mat.density,
        eps_max: 0.0,
        period: param(p, "period", 2.0e-5)?,
        model: (0.0, 0.0),
    };
    path.model = (
        param(p, "model_yield_stress", path.yield_stress)?,
        param(p, "model_tangent_modulus", path.tangent_modulus)?,
    );
    path.eps_max = param(p, "strain_over_yield", 5.0)? * path.yield_strain();
    let side = param(p, "side", 0.01)?;
    let n = param(p, "n", 4.0)? as usize;
    let mesh = mapped_mesh(side, side, n, n, param(p, "distortion", 0.1)?)?;
    let levels = param_levels(p, "steps", &[100, 200, 400, 800])?;
    if levels.len() < 3 || levels.windows(2).any(|w| w[1] != 2 * w[0]) {
        return Err("param steps: at least three, each twice the previous".into());
    }
    Ok((path, mesh, levels))
}

pub fn plastic_strain_path(p: &Params) -> Result<RunData, String> {
    let (path, mesh, levels) = setup(p)?;
    let mut m = BTreeMap::new();
    let (mut es, mut ek) = (Vec::new(), Vec::new());
    let mut finest = None;
    for &steps in &levels {
        let r = run(&path, &mesh, p, steps)?;
        let rows = r.rows(&path);
        let s = rows.iter().fold(0.0f64, |a, row| a.max(row[2]));
        let k = rows.iter().fold(0.0f64, |a, row| a.max(row[3]));
        m.insert(format!("stress_error_n{steps}"), s);
        m.insert(format!("eqps_error_n{steps}"), k);
        es.push(s);
        ek.push(k);
        finest = Some((r.dt_critical, rows));
    }
    let (dt_critical, rows) = finest.expect("levels");
    let orders = pair_orders(&es, 2.0);
    m.insert("stress_order_finest".into(), orders[orders.len() - 1]);
    m.insert("stress_order_largest_step".into(), largest_step(&orders));
    for (k, w) in levels.windows(2).enumerate() {
        m.insert(format!("stress_order_n{}_n{}", w[0], w[1]), orders[k]);
    }
    m.insert("dt_over_critical_finest".into(), {
        let dt = path.period / levels[levels.len() - 1] as f64;
        dt / dt_critical
    });
    Ok(path_run(&path, &rows, m))
}

/// The metrics every computation of the path gives (the finest level's errors, the yield
/// onset, the hardening slope, the state back at zero strain) beside `m`, and the history of
/// point 0, from `rows`: per step the time, the prescribed strain, the largest stress error over
/// the points (/ sigma_y), the largest eqps error (/ eps_y), and point 0 of element 0's
/// sigma_xx and eqps.
pub(super) fn path_run(path: &Path, rows: &[[f64; 6]], mut m: BTreeMap<String, f64>) -> RunData {
    let largest = |c: usize| rows.iter().fold(0.0f64, |a, row| a.max(row[c]));
    m.insert("stress_error_finest".into(), largest(2));
    m.insert("eqps_error_finest".into(), largest(3));
    let ey = path.yield_strain();
    if let Some(on) = onset_strain(rows) {
        m.insert("yield_onset_strain".into(), on);
    }
    m.insert("yield_strain_closed_form".into(), ey);
    m.insert("loading_slope_Pa".into(), loading_slope(rows, ey));
    let (lambda, mu) = path.lame();
    let h = path.plastic_modulus();
    m.insert(
        "loading_slope_closed_form_Pa".into(),
        lambda + 2.0 * mu - 4.0 * mu * mu / (3.0 * mu + h),
    );
    let last = rows[rows.len() - 1];
    let (exact_end, kappa_end) = path.exact(path.period);
    m.insert("final_sxx_Pa".into(), last[4]);
    m.insert("final_sxx_closed_form_Pa".into(), exact_end[0]);
    m.insert("final_eqps".into(), last[5]);
    m.insert("final_eqps_closed_form".into(), kappa_end);
    let mut values = Vec::new();
    for row in rows {
        let (s, k) = path.exact(row[0]);
        values.extend([row[0], row[1], row[4], s[0], row[5], k]);
    }
    let columns = [
        "time_s",
        "strain_xx",
        "sxx_Pa",
        "sxx_closed_form_Pa",
        "eqps",
        "eqps_closed_form",
    ];
    let history = History {
        columns: columns.iter().map(|s| s.to_string()).collect(),
        values,
    };
    RunData {
        histories: BTreeMap::from([(String::new(), history)]),
        metrics: m,
        ..Default::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn metrics(extra: &[(&str, f64)]) -> BTreeMap<String, f64> {
        let mut p = Params::new();
        p.insert("steps".into(), serde_json::json!([100, 200, 400]));
        for (k, v) in extra {
            p.insert(k.to_string(), Value::from(*v));
        }
        plastic_strain_path(&p).unwrap().metrics
    }

    /// Negative controls for the case's checks: a material that never yields misses the
    /// stress by more than twice the yield stress; hardening with E_t taken as the plastic
    /// modulus (H = E_t, i.e. a tangent modulus E H / (E + H)) moves the slope by ~4.7e-3.
    #[test]
    fn wrong_materials_fail_the_checks() {
        let right = metrics(&[]);
        assert!(right["stress_error_finest"] < 3e-5, "{right:?}");
        let never = metrics(&[("model_yield_stress", 1e12)]);
        assert!(never["stress_error_finest"] > 2.0, "{never:?}");
        assert!(!never.contains_key("yield_onset_strain"));
        let et = 20e9;
        let wrong_h = metrics(&[("model_tangent_modulus", 200e9 * et / (200e9 + et))]);
        let rel = wrong_h["loading_slope_Pa"] / wrong_h["loading_slope_closed_form_Pa"] - 1.0;
        assert!((-6e-3..-4e-3).contains(&rel), "{rel}");
    }

    /// The problem form's evaluation (`plastic_path_problem::from_fields`) on `impact`'s own
    /// fields at each step of the finest level, written as another code writes them, gives the
    /// builtin's finest-level metrics bit for bit: the two read one definition.
    #[test]
    fn own_fields_give_the_builtin_metrics() {
        for element in ["q4-sri", "q4-1pt"] {
            let mut p = Params::new();
            p.insert("steps".into(), serde_json::json!([100, 200, 400]));
            p.insert("element".into(), Value::from(element));
            let builtin = plastic_strain_path(&p).unwrap().metrics;
            let (path, mesh, _) = setup(&p).unwrap();
            let own = run(&path, &mesh, &p, 400).unwrap();
            let from_fields = super::super::plastic_path_problem::from_fields;
            let metrics = from_fields(&p, &own.fields[1..]).unwrap().metrics;
            assert_eq!(metrics.len(), 10, "{metrics:?}");
            for (k, v) in &metrics {
                assert_eq!(
                    v.to_bits(),
                    builtin[k].to_bits(),
                    "{element} {k}: {v} {}",
                    builtin[k]
                );
            }
            let mut off = own.fields[1..].to_vec();
            off[200].point_stresses[3][0][1] += 2.5e5; // 1e-3 sigma_y, at one point and step
            let moved = from_fields(&p, &off).unwrap().metrics["stress_error_finest"];
            assert!((moved - 1e-3).abs() < 2e-5, "{moved}");
        }
    }
}
