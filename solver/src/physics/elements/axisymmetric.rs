//! The three elements in the axisymmetric geometry (`geometry: axisymmetric`, `ALGORITHM.md`
//! section 3d): [`Axisymmetric`] adds to a plane element the hoop strain and the ring's
//! weights.
//!
//! The section's `x` runs from the rim to the axis at `x_a` (the half model's mid-span line),
//! so a point's radius is `r = x_a - x` and the radial displacement `u_r = -u_x`. The strain
//! `[xx, yy, zz, gamma_xy]` carries the hoop strain `eps_theta = u_r / r` in its `zz` entry
//! (plane strain's zero), `d eps_theta / d u_{x,a} = -N_a / r` (Hughes, *The Finite Element
//! Method*, section 2.12; Zienkiewicz & Taylor vol. 1, chapter 5). Weights are the whole
//! ring's, `2 pi r det J` (m^3), so forces are N on the ring and energies J of the whole body;
//! the element's nodal masses are the row sums `rho int N_a 2 pi r dA` (2 x 2 Gauss: exact for
//! the bilinear element), not quarters, so a node far from the axis carries its larger ring.
//! - `q4-full`: the four Gauss points with their hoop rows.
//! - `q4-sri`: B-bar with the hoop term (Hughes 1980): each point's volumetric part (of its
//!   three normal strains) is replaced by the element's mean dilatation `int (div u + u_r / r)
//!   dV / V`. (In plane strain the centroid's dilatation is that mean exactly; with the ring's
//!   weights it is not, and the centroid value would fail the patch test.)
//! - `q4-1pt`: the mean strain `int B dV / V` (Flanagan & Belytschko's uniform strain, on the
//!   ring's volume), the ring's exact volume, and the plane element's hourglass control with
//!   its stiffness made with that volume (the element's thickness `2 pi` times its area
//!   centroid's radius).
//!
//! The axis nodes have `u_x = 0` (the half model's symmetry condition); no integration point
//! lies on the axis, so `1 / r` is finite everywhere it is evaluated.

use crate::input::error::{Error, Result};
use crate::lanes::real::{Real, THIRD};
use crate::lanes::simd::Lanes;
use crate::mesh::Mesh;
use crate::physics::elements::element::{
    gauss_geometry, shape, Formulation, FullQ4, OnePointQ4, SelectiveQ4, GAUSS_XI,
};
use crate::physics::elements::geometry::{gradient_on, strain_on, NodeRows, SharedBatches, Vector};

/// A plane element formulation in the axisymmetric geometry.
pub struct Axisymmetric<F> {
    pub(crate) plane: F,
    ring: SharedBatches<Ring<Lanes>>,
}

/// What the ring adds to an element's geometry, for one element (`f64`) or a batch.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Ring<R> {
    /// Whole-ring weight `2 pi r det J` of each Gauss point, m^3.
    weight: [R; 4],
    /// `d eps_theta / d u_{x,a}` (= `-N_a / r`) at each Gauss point (point x node), 1/m.
    hoop: [[R; 4]; 4],
    /// The ring-volume means `int b dV / V` of the strain rows `dN_a/dx`, `dN_a/dy` and
    /// `-N_a / r`, 1/m: the mean-strain operator of the one-point element and of B-bar's
    /// dilatation (Flanagan & Belytschko 1981; Hughes 1980), which pass the axisymmetric patch
    /// test exactly (a centroid value would not: `r` varies over the element).
    mean: [[R; 4]; 3],
    /// The row-sum masses per unit density, `int N_a 2 pi r dA`, m^3.
    mass: [R; 4],
}

impl Ring<f64> {
    /// Element `e`'s ring about the axis at `axis` (m).
    fn of(mesh: &Mesh, axis: f64, e: usize) -> Result<Ring<f64>> {
        let radii = mesh.element_coords(e).map(|p| axis - p[0]);
        let radius_at =
            |xi: [f64; 2]| -> f64 { shape(xi).iter().zip(radii).map(|(n, r)| n * r).sum::<f64>() };
        let points = gauss_geometry(mesh, e)?;
        let mut ring = Ring::<f64>::default();
        let mut sums = [[0.0; 4]; 3];
        for (p, xi) in GAUSS_XI.into_iter().enumerate() {
            let (n, r) = (shape(xi), radius_at(xi));
            let weight = std::f64::consts::TAU * r * points[p].det_j;
            ring.weight[p] = weight;
            for a in 0..4 {
                ring.hoop[p][a] = -n[a] / r;
                ring.mass[a] += n[a] * weight;
                sums[0][a] += weight * points[p].dndx[a];
                sums[1][a] += weight * points[p].dndy[a];
                sums[2][a] += weight * ring.hoop[p][a];
            }
        }
        let volume: f64 = ring.weight.iter().sum();
        ring.mean = sums.map(|row| row.map(|x| x / volume));
        let finite = ring.weight.iter().chain(&ring.mass).all(|x| x.is_finite())
            && ring
                .hoop
                .iter()
                .chain(&ring.mean)
                .flatten()
                .all(|x| x.is_finite());
        let inside = radii.iter().all(|&r| r >= 0.0) && ring.weight.iter().all(|&w| w > 0.0);
        if !(finite && inside) {
            return Err(Error::Run {
                step: 0,
                time_s: 0.0,
                what: format!(
                    "element {e} (nodes {:?}) is not between the rim and the axis at x = {axis} m (radii {radii:?} m)",
                    mesh.elements[e]
                ),
            });
        }
        Ok(ring)
    }

    fn bits(&self, key: &mut Vec<u64>) {
        let rows = self.hoop.iter().chain(&self.mean).flatten();
        let values = self.weight.iter().chain(rows).chain(&self.mass);
        key.extend(values.map(|x| x.to_bits()));
    }

    fn lanes(elements: &[Ring<f64>]) -> Ring<Lanes> {
        let mut g = Ring::<Lanes>::default();
        for (l, d) in elements.iter().enumerate() {
            for p in 0..4 {
                g.weight[p].0[l] = d.weight[p];
                g.mass[p].0[l] = d.mass[p];
                for a in 0..4 {
                    g.hoop[p][a].0[l] = d.hoop[p][a];
                }
            }
            for (row, lanes) in d.mean.iter().zip(g.mean.iter_mut()) {
                for a in 0..4 {
                    lanes[a].0[l] = row[a];
                }
            }
        }
        g
    }
}

/// The ring's data of `at`, read in place as the plane geometry's ([`Real::of_batch`]).
impl Ring<Lanes> {
    #[inline(always)]
    pub(crate) fn weight<R: Real>(&self, p: usize, at: usize) -> R {
        R::of_batch(&self.weight[p], at)
    }

    /// `eps_theta` at Gauss point `p` of the element displacements `u`.
    #[inline(always)]
    pub(crate) fn hoop_strain<R: Real>(&self, p: usize, at: usize, u: &Vector<R>) -> R {
        let mut e = R::splat(0.0);
        for a in 0..4 {
            e += R::of_batch(&self.hoop[p][a], at) * u[2 * a];
        }
        e
    }

    /// Adds the hoop row's forces `d eps_theta / d u_{x,a} * ws` (`ws`: weight times the hoop
    /// stress, N m) at Gauss point `p` to `f`.
    #[inline(always)]
    pub(crate) fn add_hoop_forces<R: Real>(&self, p: usize, at: usize, ws: R, f: &mut Vector<R>) {
        for a in 0..4 {
            f[2 * a] += R::of_batch(&self.hoop[p][a], at) * ws;
        }
    }

    /// The mean-strain rows of node `a`: `(dN_a/dx, dN_a/dy, -N_a / r)` averaged, 1/m.
    #[inline(always)]
    fn mean_rows<R: Real>(&self, a: usize, at: usize) -> (R, R, R) {
        let m = &self.mean;
        let of = |row: usize| R::of_batch(&m[row][a], at);
        (of(0), of(1), of(2))
    }

    /// The mean hoop strain `sum_a (-N_a / r) u_{x,a}` averaged (the mean rows' third),
    /// summed over the nodes in order, from 0.
    #[inline(always)]
    fn mean_hoop<R: Real>(&self, at: usize, u: &Vector<R>) -> R {
        let mut hoop = R::splat(0.0);
        for a in 0..4 {
            hoop += R::of_batch(&self.mean[2][a], at) * u[2 * a];
        }
        hoop
    }

    /// The mean strain `[xx, yy, theta, gamma_xy]` of the element displacements `u`: the
    /// in-plane strain on the mean rows (a Gauss point's loop, [`strain_on`]) and the mean hoop
    /// strain (each component its own sum: the bits of one loop over the nodes).
    #[inline(always)]
    fn mean_strain<R: Real>(&self, at: usize, u: &Vector<R>) -> [R; 4] {
        let [xx, yy, _, xy] = strain_on(&MeanRows(self), at, u);
        [xx, yy, self.mean_hoop(at, u), xy]
    }

    /// The mean displacement gradient `[xX, xY, yX, yY]` of `u` and its mean hoop gradient
    /// `u_r / R` (dimensionless): the one-point element's under finite deformation (a Gauss
    /// point's gradient loop on the mean rows, [`gradient_on`]).
    #[inline(always)]
    pub(crate) fn mean_gradient<R: Real>(&self, at: usize, u: &Vector<R>) -> ([R; 4], R) {
        (gradient_on(&MeanRows(self), at, u), self.mean_hoop(at, u))
    }

    /// Adds `w P : d(mean F)/du` to `f` (N): `p` the in-plane first Piola-Kirchhoff stress
    /// (row-major `[xX, xY, yX, yY]`, Pa), `p_theta` its hoop entry `tau_theta / F_theta`
    /// (Pa), `w` the ring's volume (m^3).
    #[inline(always)]
    pub(crate) fn add_mean_piola<R: Real>(
        &self,
        at: usize,
        w: R,
        (p, p_theta): (&[R; 4], R),
        f: &mut Vector<R>,
    ) {
        for a in 0..4 {
            let (dx, dy, h) = self.mean_rows::<R>(a, at);
            f[2 * a] += w * (p[0] * dx + p[1] * dy + p_theta * h);
            f[2 * a + 1] += w * (p[2] * dx + p[3] * dy);
        }
    }

    /// The mean dilatation `xx + yy + theta` of `u`.
    #[inline(always)]
    fn mean_dilatation<R: Real>(&self, at: usize, u: &Vector<R>) -> R {
        let s = self.mean_strain(at, u);
        s[0] + s[1] + s[2]
    }

    /// Adds `w B_mean^T s` (stress `[xx, yy, theta, xy]`, Pa; weight `w`, m^3) to `f` (N).
    #[inline(always)]
    fn add_mean_transpose<R: Real>(&self, at: usize, w: R, s: &[R; 4], f: &mut Vector<R>) {
        for a in 0..4 {
            let (dx, dy, h) = self.mean_rows::<R>(a, at);
            f[2 * a] += w * (dx * s[0] + dy * s[3] + h * s[2]);
            f[2 * a + 1] += w * (dy * s[1] + dx * s[3]);
        }
    }

    /// Adds `m` times the mean dilatation's row (`m`: a weighted mean stress, N m) to `f`.
    #[inline(always)]
    fn add_dilatation_forces<R: Real>(&self, at: usize, m: R, f: &mut Vector<R>) {
        for a in 0..4 {
            let (dx, dy, h) = self.mean_rows::<R>(a, at);
            f[2 * a] += m * (dx + h);
            f[2 * a + 1] += m * dy;
        }
    }
}

/// The ring's in-plane mean rows `(dN_a/dx, dN_a/dy)` averaged, as a point's strain rows.
struct MeanRows<'a>(&'a Ring<Lanes>);

impl NodeRows for MeanRows<'_> {
    #[inline(always)]
    fn rows<R: Real>(&self, a: usize, at: usize) -> (R, R) {
        let m = &self.0.mean;
        (R::of_batch(&m[0][a], at), R::of_batch(&m[1][a], at))
    }
}

/// The element kinds that run in the axisymmetric geometry.
pub trait RingElement: Formulation + Sized {
    /// The element on `mesh` about the axis at `axis` (m); `hourglass` and `p_modulus` (Pa)
    /// as for the plane element (used by `q4-1pt` only).
    fn on_ring(mesh: &Mesh, axis: f64, hourglass: f64, p_modulus: f64) -> Result<Self>;
}

impl<F: RingElement> Axisymmetric<F> {
    /// The element `F` on `mesh` in the axisymmetric geometry about the axis at `axis` (m).
    pub fn new(mesh: &Mesh, axis: f64, hourglass: f64, p_modulus: f64) -> Result<Self> {
        Ok(Axisymmetric {
            plane: F::on_ring(mesh, axis, hourglass, p_modulus)?,
            ring: SharedBatches::new(
                mesh.elements.len(),
                |e| Ring::of(mesh, axis, e),
                Ring::bits,
                Ring::lanes,
            )?,
        })
    }

    #[inline(always)]
    pub(crate) fn ring<R: Real>(&self, at: usize) -> &Ring<Lanes> {
        self.ring.batch::<R>(at)
    }

    /// The ring's Gauss weights of `at`.
    #[inline(always)]
    fn ring_weights<R: Real>(&self, at: usize) -> [R; 4] {
        let ring = self.ring::<R>(at);
        std::array::from_fn(|p| ring.weight(p, at))
    }

    /// Row-sum masses of `e`, kg.
    fn ring_masses(&self, e: usize, density: f64) -> [f64; 4] {
        let ring = self.ring::<f64>(e);
        std::array::from_fn(|a| density * f64::of_batch(&ring.mass[a], e))
    }
}

impl RingElement for FullQ4 {
    fn on_ring(mesh: &Mesh, _: f64, _: f64, _: f64) -> Result<FullQ4> {
        FullQ4::new(mesh, 1.0)
    }
}

impl RingElement for SelectiveQ4 {
    fn on_ring(mesh: &Mesh, _: f64, _: f64, _: f64) -> Result<SelectiveQ4> {
        SelectiveQ4::new(mesh, 1.0)
    }
}

impl RingElement for OnePointQ4 {
    /// The ring's volume as the element's: its thickness `V_ring / area`.
    fn on_ring(mesh: &Mesh, axis: f64, hourglass: f64, p_modulus: f64) -> Result<OnePointQ4> {
        let thickness = |e, area| {
            let ring = Ring::of(mesh, axis, e)?;
            Ok(ring.weight.iter().sum::<f64>() / area)
        };
        OnePointQ4::with_thickness(mesh, thickness, hourglass, p_modulus)
    }
}

/// The [`Formulation`] items every ring element shares: the plane element's connectivity,
/// the ring's volume (the sum of its Gauss weights), row-sum masses and storage.
macro_rules! ring_bookkeeping {
    () => {
        fn connectivity(&self) -> &[[u32; 4]] {
            self.plane.connectivity()
        }
        fn volume(&self, e: usize) -> f64 {
            self.ring_weights::<f64>(e).iter().sum()
        }
        fn nodal_masses(&self, e: usize, density: f64) -> [f64; 4] {
            self.ring_masses(e, density)
        }
        fn heap_bytes(&self) -> usize {
            self.plane.heap_bytes() + self.ring.heap_bytes()
        }
    };
}

/// No element stiffness matrices in the axisymmetric geometry: their product drops node 0's
/// columns as a rigid translation ([`crate::kernels::stiffness`]), and a radial translation of a
/// ring strains it (`eps_theta = u_r / r`).
impl Formulation for Axisymmetric<FullQ4> {
    const POINTS: usize = 4;
    const STIFFNESS_MATRIX_PAYS: bool = false;
    #[inline(always)]
    fn strain<R: Real>(&self, at: usize, p: usize, u: &Vector<R>, shared: R) -> [R; 4] {
        let s = self.plane.strain(at, p, u, shared);
        let hoop = self.ring::<R>(at).hoop_strain(p, at, u);
        [s[0], s[1], hoop, s[3]]
    }
    #[inline(always)]
    fn weights<R: Real>(&self, at: usize) -> [R; 4] {
        self.ring_weights(at)
    }
    fn point_xi(&self) -> &'static [[f64; 2]] {
        &GAUSS_XI
    }
    #[inline(always)]
    fn add_point_forces<R: Real>(
        &self,
        at: usize,
        p: usize,
        s: &[R; 4],
        f: &mut Vector<R>,
        _: &mut R,
    ) {
        let ring = self.ring::<R>(at);
        let w = ring.weight(p, at);
        self.plane.points::<R>(at)[p].add_divergence(at, w, s, f);
        ring.add_hoop_forces(p, at, w * s[2], f);
    }
    ring_bookkeeping!();
}

impl Formulation for Axisymmetric<SelectiveQ4> {
    const POINTS: usize = 4;
    const STIFFNESS_MATRIX_PAYS: bool = false;
    /// The element's mean dilatation, hoop strain included.
    #[inline(always)]
    fn shared<R: Real>(&self, at: usize, u: &Vector<R>) -> R {
        self.ring::<R>(at).mean_dilatation(at, u)
    }
    /// B-bar: the point's three normal strains shifted so that their sum is the mean
    /// dilatation `mean`.
    #[inline(always)]
    fn strain<R: Real>(&self, at: usize, p: usize, u: &Vector<R>, mean: R) -> [R; 4] {
        let s = self.plane.full.strain(at, p, u, mean);
        let hoop = self.ring::<R>(at).hoop_strain(p, at, u);
        let shift = (mean - s[0] - s[1] - hoop) * THIRD;
        [s[0] + shift, s[1] + shift, hoop + shift, s[3]]
    }
    #[inline(always)]
    fn weights<R: Real>(&self, at: usize) -> [R; 4] {
        self.ring_weights(at)
    }
    fn point_xi(&self) -> &'static [[f64; 2]] {
        &GAUSS_XI
    }
    /// The deviatoric stress on the point's rows (hoop included); its weighted mean stress
    /// into `mean_total`.
    #[inline(always)]
    fn add_point_forces<R: Real>(
        &self,
        at: usize,
        p: usize,
        s: &[R; 4],
        f: &mut Vector<R>,
        mean_total: &mut R,
    ) {
        let ring = self.ring::<R>(at);
        let w = ring.weight(p, at);
        let mean = (s[0] + s[1] + s[2]) * THIRD;
        *mean_total += w * mean;
        let deviator = [s[0] - mean, s[1] - mean, s[2] - mean, s[3]];
        self.plane.full.points::<R>(at)[p].add_divergence(at, w, &deviator, f);
        ring.add_hoop_forces(p, at, w * deviator[2], f);
    }
    /// The points' weighted mean stress on the mean dilatation's row (hoop included).
    #[inline(always)]
    fn finish_forces<R: Real>(&self, at: usize, mean_total: R, f: &mut Vector<R>) {
        self.ring::<R>(at).add_dilatation_forces(at, mean_total, f);
    }
    ring_bookkeeping!();
}

impl Formulation for Axisymmetric<OnePointQ4> {
    const POINTS: usize = 1;
    const STIFFNESS_MATRIX_PAYS: bool = false;
    /// The element's mean strain (hoop included).
    #[inline(always)]
    fn strain<R: Real>(&self, at: usize, _: usize, u: &Vector<R>, _: R) -> [R; 4] {
        self.ring::<R>(at).mean_strain(at, u)
    }
    /// The ring's volume.
    #[inline(always)]
    fn weights<R: Real>(&self, at: usize) -> [R; 4] {
        let w = self.ring_weights::<R>(at);
        let zero = R::splat(0.0);
        [w[0] + w[1] + w[2] + w[3], zero, zero, zero]
    }
    fn point_xi(&self) -> &'static [[f64; 2]] {
        self.plane.point_xi()
    }
    #[inline(always)]
    fn add_point_forces<R: Real>(
        &self,
        at: usize,
        _: usize,
        s: &[R; 4],
        f: &mut Vector<R>,
        _: &mut R,
    ) {
        let w = self.weights::<R>(at)[0];
        self.ring::<R>(at).add_mean_transpose(at, w, s, f);
    }
    /// The plane element's hourglass control, its stiffness made with the ring's volume.
    #[inline(always)]
    fn add_hourglass<R: Real>(&self, at: usize, u: &Vector<R>, f: &mut Vector<R>) -> R {
        self.plane.add_hourglass(at, u, f)
    }
    #[inline(always)]
    fn hourglass_energy<R: Real>(&self, at: usize, u: &Vector<R>) -> R {
        self.plane.hourglass_energy(at, u)
    }
    ring_bookkeeping!();
}
