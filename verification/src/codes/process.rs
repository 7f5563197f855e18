//! An adapter's process: started in its own process group (so that a time limit or Ctrl-C
//! reaches the code it starts, e.g. `ccx`, and not only the adapter), waited for in a bounded
//! loop that polls the stop request every [`POLL`], and killed with its group past its time
//! limit. Scratch folders are registered from their creation ([`Scratch`]) and running
//! groups from their start, under one lock with a "stopped" mark, so that the command line's
//! signal handler ([`stop_all`]) kills them and removes what they wrote, and no folder or
//! group starts after it (a worker that took its next job while the handler ran).

use std::collections::BTreeSet;
use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// How often the wait loop looks at the child and the stop request.
pub const POLL: Duration = Duration::from_millis(50);

/// The adapters' scratch folders and running process groups, and whether [`stop_all`] ran.
struct Running {
    stopped: bool,
    folders: BTreeSet<PathBuf>,
    groups: BTreeSet<i32>,
}

static RUNNING: Mutex<Running> = Mutex::new(Running {
    stopped: false,
    folders: BTreeSet::new(),
    groups: BTreeSet::new(),
});

const STOPPED: &str = "interrupted";

/// A scratch folder under the temporary folder, registered while it exists and removed when
/// dropped; none is made after [`stop_all`].
pub struct Scratch(pub PathBuf);

impl Scratch {
    /// A fresh folder `impact-CODE-PID-N`.
    pub fn new(code: &str) -> Result<Scratch, String> {
        static COUNT: AtomicU64 = AtomicU64::new(0);
        let n = COUNT.fetch_add(1, Ordering::Relaxed);
        let dir = std::env::temp_dir().join(format!("impact-{code}-{}-{n}", std::process::id()));
        let mut running = RUNNING.lock().map_err(|_| STOPPED)?;
        if running.stopped {
            return Err(STOPPED.into());
        }
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        running.folders.insert(dir.clone());
        Ok(Scratch(dir))
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
        if let Ok(mut r) = RUNNING.lock() {
            r.folders.remove(&self.0);
        }
    }
}

/// How a process ended.
#[derive(Debug)]
pub enum Ended {
    /// It exited with this status (`None`: killed by a signal).
    Exited(Option<i32>),
    /// Killed past the time limit (s).
    TimedOut(f64),
    /// Killed on a stop request (Ctrl-C).
    Interrupted,
}

/// What the process wrote and how it ended.
#[derive(Debug)]
pub struct Finished {
    pub ended: Ended,
    /// Its standard output and error (merged in `log`), the last lines.
    pub tail: Vec<String>,
    pub wall_time_s: f64,
}

/// Runs `program args` in `cwd`, its output to `log`, in its own process group (none after
/// [`stop_all`]).
pub fn run(
    program: &[String],
    args: &[&Path],
    cwd: &Path,
    log: &Path,
    timeout_s: f64,
) -> Result<Finished, String> {
    let (first, rest) = program
        .split_first()
        .ok_or("the adapter's command is empty")?;
    let out = std::fs::File::create(log).map_err(|e| format!("{}: {e}", log.display()))?;
    let err = out.try_clone().map_err(|e| e.to_string())?;
    let started = Instant::now();
    let mut child = {
        let mut running = RUNNING.lock().map_err(|_| STOPPED)?;
        if running.stopped {
            return Err(STOPPED.into());
        }
        let child = Command::new(first)
            .args(rest)
            .args(args)
            .current_dir(cwd)
            .stdin(Stdio::null())
            .stdout(out)
            .stderr(err)
            .process_group(0)
            .spawn()
            .map_err(|e| format!("cannot start {first:?} in {}: {e}", cwd.display()))?;
        running.groups.insert(child.id() as i32);
        child
    };
    let group = child.id() as i32;
    let ended = loop {
        match child.try_wait() {
            Ok(Some(status)) => break Ended::Exited(status.code()),
            Ok(None) => {}
            Err(e) => break kill_with(group, &mut child, Err(e.to_string()))?,
        }
        if impact_solver::interrupt::stop_requested() {
            break kill_with(group, &mut child, Ok(Ended::Interrupted))?;
        }
        let t = started.elapsed().as_secs_f64();
        if t > timeout_s {
            break kill_with(group, &mut child, Ok(Ended::TimedOut(timeout_s)))?;
        }
        std::thread::sleep(POLL);
    };
    if let Ok(mut r) = RUNNING.lock() {
        r.groups.remove(&group);
    }
    Ok(Finished {
        ended,
        tail: last_lines(log, 8),
        wall_time_s: started.elapsed().as_secs_f64(),
    })
}

/// Kills the group (SIGTERM, then SIGKILL after a second), reaps the child, returns `how`.
fn kill_with(
    group: i32,
    child: &mut std::process::Child,
    how: Result<Ended, String>,
) -> Result<Ended, String> {
    terminate(group);
    let _ = child.wait();
    how
}

/// SIGTERM to the group; SIGKILL if it is still there after a second (bounded).
fn terminate(group: i32) {
    // SAFETY: kill(2) with a negative pid signals the process group; no memory is touched.
    unsafe {
        libc::kill(-group, libc::SIGTERM);
    }
    for _ in 0..20 {
        // SAFETY: signal 0 only asks whether the group still exists.
        if unsafe { libc::kill(-group, 0) } != 0 {
            return;
        }
        std::thread::sleep(POLL);
    }
    // SAFETY: as above.
    unsafe {
        libc::kill(-group, libc::SIGKILL);
    }
}

/// Kills every running adapter's group and removes every scratch folder, and lets none
/// start after: for the command line's signal handler, before it exits. The lock is held to
/// the end, so a worker that takes its next job meanwhile waits and is then refused.
pub fn stop_all() {
    let Ok(mut running) = RUNNING.lock() else {
        return;
    };
    running.stopped = true;
    for &group in &running.groups {
        terminate(group);
    }
    for folder in &running.folders {
        let _ = std::fs::remove_dir_all(folder);
    }
}

/// The last `n` non-empty lines of a text file (empty when unreadable).
pub fn last_lines(path: &Path, n: usize) -> Vec<String> {
    let text = std::fs::read(path).unwrap_or_default();
    let text = String::from_utf8_lossy(&text);
    let lines: Vec<String> = text
        .lines()
        .map(str::trim_end)
        .filter(|l| !l.trim().is_empty())
        .map(str::to_string)
        .collect();
    lines[lines.len().saturating_sub(n)..].to_vec()
}
