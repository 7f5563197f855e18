//! The linear-elastic fast path: for an elastic material the element internal force
//! `sum_p w_p B_p^T D B_p u_e` (eq. 14) is exactly `K_e u_e` (eq. 13), so the element
//! stiffness is formed once and applied each step. Elements of identical shape share one
//! matrix (a uniform mesh has one, a graded mesh one per column).

use std::collections::HashMap;

use crate::element::{element_stiffness, gather, ElementEnergy, ElementVector, Formulation};
use crate::heap::vec_bytes;
use crate::material::Elastic;
use crate::mesh::Mesh;

pub struct LinearKernel {
    /// Distinct element stiffness matrices, N/m, column-major: `columns[j][i] = K_ij`.
    columns: Vec<[[f64; 8]; 8]>,
    /// Index into `matrices` per element.
    matrix_of: Vec<u32>,
}

impl LinearKernel {
    pub fn new<F: Formulation>(formulation: &F, elastic: &Elastic, mesh: &Mesh) -> LinearKernel {
        let mut columns = Vec::new();
        let mut seen: HashMap<[u64; 6], u32> = HashMap::new();
        let matrix_of = (0..formulation.n_elements())
            .map(|e| {
                // The shape: nodes 1..3 relative to node 0, bit for bit.
                let c = mesh.element_coords(e);
                let key: [u64; 6] = std::array::from_fn(|i| {
                    let (a, k) = (1 + i / 2, i % 2);
                    (c[a][k] - c[0][k]).to_bits()
                });
                *seen.entry(key).or_insert_with(|| {
                    let k = element_stiffness(formulation, elastic, e);
                    columns.push(std::array::from_fn(|j| std::array::from_fn(|i| k[i][j])));
                    (columns.len() - 1) as u32
                })
            })
            .collect();
        LinearKernel { columns, matrix_of }
    }

    /// Heap bytes of the matrices and the per-element index.
    pub fn heap_bytes(&self) -> usize {
        vec_bytes(&self.columns) + vec_bytes(&self.matrix_of)
    }

    /// Number of distinct element matrices.
    pub fn n_matrices(&self) -> usize {
        self.columns.len()
    }

    /// Internal forces `K_e u_e` of element `e` with its strain and hourglass energies.
    #[inline(always)]
    pub fn element<F: Formulation>(
        &self,
        formulation: &F,
        e: usize,
        u: &[f64],
    ) -> (ElementVector, ElementEnergy) {
        self.element_of(formulation, e, &gather(formulation.nodes(e), u))
    }

    /// Internal forces `K_e ue` of element `e` for its displacement vector `ue` (m), with its
    /// strain and hourglass energies (J).
    #[inline(always)]
    pub fn element_of<F: Formulation>(
        &self,
        formulation: &F,
        e: usize,
        ue: &ElementVector,
    ) -> (ElementVector, ElementEnergy) {
        // Column by column: each lane of `fe` is an independent sum, which the compiler can
        // vectorise without reordering any addition (so the result is the same bits).
        let columns = &self.columns[self.matrix_of[e] as usize];
        let mut fe = [0.0; 8];
        for (column, &uj) in columns.iter().zip(ue) {
            for i in 0..8 {
                fe[i] += column[i] * uj;
            }
        }
        let mut work = 0.0;
        for i in 0..8 {
            work += fe[i] * ue[i];
        }
        let hourglass = formulation.hourglass_energy(e, ue);
        let energy = ElementEnergy {
            strain: 0.5 * work - hourglass,
            plastic_work: 0.0,
            hourglass,
        };
        (fe, energy)
    }
}

#[cfg(test)]
mod tests {
    //! Reference: the stress path of eq. (14) (`element_response` with the elastic
    //! material). `K_e u_e` is the same linear map, so forces and energies agree to round-off.
    use super::*;
    use crate::element::{FullQ4, OnePointQ4, SelectiveQ4};
    use crate::integrator::PlateModel;

    fn compare<F: Formulation>(make: impl Fn(&Mesh) -> F) {
        let mesh = crate::mesh::test_plate_mesh(12, 4, 3.0);
        let elastic = Elastic::new(207e9, 0.3);
        let mut generic = PlateModel::new(make(&mesh.mesh), elastic, &mesh, 7850.0);
        let mut linear = PlateModel::new(make(&mesh.mesh), elastic, &mesh, 7850.0)
            .with_linear_kernel(&mesh.mesh, &elastic);
        // Shapes are matched bit for bit: at least one matrix per graded column, at most one
        // per element (row spacings h j / ny may differ in the last bit).
        let n = linear.linear.as_ref().unwrap().n_matrices();
        assert!((12..=48).contains(&n), "{n} matrices");
        // A deterministic, non-smooth displacement field (it excites hourglass modes).
        let u: Vec<f64> = (0..2 * mesh.mesh.n_nodes())
            .map(|i| 1e-5 * ((i as f64 * 0.7).sin() + 0.3 * (i as f64 * 2.3).cos()))
            .collect();
        let (mut fa, mut fb) = (vec![0.0; u.len()], vec![0.0; u.len()]);
        let ea = generic.internal_forces(&u, &mut fa);
        let eb = linear.internal_forces(&u, &mut fb);
        let scale = fa.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for (a, b) in fa.iter().zip(&fb) {
            assert!((a - b).abs() < 1e-12 * scale, "{a:e} vs {b:e}");
        }
        assert!((ea.strain - eb.strain).abs() < 1e-12 * ea.strain);
        assert!((ea.hourglass - eb.hourglass).abs() <= 1e-12 * ea.strain);
    }

    #[test]
    fn linear_kernel_equals_the_stress_path_for_every_element() {
        compare(|m| FullQ4::new(m, 0.2).unwrap());
        compare(|m| SelectiveQ4::new(m, 0.2).unwrap());
        compare(|m| OnePointQ4::new(m, 0.2, 0.05, Elastic::new(207e9, 0.3).p_modulus()).unwrap());
    }
}
