//! A scene whose time step makes no run is refused before the run, naming the input that made
//! it: a step of 0 s or not finite (`material.density: 1e-300` gives a P-wave speed of inf
//! m/s), more than [`MAX_STEPS`] steps to the end, or no step at all (the end within 1e-9 of
//! one step: `material.density: 1e300` gives a step of 5e141 s). Checked on the estimated
//! step before anything is allocated ([`crate::input::estimate::budget::check`]) and on the run's own
//! step before its loop.

use super::measures::{count, extreme_fields, p_wave_speed, smallest_element_length};
use crate::input::error::{shown, Error, Result};
use crate::input::scene::{DtChoice, End, Scene};

/// Most time steps a run may take. The smallest mesh (2 elements) took 0.31 us a step
/// (2026-11-25, 2e6 steps in 0.61 s): 10^12 steps are 3.5 days of it, and years on the paper's
/// meshes; `u64` steps and `n dt` times stay exact far beyond (2^53 ~ 9e15).
pub const MAX_STEPS: f64 = 1.0e12;

/// Steps needed to reach time `t` with step `dt` (times within 1e-9 dt count as reached).
pub(crate) fn steps_to(t: f64, dt: f64) -> u64 {
    (t / dt - 1e-9).ceil().max(0.0) as u64
}

/// Refuses `scene` when its time step `dt` (s) is not a finite number > 0, or gives more than
/// [`MAX_STEPS`] steps or none to the run's end.
pub fn check_steps(scene: &Scene, dt: f64) -> Result<()> {
    let (end_field, end) = run_end(scene);
    let problem = if !(dt.is_finite() && dt > 0.0) {
        format!("the time step comes out as {dt:.3e} s")
    } else if end / dt > MAX_STEPS {
        format!(
            "{end_field} = {end:e} s is {} time steps of {dt:.3e} s, more than the {} a run may take",
            count(end / dt),
            count(MAX_STEPS)
        )
    } else if steps_to(end, dt) == 0 {
        format!(
            "the time step comes out as {dt:.3e} s, {:.1e} times {end_field} = {end:e} s: the run would take no step",
            dt / end
        )
    } else {
        return Ok(());
    };
    let (field, value) = culprit(scene);
    let location = scene.fields.location(&field, &scene.source);
    Err(Error::invalid(
        location,
        field,
        shown(value),
        format!(
            "{problem} (the step is {}); a run needs a finite time step > 0 s and 1 to {} steps",
            provenance(scene),
            count(MAX_STEPS)
        ),
    ))
}

/// The field that ends the run and its time, s.
fn run_end(scene: &Scene) -> (&'static str, f64) {
    match scene.time.end {
        End::At(t) => ("time.end", t),
        End::AfterContact { limit, .. } => ("time.limit", limit),
    }
}

/// Where the step comes from, in the scene's words.
fn provenance(scene: &Scene) -> String {
    let m = &scene.material;
    match scene.time.dt {
        DtChoice::Fixed(d) => format!("time.dt.fixed = {} s", shown(d)),
        DtChoice::Cfl(c) => format!(
            "time.dt.cfl = {} of the stable step of the smallest element, {:.3e} x {:.3e} m \
             (plate.length, plate.thickness, mesh.nx, mesh.ny), at the P-wave speed {:.3e} m/s of \
             material.density = {} kg/m^3, material.youngs_modulus = {} Pa, \
             material.poisson_ratio = {}",
            shown(c),
            smallest_element_length(scene),
            scene.plate.thickness / scene.mesh.ny as f64,
            p_wave_speed(m),
            shown(m.density),
            shown(m.youngs_modulus),
            shown(m.poisson_ratio)
        ),
    }
}

/// The input to name: the first of those the step comes from that lies outside anything a
/// solid plate could have (the ranges only choose the name; nothing is refused for them), else
/// the run's end. The P-wave speeds of solids lie between ~20 (soft rubber) and ~18 000 m/s
/// (diamond); densities between ~1 (aerogel) and 22 600 kg/m^3 (osmium); Young's moduli
/// between ~1e4 (gels) and 1.2e12 Pa (diamond).
fn culprit(scene: &Scene) -> (String, f64) {
    // An input beyond any physical magnitude that the step or the run's length depends on.
    let extreme = extreme_fields(scene)
        .into_iter()
        .find(|(field, _)| !field.starts_with("output."));
    if let Some(found) = extreme {
        return found;
    }
    let outside = |x: f64, lo: f64, hi: f64| !(lo..=hi).contains(&x);
    let m = &scene.material;
    let candidates = match scene.time.dt {
        DtChoice::Fixed(d) => vec![("time.dt.fixed", d, outside(d, 1e-12, 1.0))],
        DtChoice::Cfl(_) => {
            let c_p = p_wave_speed(m);
            vec![
                ("material.density", m.density, outside(m.density, 0.1, 1e5)),
                (
                    "material.youngs_modulus",
                    m.youngs_modulus,
                    outside(m.youngs_modulus, 1e3, 1e13),
                ),
                (
                    "material.poisson_ratio",
                    m.poisson_ratio,
                    outside(c_p, 1.0, 1e5),
                ),
                (
                    "plate.length",
                    scene.plate.length,
                    outside(scene.plate.length, 1e-6, 1e3),
                ),
                (
                    "plate.thickness",
                    scene.plate.thickness,
                    outside(scene.plate.thickness, 1e-6, 1e3),
                ),
            ]
        }
    };
    let (field, value) = candidates
        .into_iter()
        .find(|c| c.2)
        .map_or_else(|| run_end(scene), |c| (c.0, c.1));
    (field.to_string(), value)
}

#[cfg(test)]
mod tests {
    //! The time-step rule on the example scene with one input pushed out of any solid: the
    //! refusal names that input and its value, the step it gives, and says what a run needs;
    //! the example itself and a run of a single step pass.
    use super::*;
    use std::path::Path;

    const EXAMPLE: &str = include_str!("../../../../verification/scenes/example-elastic.yaml");

    fn example() -> Scene {
        Scene::from_yaml(EXAMPLE, Path::new("example.yaml")).unwrap()
    }

    fn refusal(scene: &Scene, dt: f64) -> String {
        check_steps(scene, dt).unwrap_err().to_string()
    }

    #[test]
    fn a_step_that_makes_no_run_is_refused_naming_its_input() {
        let scene = example();
        assert!(check_steps(&scene, 5.6e-7).is_ok());
        assert!(check_steps(&scene, 2.9e-3).is_ok(), "one step to the end");
        let mut light = scene.clone();
        light.material.density = 1e-300;
        let e = refusal(&light, 0.0);
        // Named where the file writes it (the spans the scene keeps).
        assert!(
            e.starts_with("example.yaml:5:12: material.density = 1e-300: "),
            "{e}"
        );
        assert!(
            e.contains("comes out as 0.000e0 s") && e.contains("P-wave speed inf"),
            "{e}"
        );
        let mut heavy = scene.clone();
        heavy.material.density = 1e300;
        let e = refusal(&heavy, 5.36e141);
        assert!(
            e.contains("material.density = 1e300:") && e.contains("no step"),
            "{e}"
        );
        let mut long = scene.clone();
        long.time.end = End::At(1e9);
        let e = refusal(&long, 5.6e-7);
        assert!(
            e.contains("time.end = 1e9:") && e.contains("1.79e15 time steps"),
            "{e}"
        );
        let mut fixed = scene;
        fixed.time.dt = DtChoice::Fixed(1e-20);
        let e = refusal(&fixed, 1e-20);
        assert!(e.contains("time.dt.fixed = 1e-20:"), "{e}");
        assert!(e.contains("more than the 1.00e12"), "{e}");
    }
}
