//! The wall's summary keys recomputed from the run's own history (part of the case
//! `invariants/history-summary`, `history_invariants.rs`), for every run of the matrix on the
//! rigid wall (`load: {wall}`; definitions: `solver/ALGORITHM.md` section 5c). Each key is the
//! history's column at the end, or its largest value over the run:
//! - `final-length`: `wall.final_length_m` is the last row's `bar_length_m`, exact. (Before
//!   issue 40 both were the top axis node's height, which counts the gap once the bar has
//!   left the wall; the column now reads the bar itself, and the summary must follow it.)
//! - `foot-radius`: `wall.foot_radius_m` is the last row's `foot_radius_m`, exact.
//! - `undeformed-length`: `wall.undeformed_length_m` is the last row's `undeformed_length_m`,
//!   exact (where the run gives both: a code that does not produce Taylor's `X` has no row).
//! - `max-foot-radius`, `peak-force`, `peak-step-force`: `wall.max_foot_radius_m`,
//!   `wall.peak_force_N` and `wall.peak_step_force_N` are the largest `foot_radius_m`,
//!   `bearing_force_N` and `contact_force_N` over every step: equal to the rows' largest when
//!   every step is a row, and never below it otherwise. (Before issue 40 the largest foot
//!   radius counted only the nodes touching the wall at each step, and fell below the foot
//!   radius at the end: 5.94 against 9.22 mm on the Abaqus Taylor bar; the summary's peak
//!   force was the landing's one-step stop, now `peak_step_force_N`.)
//! - `dissipation`: `wall.dissipated_energy_J` is the last row's `contact_energy_J`, exact.
//! - `release`: `wall.release_time_s` is null exactly when the last row's wall force is
//!   non-zero (positive on a resting body, negative when `hold_face` pulls the face back), and `wall.rebound_velocity_mps` is null exactly when `release_time_s` is (a
//!   rebound reported for a bar still on the wall, the old definition, counts 1).
//!
//! Exact means the same `f64`: the summary and the history are written from the same value.

use crate::definition::check::CheckResult;
use crate::definition::run_data::RunData;
use serde_json::Value;

use super::invariant_row::row;

/// What one wall run's history gives against its summary's `wall`.
#[derive(Debug, Clone, PartialEq)]
pub struct WallRecomputed {
    /// `(summary, last row)` of final length, foot radius (m) and dissipation (J).
    pub at_end: [(f64, f64); 3],
    /// `(summary, last row)` of the undeformed length (m), where the run gives both.
    pub undeformed: Option<(f64, f64)>,
    /// `(summary, rows' largest)` of the largest foot radius (m), the bearing force (N) and
    /// the step force (N).
    pub largest: [(f64, f64); 3],
    /// Whether every step is a row (then the largest are equal).
    pub every_step: bool,
    /// Disagreements of `release_time_s` with the last force, and of `rebound_velocity_mps`
    /// with `release_time_s` (0, 1 or 2).
    pub release_mismatches: usize,
}

/// The recomputation for a wall run, `None` for any other run.
pub fn recompute(run: &RunData) -> Option<WallRecomputed> {
    let s = run.summary.as_ref()?;
    let wall = s.get("wall")?;
    let h = run.history()?;
    let column = |name: &str| h.column(name);
    let [t, force] = [column("time_s")?, column("contact_force_N")?];
    let last = |name: &str| column(name).and_then(|c| c.last().copied());
    let largest_of = |c: &[f64]| c.iter().copied().fold(f64::MIN, f64::max);
    let largest = |name: &str| column(name).map(|c| largest_of(&c));
    let key = |k: &str| wall.get(k).and_then(Value::as_f64);
    // Steps 0 to n_steps are sampled; every one is a row when there are n_steps + 1 rows.
    let every_step = s.get("n_steps")?.as_u64()? + 1 == t.len() as u64;
    let released = !wall.get("release_time_s")?.is_null();
    let rebound = !wall.get("rebound_velocity_mps")?.is_null();
    let on_wall = *force.last()? != 0.0;
    Some(WallRecomputed {
        at_end: [
            (key("final_length_m")?, last("bar_length_m")?),
            (key("foot_radius_m")?, last("foot_radius_m")?),
            (key("dissipated_energy_J")?, last("contact_energy_J")?),
        ],
        undeformed: key("undeformed_length_m").zip(last("undeformed_length_m")),
        largest: [
            (key("max_foot_radius_m")?, largest("foot_radius_m")?),
            (key("peak_force_N")?, largest("bearing_force_N")?),
            (key("peak_step_force_N")?, largest_of(&force)),
        ],
        every_step,
        release_mismatches: usize::from(released == on_wall) + usize::from(rebound != released),
    })
}

/// The checks of wall run `name` (`suite/case/scene`).
pub fn checks(name: &str, r: &WallRecomputed) -> Vec<CheckResult> {
    const AT_END: [(&str, &str, &str); 3] = [
        ("final-length", "wall.final_length_m", "bar_length_m"),
        ("foot-radius", "wall.foot_radius_m", "foot_radius_m"),
        (
            "dissipation",
            "wall.dissipated_energy_J",
            "contact_energy_J",
        ),
    ];
    const LARGEST: [(&str, &str, &str); 3] = [
        ("max-foot-radius", "wall.max_foot_radius_m", "foot_radius_m"),
        ("peak-force", "wall.peak_force_N", "bearing_force_N"),
        (
            "peak-step-force",
            "wall.peak_step_force_N",
            "contact_force_N",
        ),
    ];
    const UNDEFORMED: (&str, &str, &str) = (
        "undeformed-length",
        "wall.undeformed_length_m",
        "undeformed_length_m",
    );
    let mut out = Vec::new();
    let at_end = AT_END.iter().zip(r.at_end);
    for ((id, key, col), (summary, row_value)) in
        at_end.chain(r.undeformed.map(|u| (&UNDEFORMED, u)))
    {
        out.push(row(
            format!("{name}: {id}"),
            &format!("{key} vs the last row's {col}"),
            (summary, row_value, 0.0),
            "the same value written twice (the summary's definition): exact",
        ));
    }
    for ((id, key, col), (summary, rows)) in LARGEST.iter().zip(r.largest) {
        let (title, reference, why) = if r.every_step {
            (
                format!("{key} vs the largest {col} over the rows (every step)"),
                rows,
                "every step is a row: the same largest value, exact",
            )
        } else {
            (
                format!("{key} vs the larger of itself and the largest {col} over the rows"),
                summary.max(rows),
                "the rows are some of the steps: the largest over every step is never below the rows' largest (a shortfall fails)",
            )
        };
        out.push(row(
            format!("{name}: {id}"),
            &title,
            (summary, reference, 0.0),
            why,
        ));
    }
    out.push(row(
        format!("{name}: release"),
        "release_time_s null exactly when the last wall force is positive, rebound_velocity_mps null exactly when release_time_s is: disagreements",
        (r.release_mismatches as f64, 0.0, 0.0),
        "a count: the release is the end of the last contact interval, the rebound the velocity after it",
    ));
    out
}

#[cfg(test)]
mod tests {
    //! A made-up wall run (a bar that lands, spreads and leaves the wall, rows every step or
    //! every other step) and the old definitions the checks must tell: a final length with
    //! the gap, a largest foot radius of the touching nodes only, a peak force of the landing
    //! stop, a rebound for a bar still on the wall.
    use super::*;
    use crate::definition::check::Status;
    use impact_solver::History;
    use std::collections::BTreeMap;

    const COLUMNS: [&str; 7] = [
        "time_s",
        "contact_force_N",
        "foot_radius_m",
        "bar_length_m",
        "bearing_force_N",
        "contact_energy_J",
        "undeformed_length_m",
    ];

    /// Steps of 1 us: a landing stop of 9e6 N at step 0, bearing forces rising then falling,
    /// release at step 6 (force 0 from there), the foot growing to 5 mm then recovering to
    /// 4.5 mm; rows every `every` steps and the last.
    fn run(every: usize) -> RunData {
        let step = |n: usize| -> [f64; 7] {
            let force = [9e6, 4e5, 5e5, 3e5, 2e5, 1e5, 0.0, 0.0][n];
            let bearing = [1e4, 3.9e5, 5e5, 3e5, 2e5, 1e5, 0.0, 0.0][n];
            let foot = [1e-3, 2e-3, 4e-3, 5e-3, 4.8e-3, 4.6e-3, 4.5e-3, 4.5e-3][n];
            [
                n as f64 * 1e-6,
                force,
                foot,
                0.03 - 1e-4 * n as f64,
                bearing,
                2.0,
                0.03 - 1e-3 * n as f64,
            ]
        };
        let rows: Vec<usize> = (0..8).filter(|n| n % every == 0 || *n == 7).collect();
        let values = rows.iter().flat_map(|&n| step(n)).collect();
        let summary = serde_json::json!({
            "n_steps": 7,
            "wall": {
                "final_length_m": step(7)[3], "foot_radius_m": 4.5e-3,
                "undeformed_length_m": step(7)[6],
                "dissipated_energy_J": 2.0, "max_foot_radius_m": 5e-3,
                "peak_force_N": 5e5, "peak_step_force_N": 9e6,
                "release_time_s": 6e-6, "rebound_velocity_mps": 3.0,
            }
        });
        RunData {
            histories: BTreeMap::from([(
                String::new(),
                History {
                    columns: COLUMNS.map(String::from).to_vec(),
                    values,
                },
            )]),
            summary: Some(summary),
            ..Default::default()
        }
    }

    fn failing(data: &RunData) -> Vec<String> {
        checks("bar", &recompute(data).unwrap())
            .into_iter()
            .filter(|k| k.status == Status::Fail)
            .map(|k| k.id)
            .collect()
    }

    fn with(data: &RunData, key: &str, value: Value) -> RunData {
        let mut d = data.clone();
        d.summary.as_mut().unwrap()["wall"][key] = value;
        d
    }

    #[test]
    fn the_old_definitions_fail_and_the_solver_s_pass() {
        for every in [1, 2] {
            let data = run(every);
            assert!(failing(&data).is_empty(), "{every}: {:?}", failing(&data));
            let gap = with(&data, "final_length_m", serde_json::json!(0.03));
            assert_eq!(failing(&gap), ["bar: final-length"]);
            let touching = with(&data, "max_foot_radius_m", serde_json::json!(4.0e-3));
            assert_eq!(failing(&touching), ["bar: max-foot-radius"]);
            let stop = with(&data, "peak_force_N", serde_json::json!(9e6));
            // The landing stop as the bearing peak: above the rows' largest bearing force; with
            // every step in the rows the equality fails it, else the one-sided check cannot.
            assert_eq!(failing(&stop).len(), usize::from(every == 1), "{every}");
            // Taylor's X read at the largest bulge (the old habit of reading it mid-run).
            let mid_run = with(&data, "undeformed_length_m", serde_json::json!(0.027));
            assert_eq!(failing(&mid_run), ["bar: undeformed-length"]);
            let on_wall = with(&data, "release_time_s", Value::Null);
            assert_eq!(failing(&on_wall), ["bar: release"]);
        }
        // A bar still on the wall with a rebound (the old definition): counted.
        let mut d = run(1);
        let v = &mut d.histories.get_mut("").unwrap().values;
        let last = v.len() - COLUMNS.len();
        v[last + 1] = 1e5;
        let d = with(&d, "release_time_s", Value::Null);
        assert_eq!(failing(&d), ["bar: release"]);
        assert_eq!(recompute(&d).unwrap().release_mismatches, 1);
    }

    #[test]
    fn a_code_without_taylor_s_x_has_no_undeformed_row() {
        // Another code's results (the contract's subset) without the key: the other rows stay.
        let mut d = run(1);
        d.summary.as_mut().unwrap()["wall"]
            .as_object_mut()
            .unwrap()
            .remove("undeformed_length_m");
        let r = recompute(&d).unwrap();
        assert_eq!(r.undeformed, None);
        let ids: Vec<String> = checks("bar", &r).into_iter().map(|k| k.id).collect();
        assert!(
            !ids.contains(&"bar: undeformed-length".to_string()),
            "{ids:?}"
        );
        assert!(ids.contains(&"bar: final-length".to_string()), "{ids:?}");
    }
}
