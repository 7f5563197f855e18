//! What a check's status means for the run (issue 10, section 3): a failure declared as a
//! `known_failure` is expected (XFAIL, shown `FAIL*`); a declared known failure that passes
//! is unexpected (XPASS: the declaration or the evidence behind it is stale), and so is any
//! undeclared failure. `impact verify` and the main job exit 0 when nothing is unexpected,
//! 1 otherwise, 2 on bad input or usage.

use serde::Serialize;

use crate::definition::check::{CheckResult, Status};

/// The verdict of one check against its declaration.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Verdict {
    /// Passed and not declared as a known failure.
    #[serde(rename = "OK")]
    Ok,
    /// Failed as declared (`known_failure`).
    #[serde(rename = "FAIL*")]
    KnownFail,
    /// Failed without a declaration: a new failure.
    #[serde(rename = "FAIL")]
    Fail,
    /// Declared as a known failure but passed: unexpected.
    #[serde(rename = "XPASS")]
    UnexpectedPass,
    /// Not evaluated (with its reason).
    #[serde(rename = "SKIP")]
    Skip,
    /// Not expressible in the code that ran it, or not produced by it (another code's row).
    #[serde(rename = "N/E")]
    NotExpressible,
}

impl Verdict {
    pub fn of(status: Status, known_failure: bool) -> Verdict {
        match (status, known_failure) {
            (Status::Ok, false) => Verdict::Ok,
            (Status::Ok, true) => Verdict::UnexpectedPass,
            (Status::Fail, true) => Verdict::KnownFail,
            (Status::Fail, false) => Verdict::Fail,
            (Status::Skip, _) => Verdict::Skip,
            (Status::NotExpressible, _) => Verdict::NotExpressible,
        }
    }
    pub fn of_check(k: &CheckResult) -> Verdict {
        Verdict::of(k.status, k.known_failure.is_some())
    }
    /// The label in the matrix: OK, FAIL* (known), FAIL, XPASS, SKIP.
    pub fn label(self) -> &'static str {
        match self {
            Verdict::Ok => "OK",
            Verdict::KnownFail => "FAIL*",
            Verdict::Fail => "FAIL",
            Verdict::UnexpectedPass => "XPASS",
            Verdict::Skip => "SKIP",
            Verdict::NotExpressible => "N/E",
        }
    }
    /// A new failure or an unexpected pass: what makes the run exit 1.
    pub fn is_unexpected(self) -> bool {
        matches!(self, Verdict::Fail | Verdict::UnexpectedPass)
    }
}

/// Counts of the verdicts of a set of checks.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
pub struct Tally {
    pub ok: usize,
    pub known_fail: usize,
    pub fail: usize,
    pub xpass: usize,
    pub skip: usize,
    /// Not expressible in (or not produced by) another code; 0 on `impact`'s rows.
    #[serde(skip_serializing_if = "is_zero")]
    pub not_expressible: usize,
}

fn is_zero(n: &usize) -> bool {
    *n == 0
}

impl Tally {
    pub fn add(&mut self, v: Verdict) {
        match v {
            Verdict::Ok => self.ok += 1,
            Verdict::KnownFail => self.known_fail += 1,
            Verdict::Fail => self.fail += 1,
            Verdict::UnexpectedPass => self.xpass += 1,
            Verdict::Skip => self.skip += 1,
            Verdict::NotExpressible => self.not_expressible += 1,
        }
    }
    pub fn of<'a>(checks: impl IntoIterator<Item = &'a CheckResult>) -> Tally {
        let mut t = Tally::default();
        for k in checks {
            t.add(Verdict::of_check(k));
        }
        t
    }
    /// New failures plus unexpected passes.
    pub fn unexpected(&self) -> usize {
        self.fail + self.xpass
    }
    /// The exit status of a run that got this far (input was good): 0 or 1.
    pub fn exit_status(&self) -> u8 {
        u8::from(self.unexpected() > 0)
    }
    /// The verdicts that occur, OK always first: "4 OK", "3 OK, 1 FAIL*, 1 FAIL", "0 OK, 2 SKIP".
    pub fn short(&self) -> String {
        let mut parts = vec![format!("{} OK", self.ok)];
        for (n, v) in [
            (self.known_fail, Verdict::KnownFail),
            (self.fail, Verdict::Fail),
            (self.xpass, Verdict::UnexpectedPass),
            (self.skip, Verdict::Skip),
            (self.not_expressible, Verdict::NotExpressible),
        ] {
            if n > 0 {
                parts.push(format!("{n} {}", v.label()));
            }
        }
        parts.join(", ")
    }
    /// One line: "170 OK, 6 known FAIL, 0 unexpected FAIL, 0 XPASS, 0 SKIP" (and ", 4 not
    /// expressible" when another code's rows have any).
    pub fn line(&self) -> String {
        let ne = match self.not_expressible {
            0 => String::new(),
            n => format!(", {n} not expressible"),
        };
        format!(
            "{} OK, {} known FAIL, {} unexpected FAIL, {} XPASS, {} SKIP{ne}",
            self.ok, self.known_fail, self.fail, self.xpass, self.skip
        )
    }
    /// All the checks counted.
    pub fn total(&self) -> usize {
        self.ok + self.known_fail + self.fail + self.xpass + self.skip + self.not_expressible
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_new_failures_and_unexpected_passes_fail_the_run() {
        assert_eq!(Verdict::of(Status::Ok, false), Verdict::Ok);
        assert_eq!(Verdict::of(Status::Ok, true), Verdict::UnexpectedPass);
        assert_eq!(Verdict::of(Status::Fail, true), Verdict::KnownFail);
        assert_eq!(Verdict::of(Status::Fail, false), Verdict::Fail);
        assert_eq!(Verdict::of(Status::Skip, true), Verdict::Skip);
        let mut t = Tally::default();
        for v in [
            Verdict::Ok,
            Verdict::KnownFail,
            Verdict::KnownFail,
            Verdict::Skip,
        ] {
            t.add(v);
        }
        assert_eq!(t.exit_status(), 0, "known failures alone: exit 0");
        assert_eq!(t.short(), "1 OK, 2 FAIL*, 1 SKIP");
        assert_eq!(Tally::default().short(), "0 OK");
        assert_eq!(
            t.line(),
            "1 OK, 2 known FAIL, 0 unexpected FAIL, 0 XPASS, 1 SKIP"
        );
        let mut x = t;
        x.add(Verdict::UnexpectedPass);
        assert_eq!(x.exit_status(), 1, "XPASS is a failure");
        let mut f = t;
        f.add(Verdict::Fail);
        assert_eq!(f.exit_status(), 1, "a new failure");
    }
}
