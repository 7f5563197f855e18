//! The manufactured elastodynamics problem run through the solver's own plate model
//! (element formulation, linear-kernel or stress-path internal forces, lumped masses and
//! stable-step estimate: [`PlateModel`]) with the central-difference update of
//! ALGORITHM.md section 6 (eqs. 8-12: half step at n = 0, `v_{n+1/2} = v_{n-1/2} + dt a_n`,
//! `u_{n+1} = u_n + dt v_{n+1/2}`), plus what the scene format has no words for: a body
//! force, initial displacement and velocity fields, and every boundary node held.

use impact_solver::element::{shape, Formulation};
use impact_solver::geometry::PointGeometry;
use impact_solver::integrator::PlateModel;
use impact_solver::material::Elastic;
use impact_solver::mesh::{Mesh, PlateMesh};
use impact_solver::model::AnyFormulation;
use impact_solver::scene::ElementKind;

use super::manufactured::Manufactured;

/// Hourglass coefficient of `q4-1pt` (the scene default).
const HOURGLASS_KAPPA: f64 = 0.05;

/// How the time step is set: a fraction of the stable estimate (rounded down so that the
/// end time is hit exactly), or a number of steps.
#[derive(Debug, Clone, Copy)]
pub enum Steps {
    Cfl(f64),
    Count(usize),
}

/// One run of the manufactured problem.
#[derive(Debug, Clone)]
pub struct Run {
    /// Largest over the time steps of the mass-weighted nodal L2 displacement error, relative
    /// to the mass-weighted L2 norm of the field's amplitude.
    pub l2_error: f64,
    /// Largest over the time steps and nodes of |u_h - u|, relative to the amplitude's max.
    pub max_error: f64,
    /// Nodal displacements at the end time, m.
    pub final_displacement: Vec<f64>,
    /// Lumped nodal masses, kg.
    pub mass: Vec<f64>,
    pub dt: f64,
    pub dt_critical: f64,
    pub steps: usize,
}

/// A structured nx x ny mesh of the rectangle, mapped by a smooth distortion that keeps the
/// boundary in place (`eps` = amplitude as a fraction of the side): for eps > 0 the elements
/// are not parallelograms, and become so only as h -> 0 (the asymptotic regime of a mapped
/// mesh).
pub fn mapped_mesh(
    length: f64,
    height: f64,
    nx: usize,
    ny: usize,
    eps: f64,
) -> Result<PlateMesh, String> {
    use std::f64::consts::PI;
    // The solver's structured full-plate mesh (node i + j (nx + 1)), then mapped and held.
    let text = format!(
        "plate: {{length: {length}, width: 1.0, thickness: {height}}}\n\
         material: {{density: 1.0, youngs_modulus: 1.0, poisson_ratio: 0.3}}\n\
         mesh: {{nx: {nx}, ny: {ny}, model: full}}\n\
         load: {{pulse: {{force: 1.0, duration: 1.0}}}}\n\
         time: {{end: 1.0, dt: {{cfl: 0.5}}}}\n"
    );
    let scene = impact_solver::Scene::from_yaml(&text, std::path::Path::new("(mapped mesh)"))
        .map_err(|e| e.to_string())?;
    let mut mesh = PlateMesh::new(&scene.plate, &scene.mesh);
    for (n, c) in mesh.mesh.coords.iter_mut().enumerate() {
        let (i, j) = (n % (nx + 1), n / (nx + 1));
        let (s, r) = (i as f64 / nx as f64, j as f64 / ny as f64);
        *c = [
            s * length + eps * length * (2.0 * PI * s).sin() * (PI * r).sin(),
            r * height + eps * height * (PI * s).sin() * (2.0 * PI * r).sin(),
        ];
        let boundary = i == 0 || j == 0 || i == nx || j == ny;
        mesh.fixed_dofs[2 * n] = boundary;
        mesh.fixed_dofs[2 * n + 1] = boundary;
    }
    Ok(mesh)
}

/// Runs the manufactured problem for one period `2 pi / omega` on `mesh` with `element`.
pub fn run(
    ms: &Manufactured,
    elastic: &Elastic,
    mesh: &PlateMesh,
    element: ElementKind,
    steps: Steps,
) -> Result<Run, String> {
    let any = AnyFormulation::new(element, &mesh.mesh, 1.0, HOURGLASS_KAPPA, elastic)
        .map_err(|e| e.to_string())?;
    impact_solver::with_formulation!(any, f => march(ms, elastic, mesh, f, steps))
}

/// Consistent nodal body force `int N_a b(x, 0) dV` (2x2 Gauss, width 1 m), N; the body
/// force of the manufactured solution is `b(x, 0) cos(w t)`.
fn body_force_vector(ms: &Manufactured, m: &Mesh) -> Vec<f64> {
    let g = 1.0 / 3f64.sqrt();
    let mut f = vec![0.0; 2 * m.n_nodes()];
    for (e, nodes) in m.elements.iter().enumerate() {
        let c = m.element_coords(e);
        for xi in [[-g, -g], [g, -g], [g, g], [-g, g]] {
            let n = shape(xi);
            let det_j = PointGeometry::at(&c, xi).det_j;
            let x = (0..4).fold([0.0, 0.0], |s, a| {
                [s[0] + n[a] * c[a][0], s[1] + n[a] * c[a][1]]
            });
            let b = ms.body_force(x, 0.0);
            for a in 0..4 {
                let k = nodes[a] as usize;
                f[2 * k] += n[a] * b[0] * det_j;
                f[2 * k + 1] += n[a] * b[1] * det_j;
            }
        }
    }
    f
}

fn march<F: Formulation>(
    ms: &Manufactured,
    elastic: &Elastic,
    mesh: &PlateMesh,
    formulation: F,
    steps: Steps,
) -> Result<Run, String> {
    let mut model = PlateModel::new(formulation, *elastic, mesh, ms.density);
    if F::STIFFNESS_MATRIX_PAYS {
        model = model.with_linear_kernel(elastic);
    }
    let dt_critical = model.critical_time_step(ms.density);
    let end = 2.0 * std::f64::consts::PI / ms.omega;
    let n_steps = match steps {
        Steps::Cfl(c) => (end / (c * dt_critical)).ceil() as usize,
        Steps::Count(n) => n,
    };
    let dt = end / n_steps as f64;
    let coords = &mesh.mesh.coords;
    let body = body_force_vector(ms, &mesh.mesh);
    let ndof = body.len();
    let mut u: Vec<f64> = coords
        .iter()
        .flat_map(|&x| ms.displacement(x, 0.0))
        .collect();
    let mut v: Vec<f64> = coords.iter().flat_map(|&x| ms.velocity(x, 0.0)).collect();
    let amplitude = u.clone();
    let mass = model.mass.clone();
    let norm_l2 = weighted_l2(&amplitude, &mass, |_, x| x);
    let norm_max = amplitude.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let mut f_int = vec![0.0; ndof];
    let (mut l2_error, mut max_error) = (0.0f64, 0.0f64);
    for n in 0..=n_steps {
        let t = n as f64 * dt;
        let g = (ms.omega * t).cos();
        let e_l2 = weighted_l2(&u, &mass, |d, x| x - amplitude[d] * g);
        let e_max = (0..ndof).fold(0.0f64, |a, d| a.max((u[d] - amplitude[d] * g).abs()));
        l2_error = l2_error.max(e_l2 / norm_l2);
        max_error = max_error.max(e_max / norm_max);
        if n == n_steps {
            break;
        }
        model.internal_forces(&u, &mut f_int);
        let half = if n == 0 { 0.5 } else { 1.0 };
        for d in 0..ndof {
            let a = (body[d] * g - f_int[d]) * model.inverse_mass[d];
            v[d] += half * dt * a;
            u[d] += dt * v[d];
        }
    }
    Ok(Run {
        l2_error,
        max_error,
        final_displacement: u,
        mass,
        dt,
        dt_critical,
        steps: n_steps,
    })
}

/// `sqrt(sum_a m_a |w_a|^2)` with `w_d = f(d, x_d)` (m on node a = d / 2).
pub fn weighted_l2(x: &[f64], mass: &[f64], f: impl Fn(usize, f64) -> f64) -> f64 {
    x.iter()
        .enumerate()
        .map(|(d, &xd)| mass[d / 2] * f(d, xd).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// A distorted 2x2 patch on [0, 0.02]^2: edge mid-nodes moved along the edges, the interior
/// node moved off-centre (MacNeal-Harder style). Node 4 is the only interior (free) node.
pub fn distorted_patch() -> Mesh {
    let coords = vec![
        [0.0, 0.0],
        [0.0085, 0.0],
        [0.02, 0.0],
        [0.0, 0.0115],
        [0.0123, 0.0082],
        [0.02, 0.0093],
        [0.0, 0.02],
        [0.0106, 0.02],
        [0.02, 0.02],
    ];
    let elements = vec![[0, 1, 4, 3], [1, 2, 5, 4], [3, 4, 7, 6], [4, 5, 8, 7]];
    Mesh { coords, elements }
}
