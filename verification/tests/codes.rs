//! Other codes in the matrix (issue 38), run as `impact verify` processes on scratch
//! repositories with one case (a tiny pulse scene, checks on the impulse, the mid-span
//! deflection, a key no code writes and a builtin) and a fake adapter written in `sh`, whose
//! behaviour the environment chooses:
//! - `--code fake` evaluates the same checks on what the adapter wrote: OK where it agrees,
//!   FAIL where it does not (exit 1), FAIL* where its `expected.yaml` declares it (exit 0);
//!   a key it did not write, a builtin's measure and a reference from a scene it refused are
//!   N/E, never OK or FAIL; so is a check against the fake code's own stored run (kind
//!   `other code`), which impact's row evaluates;
//! - the adapter sees the resolved scene (`scene.yaml` and `scene.json`) and its kept files
//!   land in `codes/fake/runs/`;
//! - exit status 3 makes every check of the scene N/E with the adapter's line; a crash, a
//!   hang past `timeout_s` (the process group killed, sleep included) and malformed output
//!   are one message naming the code and the scene, and the scratch folder is gone;
//! - `--results-from DIR` reads the same files; a scene with no folder is N/E, a malformed
//!   file names itself and its line;
//! - an unknown code is refused before any run (exit 2), naming the adapters there are;
//! - one scene file that two cases read through two relative paths is run once.
//!
//! A harness that evaluated nothing on the other code (or evaluated impact's runs under its
//! name) fails the first test: the fake adapter's deflection is not impact's.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::{AtomicUsize, Ordering};

static COUNTER: AtomicUsize = AtomicUsize::new(0);

const SCENE: &str = "plate: {length: 0.2, width: 0.1, thickness: 0.02}
material: {density: 7850.0, youngs_modulus: 2.0e11, poisson_ratio: 0.3}
mesh: {nx: 4, ny: 2, element: q4-full, model: half}
load:
  pulse: {force: 1000.0, duration: 1.0e-4}
time:
  end: 2.0e-4
  dt: {cfl: 0.5}
output:
  every: 1.0e-5
";

const CASE: &str = "id: c1
title: t
requirement: {id: REQ-1, text: The solver shall do a thing.}
category: code verification
scenes:
  plate: {file: plate.yaml}
  law: {builtin: hertz-law}
  refused: {file: plate.yaml, set: {time.dt.cfl: 0.25}}
checks:
  - id: impulse
    title: impulse = F t
    measure: {scene: plate, metric: impulse_Ns}
    reference: {kind: analytical, value: 0.1, source: \"1000 N x 0.1 ms\"}
    tolerance: {relative: 1.0e-6, reason: \"test\"}
  - id: deflection
    title: the fake code's deflection
    measure: {scene: plate, extreme: {column: mid_uy_m, reduce: min}}
    reference: {kind: analytical, value: -2.0e-3, source: \"what the fake adapter writes\"}
    tolerance: {relative: 1.0e-9, reason: \"test\"}
  - id: wrong
    title: a check the fake code fails
    measure: {scene: plate, metric: impulse_Ns}
    reference: {kind: analytical, value: 0.5, source: \"deliberately wrong\"}
    tolerance: {relative: 1.0e-6, reason: \"test\"}
    known_failure: \"impact's declaration, not the fake code's\"
  - id: unwritten
    title: a key no adapter writes
    measure: {scene: plate, metric: peak_contact_force_N}
    reference: {kind: analytical, value: 1000.0, source: \"the pulse\"}
    tolerance: {relative: 1.0e-6, reason: \"test\"}
  - id: against-refused
    title: the plate against itself at half the step, a scene the fake code refuses
    measure: {scene: plate, error: {column: mid_uy_m, norm: linf}}
    reference: {kind: invariant, value: 0.0, history: {scene: refused, column: mid_uy_m}, source: \"the same plate\"}
    tolerance: {absolute: 0.05, reason: \"the step's effect on impact's deflection, measured 3.8e-3 (about 13x); the fake code's status is what is read\"}
  - id: against-fake
    title: the impulse against the fake code's stored run
    measure: {scene: plate, metric: impulse_Ns}
    reference: {kind: other code, code: fake, json: {file: reference-data/codes/fake/plate/summary.json, key: impulse_Ns}, source: \"the fake code's stored run\"}
    tolerance: {relative: 1.0e-2, reason: \"impact's pulse ends within a step (3.5e-3 here)\"}
  - id: builtin
    title: impact's own kernel
    measure: {scene: law, metric: round_trip_max_rel}
    reference: {kind: analytical, value: 0.0, source: \"closed form\"}
    tolerance: {absolute: 1.0e-9, reason: \"round-off\"}
";

/// The fake code: `FAKE_MODE` = ok (the contract's three files), refuse (exit 3), crash,
/// hang, garbage (a history with a word in it); given a builtin's problem.json, the patch
/// test's exact fields (`FAKE_MODE` = patch-fails: 1 N on its free node). It refuses to write when it was not given a
/// readable scene.yaml and scene.json.
const ADAPTER: &str = r#"#!/bin/sh
scene="$1"; out="$2"
case "$scene" in
  */problem.json)
    grep -q '"problem": "static"' "$scene" || { echo "no problem.json" >&2; exit 9; }
    force=0.0; [ "$FAKE_MODE" = patch-fails ] && force=1.0
    s='[207000000.0, -47769230.76923077, 47769230.76923077, 15923076.923076924]'
    { printf '{"displacements_m": [[0,0],[0,0],[0,0],[0,0],[0,0],[0,0],[0,0],[0,0],[0,0]],\n'
      printf ' "nodal_forces_N": [[1000,0],[-1000,0],[1000,0],[-1000,0],[%s,0],[1000,0],[-1000,0],[1000,0],[-1000,0]],\n' "$force"
      printf ' "point_stresses_Pa": [[%s],[%s],[%s],[%s]]}\n' "$s" "$s" "$s" "$s"; } > "$out/fields.json"
    printf '{"code": "fake", "version": "0.1", "input": [], "wall_time_s": 0.01, "n_elements": 4, "n_steps": 1}\n' > "$out/adapter.json"
    exit 0 ;;
esac
grep -q '^plate:' "$scene" || { echo "no scene.yaml" >&2; exit 9; }
[ -n "$FAKE_LOG" ] && echo "$out" >> "$FAKE_LOG"
grep -q '"cfl": 0.25' "$out/scene.json" && { echo "not expressible: time.dt.cfl: 0.25 is too small for fake" >&2; exit 3; }
grep -q '"nx": 4' "$out/scene.json" || { echo "no scene.json" >&2; exit 9; }
case "$FAKE_MODE" in
  ok)
    printf 'time_s,mid_uy_m\n0,0\n1e-4,-2e-3\n2e-4,-1e-3\n' > "$out/history.csv"
    printf '{"impulse_Ns": 0.1, "max_von_mises_Pa": {"A": 5.0}}\n' > "$out/summary.json"
    printf 'the deck\n' > "$out/fake.inp"
    printf '{"code": "fake", "version": "0.1", "input": ["fake.inp"], "wall_time_s": 0.01, "cpu_time_s": 0.01, "substitutions": ["none"]}\n' > "$out/adapter.json" ;;
  refuse) echo "some chatter"; echo "not expressible: q4-full: no such element in fake" >&2; exit 3 ;;
  crash) echo "*ERROR in fake: the deck is wrong"; exit 7 ;;
  hang) sleep 60 ;;
  garbage)
    printf 'time_s,mid_uy_m\n0,0\n1e-4,oops\n' > "$out/history.csv"
    printf '{}' > "$out/summary.json" ;;
esac
"#;

fn scratch(expected: &str, timeout_s: f64) -> PathBuf {
    let root = std::env::temp_dir().join(format!(
        "impact-codes-{}-{}",
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::SeqCst)
    ));
    let _ = std::fs::remove_dir_all(&root);
    let dir = root.join("verification/cases/suite/case");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("case.yaml"), CASE).unwrap();
    std::fs::write(dir.join("plate.yaml"), SCENE).unwrap();
    let fake = root.join("adapters/fake");
    std::fs::create_dir_all(&fake).unwrap();
    std::fs::write(fake.join("run.sh"), ADAPTER).unwrap();
    std::fs::write(
        fake.join("adapter.yaml"),
        format!(
            "name: fake\ndescription: a fake code for the tests\ncommand: [sh, run.sh]\n\
             timeout_s: {timeout_s}\ncases: [suite/case]\nlight: [suite/case]\nexpected: expected.yaml\n"
        ),
    )
    .unwrap();
    std::fs::write(fake.join("expected.yaml"), expected).unwrap();
    // The fake code's stored run, the reference of `against-fake` (kind other code).
    let stored = root.join("reference-data/codes/fake/plate");
    std::fs::create_dir_all(&stored).unwrap();
    std::fs::write(stored.join("summary.json"), "{\"impulse_Ns\": 0.1}").unwrap();
    std::fs::write(stored.join("adapter.json"), "{\"code\": \"fake\"}").unwrap();
    std::fs::write(stored.join("../PROVENANCE.md"), "the fake code's run\n").unwrap();
    std::fs::create_dir_all(root.join("tmp")).unwrap();
    root
}

/// (exit code, stdout, stderr) of `impact verify --root ROOT --out ROOT/out ARGS` with
/// `FAKE_MODE=mode`.
fn verify(root: &Path, mode: &str, args: &[&str]) -> (i32, String, String) {
    let o = Command::new(env!("CARGO_BIN_EXE_impact"))
        .args(["verify", "--jobs", "1", "--root"])
        .arg(root)
        .arg("--out")
        .arg(root.join("out"))
        .args(args)
        .env("FAKE_MODE", mode)
        .env("TMPDIR", root.join("tmp"))
        .output()
        .expect("run impact");
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// The status of `check` on `code`'s row in matrix.txt's table.
fn status(stdout: &str, code: &str, check: &str) -> String {
    stdout
        .lines()
        .find(|l| {
            let w: Vec<&str> = l.split_whitespace().collect();
            w.len() > 4 && w[0] == code && w[3] == check
        })
        .map(|l| l.split_whitespace().nth(4).unwrap().to_string())
        .unwrap_or_else(|| panic!("no row {code} {check} in\n{stdout}"))
}

/// What the adapters left in the run's temporary folder (`TMPDIR=ROOT/tmp`).
fn scratch_left(root: &Path) -> Vec<PathBuf> {
    std::fs::read_dir(root.join("tmp"))
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .collect()
}

#[test]
fn the_same_checks_are_evaluated_on_the_other_code() {
    let root = scratch(
        "suite/case/wrong: \"the fake code's own known failure\"\n",
        60.0,
    );
    let (code, stdout, stderr) = verify(&root, "ok", &["--code", "impact", "--code", "fake"]);
    // impact's own runs fail: its deflection is not the fake's -2 mm.
    assert_eq!(code, 1, "{stdout}\n{stderr}");
    assert_eq!(status(&stdout, "impact", "deflection"), "FAIL");
    assert_eq!(status(&stdout, "fake", "deflection"), "OK");
    assert_eq!(status(&stdout, "fake", "impulse"), "OK");
    assert_eq!(status(&stdout, "fake", "wrong"), "FAIL*");
    assert_eq!(status(&stdout, "fake", "unwritten"), "N/E");
    assert_eq!(status(&stdout, "fake", "builtin"), "N/E");
    // A reference the fake code computes from a scene it refused: N/E, not FAIL.
    assert_eq!(status(&stdout, "fake", "against-refused"), "N/E");
    assert_eq!(
        status(&stdout, "impact", "against-refused"),
        "OK",
        "{stdout}"
    );
    assert!(stdout.contains("not produced by fake"), "{stdout}");
    // A reference of kind other code: evaluated on impact, N/E on the code whose run it is.
    assert_eq!(status(&stdout, "impact", "against-fake"), "OK");
    assert_eq!(status(&stdout, "fake", "against-fake"), "N/E");
    assert!(stdout.contains("fake's own stored run"), "{stdout}");
    let results = std::fs::read_to_string(root.join("out/results.json")).unwrap();
    let results: serde_json::Value = serde_json::from_str(&results).unwrap();
    assert_eq!(results["cases"][0]["code"], "impact");
    assert_eq!(results["codes"][0]["code"], "fake");
    assert_eq!(results["codes"][0]["cases"][0]["code"], "fake");
    assert_eq!(results["codes"][0]["counts"]["not_expressible"], 4);
    // The builtin only measured is impact's own computation: not run for the other code.
    assert!(results["cases"][0]["metrics"]["law"].is_object());
    assert!(results["codes"][0]["cases"][0]["metrics"]["law"].is_null());
    let run = root.join("out/codes/fake/runs/suite/case/plate");
    for f in [
        "history.csv",
        "summary.json",
        "adapter.json",
        "scene.yaml",
        "fake.inp",
    ] {
        assert!(run.join(f).is_file(), "{f} not kept in {}", run.display());
    }
    let junit = std::fs::read_to_string(root.join("out/junit.xml")).unwrap();
    assert!(junit.contains("fake:suite/case"), "{junit}");
    // The fake code alone: its one failure is declared, N/E is no failure: exit 0.
    let (code, stdout, _) = verify(&root, "ok", &["--code", "fake"]);
    assert_eq!(code, 0, "{stdout}");
    let _ = std::fs::remove_dir_all(&root);
}

/// A case of the patch builtin, whose problem another code can solve.
const PATCH_CASE: &str = "id: c1
title: t
requirement: {id: REQ-1, text: The solver shall do a thing.}
category: code verification
scenes:
  patch: {builtin: patch, params: {element: q4-full}}
checks:
  - id: free-node
    title: the free node's force
    measure: {scene: patch, metric: free_node_force_rel}
    reference: {kind: analytical, value: 0.0, source: \"patch test\"}
    tolerance: {absolute: 1.0e-12, reason: \"test\"}
  - id: stress
    title: the stress at every point
    measure: {scene: patch, metric: stress_max_rel_error}
    reference: {kind: analytical, value: 0.0, source: \"patch test\"}
    tolerance: {absolute: 1.0e-12, reason: \"test\"}
  - id: rate
    title: impact's own central differences
    measure: {scene: patch, metric: rate_free_node_deviation_rel}
    reference: {kind: analytical, value: 0.0, source: \"patch test\"}
    tolerance: {absolute: 1.0e-10, reason: \"test\"}
";

/// A builtin with a problem form (the patch test) is the other code's to solve: the fake
/// code's fields are judged by the builtin's own rules (OK when exact; FAIL when its free
/// node carries 1 N, which a harness that judged impact's computation under the fake's name
/// would pass), the part it cannot give (impact's central differences) is N/E, and the problem
/// it was given is kept with its run.
#[test]
fn a_builtin_s_problem_is_solved_by_the_other_code() {
    let root = scratch("", 60.0);
    std::fs::write(
        root.join("verification/cases/suite/case/case.yaml"),
        PATCH_CASE,
    )
    .unwrap();
    let (code, stdout, stderr) = verify(&root, "ok", &["--code", "fake"]);
    assert_eq!(code, 0, "{stdout}\n{stderr}");
    assert_eq!(status(&stdout, "fake", "free-node"), "OK");
    assert_eq!(status(&stdout, "fake", "stress"), "OK");
    assert_eq!(status(&stdout, "fake", "rate"), "N/E");
    let kept = walk(&root.join("out/codes/fake"));
    let problem = kept
        .iter()
        .find(|p| p.ends_with("problem.json"))
        .unwrap_or_else(|| panic!("no problem.json kept: {kept:?}"));
    let text = std::fs::read_to_string(problem).unwrap();
    assert!(
        text.contains("\"element\": \"q4-full\"") && text.contains("\"prescribed_m\""),
        "{text}"
    );
    let (code, stdout, stderr) = verify(&root, "patch-fails", &["--code", "fake"]);
    assert_eq!(code, 1, "{stdout}\n{stderr}");
    assert_eq!(status(&stdout, "fake", "free-node"), "FAIL");
    assert_eq!(status(&stdout, "fake", "stress"), "OK");
    assert!(scratch_left(&root).is_empty(), "{:?}", scratch_left(&root));
    let _ = std::fs::remove_dir_all(root);
}

/// Every file under `dir`.
fn walk(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        let p = e.path();
        if p.is_dir() {
            out.extend(walk(&p));
        } else {
            out.push(p);
        }
    }
    out
}

#[test]
fn one_scene_file_read_by_two_cases_is_run_once() {
    let root = scratch(
        "suite/case/wrong: \"the fake code's own known failure\"\n",
        60.0,
    );
    // Two cases read one scene file through two relative paths, as the repository's cases
    // read verification/scenes/.
    let scenes = root.join("verification/scenes");
    std::fs::create_dir_all(&scenes).unwrap();
    std::fs::write(scenes.join("plate.yaml"), SCENE).unwrap();
    let shared = |id: &str| {
        CASE.replace("id: c1", &format!("id: {id}"))
            .replace("REQ-1", &format!("REQ-{id}"))
            .replace("{file: plate.yaml", "{file: ../../../scenes/plate.yaml")
    };
    std::fs::write(
        root.join("verification/cases/suite/case/case.yaml"),
        shared("c1"),
    )
    .unwrap();
    let second = root.join("verification/cases/suite/other");
    std::fs::create_dir_all(&second).unwrap();
    std::fs::write(second.join("case.yaml"), shared("c2")).unwrap();
    let adapter = root.join("adapters/fake/adapter.yaml");
    let yaml = std::fs::read_to_string(&adapter).unwrap();
    let yaml = yaml.replace("cases: [suite/case]", "cases: [suite/case, suite/other]");
    std::fs::write(&adapter, yaml).unwrap();
    let log = root.join("runs.log");
    let o = Command::new(env!("CARGO_BIN_EXE_impact"))
        .args(["verify", "--jobs", "1", "--code", "fake", "--root"])
        .arg(&root)
        .arg("--out")
        .arg(root.join("out"))
        .env("FAKE_MODE", "ok")
        .env("FAKE_LOG", &log)
        .env("TMPDIR", root.join("tmp"))
        .output()
        .expect("run impact");
    let stdout = String::from_utf8_lossy(&o.stdout);
    let deflections = stdout
        .lines()
        .filter(|l| l.starts_with("fake") && l.contains(" deflection ") && l.contains(" OK "));
    assert_eq!(deflections.count(), 2, "both cases judged\n{stdout}");
    // The plate and its refused variant, once each, for both cases.
    let runs = std::fs::read_to_string(&log).unwrap();
    assert_eq!(runs.lines().count(), 2, "{runs}\n{stdout}");
    let _ = std::fs::remove_dir_all(&root);
}

#[test]
fn an_undeclared_failure_of_the_other_code_exits_1() {
    let root = scratch("{}\n", 60.0);
    let (code, stdout, _) = verify(&root, "ok", &["--code", "fake"]);
    assert_eq!(code, 1, "{stdout}");
    assert_eq!(status(&stdout, "fake", "wrong"), "FAIL");
    let _ = std::fs::remove_dir_all(&root);
}

#[test]
fn a_refused_scene_is_not_expressible() {
    let root = scratch("{}\n", 60.0);
    let (code, stdout, _) = verify(&root, "refuse", &["--code", "fake"]);
    assert_eq!(code, 0, "{stdout}");
    for check in ["impulse", "deflection", "wrong", "unwritten", "builtin"] {
        assert_eq!(status(&stdout, "fake", check), "N/E", "{check}");
    }
    assert!(
        stdout.contains("not expressible: q4-full: no such element in fake"),
        "{stdout}"
    );
    let _ = std::fs::remove_dir_all(&root);
}

#[test]
fn a_crash_a_hang_and_garbage_are_one_clear_message_each() {
    for (mode, words, timeout) in [
        ("crash", "fake failed on", 60.0),
        ("crash", "*ERROR in fake: the deck is wrong", 60.0),
        ("hang", "killed after its time limit of 1 s", 1.0),
        (
            "garbage",
            "history.csv: row 3, column mid_uy_m: \"oops\" is not a number (field 2 of the row)",
            60.0,
        ),
    ] {
        let root = scratch("{}\n", timeout);
        let started = std::time::Instant::now();
        let (code, stdout, _) = verify(&root, mode, &["--code", "fake"]);
        assert!(
            started.elapsed().as_secs_f64() < 20.0,
            "{mode}: not bounded"
        );
        assert_eq!(code, 1, "{mode}: {stdout}");
        assert_eq!(status(&stdout, "fake", "impulse"), "FAIL", "{mode}");
        assert!(stdout.contains(words), "{mode}: no {words:?} in\n{stdout}");
        assert!(
            stdout.contains("plate.yaml"),
            "{mode}: the scene is not named\n{stdout}"
        );
        let left = scratch_left(&root);
        assert!(left.is_empty(), "{mode}: scratch folders left: {left:?}");
        let _ = std::fs::remove_dir_all(&root);
    }
}

#[test]
fn results_from_a_folder_are_checked_like_a_code() {
    let root = scratch("{}\n", 60.0);
    let dir = root.join("abaqus");
    let scene = dir.join("suite/case/plate");
    std::fs::create_dir_all(&scene).unwrap();
    std::fs::write(
        scene.join("history.csv"),
        "time_s,mid_uy_m\n0,0\n1e-4,-2e-3\n",
    )
    .unwrap();
    std::fs::write(scene.join("summary.json"), "{\"impulse_Ns\": 0.1}\n").unwrap();
    let (code, stdout, stderr) = verify(&root, "ok", &["--results-from", dir.to_str().unwrap()]);
    assert_eq!(code, 1, "{stdout}\n{stderr}");
    assert_eq!(status(&stdout, "abaqus", "impulse"), "OK");
    assert_eq!(status(&stdout, "abaqus", "deflection"), "OK");
    assert_eq!(status(&stdout, "abaqus", "wrong"), "FAIL");
    assert_eq!(status(&stdout, "abaqus", "unwritten"), "N/E");
    // A malformed summary names the file; a scene with no folder is N/E.
    std::fs::write(scene.join("summary.json"), "{\"impulse_Ns\": ").unwrap();
    let (_, stdout, _) = verify(&root, "ok", &["--results-from", dir.to_str().unwrap()]);
    assert!(stdout.contains("summary.json: EOF"), "{stdout}");
    std::fs::remove_dir_all(&scene).unwrap();
    let (code, stdout, _) = verify(&root, "ok", &["--results-from", dir.to_str().unwrap()]);
    assert_eq!(code, 0, "{stdout}");
    assert_eq!(status(&stdout, "abaqus", "impulse"), "N/E");
    assert!(
        stdout.contains("not produced: no folder suite/case/plate"),
        "{stdout}"
    );
    let _ = std::fs::remove_dir_all(&root);
}

#[test]
fn an_unknown_code_or_folder_is_refused_before_any_run() {
    let root = scratch("{}\n", 60.0);
    let (code, _, stderr) = verify(&root, "ok", &["--code", "abaqus"]);
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("--code abaqus: no adapter"), "{stderr}");
    assert!(stderr.contains("known: impact, fake"), "{stderr}");
    let (code, _, stderr) = verify(&root, "ok", &["--results-from", "/nonexistent"]);
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("not a folder"), "{stderr}");
    assert!(!root.join("out").exists(), "nothing is written");
    let _ = std::fs::remove_dir_all(&root);
}

#[test]
fn ctrl_c_stops_the_other_code_within_a_second_and_leaves_nothing() {
    let root = scratch("{}\n", 60.0);
    let mut child = Command::new(env!("CARGO_BIN_EXE_impact"))
        .args(["verify", "--jobs", "1", "--code", "fake", "--root"])
        .arg(&root)
        .arg("--out")
        .arg(root.join("out"))
        .env("FAKE_MODE", "hang")
        .env("TMPDIR", root.join("tmp"))
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .expect("run impact");
    // Wait until the adapter runs (its scratch folder exists), then SIGINT.
    let waited = std::time::Instant::now();
    while scratch_left(&root).is_empty() && waited.elapsed().as_secs() < 20 {
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    std::thread::sleep(std::time::Duration::from_millis(200));
    let sent = std::time::Instant::now();
    // SAFETY: kill(2) on our own child's pid.
    unsafe {
        libc::kill(child.id() as i32, libc::SIGINT);
    }
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        assert!(sent.elapsed().as_secs_f64() < 5.0, "not stopped");
        std::thread::sleep(std::time::Duration::from_millis(10));
    };
    assert!(
        sent.elapsed().as_secs_f64() < 1.5,
        "took {:?}",
        sent.elapsed()
    );
    assert_eq!(status.code(), Some(130));
    assert!(scratch_left(&root).is_empty(), "{:?}", scratch_left(&root));
    assert!(!root.join("out").exists(), "nothing is written");
    let _ = std::fs::remove_dir_all(&root);
}
