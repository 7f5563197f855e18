//! Element-kernel throughput (ns per element-step) and whole-run times, against the targets
//! of the speed issue: q4-1pt elastic <= 5 ns, q4-sri elastic <= 6 ns, q4-sri with every
//! point yielding <= 30 ns, q4-sri in a plastic scene that never yields <= 1.3x its elastic
//! kernel, the elasto-plastic Table 1 run at the default mesh < 0.5 s; and of the strain-rate
//! issue: Cowper-Symonds with every point yielding <= 1.5x the rate-independent kernel,
//! Johnson-Cook with heating <= 2.5x (issue 39's; the strain-rate issue's was 2x); and of the
//! finite-deformation issue: the elasto-plastic kernel under finite deformation (q4-sri, every
//! point yielding) <= 1.5x the small-strain one. Issue 39's whole runs (full size only, one
//! thread): the Table 1 plate with Cowper-Symonds <= 1.3x the rate-independent run, the
//! 42CrMo4 Taylor bar <= 0.25 s.
//! The axisymmetric rows (the same 80 x 16 section as a round plate's, every point yielding,
//! small and finite kinematics) have no target: they show what the ring costs (measured
//! 2026-11-26, quick, two helpers compiling: q4-sri 32 ns small, 150 ns finite, whose F-bar
//! takes a cube root per point lane by lane, against 61 ns for the plane finite kernel then).
//!
//! The rate laws (2026-11-29, quick, min of 2 runs interleaved with the previous binary): the
//! Johnson-Cook kernel with heating 593 -> 268 ns (9.1x the rate-independent 29.6 ns; target
//! 2x, missed), Cowper-Symonds 127 -> 90 ns (3.0x; target 1.5x, missed), after `ln`, `exp` and
//! `pow` ran on the lanes (`lanes::transcendental`, in place of libm one lane at a time) and
//! the Newton residuals were inlined into the vector kernel (a closure had been left out of
//! line, compiled for SSE2). Here every call reverses the strain, so Newton's start from the
//! last step's increment does not help as it does in a run (a copper Taylor bar: 3.5 iterations
//! per batched call against 11.6, the whole run 7.2 -> 2.4 s); what remains is the iterations'
//! count and each one's `ln`, two `exp` and two divisions per lane.
//! On an Intel Xeon with full-width AVX-512 units (2026-11-30, full size, one thread) each law
//! in its own out-of-line function, on whole 512-bit registers (the shared function had run
//! the 8 lanes in pieces of 2, 2 and 4): Cowper-Symonds 113.9 -> 87.5 ns, Johnson-Cook with
//! heating 304.0 -> 213.3 ns, the same bits (`docs/benchmarks.md`).
//!
//! The plane finite kernel (2026-11-26, quick, min of 3 runs interleaved with the previous
//! binary, other builds on the second core): 53.4 ns against 29.7 ns small-strain, 1.80x
//! (60.2 ns, 2.03x, before each point's F-bar factor was computed one point ahead); elastic
//! 35.6 ns (43.9). Missed, and not reachable with the same arithmetic: per batch of 8 it
//! does ~1400 512-bit floating-point operations (~740 of them multiplies; the small-strain
//! kernel ~825 and ~410), from the step's midpoint and end rotations and inverses, F-bar's
//! factor and `P = tau F^-T` (~85 more multiplies per point, ~26 for the centroid), and the
//! processor retires one 512-bit multiply per cycle: at its 2.6 GHz both kernels now keep
//! the multiply pipe ~66 % busy, and 1.5x would take ~79 %. Both are bound by each point's chain of
//! dependent operations (`perf annotate`: the samples pile up after the divisions and square
//! roots), so the rest is fewer operations, which changes the finite results' bits.

use std::path::Path;
use std::time::Instant;

use impact_solver::any_model::{build_any, AnyModel};
use impact_solver::input::rate_law::{johnson_cook_42crmo4, RateLaw};
use impact_solver::mesh::PlateMesh;
use impact_solver::model::Kernel;
use impact_solver::scene::{ElementKind, Hardening, Scene};
use impact_solver::simd::KernelPath;
use impact_solver::workers;

use crate::common::{
    markdown_table, paper, taylor_bar, taylor_bar_42crmo4, timed_on, write_csv, Timing,
};

/// A displacement field of uniform strain `amplitude` (xx) and `amplitude/2` (shear).
fn uniform_strain(mesh: &PlateMesh, amplitude: f64) -> Vec<f64> {
    mesh.mesh
        .coords
        .iter()
        .flat_map(|p| {
            [
                amplitude * p[0] + 0.5 * amplitude * p[1],
                -0.3 * amplitude * p[1],
            ]
        })
        .collect()
}

/// Best ns per element over `reps` batches of `calls` internal-force evaluations,
/// alternating between `u` and `-u` (for plastic materials: every point yields every call).
fn kernel_ns(model: &mut dyn AnyModel, u: &[f64], calls: usize, reps: usize) -> f64 {
    let minus: Vec<f64> = u.iter().map(|x| -x).collect();
    let mut f = vec![0.0; u.len()];
    let mut best = f64::INFINITY;
    for rep in 0..=reps {
        let started = Instant::now();
        let mut sink = 0.0;
        for c in 0..calls {
            sink += model
                .internal_forces(if c % 2 == 0 { u } else { &minus }, &mut f)
                .strain;
        }
        std::hint::black_box(sink);
        if rep > 0 {
            best = best.min(started.elapsed().as_secs_f64());
        }
    }
    1e9 * best / (calls * model.n_elements()) as f64
}

/// The plastic paper scene with the rate law of `material` (a name of [`MATERIALS`]): mild
/// steel's Cowper-Symonds (D = 40.4 1/s, q = 5), or Johnson-Cook with heating (the DynELA
/// Taylor bar's 42CrMo4: A = 806 MPa, B = 614 MPa, n = 0.168, C = 0.0089, m = 1.1).
fn with_rate_law(mut scene: Scene, material: &str) -> Scene {
    let Some(p) = scene.material.plasticity.as_mut() else {
        return scene;
    };
    if material.contains("cowper-symonds") {
        p.rate = Some(RateLaw::CowperSymonds { d: 40.4, q: 5.0 });
    } else if material.contains("johnson-cook") {
        let ((a, b, n), law) = johnson_cook_42crmo4();
        p.yield_stress = a;
        p.hardening = Hardening::Power {
            coefficient: b,
            exponent: n,
        };
        p.rate = Some(law);
    }
    scene
}

/// The kernels timed, per element.
const MATERIALS: [&str; 11] = [
    "elastic",
    "elastic-stiffness-matrix",
    "elastic-stress-path",
    "plastic-never-yielding",
    "plastic-all-yielding",
    "plastic-cowper-symonds-all-yielding",
    "plastic-johnson-cook-heating-all-yielding",
    "elastic-finite",
    "plastic-finite-all-yielding",
    "axisymmetric-plastic-all-yielding",
    "axisymmetric-plastic-finite-all-yielding",
];

struct Case {
    element: ElementKind,
    material: &'static str,
}

/// ns per element-step of `case`'s kernel on `path`, the model built for `threads` threads
/// (the assembly runs the plastic stress path on several only on meshes of at least
/// `PARALLEL_MIN_ELEMENTS`; the elastic kernels always run on one).
fn measure(case: &Case, quick: bool, path: KernelPath, threads: usize) -> f64 {
    let mut scene = with_rate_law(paper(case.material != "elastic"), case.material);
    scene.mesh.element = case.element;
    if case.material.contains("finite") {
        scene.kinematics = impact_solver::scene::Kinematics::Finite;
    }
    // The same section as a round plate's (the kernels only: no load runs).
    if case.material.starts_with("axisymmetric") {
        scene.geometry = impact_solver::input::geometry::Geometry::Axisymmetric;
    }
    let mesh = PlateMesh::new(&scene.plate, &scene.mesh);
    let (calls, reps) = if quick { (20, 2) } else { (400, 5) };
    // Strain 1e-2 is 12x the yield strain of the plastic paper scene (176 MPa / 207 GPa): every
    // point yields; 1e-5 is 1/80 of it: a plastic scene where nothing yields.
    let amplitude = if case.material == "plastic-never-yielding" {
        1e-5
    } else {
        1e-2
    };
    let u = uniform_strain(&mesh, amplitude);
    let kernel = match case.material {
        "elastic" => Kernel::Elastic,
        "elastic-stiffness-matrix" => Kernel::ElasticStiffnessMatrix,
        "elastic-stress-path" | "elastic-finite" => Kernel::ElasticStressPath,
        _ => Kernel::Plastic,
    };
    // The model takes its thread count where it is built.
    workers::with_threads(threads, || {
        let mut model =
            build_any(&scene, &mesh, kernel, path).expect("the paper scenes build every model");
        // A rate-dependent material is told 0.8 of the stable step.
        model.set_time_step(0.8 * model.critical_time_step(scene.material.density));
        kernel_ns(&mut *model, &u, calls, reps)
    })
}

pub fn run(out: &Path, quick: bool) -> anyhow::Result<()> {
    let mut rows = Vec::new();
    for element in [
        ElementKind::Q4Full,
        ElementKind::Q4Sri,
        ElementKind::Q4OnePoint,
    ] {
        let (mut elastic_ns, mut yielding_ns) = (f64::NAN, f64::NAN);
        for material in MATERIALS {
            let case = Case { element, material };
            // Interleaved, so that both see the same load on the shared machine. The targets
            // are per core: one thread; the plastic kernels also on two (what a run uses).
            let scalar_ns = measure(&case, quick, KernelPath::Scalar, 1);
            let ns = measure(&case, quick, KernelPath::fastest(), 1);
            let two_threads_ns = (material.contains("plastic"))
                .then(|| measure(&case, quick, KernelPath::fastest(), 2));
            match material {
                "elastic" => elastic_ns = ns,
                "plastic-all-yielding" => yielding_ns = ns,
                _ => {}
            }
            let target_ns = match (element, material) {
                (ElementKind::Q4OnePoint, "elastic") => Some(5.0),
                (ElementKind::Q4Sri, "elastic") => Some(6.0),
                (ElementKind::Q4Sri, "plastic-never-yielding") => Some(1.3 * elastic_ns),
                (ElementKind::Q4Sri, "plastic-all-yielding") => Some(30.0),
                (ElementKind::Q4Sri, "plastic-cowper-symonds-all-yielding") => {
                    Some(1.5 * yielding_ns)
                }
                // Issue 39's target (the strain-rate issue's was 2x).
                (ElementKind::Q4Sri, "plastic-johnson-cook-heating-all-yielding") => {
                    Some(2.5 * yielding_ns)
                }
                (ElementKind::Q4Sri, "plastic-finite-all-yielding") => Some(1.5 * yielding_ns),
                _ => None,
            };
            rows.push(vec![
                element.name().to_string(),
                material.to_string(),
                format!("{ns:.1}"),
                format!("{:.3e}", 1e9 / ns),
                target_ns.map_or("-".into(), |t| format!("<= {t:.1}")),
                target_ns.map_or("-".into(), |t| {
                    if ns <= t {
                        "met".into()
                    } else {
                        "missed".into()
                    }
                }),
                format!("{scalar_ns:.1}"),
                KernelPath::fastest().name(),
                two_threads_ns.map_or("-".into(), |ns| format!("{ns:.1}")),
            ]);
        }
    }
    let header = [
        "element",
        "material",
        "ns_per_element_step",
        "element_steps_per_s",
        "target_ns",
        "status",
        "scalar_ns_per_element_step",
        "kernel_path",
        "ns_per_element_step_2_threads",
    ];
    write_csv(&out.join("throughput-kernels.csv"), &header, &rows)?;
    println!(
        "Element kernels (internal force + material update), 80x16 mesh, one thread (ns_per_element_step_2_threads: the plastic kernels on two, wall time per element-step; 'elastic' is the path the solver uses, the stiffness matrix for every element, the faster one: compare elastic-stress-path; ns_per_element_step on the batched kernels, scalar_ns_per_element_step on the scalar reference, interleaved, bit-identical results):\n{}",
        markdown_table(&header, &rows)
    );

    let (runs, rust_runs) = whole_runs(quick)?;
    let header = [
        "run",
        "setup_s",
        "loop_s",
        "steps",
        "ns_per_element_step",
        "target",
        "status",
        "runs",
        "loop_spread",
    ];
    write_csv(&out.join("throughput-runs.csv"), &header, &runs)?;
    println!(
        "Whole runs (Table 1 paper scenes, 80x16 q4-sri, 3 ms; without --quick also the Taylor bar, 10x36 q4-sri, 80 us, its step fixed at cfl 0.02 and re-estimated every step at cfl 0.8, and the re-estimation's own cost per element-step, the difference of the two, and on one thread the plastic Table 1 plate without and with Cowper-Symonds (target 1.3x) and the 42CrMo4 Taylor bar (target 0.25 s), their targets on setup + loop; best of the runs; loop_spread: slowest / fastest loop - 1):\n{}",
        markdown_table(&header, &runs)
    );
    python_side_by_side(out, quick, &rust_runs)
}

/// Per run: its row of the whole-run table, and (kind, Rust wall time s, impulse N s) of the
/// batched runs for the Python side by side.
type WholeRuns = (Vec<Vec<String>>, Vec<(&'static str, f64, f64)>);

/// The Table 1 paper scenes, elastic and elasto-plastic, and the elasto-plastic one on the
/// scalar kernels (the reference of the batched ones: the same bits, before/after timing).
fn whole_runs(quick: bool) -> anyhow::Result<WholeRuns> {
    let mut runs = Vec::new();
    // Per run: (kind, Rust wall time s, impulse N s), for the Python side by side.
    let mut rust_runs = Vec::new();
    for (plastic, path) in [
        (false, KernelPath::fastest()),
        (true, KernelPath::fastest()),
        (true, KernelPath::Scalar),
    ] {
        let scene = paper(plastic);
        let timing = timed_on(&scene, if quick { 1 } else { 3 }, path)?;
        let (setup, time_loop, s) = (timing.setup, timing.time_loop, &timing.outcome.summary);
        let scalar = path == KernelPath::Scalar;
        if !scalar {
            rust_runs.push((
                if plastic { "plastic" } else { "elastic" },
                setup + time_loop,
                s.impulse,
            ));
        }
        let name = match (plastic, scalar) {
            (false, _) => "table1-elastic",
            (true, false) => "table1-elasto-plastic",
            (true, true) => "table1-elasto-plastic-scalar-kernels",
        };
        let target = (plastic && !scalar).then_some(0.5);
        runs.push(run_row(name, &timing, target));
    }
    if !quick {
        // What the step re-estimated at every step saves (case taylor-bar/adaptive-step: the
        // same final length within 3e-5); 1-5 s a run, so the main job's only.
        let mut per_element_step = Vec::new();
        for (every_step, name) in [
            (false, "taylor-bar-fixed-cfl-0.02"),
            (true, "taylor-bar-every-step-cfl-0.8"),
        ] {
            let timing = timed_on(&taylor_bar(every_step), 3, KernelPath::fastest())?;
            runs.push(run_row(name, &timing, None));
            per_element_step.push(ns_per_element_step(&timing));
        }
        // The re-estimation's own cost: the every-step run's time per element-step less the
        // fixed-step run's (the same bar over the same time, its steps doing the same work);
        // the other columns of a run do not apply.
        let re_estimation = per_element_step[1] - per_element_step[0];
        let mut row = vec!["taylor-bar-step-re-estimation".to_string()];
        row.extend(["-", "-", "-"].map(String::from));
        row.push(format!("{re_estimation:.1}"));
        row.extend(["-", "-", "-", "-"].map(String::from));
        runs.push(row);
        runs.extend(one_thread_runs()?);
    }
    Ok((runs, rust_runs))
}

/// Issue 39's whole-run targets, on one thread (best of 5 runs each): the Table 1 plate with
/// Cowper-Symonds (mild steel, D = 40.4 1/s, q = 5) at most 1.3x the rate-independent run
/// (setup and loop), and DynELA's Johnson-Cook Taylor bar of 42CrMo4 in at most 0.25 s.
fn one_thread_runs() -> anyhow::Result<Vec<Vec<String>>> {
    let one =
        |scene: &Scene| workers::with_threads(1, || timed_on(scene, 5, KernelPath::fastest()));
    let independent = one(&paper(true))?;
    let cowper_symonds = one(&with_rate_law(paper(true), "cowper-symonds"))?;
    let bound = 1.3 * (independent.setup + independent.time_loop);
    Ok(vec![
        run_row("table1-elasto-plastic-1-thread", &independent, None),
        run_row(
            "table1-cowper-symonds-1-thread",
            &cowper_symonds,
            Some((bound * 1e4).round() / 1e4),
        ),
        run_row(
            "taylor-bar-42crmo4-every-step-1-thread",
            &one(&taylor_bar_42crmo4())?,
            Some(0.25),
        ),
    ])
}

/// The time loop's wall time per element and step of a timed run, ns.
fn ns_per_element_step(timing: &Timing) -> f64 {
    let s = &timing.outcome.summary;
    1e9 * timing.time_loop / (s.n_steps as f64 * s.n_elements as f64)
}

/// A row of the whole-run table for the run `name` timed as `timing`, against a `target` wall
/// time (s) if it has one.
fn run_row(name: &str, timing: &Timing, target: Option<f64>) -> Vec<String> {
    let (setup, time_loop, s) = (timing.setup, timing.time_loop, &timing.outcome.summary);
    vec![
        name.to_string(),
        format!("{setup:.4}"),
        format!("{time_loop:.4}"),
        format!("{}", s.n_steps),
        format!("{:.1}", ns_per_element_step(timing)),
        target.map_or("-".into(), |t| format!("< {t} s")),
        match target {
            None => "-",
            Some(t) if setup + time_loop < t => "met",
            Some(_) => "missed",
        }
        .into(),
        format!("{}", timing.runs),
        format!("{:.3}", timing.spread),
    ]
}

/// The same scene in the Rust solver and in the independent Python FE (scripts/indep_fe, run
/// with the project's .venv): wall times and their ratio, and the impulse of each as evidence
/// that both ran the same problem. Python runs `reference-data/independent/scenes/table1-*`,
/// the file form of the whole runs' `paper()` scenes (history every 1e-5 s, no fields), whose
/// Rust times and impulses `rust_runs` carries. Without the venv, a row says so.
fn python_side_by_side(
    out: &Path,
    quick: bool,
    rust_runs: &[(&str, f64, f64)],
) -> anyhow::Result<()> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("the benchmarks crate lives in the workspace");
    let python = root.join(".venv/bin/python");
    let compared = if quick { &rust_runs[..1] } else { rust_runs };
    let mut rows = Vec::new();
    for &(kind, rust_s, rust_impulse) in compared {
        let scene_path = root.join(format!(
            "reference-data/independent/scenes/table1-{kind}.yaml"
        ));
        let name = format!("table1-{kind}");
        if !python.is_file() {
            rows.push(vec![
                name,
                format!("{rust_s:.3}"),
                "-".into(),
                "-".into(),
                "-".into(),
                "-".into(),
                "not run: .venv missing (scripts/setup-venv.sh)".into(),
            ]);
            continue;
        }
        let work = out.join(format!("python-{kind}"));
        let started = Instant::now();
        let status = std::process::Command::new(&python)
            .args(["-m", "indep_fe", "simulate"])
            .arg(&scene_path)
            .arg("--out")
            .arg(&work)
            .env("PYTHONPATH", root.join("scripts"))
            .stdout(std::process::Stdio::null())
            .status()?;
        let process_s = started.elapsed().as_secs_f64();
        anyhow::ensure!(
            status.success(),
            "indep_fe failed on {}",
            scene_path.display()
        );
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(work.join("summary.json"))?)?;
        let python_s = summary["wall_time_s"].as_f64().unwrap_or(f64::NAN);
        let python_impulse = summary["impulse_Ns"].as_f64().unwrap_or(f64::NAN);
        let impulse_diff = (python_impulse / rust_impulse - 1.0).abs();
        rows.push(vec![
            name,
            format!("{rust_s:.3}"),
            format!("{python_s:.3}"),
            format!("{process_s:.3}"),
            format!("{:.1}", python_s / rust_s),
            format!("{impulse_diff:.1e}"),
            "same scene file, same element, mesh and dt".into(),
        ]);
        std::fs::remove_dir_all(&work)?;
    }
    let header = [
        "scene",
        "rust_s",
        "python_solver_s",
        "python_process_s",
        "python_over_rust",
        "impulse_rel_diff",
        "note",
    ];
    write_csv(&out.join("throughput-python.csv"), &header, &rows)?;
    println!(
        "The same scene in the independent Python FE (solver wall time from its summary.json; the process adds interpreter start-up and imports):\n{}",
        markdown_table(&header, &rows)
    );
    Ok(())
}
