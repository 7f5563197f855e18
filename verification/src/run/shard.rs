//! The matrix across machines: `impact verify --shard K/N --out DIR` runs a deterministic,
//! cost-balanced share of the jobs and writes their results to `DIR/shard.json`;
//! `impact verify --merge DIR... --out DIR` reads the shards back and assembles the matrix
//! exactly as a single run does (same plan, same job results: results.json, JUnit and the
//! report equal a single run's, wall times aside).
//!
//! Numbers are stored exactly: metrics and histories as Rust's shortest round-trip text
//! (parsed back to the same bits, NaN and infinities included), summaries as JSON (serde_json
//! with `float_roundtrip`).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use impact_solver::History;
use serde::{Deserialize, Serialize};
use serde_json::Value;

use crate::definition::repo::Repo;
use crate::definition::run_data::{JobResult, RunData};
use crate::run::case_rows::assemble;
use crate::run::job_loop::execute;
use crate::run::matrix::Outcome;
use crate::run::plan::{load, plan, Options};

/// File a shard writes into its output folder.
pub const SHARD_FILE: &str = "shard.json";
const FORMAT: u32 = 1;

/// Shard `index` (1-based) of `count`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    pub index: usize,
    pub count: usize,
}

impl std::str::FromStr for Shard {
    type Err = String;
    fn from_str(s: &str) -> Result<Shard, String> {
        let bad = || format!("--shard {s}: expected K/N with 1 <= K <= N, e.g. 1/4");
        let (k, n) = s.split_once('/').ok_or_else(bad)?;
        let index: usize = k.trim().parse().map_err(|_| bad())?;
        let count: usize = n.trim().parse().map_err(|_| bad())?;
        if index == 0 || index > count {
            return Err(bad());
        }
        Ok(Shard { index, count })
    }
}

/// The jobs of shard `shard`: the plan's jobs by decreasing cost (ties by plan order), each
/// given to the shard with the least cost so far (ties to the lowest index). Deterministic:
/// it depends only on the plan; every job is in exactly one shard.
pub fn share(costs: &[f64], shard: Shard) -> Vec<usize> {
    let mut order: Vec<usize> = (0..costs.len()).collect();
    order.sort_by(|&a, &b| costs[b].total_cmp(&costs[a]).then(a.cmp(&b)));
    let mut load = vec![0.0_f64; shard.count];
    let mut mine = Vec::new();
    for i in order {
        let least = (0..shard.count)
            .min_by(|&a, &b| load[a].total_cmp(&load[b]).then(a.cmp(&b)))
            .unwrap_or(0);
        load[least] += costs[i];
        if least + 1 == shard.index {
            mine.push(i);
        }
    }
    mine.sort_unstable();
    mine
}

/// What a shard writes: the options it was planned with and its jobs' results by job key.
#[derive(Debug, Serialize, Deserialize)]
struct ShardFile {
    format: u32,
    shard: usize,
    of: usize,
    selectors: Vec<String>,
    filter: Option<String>,
    include_heavy: bool,
    /// Jobs in the whole plan (all shards).
    plan_jobs: usize,
    jobs: Vec<StoredJob>,
}

#[derive(Debug, Serialize, Deserialize)]
struct StoredJob {
    key: String,
    result: Result<StoredRun, String>,
}

#[derive(Debug, Serialize, Deserialize)]
struct StoredRun {
    metrics: BTreeMap<String, String>,
    histories: BTreeMap<String, StoredHistory>,
    info: BTreeMap<String, String>,
    summary: Option<Value>,
    /// The run's cost on the shard's machine (for costs.json).
    #[serde(default)]
    cost: Option<crate::definition::run_data::Cost>,
    #[serde(default)]
    scene_values: BTreeMap<String, String>,
}

#[derive(Debug, Serialize, Deserialize)]
struct StoredHistory {
    columns: Vec<String>,
    values: Vec<String>,
}

fn exact(values: impl Iterator<Item = f64>) -> Vec<String> {
    values.map(|v| v.to_string()).collect()
}

fn parse(text: &str) -> Result<f64, String> {
    text.parse()
        .map_err(|_| format!("{text:?} is not a number"))
}

impl StoredRun {
    fn of(d: &RunData) -> StoredRun {
        StoredRun {
            metrics: d
                .metrics
                .iter()
                .map(|(k, v)| (k.clone(), v.to_string()))
                .collect(),
            histories: d
                .histories
                .iter()
                .map(|(k, h)| {
                    let values = exact(h.values.iter().copied());
                    let columns = h.columns.clone();
                    (k.clone(), StoredHistory { columns, values })
                })
                .collect(),
            info: d.info.clone(),
            summary: d.summary.clone(),
            cost: d.cost,
            scene_values: d
                .scene_values
                .iter()
                .map(|(k, v)| (k.clone(), v.to_string()))
                .collect(),
        }
    }

    fn data(self) -> Result<RunData, String> {
        let metrics = self
            .metrics
            .into_iter()
            .map(|(k, v)| Ok((k, parse(&v)?)))
            .collect::<Result<_, String>>()?;
        let histories = self
            .histories
            .into_iter()
            .map(|(k, h)| {
                let values = h
                    .values
                    .iter()
                    .map(|v| parse(v))
                    .collect::<Result<_, _>>()?;
                Ok((
                    k,
                    History {
                        columns: h.columns,
                        values,
                    },
                ))
            })
            .collect::<Result<_, String>>()?;
        Ok(RunData {
            metrics,
            histories,
            info: self.info,
            summary: self.summary,
            files: BTreeMap::new(),
            cost: self.cost,
            scene_values: self
                .scene_values
                .into_iter()
                .map(|(k, v)| Ok((k, parse(&v)?)))
                .collect::<Result<_, String>>()?,
        })
    }
}

/// Runs shard `shard` of the plan of `opts` and writes `out/shard.json`. Returns the number
/// of jobs it ran and of the plan.
pub fn run_shard(
    repo: &Repo,
    opts: &Options,
    shard: Shard,
    out: &Path,
) -> Result<(usize, usize), Vec<String>> {
    let loaded = load(repo)?;
    let plan = plan(&loaded, opts)?;
    let costs: Vec<f64> = plan.jobs.iter().map(|j| j.cost()).collect();
    let mine = share(&costs, shard);
    let results = execute(&plan, &mine, opts.jobs, opts.progress).map_err(|e| vec![e])?;
    let file = ShardFile {
        format: FORMAT,
        shard: shard.index,
        of: shard.count,
        selectors: opts.selectors.clone(),
        filter: opts.filter.clone(),
        include_heavy: opts.include_heavy,
        plan_jobs: plan.jobs.len(),
        jobs: results
            .into_iter()
            .map(|(i, r)| StoredJob {
                key: plan.jobs[i].key(),
                result: r.map(|d| StoredRun::of(&d)),
            })
            .collect(),
    };
    let write = || -> std::io::Result<()> {
        std::fs::create_dir_all(out)?;
        let text = serde_json::to_string(&file).map_err(std::io::Error::other)?;
        std::fs::write(out.join(SHARD_FILE), text + "\n")
    };
    write().map_err(|e| {
        vec![format!(
            "cannot write {}: {e}",
            out.join(SHARD_FILE).display()
        )]
    })?;
    Ok((mine.len(), plan.jobs.len()))
}

/// Reads the shards in `dirs` (all N of one plan, each once), plans again with their options
/// and assembles the matrix from their results, as a single run does.
pub fn merge(repo: &Repo, dirs: &[PathBuf], jobs: usize) -> Result<Outcome, Vec<String>> {
    let mut files = Vec::new();
    for dir in dirs {
        let path = dir.join(SHARD_FILE);
        let text = std::fs::read_to_string(&path)
            .map_err(|e| vec![format!("{}: cannot read: {e}", path.display())])?;
        let file: ShardFile = serde_json::from_str(&text)
            .map_err(|e| vec![format!("{}: not a shard file: {e}", path.display())])?;
        if file.format != FORMAT {
            return Err(vec![format!(
                "{}: shard format {} (this impact reads {FORMAT})",
                path.display(),
                file.format
            )]);
        }
        files.push((path, file));
    }
    let Some((_, first)) = files.first() else {
        return Err(vec!["--merge needs the folders of the shards".into()]);
    };
    let opts = Options {
        selectors: first.selectors.clone(),
        filter: first.filter.clone(),
        jobs,
        include_heavy: first.include_heavy,
        progress: false,
    };
    let count = first.of;
    let mut seen = vec![None; count];
    for (path, f) in &files {
        if (&f.selectors, &f.filter, f.include_heavy, f.of, f.plan_jobs)
            != (
                &first.selectors,
                &first.filter,
                first.include_heavy,
                count,
                first.plan_jobs,
            )
        {
            return Err(vec![format!(
                "{}: shard of another run (selectors, filter, heavy or shard count differ)",
                path.display()
            )]);
        }
        match seen.get_mut(f.shard - 1) {
            Some(slot @ None) => *slot = Some(path.clone()),
            Some(Some(other)) => {
                return Err(vec![format!(
                    "shard {}/{count} given twice: {} and {}",
                    f.shard,
                    other.display(),
                    path.display()
                )])
            }
            None => {
                return Err(vec![format!(
                    "{}: shard {} of {count}?",
                    path.display(),
                    f.shard
                )])
            }
        }
    }
    let missing: Vec<String> = (1..=count)
        .filter(|k| seen[k - 1].is_none())
        .map(|k| format!("{k}/{count}"))
        .collect();
    if !missing.is_empty() {
        return Err(vec![format!("missing shard(s) {}", missing.join(", "))]);
    }
    let mut by_key: BTreeMap<String, JobResult> = BTreeMap::new();
    for (path, f) in files {
        for job in f.jobs {
            let result = match job.result {
                Ok(run) => Ok(Arc::new(
                    run.data()
                        .map_err(|e| vec![format!("{}: {e}", path.display())])?,
                )),
                Err(e) => Err(e),
            };
            by_key.insert(job.key, result);
        }
    }
    let loaded = load(repo)?;
    let plan = plan(&loaded, &opts)?;
    let covered =
        by_key.len() == plan.jobs.len() && plan.jobs.iter().all(|j| by_key.contains_key(&j.key()));
    if !covered {
        return Err(vec![format!(
            "the shards hold {} job results, this checkout's plan has {} other jobs: merge in the checkout the shards ran in",
            by_key.len(),
            plan.jobs.len()
        )]);
    }
    let slots = plan.jobs.iter().map(|j| by_key.remove(&j.key())).collect();
    Ok(assemble(repo, &plan, slots, &opts.filter))
}
