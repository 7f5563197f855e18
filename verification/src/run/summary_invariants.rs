//! The summary's extremes, its start and end values and its stop reason recomputed from the
//! run's own history (part of the case `invariants/history-summary`, `history_invariants.rs`),
//! for every scene run of impact's own (definitions: `solver/ALGORITHM.md` section 8):
//! - `extremes`: `peak_contact_force_N`, `max_plate_displacement_m`, `max_bottom_displacement_m`,
//!   each probe's `max_von_mises_Pa` and `max_energy_balance_error` are the largest (the
//!   displacements: the most negative) of `contact_force_N`, `mid_uy_m`, `bottom_uy_m`,
//!   `<probe>_von_mises_Pa` and `energy_balance_error` over every step, starting from 0 (a run
//!   whose force is never positive has a peak of 0). When every step is a row the two are the
//!   same `f64`; otherwise the summary's is never short of the rows' (the rows are some of the
//!   steps). A summary that reads its extremes at the rows only, a displacement taken as the
//!   largest magnitude (an upward rebound), another probe's stress, fails.
//! - `start-and-end`: `final_time_s` is the last row's `time_s`; the seven terms of
//!   `initial_energy_J` and `final_energy_J` are the first and last rows' energy columns. The
//!   last step is always a row and the first is step 0, so each is the same `f64` written
//!   twice: a summary that reports the energies of the step before the last, or a term under
//!   another's name, fails.
//! - `stop-reason`: `stop_reason` agrees with the scene's `time.end` and the history: `end_time`
//!   when the end is a time `t_e` and the run stopped at the first step at or past it
//!   (`t_e - 1e-9 dt <= final_time_s < t_e + dt`); with `end: {after_contact, limit}`,
//!   `after_contact` when the run stopped at the first step `after` past the end of its last
//!   contact interval, `time_limit` when it stopped at the limit before that. A run that stops
//!   late, early, or for a reason its history contradicts, counts.
//!
//! Each check is a count of the keys that disagree (0), its message naming each with its two
//! values: one row per run for each of the three, rather than one per key.

use crate::definition::check::{CheckResult, Status};
use crate::definition::run_data::RunData;
use impact_solver::energy::Energies;
use serde_json::Value;

use super::invariant_row::row;

/// The scene's end as the matrix's runs record it (`RunData::scene_values` of impact's own
/// scene runs, s).
pub const END_VALUES: [&str; 3] = [
    "scene_time_end_s",
    "scene_after_contact_s",
    "scene_time_limit_s",
];

/// The summary's energy terms, in the order of their history columns (`Energies::COLUMNS`).
const ENERGY_TERMS: [&str; 7] = [
    "plate_kinetic",
    "impactor_kinetic",
    "strain",
    "plastic_work",
    "hourglass",
    "contact",
    "external_work",
];

/// One summary key against the value its history gives.
#[derive(Debug, Clone, PartialEq)]
pub struct KeyPair {
    pub key: String,
    pub summary: f64,
    pub history: f64,
}

/// What one run's history gives against its summary.
#[derive(Debug, Clone, PartialEq)]
pub struct SummaryRecomputed {
    /// The largest-over-steps keys: summary, rows' extreme (most negative for displacements).
    pub extremes: Vec<(KeyPair, Sign)>,
    /// Whether every step is a row (then the extremes are equal).
    pub every_step: bool,
    /// The start and end values: summary, first or last row.
    pub start_and_end: Vec<KeyPair>,
    /// What contradicts the stop reason (empty when it agrees).
    pub stop_mismatches: Vec<String>,
}

/// Whether a key is the largest (`Largest`) or the most negative (`Lowest`) of its column.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Sign {
    Largest,
    Lowest,
}

/// The recomputation for one of impact's own scene runs (it records the scene's end), `None`
/// for any other run.
pub fn recompute(run: &RunData) -> Option<SummaryRecomputed> {
    let s = run.summary.as_ref()?;
    if !END_VALUES.iter().any(|k| run.scene_values.contains_key(*k)) {
        return None;
    }
    let h = run.history()?;
    let t = h.column("time_s")?;
    let every_step = s.get("n_steps")?.as_u64()? + 1 == t.len() as u64;
    let number = |v: Option<&Value>| v.and_then(Value::as_f64);
    let mut extremes = Vec::new();
    let mut extreme = |key: String, summary: Option<f64>, column: &str, sign: Sign| {
        if let (Some(summary), Some(c)) = (summary, h.column(column)) {
            let history = match sign {
                Sign::Largest => c.iter().copied().fold(0.0, f64::max),
                Sign::Lowest => c.iter().copied().fold(0.0, f64::min),
            };
            extremes.push((
                KeyPair {
                    key,
                    summary,
                    history,
                },
                sign,
            ));
        }
    };
    for (key, column, sign) in [
        ("peak_contact_force_N", "contact_force_N", Sign::Largest),
        ("max_plate_displacement_m", "mid_uy_m", Sign::Lowest),
        ("max_bottom_displacement_m", "bottom_uy_m", Sign::Lowest),
        (
            "max_energy_balance_error",
            "energy_balance_error",
            Sign::Largest,
        ),
    ] {
        extreme(key.into(), number(s.get(key)), column, sign);
    }
    for (probe, value) in s.get("max_von_mises_Pa")?.as_object()? {
        let column = format!("{probe}_von_mises_Pa");
        extreme(
            format!("max_von_mises_Pa.{probe}"),
            value.as_f64(),
            &column,
            Sign::Largest,
        );
    }
    Some(SummaryRecomputed {
        extremes,
        every_step,
        start_and_end: start_and_end(s, h)?,
        stop_mismatches: stop_mismatches(run, s, *t.last()?)?,
    })
}

/// `final_time_s` against the last row's time, the energies against the first and last rows.
fn start_and_end(s: &Value, h: &impact_solver::History) -> Option<Vec<KeyPair>> {
    let pair = |key: String, summary: Option<f64>, history: Option<f64>| {
        Some(KeyPair {
            key,
            summary: summary?,
            history: history?,
        })
    };
    let mut out = vec![pair(
        "final_time_s".into(),
        s.get("final_time_s")?.as_f64(),
        h.column("time_s")?.last().copied(),
    )?];
    for (term, column) in ENERGY_TERMS.into_iter().zip(Energies::COLUMNS) {
        let c = h.column(column)?;
        for (key, row) in [
            ("initial_energy_J", c.first()),
            ("final_energy_J", c.last()),
        ] {
            let summary = s.get(key)?.get(term)?.as_f64();
            out.push(pair(format!("{key}.{term}"), summary, row.copied())?);
        }
    }
    Some(out)
}

/// What contradicts the summary's `stop_reason`, given the scene's end (`scene_values`) and the run's
/// last time `end` (s); `None` when the summary lacks a key it needs.
fn stop_mismatches(run: &RunData, s: &Value, end: f64) -> Option<Vec<String>> {
    let reason = s.get("stop_reason")?.as_str()?;
    let dt = s.get("dt_max_s").or(s.get("dt_s"))?.as_f64()?;
    let first_at_or_past = |target: f64| target - 1e-9 * dt <= end && end < target + dt;
    let metric = |k: &str| run.scene_values.get(k).copied();
    let mut out = Vec::new();
    if let Some(t_end) = metric(END_VALUES[0]) {
        if reason != "end_time" {
            out.push(format!(
                "stop_reason {reason} for an end at t = {t_end:e} s"
            ));
        } else if !first_at_or_past(t_end) {
            out.push(format!(
                "end_time at {end:e} s, not the first step at or past {t_end:e} s"
            ));
        }
        return Some(out);
    }
    let (after, limit) = (metric(END_VALUES[1])?, metric(END_VALUES[2])?);
    let intervals: Vec<[f64; 2]> =
        serde_json::from_value(s.get("contact_intervals_s")?.clone()).ok()?;
    // The end of the last interval, when contact had ended before the run's last step.
    let separated = intervals.last().map(|i| i[1]).filter(|&e| e < end);
    let waited = separated.is_some_and(|e| end - e >= after - 1e-9 * dt);
    match reason {
        "after_contact" if !separated.is_some_and(|e| first_at_or_past(e + after)) => out.push(
            format!("after_contact at {end:e} s, not the first step {after:e} s past the last contact ({separated:?})"),
        ),
        "time_limit" if !first_at_or_past(limit) => {
            out.push(format!("time_limit at {end:e} s, not the first step at or past {limit:e} s"))
        }
        "time_limit" if waited && end - separated? >= after + dt => out.push(format!(
            "time_limit at {end:e} s, though contact ended at {separated:?} s, more than {after:e} s and a step before"
        )),
        "after_contact" | "time_limit" => {}
        other => out.push(format!("stop_reason {other} for an end {after:e} s after contact")),
    }
    Some(out)
}

/// The largest-over-steps keys that disagree with their columns, as `key summary vs history`.
fn extreme_mismatches(r: &SummaryRecomputed) -> Vec<String> {
    r.extremes
        .iter()
        .filter(|(p, sign)| {
            if r.every_step {
                p.summary != p.history
            } else {
                match sign {
                    Sign::Largest => p.summary < p.history,
                    Sign::Lowest => p.summary > p.history,
                }
            }
        })
        .map(|(p, _)| format!("{} {:e} vs {:e}", p.key, p.summary, p.history))
        .collect()
}

/// A count row whose message names what disagrees.
fn count_row(id: String, title: &str, what: Vec<String>, why: &str) -> CheckResult {
    let mut c = row(id, title, (what.len() as f64, 0.0, 0.0), why);
    if c.status == Status::Fail {
        c.message = what.join("; ");
    }
    c
}

/// The three checks of run `name` (`suite/case/scene`).
pub fn checks(name: &str, r: &SummaryRecomputed) -> Vec<CheckResult> {
    let ends = r
        .start_and_end
        .iter()
        .filter(|p| p.summary != p.history)
        .map(|p| format!("{} {:e} vs {:e}", p.key, p.summary, p.history))
        .collect();
    let (extremes_title, extremes_why) = if r.every_step {
        (
            "peak_contact_force_N, max_plate/bottom_displacement_m, max_von_mises_Pa (each probe), max_energy_balance_error vs the extreme of their columns over the rows (every step): keys that differ",
            "every step is a row: the same extreme, exact",
        )
    } else {
        (
            "peak_contact_force_N, max_plate/bottom_displacement_m, max_von_mises_Pa (each probe), max_energy_balance_error vs the extreme of their columns over the rows: keys short of it",
            "the rows are some of the steps: the extreme over every step is never short of the rows' (a shortfall counts)",
        )
    };
    vec![
        count_row(format!("{name}: extremes"), extremes_title, extreme_mismatches(r), extremes_why),
        count_row(
            format!("{name}: start-and-end"),
            "final_time_s and the 7 terms of final_energy_J vs the last row, the 7 of initial_energy_J vs the first: keys that differ",
            ends,
            "the first row is step 0 and the last step is always a row: the same values written twice, exact",
        ),
        count_row(
            format!("{name}: stop-reason"),
            "stop_reason vs the scene's time.end and the history (the first step at or past the end, or after_contact s past the last contact): disagreements",
            r.stop_mismatches.clone(),
            "a count: the stop is decided on the step's own time against the end, within 1e-9 of a step",
        ),
    ]
}

#[cfg(test)]
mod tests {
    //! A made-up run (10 steps of 1 us, a contact from 2 to 5 us, a probe, the energies; rows
    //! every step or every third and the last) as the solver writes it, and the slips each
    //! check must tell: extremes read at the rows only, a displacement taken as its largest
    //! magnitude, the energies of the step before the last, a run that stopped a step late.
    use super::*;
    use impact_solver::History;
    use std::collections::BTreeMap;

    const COLUMNS: [&str; 13] = [
        "time_s",
        "contact_force_N",
        "mid_uy_m",
        "bottom_uy_m",
        "A_von_mises_Pa",
        "plate_kinetic_J",
        "impactor_kinetic_J",
        "strain_energy_J",
        "plastic_work_J",
        "hourglass_energy_J",
        "contact_energy_J",
        "external_work_J",
        "energy_balance_error",
    ];

    fn step(n: usize) -> [f64; 13] {
        let x = n as f64;
        let force = if (2..5).contains(&n) {
            1e5 * (x - 1.0)
        } else {
            0.0
        };
        let uy = -1e-4 * x * (10.0 - x) + 2e-4 * f64::from(u8::from(n == 9));
        let e = 100.0 - x;
        [
            x * 1e-6,
            force,
            uy,
            0.9 * uy,
            1e8 * x.sin().abs(),
            e,
            0.0,
            x,
            0.0,
            0.0,
            0.0,
            0.0,
            1e-4 * (x * 1.3).sin().abs(),
        ]
    }

    fn run(every: usize) -> RunData {
        let rows: Vec<usize> = (0..=10).filter(|n| n % every == 0 || *n == 10).collect();
        let all: Vec<[f64; 13]> = (0..=10).map(step).collect();
        let largest = |c: usize| all.iter().map(|r| r[c]).fold(0.0, f64::max);
        let lowest = |c: usize| all.iter().map(|r| r[c]).fold(0.0, f64::min);
        let energies = |r: &[f64; 13]| {
            serde_json::json!({"plate_kinetic": r[5], "impactor_kinetic": r[6], "strain": r[7],
                "plastic_work": r[8], "hourglass": r[9], "contact": r[10], "external_work": r[11]})
        };
        let summary = serde_json::json!({
            "n_steps": 10, "dt_s": 1e-6, "final_time_s": all[10][0], "stop_reason": "after_contact",
            "contact_intervals_s": [[2e-6, 5e-6]],
            "peak_contact_force_N": largest(1), "max_plate_displacement_m": lowest(2),
            "max_bottom_displacement_m": lowest(3), "max_von_mises_Pa": {"A": largest(4)},
            "max_energy_balance_error": largest(12),
            "initial_energy_J": energies(&all[0]), "final_energy_J": energies(&all[10]),
        });
        RunData {
            scene_values: BTreeMap::from([
                ("scene_after_contact_s".to_string(), 5e-6),
                ("scene_time_limit_s".to_string(), 1e-3),
            ]),
            histories: BTreeMap::from([(
                String::new(),
                History {
                    columns: COLUMNS.map(String::from).to_vec(),
                    values: rows.iter().flat_map(|&n| all[n]).collect(),
                },
            )]),
            summary: Some(summary),
            ..Default::default()
        }
    }

    fn failing(data: &RunData) -> Vec<String> {
        checks("r", &recompute(data).unwrap())
            .into_iter()
            .filter(|k| k.status == Status::Fail)
            .map(|k| k.id)
            .collect()
    }

    fn with(data: &RunData, path: &[&str], value: Value) -> RunData {
        let mut d = data.clone();
        let mut v = d.summary.as_mut().unwrap();
        for p in path {
            v = &mut v[*p];
        }
        *v = value;
        d
    }

    #[test]
    fn the_slips_fail_and_the_solver_s_bookkeeping_passes() {
        for every in [1, 3] {
            let data = run(every);
            assert!(failing(&data).is_empty(), "{every}: {:?}", failing(&data));
            // The rows' largest stress (every third row: steps 0, 3, 6, 9, 10) instead of every
            // step's: equal when every step is a row.
            let rows_only = [0, 3, 6, 9, 10]
                .map(|n| step(n)[4])
                .into_iter()
                .fold(0.0, f64::max);
            let d = with(
                &data,
                &["max_von_mises_Pa", "A"],
                serde_json::json!(rows_only - 1.0),
            );
            assert_eq!(failing(&d), ["r: extremes"], "{every}");
            // The largest magnitude of the mid-plane's u_y is its deepest; the largest value is
            // the rebound at the end (positive): a key that takes the largest value fails.
            let up = with(
                &data,
                &["max_plate_displacement_m"],
                serde_json::json!(step(9)[2].max(0.0)),
            );
            assert_eq!(failing(&up), ["r: extremes"], "{every}");
            let before_last = with(&data, &["final_energy_J", "strain"], serde_json::json!(9.0));
            assert_eq!(failing(&before_last), ["r: start-and-end"], "{every}");
            let late = with(&data, &["final_time_s"], serde_json::json!(1.1e-5));
            assert_eq!(failing(&late), ["r: start-and-end"], "{every}");
        }
    }

    #[test]
    fn a_stop_that_its_history_contradicts_counts() {
        let data = run(1);
        // Contact ended at 5 us; after 5 us the run stops at 10 us: the first step past.
        assert!(recompute(&data).unwrap().stop_mismatches.is_empty());
        let limit = with(&data, &["stop_reason"], serde_json::json!("time_limit"));
        assert_eq!(failing(&limit), ["r: stop-reason"]);
        let mut early = data.clone();
        early
            .scene_values
            .insert("scene_after_contact_s".into(), 6e-6);
        assert_eq!(failing(&early), ["r: stop-reason"]);
        let mut at = data.clone();
        at.scene_values = BTreeMap::from([("scene_time_end_s".to_string(), 1e-5)]);
        assert_eq!(failing(&at), ["r: stop-reason"]);
        let at = with(&at, &["stop_reason"], serde_json::json!("end_time"));
        assert!(failing(&at).is_empty());
        let mut short = at.clone();
        short.scene_values.insert("scene_time_end_s".into(), 1.2e-5);
        assert_eq!(failing(&short), ["r: stop-reason"]);
    }
}
