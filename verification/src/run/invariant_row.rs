//! One row of the case `invariants/history-summary`: a summary key against the value its own
//! history gives (`history_invariants.rs`, `wall_invariants.rs`).

use crate::definition::case::Compare;
use crate::definition::check::{CheckResult, ErrorKind, Status};

/// One check row: `computed` against `reference` within `tol` (absolute).
pub fn row(
    id: String,
    title: &str,
    (computed, reference, tol): (f64, f64, f64),
    why: &str,
) -> CheckResult {
    let error = computed - reference;
    let ok = error.abs() <= tol;
    CheckResult {
        id,
        title: title.into(),
        status: if ok { Status::Ok } else { Status::Fail },
        computed: Some(computed),
        reference: Some(reference),
        error: Some(error),
        error_kind: ErrorKind::Absolute,
        compare: Compare::Within,
        tolerance: format!("abs {tol:.1e}"),
        tolerance_reason: why.into(),
        reference_kind: "invariant".into(),
        reference_source: "the run's own history.csv".into(),
        message: if ok {
            String::new()
        } else {
            format!("|{computed:e} - {reference:e}| > {tol:.1e}")
        },
        known_failure: None,
        validation: None,
        not_produced: false,
    }
}
