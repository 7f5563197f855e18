//! criterion benchmarks: the element kernels (internal force + material update) per element
//! type, elastic (precomputed stiffness and stress path) and plastic with every point
//! yielding, on the paper scene's 80x16 mesh; and a short whole run (time loop only).
//! Throughput is reported per element: criterion's "elem/s" is element-steps per second.

use std::path::Path;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use impact_solver::any_model::{build_any, AnyModel};
use impact_solver::mesh::PlateMesh;
use impact_solver::model::Kernel;
use impact_solver::scene::{ElementKind, End};
use impact_solver::simd::KernelPath;
use impact_solver::{simulate, Quiet, Scene};

const PLASTIC: &str = include_str!("../../verification/scenes/paper-plastic.yaml");

fn scene() -> Scene {
    Scene::from_yaml(PLASTIC, Path::new("paper-plastic.yaml")).unwrap()
}

/// Benchmarks the internal forces of `model` as `name`.
fn bench_kernel(c: &mut Criterion, name: &str, mesh: &PlateMesh, model: &mut dyn AnyModel) {
    // Uniform strain 1e-2 (~12x the yield strain 176 MPa / 207 GPa = 8.5e-4), reversed every call: every point yields.
    let u: Vec<f64> = mesh
        .mesh
        .coords
        .iter()
        .flat_map(|p| [1e-2 * p[0] + 5e-3 * p[1], -3e-3 * p[1]])
        .collect();
    let minus: Vec<f64> = u.iter().map(|x| -x).collect();
    let mut f = vec![0.0; u.len()];
    let mut flip = false;
    let mut group = c.benchmark_group("element-kernel");
    group.throughput(Throughput::Elements(model.n_elements() as u64));
    group.bench_function(name, |b| {
        b.iter(|| {
            flip = !flip;
            model.internal_forces(if flip { &u } else { &minus }, &mut f)
        })
    });
    group.finish();
}

fn kernels(c: &mut Criterion) {
    for element in ElementKind::ALL {
        let mut s = scene();
        s.mesh.element = element;
        let mesh = PlateMesh::new(&s.plate, &s.mesh);
        for (material, kernel) in [
            ("elastic", Kernel::ElasticStiffnessMatrix),
            ("elastic-stress-path", Kernel::ElasticStressPath),
            ("plastic-all-yielding", Kernel::Plastic),
        ] {
            let mut model = build_any(&s, &mesh, kernel, KernelPath::fastest()).unwrap();
            let name = format!("{}/{material}", element.name());
            bench_kernel(c, &name, &mesh, &mut *model);
        }
    }
}

fn whole_steps(c: &mut Criterion) {
    let mut s = scene();
    s.output.fields_every = None;
    s.output.every = Some(1e-4);
    s.time.end = End::At(2e-4);
    let probe = simulate(&s, &mut Quiet).unwrap().summary;
    let mut group = c.benchmark_group("time-step");
    group.throughput(Throughput::Elements(
        probe.n_elements as u64 * probe.n_steps,
    ));
    group.sample_size(10);
    group.bench_function("paper-plastic/q4-sri/0.2ms", |b| {
        b.iter_custom(|iters| {
            let mut total = std::time::Duration::ZERO;
            for _ in 0..iters {
                let o = simulate(&s, &mut Quiet).unwrap();
                total += std::time::Duration::from_secs_f64(o.summary.loop_time);
            }
            total
        })
    });
    group.finish();
}

criterion_group!(benches, kernels, whole_steps);
criterion_main!(benches);
