//! The `static-pulse` builtin: the static deflection of the clamped plate as the mean of its
//! oscillation under a force held on (a pulse as long as the run), from the solver's own loop
//! (`impact_solver::simulate`, elastic). Undamped, the response oscillates about the static
//! equilibrium of the same mesh; the mean is Hann-weighted over `periods` Timoshenko first
//! periods (the window's weights suppress what whole periods of each mode would not cancel),
//! to be compared with the independent Python FE's static solve of the same scene
//! (`reference-data/independent/static-elastic/static.json`, `python -m indep_fe.static`).

use std::collections::BTreeMap;

use serde_json::Value;

use super::bending_period::{beam_periods, plate_scene};
use crate::definition::run_data::RunData;
use crate::run::builtin_params::param;

type Params = BTreeMap<String, Value>;

/// Hann-weighted mean of `x` over its samples.
fn hann_mean(x: &[f64]) -> f64 {
    let n = x.len();
    let w = |i: usize| 0.5 - 0.5 * (2.0 * std::f64::consts::PI * i as f64 / (n - 1) as f64).cos();
    let (sum, weight) = (0..n).fold((0.0, 0.0), |(s, ws), i| (s + w(i) * x[i], ws + w(i)));
    sum / weight
}

pub fn static_pulse(p: &Params) -> Result<RunData, String> {
    let (timo_period, _) = beam_periods(p)?;
    let end = param(p, "periods", 12.0)? * timo_period;
    let scene = plate_scene(p, 2.0 * end, end, timo_period / 200.0)?;
    let o =
        impact_solver::simulate(&scene, &mut impact_solver::Quiet).map_err(|e| e.to_string())?;
    let mut m = BTreeMap::new();
    for column in ["top_uy_m", "mid_uy_m", "bottom_uy_m"] {
        let x = o
            .history
            .column(column)
            .ok_or_else(|| format!("static-pulse: no {column}"))?;
        m.insert(format!("mean_{column}"), hann_mean(&x));
    }
    Ok(RunData::with_history(m, o.history))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Hann-weighted mean of an offset plus two modes over a non-whole number of their
    /// periods: the offset within 1e-3 of the amplitude (about 10x the measured -8.2e-5).
    #[test]
    fn hann_mean_removes_the_oscillation() {
        let x: Vec<f64> = (0..2400)
            .map(|i| {
                let t = i as f64 / 200.0;
                2.0 - (6.2 * t).cos() - 0.3 * (17.0 * t).cos()
            })
            .collect();
        assert!((hann_mean(&x) - 2.0).abs() < 1e-3, "{}", hann_mean(&x));
    }

    /// Negative control for the case's checks (5e-4): the plate twice as stiff halves the
    /// mean deflection.
    #[test]
    fn a_plate_twice_as_stiff_fails_the_checks() {
        let run = |e: f64| {
            let p: Params = serde_json::from_value(serde_json::json!({
                "width": 0.2, "nx": 40, "ny": 8, "model_youngs_modulus": e
            }))
            .expect("an object");
            static_pulse(&p).unwrap().metrics["mean_mid_uy_m"]
        };
        let ratio = run(414e9) / run(207e9);
        assert!((ratio - 0.5).abs() < 1e-3, "{ratio}");
    }
}
