//! The `plane-wave` builtin: the solver's plane-strain wave speed, measured by the momentum
//! deficit of the layer above a mid-depth probe, against the closed form
//! (`impact_analytical::plane_wave`).

use std::collections::BTreeMap;

use impact_analytical::plane_wave::PlaneWave;

use crate::definition::run_data::RunData;
use crate::run::builtin_params::{element_kind, param, param_str, Params};

pub(super) fn plane_wave(p: &Params) -> Result<RunData, String> {
    let element = element_kind(param_str(p, "element", "q4-sri")?)?;
    let problem = PlaneWave::new(
        param_str(p, "wave", "p")?,
        param(p, "ny", 80.0)? as usize,
        element,
        param(p, "cfl", 0.5)?,
    )?;
    let o = impact_solver::simulate(&problem.scene, &mut impact_solver::Quiet)
        .map_err(|e| e.to_string())?;
    let c = problem.measured_speed(&o.history)?;
    let exact = problem.exact_mps;
    let mut m = BTreeMap::new();
    m.insert("speed_mps".into(), c);
    m.insert("closed_form_mps".into(), exact);
    m.insert("relative_error".into(), (c / exact - 1.0).abs());
    m.insert(
        "max_energy_balance_error".into(),
        o.summary.max_energy_balance_error,
    );
    let mut histories = BTreeMap::new();
    histories.insert(String::new(), o.history);
    Ok(RunData {
        metrics: m,
        histories,
        ..Default::default()
    })
}
