//! The `impactor-spring` builtin: the solver's rigid-impactor update (eqs. 19-20, force linear
//! over a step) coupled to a fixed linear spring `F = k x` exactly as eq. (21) couples it to
//! the contact law (the end-of-step force solved implicitly with the impactor's own
//! compliance `dt^2 / (6 m)`), against the exact harmonic motion
//! `x = (v0 / w) sin(w t)`, `v = v0 cos(w t)`, `w = sqrt(k / m)`.
//! The update is Newmark's linear-acceleration method (beta 1/6, gamma 1/2): second order.

use std::collections::BTreeMap;

use impact_solver::impactor::RigidImpactor;
use impact_solver::History;
use serde_json::Value;

use super::orders::{largest_step, pair_orders};
use crate::definition::run_data::RunData;
use crate::run::builtin_params::param;

/// Largest displacement and velocity errors over one period with `n` steps, relative to the
/// amplitudes `v0 / w` and `v0`.
fn period_errors(mass: f64, v0: f64, k: f64, n: usize) -> (f64, f64) {
    let w = (k / mass).sqrt();
    let dt = 2.0 * std::f64::consts::PI / w / n as f64;
    let mut imp = RigidImpactor::new(mass, v0);
    let mut force = 0.0;
    let (mut ex, mut ev) = (0.0f64, 0.0f64);
    for step in 1..=n {
        let free = imp.displacement_after(dt, force, 0.0);
        let next = k * free / (1.0 + k * dt * dt / (6.0 * mass));
        imp.advance(dt, force, next);
        force = next;
        let t = step as f64 * dt;
        ex = ex.max((imp.displacement - v0 / w * (w * t).sin()).abs() * w / v0);
        ev = ev.max((imp.velocity - v0 * (w * t).cos()).abs() / v0);
    }
    (ex, ev)
}

pub fn spring(p: &BTreeMap<String, Value>) -> Result<RunData, String> {
    let mass = param(p, "mass", 18.0)?;
    let v0 = param(p, "velocity", 10.0)?;
    let k = param(p, "stiffness", 1.0e9)?;
    if !(mass > 0.0 && k > 0.0 && v0 != 0.0) {
        return Err("impactor-spring: mass and stiffness must be > 0, velocity nonzero".into());
    }
    let counts = [25usize, 50, 100, 200, 400];
    let (mut ex, mut ev) = (Vec::new(), Vec::new());
    let mut m = BTreeMap::new();
    for &n in &counts {
        let (x, v) = period_errors(mass, v0, k, n);
        m.insert(format!("displacement_error_n{n}"), x);
        m.insert(format!("velocity_error_n{n}"), v);
        ex.push(x);
        ev.push(v);
    }
    let (px, pv) = (pair_orders(&ex, 2.0), pair_orders(&ev, 2.0));
    let last = px.len() - 1;
    m.insert("order_displacement_finest".into(), px[last]);
    m.insert("order_velocity_finest".into(), pv[last]);
    m.insert(
        "order_largest_step".into(),
        largest_step(&px).max(largest_step(&pv)),
    );
    let rows: Vec<f64> = (0..px.len())
        .flat_map(|i| [(i + 1) as f64, px[i], pv[i], 2.0])
        .collect();
    let mut histories = BTreeMap::new();
    histories.insert(
        String::new(),
        History {
            columns: [
                "time_s",
                "observed_order_displacement",
                "observed_order_velocity",
                "formal_order",
            ]
            .map(String::from)
            .to_vec(),
            values: rows,
        },
    );
    Ok(RunData {
        metrics: m,
        histories,
        ..Default::default()
    })
}
