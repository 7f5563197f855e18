//! The `column-impact` builtin: a rigid mass striking the end of an elastic column through the
//! surface coupling. A plate whose ends are rollers (u_x = 0: every point in uniaxial strain)
//! is one element wide (half model, `nx` = 1) and `H` tall; the nose is flat (radius 1e6 m: its
//! curvature offset over the column's half-width is 1e-11 m, against the 7e-8 m the mass moves
//! in one step at the finest mesh). The solver's own time loop (`impact_solver::simulate`,
//! the scene built here) runs it.
//!
//! The reference is written here from E, nu, rho, A and M (d'Alembert with a mass boundary;
//! Goldsmith, *Impact*, 1960, ch. 4, and the case's README): with the column's impedance
//! `Z = rho c_p A`, `c_p = sqrt((lambda + 2 mu) / rho)` (uniaxial strain) and `beta = Z / M`,
//! until the wave reflected from the free far end returns at `T = 2 H / c_p` the contact force
//! is `F(t) = Z v0 exp(-beta t)`; the reflection is tensile, so the contact ends exactly at
//! `T` and the mass leaves at `v0 exp(-beta T)`.
//!
//! Measured: the force history's L2 and L-inf errors against `F(t)` over `[0, 0.95 T]`
//! (relative to `Z v0`), the least-squares fit of `ln F` over `[0.1 T, 0.9 T]` (its slope the
//! decay constant, its intercept the first contact stress times `A`), the contact duration, the
//! mass's final velocity and the energy balance.

use std::collections::BTreeMap;

use impact_solver::{History, Scene};
use serde_json::Value;

use super::scene_text::run_scene_text;
use crate::definition::run_data::RunData;
use crate::run::builtin_params::param;

type Params = BTreeMap<String, Value>;

/// Column height (the wave's path), width along x and out of plane, m.
const HEIGHT: f64 = 0.2;
const LENGTH: f64 = 0.01;
const WIDTH: f64 = 0.01;

/// The column and the striking mass, SI units.
#[derive(Debug, Clone, Copy)]
struct Column {
    youngs_modulus: f64,
    poisson_ratio: f64,
    density: f64,
    /// kg
    mass: f64,
    /// m/s
    velocity: f64,
}

impl Column {
    /// `c_p`, m/s.
    fn wave_speed(&self) -> f64 {
        let (e, nu) = (self.youngs_modulus, self.poisson_ratio);
        (e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu) * self.density)).sqrt()
    }
    /// `Z = rho c_p A`, N s/m.
    fn impedance(&self) -> f64 {
        self.density * self.wave_speed() * LENGTH * WIDTH
    }
    /// `T = 2 H / c_p`, s.
    fn return_time(&self) -> f64 {
        2.0 * HEIGHT / self.wave_speed()
    }
    /// `F(t) = Z v0 exp(-Z t / M)`, N.
    fn force(&self, t: f64) -> f64 {
        let z = self.impedance();
        z * self.velocity * (-z * t / self.mass).exp()
    }
}

/// The scene: the solver's modulus `model_modulus` (a negative control may change it), `ny`
/// rows, the time step `courant dy / c_p` of the model's column (Courant number 1 of the 1-D column is exact for the
/// waves at the nodes; above the 2-D element estimate, hence `allow_unstable_dt`), run to
/// `1.3 T` of the model's column, a history row every step.
fn scene(col: &Column, model_modulus: f64, ny: usize, courant: f64) -> String {
    let model = Column {
        youngs_modulus: model_modulus,
        ..*col
    };
    let dt = courant * HEIGHT / ny as f64 / model.wave_speed();
    format!(
        "plate: {{length: {LENGTH}, width: {WIDTH}, thickness: {HEIGHT}, ends: roller}}\n\
         material: {{density: {rho}, youngs_modulus: {model_modulus}, poisson_ratio: {nu}}}\n\
         mesh: {{nx: 1, ny: {ny}, element: q4-sri, model: half}}\n\
         load: {{impactor: {{mass: {m}, velocity: {v}, nose_radius: 1.0e6, contact: surface}}}}\n\
         time: {{end: {end}, dt: {{fixed: {dt}}}, allow_unstable_dt: true}}\n",
        rho = col.density,
        nu = col.poisson_ratio,
        m = col.mass,
        v = col.velocity,
        end = 1.3 * model.return_time(),
    )
}

/// Least-squares line `y = a + b t` through the points, `(a, b)`.
fn line_fit(t: &[f64], y: &[f64]) -> (f64, f64) {
    let n = t.len() as f64;
    let (mt, my) = (t.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let (num, den) = t.iter().zip(y).fold((0.0, 0.0), |(a, b), (ti, yi)| {
        (a + (ti - mt) * (yi - my), b + (ti - mt).powi(2))
    });
    let slope = num / den;
    (my - slope * mt, slope)
}

/// The force history against the closed form: errors and the exponential fit.
fn force_metrics(col: &Column, t: &[f64], f: &[f64]) -> Result<BTreeMap<String, f64>, String> {
    let big_t = col.return_time();
    let scale = col.impedance() * col.velocity;
    let errors: Vec<f64> = (0..t.len())
        .filter(|&i| t[i] <= 0.95 * big_t)
        .map(|i| (f[i] - col.force(t[i])) / scale)
        .collect();
    if errors.len() < 10 {
        return Err("column-impact: fewer than 10 history rows before the reflection".into());
    }
    let mut m = BTreeMap::new();
    let l2 = (errors.iter().map(|e| e * e).sum::<f64>() / errors.len() as f64).sqrt();
    m.insert("force_l2_error".into(), l2);
    let linf = errors.iter().fold(0.0_f64, |a, e| a.max(e.abs()));
    m.insert("force_linf_error".into(), linf);
    let window: Vec<usize> = (0..t.len())
        .filter(|&i| t[i] >= 0.1 * big_t && t[i] <= 0.9 * big_t && f[i] > 0.0)
        .collect();
    let tw: Vec<f64> = window.iter().map(|&i| t[i]).collect();
    let lw: Vec<f64> = window.iter().map(|&i| f[i].ln()).collect();
    let (intercept, slope) = line_fit(&tw, &lw);
    m.insert("decay_constant_per_s".into(), -slope);
    let area = LENGTH * WIDTH;
    m.insert("first_contact_stress_Pa".into(), intercept.exp() / area);
    Ok(m)
}

/// The closed-form numbers beside the measured ones.
fn closed_forms(col: &Column, m: &mut BTreeMap<String, f64>) {
    let (z, big_t) = (col.impedance(), col.return_time());
    m.insert("decay_constant_closed_form_per_s".into(), z / col.mass);
    m.insert(
        "first_contact_stress_closed_form_Pa".into(),
        col.density * col.wave_speed() * col.velocity,
    );
    m.insert("contact_duration_closed_form_s".into(), big_t);
    m.insert(
        "final_velocity_closed_form_mps".into(),
        col.velocity * (-z * big_t / col.mass).exp(),
    );
}

/// The column of the builtin's parameters and its scene's text.
fn column_of(p: &Params) -> Result<(Column, String), String> {
    let col = Column {
        youngs_modulus: param(p, "youngs_modulus", 207e9)?,
        poisson_ratio: param(p, "poisson_ratio", 0.3)?,
        density: param(p, "density", 7850.0)?,
        mass: param(p, "mass", 0.5)?,
        velocity: param(p, "velocity", 1.0)?,
    };
    let model_modulus = param(p, "model_youngs_modulus", col.youngs_modulus)?;
    let ny = param(p, "ny", 256.0)? as usize;
    let courant = param(p, "courant", 1.0)?;
    let text = scene(&col, model_modulus, ny, courant);
    Ok((col, text))
}

/// The metrics of a run of the column's scene from its history (`time_s`, `contact_force_N`)
/// and its summary (`summary.json`'s keys, the solver's or another code's): a key the run did
/// not write gives no metric (*not produced*), one written as null gives NaN.
fn column_metrics(col: &Column, history: &History, summary: &Value) -> Result<RunData, String> {
    let column = |name: &str| {
        history
            .column(name)
            .ok_or_else(|| format!("column-impact: no column {name}"))
    };
    let mut metrics = force_metrics(col, &column("time_s")?, &column("contact_force_N")?)?;
    closed_forms(col, &mut metrics);
    let number = |key: &str| {
        let v = key.split('.').try_fold(summary, |v, k| v.get(k))?;
        Some(v.as_f64().unwrap_or(f64::NAN))
    };
    if let Some(d) = number("contact_duration_s") {
        metrics.insert("contact_duration_s".into(), d);
    }
    if let Some(intervals) = summary.get("contact_intervals_s").and_then(Value::as_array) {
        metrics.insert("contact_intervals".into(), intervals.len() as f64);
    }
    if let Some(final_velocity) = number("final_impactor_velocity_mps") {
        metrics.insert("final_velocity_mps".into(), final_velocity);
        let closed = metrics["final_velocity_closed_form_mps"];
        metrics.insert(
            "final_velocity_relative_error".into(),
            (final_velocity / closed - 1.0).abs(),
        );
    }
    for (key, metric) in [
        ("max_energy_balance_error", "max_energy_balance_error"),
        ("final_energy_J.contact", "contact_energy_J"),
    ] {
        if let Some(v) = number(key) {
            metrics.insert(metric.into(), v);
        }
    }
    Ok(RunData::with_history(metrics, history.clone()))
}

pub fn column_impact(p: &Params) -> Result<RunData, String> {
    let (col, text) = column_of(p)?;
    let o = run_scene_text(&text, "(builtin column-impact)", &mut impact_solver::Quiet)?;
    let summary = serde_json::to_value(&o.summary).map_err(|e| e.to_string())?;
    column_metrics(&col, &o.history, &summary)
}

/// The column's scene, for another code to run (`crate::run::builtins::Form::Scene`).
pub fn column_scene(p: &Params) -> Result<Scene, String> {
    let (_, text) = column_of(p)?;
    Scene::from_yaml(&text, std::path::Path::new("(builtin column-impact)"))
        .map_err(|e| e.to_string())
}

/// The builtin's metrics from another code's run of [`column_scene`].
pub fn column_from_run(p: &Params, run: &RunData) -> Result<RunData, String> {
    let (col, _) = column_of(p)?;
    let history = run
        .history()
        .ok_or("column-impact: the run wrote no history")?;
    column_metrics(&col, history, run.summary.as_ref().unwrap_or(&Value::Null))
}

#[cfg(test)]
mod tests {
    //! Negative control for the case's checks (tolerances as in its case.yaml): a column twice
    //! as stiff (its impedance sqrt(2) x) fails the first contact stress and the decay constant.
    use super::*;

    fn metrics(extra: &[(&str, f64)]) -> BTreeMap<String, f64> {
        let mut p = Params::new();
        p.insert("ny".into(), Value::from(128));
        for (k, v) in extra {
            p.insert(k.to_string(), Value::from(*v));
        }
        column_impact(&p).unwrap().metrics
    }

    fn rel(m: &BTreeMap<String, f64>, a: &str, b: &str) -> f64 {
        m[a] / m[b] - 1.0
    }

    #[test]
    fn wrong_models_fail_the_checks() {
        let stress = |m: &BTreeMap<String, f64>| {
            rel(
                m,
                "first_contact_stress_Pa",
                "first_contact_stress_closed_form_Pa",
            )
        };
        let decay = |m: &BTreeMap<String, f64>| {
            rel(
                m,
                "decay_constant_per_s",
                "decay_constant_closed_form_per_s",
            )
        };
        let right = metrics(&[]);
        assert!(
            stress(&right).abs() < 1e-3 && decay(&right).abs() < 1e-3,
            "{right:?}"
        );
        let stiff = metrics(&[("model_youngs_modulus", 414e9)]);
        assert!(stress(&stiff) > 0.3 && decay(&stiff) > 0.3, "{stiff:?}");
    }

    /// The scene form against the builtin: the column's scene run by the solver and read back
    /// as another code's run (its history, its summary as summary.json holds it) gives the
    /// builtin's metrics bit for bit; a summary without the balance gives no balance metric
    /// (*not produced*), not a made-up one.
    #[test]
    fn the_scene_form_gives_the_builtin_s_metrics() {
        let p = Params::from([("ny".to_string(), Value::from(128))]);
        let builtin = column_impact(&p).unwrap().metrics;
        let scene = column_scene(&p).unwrap();
        let o = impact_solver::simulate(&scene, &mut impact_solver::Quiet).unwrap();
        let mut summary = serde_json::to_value(&o.summary).unwrap();
        let run = RunData {
            summary: Some(summary.clone()),
            ..RunData::with_history(BTreeMap::new(), o.history.clone())
        };
        let evaluated = column_from_run(&p, &run).unwrap().metrics;
        assert_eq!(evaluated.len(), builtin.len());
        for (k, v) in &builtin {
            assert_eq!(v.to_bits(), evaluated[k].to_bits(), "{k}");
        }
        summary
            .as_object_mut()
            .unwrap()
            .remove("max_energy_balance_error");
        let run = RunData {
            summary: Some(summary),
            ..RunData::with_history(BTreeMap::new(), o.history)
        };
        let evaluated = column_from_run(&p, &run).unwrap().metrics;
        assert!(!evaluated.contains_key("max_energy_balance_error"));
        assert!(evaluated.contains_key("contact_duration_s"));
    }
}
