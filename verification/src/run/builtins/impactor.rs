//! The `impactor-kinematics` builtin: the rigid impactor's update (eqs. 19-20) under a
//! constant and a linear force against the closed-form motion, and under a quadratic force,
//! where its second-order error must show.

use std::collections::BTreeMap;

use impact_solver::impactor::RigidImpactor;

use crate::definition::run_data::RunData;
use crate::run::builtin_params::Params;

pub(super) fn impactor_kinematics(_: &Params) -> Result<RunData, String> {
    let mut m = BTreeMap::new();
    // Constant force F: v = v0 - F t / m, x = v0 t - F t^2 / (2m).
    let (mass, v0, f, dt, n) = (18.0, 10.0, 1.5e5, 1e-7, 1000);
    let imp = march(mass, v0, dt, n, |_| f);
    let t = n as f64 * dt;
    let v = v0 - f / mass * t;
    let x = v0 * t - 0.5 * f / mass * t * t;
    record(&mut m, "constant", &imp, v0, v, Some(x));
    // Linear force F = k t: v = v0 - k t^2 / (2m), x = v0 t - k t^3 / (6m).
    let (mass, v0, k, dt, n) = (10.0, 5.0, 3e9, 1e-7, 2000);
    let imp = march(mass, v0, dt, n, |i| k * i as f64 * dt);
    let t = n as f64 * dt;
    let v = v0 - k * t * t / (2.0 * mass);
    let x = v0 * t - k * t * t * t / (6.0 * mass);
    record(&mut m, "linear", &imp, v0, v, Some(x));
    // A quadratic force is not linear in a step: the update is then only second order;
    // the error must be visible (this guards against a check that cannot fail).
    let (mass, v0, q, dt, n) = (10.0, 5.0, 1e13, 1e-6, 200);
    let imp = march(mass, v0, dt, n, |i| {
        let t = i as f64 * dt;
        q * t * t
    });
    let t = n as f64 * dt;
    let v = v0 - q * t * t * t / (3.0 * mass);
    record(&mut m, "quadratic", &imp, v0, v, None);
    Ok(RunData {
        metrics: m,
        ..Default::default()
    })
}

/// `n` steps of `dt` [s] from displacement 0 at speed `v0` [m/s], with the contact force
/// [N] at step boundary `i` given by `force(i)`.
fn march(mass: f64, v0: f64, dt: f64, n: usize, force: impl Fn(usize) -> f64) -> RigidImpactor {
    let mut imp = RigidImpactor::new(mass, v0);
    for i in 0..n {
        imp.advance(dt, force(i), force(i + 1));
    }
    imp
}

/// The relative velocity error (to `v0`) and, when given, the relative displacement error
/// against the exact velocity `v` [m/s] and displacement `x` [m], as `{name}_velocity_rel` and
/// `{name}_displacement_rel`.
fn record(
    m: &mut BTreeMap<String, f64>,
    name: &str,
    imp: &RigidImpactor,
    v0: f64,
    v: f64,
    x: Option<f64>,
) {
    m.insert(
        format!("{name}_velocity_rel"),
        ((imp.velocity - v) / v0).abs(),
    );
    if let Some(x) = x {
        m.insert(
            format!("{name}_displacement_rel"),
            ((imp.displacement - x) / x).abs(),
        );
    }
}
