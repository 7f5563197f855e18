//! The `beam-bending` builtin: a static clamped-clamped beam of the solver's elements (the
//! assembled element stiffness, solved by a banded Cholesky factorisation) against beam
//! theory (`impact_analytical::beam`), with the expected locking of bilinear quads and the
//! layer estimate of one-point elements.

use std::collections::BTreeMap;

use impact_analytical::beam::ClampedBeam;
use impact_solver::element::Formulation;
use impact_solver::material::Elastic;
use impact_solver::mesh::PlateMesh;
use impact_solver::scene::{MeshSettings, Model, Plate};
use impact_solver::with_formulation;

use super::patch::formulation;
use crate::definition::run_data::RunData;
use crate::run::builtin_params::{element_kind, param, param_str, Params};

/// Static clamped-clamped beam (half model: clamp at x = 0, symmetry at mid-span) with a
/// total load F at mid-span shared over the mid-span nodes; against beam theory.
pub(super) fn beam_bending(p: &Params) -> Result<RunData, String> {
    let kind = element_kind(param_str(p, "element", "q4-sri")?)?;
    let length = param(p, "length", 0.8)?;
    let thickness = param(p, "thickness", 0.02)?;
    let width = param(p, "width", 0.2)?;
    let nx = param(p, "nx", 80.0)? as usize;
    let ny = param(p, "ny", 4.0)? as usize;
    let force = param(p, "force", 1.0e4)?;
    let (e_mod, nu) = (
        param(p, "youngs_modulus", 207e9)?,
        param(p, "poisson_ratio", 0.3)?,
    );
    let elastic = Elastic::new(e_mod, nu);
    // Mesh settings from a minimal scene, so that fields the solver adds keep their defaults.
    let base = impact_solver::Scene::from_yaml(
        "plate: {length: 1.0, width: 1.0, thickness: 0.1}\nmaterial: {density: 1.0, youngs_modulus: 1.0, poisson_ratio: 0.3}\nmesh: {nx: 2, ny: 2}\nload: {pulse: {force: 1.0, duration: 1.0}}\ntime: {end: 1.0, dt: {cfl: 0.5}}\n",
        std::path::Path::new("(builtin beam-bending)"),
    )
    .map_err(|e| e.to_string())?;
    // Plate likewise (the solver may add fields: their defaults come from the scene).
    let plate = Plate {
        length,
        width,
        thickness,
        ..base.plate
    };
    let settings = MeshSettings {
        nx,
        ny,
        element: kind,
        model: Model::Half,
        ..base.mesh
    };
    let pm = PlateMesh::new(&plate, &settings);
    let form = formulation(kind, &pm.mesh, width, &elastic)?;
    // Renumber dofs column by column (x-major) for a narrow band.
    let node_of = |n: usize| {
        let (i, j) = (n % (nx + 1), n / (nx + 1));
        i * (ny + 1) + j
    };
    let ndof = 2 * pm.mesh.n_nodes();
    let dof = |n: usize, c: usize| 2 * node_of(n) + c;
    let mut k: BTreeMap<(usize, usize), f64> = BTreeMap::new();
    with_formulation!(&form, x => {
        for e in 0..x.n_elements() {
            let ke = impact_solver::element::element_stiffness(x, &elastic, e);
            let nodes = x.nodes(e);
            for a in 0..8 {
                for b in 0..8 {
                    let (i, j) = (dof(nodes[a / 2] as usize, a % 2), dof(nodes[b / 2] as usize, b % 2));
                    *k.entry((i, j)).or_insert(0.0) += 0.5 * (ke[a][b] + ke[b][a]);
                }
            }
        }
    });
    let mut rhs = vec![0.0; ndof];
    // Half the load on the half model, as a uniform shear traction over the mid-span face.
    for j in 0..=ny {
        let n = nx + j * (nx + 1);
        let share = if j == 0 || j == ny { 0.5 } else { 1.0 } / ny as f64;
        rhs[dof(n, 1)] -= 0.5 * force * share;
    }
    for n in 0..pm.mesh.n_nodes() {
        for c in 0..2 {
            if pm.fixed_dofs[2 * n + c] {
                let d = dof(n, c);
                k.retain(|&(i, j), _| i != d && j != d);
                k.insert((d, d), 1.0);
                rhs[d] = 0.0;
            }
        }
    }
    let bw = 2 * (ny + 2) + 1;
    let u = banded_solve(ndof, bw, &k, &rhs)?;
    let deflection = -u[dof(pm.mid, 1)];
    let beam = ClampedBeam::new(length, width, thickness, e_mod, nu)?;
    let eb = beam.euler_bernoulli_midspan(force);
    let shear = beam.shear_midspan(force);
    let nu_p = nu / (1.0 - nu);
    // Parasitic shear of a bilinear quad of length a under a curvature k: gamma = k a xi / 2,
    // energy G k^2 a^2 / 24 per volume against the bending energy E' k^2 h^2 / 24 averaged
    // over the depth h: ratio (1 - nu') (a/h)^2 / 2 in plane strain, whatever the layers.
    let a_over_h = (0.5 * length / nx as f64) / thickness;
    let locking = 1.0 / (1.0 + 0.5 * (1.0 - nu_p) * a_over_h * a_over_h);
    // One-point elements carry a constant strain per layer: the bending stiffness of ny
    // layers is (1 - 1/ny^2) of the exact one (hourglass control adds a little back).
    let one_point = 1.0 / (1.0 - 1.0 / (ny * ny) as f64);
    let mut m = BTreeMap::new();
    m.insert("deflection_m".into(), deflection);
    m.insert("euler_bernoulli_m".into(), eb);
    m.insert("timoshenko_m".into(), eb + shear);
    m.insert("ratio_to_timoshenko".into(), deflection / (eb + shear));
    m.insert("q4_locking_estimate".into(), locking);
    m.insert("one_point_layer_estimate".into(), one_point);
    Ok(RunData {
        metrics: m,
        ..Default::default()
    })
}

/// Banded symmetric positive definite solve (Cholesky), half-bandwidth `bw`.
fn banded_solve(
    n: usize,
    bw: usize,
    k: &BTreeMap<(usize, usize), f64>,
    rhs: &[f64],
) -> Result<Vec<f64>, String> {
    // l[i][j - i + bw] for j in [i - bw, i].
    let w = bw + 1;
    let mut a = vec![0.0; n * w];
    for (&(i, j), &v) in k {
        if j <= i && i - j <= bw {
            a[i * w + (j + bw - i)] += v;
        }
    }
    for i in 0..n {
        let j0 = i.saturating_sub(bw);
        for j in j0..=i {
            let mut s = a[i * w + (j + bw - i)];
            let k0 = j0.max(j.saturating_sub(bw));
            for kk in k0..j {
                s -= a[i * w + (kk + bw - i)] * a[j * w + (kk + bw - j)];
            }
            if i == j {
                if s <= 0.0 {
                    return Err(format!("stiffness not positive definite at dof {i}"));
                }
                a[i * w + bw] = s.sqrt();
            } else {
                a[i * w + (j + bw - i)] = s / a[j * w + bw];
            }
        }
    }
    let mut y = rhs.to_vec();
    for i in 0..n {
        let j0 = i.saturating_sub(bw);
        let mut s = y[i];
        for j in j0..i {
            s -= a[i * w + (j + bw - i)] * y[j];
        }
        y[i] = s / a[i * w + bw];
    }
    for i in (0..n).rev() {
        let mut s = y[i];
        for j in i + 1..(i + bw + 1).min(n) {
            s -= a[j * w + (i + bw - j)] * y[j];
        }
        y[i] = s / a[i * w + bw];
    }
    Ok(y)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn banded_cholesky_solves_a_tridiagonal_system() {
        let n = 5;
        let mut k = BTreeMap::new();
        for i in 0..n {
            k.insert((i, i), 2.0);
            if i + 1 < n {
                k.insert((i + 1, i), -1.0);
                k.insert((i, i + 1), -1.0);
            }
        }
        let x = banded_solve(n, 1, &k, &[1.0, 0.0, 0.0, 0.0, 1.0]).unwrap();
        for v in x {
            assert!((v - 1.0).abs() < 1e-12);
        }
    }
}
