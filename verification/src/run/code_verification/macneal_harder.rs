//! The `macneal-harder-patch` builtin: the five-element distorted patch of MacNeal & Harder
//! (1985, "A proposed standard set of problems to test finite element accuracy", Finite
//! Elements in Analysis and Design 1:3-20, fig. 2), rectangle 0.24 x 0.12 with interior nodes
//! (0.04, 0.02), (0.18, 0.03), (0.16, 0.08), (0.08, 0.08), E = 1e6, nu = 0.25, under the
//! linear field u = 1e-3 (x + y/2), v = 1e-3 (y + x/2) (strains exx = eyy = gxy = 1e-3).
//! - Test A: the four corner nodes displaced by the field, the interior free: a static solve.
//! - Test B: the corners loaded by the consistent nodal forces of the exact stress, three
//!   dofs held against rigid motion (at the field's values): a static solve of all others.
//! - Test C (out-of-plane bending) needs a plate element: not applicable to plane Q4s.
//! Each test is solved twice, with the global stiffness probed column by column from the
//! solver's stress path (`element_response`) and from its precomputed linear kernel
//! (`LinearKernel`); the stresses at every integration point come from the solver's
//! constitutive code and are compared, in the case, with values computed by hand from E and
//! nu (plane strain: sxx = syy = 1600 Pa, sxy = 400 Pa, szz = 800 Pa).

use std::collections::BTreeMap;

use impact_solver::element::{element_response, gather, scatter_add, Formulation};
use impact_solver::material::Elastic;
use impact_solver::mesh::Mesh;
use impact_solver::model::AnyFormulation;
use impact_solver::stiffness::LinearKernel;
use nalgebra::{DMatrix, DVector};
use serde_json::Value;

use crate::codes::problem::{by_node, Fields, Problem};
use crate::definition::run_data::RunData;

/// E (Pa), nu and the out-of-plane thickness (m) of the benchmark.
const E: f64 = 1.0e6;
const NU: f64 = 0.25;
const THICKNESS: f64 = 0.001;

/// Nodes: corners 0-3, interior 4-7; five elements, counter-clockwise.
pub fn patch_mesh() -> Mesh {
    Mesh {
        coords: vec![
            [0.0, 0.0],
            [0.24, 0.0],
            [0.24, 0.12],
            [0.0, 0.12],
            [0.04, 0.02],
            [0.18, 0.03],
            [0.16, 0.08],
            [0.08, 0.08],
        ],
        elements: vec![
            [0, 1, 5, 4],
            [1, 2, 6, 5],
            [2, 3, 7, 6],
            [3, 0, 4, 7],
            [4, 5, 6, 7],
        ],
    }
}

fn field(x: [f64; 2]) -> [f64; 2] {
    [1e-3 * (x[0] + 0.5 * x[1]), 1e-3 * (x[1] + 0.5 * x[0])]
}

/// Which internal-force path builds the stiffness.
#[derive(Clone, Copy)]
enum Path {
    Stress,
    Kernel,
}

/// Global stiffness (N/m) probed column by column from the chosen path.
fn stiffness<F: Formulation>(f: &F, elastic: &Elastic, mesh: &Mesh, path: Path) -> DMatrix<f64> {
    let n = 2 * mesh.n_nodes();
    let kernel = LinearKernel::new(f, elastic);
    let mut k = DMatrix::zeros(n, n);
    for j in 0..n {
        let mut u = vec![0.0; n];
        u[j] = 1.0;
        let mut out = vec![0.0; n];
        for e in 0..f.n_elements() {
            let nodes = f.nodes(e);
            let (fe, _) = match path {
                Path::Stress => element_response(f, elastic, e, &gather(nodes, &u), &mut [(); 4]),
                Path::Kernel => kernel.element(f, e, &u),
            };
            scatter_add(nodes, &fe, &mut out);
        }
        for i in 0..n {
            k[(i, j)] = out[i];
        }
    }
    k
}

/// Solves `K u = f` for the free dofs with `u` prescribed on the others.
fn solve(
    k: &DMatrix<f64>,
    f: &[f64],
    prescribed: &BTreeMap<usize, f64>,
) -> Result<Vec<f64>, String> {
    let n = f.len();
    let free: Vec<usize> = (0..n).filter(|d| !prescribed.contains_key(d)).collect();
    let kff = DMatrix::from_fn(free.len(), free.len(), |i, j| k[(free[i], free[j])]);
    let rhs = DVector::from_fn(free.len(), |i, _| {
        f[free[i]]
            - prescribed
                .iter()
                .map(|(&d, &v)| k[(free[i], d)] * v)
                .sum::<f64>()
    });
    let x = kff
        .lu()
        .solve(&rhs)
        .ok_or("the patch stiffness is singular on the free dofs")?;
    let mut u = vec![0.0; n];
    for (&d, &v) in prescribed {
        u[d] = v;
    }
    for (i, &d) in free.iter().enumerate() {
        u[d] = x[i];
    }
    Ok(u)
}

/// Test B loads: the exact stress (plane strain, from the hand values sxx = syy = 1600,
/// sxy = 400 Pa) as tractions on the four straight edges, half of each edge to each corner.
fn corner_loads(mesh: &Mesh, sxx: f64, syy: f64, sxy: f64) -> Vec<f64> {
    let mut f = vec![0.0; 2 * mesh.n_nodes()];
    for a in 0..4 {
        let (p, q) = (mesh.coords[a], mesh.coords[(a + 1) % 4]);
        // Outward normal times edge length of the counter-clockwise edge p -> q.
        let n = [q[1] - p[1], -(q[0] - p[0])];
        let t = [sxx * n[0] + sxy * n[1], sxy * n[0] + syy * n[1]];
        for node in [a, (a + 1) % 4] {
            f[2 * node] += 0.5 * t[0] * THICKNESS;
            f[2 * node + 1] += 0.5 * t[1] * THICKNESS;
        }
    }
    f
}

/// The linear field at every node (two values per node, m) and test B's supports and loads:
/// node 0 held in both dofs and node 1 in y, at the field's values (against rigid motion), the
/// corners loaded by the exact tractions (hand-computed plane-strain stresses, see the case).
fn field_and_test_b(mesh: &Mesh) -> (Vec<f64>, BTreeMap<usize, f64>, Vec<f64>) {
    let exact: Vec<f64> = mesh.coords.iter().flat_map(|&x| field(x)).collect();
    let supports: BTreeMap<usize, f64> = [0usize, 1, 3].iter().map(|&d| (d, exact[d])).collect();
    let loads = corner_loads(mesh, 1600.0, 1600.0, 400.0);
    (exact, supports, loads)
}

/// Test `test`'s metrics on the path `name` from the nodal displacements `u` (two per node,
/// m) against the field `exact`, and the stresses at every integration point (Pa).
fn test_metrics(
    (test, name): (&str, &str),
    u: &[f64],
    exact: &[f64],
    stresses: impl Iterator<Item = [f64; 4]>,
    m: &mut BTreeMap<String, f64>,
) {
    let scale = exact.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let err = u
        .iter()
        .zip(exact)
        .fold(0.0f64, |a, (u, x)| a.max((u - x).abs()));
    m.insert(
        format!("{test}_{name}_displacement_max_rel_error"),
        err / scale,
    );
    let mut lo = [f64::INFINITY; 4];
    let mut hi = [f64::NEG_INFINITY; 4];
    for st in stresses {
        for c in 0..4 {
            lo[c] = lo[c].min(st[c]);
            hi[c] = hi[c].max(st[c]);
        }
    }
    // The component farthest from the hand value is what the case compares: report the
    // extreme of each component on the side away from the exact value.
    for (c, label, exact_value) in [
        (0, "sxx", 1600.0),
        (1, "syy", 1600.0),
        (3, "sxy", 400.0),
        (2, "szz", 800.0),
    ] {
        let worst = if (hi[c] - exact_value).abs() > (lo[c] - exact_value).abs() {
            hi[c]
        } else {
            lo[c]
        };
        m.insert(format!("{test}_{name}_{label}_worst_Pa"), worst);
    }
}

fn run_tests<F: Formulation>(
    f: &F,
    elastic: &Elastic,
    mesh: &Mesh,
) -> Result<BTreeMap<String, f64>, String> {
    let (exact, supports, loads) = field_and_test_b(mesh);
    let mut m = BTreeMap::new();
    let corners: BTreeMap<usize, f64> = (0..8).map(|d| (d, exact[d])).collect();
    for (name, path) in [("stress_path", Path::Stress), ("kernel", Path::Kernel)] {
        let k = stiffness(f, elastic, mesh, path);
        for (test, u) in [
            ("a", solve(&k, &vec![0.0; exact.len()], &corners)?),
            ("b", solve(&k, &loads, &supports)?),
        ] {
            // Stresses at every integration point, by the solver's constitutive code.
            let stresses: Vec<[f64; 4]> = (0..f.n_elements())
                .flat_map(|e| {
                    let strains = f.strains(e, &gather(f.nodes(e), &u));
                    let points: Vec<[f64; 4]> = strains
                        .iter()
                        .take(F::POINTS)
                        .map(|s| elastic.stress_of(s))
                        .collect();
                    points
                })
                .collect();
            test_metrics((test, name), &u, &exact, stresses.into_iter(), &mut m);
        }
    }
    Ok(m)
}

/// Tests A and B as problems another code solves (`crate::codes::problem`): A holds the four
/// corners on the field, B holds three dofs against rigid motion and loads the corners.
pub fn problems(p: &BTreeMap<String, Value>) -> Result<Vec<(&'static str, Problem)>, String> {
    let kind = super::space_time::element(p)?;
    let mesh = patch_mesh();
    let (exact, supports, loads) = field_and_test_b(&mesh);
    let corners = (0..8).map(|d| (d, exact[d]));
    let free_loads = (0..loads.len())
        .filter(|d| !supports.contains_key(d) && loads[*d] != 0.0)
        .map(|d| (d, loads[d]));
    let problem =
        |held, loads| Problem::plane_strain(kind.name(), THICKNESS, (E, NU), &mesh, held, loads);
    Ok(vec![
        ("a", problem(by_node(corners), Vec::new())),
        ("b", problem(by_node(supports.clone()), by_node(free_loads))),
    ])
}

/// Tests A and B's metrics from another code's fields: its one path answers the checks of
/// impact's stress path; those of impact's precomputed kernel are not produced.
pub fn from_fields(_: &BTreeMap<String, Value>, fields: &[Fields]) -> Result<RunData, String> {
    let [a, b] = fields else {
        return Err(format!(
            "macneal-harder-patch: {} fields for its two problems",
            fields.len()
        ));
    };
    let (exact, _, _) = field_and_test_b(&patch_mesh());
    let mut metrics = BTreeMap::new();
    for (test, f) in [("a", a), ("b", b)] {
        let u: Vec<f64> = f.displacements.iter().flatten().copied().collect();
        let stresses = f.point_stresses.iter().flatten().copied();
        test_metrics((test, "stress_path"), &u, &exact, stresses, &mut metrics);
    }
    Ok(RunData {
        metrics,
        ..Default::default()
    })
}

pub fn patch(p: &BTreeMap<String, Value>) -> Result<RunData, String> {
    let kind = super::space_time::element(p)?;
    let mesh = patch_mesh();
    let elastic = Elastic::new(E, NU);
    let any =
        AnyFormulation::new(kind, &mesh, THICKNESS, 0.05, &elastic).map_err(|e| e.to_string())?;
    let metrics = impact_solver::with_formulation!(&any, f => run_tests(f, &elastic, &mesh))?;
    Ok(RunData {
        metrics,
        ..Default::default()
    })
}

#[cfg(test)]
mod tests {
    //! The problem form against the builtin itself: each problem solved with impact's own
    //! stiffness and written as another code writes its fields gives the builtin's
    //! stress-path metrics bit for bit; a field off the linear field by 1e-9 m at one interior
    //! node fails test A's displacement check (1e-12 of the largest displacement).
    use super::*;
    use impact_solver::model::AnyFormulation;

    /// impact's fields of `problem` (its prescribed dofs and loads) with the stress path.
    fn own_fields<F: Formulation>(
        f: &F,
        elastic: &Elastic,
        mesh: &Mesh,
        problem: &Problem,
    ) -> Fields {
        let k = stiffness(f, elastic, mesh, Path::Stress);
        let held: BTreeMap<usize, f64> = problem
            .prescribed_m
            .iter()
            .map(|&(n, d, v)| (2 * n + d, v))
            .collect();
        let mut loads = vec![0.0; 2 * mesh.n_nodes()];
        for &(n, d, v) in &problem.loads_n {
            loads[2 * n + d] = v;
        }
        let u = solve(&k, &loads, &held).unwrap();
        let forces = &k * DVector::from_column_slice(&u);
        Fields {
            point_eqps: None,
            displacements: u.chunks(2).map(|c| [c[0], c[1]]).collect(),
            nodal_forces: Some(forces.as_slice().chunks(2).map(|c| [c[0], c[1]]).collect()),
            point_stresses: (0..f.n_elements())
                .map(|e| {
                    let strains = f.strains(e, &gather(f.nodes(e), &u));
                    strains
                        .iter()
                        .take(F::POINTS)
                        .map(|s| elastic.stress_of(s))
                        .collect()
                })
                .collect(),
        }
    }

    #[test]
    fn impact_s_own_fields_give_the_builtin_s_stress_path_metrics() {
        for element in ["q4-full", "q4-sri", "q4-1pt"] {
            let p = BTreeMap::from([("element".to_string(), Value::from(element))]);
            let builtin = patch(&p).unwrap().metrics;
            let mesh = patch_mesh();
            let elastic = Elastic::new(E, NU);
            let kind = super::super::space_time::element(&p).unwrap();
            let any = AnyFormulation::new(kind, &mesh, THICKNESS, 0.05, &elastic).unwrap();
            let problems = problems(&p).unwrap();
            let mut fields: Vec<Fields> = problems
                .iter()
                .map(|(_, pr)| impact_solver::with_formulation!(&any, f => own_fields(f, &elastic, &mesh, pr)))
                .collect();
            let evaluated = from_fields(&p, &fields).unwrap().metrics;
            assert_eq!(evaluated.len(), 10, "{evaluated:?}");
            for (k, v) in &evaluated {
                assert!(k.contains("_stress_path_"), "{k}");
                assert_eq!(builtin[k].to_bits(), v.to_bits(), "{element} {k}");
            }
            fields[0].displacements[5][0] += 1e-9;
            let pushed = from_fields(&p, &fields).unwrap().metrics;
            // 1e-9 m over the largest displacement (3e-4 m): 3.3e-6.
            assert!(
                pushed["a_stress_path_displacement_max_rel_error"] > 1e-7,
                "{pushed:?}"
            );
        }
    }
}
