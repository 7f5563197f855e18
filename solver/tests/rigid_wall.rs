//! The rigid wall (`load: {wall}`) in whole runs, against invariants of the method and of the
//! physics (the 1-D closed forms are the verification case `wave-speed/wall-bar`):
//! - impulse = momentum change: the trapezoid of the wall force (with `dt/2` at the first step)
//!   is the sum of its impulses, so `impulse = M (v0 + v_rebound)` to round-off; the bar's
//!   length after it left the wall is its own, not its height above the wall;
//! - the Taylor bar scene (`verification/scenes/taylor-bar.yaml`, finite deformation, 80 us) runs, its
//!   balance closes at every landing (the wall's dissipation booked at `t_n`), it shortens and its foot spreads, and its bits do not depend on the thread
//!   count;
//! - the scenes the wall cannot run are refused with the file, line, column, field and value.

use std::path::Path;

use impact_solver::{simulate, Outcome, Quiet, Scene};

const TAYLOR: &str = include_str!("../../verification/scenes/taylor-bar.yaml");

/// An elastic plane-strain bar (nu = 0: 1-D), 0.1 m long, 10 mm wide, at 10 m/s.
const BAR: &str = "
plate: {length: 0.01, width: 1.0, thickness: 0.1, ends: free}
material: {density: 7800.0, youngs_modulus: 200.0e9, poisson_ratio: 0.0}
mesh: {nx: 2, ny: 40, element: q4-sri}
load: {wall: {velocity: 10.0}}
time: {end: 6.0e-5, dt: {cfl: 0.9}}
";

fn run(text: &str) -> Outcome {
    let scene = Scene::from_yaml(text, Path::new("wall.yaml")).unwrap();
    simulate(&scene, &mut Quiet).unwrap()
}

fn refusal(text: &str) -> String {
    Scene::from_yaml(text, Path::new("wall.yaml"))
        .unwrap_err()
        .to_string()
}

#[test]
fn the_wall_impulse_is_the_bars_momentum_change() {
    let o = run(BAR);
    let wall = o.summary.wall.as_ref().expect("a wall summary");
    let mass = 7800.0 * 0.01 * 0.1 * 1.0;
    let change = mass * (10.0 + wall.rebound_velocity.expect("the bar left the wall"));
    // Measured 1.8e-16: the same sum in another order.
    assert!(
        (o.summary.impulse - change).abs() < 1e-12 * change,
        "{} vs {change}",
        o.summary.impulse
    );
    // The elastic bar leaves the wall (2 L/c = 39.5 us) and flies on. Bound 1e-6 s, about two
    // steps (dt = 4.44e-7 s): measured 39.99 us, 4.9e-7 s late (the 40-row bar's front is
    // spread over rows); a bar twice as stiff leaves 11.6 us early.
    let release = wall.release_time.expect("released");
    assert!((release - 3.95e-5).abs() < 1e-6, "{release}");
    // Measured 5.5e-3 (the bottom row's landing and the coarse front's ringing).
    assert!(o.summary.max_energy_balance_error < 0.02);
    // The wall took the bottom row's kinetic energy: (1/80 of the mass) v0^2 / 2 = 4.875 J.
    // Bound 1e-12 J: about 16x the measured 6.2e-14 (round-off of the per-node sums); a wall
    // that also charged the resting nodes, or counted the landing twice, misses by joules.
    assert!((wall.dissipated_energy - 4.875).abs() < 1e-12, "{wall:?}");
    // The bar's length after it has left the wall (20 us earlier, at 9.8 m/s): 0.1 m less
    // the ringing's 6.3e-6 m (measured); the top node's height (the old definition) counts
    // the gap as well, 2.06e-4 m. Bound 5e-5 m, 8x the ringing, 4x below the gap.
    assert!((wall.final_length - 0.1).abs() < 5e-5, "{wall:?}");
}

#[test]
fn the_taylor_bar_scene_runs_shortens_and_spreads_on_any_thread_count() {
    let on = |threads| impact_solver::workers::with_threads(threads, || run(TAYLOR));
    let (one, two) = (on(1), on(2));
    assert_eq!(one.history.values.len(), two.history.values.len());
    assert!(one
        .history
        .values
        .iter()
        .zip(&two.history.values)
        .all(|(a, b)| a.to_bits() == b.to_bits()));
    let wall = one.summary.wall.as_ref().unwrap();
    // Measured 1.0e-7 (finite deformation, q4-sri, 80 us), the landings' loss booked at
    // t_n as the kinetic energy is read (ALGORITHM.md 7); booking half of a landing step's
    // work at t_n left a one-step spike at each landing, 1.4e-4 at most. Bound 10x measured.
    assert!(
        one.summary.max_energy_balance_error < 1e-6,
        "{}",
        one.summary.max_energy_balance_error
    );
    assert!(
        wall.final_length < 0.0324 && wall.foot_radius > 0.0032,
        "{wall:?}"
    );
    assert!(
        wall.max_equivalent_plastic_strain.unwrap() > 0.1,
        "{wall:?}"
    );
    // The foot at the end is one of the foot radii the run went through; the bearing force
    // is below the one-step force that stops the bottom row at t_0 (measured 1.6e5 against
    // 9.0e7 N).
    assert!(wall.max_foot_radius >= wall.foot_radius, "{wall:?}");
    assert!(wall.peak_force < 1e-2 * wall.peak_step_force, "{wall:?}");
    // Still on the wall at 80 us (moving toward it at 29 m/s): no release, no rebound.
    assert!(wall.release_time.is_none() && wall.rebound_velocity.is_none());
}

#[test]
fn scenes_the_wall_cannot_run_are_refused_with_their_place() {
    let clamped = refusal(&BAR.replace(", ends: free", ""));
    assert!(
        clamped.contains("wall.yaml:2:") && clamped.contains("plate.ends"),
        "{clamped}"
    );
    let roller = refusal(&BAR.replace("ends: free", "ends: roller"));
    assert!(
        roller.contains("plate.ends") && roller.contains("roller"),
        "{roller}"
    );
    let full = refusal(&BAR.replace("element: q4-sri", "element: q4-sri, model: full"));
    assert!(
        full.contains("mesh.model") && full.contains("wall.yaml:4:"),
        "{full}"
    );
    let after = refusal(&BAR.replace("end: 6.0e-5", "end: {after_contact: 1.0e-6}"));
    assert!(
        after.contains("time.end") && after.contains("wall.yaml:6:"),
        "{after}"
    );
    let slow = refusal(&BAR.replace("velocity: 10.0", "velocity: -1.0"));
    assert!(slow.contains("load.wall.velocity"), "{slow}");
}
