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

use crate::codes::problem::{by_node, Fields, Problem};
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
            for strain in f.strains(e, &ue).iter().take(F::POINTS) {
                stress_err = stress_err.max(stress_error(&elastic.stress_of(strain), s));
            }
        }
    }
    (out, stress_err)
}

/// A point's stress `st` against the exact `s` (Pa): the largest component's error over the
/// largest exact component.
fn stress_error(st: &[f64; 4], s: &[f64; 4]) -> f64 {
    let scale = s.iter().map(|x| x.abs()).fold(0.0, f64::max);
    (0..4).fold(0.0, |m, c| m.max((st[c] - s[c]).abs() / scale))
}

/// The patch: Young's modulus (Pa), Poisson's ratio, density (kg/m^3), width (m).
const MATERIAL: (f64, f64, f64, f64) = (207e9, 0.3, 7850.0, 0.2);
/// The linear field's gradient `G` (u = a + G x).
const G: [[f64; 2]; 2] = [[1.0e-3, 4.0e-4], [-2.0e-4, -6.0e-4]];
/// The patch's interior node, the only free one.
const FREE: usize = 4;

/// The linear field `u = a + G x` at `x`, m.
fn field(x: [f64; 2]) -> [f64; 2] {
    [
        1e-5 + G[0][0] * x[0] + G[0][1] * x[1],
        -2e-5 + G[1][0] * x[0] + G[1][1] * x[1],
    ]
}

/// The plane-strain stress of the field's constant strain, Pa.
fn exact_stress(elastic: &Elastic) -> [f64; 4] {
    elastic.stress_of(&[G[0][0], G[1][1], 0.0, G[0][1] + G[1][0]])
}

/// The static patch test's metrics from the internal forces `f` (two per node, N) and the
/// largest relative stress error: the free node's force and the sum of all forces, each over
/// the largest boundary force.
fn static_metrics(f: &[f64], stress_err: f64) -> BTreeMap<String, f64> {
    let nodes = f.len() / 2;
    let boundary_max = (0..nodes)
        .filter(|&n| n != FREE)
        .map(|n| f[2 * n].hypot(f[2 * n + 1]))
        .fold(0.0, f64::max);
    let mut m = BTreeMap::new();
    m.insert(
        "free_node_force_rel".into(),
        f[2 * FREE].hypot(f[2 * FREE + 1]) / boundary_max,
    );
    m.insert("stress_max_rel_error".into(), stress_err);
    // Global equilibrium of the boundary forces (sum of nodal forces = 0).
    let (sx, sy): (f64, f64) =
        (0..nodes).fold((0.0, 0.0), |a, n| (a.0 + f[2 * n], a.1 + f[2 * n + 1]));
    m.insert("force_sum_rel".into(), sx.hypot(sy) / boundary_max);
    m
}

/// The static patch test as a problem another code solves (`crate::codes::problem`): every
/// node held on the linear field.
pub(super) fn patch_problems(p: &Params) -> Result<Vec<(&'static str, Problem)>, String> {
    Ok(vec![("", patch_problem(p)?)])
}

fn patch_problem(p: &Params) -> Result<Problem, String> {
    let element = param_str(p, "element", "q4-sri")?;
    element_kind(element)?;
    let (youngs_modulus, poisson_ratio, _, width_m) = MATERIAL;
    let mesh = distorted_patch();
    let prescribed_m = by_node(mesh.coords.iter().flat_map(|&x| field(x)).enumerate());
    Ok(Problem::plane_strain(
        element,
        width_m,
        (youngs_modulus, poisson_ratio),
        &mesh,
        prescribed_m,
        Vec::new(),
    ))
}

/// The static patch test's metrics from another code's `fields` (the strain-rate part is
/// `impact`'s central differences: not produced; nor are the force metrics when the code
/// gives no nodal forces).
pub(super) fn patch_from_fields(_: &Params, fields: &[Fields]) -> Result<RunData, String> {
    let [fields] = fields else {
        return Err(format!(
            "patch: {} fields for its one problem",
            fields.len()
        ));
    };
    let (youngs_modulus, poisson_ratio, _, _) = MATERIAL;
    let exact = exact_stress(&Elastic::new(youngs_modulus, poisson_ratio));
    let stress_err = fields
        .point_stresses
        .iter()
        .flatten()
        .fold(0.0, |m: f64, st| m.max(stress_error(st, &exact)));
    let metrics = match &fields.nodal_forces {
        Some(forces) => static_metrics(forces.as_flattened(), stress_err),
        None => BTreeMap::from([("stress_max_rel_error".to_string(), stress_err)]),
    };
    Ok(RunData {
        metrics,
        ..Default::default()
    })
}

pub(super) fn patch(p: &Params) -> Result<RunData, String> {
    let kind = element_kind(param_str(p, "element", "q4-sri")?)?;
    let (e_mod, nu, rho, width) = MATERIAL;
    let elastic = Elastic::new(e_mod, nu);
    let mesh = distorted_patch();
    let form = formulation(kind, &mesh, width, &elastic)?;
    let u: Vec<f64> = mesh.coords.iter().flat_map(|&x| field(x)).collect();
    let exact = exact_stress(&elastic);
    let free = FREE;
    let (f, stress_err) = with_formulation!(&form, x => assemble(x, &elastic, &u, Some(&exact)));
    let mut m = static_metrics(&f, stress_err);

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

#[cfg(test)]
mod tests {
    //! The patch test's problem form against the builtin itself: impact's own fields, written
    //! as another code writes them, give the builtin's static metrics bit for bit, so a code
    //! is judged by the same rules; 1 N on the free node fails the checks' 1e-12; the problem
    //! holds every node on the linear field.
    use super::*;
    use impact_solver::element::Formulation;
    use serde_json::Value;

    fn point_stresses<F: Formulation>(f: &F, elastic: &Elastic, u: &[f64]) -> Vec<Vec<[f64; 4]>> {
        (0..f.n_elements())
            .map(|e| {
                let ue = gather(f.nodes(e), u);
                let strains = f.strains(e, &ue);
                strains
                    .iter()
                    .take(F::POINTS)
                    .map(|s| elastic.stress_of(s))
                    .collect()
            })
            .collect()
    }

    /// impact's fields of the static patch test with `kind`.
    fn own_fields(kind: ElementKind) -> Fields {
        let (e_mod, nu, _, width) = MATERIAL;
        let elastic = Elastic::new(e_mod, nu);
        let mesh = distorted_patch();
        let form = formulation(kind, &mesh, width, &elastic).unwrap();
        let u: Vec<f64> = mesh.coords.iter().flat_map(|&x| field(x)).collect();
        let (f, _) = with_formulation!(&form, x => assemble(x, &elastic, &u, None));
        Fields {
            point_eqps: None,
            displacements: mesh.coords.iter().map(|&x| field(x)).collect(),
            nodal_forces: Some(f.chunks(2).map(|c| [c[0], c[1]]).collect()),
            point_stresses: with_formulation!(&form, x => point_stresses(x, &elastic, &u)),
        }
    }

    #[test]
    fn impact_s_own_fields_give_the_builtin_s_metrics() {
        for element in ["q4-full", "q4-sri", "q4-1pt"] {
            let p = Params::from([("element".to_string(), Value::from(element))]);
            let builtin = patch(&p).unwrap().metrics;
            let mut fields = own_fields(element_kind(element).unwrap());
            let evaluated = patch_from_fields(&p, std::slice::from_ref(&fields))
                .unwrap()
                .metrics;
            for k in [
                "free_node_force_rel",
                "stress_max_rel_error",
                "force_sum_rel",
            ] {
                assert_eq!(
                    builtin[k].to_bits(),
                    evaluated[k].to_bits(),
                    "{element} {k}"
                );
            }
            assert!(!evaluated.contains_key("rate_free_node_deviation_rel"));
            fields.nodal_forces.as_mut().unwrap()[FREE][0] += 1.0;
            let pushed = patch_from_fields(&p, &[fields]).unwrap().metrics;
            // 1 N over the largest boundary force (about 4e5 N): 2.4e-6, far above 1e-12.
            assert!(pushed["free_node_force_rel"] > 1e-7, "{element} {pushed:?}");
            let problem = patch_problem(&p).unwrap();
            assert_eq!(problem.prescribed_m.len(), 2 * problem.nodes_m.len());
            assert_eq!(problem.element, element);
        }
    }
}
