//! The keys of a scene's `summary.json` that hold numbers (nested ones dotted:
//! `max_von_mises_Pa.A`), known before any run from the validated scene, as
//! `impact_solver::summary::Summary::new` writes them: the outputs an uncertainty study may
//! declare. `python/tests/test_uq_declaration.py` holds them to the summaries of real runs of
//! every kind of scene (point force, surface contact, pulse, wall, rate-dependent, heating).

use impact_solver::scene::DtUpdate;
use impact_solver::time_loop::energy::Energies;
use impact_solver::Scene;

/// Written for every scene.
const ALWAYS: [&str; 16] = [
    "impulse_Ns",
    "peak_contact_force_N",
    "max_plate_displacement_m",
    "max_bottom_displacement_m",
    "contact_duration_s",
    "max_energy_balance_error",
    "dt_s",
    "n_steps",
    "n_elements",
    "wall_time_s",
    "cfl",
    "dt_critical_s",
    "final_time_s",
    "setup_time_s",
    "loop_time_s",
    "ns_per_element_step",
];
/// An impactor's (either coupling).
const IMPACTOR: [&str; 2] = ["final_impactor_velocity_mps", "impulse_momentum_error"];
/// A step re-estimated at every step.
const EVERY_STEP: [&str; 2] = ["dt_min_s", "dt_max_s"];
/// The surface coupling's.
const SURFACE: [&str; 4] = [
    "contact_step_factor",
    "max_contact_half_width_m",
    "max_nodes_in_contact",
    "max_penetration_m",
];
/// Heating's.
const THERMAL: [&str; 2] = ["max_temperature_K", "heat_J"];
/// The rigid wall's (`wall.KEY`; `release_time_s` and `rebound_velocity_mps` are null while
/// the body is still on the wall at the end).
const WALL: [&str; 11] = [
    "peak_force_N",
    "peak_step_force_N",
    "release_time_s",
    "final_length_m",
    "length_ratio",
    "undeformed_length_m",
    "foot_radius_m",
    "foot_radius_ratio",
    "max_foot_radius_m",
    "rebound_velocity_mps",
    "dissipated_energy_J",
];

/// The numeric summary keys of a run of `scene`, in the summary's order of kinds.
pub fn numeric(scene: &Scene) -> Vec<String> {
    let owned = |keys: &[&str]| keys.iter().map(|k| k.to_string()).collect::<Vec<_>>();
    let within = |map: &str, names: &mut dyn Iterator<Item = &str>| {
        names.map(|n| format!("{map}.{n}")).collect::<Vec<_>>()
    };
    let probes = || scene.output.probes.iter().map(|(name, _)| name.as_str());
    let mut keys = owned(&ALWAYS);
    keys.extend(within("max_von_mises_Pa", &mut probes()));
    for side in ["initial_energy_J", "final_energy_J"] {
        keys.extend(within(side, &mut energy_terms().iter().map(String::as_str)));
    }
    let when = |on: bool, kind: &[&str]| if on { owned(kind) } else { Vec::new() };
    keys.extend(when(scene.impactor_motion().is_some(), &IMPACTOR));
    keys.extend(when(
        scene.time.dt_update == DtUpdate::EveryStep,
        &EVERY_STEP,
    ));
    keys.extend(when(scene.surface_impactor().is_some(), &SURFACE));
    if scene.rate_law().is_some() {
        keys.extend(within("max_plastic_strain_rate_1_s", &mut probes()));
    }
    keys.extend(when(
        scene.rate_law().and_then(|r| r.thermal()).is_some(),
        &THERMAL,
    ));
    if scene.wall().is_some() {
        keys.extend(within("wall", &mut WALL.iter().copied()));
        if scene.is_plastic() {
            keys.push("wall.max_equivalent_plastic_strain".into());
        }
    }
    keys
}

/// The energy terms of `initial_energy_J` and `final_energy_J`, as the summary names them.
fn energy_terms() -> Vec<String> {
    match serde_json::to_value(Energies::default()) {
        Ok(serde_json::Value::Object(map)) => map.keys().cloned().collect(),
        _ => Vec::new(),
    }
}
