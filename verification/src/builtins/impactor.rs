//! The `impactor-kinematics` builtin: the rigid impactor's update (eqs. 19-20) under a
//! constant and a linear force against the closed-form motion, and under a quadratic force,
//! where its second-order error must show.

use std::collections::BTreeMap;

use impact_solver::impactor::RigidImpactor;

use super::Params;
use crate::data::RunData;

pub(super) fn impactor_kinematics(_: &Params) -> Result<RunData, String> {
    let mut m = BTreeMap::new();
    // Constant force F: v = v0 - F t / m, x = v0 t - F t^2 / (2m).
    let (mass, v0, f, dt, n) = (18.0, 10.0, 1.5e5, 1e-7, 1000);
    let mut imp = RigidImpactor::new(mass, v0);
    for _ in 0..n {
        imp.advance(dt, f, f);
    }
    let t = n as f64 * dt;
    let v = v0 - f / mass * t;
    let x = v0 * t - 0.5 * f / mass * t * t;
    m.insert(
        "constant_velocity_rel".into(),
        ((imp.velocity - v) / v0).abs(),
    );
    m.insert(
        "constant_displacement_rel".into(),
        ((imp.displacement - x) / x).abs(),
    );
    // Linear force F = k t: v = v0 - k t^2 / (2m), x = v0 t - k t^3 / (6m).
    let (mass, v0, k, dt, n) = (10.0, 5.0, 3e9, 1e-7, 2000);
    let mut imp = RigidImpactor::new(mass, v0);
    for i in 0..n {
        imp.advance(dt, k * i as f64 * dt, k * (i + 1) as f64 * dt);
    }
    let t = n as f64 * dt;
    let v = v0 - k * t * t / (2.0 * mass);
    let x = v0 * t - k * t * t * t / (6.0 * mass);
    m.insert(
        "linear_velocity_rel".into(),
        ((imp.velocity - v) / v0).abs(),
    );
    m.insert(
        "linear_displacement_rel".into(),
        ((imp.displacement - x) / x).abs(),
    );
    // A quadratic force is not linear in a step: the update is then only second order;
    // the error must be visible (this guards against a check that cannot fail).
    let (mass, v0, q, dt, n) = (10.0, 5.0, 1e13, 1e-6, 200);
    let mut imp = RigidImpactor::new(mass, v0);
    for i in 0..n {
        let (t0, t1) = (i as f64 * dt, (i + 1) as f64 * dt);
        imp.advance(dt, q * t0 * t0, q * t1 * t1);
    }
    let t = n as f64 * dt;
    let v = v0 - q * t * t * t / (3.0 * mass);
    m.insert(
        "quadratic_velocity_rel".into(),
        ((imp.velocity - v) / v0).abs(),
    );
    Ok(RunData {
        metrics: m,
        ..Default::default()
    })
}
