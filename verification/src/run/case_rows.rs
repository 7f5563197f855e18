//! The matrix's rows: a case's checks evaluated on its runs (SKIP when the case is skipped,
//! FAIL when its jobs could not be made) with its series, the discrimination by its wrong
//! models and what its runs report; a broken case's one FAIL row; the row of the history
//! invariants over every impact run; and the matrix assembled from them, whoever ran the jobs.

use std::collections::{BTreeMap, BTreeSet};

use crate::codes::Code;
use crate::definition::broken::Broken;
use crate::definition::case::{Case, Category};
use crate::definition::check::{self, CheckResult, Context, Status};
use crate::definition::not_compared::NotComparedRow;
use crate::definition::repo::Repo;
use crate::definition::run_data::JobResult;
use crate::run::history_invariants;
use crate::run::matrix::{CaseResult, Counts, Matrix, Outcome, SeriesData};
use crate::run::plan::{check_matches, Plan};

/// The matrix from the plan's job results (`slots[i]`: the result of `plan.jobs[i]`; None:
/// not run): the checks evaluated case by case, whoever ran the jobs.
pub fn assemble(
    repo: &Repo,
    plan: &Plan,
    slots: Vec<Option<JobResult>>,
    filter: &Option<String>,
) -> Outcome {
    let none = plan.cases.iter().map(|_| None).collect();
    assemble_judged(repo, plan, slots, filter, none)
}

/// [`assemble`], taking the rows of the cases already judged (`judged[c]` for
/// `plan.cases[c]`) as they are.
pub(super) fn assemble_judged(
    repo: &Repo,
    plan: &Plan,
    slots: Vec<Option<JobResult>>,
    filter: &Option<String>,
    judged: Vec<Option<CaseResult>>,
) -> Outcome {
    let mut matrix = Matrix {
        counts: Counts::default(),
        cases: Vec::new(),
        codes: Vec::new(),
    };
    let mut data = BTreeMap::new();
    for ((case, jobs_of), row) in plan.cases.iter().zip(&plan.case_jobs).zip(judged) {
        let (results, setup_error) = case_runs(jobs_of, |i| slots[i].clone());
        let row = row
            .unwrap_or_else(|| case_result(repo, &plan.code, case, &results, setup_error, filter));
        matrix.cases.push(row);
        data.insert((case.suite.clone(), case.name.clone()), results);
    }
    matrix
        .cases
        .extend(plan.broken.iter().map(|b| broken_row(b)));
    matrix
        .cases
        .sort_by(|a, b| (&a.suite, &a.case).cmp(&(&b.suite, &b.case)));
    // The matrix's own invariant on impact's runs above, after the cases of the selection.
    if plan.code.is_impact() {
        matrix.cases.extend(invariant_row(plan, &slots, filter));
    }
    matrix.counts = Counts::from_tally(&matrix.tally());
    Outcome {
        matrix,
        data,
        code_data: Vec::new(),
    }
}

/// The row of [`history_invariants`] from the plan's impact runs, each named by the first
/// case and scene that uses it; `None` when no check is left.
fn invariant_row(
    plan: &Plan,
    slots: &[Option<JobResult>],
    filter: &Option<String>,
) -> Option<CaseResult> {
    let mut names = BTreeMap::new();
    for (case, jobs_of) in plan.cases.iter().zip(&plan.case_jobs) {
        for (scene, i) in jobs_of {
            if let Ok(i) = i {
                names
                    .entry(*i)
                    .or_insert_with(|| format!("{}/{}/{scene}", case.suite, case.name));
            }
        }
    }
    let runs = names.iter().filter_map(|(i, name)| match &slots[*i] {
        Some(Ok(run)) => Some((name.clone(), run.as_ref())),
        _ => None,
    });
    let checks = history_invariants::case_checks(runs, filter);
    if checks.is_empty() {
        return None;
    }
    Some(CaseResult {
        code: "impact".into(),
        suite: history_invariants::SUITE.into(),
        case: history_invariants::CASE.into(),
        id: history_invariants::CASE.into(),
        title: history_invariants::TITLE.into(),
        requirement_id: history_invariants::REQUIREMENT.0.into(),
        requirement: history_invariants::REQUIREMENT.1.into(),
        category: Category::CodeVerification,
        heavy: false,
        problem: history_invariants::PROBLEM.into(),
        modelling: BTreeMap::new(),
        metrics: BTreeMap::new(),
        job_errors: BTreeMap::new(),
        series: BTreeMap::new(),
        plots: Vec::new(),
        report: None,
        checks,
        wrong_models: BTreeMap::new(),
        discrimination: Vec::new(),
        not_compared: Vec::new(),
    })
}

/// One case's runs by scene name (`result(i)`: job i's result, None when it did not run),
/// and why its jobs could not be made, if so.
pub(super) fn case_runs(
    jobs_of: &BTreeMap<String, Result<usize, String>>,
    result: impl Fn(usize) -> Option<JobResult>,
) -> (BTreeMap<String, JobResult>, Option<String>) {
    let mut results = BTreeMap::new();
    let mut setup_error = None;
    for (name, idx) in jobs_of {
        match idx {
            Ok(i) => {
                results.insert(
                    name.clone(),
                    result(*i).unwrap_or_else(|| Err("not run".into())),
                );
            }
            Err(e) => setup_error = Some(e.clone()),
        }
    }
    (results, setup_error)
}

/// A broken case's row: one FAIL check `case-loads` carrying why (file:line:col).
fn broken_row(b: &Broken) -> CaseResult {
    let message = b.messages.join("; ");
    let check = CheckResult {
        id: "case-loads".into(),
        title: "the case loads and lints clean".into(),
        status: Status::Fail,
        computed: None,
        reference: None,
        error: None,
        error_kind: crate::definition::check::ErrorKind::Absolute,
        compare: crate::definition::case::Compare::Within,
        tolerance: "-".into(),
        tolerance_reason: "a case that does not load cannot be checked".into(),
        reference_kind: "invariant".into(),
        reference_source: "impact lint".into(),
        message: message.clone(),
        known_failure: None,
        validation: None,
        not_produced: false,
    };
    let (id, title, requirement_id, requirement, category, heavy) = match &b.parsed {
        Some(c) => (
            c.id().to_string(),
            c.file.title.clone(),
            c.file.requirement.id.value.clone(),
            c.file.requirement.text.value.clone(),
            c.file.category,
            c.file.heavy,
        ),
        None => (
            format!("{}/{}", b.suite, b.case),
            "(case.yaml does not load)".into(),
            "-".into(),
            "-".into(),
            Category::Unknown,
            false,
        ),
    };
    CaseResult {
        code: "impact".into(),
        suite: b.suite.clone(),
        case: b.case.clone(),
        id,
        title,
        requirement_id,
        requirement,
        category,
        heavy,
        problem: String::new(),
        modelling: BTreeMap::new(),
        metrics: BTreeMap::new(),
        job_errors: BTreeMap::from([("(case.yaml)".to_string(), message)]),
        series: BTreeMap::new(),
        plots: Vec::new(),
        report: None,
        checks: vec![check],
        wrong_models: BTreeMap::new(),
        discrimination: Vec::new(),
        not_compared: Vec::new(),
    }
}

/// One case's row of the matrix: its checks evaluated on its runs' `results` (all FAIL with
/// `setup_error` when its jobs could not be made, SKIP when the case is skipped), the
/// discrimination by its wrong models, its series and what its runs report.
pub(super) fn case_result(
    repo: &Repo,
    code: &Code,
    case: &Case,
    results: &BTreeMap<String, JobResult>,
    setup_error: Option<String>,
    filter: &Option<String>,
) -> CaseResult {
    let series: BTreeMap<String, crate::definition::case::SeriesSpec> = case
        .file
        .series
        .iter()
        .map(|(k, v)| (k.clone(), v.value.clone()))
        .collect();
    let ctx = Context {
        results,
        series: &series,
        root: &repo.root,
        default_scene: case.default_scene(),
    };
    let case_skip = case.file.skip.as_ref().filter(|s| s.value.is_skip());
    let evaluated: Vec<&crate::definition::case::CheckFile> = case
        .file
        .checks
        .iter()
        .map(|k| &k.value)
        .filter(|k| check_matches(case, &k.id, filter))
        .collect();
    let expected = code.expected();
    let mut checks = Vec::new();
    let mut series_metrics: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for k in &evaluated {
        if let Some(q) = k.measure.value.series_quantity() {
            series_metrics
                .entry(q.series.clone())
                .or_default()
                .insert(q.metric.clone());
        }
        let mut r = check::evaluate(k, &ctx);
        if let Some(skip) = case_skip {
            r.status = Status::Skip;
            r.message = format!("case skipped: {}", skip.value.reason().unwrap_or(""));
            r.computed = None;
            r.error = None;
        } else if let Some(e) = &setup_error {
            r.status = Status::Fail;
            r.message = e.clone();
        } else if !code.is_impact() {
            crate::run::other_code::judge(&mut r, k, case, results, code, expected);
        }
        checks.push(r);
    }
    // The series values a `plots:` entry draws (a metric of several series).
    for p in &case.file.plots {
        if let Some(metric) = &p.metric {
            for name in &p.series {
                series_metrics
                    .entry(name.clone())
                    .or_default()
                    .insert(metric.clone());
            }
        }
    }
    let discrimination = if case_skip.is_none() && setup_error.is_none() && code.is_impact() {
        crate::run::discriminate::rows(case, &evaluated, &ctx)
    } else {
        Vec::new()
    };
    let (modelling, metrics, mut job_errors) = run_reports(results);
    if let Some(e) = setup_error {
        job_errors.insert("(setup)".into(), e);
    }
    CaseResult {
        code: code.name(),
        suite: case.suite.clone(),
        case: case.name.clone(),
        id: case.id().to_string(),
        title: case.file.title.clone(),
        requirement_id: case.file.requirement.id.value.clone(),
        requirement: case.file.requirement.text.value.clone(),
        category: case.file.category,
        heavy: case.file.heavy,
        problem: case.file.problem.clone().unwrap_or_default(),
        modelling,
        metrics,
        job_errors,
        series: series_data(series_metrics, &series, &ctx),
        plots: case.file.plots.clone(),
        report: case.file.report.clone(),
        checks,
        wrong_models: crate::run::discriminate::titles(case),
        discrimination,
        not_compared: not_compared(repo, case),
    }
}

/// The measurements the case declares it does not compare (the lint has checked that each
/// entry's rows exist: a broken case never gets here).
fn not_compared(repo: &Repo, case: &Case) -> Vec<NotComparedRow> {
    case.file
        .not_compared
        .iter()
        .flat_map(|e| {
            crate::definition::not_compared::rows(&repo.root, &e.value).unwrap_or_default()
        })
        .collect()
}

/// The values of each series' metrics that the checks use, with the series' levels.
fn series_data(
    series_metrics: BTreeMap<String, BTreeSet<String>>,
    series: &BTreeMap<String, crate::definition::case::SeriesSpec>,
    ctx: &Context,
) -> BTreeMap<String, SeriesData> {
    let mut series_data = BTreeMap::new();
    for (name, metrics) in series_metrics {
        let Some(spec) = series.get(&name) else {
            continue;
        };
        let mut m = BTreeMap::new();
        for metric in metrics {
            if let Ok((_, values, _)) = check::series_values(&name, &metric, ctx) {
                m.insert(metric, values);
            }
        }
        series_data.insert(
            name,
            SeriesData {
                refine: spec.refine,
                levels: spec.levels.clone(),
                metrics: m,
            },
        );
    }
    series_data
}

type RunReports = (
    BTreeMap<String, BTreeMap<String, String>>,
    BTreeMap<String, BTreeMap<String, f64>>,
    BTreeMap<String, String>,
);

/// Per run: its modelling lines (when it has any), its metrics, or its error.
fn run_reports(results: &BTreeMap<String, JobResult>) -> RunReports {
    let mut modelling = BTreeMap::new();
    let mut metrics = BTreeMap::new();
    let mut job_errors = BTreeMap::new();
    for (name, r) in results {
        match r {
            Ok(d) => {
                if !d.info.is_empty() {
                    modelling.insert(name.clone(), d.info.clone());
                }
                metrics.insert(name.clone(), d.metrics.clone());
            }
            Err(e) => {
                job_errors.insert(name.clone(), e.clone());
            }
        }
    }
    (modelling, metrics, job_errors)
}
