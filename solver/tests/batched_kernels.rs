//! The batched element kernels (`impact_solver::batch`, on this processor's best instruction
//! set) against the scalar kernels, the reference: forces, energies and material states must
//! be BIT-IDENTICAL, element by element and over whole runs.
//! - Element level: every element x material (elastic by stiffness matrix and by stress path,
//!   von Mises with linear and with tabulated hardening, with the elastic screen where the
//!   solver uses it; rate-dependent: Cowper-Symonds with a whole exponent (products) and with a
//!   real one on a table (`powf`), Johnson-Cook with heating), seeded random distorted meshes whose element counts are not multiples
//!   of the lane count (and span several chunks), random displacement fields that load some
//!   elements past yield while others stay elastic, unload them and reverse them.
//! - Whole runs: the example and paper scenes' summaries and histories, bit for bit, and the
//!   Table 1 plate with Cowper-Symonds and with Johnson-Cook and heating.
//! - Both kinematics: every combination above (but the small-strain stiffness matrices) also
//!   under finite deformation, and the Table 1 plate under finite deformation.
//! - Both geometries: every combination of either kinematics (but the stiffness matrices) also
//!   in the axisymmetric geometry, and the Table 1 plate under surface contact as a round
//!   plate, in small and in finite kinematics.
//! - Every model the factory builds above runs the function compiled for its (formulation,
//!   material) pair in the solver crate (`AnyModel::forces_compiled_here`).

use std::path::Path;

use impact_solver::any_model::{build_any, AnyModel};
use impact_solver::input::geometry::Geometry;
use impact_solver::input::rate_law::{johnson_cook_42crmo4, RateLaw};
use impact_solver::mesh::PlateMesh;
use impact_solver::model::Kernel;
use impact_solver::scene::{ElementKind, Hardening, Kinematics, Model, Plasticity};
use impact_solver::simd::{Isa, KernelPath, LANES};
use impact_solver::{simulate_on, History, Quiet, Scene};

const ELASTIC: &str = include_str!("../../verification/scenes/example-elastic.yaml");
const PLASTIC: &str = include_str!("../../verification/scenes/example-plastic.yaml");
const PAPER_ELASTIC: &str = include_str!("../../verification/scenes/paper-elastic.yaml");
const PAPER_PLASTIC: &str = include_str!("../../verification/scenes/paper-plastic.yaml");
const PAPER_SURFACE: &str = include_str!("../../verification/scenes/paper-plastic-surface.yaml");
const PAPER_COWPER_SYMONDS: &str =
    include_str!("../../verification/scenes/paper-plastic-cowper-symonds.yaml");

/// The plastic materials of the element-level comparison.
const PLASTIC_VARIANTS: [&str; 5] = [
    "linear",
    "table",
    "cowper-symonds",
    "cowper-symonds-table-real-q",
    "johnson-cook-heating",
];

/// A time step for the rate-dependent models (s); the fields below jump, so their rates are
/// huge: the solve's far end.
const RATE_DT: f64 = 1e-7;

const ELEMENTS: [ElementKind; 3] = [
    ElementKind::Q4Full,
    ElementKind::Q4Sri,
    ElementKind::Q4OnePoint,
];

/// A small deterministic generator (SplitMix64), uniform in [-1, 1).
struct Random(u64);
impl Random {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

/// Every bit a kernel call produces: nodal forces, energies and the material states.
fn trace_of(model: &mut dyn AnyModel, u: &[f64]) -> Vec<String> {
    let mut f = vec![0.0; u.len()];
    let e = model.internal_forces(u, &mut f);
    let mut out: Vec<String> = f.iter().map(|x| format!("{:016x}", x.to_bits())).collect();
    for x in [e.strain, e.plastic_work, e.hourglass] {
        out.push(format!("{:016x}", x.to_bits()));
    }
    // Debug prints each f64 in its shortest round-trip form (and -0.0 as such): equal
    // strings are equal bits.
    let points = model.points_per_element();
    out.extend(
        (0..model.n_elements())
            .flat_map(|e| (0..points).map(move |p| (e, p)))
            .map(|(e, p)| model.state_debug(e, p)),
    );
    out
}

/// The model of `s` with `kernel` on `path`, run on each displacement field in turn, every
/// call traced.
fn trace(
    s: &Scene,
    mesh: &PlateMesh,
    kernel: Kernel,
    path: KernelPath,
    u: &[Vec<f64>],
) -> Vec<Vec<String>> {
    let mut model = build_any(s, mesh, kernel, path).unwrap();
    // Every model the factory builds runs the function compiled for its pair in the solver
    // crate (`time_loop::internal_forces`), the code `impact` runs: a pair missing from that
    // list would run a copy compiled here, and the benchmarks would time other code.
    assert!(
        model.forces_compiled_here(),
        "{} {kernel:?} (rate-dependent: {}) {:?} {:?}: no function compiled in the solver crate for this pair",
        s.mesh.element.name(),
        s.material.plasticity.as_ref().is_some_and(|p| p.rate.is_some()),
        s.kinematics,
        s.geometry
    );
    model.set_time_step(RATE_DT);
    u.iter().map(|u| trace_of(&mut *model, u)).collect()
}

/// Displacement fields of random direction growing along x (elements near the clamp stay
/// elastic while those at mid-span yield): loading, unloading, reversal, reloading.
fn fields(mesh: &PlateMesh, random: &mut Random, length: f64) -> Vec<Vec<f64>> {
    let shape: Vec<f64> = mesh
        .mesh
        .coords
        .iter()
        .flat_map(|p| [p[0], p[0]])
        .zip(std::iter::repeat_with(|| random.next()))
        .map(|(x, r)| r * (x / length).powi(3))
        .collect();
    // Strain ~ amplitude / element size; yield strain ~1.2e-3.
    let h = length / mesh.mesh.elements.len() as f64;
    [0.02, 0.3, 1.0, 3.0, 10.0, 6.0, -2.0, -12.0, 0.0, 25.0]
        .iter()
        .map(|a| shape.iter().map(|s| a * 1.2e-3 * 30.0 * h * s).collect())
        .collect()
}

/// Johnson-Cook with heating: the DynELA Taylor bar's 42CrMo4 law, its curve scaled to yield
/// near the example plate's 250 MPa.
fn johnson_cook_heating() -> Plasticity {
    let ((_, _, n), law) = johnson_cook_42crmo4();
    Plasticity {
        yield_stress: 250e6,
        hardening: Hardening::Power {
            coefficient: 190e6,
            exponent: n,
        },
        rate: Some(law),
    }
}

/// The example plate's material as `variant` (one of [`PLASTIC_VARIANTS`]).
fn plastic_variant(variant: &str) -> Option<Plasticity> {
    let table = Hardening::Table(vec![(0.0, 250e6), (0.002, 290e6), (0.01, 320e6)]);
    let cowper_symonds = |q| Some(RateLaw::CowperSymonds { d: 40.4, q });
    let with = |hardening, rate| Plasticity {
        yield_stress: 250e6,
        hardening,
        rate,
    };
    match variant {
        "table" => Some(with(table, None)),
        "cowper-symonds" => Some(with(
            Hardening::Linear {
                tangent_modulus: 2e9,
            },
            cowper_symonds(5.0),
        )),
        "cowper-symonds-table-real-q" => Some(with(table, cowper_symonds(4.5))),
        "johnson-cook-heating" => Some(johnson_cook_heating()),
        _ => None,
    }
}

fn scene(nx: usize, ny: usize, element: ElementKind, seed: u64, variant: &str) -> Scene {
    let mut s = Scene::from_yaml(PLASTIC, Path::new("batched.yaml")).unwrap();
    s.mesh.nx = nx;
    s.mesh.ny = ny;
    s.mesh.element = element;
    s.mesh.distortion = 0.05 * (seed % 5) as f64;
    if let Some(p) = plastic_variant(variant) {
        s.material.plasticity = Some(p);
    }
    s
}

#[test]
fn batched_kernels_are_bit_identical_to_the_scalar_ones() {
    let batched = KernelPath::fastest();
    println!("batched path: {}", batched.name());
    let mut paths = vec![KernelPath::Batched(Isa::Baseline)];
    if batched != paths[0] {
        paths.push(batched);
    }
    let mut random = Random(12);
    let mut yielded_and_elastic = 0;
    for (case, (nx, ny)) in [(5, 3), (13, 6), (7, 5), (31, 4)].into_iter().enumerate() {
        // 15, 78, 35, 124 elements: partial batches, several chunks.
        assert!((nx * ny) % LANES != 0);
        for element in ELEMENTS {
            let elastic = [
                Kernel::Elastic,
                Kernel::ElasticStressPath,
                Kernel::ElasticStiffnessMatrix,
            ]
            .map(|k| (k, "linear"));
            let plastic = PLASTIC_VARIANTS.map(|v| (Kernel::Plastic, v));
            let variants = [
                (Kinematics::Small, Geometry::PlaneStrain),
                (Kinematics::Finite, Geometry::PlaneStrain),
                (Kinematics::Small, Geometry::Axisymmetric),
                (Kinematics::Finite, Geometry::Axisymmetric),
            ];
            let all = elastic
                .into_iter()
                .chain(plastic)
                .flat_map(|k| variants.map(|v| (k, v)));
            for ((kernel, table), (kinematics, geometry)) in all {
                let small_plane = (kinematics, geometry) == variants[0];
                if !small_plane && kernel == Kernel::ElasticStiffnessMatrix {
                    continue;
                }
                let mut s = scene(nx, ny, element, case as u64, table);
                s.kinematics = kinematics;
                s.geometry = geometry;
                if geometry == Geometry::Axisymmetric {
                    s.mesh.model = Model::Half;
                }
                let mesh = PlateMesh::of_scene(&s);
                let u = fields(&mesh, &mut random, s.plate.length);
                let reference = trace(&s, &mesh, kernel, KernelPath::Scalar, &u);
                for &path in &paths {
                    let traced = trace(&s, &mesh, kernel, path, &u);
                    for (call, (a, b)) in reference.iter().zip(&traced).enumerate() {
                        assert!(
                            a == b,
                            "{} {kernel:?} {table} {kinematics:?} {geometry:?} {nx}x{ny} call {call} on {}: differs",
                            element.name(),
                            path.name()
                        );
                    }
                }
                if kernel == Kernel::Plastic {
                    // The sweep must reach both branches: some points yielded, some not.
                    let states = reference.last().unwrap();
                    let virgin = states.iter().filter(|s| s.contains("eqps: 0.0 ")).count();
                    let plastic = states.iter().filter(|s| s.contains("eqps: ")).count() - virgin;
                    assert!(
                        virgin > 0 && plastic > 0,
                        "{virgin} virgin, {plastic} plastic"
                    );
                    yielded_and_elastic += 1;
                }
            }
        }
    }
    assert_eq!(yielded_and_elastic, 3 * 4 * 4 * PLASTIC_VARIANTS.len());
}

/// A whole run's summary without its timings, and its history.
fn run(scene: &Scene, path: KernelPath) -> (serde_json::Value, History) {
    let mut history = History::default();
    let (summary, _) = simulate_on(scene, &mut Quiet, None, &mut history, path).unwrap();
    let mut json = serde_json::to_value(&summary).unwrap();
    let map = json.as_object_mut().unwrap();
    for k in impact_solver::summary::TIMING_KEYS {
        map.remove(k);
    }
    (json, history)
}

#[test]
fn whole_runs_are_bit_identical_on_both_paths() {
    for (name, text) in [
        ("example-elastic", ELASTIC),
        ("example-plastic", PLASTIC),
        ("paper-elastic", PAPER_ELASTIC),
        ("paper-plastic", PAPER_PLASTIC),
        ("paper-plastic-cowper-symonds", PAPER_COWPER_SYMONDS),
        ("paper-plastic-johnson-cook-heating", PAPER_PLASTIC),
        ("paper-plastic-finite", PAPER_PLASTIC),
        ("paper-plastic-surface-axisymmetric", PAPER_SURFACE),
        ("paper-plastic-surface-axisymmetric-finite", PAPER_SURFACE),
    ] {
        let mut s = Scene::from_yaml(text, Path::new(name)).unwrap();
        if name.contains("axisymmetric") {
            s.geometry = Geometry::Axisymmetric;
            s.time.end = impact_solver::scene::End::At(1e-3);
        }
        if name.ends_with("finite") {
            s.kinematics = Kinematics::Finite;
        }
        if name.contains("johnson-cook") {
            s.material.plasticity = Some(johnson_cook_heating());
            s.time.end = impact_solver::scene::End::At(1e-3);
        }
        s.output.fields_every = None;
        let (summary, history) = run(&s, KernelPath::Scalar);
        let (summary_b, history_b) = run(&s, KernelPath::fastest());
        assert_eq!(summary, summary_b, "{name}: summaries differ");
        assert_eq!(history.columns, history_b.columns);
        assert!(history.n_rows() > 100, "{name}: {} rows", history.n_rows());
        let same = history
            .values
            .iter()
            .zip(&history_b.values)
            .all(|(a, b)| a.to_bits() == b.to_bits());
        assert!(
            same && history.values.len() == history_b.values.len(),
            "{name}: histories differ"
        );
    }
}
