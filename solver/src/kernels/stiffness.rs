//! The linear-elastic fast path: for an elastic material the element internal force
//! `sum_p w_p B_p^T D B_p u_e` (eq. 14) is exactly `K_e u_e` (eq. 13), so the element
//! stiffness is formed once and applied each step. Elements of identical shape share one
//! matrix (stored per batch of elements in lanes, each distinct batch once).
//!
//! `K_e` kills rigid translations, so `K_e u_e = K_e (u_e - t)` for node 0's translation
//! `t`: the product is formed on the displacements relative to node 0, whose first two
//! entries are zero. Their two columns are neither stored nor multiplied (48 of the 64
//! products), and the energy `u . K u / 2` suffers no cancellation from a large rigid
//! translation.

use std::convert::Infallible;

use crate::lanes::real::Real;
use crate::lanes::simd::Lanes;
use crate::physics::elements::element::{
    element_stiffness, gather, ElementEnergy, ElementVector, Energy, Formulation,
};
use crate::physics::elements::geometry::{SharedBatches, Vector};
use crate::physics::materials::material::Elastic;

/// Columns of `K_e` stored: all but node 0's two (see the module documentation).
const STORED: usize = 6;

/// Element stiffness matrices in batches of [`crate::lanes::simd::LANES`] elements, column-major
/// without node 0's columns (`[j - 2][i]` is `K_ij`, N/m, in lanes), each distinct batch
/// stored once ([`SharedBatches`]: the batches of a structured mesh repeat).
pub struct LinearKernel {
    matrices: SharedBatches<[Vector<Lanes>; STORED]>,
}

impl LinearKernel {
    pub fn new<F: Formulation>(formulation: &F, elastic: &Elastic) -> LinearKernel {
        // Column-major per element, columns 2.. (node 0's left out).
        let columns = |e| -> Result<[[f64; 8]; STORED], Infallible> {
            let k = element_stiffness(formulation, elastic, e);
            Ok(std::array::from_fn(|j| {
                std::array::from_fn(|i| k[i][j + 2])
            }))
        };
        let matrices = SharedBatches::new(
            formulation.n_elements(),
            columns,
            |columns, key| key.extend(columns.iter().flatten().map(|x| x.to_bits())),
            |batch| {
                let mut lanes = [[Lanes::splat(0.0); 8]; STORED];
                for (l, columns) in batch.iter().enumerate() {
                    for (j, column) in columns.iter().enumerate() {
                        for (i, &k) in column.iter().enumerate() {
                            lanes[j][i].0[l] = k;
                        }
                    }
                }
                lanes
            },
        )
        .unwrap_or_else(|never| match never {});
        LinearKernel { matrices }
    }

    /// Heap bytes of the matrices and the per-batch index.
    pub fn heap_bytes(&self) -> usize {
        self.matrices.heap_bytes()
    }

    /// Number of distinct batches of element matrices.
    pub fn n_matrices(&self) -> usize {
        self.matrices.n_distinct()
    }

    /// [`LinearKernel::product`] of element `e` at the global displacements `u` (m).
    #[inline(always)]
    pub fn element<F: Formulation>(
        &self,
        formulation: &F,
        e: usize,
        u: &[f64],
    ) -> (ElementVector, ElementEnergy) {
        self.product(formulation, e, &gather(formulation.nodes(e), u))
    }

    /// Internal forces `K_e ue` of `at` (an element for `f64`, a batch for [`Lanes`]) for its
    /// displacement vector `ue` (m), with the strain and hourglass energies (J), both formed
    /// on the displacements relative to node 0.
    #[inline(always)]
    pub fn product<F: Formulation, R: Real>(
        &self,
        formulation: &F,
        at: usize,
        ue: &Vector<R>,
    ) -> (Vector<R>, Energy<R>) {
        // Node 0's entries are zeros: its columns are not stored (see the module doc).
        let relative = relative_to_node_0(ue);
        // The stored columns' entries as an array of their own: read through the eight
        // (`relative[2..]`), q4-sri's elastic kernel took 10 ns instead of 5.2, and copied by
        // `copy_from_slice` 5.7 (LLVM's code changed; kprof, interleaved, 2026-11-25).
        let stored: [R; STORED] = std::array::from_fn(|j| relative[j + 2]);
        // Column by column: each row of `fe` is an independent sum in column order.
        let columns = self.matrices.batch::<R>(at);
        let mut fe = [R::splat(0.0); 8];
        for (column, &uj) in columns.iter().zip(&stored) {
            for (f, k) in fe.iter_mut().zip(column) {
                *f += R::of_batch(k, at) * uj;
            }
        }
        let mut work = R::splat(0.0);
        for (&f, &u) in fe.iter().skip(2).zip(&stored) {
            work += f * u;
        }
        let hourglass = formulation.hourglass_energy(at, &relative);
        (fe, energies(work, hourglass))
    }

    /// [`LinearKernel::product`] for the elastic screen, written as a product over all eight
    /// columns of the displacements relative to node 0, the first two (not stored) standing
    /// in by columns 2 and 3 times node 0's exact zeros: each adds +-0 to a +0 sum, so the
    /// bits are `product`'s. Why: this is the shape
    /// the stress path's kernel was tuned with; with `product`'s shape inlined there (never
    /// run in it when every point yields), the all-yielding kernel took 31.2 ns instead of
    /// 29.9 (other registers).
    #[inline(always)]
    pub fn screen_product<F: Formulation, R: Real>(
        &self,
        formulation: &F,
        at: usize,
        ue: &Vector<R>,
    ) -> (Vector<R>, Energy<R>) {
        let relative = &relative_to_node_0(ue);
        let c = self.matrices.batch::<R>(at);
        let columns = [&c[0], &c[1], &c[0], &c[1], &c[2], &c[3], &c[4], &c[5]];
        let mut fe = [R::splat(0.0); 8];
        for (column, &uj) in columns.iter().zip(relative) {
            for (f, k) in fe.iter_mut().zip(column.iter()) {
                *f += R::of_batch(k, at) * uj;
            }
        }
        let mut work = R::splat(0.0);
        for (&f, &u) in fe.iter().zip(relative) {
            work += f * u;
        }
        let hourglass = formulation.hourglass_energy(at, relative);
        (fe, energies(work, hourglass))
    }
}

/// The displacements `ue` (m) relative to node 0's: `K_e ue` of these is `K_e ue` (see the
/// module documentation), and node 0's entries are exact zeros (for finite `ue`).
#[inline(always)]
fn relative_to_node_0<R: Real>(ue: &Vector<R>) -> Vector<R> {
    let (tx, ty) = (ue[0], ue[1]);
    let mut relative = *ue;
    for (i, x) in relative.iter_mut().enumerate() {
        *x = *x - if i % 2 == 0 { tx } else { ty };
    }
    relative
}

/// The energies (J) of a stiffness product: `work = u . K u` less the `hourglass` energy.
#[inline(always)]
fn energies<R: Real>(work: R, hourglass: R) -> Energy<R> {
    Energy {
        strain: work * 0.5 - hourglass,
        plastic_work: R::splat(0.0),
        hourglass,
    }
}

#[cfg(test)]
mod tests {
    //! Reference: the stress path of eq. (14) (`element_response` with the elastic
    //! material). `K_e u_e` is the same linear map, so forces and energies agree to round-off.
    use super::*;
    use crate::mesh::Mesh;
    use crate::physics::elements::element::{FullQ4, OnePointQ4, SelectiveQ4};
    use crate::time_loop::plate_model::PlateModel;

    fn compare<F: Formulation>(make: impl Fn(&Mesh) -> F) {
        let mesh = crate::mesh::test_plate_mesh(12, 4, 3.0);
        let elastic = Elastic::new(207e9, 0.3);
        let mut generic = PlateModel::new(make(&mesh.mesh), elastic, &mesh, 7850.0);
        let mut linear =
            PlateModel::new(make(&mesh.mesh), elastic, &mesh, 7850.0).with_linear_kernel(&elastic);
        // Batches are shared only when every matrix entry has the same bits: at most one
        // per batch of 8 elements (48 elements: 6 batches; on this graded mesh the rows
        // repeat, but the batches straddle them).
        let n = linear.linear.as_ref().unwrap().n_matrices();
        assert!((1..=6).contains(&n), "{n} distinct batches of matrices");
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

    /// The screen's eight-column form gives the product's bits: forces and energies, every
    /// element, with a large rigid translation in the displacements.
    #[test]
    fn the_screen_product_has_the_product_bits() {
        let mesh = crate::mesh::test_plate_mesh(12, 4, 3.0);
        let elastic = Elastic::new(207e9, 0.3);
        let formulation = OnePointQ4::new(&mesh.mesh, 0.2, 0.05, elastic.p_modulus()).unwrap();
        let kernel = LinearKernel::new(&formulation, &elastic);
        let u: Vec<f64> = (0..2 * mesh.mesh.n_nodes())
            .map(|i| 1e-3 + 1e-5 * ((i as f64 * 0.7).sin() + 0.3 * (i as f64 * 2.3).cos()))
            .collect();
        let bits = |(f, en): (ElementVector, ElementEnergy)| {
            let energies = [en.strain, en.plastic_work, en.hourglass];
            f.iter()
                .chain(&energies)
                .map(|x| x.to_bits())
                .collect::<Vec<_>>()
        };
        for e in 0..formulation.n_elements() {
            let ue = gather(formulation.nodes(e), &u);
            assert_eq!(
                bits(kernel.product(&formulation, e, &ue)),
                bits(kernel.screen_product(&formulation, e, &ue)),
                "element {e}"
            );
        }
    }
}
