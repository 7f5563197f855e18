//! The matrix's invariant on every run of the rigid nose in surface contact under the kinematic
//! enforcement (`contact_law` `surface(kinematic)`, solver/ALGORITHM.md 5b), a row of case
//! `invariants/history-summary`: `penetration`, the summary's `max_penetration_m` (the deepest
//! top-surface node in the nose at any `t_n`) is round-off against the plate's deflection. The
//! enforcement puts back on the nose's surface every node the contact-free step would push
//! into it, so what is left is the round-off of the linearised gap; a solve that closes only
//! part of the gap (a wrong `c = dt h`, a mobility without the impactor's recoil), or lets a
//! node through, leaves a penetration of the order of the step's motion.

use crate::definition::check::CheckResult;
use crate::definition::run_data::RunData;

use super::invariant_row::row;

/// The bound on the deepest penetration over the largest mid-span deflection: round-off of
/// positions of that size, about 3000x the largest measured (3.3e-16, the elasto-plastic Table 1
/// surface run at 80 x 16; the elastic one 1.2e-16).
const ROUND_OFF: f64 = 1e-12;

/// `max_penetration_m` and the largest mid-span deflection `|max_plate_displacement_m|` (m) of a
/// kinematic surface-coupling run; `None` for any other run.
pub fn kinematic_penetration(run: &RunData) -> Option<(f64, f64)> {
    let s = run.summary.as_ref()?;
    if s.get("contact_law")?.as_str()? != "surface(kinematic)" {
        return None;
    }
    let depth = s.get("max_penetration_m")?.as_f64()?;
    let deflection = s.get("max_plate_displacement_m")?.as_f64()?.abs();
    Some((depth, deflection))
}

/// The check of run `name` that no node stayed in the nose beyond round-off.
pub fn penetration_check(name: &str, (depth, deflection): (f64, f64)) -> CheckResult {
    row(
        format!("{name}: penetration"),
        "max_penetration_m of a kinematic surface run vs 0 (m): round-off of the deflection",
        (depth, 0.0, ROUND_OFF * deflection),
        "the kinematic enforcement closes every predicted gap: 1e-12 of the largest deflection, the round-off of positions of that size (measured up to 3.3e-16 of it on the Table 1 surface runs)",
    )
}

#[cfg(test)]
mod tests {
    //! The check on made-up summaries: round-off passes, a node left a micrometre in the nose
    //! fails, a penalty run has no check.
    use super::*;
    use crate::definition::check::Status;

    fn run(law: &str, depth: f64) -> RunData {
        RunData {
            summary: Some(serde_json::json!({
                "contact_law": law, "max_penetration_m": depth, "max_plate_displacement_m": -1.8e-3
            })),
            ..Default::default()
        }
    }

    #[test]
    fn a_node_left_in_the_nose_fails() {
        let status = |depth| {
            let r = run("surface(kinematic)", depth);
            penetration_check("r", kinematic_penetration(&r).unwrap()).status
        };
        assert_eq!(status(2.2e-19), Status::Ok);
        assert_eq!(status(1.0e-6), Status::Fail);
        assert!(kinematic_penetration(&run("surface(penalty, penalty_scale=0.1)", 1e-4)).is_none());
    }
}
