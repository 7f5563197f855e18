//! What a verify run will do: the repository's cases, loaded and linted (the broken ones
//! apart, each to be a FAIL row), those that the [`Options`] select, and their jobs,
//! deduplicated by content (a scene shared by several checks or cases runs once).

use std::collections::BTreeMap;

use crate::codes::Code;
use crate::definition::broken::Broken;
use crate::definition::case::Case;
use crate::definition::repo::Repo;
use crate::run::jobs::{self, Job};

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

fn selected(case: &Case, opts: &Options) -> bool {
    selected_by(case, opts, &opts.selectors)
}

/// Whether `case` is selected by `selectors` (empty: all) and the heavy setting of `opts`.
fn selected_by(case: &Case, opts: &Options, selectors: &[String]) -> bool {
    if case.file.heavy && !opts.include_heavy {
        return false;
    }
    if selectors.is_empty() {
        return true;
    }
    let full = format!("{}/{}", case.suite, case.name);
    selectors
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

pub(super) fn check_matches(case: &Case, check_id: &str, filter: &Option<String>) -> bool {
    match filter {
        None => true,
        Some(f) => format!("{}/{}/{}", case.suite, case.name, check_id).contains(f.as_str()),
    }
}

/// What stops a case's scenes from loading (`impact lint`, before any run): a scene file with
/// its `set` overrides that the solver's scene reader refuses (an odd `mesh.ny`, a key the
/// file lacks, a value out of range), named at the case's line and column; then the wrong
/// models' runs, which put their overrides on top.
pub fn scene_problems(case: &Case) -> Vec<String> {
    match jobs::case_jobs_or_every_error(case) {
        Err(errors) => errors,
        Ok(base) => crate::run::discriminate::jobs(case, &base, true)
            .err()
            .into_iter()
            .collect(),
    }
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
    /// The code that runs the scene jobs (builtins always run in-process).
    pub code: Code,
    pub cases: Vec<&'a Case>,
    /// The selected broken cases (no jobs; a FAIL row each).
    pub broken: Vec<&'a Broken>,
    pub jobs: Vec<Job>,
    /// Per case: scene name -> index into `jobs` (or why its jobs could not be made).
    pub(super) case_jobs: Vec<BTreeMap<String, Result<usize, String>>>,
}

impl Plan<'_> {
    /// Runs job `i` on the plan's code: `impact` runs every job in-process; another code
    /// runs the scenes (through its adapter, or read from its folder), not the scenes whose
    /// point is `impact`'s input validation (`expect_error`), a builtin's problem through its
    /// adapter when the builtin has one, and the other builtins in-process.
    pub fn run_job(&self, i: usize) -> crate::definition::run_data::JobResult {
        use std::sync::Arc;
        let job = &self.jobs[i];
        let Job::Scene {
            scene,
            expect_error,
            ..
        } = job
        else {
            if let (Code::Adapter(a), Job::Builtin { name, params }) = (&self.code, job) {
                if let Some(run) = crate::run::builtins::run_on(a, name, params) {
                    return run.map(Arc::new);
                }
            }
            return job.run();
        };
        match &self.code {
            Code::Impact => job.run(),
            _ if !expect_error.is_empty() => Err(format!(
                "{}the scene checks impact's own input validation",
                crate::codes::NOT_EXPRESSIBLE
            )),
            Code::Adapter(a) => a.run(scene).map(Arc::new),
            Code::ResultsFrom(dir, _) => {
                crate::codes::results_from::read(dir, &self.names_of(i), scene).map(Arc::new)
            }
        }
    }

    /// Every (suite, case, scene) that uses job `i`.
    pub fn names_of(&self, i: usize) -> Vec<(String, String, String)> {
        self.cases
            .iter()
            .zip(&self.case_jobs)
            .flat_map(|(case, jobs_of)| {
                jobs_of
                    .iter()
                    .filter(move |(_, j)| matches!(j, Ok(j) if *j == i))
                    .map(move |(scene, _)| (case.suite.clone(), case.name.clone(), scene.clone()))
            })
            .collect()
    }
}

/// Selects the cases of `opts` and makes their jobs, for `impact`. Errors: no case matches.
pub fn plan<'a>(loaded: &'a Loaded, opts: &Options) -> Result<Plan<'a>, Vec<String>> {
    plan_for(loaded, opts, Code::Impact)
}

/// [`plan`] for `code`: with no selector, an adapter's own `cases` (`light` with
/// `--light`); another code runs no wrong models (they are `impact`'s evidence).
pub fn plan_for<'a>(
    loaded: &'a Loaded,
    opts: &Options,
    code: Code,
) -> Result<Plan<'a>, Vec<String>> {
    let selectors = match code.default_cases(!opts.include_heavy) {
        Some(own) if opts.selectors.is_empty() => own,
        _ => opts.selectors.clone(),
    };
    let broken: Vec<&Broken> = loaded
        .broken
        .iter()
        .filter(|b| code.is_impact() && broken_selected(b, opts))
        .collect();
    let chosen: Vec<&Case> = loaded
        .cases
        .iter()
        .filter(|c| selected_by(c, opts, &selectors))
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
            selectors,
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
                if code.is_impact() {
                    js.extend(crate::run::discriminate::jobs(
                        case,
                        &js,
                        opts.include_heavy,
                    )?);
                } else {
                    // Another code runs the scenes and, through its adapter, the builtins
                    // with a problem form; the harness the builtins its references need.
                    let needed = crate::run::other_code::referenced_builtins(case);
                    js.retain(|name, job| match job {
                        Job::Scene { .. } => true,
                        Job::Builtin { name: b, .. } => {
                            needed.contains(name) || crate::run::builtins::runs_on(&code, b)
                        }
                    });
                }
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
        code,
        cases: chosen,
        broken,
        jobs: unique,
        case_jobs,
    })
}
