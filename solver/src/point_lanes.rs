//! The geometry of one integration point in [`crate::simd::LANES`] elements (struct of arrays) and the
//! strain and divergence operators of [`crate::element::PointGeometry`] in lanes, for the
//! batched kernels ([`crate::batch`]): the same expressions in the same order per lane.

use crate::simd::Lanes;

/// Element displacement vectors of a batch: dof x lanes, m.
pub type VectorLanes = [Lanes; 8];

/// [`crate::element::PointGeometry`] of one point in [`crate::simd::LANES`] elements.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PointLanes {
    /// dN_a/dx per lane, 1/m
    pub dndx: [Lanes; 4],
    /// dN_a/dy per lane, 1/m
    pub dndy: [Lanes; 4],
    /// det J per lane
    pub det_j: Lanes,
}

impl PointLanes {
    /// [`crate::element::PointGeometry::strain`] in lanes: components `[xx, yy, 0, gamma_xy]`.
    #[inline(always)]
    pub fn strain(&self, u: &VectorLanes) -> [Lanes; 4] {
        let zero = Lanes::splat(0.0);
        let (mut xx, mut yy, mut xy) = (zero, zero, zero);
        for a in 0..4 {
            let (ux, uy) = (u[2 * a], u[2 * a + 1]);
            xx += self.dndx[a] * ux;
            yy += self.dndy[a] * uy;
            xy += self.dndy[a] * ux + self.dndx[a] * uy;
        }
        [xx, yy, zero, xy]
    }

    /// [`crate::element::PointGeometry::dilatation`] in lanes (an iterator sum: it starts from -0.0).
    #[inline(always)]
    pub fn dilatation(&self, u: &VectorLanes) -> Lanes {
        let mut d = Lanes::splat(-0.0);
        for a in 0..4 {
            d += self.dndx[a] * u[2 * a] + self.dndy[a] * u[2 * a + 1];
        }
        d
    }

    /// [`crate::element::PointGeometry::add_divergence`] in lanes.
    #[inline(always)]
    pub fn add_divergence(&self, w: Lanes, s: &[Lanes; 4], f: &mut VectorLanes) {
        for a in 0..4 {
            f[2 * a] += w * (self.dndx[a] * s[0] + self.dndy[a] * s[3]);
            f[2 * a + 1] += w * (self.dndy[a] * s[1] + self.dndx[a] * s[3]);
        }
    }
}
