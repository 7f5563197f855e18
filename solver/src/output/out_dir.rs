//! The output folder of a run: refused when writing there would mix our files with the
//! user's (`/`, the home folder, a non-empty folder that holds no earlier run), its lock
//! `.NAME.lock` beside it (one run at a time per folder), its staging folder
//! `.NAME.partial-PID/` beside it, and the staging folders and locks that killed runs left.

use std::fs;
use std::path::{Path, PathBuf};

use crate::input::error::{Error, Result};

/// Files `impact simulate` writes into its output folder.
pub const OUTPUT_FILES: [&str; 5] = [
    "history.csv",
    "summary.json",
    "fields",
    "fields.pvd",
    STOPPED_FILE,
];

/// What a run that stopped before its end kept beside its partial history (`--keep-partial`).
pub const STOPPED_FILE: &str = "stopped.json";

/// Refuses `out` when it is `/`, the home folder, a file, or a non-empty folder without any
/// of an earlier run's [`OUTPUT_FILES`] (unless `force`).
pub fn check_out_dir(out: &Path, force: bool) -> Result<()> {
    let refuse = |why: String| {
        Err(Error::OutputFolder {
            path: out.to_path_buf(),
            why,
        })
    };
    let resolved = fs::canonicalize(out).unwrap_or_else(|_| out.to_path_buf());
    if resolved.parent().is_none() {
        return refuse("is the root folder; give a folder of its own, e.g. --out out/run".into());
    }
    let home = std::env::var_os("HOME").map(PathBuf::from);
    if let Some(home) = home.and_then(|h| fs::canonicalize(h).ok()) {
        if resolved == home {
            return refuse(
                "is your home folder; give a folder of its own, e.g. --out out/run".into(),
            );
        }
    }
    if out.is_file() {
        return refuse("is a file; --out names a folder".into());
    }
    if force || !out.is_dir() {
        return Ok(());
    }
    let entries: Vec<String> = fs::read_dir(out)
        .map_err(|e| Error::write(out, e))?
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| staging_pid(n).is_none())
        .collect();
    let earlier_run = entries.iter().any(|n| OUTPUT_FILES.contains(&n.as_str()));
    if entries.is_empty() || earlier_run {
        return Ok(());
    }
    let mut shown: Vec<&str> = entries.iter().map(String::as_str).take(3).collect();
    shown.sort_unstable();
    refuse(format!(
        "is not empty ({} entries, e.g. {}) and holds no earlier run (no {}); choose an empty or new folder, or pass --force to write {} into it",
        entries.len(),
        shown.join(", "),
        OUTPUT_FILES.join(", "),
        OUTPUT_FILES.join(", ")
    ))
}

/// The lock of an output folder: the file `.NAME.lock` beside it, holding the id of the
/// process whose run writes into it; removed when dropped (the run's end, its error, or its
/// stop on Ctrl-C). A second run into the same folder while the first runs is refused
/// ([`OutLock::take`]); a lock left by a process that no longer runs (killed with SIGKILL, a
/// second Ctrl-C) is removed and reported by the next run.
#[derive(Debug)]
pub struct OutLock {
    path: PathBuf,
}

impl OutLock {
    /// Takes the lock of `out`; also returns the path of a stale lock it removed. Refused
    /// with [`Error::OutputFolder`] while another run (of any process, this one included)
    /// holds it.
    pub fn take(out: &Path) -> Result<(OutLock, Option<PathBuf>)> {
        let parent = parent_of(out);
        fs::create_dir_all(parent).map_err(|e| Error::write(parent, e))?;
        let path = lock_path(out);
        let pid = std::process::id();
        // Written whole beside the lock, then linked to its name: the link is atomic and fails
        // when the lock exists, so a lock is never seen half-written.
        let draft = parent.join(format!(".{}.lock-{pid}-{}", folder_name(out), next_draft()));
        fs::write(&draft, format!("{pid}\n")).map_err(|e| Error::write(out, e))?;
        let mut stale = None;
        let taken = loop {
            match fs::hard_link(&draft, &path) {
                Ok(()) => break Ok(()),
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {}
                Err(e) => break Err(Error::write(out, e)),
            }
            let holder = fs::read_to_string(&path)
                .ok()
                .and_then(|t| t.trim().parse::<u32>().ok());
            match holder {
                Some(other) if other == pid || process_alive(other) => {
                    break Err(Error::OutputFolder {
                        path: out.to_path_buf(),
                        why: format!(
                            "another run (process {other}{}) is writing into it now (its lock is {}); wait for it to finish, or give another --out",
                            if other == pid { ", this one" } else { "" },
                            path.display()
                        ),
                    })
                }
                _ if stale.is_some() => {
                    break Err(Error::write(
                        &path,
                        std::io::Error::other("a stale lock keeps coming back"),
                    ))
                }
                _ => {
                    // Left by a process that no longer runs (or unreadable): remove, retry once.
                    let _ = fs::remove_file(&path);
                    stale = Some(path.clone());
                }
            }
        };
        let _ = fs::remove_file(&draft);
        taken.map(|()| (OutLock { path }, stale))
    }
}

impl Drop for OutLock {
    fn drop(&mut self) {
        let _ = fs::remove_file(&self.path);
    }
}

/// `.NAME.lock` beside `out`.
pub fn lock_path(out: &Path) -> PathBuf {
    parent_of(out).join(format!(".{}.lock", folder_name(out)))
}

/// A number for a lock's draft file, distinct for each call in this process.
fn next_draft() -> u64 {
    static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed)
}

/// `.NAME.partial-PID` beside `out`: where a run writes before moving its files in.
pub fn staging_dir(out: &Path) -> PathBuf {
    parent_of(out).join(format!(
        ".{}.partial-{}",
        folder_name(out),
        std::process::id()
    ))
}

/// Removes the staging folders of `out` whose process is no longer running (a killed run);
/// returns the folders removed and those that could not be (with the reason).
pub fn clean_stale_staging(out: &Path) -> Vec<(PathBuf, Option<String>)> {
    let prefix = format!(".{}.partial-", folder_name(out));
    let Ok(entries) = fs::read_dir(parent_of(out)) else {
        return Vec::new();
    };
    let mut found = Vec::new();
    for e in entries.filter_map(|e| e.ok()) {
        let name = e.file_name().to_string_lossy().into_owned();
        let Some(pid) = name
            .strip_prefix(&prefix)
            .and_then(|p| p.parse::<u32>().ok())
        else {
            continue;
        };
        if pid == std::process::id() || process_alive(pid) {
            continue;
        }
        let path = e.path();
        let failure = fs::remove_dir_all(&path).err().map(|e| e.to_string());
        found.push((path, failure));
    }
    found.sort();
    found
}

fn staging_pid(name: &str) -> Option<u32> {
    let (_, pid) = name.strip_prefix('.')?.rsplit_once(".partial-")?;
    pid.parse().ok()
}

/// Whether a process with this id runs (Linux: /proc/PID exists; elsewhere assumed so,
/// which only keeps a stale folder).
fn process_alive(pid: u32) -> bool {
    if Path::new("/proc/self").exists() {
        Path::new(&format!("/proc/{pid}")).exists()
    } else {
        true
    }
}

fn folder_name(out: &Path) -> String {
    out.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "out".into())
}

fn parent_of(out: &Path) -> &Path {
    out.parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."))
}

/// The same error with a path inside `staging` replaced by the path inside `out` the user
/// asked for.
pub fn in_user_terms(error: Error, staging: &Path, out: &Path) -> Error {
    match error {
        Error::WriteOutput { path, source } => {
            let path = match path.strip_prefix(staging) {
                Ok(rel) if rel.as_os_str().is_empty() => out.to_path_buf(),
                Ok(rel) => out.join(rel),
                Err(_) => path,
            };
            Error::WriteOutput { path, source }
        }
        other => other,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("impact-outdir-{name}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&d);
        fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn root_home_files_and_foreign_folders_are_refused() {
        assert!(check_out_dir(Path::new("/"), true)
            .unwrap_err()
            .to_string()
            .contains("root folder"));
        if let Some(home) = std::env::var_os("HOME") {
            let e = check_out_dir(Path::new(&home), true).unwrap_err();
            assert!(e.to_string().contains("home folder"), "{e}");
        }
        let d = temp("foreign");
        fs::write(d.join("thesis.tex"), "x").unwrap();
        let e = check_out_dir(&d, false).unwrap_err().to_string();
        assert!(e.contains("not empty") && e.contains("thesis.tex") && e.contains("--force"));
        assert!(check_out_dir(&d, true).is_ok());
        assert!(check_out_dir(&d.join("thesis.tex"), true).is_err());
        // An earlier run's folder, an empty one and a new one are fine.
        fs::write(d.join("summary.json"), "{}").unwrap();
        assert!(check_out_dir(&d, false).is_ok());
        assert!(check_out_dir(&d.join("new"), false).is_ok());
        let _ = fs::remove_dir_all(&d);
    }

    #[test]
    fn staging_folders_of_dead_processes_are_removed_and_live_ones_kept() {
        let d = temp("stale");
        let out = d.join("run");
        // A pid above the kernel's maximum (4194304) never runs.
        let dead = d.join(".run.partial-4194400");
        let mine = staging_dir(&out);
        fs::create_dir_all(dead.join("fields")).unwrap();
        fs::create_dir_all(&mine).unwrap();
        let removed = clean_stale_staging(&out);
        assert_eq!(removed, vec![(dead.clone(), None)]);
        assert!(!dead.exists() && mine.exists());
        let _ = fs::remove_dir_all(&d);
    }

    #[test]
    fn a_second_run_into_a_locked_folder_is_refused_and_a_dead_runs_lock_is_removed() {
        let d = temp("lock");
        let out = d.join("run");
        let (lock, stale) = OutLock::take(&out).unwrap();
        assert_eq!(stale, None);
        assert!(lock_path(&out).is_file());
        let e = OutLock::take(&out).unwrap_err().to_string();
        assert!(
            e.contains("another run (process") && e.contains("is writing into it now"),
            "{e}"
        );
        drop(lock);
        assert!(!lock_path(&out).exists());
        // A lock left by a process that no longer runs (above the kernel's largest pid).
        fs::write(lock_path(&out), "4194400\n").unwrap();
        let (lock, stale) = OutLock::take(&out).unwrap();
        assert_eq!(stale, Some(lock_path(&out)));
        drop(lock);
        // Nothing else is left beside the folder.
        let left: Vec<_> = fs::read_dir(&d).unwrap().filter_map(|e| e.ok()).collect();
        assert!(left.is_empty(), "{left:?}");
        let _ = fs::remove_dir_all(&d);
    }

    #[test]
    fn staging_paths_in_errors_become_the_users_folder() {
        let e = Error::write(
            "/x/.run.partial-7/history.csv",
            std::io::Error::other("disk full"),
        );
        let e = in_user_terms(e, Path::new("/x/.run.partial-7"), Path::new("/x/run"));
        assert!(e.to_string().starts_with("/x/run/history.csv:"), "{e}");
    }
}
