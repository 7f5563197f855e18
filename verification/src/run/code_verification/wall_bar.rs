//! The `wall-bar` builtin: an elastic bar striking a rigid wall (Code_Aster SDNV100, V5.03.100,
//! in its one-dimensional reading), run on the solver's own time loop
//! (`impact_solver::simulate`, scene built here) with `load: {wall}`.
//!
//! With `nu = 0` the bar is exactly one-dimensional in both geometries (no lateral strain is
//! coupled to the axial one: plane strain and the ring are then the uniaxial bar), so the 1-D
//! wave solution is the reference, written here from E, rho, L and v0 (not from the solver):
//! at impact a compression wave `sigma = rho c v0` (`c = sqrt(E / rho)`) runs up the bar,
//! reflects from the free top as unloading, and the bar leaves the wall at `t = 2 L / c` with
//! velocity `v0` away from it (elastic: its kinetic energy returns). The wall force is
//! `rho c v0 A` while in contact (`A` the bar's section: `pi a^2` for the ring, `2 a W` in plane
//! strain for the width `W`).
//!
//! Measured: the contact duration (the summary's end of contact), the mean wall force over the
//! middle half of the closed-form contact, over `A` (the plateau's ringing averages out), and
//! the body's mean velocity away from the wall at the end (the summary's
//! `wall.rebound_velocity_mps`).

use std::collections::BTreeMap;

use impact_solver::input::geometry::Geometry;
use serde_json::Value;

use super::scene_text::run_scene_text;
use crate::definition::run_data::RunData;
use crate::run::builtin_params::{param, param_geometry};

type Params = BTreeMap<String, Value>;

/// The bar (SI units): steel-like, 0.1 m long, radius (half-width) 5 mm, at 10 m/s.
#[derive(Debug, Clone, Copy)]
struct Bar {
    /// Pa
    youngs_modulus: f64,
    /// kg/m^3
    density: f64,
    /// m
    length: f64,
    /// Radius (ring) or half-width (plane strain), m.
    radius: f64,
    /// Out-of-plane width in plane strain, m.
    width: f64,
    /// m/s
    velocity: f64,
}

const BAR: Bar = Bar {
    youngs_modulus: 200e9,
    density: 7800.0,
    length: 0.1,
    radius: 0.005,
    width: 1.0,
    velocity: 10.0,
};

impl Bar {
    /// The 1-D bar speed `sqrt(E / rho)`, m/s.
    fn speed(&self) -> f64 {
        (self.youngs_modulus / self.density).sqrt()
    }

    /// The section the wall pushes on, m^2.
    fn area(&self, axisymmetric: bool) -> f64 {
        if axisymmetric {
            std::f64::consts::PI * self.radius * self.radius
        } else {
            2.0 * self.radius * self.width
        }
    }
}

/// The scene: half model `nx = 2` across the radius, `ny` rows along the bar, q4-sri,
/// Courant number 0.9, run to 1.5 contact durations; the solver's Young's modulus
/// `model_youngs_modulus` (a negative control may change it).
fn scene(bar: &Bar, geometry: &str, ny: usize, model_youngs_modulus: f64) -> String {
    let end = 1.5 * 2.0 * bar.length / bar.speed();
    format!(
        "title: elastic bar onto a rigid wall (builtin wall-bar)\n\
         geometry: {geometry}\n\
         plate: {{length: {}, width: {}, thickness: {}, ends: free}}\n\
         material: {{density: {}, youngs_modulus: {model_youngs_modulus:e}, poisson_ratio: 0.0}}\n\
         mesh: {{nx: 2, ny: {ny}, element: q4-sri}}\n\
         load: {{wall: {{velocity: {}}}}}\n\
         time: {{end: {end:e}, dt: {{cfl: 0.9}}}}\n",
        2.0 * bar.radius,
        bar.width,
        bar.length,
        bar.density,
        bar.velocity,
    )
}

/// The measured metrics of a run's `history` and `summary` (`force_factor`: the wall force read
/// that many times, a negative control of the bookkeeping) with the closed forms beside them.
fn measure(
    o: &impact_solver::Outcome,
    bar: &Bar,
    axisymmetric: bool,
    force_factor: f64,
) -> Result<BTreeMap<String, f64>, String> {
    let col = |name: &str| {
        o.history
            .column(name)
            .ok_or_else(|| format!("wall-bar: no column {name}"))
    };
    let (t, force) = (col("time_s")?, col("contact_force_N")?);
    let duration = 2.0 * bar.length / bar.speed();
    let plateau: Vec<f64> = (0..t.len())
        .filter(|&i| t[i] >= 0.25 * duration && t[i] <= 0.75 * duration)
        .map(|i| force_factor * force[i])
        .collect();
    if plateau.is_empty() {
        return Err("wall-bar: no rows in the middle of the contact".into());
    }
    let stress = plateau.iter().sum::<f64>() / plateau.len() as f64 / bar.area(axisymmetric);
    let wall = o
        .summary
        .wall
        .as_ref()
        .ok_or("wall-bar: the summary has no wall")?;
    let mut m = BTreeMap::new();
    m.insert("contact_duration_s".into(), o.summary.contact_duration);
    m.insert("contact_stress_Pa".into(), stress);
    let rebound = wall
        .rebound_velocity
        .ok_or("wall-bar: the bar did not leave the wall")?;
    m.insert("rebound_velocity_mps".into(), rebound);
    m.insert("duration_closed_form_s".into(), duration);
    m.insert(
        "stress_closed_form_Pa".into(),
        bar.density * bar.speed() * bar.velocity,
    );
    m.insert("impact_velocity_mps".into(), bar.velocity);
    m.insert(
        "max_energy_balance_error".into(),
        o.summary.max_energy_balance_error,
    );
    Ok(m)
}

pub fn wall_bar(p: &Params) -> Result<RunData, String> {
    let geometry = param_geometry(p, Geometry::Axisymmetric)?;
    let axisymmetric = geometry == Geometry::Axisymmetric;
    let ny = param(p, "ny", 80.0)? as usize;
    let model_e = param(p, "model_youngs_modulus", BAR.youngs_modulus)?;
    let force_factor = param(p, "force_factor", 1.0)?;
    let text = scene(&BAR, geometry.name(), ny, model_e);
    let o = run_scene_text(&text, "(builtin wall-bar)", &mut impact_solver::Quiet)?;
    let metrics = measure(&o, &BAR, axisymmetric, force_factor)?;
    Ok(RunData::with_history(metrics, o.history))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn metrics(geometry: &str, extra: &[(&str, f64)]) -> BTreeMap<String, f64> {
        let mut p = Params::new();
        p.insert("geometry".into(), Value::from(geometry));
        for (k, v) in extra {
            p.insert(k.to_string(), Value::from(*v));
        }
        wall_bar(&p).unwrap().metrics
    }

    fn rel(m: &BTreeMap<String, f64>, a: &str, b: &str) -> f64 {
        m[a] / m[b] - 1.0
    }

    /// Negative controls for the case's checks (tolerances as in its case.yaml): a bar twice as
    /// stiff (c off by sqrt 2: what a wall that doubles the stiffness does to the waves) and
    /// the wall's reaction counted twice each fail a check the right model passes.
    #[test]
    fn wrong_models_fail_the_checks() {
        for geometry in ["axisymmetric", "plane-strain"] {
            let right = metrics(geometry, &[]);
            let duration =
                |m: &BTreeMap<String, f64>| rel(m, "contact_duration_s", "duration_closed_form_s");
            let stress =
                |m: &BTreeMap<String, f64>| rel(m, "contact_stress_Pa", "stress_closed_form_Pa");
            let rebound =
                |m: &BTreeMap<String, f64>| rel(m, "rebound_velocity_mps", "impact_velocity_mps");
            assert!(duration(&right).abs() < 0.05, "{right:?}");
            assert!(stress(&right).abs() < 5e-5, "{right:?}");
            assert!(rebound(&right).abs() < 0.05, "{right:?}");
            let stiff = metrics(geometry, &[("model_youngs_modulus", 400e9)]);
            assert!(duration(&stiff) < -0.25, "{stiff:?}");
            // +41 % while in contact, averaged with the zeros after its early release.
            assert!(stress(&stiff) > 0.2, "{stiff:?}");
            let twice = metrics(geometry, &[("force_factor", 2.0)]);
            assert!(stress(&twice) > 0.99, "{twice:?}");
        }
    }
}
