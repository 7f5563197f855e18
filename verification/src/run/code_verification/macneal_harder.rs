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

fn run_tests<F: Formulation>(
    f: &F,
    elastic: &Elastic,
    mesh: &Mesh,
) -> Result<BTreeMap<String, f64>, String> {
    let exact: Vec<f64> = mesh.coords.iter().flat_map(|&x| field(x)).collect();
    let scale = exact.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let mut m = BTreeMap::new();
    let corners: BTreeMap<usize, f64> = (0..8).map(|d| (d, exact[d])).collect();
    // Rigid-body supports for test B: node 0 both dofs, node 1 y (at the field's values).
    let supports: BTreeMap<usize, f64> = [0usize, 1, 3].iter().map(|&d| (d, exact[d])).collect();
    // Hand-computed plane-strain stresses (see the case): the loads of test B.
    let loads = corner_loads(mesh, 1600.0, 1600.0, 400.0);
    for (name, path) in [("stress_path", Path::Stress), ("kernel", Path::Kernel)] {
        let k = stiffness(f, elastic, mesh, path);
        for (test, u) in [
            ("a", solve(&k, &vec![0.0; exact.len()], &corners)?),
            ("b", solve(&k, &loads, &supports)?),
        ] {
            let err = u
                .iter()
                .zip(&exact)
                .fold(0.0f64, |a, (u, x)| a.max((u - x).abs()));
            m.insert(
                format!("{test}_{name}_displacement_max_rel_error"),
                err / scale,
            );
            // Stresses at every integration point, by the solver's constitutive code.
            let mut lo = [f64::INFINITY; 4];
            let mut hi = [f64::NEG_INFINITY; 4];
            for e in 0..f.n_elements() {
                let strains = f.strains(e, &gather(f.nodes(e), &u));
                for s in strains.iter().take(F::POINTS) {
                    let st = elastic.stress_of(s);
                    for c in 0..4 {
                        lo[c] = lo[c].min(st[c]);
                        hi[c] = hi[c].max(st[c]);
                    }
                }
            }
            // The component farthest from the hand value is what the case compares: report
            // the extreme of each component on the side away from the exact value.
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
    }
    Ok(m)
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
