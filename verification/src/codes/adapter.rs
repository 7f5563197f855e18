//! Another code through its adapter (`adapters/<name>/adapter.yaml`, the contract in
//! `adapters/README.md`): the scene written out as `scene.yaml` and `scene.json` into a
//! scratch folder, the adapter run there with a time limit, and its `history.csv`,
//! `summary.json` and `adapter.json` read back; a builtin's problem likewise, as `problem.json`
//! in and `fields.json` out (`super::problem`). Exit status 3 is *not expressible* (its last
//! line of output names the feature); any other failure is one message naming the code, the
//! scene, the status and the code's last lines. The scratch folder is removed whatever
//! happens; the files worth keeping (the scene, the code's input, `adapter.json`) travel with
//! the run into `codes/<name>/runs/`.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use impact_solver::Scene;
use serde::Deserialize;

use super::problem::{Fields, Problem};
use super::process::{self, Ended};
use super::NOT_EXPRESSIBLE;
use crate::definition::run_data::RunData;

/// The exit status of an adapter that cannot express the scene.
pub const EXIT_NOT_EXPRESSIBLE: i32 = 3;

/// `adapter.yaml` as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct AdapterFile {
    name: String,
    description: String,
    /// The program and its first arguments, run from the adapter's folder.
    command: Vec<String>,
    /// s, per scene.
    timeout_s: f64,
    #[serde(default)]
    cases: Vec<String>,
    #[serde(default)]
    light: Vec<String>,
    /// A file beside it: `suite/case/check: reason` for the code's known failures.
    #[serde(default)]
    expected: Option<String>,
}

/// An adapter, loaded.
#[derive(Debug, Clone)]
pub struct Adapter {
    pub name: String,
    pub description: String,
    pub dir: PathBuf,
    pub command: Vec<String>,
    pub timeout_s: f64,
    pub cases: Vec<String>,
    pub light: Vec<String>,
    pub expected: BTreeMap<String, String>,
}

impl Adapter {
    /// `<root>/adapters/<name>/adapter.yaml`; errors name the file, line and column.
    pub fn load(root: &Path, name: &str) -> Result<Adapter, String> {
        let dir = root.join("adapters").join(name);
        let path = dir.join("adapter.yaml");
        if !path.is_file() {
            return Err(format!(
                "--code {name}: no adapter {} (known: impact{})",
                path.display(),
                known(root)
                    .iter()
                    .map(|k| format!(", {k}"))
                    .collect::<String>()
            ));
        }
        let text =
            std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        let file: AdapterFile =
            serde_saphyr::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
        if file.name != name {
            return Err(format!(
                "{}: name: {:?} is not the folder's name {name:?}",
                path.display(),
                file.name
            ));
        }
        if !(file.timeout_s.is_finite() && file.timeout_s > 0.0) {
            return Err(format!(
                "{}: timeout_s: {} (allowed: a number of seconds > 0)",
                path.display(),
                file.timeout_s
            ));
        }
        let expected = match &file.expected {
            None => BTreeMap::new(),
            Some(f) => {
                let p = dir.join(f);
                let text =
                    std::fs::read_to_string(&p).map_err(|e| format!("{}: {e}", p.display()))?;
                serde_saphyr::from_str::<Option<BTreeMap<String, String>>>(&text)
                    .map_err(|e| format!("{}: {e}", p.display()))?
                    .unwrap_or_default()
            }
        };
        Ok(Adapter {
            name: file.name,
            description: file.description,
            dir,
            command: file.command,
            timeout_s: file.timeout_s,
            cases: file.cases,
            light: file.light,
            expected,
        })
    }

    /// Runs `scene` through the adapter (see the module's documentation).
    pub fn run(&self, scene: &Scene) -> Result<RunData, String> {
        let scratch = super::process::Scratch::new(&self.name)?;
        let dir = &scratch.0;
        let yaml = dir.join("scene.yaml");
        let value = scene.to_file_value();
        let json = serde_json::to_string_pretty(&value).map_err(|e| e.to_string())?;
        std::fs::write(
            &yaml,
            impact_solver::input::scene::scene_text::file_text(&value),
        )
        .map_err(|e| format!("{}: {e}", yaml.display()))?;
        std::fs::write(dir.join("scene.json"), json + "\n").map_err(|e| e.to_string())?;
        let source = scene.source.display().to_string();
        let wall_time_s = self.execute(&yaml, dir, &source)?;
        let mut run = super::contract::read_run(dir, Some(scene))
            .map_err(|e| format!("{} on {source}: unreadable output: {e}", self.name))?;
        Self::whole_time(&mut run, wall_time_s);
        run.files = kept_files(dir, &run, "scene.yaml");
        Ok(run)
    }

    /// Runs builtin `builtin`'s `problem` through the adapter (`problem.json` in, `fields.json`
    /// out: `super::problem`): the fields, and a run that records the adapter's input,
    /// substitutions and cost.
    pub fn run_problem(
        &self,
        builtin: &str,
        problem: &Problem,
    ) -> Result<(Vec<Fields>, RunData), String> {
        let scratch = super::process::Scratch::new(&self.name)?;
        let dir = &scratch.0;
        let input = dir.join("problem.json");
        let json = serde_json::to_string_pretty(problem).map_err(|e| e.to_string())?;
        std::fs::write(&input, json + "\n").map_err(|e| format!("{}: {e}", input.display()))?;
        let source = format!("the problem of builtin {builtin}");
        let wall_time_s = self.execute(&input, dir, &source)?;
        let unreadable = |e: String| format!("{} on {source}: unreadable output: {e}", self.name);
        let fields = Fields::read(&dir.join("fields.json"), problem).map_err(unreadable)?;
        let (info, cost) = super::contract::read_adapter_record(dir, &serde_json::Value::Null)
            .map_err(unreadable)?;
        let mut run = RunData {
            info,
            cost,
            ..Default::default()
        };
        Self::whole_time(&mut run, wall_time_s);
        run.files = kept_files(dir, &run, "problem.json");
        Ok((fields, run))
    }

    /// The whole adapter's time (input, code, output) is the code's cost on this run; the
    /// code's own, from `adapter.json`, is kept apart.
    fn whole_time(run: &mut RunData, wall_time_s: f64) {
        if let Some(c) = &mut run.cost {
            c.code_time_s = Some(c.wall_time_s);
            c.wall_time_s = wall_time_s;
        }
    }

    /// Runs the adapter on `input` in `dir` (`source` names the input in messages): the wall
    /// time, s, or the one message of a refusal (*not expressible*), a failure, a timeout or an
    /// interrupt.
    fn execute(&self, input: &Path, dir: &Path, source: &str) -> Result<f64, String> {
        let log = dir.join("adapter.log");
        let done = process::run(
            &self.command,
            &[input, dir],
            &self.dir,
            &log,
            self.timeout_s,
        )?;
        let tail = done.tail.join(" | ");
        match done.ended {
            Ended::Exited(Some(0)) => Ok(done.wall_time_s),
            Ended::Exited(Some(EXIT_NOT_EXPRESSIBLE)) => {
                let line = done.tail.last().cloned().unwrap_or_default();
                let line = line.trim_start_matches("not expressible:").trim();
                Err(format!("{NOT_EXPRESSIBLE}{line}"))
            }
            Ended::Exited(status) => {
                let status = status.map_or("killed by a signal".into(), |s| format!("exit {s}"));
                Err(format!("{} failed on {source} ({status}): {tail}", self.name))
            }
            Ended::TimedOut(limit) => Err(format!("{} on {source}: killed after its time limit of {limit} s (adapter.yaml timeout_s): {tail}", self.name)),
            Ended::Interrupted => Err(format!("{} on {source}: interrupted", self.name)),
        }
    }
}

/// The files kept with the run: the harness's input (`scene.yaml`, `problem.json`),
/// `adapter.json`, and the inputs it names.
fn kept_files(dir: &Path, run: &RunData, input: &str) -> BTreeMap<String, Vec<u8>> {
    let mut names = vec![
        input.to_string(),
        "adapter.json".into(),
        "adapter.log".into(),
    ];
    if let Some(inputs) = run.info.get("input") {
        names.extend(inputs.split("; ").map(str::to_string));
    }
    names
        .into_iter()
        .filter(|n| !n.contains("..") && !n.starts_with('/'))
        .filter_map(|n| std::fs::read(dir.join(&n)).ok().map(|b| (n, b)))
        .collect()
}

/// The adapters under `<root>/adapters/` (folders with an `adapter.yaml`).
pub fn known(root: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(root.join("adapters"))
        .map(|d| {
            d.flatten()
                .filter(|e| e.path().join("adapter.yaml").is_file())
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .collect()
        })
        .unwrap_or_default();
    names.sort();
    names
}
