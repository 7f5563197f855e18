//! The `patch` builtin: the patch test of each element on a distorted 2 x 2 patch (a linear
//! field gives the exact constant stress and no force on the free node) and under a uniform
//! strain rate integrated by central differences.

use std::collections::BTreeMap;

use impact_solver::element::{
    element_max_eigenvalue, element_response, gather, lumped_masses, scatter_add, Formulation,
};
use impact_solver::material::Elastic;
use impact_solver::mesh::Mesh;
use impact_solver::model::AnyFormulation;
use impact_solver::scene::{ElementKind, DEFAULT_HOURGLASS};
use impact_solver::with_formulation;

use crate::definition::run_data::RunData;
use crate::run::builtin_params::{element_kind, param_str, Params};
use crate::run::code_verification::driver::distorted_patch;

pub(super) fn formulation(
    kind: ElementKind,
    mesh: &Mesh,
    width: f64,
    elastic: &Elastic,
) -> Result<AnyFormulation, String> {
    AnyFormulation::new(kind, mesh, width, DEFAULT_HOURGLASS, elastic).map_err(|e| e.to_string())
}

/// Internal forces of the whole mesh at `u`, and the max stress error against `exact`.
fn assemble<F: Formulation>(
    f: &F,
    elastic: &Elastic,
    u: &[f64],
    exact: Option<&[f64; 4]>,
) -> (Vec<f64>, f64) {
    let mut out = vec![0.0; u.len()];
    let mut stress_err: f64 = 0.0;
    for e in 0..f.n_elements() {
        let nodes = f.nodes(e);
        let ue = gather(nodes, u);
        let mut states = [(); 4];
        let (fe, _) = element_response(f, elastic, e, &ue, &mut states);
        scatter_add(nodes, &fe, &mut out);
        if let Some(s) = exact {
            let scale = s.iter().map(|x| x.abs()).fold(0.0, f64::max);
            for strain in f.strains(e, &ue).iter().take(F::POINTS) {
                let st = elastic.stress_of(strain);
                for c in 0..4 {
                    stress_err = stress_err.max((st[c] - s[c]).abs() / scale);
                }
            }
        }
    }
    (out, stress_err)
}

pub(super) fn patch(p: &Params) -> Result<RunData, String> {
    let kind = element_kind(param_str(p, "element", "q4-sri")?)?;
    let (e_mod, nu, rho, width) = (207e9, 0.3, 7850.0, 0.2);
    let elastic = Elastic::new(e_mod, nu);
    let mesh = distorted_patch();
    let form = formulation(kind, &mesh, width, &elastic)?;
    // Linear field u = a + G x with a general constant strain.
    let g = [[1.0e-3, 4.0e-4], [-2.0e-4, -6.0e-4]];
    let field = |x: [f64; 2]| {
        [
            1e-5 + g[0][0] * x[0] + g[0][1] * x[1],
            -2e-5 + g[1][0] * x[0] + g[1][1] * x[1],
        ]
    };
    let u: Vec<f64> = mesh.coords.iter().flat_map(|&x| field(x)).collect();
    let strain = [g[0][0], g[1][1], 0.0, g[0][1] + g[1][0]];
    let exact = elastic.stress_of(&strain);
    let free = 4usize;
    let (f, stress_err) = with_formulation!(&form, x => assemble(x, &elastic, &u, Some(&exact)));
    let boundary_max = (0..mesh.coords.len())
        .filter(|&n| n != free)
        .map(|n| f[2 * n].hypot(f[2 * n + 1]))
        .fold(0.0, f64::max);
    let mut m = BTreeMap::new();
    m.insert(
        "free_node_force_rel".into(),
        f[2 * free].hypot(f[2 * free + 1]) / boundary_max,
    );
    m.insert("stress_max_rel_error".into(), stress_err);
    // Global equilibrium of the boundary forces (sum of nodal forces = 0).
    let (sx, sy): (f64, f64) =
        (0..mesh.coords.len()).fold((0.0, 0.0), |a, n| (a.0 + f[2 * n], a.1 + f[2 * n + 1]));
    m.insert("force_sum_rel".into(), sx.hypot(sy) / boundary_max);

    // Uniform strain rate: boundary nodes follow v = G x / T; the free node, integrated by
    // central differences with its lumped mass, must stay on the linear field.
    let masses = with_formulation!(&form, x => lumped_masses(x, mesh.coords.len(), rho));
    let lambda_max = with_formulation!(&form, x => (0..x.n_elements()).map(|e| element_max_eigenvalue(x, &elastic, rho, e)).fold(0.0, f64::max));
    let dt = 0.5 * 2.0 / lambda_max.sqrt();
    let steps = 2000;
    let t_end = steps as f64 * dt;
    let rate = |x: [f64; 2], t: f64| {
        let s = t / t_end;
        let v = field(x);
        [v[0] * s, v[1] * s]
    };
    let mut u = vec![0.0; 2 * mesh.coords.len()];
    let x4 = mesh.coords[free];
    let mut v4 = [field(x4)[0] / t_end, field(x4)[1] / t_end];
    let mut dev: f64 = 0.0;
    for n in 0..steps {
        let t = n as f64 * dt;
        for (i, &x) in mesh.coords.iter().enumerate() {
            if i != free {
                let r = rate(x, t);
                u[2 * i] = r[0];
                u[2 * i + 1] = r[1];
            }
        }
        let (f, _) = with_formulation!(&form, x => assemble(x, &elastic, &u, None));
        for c in 0..2 {
            v4[c] += -f[2 * free + c] / masses[free] * dt;
            u[2 * free + c] += v4[c] * dt;
        }
        let r = rate(x4, t + dt);
        dev = dev.max((u[2 * free] - r[0]).hypot(u[2 * free + 1] - r[1]));
    }
    let scale = field(x4)[0].hypot(field(x4)[1]);
    m.insert("rate_free_node_deviation_rel".into(), dev / scale);
    Ok(RunData {
        metrics: m,
        ..Default::default()
    })
}
