//! Constant-strain patch test on a distorted mesh, for each element formulation.
//!
//! Reference (analytical): a linear displacement field `u = B x` gives a uniform strain,
//! so every integration point must carry the stress `C eps` and the internal forces of the
//! interior (free) nodes must cancel. Tolerance 1e-10 relative: the exact answer is
//! reproduced up to round-off of sums of O(10) terms.

use impact_solver::element::{
    element_response, gather, scatter_add, Formulation, FullQ4, OnePointQ4, SelectiveQ4,
};
use impact_solver::material::{ConstitutiveModel, Elastic};
use impact_solver::mesh::Mesh;

/// MESH: a unit square cut into 2x2 quads whose centre node is moved off-centre, and the
/// mid-side nodes moved too, so no element is a parallelogram.
///
/// ```text
///  6-----7-----8
///  |   /  \    |
///  3--4    \   |
///  |   \    \  |
///  0----1----2
/// ```
fn distorted_patch() -> (Mesh, usize) {
    let coords = vec![
        [0.0, 0.0],
        [0.45, 0.0],
        [1.0, 0.0],
        [0.0, 0.55],
        [0.62, 0.41],
        [1.0, 0.48],
        [0.0, 1.0],
        [0.38, 1.0],
        [1.0, 1.0],
    ];
    let elements = vec![[0, 1, 4, 3], [1, 2, 5, 4], [3, 4, 7, 6], [4, 5, 8, 7]];
    (Mesh { coords, elements }, 4)
}

const ELASTIC: Elastic = Elastic {
    lambda: 1.2e11,
    mu: 0.8e11,
};

/// The linear field u = B x with all strain components non-zero, and its strain.
fn linear_field(mesh: &Mesh) -> (Vec<f64>, [f64; 4]) {
    let b = [[1.0e-3, 0.4e-3], [-0.7e-3, 2.0e-3]];
    let u = mesh
        .coords
        .iter()
        .flat_map(|p| {
            [
                b[0][0] * p[0] + b[0][1] * p[1] + 1e-4,
                b[1][0] * p[0] + b[1][1] * p[1] - 2e-4,
            ]
        })
        .collect();
    (u, [b[0][0], b[1][1], 0.0, b[0][1] + b[1][0]])
}

fn check_patch<F: Formulation>(name: &str, formulation: F) {
    let (mesh, centre) = distorted_patch();
    let (u, strain) = linear_field(&mesh);
    let expected = ELASTIC.stress_of(&strain);
    let mut forces = vec![0.0; u.len()];
    let mut largest = 0.0f64;
    for e in 0..formulation.n_elements() {
        let nodes = formulation.nodes(e);
        let ue = gather(nodes, &u);
        let mut states = [(); 4];
        let (fe, energy) = element_response(&formulation, &ELASTIC, e, &ue, &mut states);
        largest = largest.max(fe.iter().fold(0.0, |m, x| m.max(x.abs())));
        scatter_add(nodes, &fe, &mut forces);
        // A linear field is orthogonal to the hourglass base vectors: only round-off remains.
        assert!(
            energy.hourglass <= 1e-20 * energy.strain,
            "{name}: hourglass energy {:e} of a linear field",
            energy.hourglass
        );
        for p in 0..F::POINTS {
            let s = ELASTIC.stress(&formulation.strains(e, &ue)[p], &());
            for c in 0..4 {
                let err = (s[c] - expected[c]).abs() / expected[0].abs();
                assert!(
                    err < 1e-10,
                    "{name}: element {e} point {p} stress {c}: {} vs {}",
                    s[c],
                    expected[c]
                );
            }
        }
    }
    let residual = forces[2 * centre].abs().max(forces[2 * centre + 1].abs());
    assert!(
        residual < 1e-10 * largest,
        "{name}: free-node force {residual:e} vs element forces {largest:e}"
    );
}

#[test]
fn full_integration_passes_the_patch_test() {
    let (mesh, _) = distorted_patch();
    check_patch("q4-full", FullQ4::new(&mesh, 0.2).unwrap());
}

#[test]
fn selective_reduced_integration_passes_the_patch_test() {
    let (mesh, _) = distorted_patch();
    check_patch("q4-sri", SelectiveQ4::new(&mesh, 0.2).unwrap());
}

#[test]
fn one_point_with_hourglass_control_passes_the_patch_test() {
    let (mesh, _) = distorted_patch();
    check_patch(
        "q4-1pt",
        OnePointQ4::new(&mesh, 0.2, 0.05, ELASTIC.p_modulus()).unwrap(),
    );
}

/// The patch must also be free of forces for rigid-body motion (translation + small
/// rotation): the element stiffness has the three zero-energy modes and no more.
#[test]
fn rigid_body_modes_produce_no_force() {
    let (mesh, _) = distorted_patch();
    let f = SelectiveQ4::new(&mesh, 1.0).unwrap();
    let theta = 1e-3;
    let u: Vec<f64> = mesh
        .coords
        .iter()
        .flat_map(|p| [0.3 - theta * p[1], -0.1 + theta * p[0]])
        .collect();
    for e in 0..f.n_elements() {
        let ue = gather(f.nodes(e), &u);
        let (fe, _) = element_response(&f, &ELASTIC, e, &ue, &mut [(); 4]);
        for x in fe {
            assert!(x.abs() < 1e-10 * ELASTIC.mu * theta, "{x:e}");
        }
    }
}

#[test]
fn an_inverted_element_is_refused_with_its_number() {
    let (mut mesh, _) = distorted_patch();
    mesh.coords[4] = [1.3, 1.2]; // pull the centre node through the far corner
    let err = FullQ4::new(&mesh, 1.0)
        .err()
        .expect("must be refused")
        .to_string();
    assert!(err.contains("inverted or degenerate"), "{err}");
}
