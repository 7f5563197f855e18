//! One check as every table shows it: the terminal matrix, JUnit's detail and the report
//! (issue 11: one row formatter). The verdict (a declared known failure is FAIL*, one that
//! passes XPASS), the computed value, the reference with its comparison (`<= 1.0e-6`), the
//! error, or for a one-sided check the margin to its bound (positive inside), and the
//! tolerance as written.

use crate::definition::case::Compare;
use crate::definition::check::{CheckResult, ErrorKind};
use crate::definition::verdict::Verdict;

/// The cells of one check's row.
#[derive(Debug, Clone, PartialEq)]
pub struct CheckRow {
    pub verdict: Verdict,
    pub computed: String,
    /// The reference, `<= ` or `>= ` before it for a one-sided check.
    pub reference: String,
    /// `1.2e-3 rel`, `4.0e-9` (absolute), `margin 9.0e-7` (one-sided) or `-`.
    pub error: String,
    pub tolerance: String,
}

impl CheckRow {
    pub fn of(k: &CheckResult) -> CheckRow {
        let cmp = match k.compare {
            Compare::Within => "",
            Compare::AtMost => "<= ",
            Compare::AtLeast => ">= ",
        };
        CheckRow {
            verdict: Verdict::of_check(k),
            computed: num(k.computed),
            reference: format!("{cmp}{}", num(k.reference)),
            error: error_cell(k),
            tolerance: k.tolerance.clone(),
        }
    }
}

/// The error of a two-sided check (relative or absolute); for a one-sided bound the margin
/// to the bound, bound minus computed for `<=` and computed minus bound for `>=` (positive:
/// inside), since an "error" against a bound reads as a miss.
fn error_cell(k: &CheckResult) -> String {
    let margin = match (k.compare, k.computed, k.reference) {
        (Compare::AtMost, Some(c), Some(b)) => Some(b - c),
        (Compare::AtLeast, Some(c), Some(b)) => Some(c - b),
        _ => None,
    };
    if let Some(m) = margin {
        return format!("margin {}", num(Some(m)));
    }
    match (k.error, k.error_kind) {
        (Some(e), ErrorKind::Relative) => format!("{} rel", num(Some(e))),
        (Some(e), ErrorKind::Absolute) => num(Some(e)),
        (None, _) => "-".into(),
    }
}

/// Compact number for the matrix.
pub fn num(x: Option<f64>) -> String {
    match x {
        None => "-".into(),
        Some(v) if v == 0.0 => "0".into(),
        Some(v) if v.is_infinite() => {
            if v > 0.0 {
                "inf".into()
            } else {
                "-inf".into()
            }
        }
        Some(v) => format!("{v:.6e}"),
    }
}

#[cfg(test)]
pub(crate) mod tests {
    //! The row on hand-made checks: FAIL* / XPASS, the margin of one-sided checks (the old
    //! report printed "error 6.8e1 against tolerance 1e-6, OK" for a bound that held).
    use super::*;
    use crate::definition::check::Status;

    pub fn check(status: Status, known: bool, compare: Compare) -> CheckResult {
        CheckResult {
            id: "c".into(),
            title: "t".into(),
            status,
            computed: Some(1.0e-7),
            reference: Some(1.0e-6),
            error: Some(68.0),
            error_kind: ErrorKind::Absolute,
            compare,
            tolerance: "abs 1.0e-6".into(),
            tolerance_reason: "r".into(),
            reference_kind: "acceptance".into(),
            reference_source: "s".into(),
            message: String::new(),
            known_failure: known.then(|| "why".to_string()),
            validation: None,
            not_produced: false,
        }
    }

    #[test]
    fn one_sided_checks_show_the_margin_and_known_failures_their_verdict() {
        let at_most = CheckRow::of(&check(Status::Ok, false, Compare::AtMost));
        assert_eq!(at_most.error, format!("margin {}", num(Some(9.0e-7))));
        assert_eq!(at_most.reference, format!("<= {}", num(Some(1.0e-6))));
        let mut at_least = check(Status::Fail, true, Compare::AtLeast);
        (at_least.computed, at_least.reference) = (Some(3.0), Some(5.0));
        let row = CheckRow::of(&at_least);
        assert_eq!(row.error, format!("margin {}", num(Some(-2.0))));
        assert_eq!(row.verdict.label(), "FAIL*");
        let mut within = check(Status::Ok, true, Compare::Within);
        (within.error, within.error_kind) = (Some(0.1), ErrorKind::Relative);
        let row = CheckRow::of(&within);
        assert_eq!(row.error, format!("{} rel", num(Some(0.1))));
        assert_eq!(row.verdict.label(), "XPASS");
    }

    #[test]
    fn a_check_reads_back_from_results_json() {
        let k = check(Status::Fail, true, Compare::AtMost);
        let mut json = serde_json::to_value(&k).unwrap();
        assert_eq!(json["error_kind"], "absolute");
        json["baseline"] = serde_json::json!({"computed": 1.0}); // added by --baseline
        let back: CheckResult = serde_json::from_value(json).unwrap();
        assert_eq!(back, k);
    }
}
