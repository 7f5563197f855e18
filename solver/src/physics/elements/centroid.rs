//! The shape-function derivatives at the centroid of a Q4 (`xi = eta = 0`), where the
//! one-point element integrates and B-bar takes its dilatation, stored for nodes 0 and 1
//! only: nodes 2 and 3's are theirs negated, exactly.
//!
//! Why exactly: at the centroid the natural derivatives `(dN_a/dxi, dN_a/deta)` are
//! `(-1, -1) / 4`, `(1, -1) / 4`, `(1, 1) / 4`, `(-1, 1) / 4`, so node 2's are node 0's
//! negated and node 3's node 1's; [`PointGeometry::at`] maps each node's pair by the same
//! products, difference and quotient, and round-to-nearest rounds `-x` to `-round(x)`.
//!
//! Two kinds of operator:
//! - B-bar's ([`CentroidGeometry::dilatation`], [`CentroidGeometry::add_gradients`]) read
//!   nodes 2 and 3's derivatives as the stored ones negated, in the order [`PointGeometry`]'s
//!   operators use all four; IEEE 754 defines `x - y` as `x + (-y)`, so the bits are
//!   [`PointGeometry`]'s, with half the products in the forces.
//! - The one-point element's ([`CentroidGeometry::strain`], [`CentroidGeometry::add_transpose`])
//!   are Flanagan and Belytschko's (1981) form of `B` at the centroid: the strain is
//!   `b_0 (u_0 - u_2) + b_1 (u_1 - u_3)`, half the products of the four-term sum (its value to
//!   round-off, not its bits), and the forces `B^T s` of nodes 2 and 3 are nodes 0 and 1's
//!   negated. The element stores its `B` weighted by its volume for the forces, so that
//!   `w B^T s` takes no product by `w`.

use crate::lanes::real::Real;
use crate::lanes::simd::Lanes;
use crate::physics::elements::geometry::{PointGeometry, Vector};

/// dN_a/dx and dN_a/dy (1/m) of nodes 0 and 1 at the centroid of one element (`f64`) or of a
/// batch ([`Lanes`]); nodes 2 and 3's are these negated (see the module documentation).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct CentroidGeometry<R> {
    pub dndx: [R; 2],
    pub dndy: [R; 2],
}

impl CentroidGeometry<f64> {
    /// The centroid geometry of `point`, the [`PointGeometry`] at `xi = eta = 0`; `None` if
    /// its nodes 2 and 3 are not nodes 0 and 1 negated (it is not a centroid's).
    pub fn of(point: &PointGeometry<f64>) -> Option<CentroidGeometry<f64>> {
        let negated = (0..2).all(|a| {
            point.dndx[a + 2].to_bits() == (-point.dndx[a]).to_bits()
                && point.dndy[a + 2].to_bits() == (-point.dndy[a]).to_bits()
        });
        negated.then_some(CentroidGeometry {
            dndx: [point.dndx[0], point.dndx[1]],
            dndy: [point.dndy[0], point.dndy[1]],
        })
    }

    /// Every derivative times `factor` (the volume, m^3, for the one-point element's forces).
    pub fn scaled(&self, factor: f64) -> CentroidGeometry<f64> {
        CentroidGeometry {
            dndx: self.dndx.map(|x| x * factor),
            dndy: self.dndy.map(|x| x * factor),
        }
    }

    /// Every value's bits (the key under which equal geometry is shared).
    pub fn bits(&self, key: &mut Vec<u64>) {
        key.extend(self.dndx.iter().chain(&self.dndy).map(|x| x.to_bits()));
    }

    /// The lanes of `centroids` (at most [`crate::lanes::simd::LANES`]; missing lanes are zero).
    pub fn lanes(centroids: &[CentroidGeometry<f64>]) -> CentroidGeometry<Lanes> {
        let mut g = CentroidGeometry::<Lanes>::default();
        for (l, c) in centroids.iter().enumerate() {
            for a in 0..2 {
                g.dndx[a].0[l] = c.dndx[a];
                g.dndy[a].0[l] = c.dndy[a];
            }
        }
        g
    }
}

/// The kernels read the stored lanes in place ([`Real::of_batch`]), as [`PointGeometry`]'s.
impl CentroidGeometry<Lanes> {
    /// dN_a/dx and dN_a/dy of node `a` (0 or 1) at `at`, 1/m.
    #[inline(always)]
    fn derivatives<R: Real>(&self, a: usize, at: usize) -> (R, R) {
        (
            R::of_batch(&self.dndx[a], at),
            R::of_batch(&self.dndy[a], at),
        )
    }

    /// Small strain `[xx, yy, 0, gamma_xy]` of an element displacement vector at `at`, in
    /// the difference form (see the module documentation).
    #[inline(always)]
    pub fn strain<R: Real>(&self, at: usize, u: &Vector<R>) -> [R; 4] {
        let (dx0, dy0) = self.derivatives::<R>(0, at);
        let (dx1, dy1) = self.derivatives::<R>(1, at);
        // Nodes 0 and 1 relative to nodes 2 and 3.
        let (x0, y0, x1, y1) = (u[0] - u[4], u[1] - u[5], u[2] - u[6], u[3] - u[7]);
        let xy = (dy0 * x0 + dy1 * x1) + (dx0 * y0 + dx1 * y1);
        [dx0 * x0 + dx1 * x1, dy0 * y0 + dy1 * y1, R::splat(0.0), xy]
    }

    /// [`PointGeometry::dilatation`] at the centroid, with its bits.
    #[inline(always)]
    pub fn dilatation<R: Real>(&self, at: usize, u: &Vector<R>) -> R {
        let mut d = R::splat(-0.0);
        for a in 0..2 {
            let (dx, dy) = self.derivatives::<R>(a, at);
            d += dx * u[2 * a] + dy * u[2 * a + 1];
        }
        for a in 0..2 {
            let (dx, dy) = self.derivatives::<R>(a, at);
            d = d - (dx * u[2 * a + 4] + dy * u[2 * a + 5]);
        }
        d
    }

    /// Adds `B^T s` (in-plane stress components `s`, Pa) to `f`: N when this geometry is
    /// weighted by the volume (m^3; see [`CentroidGeometry::scaled`]). Nodes 2 and 3's terms are
    /// nodes 0 and 1's negated.
    #[inline(always)]
    pub fn add_transpose<R: Real>(&self, at: usize, s: &[R; 4], f: &mut Vector<R>) {
        let mut add = [R::splat(0.0); 4];
        for a in 0..2 {
            let (dx, dy) = self.derivatives::<R>(a, at);
            add[2 * a] = dx * s[0] + dy * s[3];
            add[2 * a + 1] = dy * s[1] + dx * s[3];
        }
        add_antisymmetric(f, add);
    }

    /// Adds `m grad N_a` (`f[2 a] += m dN_a/dx`, `f[2 a + 1] += m dN_a/dy`) to `f`, with the
    /// bits of those products over all four nodes.
    #[inline(always)]
    pub fn add_gradients<R: Real>(&self, at: usize, m: R, f: &mut Vector<R>) {
        let mut add = [R::splat(0.0); 4];
        for a in 0..2 {
            let (dx, dy) = self.derivatives::<R>(a, at);
            add[2 * a] = m * dx;
            add[2 * a + 1] = m * dy;
        }
        add_antisymmetric(f, add);
    }
}

/// The finite-deformation operators ([`crate::physics::kinematics`]) at the centroid, in the
/// difference form of the one-point element's.
impl CentroidGeometry<Lanes> {
    /// Displacement gradient `du/dX` at `at`, row-major `[xX, xY, yX, yY]`.
    #[inline(always)]
    pub fn gradient<R: Real>(&self, at: usize, u: &Vector<R>) -> [R; 4] {
        let (dx0, dy0) = self.derivatives::<R>(0, at);
        let (dx1, dy1) = self.derivatives::<R>(1, at);
        let (x0, y0, x1, y1) = (u[0] - u[4], u[1] - u[5], u[2] - u[6], u[3] - u[7]);
        [
            dx0 * x0 + dx1 * x1,
            dy0 * x0 + dy1 * x1,
            dx0 * y0 + dx1 * y1,
            dy0 * y0 + dy1 * y1,
        ]
    }

    /// Adds `P dN_a/dX` (first Piola-Kirchhoff stress `P`, row-major `[xX, xY, yX, yY]`, Pa)
    /// to `f`: N when this geometry is weighted by the volume (m^3).
    #[inline(always)]
    pub fn add_piola<R: Real>(&self, at: usize, p: &[R; 4], f: &mut Vector<R>) {
        let mut add = [R::splat(0.0); 4];
        for a in 0..2 {
            let (dx, dy) = self.derivatives::<R>(a, at);
            add[2 * a] = p[0] * dx + p[1] * dy;
            add[2 * a + 1] = p[2] * dx + p[3] * dy;
        }
        add_antisymmetric(f, add);
    }
}

/// Adds nodes 0 and 1's terms `add` to their entries of `f` and subtracts them from nodes 2
/// and 3's (whose terms are theirs negated: `+= -x` is `-= x`).
#[inline(always)]
fn add_antisymmetric<R: Real>(f: &mut Vector<R>, add: [R; 4]) {
    for (i, add) in add.into_iter().enumerate() {
        f[i] += add;
        f[i + 4] = f[i + 4] - add;
    }
}

#[cfg(test)]
mod tests {
    //! Reference: [`PointGeometry`]'s operators with all four nodes' derivatives stored, on
    //! distorted quadrilaterals: B-bar's bit for bit, the one-point element's to round-off.
    use super::*;
    use crate::lanes::simd::LANES;

    /// A distorted quadrilateral per lane (counter-clockwise, convex), displacements and
    /// stresses of mixed signs and magnitudes.
    fn batch() -> ([PointGeometry<f64>; LANES], Vector<Lanes>, [Lanes; 4]) {
        let points = std::array::from_fn(|l| {
            let t = l as f64;
            let wobble = |k: f64| 1e-3 * (0.37 * t + k).sin();
            let coords = [
                [wobble(0.1), wobble(0.2)],
                [2e-3 + wobble(0.3), wobble(0.4)],
                [2.3e-3 + wobble(0.5), 1.7e-3 + wobble(0.6)],
                [wobble(0.7), 1.9e-3 + wobble(0.8)],
            ];
            PointGeometry::at(&coords, [0.0, 0.0])
        });
        let lanes = |k: usize, scale: f64| {
            Lanes(std::array::from_fn(|l| {
                scale * ((k * LANES + l) as f64 * 0.91).sin() * 10f64.powi(((k + l) % 5) as i32)
            }))
        };
        let u = std::array::from_fn(|i| lanes(i, 1e-6));
        let s = std::array::from_fn(|i| lanes(i + 8, 1e6));
        (points, u, s)
    }

    /// [`batch`]'s quadrilaterals as the four-node geometry (`full`) and as the centroid's,
    /// per element and in lanes (`half`), with its displacements and stresses.
    struct Fixture {
        full: PointGeometry<Lanes>,
        centroids: Vec<CentroidGeometry<f64>>,
        half: CentroidGeometry<Lanes>,
        u: Vector<Lanes>,
        s: [Lanes; 4],
    }

    fn fixture() -> Fixture {
        let (points, u, s) = batch();
        let centroids: Vec<_> = points
            .iter()
            .map(|p| CentroidGeometry::of(p).unwrap())
            .collect();
        Fixture {
            full: PointGeometry::lanes(&points),
            half: CentroidGeometry::lanes(&centroids),
            centroids,
            u,
            s,
        }
    }

    fn bits(x: &[Lanes]) -> Vec<u64> {
        x.iter().flat_map(|l| l.0.map(f64::to_bits)).collect()
    }

    #[test]
    fn b_bar_operators_have_the_point_geometry_bits() {
        let Fixture {
            full, half, u, s, ..
        } = fixture();
        assert_eq!(
            bits(&[half.dilatation(0, &u)]),
            bits(&[full.dilatation(0, &u)])
        );
        // The gradients, as B-bar's mean-stress forces add them.
        let (mut fa, mut fb) = (u, u);
        for a in 0..4 {
            fa[2 * a] += s[0] * full.dndx[a];
            fa[2 * a + 1] += s[0] * full.dndy[a];
        }
        half.add_gradients(0, s[0], &mut fb);
        assert_eq!(bits(&fa), bits(&fb));
    }

    /// The one-point operators (difference form, volume-weighted `B`) against the four-node
    /// sums: equal to round-off. Bound: 3e-15 of the largest value, about 10x the measured
    /// 1.9e-16 (strain) and 2.9e-16 (forces), a few roundings of sums of four products.
    #[test]
    fn one_point_operators_equal_the_four_node_sums() {
        let Fixture {
            full,
            centroids,
            half,
            u,
            s,
        } = fixture();
        let w = 3.7e-5;
        let weighted: Vec<_> = centroids.iter().map(|c| c.scaled(w)).collect();
        let weighted = CentroidGeometry::lanes(&weighted);
        let close = |a: &[Lanes], b: &[Lanes], what: &str| {
            let scale = a
                .iter()
                .flat_map(|x| x.0)
                .fold(0.0f64, |m, x| m.max(x.abs()));
            for (x, y) in a.iter().flat_map(|x| x.0).zip(b.iter().flat_map(|x| x.0)) {
                assert!((x - y).abs() <= 3e-15 * scale, "{what}: {x:e} vs {y:e}");
            }
        };
        close(&full.strain(0, &u), &half.strain(0, &u), "strain");
        let zero = [Lanes::splat(0.0); 8];
        let (mut fa, mut fb) = (zero, zero);
        full.add_divergence(0, Lanes::splat(w), &s, &mut fa);
        weighted.add_transpose(0, &s, &mut fb);
        close(&fa, &fb, "forces");
        // Nodes 2 and 3's forces are exactly nodes 0 and 1's negated.
        for i in 0..4 {
            assert_eq!(bits(&[fb[i + 4]]), bits(&[Lanes::splat(0.0) - fb[i]]));
        }
    }

    #[test]
    fn only_a_centroid_geometry_is_taken() {
        let coords = [[0.0, 0.0], [2e-3, 1e-4], [2.3e-3, 1.7e-3], [-1e-4, 1.9e-3]];
        assert!(CentroidGeometry::of(&PointGeometry::at(&coords, [0.0, 0.0])).is_some());
        let gauss = PointGeometry::at(&coords, [0.3, -0.2]);
        assert_eq!(CentroidGeometry::of(&gauss), None);
    }
}
