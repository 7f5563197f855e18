//! The `thread-invariance` builtin: one elasto-plastic impact of at least
//! `impact_solver::assembly::PARALLEL_MIN_ELEMENTS` elements (the size from which the plastic
//! stress path runs on the element team, as `impact simulate` runs it by default: one part per
//! core) run on one thread and on a team of two (`impact_solver::workers::with_threads`, as
//! `--threads 2`); the matrix's other runs are on one thread each (a rayon worker's model gets
//! one thread), so without this case the team's assembly is never in the matrix.
//!
//! Invariant: the results are the same bits (README: bit-identical output for any thread
//! count): every summary key (wall times aside) and every history value. A team that adds the
//! parts' forces or energies in another order than the element order changes the last bits;
//! what such an order gives on this run's own numbers is reported as `two_part_sum_ulps`: the
//! final element von Mises stresses (Pa) added in element order and as two contiguous
//! halves added afterwards (a two-part team's partial sums) differ by that many units in the
//! last place.

use std::collections::BTreeMap;

use impact_solver::integrator::FieldFrame;
use impact_solver::Observer;
use serde_json::Value;

use super::scene_text::run_scene_text;
use crate::definition::run_data::RunData;
use crate::run::builtin_params::param;

/// The elasto-plastic example at `nx` x `ny` (history every 1 us, one field frame at
/// the end), 3 ms.
fn scene_text(nx: usize, ny: usize) -> String {
    format!(
        "plate: {{length: 0.2, width: 0.2, thickness: 0.02}}\n\
         material:\n  density: 7850.0\n  youngs_modulus: 207.0e9\n  poisson_ratio: 0.3\n  \
         plasticity: {{yield_stress: 250.0e6, hardening: {{linear: 1.5e9}}}}\n\
         mesh: {{nx: {nx}, ny: {ny}, element: q4-sri, model: half}}\n\
         load:\n  impactor: {{mass: 18.0, velocity: 10.0, nose_radius: 0.010, youngs_modulus: 207.0e9, \
         poisson_ratio: 0.3, contact_law: {{paper: {{length_unit: 1.0}}}}}}\n\
         time: {{end: 3.0e-3, dt: {{cfl: 0.8}}}}\n\
         output: {{every: 1.0e-6, probes: {{A: {{x: 0.1, y: 0.0}}}}, fields: {{every: 3.0e-3}}}}\n"
    )
}

/// Keeps the last field frame's element von Mises stresses, Pa.
#[derive(Default)]
struct LastStresses(Vec<f64>);

impl Observer for LastStresses {
    fn wants_fields(&self) -> bool {
        true
    }
    fn fields(&mut self, frame: FieldFrame) -> impact_solver::Result<()> {
        self.0 = frame.von_mises;
        Ok(())
    }
}

/// A run's summary (top-level keys as JSON text, without the timing keys), history values (bits)
/// and final element von Mises stresses.
type Results = (BTreeMap<String, String>, Vec<u64>, Vec<f64>);

fn run_on(threads: usize, text: &str) -> Result<Results, String> {
    let mut last = LastStresses::default();
    let out = impact_solver::workers::with_threads(threads, || {
        run_scene_text(text, "thread-invariance", &mut last)
    })?;
    // What measures the machine (wall times, the team's fallback on a loaded machine) differs
    // run to run; everything else must not.
    let summary = match serde_json::to_value(&out.summary).map_err(|e| e.to_string())? {
        Value::Object(map) => map
            .into_iter()
            .filter(|(k, _)| !impact_solver::summary::is_timing_key(k))
            .map(|(k, v)| (k, v.to_string()))
            .collect(),
        other => return Err(format!("thread-invariance: summary is not a map: {other}")),
    };
    let history = out.history.values.iter().map(|x| x.to_bits()).collect();
    Ok((summary, history, last.0))
}

/// Units in the last place between `a` and `b` (same sign assumed).
fn ulps(a: f64, b: f64) -> f64 {
    (a.to_bits() as i64 - b.to_bits() as i64).unsigned_abs() as f64
}

/// Parameters: `nx`, `ny` (default 40 x 8 = 320 elements).
pub fn thread_invariance(p: &BTreeMap<String, Value>) -> Result<RunData, String> {
    let nx = param(p, "nx", 40.0)? as usize;
    let ny = param(p, "ny", 8.0)? as usize;
    let text = scene_text(nx, ny);
    let (s1, h1, x1) = run_on(1, &text)?;
    let (s2, h2, _) = run_on(2, &text)?;
    let keys_differing = s1
        .keys()
        .chain(s2.keys())
        .collect::<std::collections::BTreeSet<_>>()
        .into_iter()
        .filter(|k| s1.get(*k) != s2.get(*k))
        .count();
    let values_differing = if h1.len() == h2.len() {
        h1.iter().zip(&h2).filter(|(a, b)| a != b).count()
    } else {
        h1.len().max(h2.len())
    };
    let forward: f64 = x1.iter().sum();
    let (a, b) = x1.split_at(x1.len() / 2);
    let halves = a.iter().sum::<f64>() + b.iter().sum::<f64>();
    let metrics = BTreeMap::from([
        ("elements".to_string(), (nx * ny) as f64),
        (
            "parallel_min_elements".to_string(),
            impact_solver::assembly::PARALLEL_MIN_ELEMENTS as f64,
        ),
        ("summary_keys_compared".to_string(), s1.len() as f64),
        ("summary_keys_differing".to_string(), keys_differing as f64),
        ("history_values_compared".to_string(), h1.len() as f64),
        (
            "history_values_differing".to_string(),
            values_differing as f64,
        ),
        ("two_part_sum_ulps".to_string(), ulps(forward, halves)),
    ]);
    Ok(RunData {
        metrics,
        ..Default::default()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The negative control: adding the run's final element stresses as two parts (a
    /// two-thread team's partial sums) instead of in element order changes the bits, so a team
    /// assembly in another order would change the results the case compares bit for bit.
    #[test]
    fn another_summation_order_changes_the_bits() {
        let m = thread_invariance(&BTreeMap::new()).unwrap().metrics;
        assert!(m["elements"] >= m["parallel_min_elements"], "{m:?}");
        assert_eq!(m["summary_keys_differing"], 0.0, "{m:?}");
        assert_eq!(m["history_values_differing"], 0.0, "{m:?}");
        assert!(m["two_part_sum_ulps"] > 0.0, "{m:?}");
    }
}
