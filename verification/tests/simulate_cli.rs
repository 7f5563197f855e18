//! `impact simulate` protects the user (issue 13): a scene too large for the machine is
//! refused in well under a second with the estimate in the message; SIGTERM stops a run
//! cleanly and leaves nothing behind; a run killed with SIGKILL leaves a staging folder that
//! the next run removes and reports; `/` and foreign non-empty folders are refused as --out;
//! progress goes to stderr as plain lines when it is not a terminal; --threads 0 is refused;
//! a time step that makes no run (density 1e-300 or 1e300) is refused at once naming the
//! input, and a tiny output.every writes every step instead of hanging; with --keep-partial a
//! run stopped by an error or by SIGTERM keeps its history up to the stop and stopped.json
//! (no summary.json), which the next complete run replaces (issue 40).
//! Reference: the behaviour the issue asks for, observed through the real binary.

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

const EXAMPLE: &str = include_str!("../scenes/example-elastic.yaml");

fn dir(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("simulate-{name}"));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn scene(d: &Path, name: &str, edit: impl Fn(&str) -> String) -> PathBuf {
    let p = d.join(format!("{name}.yaml"));
    std::fs::write(&p, edit(&EXAMPLE.replace("  fields: {every: 1.0e-4}", ""))).unwrap();
    p
}

/// `impact simulate` of the example on a 20 x 4 mesh to 0.1 ms (a run that completes in
/// moments) into `out`: its exit status and stderr.
fn simulate_short(d: &Path, name: &str, out: &Path) -> (i32, String) {
    let s = scene(d, name, |t| {
        t.replace("nx: 80, ny: 16", "nx: 20, ny: 4")
            .replace("end: 3.0e-3", "end: 1.0e-4")
    });
    run(&[
        "simulate",
        s.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ])
}

fn impact(args: &[&str]) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_impact"));
    c.args(args);
    c
}

fn run(args: &[&str]) -> (i32, String) {
    let Output { status, stderr, .. } = impact(args).output().unwrap();
    (
        status.code().unwrap_or(-1),
        String::from_utf8_lossy(&stderr).into_owned(),
    )
}

fn leftovers(d: &Path) -> Vec<String> {
    std::fs::read_dir(d)
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains(".partial-"))
        .collect()
}

#[test]
fn a_billion_element_scene_is_refused_at_once_with_its_estimate() {
    let d = dir("huge");
    let s = scene(&d, "huge", |t| {
        t.replace("nx: 80, ny: 16", "nx: 100000, ny: 10000")
    });
    let out = d.join("out");
    let started = Instant::now();
    let (code, err) = run(&[
        "simulate",
        s.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(
        started.elapsed() < Duration::from_secs(1),
        "{:?}",
        started.elapsed()
    );
    assert_eq!(code, 2, "{err}");
    for part in ["1.00e9 elements", "GB of memory", "mesh.nx", "--max-memory"] {
        assert!(err.contains(part), "{err:?} lacks {part:?}");
    }
    assert!(!out.exists() && leftovers(&d).is_empty());
    // A user limit below a small run's estimate refuses it too, naming the limit.
    let small = scene(&d, "small", |t| t.to_string());
    let (code, err) = run(&[
        "simulate",
        small.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--max-memory",
        "1M",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("the limit --max-memory (1.00 MB)"), "{err}");
    let (code, err) = run(&["simulate", "x.yaml", "--out", "o", "--max-memory", "lots"]);
    assert_eq!(code, 2);
    assert!(err.contains("expected a size such as 16G"), "{err}");
}

/// Starts a run of a few seconds with stderr piped and waits until its staging folder exists.
fn start_long_run(d: &Path, out: &Path) -> Child {
    start_long_run_with(d, out, &[])
}

/// [`start_long_run`] with `extra` arguments.
fn start_long_run_with(d: &Path, out: &Path, extra: &[&str]) -> Child {
    let s = scene(d, "long", |t| {
        t.replace("end: 3.0e-3", "end: 2.0")
            .replace("every: 1.0e-6", "every: 1.0e-3")
    });
    let child = impact(&[
        "simulate",
        s.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ])
    .args(extra)
    .stderr(Stdio::piped())
    .stdout(Stdio::null())
    .spawn()
    .unwrap();
    let started = Instant::now();
    while leftovers(d).is_empty() {
        assert!(
            started.elapsed() < Duration::from_secs(20),
            "no staging folder"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    std::thread::sleep(Duration::from_millis(300));
    child
}

fn signal(child: &Child, name: &str) {
    let ok = Command::new("kill")
        .args([&format!("-{name}"), &child.id().to_string()])
        .status()
        .unwrap()
        .success();
    assert!(ok);
}

#[test]
fn sigterm_stops_cleanly_and_a_killed_runs_staging_is_removed_by_the_next_run() {
    let d = dir("signals");
    let out = d.join("run");
    let child = start_long_run(&d, &out);
    signal(&child, "TERM");
    let o = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(130), "{err}");
    assert!(err.contains("stopped: interrupted at step"), "{err}");
    assert!(err.contains("removed the staging folder"), "{err}");
    assert!(
        leftovers(&d).is_empty() && !out.exists(),
        "{:?}",
        leftovers(&d)
    );

    // `timeout` signals the child and then its process group: two TERMs at once are one
    // stop request, still a clean stop.
    let child = start_long_run(&d, &out);
    signal(&child, "TERM");
    signal(&child, "TERM");
    let o = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("removed the staging folder"), "{err}");
    assert!(leftovers(&d).is_empty(), "{:?}", leftovers(&d));

    let child = start_long_run(&d, &out);
    signal(&child, "KILL");
    let _ = child.wait_with_output().unwrap();
    assert_eq!(leftovers(&d).len(), 1);
    let (code, err) = simulate_short(&d, "short", &out);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("left by a run that was killed"), "{err}");
    assert!(leftovers(&d).is_empty());
    // Progress to a pipe: plain lines, the estimate first.
    assert!(err.contains("simulate: 80 elements, about"), "{err}");
    assert!(err.contains("simulate: setting up 80 elements"), "{err}");
    assert!(
        err.contains("simulate:   0% t = 0.0000 of 0.1000 ms"),
        "{err}"
    );
}

#[test]
fn root_and_foreign_folders_are_refused_as_out() {
    let d = dir("folders");
    let s = scene(&d, "s", |t| t.to_string());
    let s = s.to_str().unwrap();
    let (code, err) = run(&["simulate", s, "--out", "/"]);
    assert_eq!(code, 2);
    assert!(err.contains("--out /: is the root folder"), "{err}");
    let mine = d.join("mine");
    std::fs::create_dir_all(&mine).unwrap();
    std::fs::write(mine.join("notes.txt"), "mine").unwrap();
    let (code, err) = run(&["simulate", s, "--out", mine.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(
        err.contains("notes.txt") && err.contains("--force"),
        "{err}"
    );
    assert_eq!(
        std::fs::read_to_string(mine.join("notes.txt")).unwrap(),
        "mine"
    );
    let (code, err) = run(&["simulate", s, "--out", "o", "--threads", "0"]);
    assert_eq!(code, 2);
    assert!(err.contains("--threads"), "{err}");
}

/// `impact simulate SCENE --out OUT --quiet`, killed when still running after 60 s (a hang is
/// a failure here, not a test that never ends): exit status and stderr.
fn run_or_kill(scene: &Path, out: &Path) -> (i32, String) {
    let mut child = impact(&[
        "simulate",
        scene.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ])
    .stderr(Stdio::piped())
    .stdout(Stdio::null())
    .spawn()
    .unwrap();
    let started = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if started.elapsed() > Duration::from_secs(60) {
            let _ = child.kill();
            let _ = child.wait();
            panic!("{}: still running after 60 s", scene.display());
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let Output { status, stderr, .. } = child.wait_with_output().unwrap();
    (
        status.code().unwrap_or(-1),
        String::from_utf8_lossy(&stderr).into_owned(),
    )
}

#[test]
fn a_time_step_that_makes_no_run_is_refused_and_a_tiny_output_interval_does_not_hang() {
    let d = dir("steps");
    for (density, says) in [("1e-300", "comes out as 0.000e0 s"), ("1e300", "no step")] {
        let s = scene(&d, &format!("rho{density}"), |t| {
            t.replace("density: 7850.0", &format!("density: {density}"))
        });
        let (code, err) = run_or_kill(&s, &d.join("out"));
        assert_eq!(code, 2, "{err}");
        // At the line and column where the scene writes it.
        let named = format!("{}:5:12: material.density = {density}: ", s.display());
        assert!(err.contains(&named) && err.contains(says), "{err}");
    }
    // 10^8 history intervals in each step: a row every step, written at once.
    let s = scene(&d, "every", |t| {
        t.replace("nx: 80, ny: 16", "nx: 20, ny: 4")
            .replace("end: 3.0e-3", "end: 2.0e-4")
            .replace("every: 1.0e-6", "every: 1.0e-15")
    });
    let out = d.join("every-out");
    let (code, err) = run_or_kill(&s, &out);
    assert_eq!(code, 0, "{err}");
    let summary = std::fs::read_to_string(out.join("summary.json")).unwrap();
    let steps: usize = summary
        .split("\"n_steps\": ")
        .nth(1)
        .and_then(|t| t.split(',').next())
        .and_then(|n| n.trim().parse().ok())
        .unwrap();
    let rows = std::fs::read_to_string(out.join("history.csv"))
        .unwrap()
        .lines()
        .count()
        - 1;
    assert_eq!(rows, steps + 1, "one row per step, step 0 included");
    let _ = std::fs::remove_dir_all(&d);
}

/// The rows of `out/history.csv` (without the header) and `out/stopped.json`.
fn partial(out: &Path) -> (Vec<String>, serde_json::Value) {
    let csv = std::fs::read_to_string(out.join("history.csv")).unwrap();
    let rows = csv.lines().skip(1).map(String::from).collect();
    let text = std::fs::read_to_string(out.join("stopped.json")).unwrap();
    (rows, serde_json::from_str(&text).unwrap())
}

/// An unstable run (a fixed step 1.42x the stable one, allowed) stops at step 21 with exit 2:
/// with --keep-partial its 21 rows (steps 0 to 20, every row whole, the last at the time
/// stopped.json names) and stopped.json are in --out and no summary.json; without it nothing.
/// A complete run into the same folder then removes stopped.json. SIGTERM with --keep-partial:
/// exit 130, the rows so far kept and said so.
#[test]
fn keep_partial_keeps_the_rows_of_a_stopped_run_and_says_why() {
    let d = dir("partial");
    let s = scene(&d, "unstable", |t| {
        t.replace("nx: 80, ny: 16", "nx: 20, ny: 4")
            .replace(
                "  dt: {cfl: 0.8}",
                "  dt: {fixed: 1.0e-6}\n  allow_unstable_dt: true\n  # was",
            )
            .replace("every: 1.0e-6", "every: 1.0e-9")
    });
    let out = d.join("kept");
    let (scene_path, out_path) = (s.to_str().unwrap(), out.to_str().unwrap());
    let (code, err) = run(&["simulate", scene_path, "--out", out_path, "--keep-partial"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("kept the partial output in"), "{err}");
    let (rows, stopped) = partial(&out);
    assert_eq!(rows.len(), 21, "{err}");
    let width = rows[0].split(',').count();
    assert!(rows.iter().all(|r| r.split(',').count() == width));
    let last: f64 = rows[20].split(',').next().unwrap().parse().unwrap();
    assert_eq!(stopped["last_row_time_s"].as_f64(), Some(last));
    assert_eq!(stopped["history_rows"], 21);
    assert!(
        stopped["error"].as_str().unwrap().contains("unstable"),
        "{stopped}"
    );
    assert!(!out.join("summary.json").exists());
    assert!(leftovers(&d).is_empty(), "{:?}", leftovers(&d));
    // Without the flag: nothing in --out.
    let bare = d.join("bare");
    let (code, _) = run(&["simulate", scene_path, "--out", bare.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(!bare.exists() && leftovers(&d).is_empty());
    // A complete run into the kept folder replaces the partial output.
    let (code, err) = simulate_short(&d, "fine", &out);
    assert_eq!(code, 0, "{err}");
    assert!(out.join("summary.json").exists() && !out.join("stopped.json").exists());

    let out = d.join("interrupted");
    let child = start_long_run_with(&d, &out, &["--keep-partial"]);
    signal(&child, "TERM");
    let o = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(130), "{err}");
    assert!(err.contains("kept the partial output in"), "{err}");
    let (rows, stopped) = partial(&out);
    assert!(!rows.is_empty(), "{err}");
    assert!(
        stopped["error"].as_str().unwrap().contains("interrupted"),
        "{stopped}"
    );
    assert!(!out.join("summary.json").exists() && leftovers(&d).is_empty());
}
