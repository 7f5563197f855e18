//! The geometry of the element kernels: shape-function derivatives at a point
//! ([`PointGeometry`], stored in lanes, with the strain and divergence operators written
//! once over [`Real`]), and the one store of per-element data, [`SharedBatches`]: batch-major (struct
//! of arrays, [`LANES`] elements per batch), each distinct batch stored once. The batched
//! path reads a whole batch, the scalar path its element's lane of it.

use std::collections::HashMap;

use crate::lanes::heap::vec_bytes;
use crate::lanes::real::Real;
use crate::lanes::simd::{Lanes, LANES};

/// Natural coordinates of the nodes (counter-clockwise).
pub const NODE_XI: [[f64; 2]; 4] = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];

/// Element displacement (m) or force (N) vectors `[ux0, uy0, ..., ux3, uy3]` of
/// [`Real::LANES`] elements.
pub type Vector<R> = [R; 8];

/// Cartesian shape-function derivatives and det J at a point of one element (`f64`) or of
/// a batch ([`Lanes`]).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PointGeometry<R> {
    /// dN_a/dx, 1/m
    pub dndx: [R; 4],
    /// dN_a/dy, 1/m
    pub dndy: [R; 4],
    /// det J, m^2 per unit natural area
    pub det_j: R,
}

impl PointGeometry<f64> {
    /// The geometry at natural coordinates `xi` of the element with node coordinates
    /// `coords` (m).
    pub fn at(coords: &[[f64; 2]; 4], xi: [f64; 2]) -> PointGeometry<f64> {
        let dxi = NODE_XI.map(|n| 0.25 * n[0] * (1.0 + xi[1] * n[1]));
        let deta = NODE_XI.map(|n| 0.25 * n[1] * (1.0 + xi[0] * n[0]));
        let mut j = [[0.0; 2]; 2];
        for a in 0..4 {
            for k in 0..2 {
                j[0][k] += dxi[a] * coords[a][k];
                j[1][k] += deta[a] * coords[a][k];
            }
        }
        let det_j = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        let mut g = PointGeometry {
            det_j,
            ..Default::default()
        };
        for a in 0..4 {
            g.dndx[a] = (j[1][1] * dxi[a] - j[0][1] * deta[a]) / det_j;
            g.dndy[a] = (-j[1][0] * dxi[a] + j[0][0] * deta[a]) / det_j;
        }
        g
    }

    /// Every value's bits (the key under which equal geometry is shared).
    pub fn bits(&self, key: &mut Vec<u64>) {
        key.extend(self.dndx.iter().chain(&self.dndy).map(|x| x.to_bits()));
        key.push(self.det_j.to_bits());
    }

    /// The lanes of `points` (at most [`LANES`]; missing lanes are zero).
    pub fn lanes(points: &[PointGeometry<f64>]) -> PointGeometry<Lanes> {
        let mut g = PointGeometry::<Lanes>::default();
        for (l, p) in points.iter().enumerate() {
            for a in 0..4 {
                g.dndx[a].0[l] = p.dndx[a];
                g.dndy[a].0[l] = p.dndy[a];
            }
            g.det_j.0[l] = p.det_j;
        }
        g
    }
}

/// The kernels read the stored lanes in place, each value as it is used (a copy of a
/// batch's geometry costs as much as the arithmetic on it): at `at`, [`Real::of_batch`].
impl PointGeometry<Lanes> {
    /// dN_a/dx at `at`, 1/m.
    #[inline(always)]
    pub fn dndx<R: Real>(&self, a: usize, at: usize) -> R {
        R::of_batch(&self.dndx[a], at)
    }

    /// dN_a/dy at `at`, 1/m.
    #[inline(always)]
    pub fn dndy<R: Real>(&self, a: usize, at: usize) -> R {
        R::of_batch(&self.dndy[a], at)
    }

    /// det J at `at`.
    #[inline(always)]
    pub fn det_j<R: Real>(&self, at: usize) -> R {
        R::of_batch(&self.det_j, at)
    }

    /// Small strain `[xx, yy, 0, gamma_xy]` of an element displacement vector at `at`.
    #[inline(always)]
    pub fn strain<R: Real>(&self, at: usize, u: &Vector<R>) -> [R; 4] {
        strain_on(self, at, u)
    }

    /// Volumetric strain `div u` at `at` (summed as an iterator sum: from -0.0).
    #[inline(always)]
    pub fn dilatation<R: Real>(&self, at: usize, u: &Vector<R>) -> R {
        let mut d = R::splat(-0.0);
        for a in 0..4 {
            d += self.dndx::<R>(a, at) * u[2 * a] + self.dndy::<R>(a, at) * u[2 * a + 1];
        }
        d
    }

    /// Displacement gradient `du/dX` at `at`, row-major `[xX, xY, yX, yY]`
    /// ([`crate::physics::kinematics::Gradient`]; `X` the coordinates this geometry was made on).
    #[inline(always)]
    pub fn gradient<R: Real>(&self, at: usize, u: &Vector<R>) -> [R; 4] {
        gradient_on(self, at, u)
    }

    /// Adds `w P dN_a/dX` (first Piola-Kirchhoff stress `P`, row-major `[xX, xY, yX, yY]`,
    /// Pa; reference weight `w`, m^3) at `at` to `f` (N).
    #[inline(always)]
    pub fn add_piola<R: Real>(&self, at: usize, w: R, p: &[R; 4], f: &mut Vector<R>) {
        let mut add = [R::splat(0.0); 8];
        for a in 0..4 {
            let (dx, dy) = (self.dndx::<R>(a, at), self.dndy::<R>(a, at));
            add[2 * a] = w * (p[0] * dx + p[1] * dy);
            add[2 * a + 1] = w * (p[2] * dx + p[3] * dy);
        }
        for (x, add) in f.iter_mut().zip(add) {
            *x += add;
        }
    }

    /// Adds `w B^T s` (in-plane stress components, Pa; weight `w`, m^3) at `at` to `f` (N).
    #[inline(always)]
    pub fn add_divergence<R: Real>(&self, at: usize, w: R, s: &[R; 4], f: &mut Vector<R>) {
        // The terms first, then the sums: as one loop, LLVM vectorised it across the nodes
        // (with gathers and scatters per batch: q4-full's all-yielding kernel 64 ns) instead
        // of across the lanes.
        let mut add = [R::splat(0.0); 8];
        for a in 0..4 {
            let (dx, dy) = (self.dndx::<R>(a, at), self.dndy::<R>(a, at));
            add[2 * a] = w * (dx * s[0] + dy * s[3]);
            add[2 * a + 1] = w * (dy * s[1] + dx * s[3]);
        }
        for (x, add) in f.iter_mut().zip(add) {
            *x += add;
        }
    }
}

/// The in-plane rows of a point's strain operator: `(dN_a/dx, dN_a/dy)` of node `a` at `at`,
/// 1/m. A Gauss point's ([`PointGeometry`]) and the axisymmetric ring's mean rows
/// (`axisymmetric.rs`) are read by the same strain and gradient loops ([`strain_on`],
/// [`gradient_on`]).
pub(crate) trait NodeRows {
    fn rows<R: Real>(&self, a: usize, at: usize) -> (R, R);
}

impl NodeRows for PointGeometry<Lanes> {
    #[inline(always)]
    fn rows<R: Real>(&self, a: usize, at: usize) -> (R, R) {
        (self.dndx::<R>(a, at), self.dndy::<R>(a, at))
    }
}

/// Small strain `[xx, yy, 0, gamma_xy]` of an element displacement vector `u` on the rows of
/// `g` at `at`: each component summed over the nodes in order, from 0.
#[inline(always)]
pub(crate) fn strain_on<G: NodeRows, R: Real>(g: &G, at: usize, u: &Vector<R>) -> [R; 4] {
    let zero = R::splat(0.0);
    let (mut xx, mut yy, mut xy) = (zero, zero, zero);
    for a in 0..4 {
        let (ux, uy) = (u[2 * a], u[2 * a + 1]);
        let (dx, dy) = g.rows::<R>(a, at);
        xx += dx * ux;
        yy += dy * uy;
        xy += dy * ux + dx * uy;
    }
    [xx, yy, zero, xy]
}

/// Displacement gradient `du/dX`, row-major `[xX, xY, yX, yY]`, of `u` on the rows of `g`
/// at `at`: each entry summed over the nodes in order, from 0.
#[inline(always)]
pub(crate) fn gradient_on<G: NodeRows, R: Real>(g: &G, at: usize, u: &Vector<R>) -> [R; 4] {
    let zero = R::splat(0.0);
    let mut grad = [zero; 4];
    for a in 0..4 {
        let (ux, uy) = (u[2 * a], u[2 * a + 1]);
        let (dx, dy) = g.rows::<R>(a, at);
        grad[0] += dx * ux;
        grad[1] += dy * ux;
        grad[2] += dx * uy;
        grad[3] += dy * uy;
    }
    grad
}

/// Per-element data in batches of [`LANES`] elements (`B`: one batch in lanes), each
/// distinct batch stored once: the batches of a structured mesh repeat (a uniform mesh's
/// rows share theirs), so the store holds few. Batches are shared only when every value of
/// every element has the same bits, so sharing changes no result.
pub struct SharedBatches<B> {
    distinct: Vec<B>,
    /// Per batch, its index into `distinct`.
    index: Vec<u32>,
}

impl<B> SharedBatches<B> {
    /// The batches of `n` elements, element `e`'s data `element(e)` (computed a batch at a
    /// time: the per-element data is never held for the whole mesh): `bits` appends an
    /// element's key (the bits of every value it stores), `lanes` makes a batch of up to
    /// [`LANES`] elements. The first error of `element` is returned.
    pub fn new<T, E>(
        n: usize,
        element: impl Fn(usize) -> Result<T, E>,
        bits: impl Fn(&T, &mut Vec<u64>),
        lanes: impl Fn(&[T]) -> B,
    ) -> Result<SharedBatches<B>, E> {
        let mut seen: HashMap<Vec<u64>, u32> = HashMap::new();
        let mut distinct = Vec::new();
        let mut index = Vec::with_capacity(n.div_ceil(LANES));
        let mut batch = Vec::with_capacity(LANES);
        for first in (0..n).step_by(LANES) {
            batch.clear();
            for e in first..(first + LANES).min(n) {
                batch.push(element(e)?);
            }
            let mut key = Vec::new();
            for element in &batch {
                bits(element, &mut key);
            }
            index.push(*seen.entry(key).or_insert_with(|| {
                distinct.push(lanes(&batch));
                (distinct.len() - 1) as u32
            }));
        }
        let mut shared = SharedBatches { distinct, index };
        shared.distinct.shrink_to_fit();
        Ok(shared)
    }

    /// The batch that holds `at` ([`Real::batch_of`]: an element or a batch).
    #[inline(always)]
    pub fn batch<R: Real>(&self, at: usize) -> &B {
        &self.distinct[self.index[R::batch_of(at)] as usize]
    }

    /// Distinct batches stored.
    pub fn n_distinct(&self) -> usize {
        self.distinct.len()
    }

    /// Heap bytes held.
    pub fn heap_bytes(&self) -> usize {
        vec_bytes(&self.distinct) + vec_bytes(&self.index)
    }
}
