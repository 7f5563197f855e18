//! `impact verify --baseline DIR` (issue 13) on a scratch repository whose one case runs a
//! small impact scene: verified once (the baseline), then with the scene deliberately changed
//! (impactor 10 -> 10.5 m/s, as a pull request might), the second results.json carries per
//! check the baseline value, the change and the change over the tolerance; what-changed.md
//! counts and lists the moved checks; the report opens with "What changed" and overlays the
//! moved history. Reference: the impulse scales with the impact momentum (+5 % velocity moves
//! it by several percent), and an unchanged scene moves nothing.

use std::path::{Path, PathBuf};
use std::process::Command;

const EXAMPLE: &str = include_str!("../scenes/example-elastic.yaml");

fn scratch(velocity: &str) -> PathBuf {
    let root = Path::new(env!("CARGO_TARGET_TMPDIR")).join("baseline-repo");
    let dir = root.join("verification/cases/suite/case");
    std::fs::create_dir_all(&dir).unwrap();
    let scene = EXAMPLE
        .replace("nx: 80, ny: 16", "nx: 20, ny: 4")
        .replace("end: 3.0e-3", "end: 6.0e-4")
        .replace("velocity: 10.0", &format!("velocity: {velocity}"))
        .replace("  fields: {every: 1.0e-4}", "");
    std::fs::write(dir.join("scene.yaml"), scene).unwrap();
    let yaml = "id: c1\ntitle: t\nrequirement: {id: REQ-1, text: The solver shall do a thing.}\n\
         category: code verification\nscenes:\n  run: {file: scene.yaml}\nchecks:\n\
         \x20 - id: impulse\n    title: impulse\n    measure: {scene: run, metric: impulse_Ns}\n\
         \x20   reference: {kind: regression, value: 358.4, source: \"pinned\"}\n\
         \x20   tolerance: {relative: 0.1, reason: \"a test of the baseline\"}\n\
         \x20 - id: elements\n    title: elements\n    measure: {scene: run, metric: n_elements}\n\
         \x20   reference: {kind: regression, value: 80, source: \"pinned\"}\n\
         \x20   tolerance: {absolute: 0.5, reason: \"a count\"}\n";
    std::fs::write(dir.join("case.yaml"), yaml).unwrap();
    root
}

fn verify(root: &Path, out: &Path, extra: &[&str]) -> String {
    let o = Command::new(env!("CARGO_BIN_EXE_impact"))
        .args(["verify", "--jobs", "1", "--report", "--root"])
        .arg(root)
        .arg("--out")
        .arg(out)
        .args(extra)
        .output()
        .unwrap();
    let text =
        String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr);
    assert!(o.status.code().unwrap_or(-1) <= 1, "{text}");
    text
}

#[test]
fn a_changed_scene_is_reported_check_by_check_against_the_baseline() {
    let root = scratch("10.0");
    let main = root.join("out-main");
    let text = verify(&root, &main, &[]);
    // Each case is announced as it finishes (issue 13, "say what is happening").
    assert!(
        text.contains("finished suite/case: 2 OK (1 run, "),
        "{text}"
    );
    let same = root.join("out-same");
    let text = verify(&root, &same, &["--baseline", main.to_str().unwrap()]);
    // 2 checks of the case and 7 of invariants/history-summary on its impact run.
    assert!(text.contains("9 unchanged, 0 moved within 10 % of their tolerance, 0 moved more, 0 changed status; 0 run histories moved"), "{text}");

    scratch("10.5");
    let branch = root.join("out-branch");
    let text = verify(&root, &branch, &["--baseline", main.to_str().unwrap()]);
    assert!(
        // the impulse and one invariants/history-summary check of the changed run moved
        // (the contact energy's sign and the counts of extremes, start and end values and stop
        // reason that disagree stay 0)
        text.contains("7 unchanged, 0 moved within 10 % of their tolerance, 2 moved more"),
        "{text}"
    );
    let results: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(branch.join("results.json")).unwrap())
            .unwrap();
    let check = &results["cases"][0]["checks"][0];
    assert_eq!(check["id"], "impulse");
    let b = &check["baseline"];
    let (now, before) = (
        check["computed"].as_f64().unwrap(),
        b["computed"].as_f64().unwrap(),
    );
    assert!((b["change"].as_f64().unwrap() - (now - before)).abs() < 1e-9);
    assert!(
        (0.03..0.07).contains(&((now - before) / before)),
        "{now} {before}"
    );
    // Allowance 0.1 x 358.4: a change of ~17.9 N s is ~50 % of it.
    let r = b["change_over_tolerance"].as_f64().unwrap();
    assert!((r - (now - before) / 35.84).abs() < 1e-9 && r > 0.1, "{r}");

    let page = std::fs::read_to_string(branch.join("what-changed.md")).unwrap();
    assert!(page.contains("| suite/case/impulse | OK -> OK |"), "{page}");
    assert!(page.contains("suite/case/run/history.csv"), "{page}");
    let html = std::fs::read_to_string(branch.join("index.html")).unwrap();
    let changed = html
        .find("<h2 id=\"changes\">What changed</h2>")
        .expect("section");
    assert!(
        changed < html.find("<h2 id=\"glance\">").unwrap(),
        "the report opens with it"
    );
    assert!(
        html[changed..].contains("data:image/svg+xml;base64,"),
        "the overlay is drawn"
    );
    assert!(
        page.contains("(contact_force_N; ISO/TS 18571 ") || page.contains("_J; ISO/TS 18571 "),
        "the moved column and its rating against the baseline: {page}"
    );
    // Each overlay is written once, beside the page that links it (the old report copied
    // them again into what-changed/what-changed/).
    let plots = std::fs::read_dir(branch.join("what-changed"))
        .unwrap()
        .count();
    assert!(plots > 0);
    assert!(!branch.join("what-changed/what-changed").exists());
    let _ = std::fs::remove_dir_all(&root);
}

/// A baseline that does not exist, or whose results.json is not the matrix's, is refused
/// before the first run (exit 2, nothing written), naming the file and the key, as
/// `impact report --from` refuses it. The old command ran the whole matrix first, and took
/// `{"cases": 3}` ("25 changed status", exit 0).
#[test]
fn a_missing_or_malformed_baseline_is_refused_before_anything_runs() {
    let root = Path::new(env!("CARGO_TARGET_TMPDIR")).join("baseline-refused");
    let _ = std::fs::remove_dir_all(&root);
    let bad = root.join("bad");
    std::fs::create_dir_all(&bad).unwrap();
    std::fs::write(bad.join("results.json"), "{\"cases\": 3}").unwrap();
    for (baseline, said) in [
        (
            root.join("nonexistent"),
            "results.json: run `impact verify --out DIR` first",
        ),
        (bad.clone(), "cases: expected an array, found a number"),
    ] {
        let out = root.join("out");
        let o = Command::new(env!("CARGO_BIN_EXE_impact"))
            .args(["verify", "no-such-suite", "--baseline"])
            .arg(&baseline)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(err.contains("--baseline") && err.contains(said), "{err}");
        assert!(
            !err.contains("no case matches"),
            "refused before the cases: {err}"
        );
        assert!(!out.exists(), "nothing written");
    }
    let _ = std::fs::remove_dir_all(&root);
}
