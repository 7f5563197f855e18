//! `impact verify`: select cases, run their jobs in parallel (each job is single-threaded
//! and independent, results are keyed by job, so the outcome does not depend on the thread
//! count or the scheduling), evaluate the checks, print the matrix, write results.json,
//! JUnit XML and the run data the report reads.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;
use std::sync::OnceLock;

use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;
use serde::Serialize;

use crate::definition::broken::Broken;
use crate::definition::case::{Case, Category};
use crate::definition::check::{self, CheckResult, Context, Status};
use crate::definition::verdict::{Tally, Verdict};
use crate::run::history_invariants;
use crate::run::jobs::{self, Job, JobResult};

pub use crate::definition::check_row::num;
pub use crate::definition::repo::Repo;

#[derive(Debug, Clone)]
pub struct Options {
    /// Suites, case ids or `suite/case` names; empty = all.
    pub selectors: Vec<String>,
    /// Substring of `suite/case/check`.
    pub filter: Option<String>,
    pub jobs: usize,
    pub include_heavy: bool,
    pub progress: bool,
}

/// One case's outcome.
#[derive(Debug, Clone, Serialize)]
pub struct CaseResult {
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
        }
    }
}

#[derive(Debug, Clone, Serialize)]
pub struct Matrix {
    pub counts: Counts,
    pub cases: Vec<CaseResult>,
}

/// What a verify run holds in memory besides the matrix: the job results for the run data.
pub struct Outcome {
    pub matrix: Matrix,
    /// (suite, case) -> scene -> result.
    pub data: BTreeMap<(String, String), BTreeMap<String, JobResult>>,
}

impl Matrix {
    pub fn all_checks(&self) -> impl Iterator<Item = (&CaseResult, &CheckResult)> {
        self.cases
            .iter()
            .flat_map(|c| c.checks.iter().map(move |k| (c, k)))
    }
    /// The verdicts of all checks (known failures and unexpected passes apart).
    pub fn tally(&self) -> Tally {
        Tally::of(self.all_checks().map(|(_, k)| k))
    }
    /// 0 when every failing check is a declared known failure and none passes unexpectedly,
    /// 1 otherwise (issue 10, section 3).
    pub fn exit_status(&self) -> u8 {
        self.tally().exit_status()
    }
}

fn selected(case: &Case, opts: &Options) -> bool {
    if case.file.heavy && !opts.include_heavy {
        return false;
    }
    if opts.selectors.is_empty() {
        return true;
    }
    let full = format!("{}/{}", case.suite, case.name);
    opts.selectors
        .iter()
        .any(|s| s == &case.suite || s == case.id() || s == &case.name || *s == full)
}

/// A broken case is selected as a case would be (its suite, name or id; heavy when it says so).
fn broken_selected(b: &Broken, opts: &Options) -> bool {
    if let Some(case) = &b.parsed {
        return selected(case, opts);
    }
    let full = format!("{}/{}", b.suite, b.case);
    opts.selectors.is_empty()
        || opts
            .selectors
            .iter()
            .any(|s| s == &b.suite || s == &b.case || *s == full)
}

fn check_matches(case: &Case, check_id: &str, filter: &Option<String>) -> bool {
    match filter {
        None => true,
        Some(f) => format!("{}/{}/{}", case.suite, case.name, check_id).contains(f.as_str()),
    }
}

/// Runs the selected cases, announcing each as it finishes with its checks' verdicts, then
/// the total. Errors: cases that do not load or do not lint.
pub fn verify(repo: &Repo, opts: &Options) -> Result<Outcome, Vec<String>> {
    let started = std::time::Instant::now();
    let loaded = load(repo)?;
    let plan = plan(&loaded, opts)?;
    let all: Vec<usize> = (0..plan.jobs.len()).collect();
    let judge = Judge {
        repo,
        filter: &opts.filter,
    };
    let (finished, judged) =
        run_jobs(&plan, &all, opts.jobs, opts.progress, Some(&judge)).map_err(|e| vec![e])?;
    let mut slots: Vec<Option<JobResult>> = vec![None; plan.jobs.len()];
    for (i, r) in finished {
        slots[i] = Some(r);
    }
    let outcome = assemble_judged(repo, &plan, slots, &opts.filter, judged);
    eprintln!(
        "{}",
        total_line(&outcome.matrix, started.elapsed().as_secs_f64())
    );
    Ok(outcome)
}

/// The one-line total: `verify: 2 cases, 5 checks: 4 OK, 1 FAIL* (exit 0, 3.2 s)`.
pub fn total_line(m: &Matrix, seconds: f64) -> String {
    let t = m.tally();
    let n_checks = t.ok + t.known_fail + t.fail + t.xpass + t.skip;
    format!(
        "verify: {} case{}, {n_checks} check{}: {} (exit {}, {seconds:.1} s)",
        m.cases.len(),
        if m.cases.len() == 1 { "" } else { "s" },
        if n_checks == 1 { "" } else { "s" },
        t.short(),
        t.exit_status()
    )
}

/// What judges a case as soon as its runs are done: where its references live and which of
/// its checks to evaluate.
pub struct Judge<'a> {
    pub repo: &'a Repo,
    pub filter: &'a Option<String>,
}

/// The repository's cases: those that load and lint clean, and the broken ones (each will be
/// a FAIL row). Errors: lint findings that are no single case's.
pub fn load(repo: &Repo) -> Result<Loaded, Vec<String>> {
    let (cases, errors) = crate::definition::case::load_cases(&repo.cases_dir());
    let findings = crate::definition::lint::lint(repo, &cases);
    let (cases, broken, fatal) = crate::definition::broken::split(cases, errors, findings);
    if !fatal.is_empty() {
        return Err(fatal);
    }
    Ok(Loaded { cases, broken })
}

/// What [`load`] found.
pub struct Loaded {
    pub cases: Vec<Case>,
    pub broken: Vec<Broken>,
}

/// The selected cases and their jobs, deduplicated by content (what a run or a shard of it
/// executes; `crate::run::shard` shares `jobs` out by cost).
pub struct Plan<'a> {
    pub cases: Vec<&'a Case>,
    /// The selected broken cases (no jobs; a FAIL row each).
    pub broken: Vec<&'a Broken>,
    pub jobs: Vec<Job>,
    /// Per case: scene name -> index into `jobs` (or why its jobs could not be made).
    case_jobs: Vec<BTreeMap<String, Result<usize, String>>>,
}

/// Selects the cases of `opts` and makes their jobs. Errors: no case matches.
pub fn plan<'a>(loaded: &'a Loaded, opts: &Options) -> Result<Plan<'a>, Vec<String>> {
    let broken: Vec<&Broken> = loaded
        .broken
        .iter()
        .filter(|b| broken_selected(b, opts))
        .collect();
    let chosen: Vec<&Case> = loaded
        .cases
        .iter()
        .filter(|c| selected(c, opts))
        .filter(|c| {
            c.file
                .checks
                .iter()
                .any(|k| check_matches(c, &k.value.id, &opts.filter))
        })
        .collect();
    if chosen.is_empty() && broken.is_empty() {
        return Err(vec![format!(
            "no case matches {:?}{}",
            opts.selectors,
            opts.filter
                .as_ref()
                .map(|f| format!(" with filter {f:?}"))
                .unwrap_or_default()
        )]);
    }

    // Jobs, deduplicated by content.
    let mut unique: Vec<Job> = Vec::new();
    let mut index_of: BTreeMap<String, usize> = BTreeMap::new();
    let mut case_jobs: Vec<BTreeMap<String, Result<usize, String>>> = Vec::new();
    for case in &chosen {
        let case_skipped = case.file.skip.as_ref().is_some_and(|s| s.value.is_skip());
        let mut map = BTreeMap::new();
        if !case_skipped {
            let all = jobs::case_jobs(case).and_then(|mut js| {
                js.extend(crate::run::discriminate::jobs(
                    case,
                    &js,
                    opts.include_heavy,
                )?);
                Ok(js)
            });
            match all {
                Ok(js) => {
                    for (name, job) in js {
                        let key = job.key();
                        let i = *index_of.entry(key).or_insert_with(|| {
                            unique.push(job);
                            unique.len() - 1
                        });
                        map.insert(name, Ok(i));
                    }
                }
                Err(e) => {
                    map.insert(String::new(), Err(e));
                }
            }
        }
        case_jobs.push(map);
    }
    Ok(Plan {
        cases: chosen,
        broken,
        jobs: unique,
        case_jobs,
    })
}

/// Runs the jobs `which` on `threads` threads, largest first; each result is returned with
/// its index, whatever the thread that ran it. Each case whose runs are all among `which`
/// is announced as it finishes (without verdicts: a shard's cases are judged at the merge).
pub fn execute(
    plan: &Plan,
    which: &[usize],
    threads: usize,
    progress: bool,
) -> Result<Vec<(usize, JobResult)>, String> {
    run_jobs(plan, which, threads, progress, None).map(|(finished, _)| finished)
}

/// [`execute`], and with a `judge` each case's row is made as soon as its last run has
/// finished, announced with its verdicts and returned (per case of the plan) for
/// [`assemble_judged`].
fn run_jobs(
    plan: &Plan,
    which: &[usize],
    threads: usize,
    progress: bool,
    judge: Option<&Judge>,
) -> Result<(Vec<(usize, JobResult)>, Vec<Option<CaseResult>>), String> {
    let jobs = &plan.jobs;
    let mut order = which.to_vec();
    order.sort_by(|&a, &b| jobs[b].cost().total_cmp(&jobs[a].cost()).then(a.cmp(&b)));
    let bar = progress.then(|| {
        let b = ProgressBar::new(order.len() as u64);
        b.set_style(
            ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {pos}/{len} runs {msg}")
                .unwrap_or_else(|_| ProgressStyle::default_bar())
                .progress_chars("=> "),
        );
        b
    });
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads.max(1))
        .build()
        .map_err(|e| format!("cannot start {threads} threads: {e}"))?;
    let mine: BTreeSet<usize> = which.iter().copied().collect();
    let case_progress = crate::run::case_progress::CaseProgress::new(
        plan.cases
            .iter()
            .zip(&plan.case_jobs)
            .map(|(c, jobs_of)| {
                let runs = jobs_of.values().filter_map(|j| j.as_ref().ok().copied());
                let runs = runs.filter(|j| mine.contains(j));
                (format!("{}/{}", c.suite, c.name), runs.collect())
            })
            .collect(),
        jobs.len(),
    );
    let slots: Vec<OnceLock<JobResult>> = jobs.iter().map(|_| OnceLock::new()).collect();
    let judged: Vec<OnceLock<CaseResult>> = plan.cases.iter().map(|_| OnceLock::new()).collect();
    // A finished case: judged (its row kept) and announced above the bar.
    let announce = |c: usize| {
        let row = judge.map(|j| {
            let (results, setup_error) = case_runs(&plan.case_jobs[c], |i| slots[i].get().cloned());
            case_result(j.repo, plan.cases[c], &results, setup_error, j.filter)
        });
        let line = case_progress.line(c, row.as_ref().map(|r| Tally::of(&r.checks)).as_ref());
        if let Some(r) = row {
            let _ = judged[c].set(r);
        }
        match &bar {
            Some(b) => b.println(line),
            None => eprintln!("{line}"),
        }
    };
    case_progress.idle().into_iter().for_each(announce);
    pool.install(|| {
        order.par_iter().for_each(|&i| {
            let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| jobs[i].run()))
                .unwrap_or_else(|p| Err(format!("the run panicked: {}", panic_text(&*p))));
            let _ = slots[i].set(r);
            case_progress.run_done(i).into_iter().for_each(announce);
            if let Some(b) = &bar {
                b.inc(1);
            }
        })
    });
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let finished = slots
        .into_iter()
        .enumerate()
        .filter_map(|(i, s)| s.into_inner().map(|r| (i, r)))
        .collect();
    Ok((
        finished,
        judged.into_iter().map(OnceLock::into_inner).collect(),
    ))
}

/// The text of a panic's payload (a `&str` or `String`; otherwise "no message").
fn panic_text(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "no message".into())
}

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
fn assemble_judged(
    repo: &Repo,
    plan: &Plan,
    slots: Vec<Option<JobResult>>,
    filter: &Option<String>,
    judged: Vec<Option<CaseResult>>,
) -> Outcome {
    let mut matrix = Matrix {
        counts: Counts::default(),
        cases: Vec::new(),
    };
    let mut data = BTreeMap::new();
    for ((case, jobs_of), row) in plan.cases.iter().zip(&plan.case_jobs).zip(judged) {
        let (results, setup_error) = case_runs(jobs_of, |i| slots[i].clone());
        let row = row.unwrap_or_else(|| case_result(repo, case, &results, setup_error, filter));
        matrix.cases.push(row);
        data.insert((case.suite.clone(), case.name.clone()), results);
    }
    matrix
        .cases
        .extend(plan.broken.iter().map(|b| broken_row(b)));
    matrix
        .cases
        .sort_by(|a, b| (&a.suite, &a.case).cmp(&(&b.suite, &b.case)));
    // The matrix's own invariant on the runs above, after the cases of the selection.
    matrix.cases.extend(invariant_row(plan, &slots, filter));
    matrix.counts = Counts::from_tally(&matrix.tally());
    Outcome { matrix, data }
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
    })
}

/// One case's runs by scene name (`result(i)`: job i's result, None when it did not run),
/// and why its jobs could not be made, if so.
fn case_runs(
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
    }
}

/// One case's row of the matrix: its checks evaluated on its runs' `results` (all FAIL with
/// `setup_error` when its jobs could not be made, SKIP when the case is skipped), the
/// discrimination by its wrong models, its series and what its runs report.
fn case_result(
    repo: &Repo,
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
    let default_scene = if case.file.scenes.len() == 1 {
        case.file.scenes.keys().next().map(|s| s.as_str())
    } else {
        None
    };
    let ctx = Context {
        results,
        series: &series,
        root: &repo.root,
        default_scene,
    };
    let case_skip = case.file.skip.as_ref().filter(|s| s.value.is_skip());
    let evaluated: Vec<&crate::definition::case::CheckFile> = case
        .file
        .checks
        .iter()
        .map(|k| &k.value)
        .filter(|k| check_matches(case, &k.id, filter))
        .collect();
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
    let discrimination = if case_skip.is_none() && setup_error.is_none() {
        crate::run::discriminate::rows(case, &evaluated, &ctx)
    } else {
        Vec::new()
    };
    let (modelling, metrics, mut job_errors) = run_reports(results);
    if let Some(e) = setup_error {
        job_errors.insert("(setup)".into(), e);
    }
    CaseResult {
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
    }
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

/// The matrix as text: one row per check.
pub fn matrix_text(m: &Matrix) -> String {
    let mut rows = vec![[
        "suite".to_string(),
        "case".into(),
        "check".into(),
        "status".into(),
        "computed".into(),
        "reference".into(),
        "error (one-sided: margin)".into(),
        "tolerance".into(),
    ]];
    for (c, k) in m.all_checks() {
        let row = crate::definition::check_row::CheckRow::of(k);
        rows.push([
            c.suite.clone(),
            c.case.clone(),
            k.id.clone(),
            row.verdict.label().to_string(),
            row.computed,
            row.reference,
            row.error,
            row.tolerance,
        ]);
    }
    let mut widths = [0usize; 8];
    for r in &rows {
        for (w, s) in widths.iter_mut().zip(r) {
            *w = (*w).max(s.chars().count());
        }
    }
    let mut out = String::new();
    for r in &rows {
        let line: Vec<String> = r
            .iter()
            .zip(widths)
            .map(|(s, w)| format!("{s:<w$}"))
            .collect();
        out.push_str(line.join("  ").trim_end());
        out.push('\n');
    }
    out
}

/// Per-suite counts (known failures and unexpected passes apart), the total line, and the
/// list of non-OK checks with their messages.
pub fn summary_text(m: &Matrix) -> String {
    let mut per: BTreeMap<&str, Tally> = BTreeMap::new();
    for (c, k) in m.all_checks() {
        per.entry(&c.suite).or_default().add(Verdict::of_check(k));
    }
    let row = |name: &str, t: &Tally| {
        format!(
            "{name:<20} {:>4} {:>6} {:>5} {:>6} {:>5}\n",
            t.ok, t.known_fail, t.fail, t.xpass, t.skip
        )
    };
    let mut out = String::from("\nsuite                 OK  FAIL*  FAIL  XPASS  SKIP\n");
    for (s, t) in &per {
        out.push_str(&row(s, t));
    }
    let total = m.tally();
    out.push_str(&row("total", &total));
    out.push_str(&format!(
        "matrix: {} ({} unexpected: {})\n",
        total.line(),
        total.unexpected(),
        if total.unexpected() == 0 {
            "exit 0"
        } else {
            "exit 1"
        }
    ));
    let notes: Vec<String> = m
        .all_checks()
        .filter(|(_, k)| Verdict::of_check(k) != Verdict::Ok)
        .map(|(c, k)| {
            let v = Verdict::of_check(k);
            let known = k
                .known_failure
                .as_ref()
                .map(|r| format!(" [known: {r}]"))
                .unwrap_or_default();
            let message = if v == Verdict::UnexpectedPass {
                "passes, but is declared a known failure: remove the declaration or explain".into()
            } else {
                k.message.clone()
            };
            format!(
                "  {} {}/{}/{}: {message}{known}",
                v.label(),
                c.suite,
                c.case,
                k.id
            )
        })
        .collect();
    if !notes.is_empty() {
        out.push_str("\nnot OK:\n");
        out.push_str(&notes.join("\n"));
        out.push('\n');
    }
    out
}

/// JUnit XML: one test suite per case, one test case per check.
pub fn junit_xml(m: &Matrix) -> Result<String, String> {
    use quick_junit::{NonSuccessKind, Report, TestCase, TestCaseStatus, TestSuite};
    let mut report = Report::new("impact-verify");
    for c in &m.cases {
        let mut suite = TestSuite::new(format!("{}/{}", c.suite, c.case));
        for k in &c.checks {
            let row = crate::definition::check_row::CheckRow::of(k);
            let detail = format!(
                "computed {} reference {} ({}) error {} tolerance {} ({})",
                row.computed,
                row.reference,
                k.reference_kind,
                row.error,
                k.tolerance,
                k.tolerance_reason
            );
            let status = match k.status {
                Status::Ok if k.known_failure.is_some() => {
                    let mut s = TestCaseStatus::non_success(NonSuccessKind::Failure);
                    s.set_message("XPASS: passes, but is declared a known failure");
                    s.set_description(detail.clone());
                    s
                }
                Status::Ok => TestCaseStatus::success(),
                Status::Fail => {
                    let mut s = TestCaseStatus::non_success(NonSuccessKind::Failure);
                    s.set_message(k.message.clone());
                    s.set_description(detail.clone());
                    s
                }
                Status::Skip => {
                    let mut s = TestCaseStatus::skipped();
                    s.set_message(k.message.clone());
                    s
                }
            };
            let mut tc = TestCase::new(k.id.clone(), status);
            tc.set_classname(format!("{}.{}", c.suite, c.case));
            tc.set_system_out(detail);
            suite.add_test_case(tc);
        }
        report.add_test_suite(suite);
    }
    report.to_string().map_err(|e| e.to_string())
}

/// Writes results.json, junit.xml, matrix.txt and runs/<suite>/<case>/<scene>/ into `out`.
pub fn write_outputs(outcome: &Outcome, out: &Path) -> std::io::Result<()> {
    std::fs::create_dir_all(out)?;
    let json = serde_json::to_string_pretty(&outcome.matrix).map_err(std::io::Error::other)?;
    std::fs::write(out.join("results.json"), json + "\n")?;
    std::fs::write(
        out.join("junit.xml"),
        junit_xml(&outcome.matrix).map_err(std::io::Error::other)?,
    )?;
    std::fs::write(
        out.join("matrix.txt"),
        matrix_text(&outcome.matrix) + &summary_text(&outcome.matrix),
    )?;
    let runs = out.join("runs");
    if runs.exists() {
        std::fs::remove_dir_all(&runs)?;
    }
    for ((suite, case), results) in &outcome.data {
        for (scene, r) in results {
            let Ok(d) = r else { continue };
            let dir = runs.join(suite).join(case).join(scene);
            std::fs::create_dir_all(&dir)?;
            for (name, h) in &d.histories {
                let file = if name.is_empty() {
                    "history.csv".to_string()
                } else {
                    format!("{name}.csv")
                };
                impact_solver::output::write_history(h, &dir.join(file))
                    .map_err(std::io::Error::other)?;
            }
            if let Some(s) = &d.summary {
                let text = serde_json::to_string_pretty(s).map_err(std::io::Error::other)?;
                std::fs::write(dir.join("summary.json"), text + "\n")?;
            }
        }
    }
    Ok(())
}
