//! The matrix a verify run makes: a row per case (its checks, what its runs report, its
//! series and the discrimination by its wrong models), the counts by verdict that decide the
//! exit status, and, held beside it in memory, the runs' results the run data is written from.

use std::collections::BTreeMap;

use serde::Serialize;

use crate::definition::case::Category;
use crate::definition::check::CheckResult;
use crate::definition::run_data::JobResult;
use crate::definition::verdict::Tally;

/// One case's outcome.
#[derive(Debug, Clone, Serialize)]
pub struct CaseResult {
    /// The code its checks were evaluated on (`impact`, or another code's name: issue 38).
    pub code: String,
    pub suite: String,
    pub case: String,
    pub id: String,
    pub title: String,
    pub requirement_id: String,
    pub requirement: String,
    pub category: Category,
    pub heavy: bool,
    pub problem: String,
    /// Modelling of each scene run (mesh, element, dt, contact law, ...).
    pub modelling: BTreeMap<String, BTreeMap<String, String>>,
    /// Metrics of each scene and builtin (no wall times).
    pub metrics: BTreeMap<String, BTreeMap<String, f64>>,
    /// Errors of failed jobs.
    pub job_errors: BTreeMap<String, String>,
    /// Series data for convergence plots: series -> metric -> (levels, values).
    pub series: BTreeMap<String, SeriesData>,
    pub plots: Vec<crate::definition::case::PlotSpec>,
    /// The case's `report:` block (absent when it declares none).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub report: Option<crate::definition::case::ReportSpec>,
    pub checks: Vec<CheckResult>,
    /// The case's trivial or wrong models (name -> title) and what each gives for every
    /// evidence check (issue 10; empty when the case declares none).
    #[serde(skip_serializing_if = "BTreeMap::is_empty")]
    pub wrong_models: BTreeMap<String, String>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub discrimination: Vec<crate::run::discriminate::Row>,
    /// The rows of measurement tables the case does not compare, with why (validation cases).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub not_compared: Vec<crate::definition::not_compared::NotComparedRow>,
}

#[derive(Debug, Clone, Serialize)]
pub struct SeriesData {
    pub refine: crate::definition::case::Refine,
    pub levels: Vec<f64>,
    pub metrics: BTreeMap<String, Vec<f64>>,
}

/// Check counts by status (`fail` includes the declared known failures), and apart: the
/// known failures among the FAILs, the unexpected passes (XPASS) among the OKs, and the
/// unexpected total (new FAILs + XPASSes) that decides the exit status.
#[derive(Debug, Clone, Default, Serialize, PartialEq)]
pub struct Counts {
    pub ok: usize,
    pub fail: usize,
    pub skip: usize,
    pub known_fail: usize,
    pub xpass: usize,
    pub unexpected: usize,
    /// Checks another code cannot express or did not produce (absent on `impact`'s counts).
    #[serde(skip_serializing_if = "is_zero")]
    pub not_expressible: usize,
}

fn is_zero(n: &usize) -> bool {
    *n == 0
}

impl Counts {
    pub fn from_tally(t: &Tally) -> Counts {
        Counts {
            ok: t.ok + t.xpass,
            fail: t.fail + t.known_fail,
            skip: t.skip,
            known_fail: t.known_fail,
            xpass: t.xpass,
            unexpected: t.unexpected(),
            not_expressible: t.not_expressible,
        }
    }
}

#[derive(Debug, Clone, Serialize)]
pub struct Matrix {
    /// The counts of `impact`'s rows.
    pub counts: Counts,
    /// `impact`'s rows.
    pub cases: Vec<CaseResult>,
    /// The rows of the other codes the run verified (`impact verify --code NAME`,
    /// `--results-from DIR`), code by code in the order given: the same cases' checks,
    /// references and tolerances evaluated on each code's results.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub codes: Vec<CodeMatrix>,
}

/// Another code's rows of the matrix.
#[derive(Debug, Clone, Serialize)]
pub struct CodeMatrix {
    pub code: String,
    /// What the code is (its adapter's description).
    pub description: String,
    pub counts: Counts,
    pub cases: Vec<CaseResult>,
}

/// What a verify run holds in memory besides the matrix: the job results for the run data.
pub struct Outcome {
    pub matrix: Matrix,
    /// (suite, case) -> scene -> result.
    pub data: BTreeMap<(String, String), BTreeMap<String, JobResult>>,
    /// The same for each other code, by its name.
    pub code_data: Vec<(
        String,
        BTreeMap<(String, String), BTreeMap<String, JobResult>>,
    )>,
}

impl CaseResult {
    /// `NAME:` before the suite on another code's rows (matrix.txt's notes, JUnit), nothing
    /// on impact's.
    pub fn code_prefix(&self) -> String {
        match self.code.as_str() {
            "impact" => String::new(),
            code => format!("{code}:"),
        }
    }
}

impl Matrix {
    pub fn all_checks(&self) -> impl Iterator<Item = (&CaseResult, &CheckResult)> {
        self.cases
            .iter()
            .flat_map(|c| c.checks.iter().map(move |k| (c, k)))
    }
    /// The verdicts of `impact`'s checks (known failures and unexpected passes apart).
    pub fn tally(&self) -> Tally {
        Tally::of(self.all_checks().map(|(_, k)| k))
    }
    /// The verdicts of every code's checks.
    pub fn tally_all(&self) -> Tally {
        let other = self.codes.iter().flat_map(|c| c.cases.iter());
        Tally::of(self.cases.iter().chain(other).flat_map(|c| c.checks.iter()))
    }
    /// Every code's rows, `impact`'s first.
    pub fn all_codes_checks(&self) -> impl Iterator<Item = (&CaseResult, &CheckResult)> {
        let other = self.codes.iter().flat_map(|c| c.cases.iter());
        self.cases
            .iter()
            .chain(other)
            .flat_map(|c| c.checks.iter().map(move |k| (c, k)))
    }
    /// 0 when every failing check of every code is a declared known failure and none passes
    /// unexpectedly, 1 otherwise (issue 10, section 3).
    pub fn exit_status(&self) -> u8 {
        self.tally_all().exit_status()
    }
}
