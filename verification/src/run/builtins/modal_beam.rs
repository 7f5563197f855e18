//! The `modal-beam` builtin: the mid-span deflection history of a clamped-clamped beam under
//! a rectangular pulse by modal superposition (`impact_analytical::modal_beam`), the reference
//! the solver's pulse runs are compared with.

use std::collections::BTreeMap;

use impact_analytical::beam::ClampedBeam;
use impact_analytical::modal_beam::ModalBeam;
use impact_solver::History;

use crate::definition::run_data::RunData;
use crate::run::builtin_params::{param, Params};

/// Euler-Bernoulli clamped-clamped beam (plane strain modulus) under a rectangular pulse at
/// mid-span: modal superposition, mid-span deflection history (negative = down).
pub(super) fn modal_beam(p: &Params) -> Result<RunData, String> {
    let length = param(p, "length", 0.8)?;
    let thickness = param(p, "thickness", 0.02)?;
    let width = param(p, "width", 0.2)?;
    let (e_mod, nu, rho) = (
        param(p, "youngs_modulus", 207e9)?,
        param(p, "poisson_ratio", 0.3)?,
        param(p, "density", 7850.0)?,
    );
    let force = param(p, "force", 86.5e3)?;
    let duration = param(p, "duration", 1e-3)?;
    let end = param(p, "end", 4e-3)?;
    let every = param(p, "every", 1e-6)?;
    let n_modes = param(p, "modes", 40.0)? as usize;
    let beam = ClampedBeam::new(length, width, thickness, e_mod, nu)?;
    let beam = ModalBeam::new(&beam, rho, n_modes)?;
    let rows = (end / every).round() as usize;
    let mut values = Vec::with_capacity(2 * (rows + 1));
    for i in 0..=rows {
        let t = i as f64 * every;
        values.extend([t, -beam.midspan_deflection(force, duration, t)]);
    }
    let mut m = BTreeMap::new();
    m.insert("static_deflection_m".into(), beam.static_midspan(force));
    m.insert("first_period_s".into(), beam.first_period_s());
    m.insert(
        "min_mid_uy_m".into(),
        values
            .iter()
            .skip(1)
            .step_by(2)
            .copied()
            .fold(f64::INFINITY, f64::min),
    );
    m.insert("series_static_m".into(), beam.series_static_midspan(force));
    let mut histories = BTreeMap::new();
    histories.insert(
        String::new(),
        History {
            columns: vec!["time_s".into(), "mid_uy_m".into()],
            values,
        },
    );
    Ok(RunData {
        metrics: m,
        histories,
        ..Default::default()
    })
}
