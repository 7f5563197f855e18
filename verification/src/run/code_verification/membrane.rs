//! The `membrane-regime` builtin: the Table 1 elasto-plastic plate (and thinner ones) struck
//! at rising velocity until the deflection is several thicknesses, with small and finite
//! kinematics side by side, against the rigid-plastic bands of a clamped beam struck by a mass
//! (`impact_analytical::rigid_plastic`, after Jones, *Structural Impact*): the lower edge
//! (circumscribing square yield curve, hardened, with the energy left after the momentum
//! transfer) and the membrane upper edge (inscribing square yield curve with all of the
//! energy). Once the deflection passes the thickness, membrane forces carry the load: the
//! finite answers stay in the band, the small-strain ones grow like bending alone.
//!
//! The scene is `verification/scenes/paper-plastic.yaml` with the mesh, the thickness, the
//! velocity, the kinematics and the end (0.2 ms after contact, at most 30 ms) set per run.

use std::collections::BTreeMap;

use impact_solver::scene::{End, Kinematics};
use impact_solver::{Quiet, Scene};
use serde_json::Value;

use crate::definition::run_data::RunData;
use crate::run::builtin_params::{param, param_numbers};
use crate::run::rigid_plastic::beam_impact;

type Params = BTreeMap<String, Value>;

const SCENE: &str = include_str!("../../../scenes/paper-plastic.yaml");

/// The largest mid-plane deflection (m, positive) of the Table 1 plate of thickness `h` (m)
/// struck at `v` (m/s), with `kinematics`, on an `nx` x `ny` half model; and the scene.
fn deflection(
    h: f64,
    v: f64,
    kinematics: Kinematics,
    (nx, ny): (usize, usize),
) -> Result<(f64, Scene), String> {
    let mut s = Scene::from_yaml(SCENE, std::path::Path::new("paper-plastic.yaml"))
        .map_err(|e| e.to_string())?;
    s.plate.thickness = h;
    s.mesh.nx = nx;
    s.mesh.ny = ny;
    s.kinematics = kinematics;
    s.time.end = End::AfterContact {
        after: 2e-4,
        limit: 0.03,
    };
    match &mut s.load {
        impact_solver::scene::Load::Impactor(i) => i.velocity = v,
        _ => return Err("paper-plastic.yaml: expected the point-force impactor".into()),
    }
    s.output.fields_every = None;
    let out = impact_solver::simulate(&s, &mut Quiet).map_err(|e| e.to_string())?;
    Ok((out.summary.max_plate_displacement.abs(), s))
}

pub fn membrane_regime(p: &Params) -> Result<RunData, String> {
    let thicknesses = param_numbers(p, "thicknesses", &[0.0188, 0.0094])?;
    let velocities = param_numbers(p, "velocities", &[10.0, 20.0, 40.0])?;
    let mesh = (
        param(p, "nx", 40.0)? as usize,
        param(p, "ny", 8.0)? as usize,
    );
    let mut m = BTreeMap::new();
    let mut rows: Vec<[f64; 7]> = Vec::new();
    for &h in &thicknesses {
        for &v in &velocities {
            let (small, _) = deflection(h, v, Kinematics::Small, mesh)?;
            let (finite, scene) = deflection(h, v, Kinematics::Finite, mesh)?;
            let b = beam_impact(&scene)
                .ok_or("the scene is not a clamped beam struck by a mass")?
                .bounds();
            let tag = format!("h{:.1}_v{v}", h * 1e3);
            m.insert(format!("small_{tag}_m"), small);
            m.insert(format!("finite_{tag}_m"), finite);
            m.insert(format!("lower_{tag}_m"), b.lower);
            m.insert(format!("membrane_upper_{tag}_m"), b.membrane_upper);
            m.insert(format!("bending_upper_{tag}_m"), b.upper);
            m.insert(format!("energy_ratio_{tag}"), b.energy_ratio);
            m.insert(format!("deflection_over_thickness_{tag}"), finite / h);
            m.insert(format!("small_over_finite_{tag}"), small / finite - 1.0);
            rows.push([
                finite / h,
                finite / h,
                small / finite - 1.0,
                small / h,
                b.lower / h,
                b.membrane_upper / h,
                v,
            ]);
        }
    }
    rows.sort_by(|a, b| a[0].total_cmp(&b[0]));
    let columns = [
        "time_s",
        "finite_deflection_over_thickness",
        "small_over_finite_minus_one",
        "small_deflection_over_thickness",
        "lower_edge_over_thickness",
        "membrane_upper_edge_over_thickness",
        "velocity_mps",
    ]
    .map(String::from)
    .to_vec();
    let values = rows.iter().flatten().copied().collect();
    Ok(RunData::with_history(
        m,
        impact_solver::History { columns, values },
    ))
}
