//! The `element-eigenvalues` builtin: the eigenvalues of each element's stiffness on one
//! distorted quadrilateral. The solver's matrix (`impact_solver::element::element_stiffness`,
//! built column by column from its internal forces, hourglass control included) against one
//! assembled here from the formulas of ALGORITHM.md section 2 (2x2 Gauss `B^T D B`; B-bar
//! with the centroid volumetric strain; one point plus the Flanagan-Belytschko hourglass
//! stiffness), independent of the solver's element code. Reports the number of zero-energy
//! modes (eigenvalues below 1e-10 of the largest: the three rigid-body modes, plus the two
//! hourglass modes of one-point quadrature without control) and the largest relative
//! difference between the two sets of eigenvalues (round-off, below 1e-14, reported as 1e-14).

use std::collections::BTreeMap;

use impact_solver::element::{element_stiffness, FullQ4, OnePointQ4, SelectiveQ4};
use impact_solver::material::Elastic;
use impact_solver::mesh::Mesh;
use nalgebra::{SMatrix, SymmetricEigen};
use serde_json::Value;

use crate::definition::run_data::RunData;
use crate::run::builtin_params::param;

type Matrix8 = SMatrix<f64, 8, 8>;

/// Relative eigenvalue differences below this are round-off and reported as this.
const ROUND_OFF_FLOOR: f64 = 1.0e-14;

/// The distorted element (m): no two sides parallel.
const NODES: [[f64; 2]; 4] = [
    [0.0, 0.0],
    [1.2e-2, 1.0e-3],
    [1.0e-2, 9.0e-3],
    [-1.0e-3, 1.1e-2],
];

/// Shape-function derivatives in x, y and det J at (xi, eta).
fn derivatives(xi: f64, eta: f64) -> ([f64; 4], [f64; 4], f64) {
    let s = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];
    let dxi: [f64; 4] = std::array::from_fn(|a| 0.25 * s[a][0] * (1.0 + eta * s[a][1]));
    let deta: [f64; 4] = std::array::from_fn(|a| 0.25 * s[a][1] * (1.0 + xi * s[a][0]));
    let (mut j11, mut j12, mut j21, mut j22) = (0.0, 0.0, 0.0, 0.0);
    for a in 0..4 {
        j11 += dxi[a] * NODES[a][0];
        j12 += dxi[a] * NODES[a][1];
        j21 += deta[a] * NODES[a][0];
        j22 += deta[a] * NODES[a][1];
    }
    let det = j11 * j22 - j12 * j21;
    let dx = std::array::from_fn(|a| (j22 * dxi[a] - j12 * deta[a]) / det);
    let dy = std::array::from_fn(|a| (-j21 * dxi[a] + j11 * deta[a]) / det);
    (dx, dy, det)
}

/// `w B^T D B` added to `k` for a strain operator `b` (rows xx, yy, zz, gamma_xy).
fn add_btdb(k: &mut Matrix8, b: &SMatrix<f64, 4, 8>, lambda: f64, mu: f64, w: f64) {
    let mut d = SMatrix::<f64, 4, 4>::zeros();
    for i in 0..3 {
        for j in 0..3 {
            d[(i, j)] = lambda + if i == j { 2.0 * mu } else { 0.0 };
        }
    }
    d[(3, 3)] = mu;
    *k += w * b.transpose() * d * b;
}

/// The strain operator (rows xx, yy, zz = 0, gamma_xy) of shape-function derivatives.
fn strain_operator(dx: &[f64; 4], dy: &[f64; 4]) -> SMatrix<f64, 4, 8> {
    let mut b = SMatrix::<f64, 4, 8>::zeros();
    for a in 0..4 {
        b[(0, 2 * a)] = dx[a];
        b[(1, 2 * a + 1)] = dy[a];
        b[(3, 2 * a)] = dy[a];
        b[(3, 2 * a + 1)] = dx[a];
    }
    b
}

/// The element stiffness from ALGORITHM.md section 2 (width 1 m): "q4-full", "q4-sri",
/// "q4-1pt" with hourglass coefficient `kappa`.
fn independent(kind: &str, lambda: f64, mu: f64, kappa: f64) -> Matrix8 {
    let g = 1.0 / 3f64.sqrt();
    let (bx, by, _) = derivatives(0.0, 0.0);
    let mut k = Matrix8::zeros();
    let mut area = 0.0;
    for (xi, eta) in [(-g, -g), (g, -g), (g, g), (-g, g)] {
        let (dx, dy, det) = derivatives(xi, eta);
        area += det;
        let mut b = strain_operator(&dx, &dy);
        for a in 0..4 {
            if kind == "q4-sri" {
                // shift = (e_c - e) / 3 on xx, yy and zz.
                for row in 0..3 {
                    b[(row, 2 * a)] += (bx[a] - dx[a]) / 3.0;
                    b[(row, 2 * a + 1)] += (by[a] - dy[a]) / 3.0;
                }
            }
        }
        if kind != "q4-1pt" {
            add_btdb(&mut k, &b, lambda, mu, det);
        }
    }
    if kind == "q4-1pt" {
        add_btdb(&mut k, &strain_operator(&bx, &by), lambda, mu, area);
        let h = [1.0, -1.0, 1.0, -1.0];
        let hx: f64 = (0..4).map(|a| h[a] * NODES[a][0]).sum();
        let hy: f64 = (0..4).map(|a| h[a] * NODES[a][1]).sum();
        let gamma: [f64; 4] = std::array::from_fn(|a| 0.25 * (h[a] - hx * bx[a] - hy * by[a]));
        let bb: f64 = (0..4).map(|a| bx[a] * bx[a] + by[a] * by[a]).sum();
        let k_hg = kappa * (lambda + 2.0 * mu) * area * bb;
        for a in 0..4 {
            for c in 0..4 {
                for comp in 0..2 {
                    k[(2 * a + comp, 2 * c + comp)] += k_hg * gamma[a] * gamma[c];
                }
            }
        }
    }
    k
}

/// Sorted eigenvalues of a symmetric 8 x 8 matrix, N/m.
fn eigenvalues(k: Matrix8) -> Vec<f64> {
    let mut v: Vec<f64> = SymmetricEigen::new(k).eigenvalues.iter().copied().collect();
    v.sort_by(f64::total_cmp);
    v
}

/// The solver's stiffness of the element kind, symmetrised.
fn solver(kind: &str, elastic: &Elastic, kappa: f64) -> Result<Matrix8, String> {
    let mesh = Mesh {
        coords: NODES.to_vec(),
        elements: vec![[0, 1, 2, 3]],
    };
    let err = |e: impact_solver::error::Error| e.to_string();
    let k = match kind {
        "q4-full" => element_stiffness(&FullQ4::new(&mesh, 1.0).map_err(err)?, elastic, 0),
        "q4-sri" => element_stiffness(&SelectiveQ4::new(&mesh, 1.0).map_err(err)?, elastic, 0),
        "q4-1pt" => element_stiffness(
            &OnePointQ4::new(&mesh, 1.0, kappa, elastic.p_modulus()).map_err(err)?,
            elastic,
            0,
        ),
        o => {
            return Err(format!(
                "param element: {o:?} is not q4-full, q4-sri or q4-1pt"
            ))
        }
    };
    let k = Matrix8::from_fn(|i, j| k[i][j]);
    Ok(0.5 * (k + k.transpose()))
}

pub fn element_eigenvalues(p: &BTreeMap<String, Value>) -> Result<RunData, String> {
    let kind = p.get("element").and_then(Value::as_str).unwrap_or("q4-sri");
    let kappa = param(p, "hourglass", 0.05)?;
    let elastic = Elastic::new(
        param(p, "youngs_modulus", 207e9)?,
        param(p, "poisson_ratio", 0.3)?,
    );
    let ours = eigenvalues(solver(kind, &elastic, kappa)?);
    let theirs = eigenvalues(independent(kind, elastic.lambda, elastic.mu, kappa));
    let largest = ours[7].abs().max(theirs[7].abs());
    let zero = |v: &[f64]| v.iter().filter(|x| x.abs() < 1e-10 * largest).count() as f64;
    let diff = ours
        .iter()
        .zip(&theirs)
        .filter(|(a, _)| a.abs() >= 1e-10 * largest)
        .map(|(a, b)| ((a - b) / a).abs())
        .fold(0.0, f64::max);
    let mut m = BTreeMap::new();
    m.insert("zero_modes".into(), zero(&ours));
    m.insert("zero_modes_independent".into(), zero(&theirs));
    // Round-off (~1e-15) is reported as the floor 1e-14, so that snapshots do not pin it.
    m.insert(
        "nonzero_eigenvalue_max_rel_diff".into(),
        diff.max(ROUND_OFF_FLOOR),
    );
    m.insert(
        "smallest_nonzero_over_largest".into(),
        ours[zero(&ours) as usize] / largest,
    );
    for (i, v) in ours.iter().enumerate() {
        m.insert(format!("eigenvalue_{i}_N_per_m"), *v);
    }
    Ok(RunData {
        metrics: m,
        ..Default::default()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The spectrum tells the formulations apart (a swapped or half-done B-bar would show),
    /// and the independent q4-1pt without control has the five zero modes.
    #[test]
    fn spectra_differ_between_formulations() {
        let el = Elastic::new(207e9, 0.3);
        let full = eigenvalues(independent("q4-full", el.lambda, el.mu, 0.0));
        let sri = eigenvalues(independent("q4-sri", el.lambda, el.mu, 0.0));
        assert!((sri[3] / full[3] - 1.0).abs() > 0.1, "{sri:?} {full:?}");
        let one = eigenvalues(independent("q4-1pt", el.lambda, el.mu, 0.0));
        assert!(
            one[4].abs() < 1e-10 * one[7] && one[5] > 1e-3 * one[7],
            "{one:?}"
        );
    }
}
