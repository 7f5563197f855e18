//! Bad input gets one clear message naming the file, line and column, the field, the value
//! and what is allowed - never a panic - and leaves no output behind.
//!
//! Reference: the scene contract of docs/scene-reference.md / ALGORITHM.md (which values are allowed).

use std::path::{Path, PathBuf};

use impact_solver::output::simulate_to_dir;
use impact_solver::Scene;

const EXAMPLE: &str = include_str!("../../verification/scenes/example-elastic.yaml");

fn error_for(edit: impl Fn(&str) -> String) -> String {
    let text = edit(EXAMPLE);
    Scene::from_yaml(&text, Path::new("bad.yaml"))
        .err()
        .expect("the scene must be refused")
        .to_string()
}

fn assert_mentions(message: &str, parts: &[&str]) {
    for p in parts {
        assert!(message.contains(p), "{message:?} does not mention {p:?}");
    }
}

#[test]
fn the_example_scene_is_accepted_as_written() {
    let scene = Scene::from_yaml(EXAMPLE, Path::new("example.yaml")).unwrap();
    assert_eq!(scene.mesh.nx, 80);
    assert_eq!(scene.output.probes, vec![("A".to_string(), [0.1, 0.0])]);
}

#[test]
fn non_physical_values_name_line_column_field_value_and_range() {
    let e = error_for(|s| s.replace("density: 7850.0", "density: -7850.0"));
    assert_mentions(&e, &["bad.yaml:5:12", "material.density", "-7850", "> 0"]);
    let e = error_for(|s| s.replace("poisson_ratio: 0.3\nmesh", "poisson_ratio: 0.5\nmesh"));
    assert_mentions(
        &e,
        &[
            "bad.yaml:7:18",
            "material.poisson_ratio",
            "0.5",
            "(-1, 0.5)",
        ],
    );
    let e = error_for(|s| s.replace("thickness: 0.020", "thickness: 0.0"));
    assert_mentions(&e, &["bad.yaml:3:49", "plate.thickness", "> 0"]);
    let e = error_for(|s| s.replace("ny: 16", "ny: 1"));
    assert_mentions(&e, &["bad.yaml:8:", "mesh.ny", "= 1", "even integer in [2"]);
    let e = error_for(|s| s.replace("ny: 16", "ny: 3"));
    assert_mentions(&e, &["mesh.ny", "= 3", "mid-plane"]);
    let e = error_for(|s| s.replace("x: 0.100, y: 0.0", "x: 0.100, y: 0.05"));
    assert_mentions(
        &e,
        &[
            "bad.yaml:24:",
            "output.probes.A.y",
            "0.05",
            "plate.thickness",
        ],
    );
    let e = error_for(|s| s.replace("end: 3.0e-3 ", "end: -1 "));
    assert_mentions(&e, &["bad.yaml:20:", "time.end", "-1"]);
    let e = error_for(|s| s.replace("{cfl: 0.8}", "{cfl: 1.2}"));
    assert_mentions(&e, &["time.dt.cfl", "1.2", "(0, 1]"]);
    let e = error_for(|s| s.replace("{cfl: 0.8}", "{cfl: 0.8, fixed: 1.0e-7}"));
    assert_mentions(
        &e,
        &[
            "bad.yaml:21:",
            "time.dt",
            "both cfl and fixed",
            "exactly one",
        ],
    );
    let e = error_for(|s| s.replace("{cfl: 0.8}", "{estimate: global}"));
    assert_mentions(&e, &["time.dt", "neither cfl nor fixed"]);
    let e = error_for(|s| s.replace("{cfl: 0.8}", "{cfl: 0.8, estimate: exact}"));
    assert_mentions(&e, &["time.dt.estimate", "element", "global"]);
}

#[test]
fn the_stable_step_estimate_is_element_unless_asked() {
    use impact_solver::scene::DtChoice;
    use impact_solver::stable_step::Estimate;
    let plain = Scene::from_yaml(EXAMPLE, Path::new("example.yaml")).unwrap();
    assert_eq!(plain.time.dt_estimate, Estimate::Element);
    let text = EXAMPLE.replace("{cfl: 0.8}", "{cfl: 0.9, estimate: global}");
    let global = Scene::from_yaml(&text, Path::new("example.yaml")).unwrap();
    assert_eq!(global.time.dt_estimate, Estimate::Global);
    assert_eq!(global.time.dt, DtChoice::Cfl(0.9));
    // An override of the variant keeps the estimate, and the estimate keeps the variant.
    let o = [("time.dt.fixed".to_string(), serde_json::json!(1e-8))]
        .into_iter()
        .collect();
    let s = Scene::from_yaml_with(&text, &o, Path::new("example.yaml")).unwrap();
    assert_eq!(
        (s.time.dt, s.time.dt_estimate),
        (DtChoice::Fixed(1e-8), Estimate::Global)
    );
    let o = [("time.dt.estimate".to_string(), serde_json::json!("element"))]
        .into_iter()
        .collect();
    let s = Scene::from_yaml_with(&text, &o, Path::new("example.yaml")).unwrap();
    assert_eq!(
        (s.time.dt, s.time.dt_estimate),
        (DtChoice::Cfl(0.9), Estimate::Element)
    );
}

#[test]
fn structural_errors_name_line_and_column() {
    let e = error_for(|s| s.replace("density: 7850.0", "densty: 7850.0"));
    assert_mentions(
        &e,
        &["bad.yaml:5:3", "unknown field `densty`", "expected one of"],
    );
    let e = error_for(|s| s.replace("density: 7850.0", "density: heavy"));
    assert_mentions(&e, &["bad.yaml:5:12", "expected a number"]);
    let e = error_for(|s| s.replacen("  youngs_modulus: 207.0e9\n", "", 1));
    assert_mentions(&e, &["bad.yaml:", "missing field `youngs_modulus`"]);
    let e = error_for(|s| s.replace("mass: 18.0 ", "mass: 18.0\n    mass: 19.0 "));
    assert_mentions(&e, &["bad.yaml:12:5", "duplicate mapping key: mass"]);
    let e = error_for(|s| s.replace("q4-sri", "q4-quadratic"));
    assert_mentions(&e, &["bad.yaml:8:", "q4-quadratic"]);
    assert!(!e.contains("DuplicateKeyPolicy"));
    // kinematics: the two words, the wrong one named where it is.
    let e = error_for(|s| format!("{s}kinematics: large\n"));
    assert_mentions(
        &e,
        &["bad.yaml:", ":13", "kinematics", "large", "small", "finite"],
    );
    let ok = Scene::from_yaml(
        &format!("{EXAMPLE}kinematics: finite\n"),
        Path::new("k.yaml"),
    );
    assert_eq!(
        ok.unwrap().kinematics,
        impact_solver::scene::Kinematics::Finite
    );
}

/// `geometry: axisymmetric` and what it cannot run with, each refused at the key with the
/// way out (the example scene: the nodal contact law).
#[test]
fn the_axisymmetric_geometry_names_what_it_cannot_run_with() {
    let surface = |s: &str| {
        let start = s.find("    youngs_modulus: 207.0e9\n    poisson").unwrap();
        let end = s.find("  # instead of impactor").unwrap();
        format!("{}    contact: surface\n{}", &s[..start], &s[end..])
    };
    let e = error_for(|s| format!("{s}geometry: round\n"));
    assert_mentions(
        &e,
        &[
            "bad.yaml:",
            "geometry",
            "round",
            "plane-strain",
            "axisymmetric",
        ],
    );
    let e = error_for(|s| format!("{s}geometry: axisymmetric\n"));
    assert_mentions(&e, &["bad.yaml:26:11", "geometry", "contact: surface"]);
    let e = error_for(|s| {
        format!(
            "{}geometry: axisymmetric\n",
            surface(s).replace("model: half", "model: full")
        )
    });
    assert_mentions(&e, &["geometry", "axisymmetric", "mesh.model: half"]);
    let e = error_for(|s| {
        let global = surface(s).replace("{cfl: 0.8}", "{cfl: 0.8, estimate: global}");
        format!("{global}geometry: axisymmetric\n")
    });
    assert_mentions(&e, &["geometry", "estimate: element"]);
    let ok = Scene::from_yaml(
        &format!("{}geometry: axisymmetric\n", surface(EXAMPLE)),
        Path::new("round.yaml"),
    );
    assert_eq!(
        ok.unwrap().geometry,
        impact_solver::input::geometry::Geometry::Axisymmetric
    );
    let finite = Scene::from_yaml(
        &format!(
            "{}geometry: axisymmetric\nkinematics: finite\n",
            surface(EXAMPLE)
        ),
        Path::new("round.yaml"),
    );
    assert!(finite.is_ok(), "finite deformation runs in the ring");
}

fn scratch(name: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("impact-scene-errors-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn a_step_above_the_stable_limit_is_refused_before_any_output() {
    let dir = scratch("dt");
    let scene = dir.join("scene.yaml");
    std::fs::write(&scene, EXAMPLE.replace("{cfl: 0.8}", "{fixed: 1.0e-6}")).unwrap();
    let out = dir.join("out");
    let e = simulate_to_dir(&scene, &out, false)
        .unwrap_err()
        .to_string();
    assert_mentions(&e, &["scene.yaml:21:", "time.dt.fixed", "stable estimate"]);
    assert!(!out.exists(), "nothing may be written");
    assert_eq!(
        std::fs::read_dir(&dir).unwrap().count(),
        1,
        "no staging folder left"
    );
}

#[test]
fn a_run_that_fails_midway_leaves_nothing_behind() {
    // A hidden length of 10 um puts the law's maximum far below the first step's force.
    let dir = scratch("midway");
    let scene = dir.join("scene.yaml");
    std::fs::write(
        &scene,
        EXAMPLE
            .replace("length_unit: 1.0}", "length_unit: 1.0e-5}")
            .replace("nx: 80, ny: 16", "nx: 8, ny: 2"),
    )
    .unwrap();
    let out = dir.join("out");
    let e = simulate_to_dir(&scene, &out, false)
        .unwrap_err()
        .to_string();
    assert_mentions(&e, &["run stopped at step", "no root", "maximum"]);
    // The message names the law's maximum force, the input that exceeds it and the
    // alternative (issue 13).
    assert_mentions(
        &e,
        &[
            "with length_unit 1e-5 m",
            "its maximum is",
            "18 kg at 10 m/s carries 9.000e2 J",
            "contact_law: {johnson: {datum_depth: 0.01}}",
        ],
    );
    assert!(!out.exists());
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
}

/// Overrides are set at the scene's dotted YAML paths before validation: the same rules,
/// messages naming the override, and an unchanged scene where nothing is overridden.
#[test]
fn overrides_obey_the_scene_rules_and_name_the_override() {
    use impact_solver::overrides::Overrides;
    use impact_solver::scene::{DtChoice, End};
    let with = |pairs: &[(&str, serde_json::Value)]| {
        let o: Overrides = pairs
            .iter()
            .map(|(k, v)| (k.to_string(), v.clone()))
            .collect();
        Scene::from_yaml_with(EXAMPLE, &o, Path::new("example.yaml"))
    };
    let plain = Scene::from_yaml(EXAMPLE, Path::new("example.yaml")).unwrap();
    assert_eq!(with(&[]).unwrap(), plain);
    let e = with(&[("time.dt.cfl", 1.5.into())])
        .unwrap_err()
        .to_string();
    assert_mentions(
        &e,
        &[
            "example.yaml: override time.dt.cfl = 1.5",
            "time.dt.cfl = 1.5: must lie in (0, 1]",
        ],
    );
    let e = with(&[("mesh.nx", 40.into()), ("mesh.ny", 3.into())])
        .unwrap_err()
        .to_string();
    assert_mentions(&e, &["override mesh.ny = 3", "mesh.ny = 3", "even integer"]);
    let e = with(&[("load.impactor.mas", 1.0.into())])
        .unwrap_err()
        .to_string();
    assert_mentions(&e, &["override load.impactor.mas", "unknown field `mas`"]);
    let e = with(&[("mesh.element", "q5".into())])
        .unwrap_err()
        .to_string();
    assert_mentions(&e, &["override mesh.element", "q5", "q4-sri"]);
    let s = with(&[
        ("time.dt.fixed", 1e-8.into()),
        ("time.end.after_contact", 2e-4.into()),
        ("mesh.nx", 40.into()),
        ("load.impactor.mass", 9.0.into()),
    ])
    .unwrap();
    assert_eq!(s.time.dt, DtChoice::Fixed(1e-8));
    assert_eq!(
        s.time.end,
        End::AfterContact {
            after: 2e-4,
            limit: 0.05
        }
    );
    assert_eq!(s.mesh.nx, 40);
    assert_eq!(s.impactor().unwrap().mass, 9.0);
    let mut back = s.clone();
    back.time = plain.time.clone();
    back.mesh.nx = plain.mesh.nx;
    back.load = plain.load.clone();
    assert_eq!(back, plain, "nothing else changes");
}

#[test]
fn yaml_type_errors_name_the_field_and_the_expected_type() {
    let e = error_for(|s| s.replace("nx: 80", "nx: abc"));
    assert_mentions(&e, &["bad.yaml:8:12", "mesh.nx: expected an integer"]);
    let e = error_for(|s| s.replace("nx: 80", "nx: 8.5"));
    assert_mentions(&e, &["mesh.nx: expected an integer"]);
    let e = error_for(|s| s.replace("density: 7850.0", "density: heavy"));
    assert_mentions(
        &e,
        &["bad.yaml:5:12", "material.density: expected a number"],
    );
    let e = error_for(|s| s.replace("  # instead of impactor:  pulse", "  pulse"));
    assert_mentions(&e, &["load.pulse: load takes exactly one kind", "keep one"]);
    let e = error_for(|s| s.replace("mass: 18.0 ", "mass: [1] "));
    assert_mentions(&e, &["load.impactor.mass: expected a single value"]);
}

#[test]
fn a_feather_weight_impactor_is_reported_as_the_cause_of_the_instability() {
    let dir = scratch("light");
    let scene = dir.join("scene.yaml");
    std::fs::write(
        &scene,
        EXAMPLE
            .replace("mass: 18.0 ", "mass: 1.0e-12 ")
            .replace("nx: 80, ny: 16", "nx: 20, ny: 4"),
    )
    .unwrap();
    let e = simulate_to_dir(&scene, &dir.join("out"), false)
        .unwrap_err()
        .to_string();
    assert_mentions(
        &e,
        &[
            "unstable",
            "impactor's mass 1.000e-12 kg",
            "load.impactor.mass",
        ],
    );
}

#[test]
fn every_run_refuses_a_billion_elements_before_allocating() {
    // Not only the CLI's `simulate`: the library entry the harness and the Python package
    // call (`impact.simulate` without `out=`) estimates and refuses too, at once.
    let text = EXAMPLE.replace("nx: 80, ny: 16", "nx: 100000, ny: 10000");
    let scene = Scene::from_yaml(&text, Path::new("huge.yaml")).unwrap();
    let started = std::time::Instant::now();
    let err = impact_solver::simulate(&scene, &mut impact_solver::Quiet)
        .err()
        .expect("a 1e9-element run must be refused")
        .to_string();
    assert!(
        started.elapsed().as_secs_f64() < 1.0,
        "{:?}",
        started.elapsed()
    );
    assert_mentions(&err, &["1.00e9 elements", "GB of memory", "mesh.nx"]);
    // An explicit limit below a small run's estimate refuses it as well.
    let small = Scene::from_yaml(EXAMPLE, Path::new("example.yaml")).unwrap();
    let err = impact_solver::simulate_within(&small, &mut impact_solver::Quiet, Some(1.0e3))
        .err()
        .expect("a 1 kB limit must refuse")
        .to_string();
    assert_mentions(&err, &["--max-memory"]);
}

/// The example's impactor under the surface coupling: its nodal keys replaced by `contact`.
fn surface(s: &str, contact: &str) -> String {
    let start = s
        .find("    youngs_modulus: 207.0e9\n    poisson_ratio")
        .unwrap();
    let end = s.find("  # instead of impactor").unwrap();
    format!("{}    contact: {contact}\n{}", &s[..start], &s[end..])
}

#[test]
fn the_surface_coupling_is_read_with_its_options() {
    use impact_solver::scene::{Enforcement, Load};
    let read = |contact: &str| Scene::from_yaml(&surface(EXAMPLE, contact), Path::new("s.yaml"));
    let Load::SurfaceImpactor(i) = read("surface").unwrap().load else {
        panic!("contact: surface must give the surface coupling")
    };
    assert_eq!(i.contact.enforcement, Enforcement::Kinematic);
    let Load::SurfaceImpactor(i) = read("{surface: {enforcement: penalty, penalty_scale: 0.3}}")
        .unwrap()
        .load
    else {
        panic!("the penalty options must give the surface coupling")
    };
    assert_eq!(
        (i.contact.enforcement, i.contact.penalty_scale),
        (Enforcement::Penalty, 0.3)
    );
    assert!(
        matches!(read("nodal"), Err(_)),
        "nodal without its law is refused"
    );
}

#[test]
fn surface_coupling_errors_name_the_field_and_what_is_allowed() {
    let refused = |text: String| {
        Scene::from_yaml(&text, Path::new("bad.yaml"))
            .err()
            .expect("the scene must be refused")
            .to_string()
    };
    // A nodal key with the surface coupling: named where it is written.
    let e = refused(EXAMPLE.replace(
        "    indentation_datum: mid-plane",
        "    indentation_datum: mid-plane\n    contact: surface",
    ));
    assert_mentions(
        &e,
        &[
            "bad.yaml:14:",
            "load.impactor.youngs_modulus",
            "nodal coupling",
            "remove it",
        ],
    );
    let e = refused(
        surface(EXAMPLE, "surface")
            .replace("    contact:", "    force_node: top-surface\n    contact:"),
    );
    assert_mentions(
        &e,
        &["bad.yaml:14:", "load.impactor.force_node", "nodal coupling"],
    );
    // The nodal coupling without its law: named, with the way out.
    let e = refused(EXAMPLE.replace("    contact_law: {paper: {length_unit: 1.0}}", ""));
    assert_mentions(
        &e,
        &[
            "bad.yaml:11:",
            "load.impactor.contact_law",
            "missing",
            "contact: surface",
        ],
    );
    // Options that make no sense, values out of range, unknown words.
    let e = refused(surface(EXAMPLE, "{surface: {penalty_scale: 0.2}}"));
    assert_mentions(
        &e,
        &[
            "load.impactor.contact.surface.penalty_scale",
            "enforcement: penalty",
        ],
    );
    let e = refused(surface(
        EXAMPLE,
        "{surface: {enforcement: penalty, penalty_scale: 2.0}}",
    ));
    assert_mentions(
        &e,
        &["load.impactor.contact.surface.penalty_scale", "2", "(0, 1]"],
    );
    let e = refused(surface(EXAMPLE, "sticky"));
    assert_mentions(
        &e,
        &[
            "bad.yaml:14:",
            "unknown contact `sticky`",
            "`nodal`, `surface`",
        ],
    );
    let e = refused(surface(EXAMPLE, "{surface: {enforcement: glue}}"));
    assert_mentions(&e, &["bad.yaml:14:", "glue"]);
}

#[test]
fn a_time_step_that_makes_no_run_is_refused_before_the_run_naming_its_input() {
    // density 1e-300: a P-wave speed of inf m/s, a step of 0 s (the run never ended); 1e300:
    // a step of 5e141 s, which takes no step to time.end (the run hung in its first step);
    // density 1e-200: ~1e105 steps. The estimate refuses them before anything is allocated
    // (every run checks it), with the input and its value.
    for (density, words) in [
        (
            "1e-300",
            &[
                "material.density = 1e-300:",
                "comes out as 0.000e0 s",
                "P-wave speed inf",
            ][..],
        ),
        (
            "1e300",
            &["material.density = 1e300:", "the run would take no step"][..],
        ),
        (
            "1e-200",
            &[
                "material.density = 1e-200:",
                "time steps of",
                "more than the 1.00e12",
            ][..],
        ),
    ] {
        let text = EXAMPLE.replace("density: 7850.0", &format!("density: {density}"));
        let scene = Scene::from_yaml(&text, Path::new("steps.yaml")).unwrap();
        let estimate = impact_solver::budget::Estimate::of(&scene);
        let err = impact_solver::budget::check(&scene, &estimate, None)
            .err()
            .unwrap_or_else(|| panic!("density {density}: no refusal"))
            .to_string();
        // Named where the file writes it (line 5, column 12).
        assert!(
            err.starts_with("steps.yaml:5:12: material.density"),
            "{err}"
        );
        assert_mentions(&err, words);
        assert_mentions(
            &err,
            &["a run needs a finite time step > 0 s and 1 to 1.00e12 steps"],
        );
        let run = impact_solver::simulate(&scene, &mut impact_solver::Quiet);
        assert_eq!(run.err().map(|e| e.to_string()), Some(err));
    }
}

/// The example with `plate` as a block mapping (the example writes it as a flow mapping).
fn block_plate(s: &str) -> String {
    s.replace(
        "plate: {length: 0.200, width: 0.200, thickness: 0.020}",
        "plate:\n  length: 0.200\n  width: 0.200\n  thickness: 0.020",
    )
}

#[test]
fn a_missing_field_is_named_under_its_own_mapping_at_that_mapping() {
    let e = error_for(|s| block_plate(s).replace("\n  thickness: 0.020", ""));
    assert_mentions(&e, &["bad.yaml:3:1: plate: missing field `thickness`"]);
    let e = error_for(|s| s.replace("  density: 7850.0\n", ""));
    assert_mentions(&e, &["bad.yaml:4:1: material: missing field `density`"]);
    let e = error_for(|s| s.replace("    mass: 18.0 ", "#"));
    assert_mentions(&e, &["bad.yaml:10:3: load.impactor: missing field `mass`"]);
    let e = error_for(|s| s.replace("  dt: {cfl: 0.8}", "#"));
    assert_mentions(&e, &["bad.yaml:19:1: time: missing field `dt`"]);
    // A flow mapping: named as before, on its own line.
    let e = error_for(|s| s.replace(", thickness: 0.020", ""));
    assert_mentions(&e, &["bad.yaml:3:", "plate: missing field `thickness`"]);
    let e = error_for(|s| s.replace("{paper: {length_unit: 1.0}}", "{paper: {}}"));
    assert_mentions(
        &e,
        &[
            "bad.yaml:16:",
            "load.impactor.contact_law.paper: missing field `length_unit`",
        ],
    );
}

#[test]
fn a_missing_section_is_named_at_the_start_of_the_scene() {
    let e = error_for(|s| s.replace("plate: {length: 0.200, width: 0.200, thickness: 0.020}", ""));
    assert_mentions(
        &e,
        &[
            "bad.yaml:1:1: ",
            "no `plate` section",
            "material, mesh, load and time",
        ],
    );
    assert!(!e.contains("output"), "{e}");
}

#[test]
fn a_bad_end_time_says_what_end_takes() {
    for bad in ["soon", "{after: 1}"] {
        let e = error_for(|s| s.replace("end: 3.0e-3 ", &format!("end: {bad} ")));
        assert_mentions(&e, &["bad.yaml:20:", "time.end", "after_contact"]);
        assert!(!e.contains("untagged"), "{e}");
    }
}

#[test]
fn a_kind_written_wrongly_is_told_the_kinds() {
    let e = error_for(|s| s.replace("{paper: {length_unit: 1.0}}", "{[a]: 1}"));
    assert_mentions(
        &e,
        &[
            "load.impactor.contact_law: expected one kind written as a mapping",
            "{paper: {length_unit: m}}",
            "{johnson: {datum_depth: m}}",
        ],
    );
    assert!(!e.contains("externally tagged"), "{e}");
    let e = error_for(|s| s.replace("load:\n  impactor:", "load: [1]\nxload:\n  impactor:"));
    assert_mentions(
        &e,
        &[
            "bad.yaml:9:",
            "load: expected one kind",
            "impactor",
            "pulse",
            "traction",
        ],
    );
    assert!(!e.contains("externally tagged"), "{e}");
}

#[test]
fn a_second_document_is_refused_at_its_separator() {
    let e = error_for(|s| format!("{s}---\n{s}"));
    assert_mentions(
        &e,
        &[
            "bad.yaml:26:1: ",
            "a scene is one YAML document; found a second one (---) at line 26",
        ],
    );
    assert!(!e.contains("from_str_multiple"), "{e}");
}

#[test]
fn an_infinite_value_must_be_finite() {
    let e = error_for(|s| s.replace("end: 3.0e-3 ", "end: .inf "));
    assert_mentions(&e, &["bad.yaml:20:8", "time.end: must be a finite number"]);
    assert!(!e.contains("policy"), "{e}");
}

#[test]
fn an_unclosed_quote_says_where_the_string_starts() {
    let e = error_for(|s| format!("title: \"abc\n{s}"));
    assert_mentions(
        &e,
        &[
            "bad.yaml:1:8: ",
            "title: the quoted string that starts at line 1 column 8 is not closed",
        ],
    );
    assert!(!e.contains("integer"), "{e}");
    let e = error_for(|s| s.replace("element: q4-sri", "element: 'q4-sri"));
    assert_mentions(
        &e,
        &[
            "bad.yaml:8:",
            "mesh.element: the quoted string that starts at line 8 column",
            "not closed",
        ],
    );
}

const PLASTIC_EXAMPLE: &str = include_str!("../../verification/scenes/example-plastic.yaml");

/// The plastic example scene with its `hardening` line (line 10) followed by `rate` lines,
/// or with `yield_stress` and `hardening` replaced by `rate` lines (`johnson_cook`).
fn with_rate(rate: &str, keep_curve: bool) -> std::result::Result<Scene, String> {
    let curve = "    yield_stress: 250.0e6\n    hardening: {linear: 1.5e9}";
    let at = PLASTIC_EXAMPLE.find(curve).expect("the example's curve");
    let end = PLASTIC_EXAMPLE[at..].find('\n').unwrap() + at + 1;
    let end = PLASTIC_EXAMPLE[end..].find('\n').unwrap() + end;
    let kept = if keep_curve {
        &PLASTIC_EXAMPLE[at..end]
    } else {
        ""
    };
    let text = format!(
        "{}{kept}\n    rate:\n{rate}{}",
        &PLASTIC_EXAMPLE[..at],
        &PLASTIC_EXAMPLE[end..]
    );
    Scene::from_yaml(&text, Path::new("bad.yaml")).map_err(|e| e.to_string())
}

#[test]
fn rate_laws_are_read_and_bad_parameters_named() {
    use impact_solver::input::rate_law::RateLaw;
    let cs = with_rate("      cowper_symonds: {D: 40.4, q: 5}", true).unwrap();
    assert_eq!(
        cs.rate_law(),
        Some(&RateLaw::CowperSymonds { d: 40.4, q: 5.0 })
    );
    let jc = "      johnson_cook: {A: 806.0e6, B: 614.0e6, n: 0.168, C: 0.0089, reference_rate: 1.0, m: 1.1,\n        thermal: {initial_temperature: 293.15, melting_temperature: 1813.15, specific_heat: 473.0, taylor_quinney: 0.9}}";
    let s = with_rate(jc, false).unwrap();
    let p = s.material.plasticity.as_ref().unwrap();
    assert_eq!(p.yield_stress, 806e6);
    assert!(s.rate_law().unwrap().thermal().is_some());
    let e = with_rate("      cowper_symonds: {D: -40.4, q: 5}", true).unwrap_err();
    assert_mentions(
        &e,
        &[
            "bad.yaml:12:",
            "material.plasticity.rate.cowper_symonds.D",
            "-40.4",
            "> 0",
        ],
    );
    let e = with_rate("      cowper_symonds: {D: 40.4, q: 0}", true).unwrap_err();
    assert_mentions(&e, &["bad.yaml:12:", "cowper_symonds.q", "= 0", "exponent"]);
    let e = with_rate(
        &jc.replace("melting_temperature: 1813.15", "melting_temperature: 200.0"),
        false,
    )
    .unwrap_err();
    assert_mentions(
        &e,
        &[
            "bad.yaml:12:",
            "thermal.melting_temperature",
            "200",
            "above initial_temperature = 293.15 K",
        ],
    );
    let e = with_rate(&jc.replace(" m: 1.1,", ""), false).unwrap_err();
    assert_mentions(&e, &["johnson_cook.m", "missing", "needed with thermal"]);
    let e = with_rate(
        &jc.replace("taylor_quinney: 0.9", "taylor_quinney: 1.5"),
        false,
    )
    .unwrap_err();
    assert_mentions(&e, &["thermal.taylor_quinney", "1.5", "[0, 1]"]);
    let e = with_rate(jc, true).unwrap_err();
    assert_mentions(
        &e,
        &[
            "bad.yaml:9:",
            "material.plasticity.yield_stress",
            "left out",
            "johnson_cook",
        ],
    );
    let e = with_rate("      viscous: {D: 40.4}", true).unwrap_err();
    assert_mentions(
        &e,
        &["material.plasticity.rate", "cowper_symonds", "johnson_cook"],
    );
}
