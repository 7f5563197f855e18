//! The V&V report: index.html (self-contained) and report.md from a verify output folder.

use std::path::{Path, PathBuf};

use crate::runner::Repo;

/// Writes environment.json (commit, rustc, machine, date, wall time) next to results.json.
pub fn write_environment(repo: &Repo, out: &Path, wall_s: f64, jobs: usize) -> std::io::Result<()> {
    let env = environment(repo, wall_s, jobs);
    std::fs::write(out.join("environment.json"), serde_json::to_string_pretty(&env).map_err(std::io::Error::other)? + "\n")
}

fn command(cmd: &str, args: &[&str], dir: &Path) -> String {
    std::process::Command::new(cmd)
        .args(args)
        .current_dir(dir)
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .unwrap_or_else(|| "unknown".into())
}

pub fn environment(repo: &Repo, wall_s: f64, jobs: usize) -> serde_json::Value {
    let dirty = command("git", &["status", "--porcelain", "--untracked-files=no"], &repo.root);
    let commit = command("git", &["rev-parse", "HEAD"], &repo.root);
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|t| t.lines().find(|l| l.starts_with("model name")).map(|l| l.split(':').nth(1).unwrap_or("").trim().to_string()))
        .unwrap_or_else(|| "unknown".into());
    serde_json::json!({
        "commit": if dirty.is_empty() || dirty == "unknown" { commit } else { format!("{commit} (with uncommitted changes)") },
        "rustc": command("rustc", &["--version"], &repo.root),
        "machine": format!("{} {}, {} cores, {cpu}", std::env::consts::OS, std::env::consts::ARCH,
            std::thread::available_parallelism().map_or(1, |n| n.get())),
        "date_utc": command("date", &["-u", "+%Y-%m-%dT%H:%M:%SZ"], &repo.root),
        "wall_time_s": wall_s,
        "jobs": jobs,
    })
}

pub fn write_report(_from: &Path, _out: &Path) -> anyhow::Result<Vec<PathBuf>> {
    anyhow::bail!("not yet")
}
