//! The lint runs inside `cargo test`: the repository's cases must be clean, each lint rule
//! must fire on a case that breaks it, and a malformed case.yaml must give file:line:column.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use impact_verification::case::{load_cases, parse_case};
use impact_verification::lint::lint;
use impact_verification::runner::Repo;

#[test]
fn the_repository_cases_are_lint_clean() {
    let repo = Repo::this();
    let (cases, errors) = load_cases(&repo.cases_dir());
    assert!(errors.is_empty(), "unreadable cases: {errors:#?}");
    assert!(
        cases.len() >= 8,
        "expected the eight suites, found {} cases",
        cases.len()
    );
    let findings = lint(&repo, &cases);
    let text: Vec<String> = findings.iter().map(|f| f.to_string()).collect();
    assert!(findings.is_empty(), "lint findings:\n{}", text.join("\n"));
    let refused: Vec<String> = cases
        .iter()
        .flat_map(impact_verification::run::plan::scene_problems)
        .collect();
    assert!(
        refused.is_empty(),
        "scenes refused:\n{}",
        refused.join("\n")
    );
    let suites: std::collections::BTreeSet<&str> = cases.iter().map(|c| c.suite.as_str()).collect();
    for s in [
        "patch",
        "wave-speed",
        "pulse-86.5kN",
        "hertz",
        "momentum-impulse",
        "table1",
        "energy",
        "convergence",
    ] {
        assert!(suites.contains(s), "suite {s} missing");
    }
}

static COUNTER: AtomicUsize = AtomicUsize::new(0);

/// A scratch repository with one case and a reference-data folder.
fn scratch(case_yaml: &str, provenance: bool) -> PathBuf {
    let root = std::env::temp_dir().join(format!(
        "impact-lint-{}-{}",
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::SeqCst)
    ));
    let _ = std::fs::remove_dir_all(&root);
    let dir = root.join("verification/cases/suite/case");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("case.yaml"), case_yaml).unwrap();
    let data = root.join("reference-data/thing");
    std::fs::create_dir_all(&data).unwrap();
    std::fs::write(data.join("table.csv"), "key,value\na,1.5\n").unwrap();
    if provenance {
        std::fs::write(data.join("PROVENANCE.md"), "made by hand\n").unwrap();
    }
    root
}

fn findings(yaml: &str, provenance: bool) -> Vec<String> {
    let root = scratch(yaml, provenance);
    let repo = Repo { root: root.clone() };
    let (cases, errors) = load_cases(&repo.cases_dir());
    assert!(errors.is_empty(), "{errors:?}");
    let f = lint(&repo, &cases).iter().map(|f| f.to_string()).collect();
    let _ = std::fs::remove_dir_all(root);
    f
}

const GOOD: &str = r#"
id: c1
title: t
requirement: {id: REQ-1, text: The solver shall do a thing.}
category: code verification
scenes:
  law: {builtin: hertz-law}
checks:
  - id: k1
    title: a check
    measure: {metric: round_trip_max_rel}
    reference: {kind: analytical, value: 0.0, source: "closed form"}
    tolerance: {absolute: 1.0e-12, reason: "round-off"}
  - id: k2
    title: a table check
    measure: {metric: round_trip_max_rel}
    reference: {kind: paper, table: {file: reference-data/thing/table.csv, row: {key: a}, column: value}, source: "a table"}
    tolerance: {relative: 0.1, reason: "printed digits"}
"#;

#[test]
fn a_good_case_is_clean() {
    assert_eq!(findings(GOOD, true), Vec::<String>::new());
}

#[test]
fn a_check_without_reference_kind_is_refused() {
    let f = findings(&GOOD.replace("kind: analytical, ", ""), true);
    assert!(
        f.iter()
            .any(|m| m.contains("check k1: the reference has no kind") && m.contains("case.yaml:")),
        "{f:?}"
    );
}

#[test]
fn a_tolerance_without_reason_is_refused() {
    let f = findings(&GOOD.replace(", reason: \"round-off\"", ""), true);
    assert!(
        f.iter()
            .any(|m| m.contains("check k1: the tolerance has no reason")),
        "{f:?}"
    );
    let f = findings(
        &GOOD.replace("reason: \"round-off\"", "reason: \"  \""),
        true,
    );
    assert!(
        f.iter()
            .any(|m| m.contains("check k1: the tolerance has no reason")),
        "{f:?}"
    );
}

#[test]
fn a_skip_without_reason_is_refused() {
    let yaml = GOOD.replace(
        "    title: a check\n",
        "    title: a check\n    skip: true\n",
    );
    let f = findings(&yaml, true);
    assert!(
        f.iter()
            .any(|m| m.contains("check k1: a skip needs a reason")),
        "{f:?}"
    );
    let yaml = GOOD.replace(
        "category: code verification\n",
        "category: code verification\nskip: \"\"\n",
    );
    let f = findings(&yaml, true);
    assert!(
        f.iter().any(|m| m.contains("a skip needs a reason")),
        "{f:?}"
    );
}

#[test]
fn a_reference_file_without_provenance_is_refused() {
    let f = findings(GOOD, false);
    assert!(
        f.iter()
            .any(|m| m.contains("check k2: reference file") && m.contains("no provenance")),
        "{f:?}"
    );
    assert!(
        f.iter()
            .any(|m| m.contains("table.csv: reference file without provenance")),
        "{f:?}"
    );
}

#[test]
fn duplicate_requirement_ids_are_refused() {
    let root = scratch(GOOD, true);
    let other = root.join("verification/cases/suite/other");
    std::fs::create_dir_all(&other).unwrap();
    std::fs::write(other.join("case.yaml"), GOOD.replace("id: c1", "id: c2")).unwrap();
    let repo = Repo { root: root.clone() };
    let (cases, _) = load_cases(&repo.cases_dir());
    let f: Vec<String> = lint(&repo, &cases).iter().map(|f| f.to_string()).collect();
    let _ = std::fs::remove_dir_all(root);
    assert!(
        f.iter()
            .any(|m| m.contains("duplicate requirement id \"REQ-1\"")),
        "{f:?}"
    );
}

#[test]
fn unknown_scenes_and_missing_reference_files_are_refused() {
    let f = findings(
        &GOOD.replace(
            "measure: {metric: round_trip_max_rel}\n    reference: {kind: analytical",
            "measure: {scene: nope, metric: x}\n    reference: {kind: analytical",
        ),
        true,
    );
    assert!(f.iter().any(|m| m.contains("no scene \"nope\"")), "{f:?}");
    let f = findings(&GOOD.replace("thing/table.csv", "thing/missing.csv"), true);
    assert!(f.iter().any(|m| m.contains("does not exist")), "{f:?}");
}

fn parse_error(yaml: &str) -> String {
    match parse_case(yaml, Path::new("cases/x/case.yaml")) {
        Ok(_) => panic!("expected an error for:\n{yaml}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn malformed_case_files_give_file_line_column() {
    // Unknown key on line 6 (GOOD starts with an empty line).
    let e = parse_error(&GOOD.replace(
        "category: code verification\n",
        "category: code verification\ncolour: red\n",
    ));
    assert!(e.starts_with("cases/x/case.yaml:6:"), "{e}");
    assert!(e.contains("colour"), "{e}");
    // Wrong type: a tolerance that is not a number.
    let e = parse_error(&GOOD.replace("absolute: 1.0e-12", "absolute: tiny"));
    // Named as the field it is, in the scene parser's plain words (issue 28).
    assert!(
        e.starts_with("cases/x/case.yaml:13:27: checks[0].tolerance.absolute: expected a number"),
        "{e}"
    );
    // Unknown category.
    let e = parse_error(&GOOD.replace("code verification", "vibes"));
    assert!(e.starts_with("cases/x/case.yaml:5:"), "{e}");
    // Broken YAML syntax.
    let e = parse_error("id: [unclosed\ntitle: x\n");
    assert!(e.starts_with("cases/x/case.yaml:"), "{e}");
    // Missing field.
    let e = parse_error("id: x\ntitle: y\n");
    assert!(e.contains("cases/x/case.yaml"), "{e}");
}

/// A case's `report:` block (what the report shows of it): a known part parses, an unknown
/// key or an unknown part is refused with file:line:col and what was written.
#[test]
fn report_blocks_refuse_unknown_keys_and_parts() {
    let with = |block: &str| format!("{GOOD}report:\n{block}");
    let c = parse_case(
        &with("  table: paper-table1\n  plots: [energy-balance]\n  reading: [literal-error]\n"),
        Path::new("cases/x/case.yaml"),
    )
    .unwrap();
    let r = c.report.unwrap();
    assert_eq!(
        r.table,
        Some(impact_verification::case::PaperTable::PaperTable1)
    );
    assert_eq!(r.plots.len(), 1);
    // `report:` is line 19 (GOOD starts with an empty line), its first key line 20.
    let e = parse_error(&with("  tables: paper-table1\n"));
    assert!(e.starts_with("cases/x/case.yaml:20:"), "{e}");
    assert!(e.contains("tables"), "{e}");
    let e = parse_error(&with("  table: paper-table3\n"));
    assert!(e.starts_with("cases/x/case.yaml:20:"), "{e}");
    assert!(e.contains("paper-table3"), "{e}");
}

/// One scene language: a case's `set:` override goes through the solver's own validation
/// (reference: the solver's rule for `time.dt.cfl`, "must lie in (0, 1]").
#[test]
fn an_override_the_scene_rules_refuse_is_refused_with_the_solvers_message() {
    let scene = include_str!("../scenes/example-elastic.yaml");
    let yaml = GOOD.replace(
        "  law: {builtin: hertz-law}\n",
        "  law: {builtin: hertz-law}\n  fast: {file: scene.yaml, set: {time.dt.cfl: 1.5}}\n",
    );
    let root = scratch(&yaml, true);
    let dir = root.join("verification/cases/suite/case");
    std::fs::write(dir.join("scene.yaml"), scene).unwrap();
    let (cases, errors) = load_cases(&root.join("verification/cases"));
    assert!(errors.is_empty(), "{errors:?}");
    let refused = impact_verification::jobs::case_jobs(&cases[0]).unwrap_err();
    let accepted = {
        std::fs::write(
            dir.join("case.yaml"),
            yaml.replace("time.dt.cfl: 1.5", "time.dt.cfl: 0.5, mesh.element: q4-1pt"),
        )
        .unwrap();
        let (cases, _) = load_cases(&root.join("verification/cases"));
        impact_verification::jobs::case_jobs(&cases[0])
    };
    let _ = std::fs::remove_dir_all(root);
    for part in [
        "case.yaml:",
        "override time.dt.cfl = 1.5",
        "time.dt.cfl = 1.5: must lie in (0, 1] (fraction of the stable step)",
    ] {
        assert!(refused.contains(part), "{refused:?} lacks {part:?}");
    }
    let jobs = accepted.unwrap();
    let Some(impact_verification::jobs::Job::Scene { scene, .. }) = jobs.get("fast") else {
        panic!("no scene job `fast`");
    };
    assert_eq!(
        scene.time.dt,
        impact_solver::scene::DtChoice::Cfl(0.5),
        "the override is applied"
    );
    assert_eq!(
        scene.mesh.element,
        impact_solver::scene::ElementKind::Q4OnePoint
    );
}

/// `impact lint` loads every scene with its overrides before anything runs: each refused
/// scene is named (not only the first), and a wrong model's overrides on top are checked too
/// (reference: the solver's rule for `mesh.ny`, "must be an even integer").
#[test]
fn lint_names_every_scene_and_wrong_model_the_scene_reader_refuses() {
    let scene = include_str!("../scenes/example-elastic.yaml");
    let with = |scenes: &str, wrong: &str| {
        GOOD.replace(
            "  law: {builtin: hertz-law}\n",
            &format!("  law: {{builtin: hertz-law}}\n{scenes}"),
        ) + wrong
    };
    let problems = |yaml: &str| {
        let root = scratch(yaml, true);
        let dir = root.join("verification/cases/suite/case");
        std::fs::write(dir.join("scene.yaml"), scene).unwrap();
        let (cases, errors) = load_cases(&root.join("verification/cases"));
        assert!(errors.is_empty(), "{errors:?}");
        let p = impact_verification::run::plan::scene_problems(&cases[0]);
        let _ = std::fs::remove_dir_all(root);
        p
    };
    let two_bad = with(
        "  a: {file: scene.yaml, set: {mesh.ny: 27}}\n  b: {file: scene.yaml, set: {time.dt.cfl: 1.5}}\n",
        "",
    );
    let p = problems(&two_bad);
    assert_eq!(p.len(), 2, "{p:#?}");
    assert!(
        p[0].contains("override mesh.ny = 27") && p[0].contains("even integer"),
        "{p:#?}"
    );
    assert!(p[1].contains("override time.dt.cfl = 1.5"), "{p:#?}");
    let wrong = with(
        "  a: {file: scene.yaml, set: {mesh.ny: 8}}\n",
        "wrong_models:\n  odd: {title: an odd mesh, set: {mesh.ny: 9}, scenes: [a]}\n",
    );
    let p = problems(&wrong);
    assert_eq!(p.len(), 1, "{p:#?}");
    assert!(p[0].contains("mesh.ny = 9"), "{p:#?}");
    let good = with("  a: {file: scene.yaml, set: {mesh.ny: 8}}\n", "");
    assert_eq!(problems(&good), Vec::<String>::new());
}

/// `not_compared` (issue 40): every row of a measurement table the validation cases read is
/// compared by a check or declared left out with why, never both; a declared row must exist.
/// Each rule is shown to fire on the slip it targets, and a whole account is clean.
#[test]
fn every_row_of_a_measurement_table_is_compared_or_declared_left_out() {
    // Rows a (compared by k3), b and c (declared or not).
    let experiment = r#"  - id: k3
    title: a measured value
    measure: {scene: law, metric: round_trip_max_rel}
    reference: {kind: experiment, table: {file: reference-data/thing/shots.csv, row: {shot: a}, column: value}, source: "a test"}
    validation:
      experiment: {relative: 0.01, reason: "repeats"}
      numerical: {scene: law, reason: "a coarser mesh"}
"#;
    let with = |not_compared: &str| {
        let root = scratch(&format!("{GOOD}{experiment}{not_compared}"), true);
        std::fs::write(
            root.join("reference-data/thing/shots.csv"),
            "shot,value\na,1.0\nb,2.0\nc,3.0\n",
        )
        .unwrap();
        let repo = Repo { root: root.clone() };
        let (cases, errors) = load_cases(&repo.cases_dir());
        assert!(errors.is_empty(), "{errors:?}");
        let f: Vec<String> = lint(&repo, &cases).iter().map(|f| f.to_string()).collect();
        let _ = std::fs::remove_dir_all(root);
        f
    };
    let entry = |rows: &str| {
        format!("not_compared:\n  - {{file: reference-data/thing/shots.csv, key: shot, rows: [{rows}], why: \"the mesh inverts\"}}\n")
    };
    assert_eq!(with(&entry("b, c")), Vec::<String>::new());
    // Each slip and the words of its finding.
    let slips: [(String, [&str; 2]); 6] = [
        (
            entry("b"),
            [
                "1 row(s) neither compared by a check nor declared",
                "shot = c",
            ],
        ),
        (String::new(), ["2 row(s) neither", "shot = b, c"]),
        (
            entry("a, b, c"),
            [
                "not_compared: shot = a is compared by the check at",
                "case.yaml",
            ],
        ),
        (
            entry("b, c, d"),
            ["not_compared:", "no row with shot = \"d\""],
        ),
        (
            entry("b, c, b"),
            ["shot = b is declared already at", "case.yaml"],
        ),
        (
            entry("b, c").replace("the mesh inverts", " "),
            ["says why it is left out", "not_compared:"],
        ),
    ];
    for (declaration, words) in slips {
        let f = with(&declaration);
        assert!(
            f.iter().any(|m| words.iter().all(|w| m.contains(w))),
            "{declaration}: {f:?}"
        );
    }
}
