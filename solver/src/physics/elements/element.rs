//! 4-node quadrilateral elements in plane strain: internal forces from stresses (eqs 13-14),
//! lumped mass, and the element eigenvalue bound behind the stable time step (eq. 15).
//!
//! - [`FullQ4`]: 2x2 Gauss.
//! - [`SelectiveQ4`]: B-bar (Hughes): deviatoric strain at 2x2 points, volumetric strain at
//!   the centroid; no volumetric locking under plastic flow.
//! - [`OnePointQ4`]: one point with Flanagan-Belytschko hourglass control (stiffness form).
//!
//! Element displacement vectors are `[ux0, uy0, ux1, uy1, ux2, uy2, ux3, uy3]`, nodes
//! counter-clockwise. Every element has out-of-plane thickness `W` (the plate width), so
//! forces are N and volumes m^3 for the whole width.

use crate::input::error::{Error, Result};
use crate::lanes::heap::vec_bytes;
use crate::lanes::real::{Real, THIRD};
use crate::lanes::simd::{Lanes, LANES};
use crate::mesh::Mesh;
use crate::physics::elements::centroid::CentroidGeometry;
use crate::physics::elements::geometry::{PointGeometry, SharedBatches, Vector, NODE_XI};
use crate::physics::materials::material::{ConstitutiveModel, Elastic};

pub type ElementVector = [f64; 8];

const G: f64 = 0.577_350_269_189_625_8; // 1/sqrt(3)
/// Natural coordinates of the 2x2 Gauss points (ordered as the nodes).
pub(crate) const GAUSS_XI: [[f64; 2]; 4] = [[-G, -G], [G, -G], [G, G], [-G, G]];

/// Shape function values at natural coordinates.
pub fn shape(xi: [f64; 2]) -> [f64; 4] {
    NODE_XI.map(|n| 0.25 * (1.0 + xi[0] * n[0]) * (1.0 + xi[1] * n[1]))
}

/// Energy contributions of [`Real::LANES`] elements in one step, J.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Energy<R> {
    pub strain: R,
    pub plastic_work: R,
    pub hourglass: R,
}

/// Energy contributions of one element in one step, J.
pub type ElementEnergy = Energy<f64>;

impl<R: Real> std::ops::AddAssign for Energy<R> {
    #[inline(always)]
    fn add_assign(&mut self, o: Energy<R>) {
        self.strain += o.strain;
        self.plastic_work += o.plastic_work;
        self.hourglass += o.hourglass;
    }
}

impl<R: Real> Energy<R> {
    /// Per lane: `a` where `mask`, else `b`.
    #[inline(always)]
    pub fn select(mask: R::Mask, a: Energy<R>, b: Energy<R>) -> Energy<R> {
        Energy {
            strain: R::select(mask, a.strain, b.strain),
            plastic_work: R::select(mask, a.plastic_work, b.plastic_work),
            hourglass: R::select(mask, a.hourglass, b.hourglass),
        }
    }
}

impl Energy<Lanes> {
    /// Lane `l`'s energies.
    #[inline(always)]
    pub fn lane(&self, l: usize) -> ElementEnergy {
        ElementEnergy {
            strain: self.strain.0[l],
            plastic_work: self.plastic_work.0[l],
            hourglass: self.hourglass.0[l],
        }
    }

    /// Adds `energy` to lane `l`.
    #[inline(always)]
    pub fn add_to_lane(&mut self, l: usize, energy: ElementEnergy) {
        self.strain.0[l] += energy.strain;
        self.plastic_work.0[l] += energy.plastic_work;
        self.hourglass.0[l] += energy.hourglass;
    }

    /// The lanes added in lane order. How a chunk's element energies are summed: element
    /// `e` into the partial sum of lane `e mod LANES` in element order, then the partial sums
    /// in lane order (the same additions on the scalar path and in lanes, on any number of
    /// threads; a sum in element order would be a chain of dependent additions, ~17 % of
    /// the elastic kernel's time).
    #[inline(always)]
    pub fn lane_total(&self) -> ElementEnergy {
        let mut total = ElementEnergy::default();
        for l in 0..LANES {
            total += self.lane(l);
        }
        total
    }
}

/// An element formulation over a whole mesh (geometry precomputed per element, stored once
/// in batches: [`SharedBatches`]). Its kernels are written once over the number type `R`
/// ([`Real`]): `at` is an element for `R = f64` (the scalar reference path) and a batch of
/// [`crate::lanes::simd::LANES`] elements `at * LANES ..` for `R = Lanes` (the batched path).
pub trait Formulation: Sync + 'static {
    /// Integration points that carry material state (4 or 1).
    const POINTS: usize;
    /// Whether an elastic run is faster with precomputed element stiffness matrices than
    /// with the stress path (measured by `impact-bench throughput`: not for one point; see
    /// [`crate::time_loop::model::Kernel::Elastic`]).
    const STIFFNESS_MATRIX_PAYS: bool = true;
    /// The four node numbers of every element, counter-clockwise.
    fn connectivity(&self) -> &[[u32; 4]];
    fn n_elements(&self) -> usize {
        self.connectivity().len()
    }
    #[inline(always)]
    fn nodes(&self, e: usize) -> [u32; 4] {
        self.connectivity()[e]
    }
    /// What the points of `at` share for displacements `u` (B-bar: the centroid dilatation),
    /// computed once per evaluation; unused by the others.
    #[inline(always)]
    fn shared<R: Real>(&self, _at: usize, _u: &Vector<R>) -> R {
        R::splat(0.0)
    }
    /// Strain at integration point `p` of `at` (`shared`: [`Formulation::shared`]).
    fn strain<R: Real>(&self, at: usize, p: usize, u: &Vector<R>, shared: R) -> [R; 4];
    /// Strain at each integration point of `at` (the first `POINTS` entries are set): point x
    /// component.
    #[inline(always)]
    fn strains<R: Real>(&self, at: usize, u: &Vector<R>) -> [[R; 4]; 4] {
        let shared = self.shared(at, u);
        let mut strains = [[R::splat(0.0); 4]; 4];
        for (p, s) in strains.iter_mut().enumerate().take(Self::POINTS) {
            *s = self.strain(at, p, u, shared);
        }
        strains
    }
    /// Integration weight of each point of `at`: det J * W (m^3).
    fn weights<R: Real>(&self, at: usize) -> [R; 4];
    /// Natural coordinates of each integration point.
    fn point_xi(&self) -> &'static [[f64; 2]];
    /// Adds point `p`'s part of the nodal forces for its stress `s` (Pa) to `f` (N), and to
    /// `acc` what the points' forces share (B-bar: the weighted mean stress); points in order
    /// from 0, `f` and `acc` from 0.
    fn add_point_forces<R: Real>(
        &self,
        at: usize,
        p: usize,
        s: &[R; 4],
        f: &mut Vector<R>,
        acc: &mut R,
    );
    /// Adds to `f` what the points' forces share, from their `acc`.
    #[inline(always)]
    fn finish_forces<R: Real>(&self, _at: usize, _acc: R, _f: &mut Vector<R>) {}
    /// Nodal forces `sum_p w_p B_p^T s_p` of the point stresses (point x component, Pa), N.
    #[inline(always)]
    fn forces<R: Real>(&self, at: usize, stresses: &[[R; 4]; 4]) -> Vector<R> {
        let (mut f, mut acc) = ([R::splat(0.0); 8], R::splat(0.0));
        for (p, s) in stresses.iter().enumerate().take(Self::POINTS) {
            self.add_point_forces(at, p, s, &mut f, &mut acc);
        }
        self.finish_forces(at, acc, &mut f);
        f
    }
    /// Adds hourglass forces to `f`, returns the hourglass energy (J).
    #[inline(always)]
    fn add_hourglass<R: Real>(&self, _at: usize, _u: &Vector<R>, _f: &mut Vector<R>) -> R {
        R::splat(0.0)
    }
    /// Hourglass energy (J) of `at` at `u`, without forces.
    #[inline(always)]
    fn hourglass_energy<R: Real>(&self, _at: usize, _u: &Vector<R>) -> R {
        R::splat(0.0)
    }
    /// Element volume (area * W), m^3.
    fn volume(&self, e: usize) -> f64;
    /// Lumped masses of the element's four nodes for `density` (kg/m^3), kg: a quarter of
    /// its mass each unless the formulation says otherwise (the axisymmetric row sums).
    fn nodal_masses(&self, e: usize, density: f64) -> [f64; 4] {
        [0.25 * density * self.volume(e); 4]
    }
    /// Heap bytes of the connectivity and the geometry.
    fn heap_bytes(&self) -> usize;
    /// Internal nodal forces and energies of `at`, updating its points' material states
    /// ([`response`]); small strain ([`small_strain_response`]) unless the formulation is a
    /// finite-deformation one ([`crate::physics::elements::finite_element::UpdatedLagrangian`]).
    #[inline(always)]
    fn response<M: ConstitutiveModel, R: Real>(
        &self,
        material: &M,
        at: usize,
        u: &Vector<R>,
        states: (&mut [M::Batch], R::Mask),
    ) -> (Vector<R>, Energy<R>)
    where
        Self: Sized,
    {
        small_strain_response(self, material, at, u, states)
    }
}

/// Internal nodal forces and energies of `at` ([`Formulation`]), updating the material
/// states of its points: point `p`'s are `batches[p]` (the batch that holds `at`), written
/// where `active` has the lane (inactive lanes: states untouched, results unspecified). The
/// formulation's [`Formulation::response`]: small strain unless it says otherwise.
#[inline(always)]
pub fn response<F: Formulation, M: ConstitutiveModel, R: Real>(
    formulation: &F,
    material: &M,
    at: usize,
    u: &Vector<R>,
    states: (&mut [M::Batch], R::Mask),
) -> (Vector<R>, Energy<R>) {
    formulation.response(material, at, u, states)
}

/// [`response`] in small strain (eqs. 13-14): strain, material update and `w B^T s` point by
/// point.
#[inline(always)]
pub fn small_strain_response<F: Formulation, M: ConstitutiveModel, R: Real>(
    formulation: &F,
    material: &M,
    at: usize,
    u: &Vector<R>,
    (batches, active): (&mut [M::Batch], R::Mask),
) -> (Vector<R>, Energy<R>) {
    // Point by point (strain, update, forces), so that only one point's values are live:
    // the same operations in the same order as `strains`, then `forces`.
    let shared = formulation.shared(at, u);
    let w = formulation.weights::<R>(at);
    let (mut f, mut acc) = ([R::splat(0.0); 8], R::splat(0.0));
    let mut energy = Energy::<R>::default();
    for (p, batch) in batches.iter_mut().enumerate().take(F::POINTS) {
        let strain = formulation.strain(at, p, u, shared);
        let r = material.update(&strain, batch, at, active);
        energy.strain += w[p] * r.strain_energy_density;
        // (A material without states does no plastic work: +0 stays +0.)
        if M::HAS_STATES {
            energy.plastic_work += w[p] * r.plastic_work_density;
        }
        formulation.add_point_forces(at, p, &r.stress, &mut f, &mut acc);
    }
    formulation.finish_forces(at, acc, &mut f);
    energy.hourglass = formulation.add_hourglass(at, u, &mut f);
    (f, energy)
}

/// [`response`] of element `e` with its `POINTS` material `states` one per point (not in
/// batches: for checks and set-ups, not the time loop).
pub fn element_response<F: Formulation, M: ConstitutiveModel>(
    formulation: &F,
    material: &M,
    e: usize,
    u: &ElementVector,
    states: &mut [M::State],
) -> (ElementVector, ElementEnergy) {
    let lane = e % LANES;
    let mut batches = [M::Batch::default(); 4];
    for (batch, &state) in batches.iter_mut().zip(states.iter()) {
        M::set_state(batch, lane, state);
    }
    let out = response(
        formulation,
        material,
        e,
        u,
        (&mut batches[..F::POINTS], true),
    );
    for (batch, state) in batches.iter().zip(states.iter_mut()) {
        *state = M::state_of(batch, lane);
    }
    out
}

/// Elastic element stiffness (8x8, N/m), column by column from the force response.
pub fn element_stiffness<F: Formulation>(
    formulation: &F,
    elastic: &Elastic,
    e: usize,
) -> [[f64; 8]; 8] {
    let mut k = [[0.0; 8]; 8];
    let mut states = [(); 4];
    for j in 0..8 {
        let mut unit = [0.0; 8];
        unit[j] = 1.0;
        let (f, _) = element_response(formulation, elastic, e, &unit, &mut states);
        for i in 0..8 {
            k[i][j] = f[i];
        }
    }
    k
}

/// Largest eigenvalue of `M^-1/2 K M^-1/2` for an element with lumped mass `volume rho / 4`
/// per node: the square of its highest circular frequency, (rad/s)^2.
pub fn element_max_eigenvalue<F: Formulation>(
    formulation: &F,
    elastic: &Elastic,
    density: f64,
    e: usize,
) -> f64 {
    let k = element_stiffness(formulation, elastic, e);
    let m = formulation.nodal_masses(e, density);
    // sqrt(m_i m_j) is m where the two are equal (the square root of a rounded square is
    // exact), so equal masses keep the quotient `/ m`.
    let a = nalgebra::SMatrix::<f64, 8, 8>::from_fn(|i, j| {
        let (mi, mj) = (m[i / 2], m[j / 2]);
        let mass = if mi == mj { mi } else { (mi * mj).sqrt() };
        0.5 * (k[i][j] + k[j][i]) / mass
    });
    a.symmetric_eigenvalues().max()
}

/// Element `e`'s node coordinates relative to its node 0, m: its shape, wherever it lies.
/// The geometry is computed from these, so congruent elements (the same relative
/// coordinates, bit for bit) have the same geometry and share it ([`SharedBatches`]), and
/// the Jacobian sums no large absolute coordinates that cancel.
pub(crate) fn shape_coords(mesh: &Mesh, e: usize) -> [[f64; 2]; 4] {
    let c = mesh.element_coords(e);
    c.map(|p| [p[0] - c[0][0], p[1] - c[0][1]])
}

pub(crate) fn gauss_geometry(mesh: &Mesh, e: usize) -> Result<[PointGeometry<f64>; 4]> {
    let c = shape_coords(mesh, e);
    let g = GAUSS_XI.map(|xi| PointGeometry::at(&c, xi));
    if let Some(bad) = g.iter().find(|p| !(p.det_j > 0.0)) {
        return Err(Error::Run {
            step: 0,
            time_s: 0.0,
            what: format!(
                "element {e} (nodes {:?}) is inverted or degenerate: det J = {:e} at a Gauss point",
                mesh.elements[e], bad.det_j
            ),
        });
    }
    Ok(g)
}

/// Centroid derivatives (all four nodes', and [`CentroidGeometry`]'s two) with the element's
/// exact area (sum of the 2x2 det J), m^2.
fn centroid_geometry(
    mesh: &Mesh,
    e: usize,
) -> Result<(PointGeometry<f64>, CentroidGeometry<f64>, f64)> {
    let area = gauss_geometry(mesh, e)?.iter().map(|g| g.det_j).sum();
    let point = PointGeometry::at(&shape_coords(mesh, e), [0.0, 0.0]);
    let centroid = CentroidGeometry::of(&point).ok_or_else(|| Error::Run {
        step: 0,
        time_s: 0.0,
        what: format!(
            "element {e} (nodes {:?}): its centroid derivatives are not finite",
            mesh.elements[e]
        ),
    })?;
    Ok((point, centroid, area))
}

/// 2x2 Gauss quadrature of the plain displacement-based element.
pub struct FullQ4 {
    nodes: Vec<[u32; 4]>,
    /// The Gauss points' geometry.
    points: SharedBatches<[PointGeometry<Lanes>; 4]>,
    /// Out-of-plane thickness, m.
    pub(crate) width: f64,
}

impl FullQ4 {
    pub fn new(mesh: &Mesh, width: f64) -> Result<FullQ4> {
        Ok(FullQ4 {
            nodes: mesh.elements.clone(),
            points: SharedBatches::new(
                mesh.elements.len(),
                |e| gauss_geometry(mesh, e),
                |g, key| g.iter().for_each(|p| p.bits(key)),
                |b| {
                    std::array::from_fn(|p| {
                        PointGeometry::lanes(&b.iter().map(|g| g[p]).collect::<Vec<_>>())
                    })
                },
            )?,
            width,
        })
    }

    /// The Gauss points of the batch that holds `at`.
    #[inline(always)]
    pub(crate) fn points<R: Real>(&self, at: usize) -> &[PointGeometry<Lanes>; 4] {
        self.points.batch::<R>(at)
    }
}

impl Formulation for FullQ4 {
    const POINTS: usize = 4;
    fn connectivity(&self) -> &[[u32; 4]] {
        &self.nodes
    }
    #[inline(always)]
    fn strain<R: Real>(&self, at: usize, p: usize, u: &Vector<R>, _: R) -> [R; 4] {
        self.points::<R>(at)[p].strain(at, u)
    }
    #[inline(always)]
    fn weights<R: Real>(&self, at: usize) -> [R; 4] {
        let mut w = [R::splat(0.0); 4];
        for (w, g) in w.iter_mut().zip(self.points::<R>(at)) {
            *w = g.det_j::<R>(at) * self.width;
        }
        w
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
        let g = &self.points::<R>(at)[p];
        g.add_divergence(at, g.det_j::<R>(at) * self.width, s, f);
    }
    fn volume(&self, e: usize) -> f64 {
        self.weights::<f64>(e).iter().sum()
    }
    fn heap_bytes(&self) -> usize {
        vec_bytes(&self.nodes) + self.points.heap_bytes()
    }
}

/// Selective-reduced integration (B-bar): 2x2 deviatoric, centroid volumetric.
pub struct SelectiveQ4 {
    pub(crate) full: FullQ4,
    pub(crate) centroid: SharedBatches<CentroidGeometry<Lanes>>,
}

impl SelectiveQ4 {
    pub fn new(mesh: &Mesh, width: f64) -> Result<SelectiveQ4> {
        Ok(SelectiveQ4 {
            full: FullQ4::new(mesh, width)?,
            centroid: SharedBatches::new(
                mesh.elements.len(),
                |e| centroid_geometry(mesh, e).map(|c| c.1),
                CentroidGeometry::bits,
                CentroidGeometry::lanes,
            )?,
        })
    }
}

impl Formulation for SelectiveQ4 {
    const POINTS: usize = 4;
    fn connectivity(&self) -> &[[u32; 4]] {
        self.full.connectivity()
    }
    /// The centroid dilatation.
    #[inline(always)]
    fn shared<R: Real>(&self, at: usize, u: &Vector<R>) -> R {
        self.centroid.batch::<R>(at).dilatation(at, u)
    }
    /// B-bar strain: the point's volumetric part replaced by the centroid's (`centroid`:
    /// its dilatation), `zz` carrying the shift so that the trace is the centroid dilatation.
    #[inline(always)]
    fn strain<R: Real>(&self, at: usize, p: usize, u: &Vector<R>, centroid: R) -> [R; 4] {
        let s = self.full.strain(at, p, u, centroid);
        let shift = (centroid - s[0] - s[1]) * THIRD;
        [s[0] + shift, s[1] + shift, shift, s[3]]
    }
    #[inline(always)]
    fn weights<R: Real>(&self, at: usize) -> [R; 4] {
        self.full.weights(at)
    }
    fn point_xi(&self) -> &'static [[f64; 2]] {
        &GAUSS_XI
    }
    /// The deviatoric stress at the Gauss point; its weighted mean stress into `mean_total`.
    #[inline(always)]
    fn add_point_forces<R: Real>(
        &self,
        at: usize,
        p: usize,
        s: &[R; 4],
        f: &mut Vector<R>,
        mean_total: &mut R,
    ) {
        let g = &self.full.points::<R>(at)[p];
        let w = g.det_j::<R>(at) * self.full.width;
        let mean = (s[0] + s[1] + s[2]) * THIRD;
        *mean_total += w * mean;
        for a in 0..4 {
            let (dx, dy) = (g.dndx::<R>(a, at), g.dndy::<R>(a, at));
            f[2 * a] += w * (dx * (s[0] - mean) + dy * s[3]);
            f[2 * a + 1] += w * (dy * (s[1] - mean) + dx * s[3]);
        }
    }
    /// The points' weighted mean stress at the centroid.
    #[inline(always)]
    fn finish_forces<R: Real>(&self, at: usize, mean_total: R, f: &mut Vector<R>) {
        self.centroid
            .batch::<R>(at)
            .add_gradients(at, mean_total, f);
    }
    fn volume(&self, e: usize) -> f64 {
        self.full.volume(e)
    }
    fn heap_bytes(&self) -> usize {
        self.full.heap_bytes() + self.centroid.heap_bytes()
    }
}

/// One-point quadrature with Flanagan-Belytschko hourglass control.
pub struct OnePointQ4 {
    nodes: Vec<[u32; 4]>,
    /// The centroid, volume, hourglass vectors and stiffness.
    pub(crate) data: SharedBatches<OnePoint<Lanes>>,
}

/// [`OnePointQ4`]'s data of [`Real::LANES`] elements.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct OnePoint<R> {
    /// The derivatives at the centroid, 1/m, for the strain.
    pub(crate) centroid: CentroidGeometry<R>,
    /// The same times the volume, m^2, for the forces `w B^T s`.
    pub(crate) weighted: CentroidGeometry<R>,
    /// Element volume, m^3.
    pub(crate) volume: R,
    /// Hourglass base vectors gamma_a (dimensionless).
    gamma: [R; 4],
    /// Hourglass stiffness, N/m.
    stiffness: R,
}

const HOURGLASS_H: [f64; 4] = [1.0, -1.0, 1.0, -1.0];
const CENTROID_XI: [[f64; 2]; 1] = [[0.0, 0.0]];

impl OnePoint<f64> {
    fn bits(&self, key: &mut Vec<u64>) {
        self.centroid.bits(key);
        self.weighted.bits(key);
        key.extend(
            [self.volume, self.stiffness]
                .iter()
                .chain(&self.gamma)
                .map(|x| x.to_bits()),
        );
    }

    fn lanes(elements: &[OnePoint<f64>]) -> OnePoint<Lanes> {
        let lanes = |of: fn(&OnePoint<f64>) -> CentroidGeometry<f64>| {
            CentroidGeometry::lanes(&elements.iter().map(of).collect::<Vec<_>>())
        };
        let mut g = OnePoint {
            centroid: lanes(|d| d.centroid),
            weighted: lanes(|d| d.weighted),
            ..Default::default()
        };
        for (l, d) in elements.iter().enumerate() {
            g.volume.0[l] = d.volume;
            g.stiffness.0[l] = d.stiffness;
            for a in 0..4 {
                g.gamma[a].0[l] = d.gamma[a];
            }
        }
        g
    }
}

impl OnePointQ4 {
    /// `kappa`: hourglass coefficient; `p_modulus`: lambda + 2 mu, Pa.
    pub fn new(mesh: &Mesh, width: f64, kappa: f64, p_modulus: f64) -> Result<OnePointQ4> {
        OnePointQ4::with_thickness(mesh, |_, _| Ok(width), kappa, p_modulus)
    }

    /// [`OnePointQ4::new`] with element `e`'s out-of-plane thickness `thickness(e, area)` (m;
    /// its area in m^2): its volume is `area * thickness` (the axisymmetric ring's: 2 pi times
    /// the radius of its area's centroid).
    pub(crate) fn with_thickness(
        mesh: &Mesh,
        thickness: impl Fn(usize, f64) -> Result<f64>,
        kappa: f64,
        p_modulus: f64,
    ) -> Result<OnePointQ4> {
        let element = |e| {
            let (c, centroid, area) = centroid_geometry(mesh, e)?;
            let xy = shape_coords(mesh, e);
            let hx: f64 = (0..4).map(|a| HOURGLASS_H[a] * xy[a][0]).sum();
            let hy: f64 = (0..4).map(|a| HOURGLASS_H[a] * xy[a][1]).sum();
            let bb: f64 = (0..4).map(|a| c.dndx[a].powi(2) + c.dndy[a].powi(2)).sum();
            let width = thickness(e, area)?;
            let volume = area * width;
            Ok(OnePoint {
                centroid,
                weighted: centroid.scaled(volume),
                volume,
                gamma: std::array::from_fn(|a| {
                    0.25 * (HOURGLASS_H[a] - hx * c.dndx[a] - hy * c.dndy[a])
                }),
                stiffness: kappa * p_modulus * area * width * bb,
            })
        };
        let n = mesh.elements.len();
        Ok(OnePointQ4 {
            nodes: mesh.elements.clone(),
            data: SharedBatches::new(n, element, OnePoint::bits, OnePoint::lanes)?,
        })
    }

    /// Hourglass mode amplitudes `q_x = gamma . u_x`, `q_y = gamma . u_y` of `at`, m.
    #[inline(always)]
    fn hourglass_modes<R: Real>(&self, at: usize, u: &Vector<R>) -> (R, R) {
        let d = self.data.batch::<R>(at);
        let (mut qx, mut qy) = (R::splat(0.0), R::splat(0.0));
        for a in 0..4 {
            let g = R::of_batch(&d.gamma[a], at);
            qx += g * u[2 * a];
            qy += g * u[2 * a + 1];
        }
        (qx, qy)
    }
}

/// Hourglass energy `k (q_x^2 + q_y^2) / 2`, J (stiffness `k`, N/m; mode amplitudes, m).
#[inline(always)]
fn hourglass_energy_of<R: Real>(k: R, qx: R, qy: R) -> R {
    k * 0.5 * (qx * qx + qy * qy)
}

impl Formulation for OnePointQ4 {
    const POINTS: usize = 1;
    const STIFFNESS_MATRIX_PAYS: bool = false;
    fn connectivity(&self) -> &[[u32; 4]] {
        &self.nodes
    }
    #[inline(always)]
    fn strain<R: Real>(&self, at: usize, _: usize, u: &Vector<R>, _: R) -> [R; 4] {
        self.data.batch::<R>(at).centroid.strain(at, u)
    }
    #[inline(always)]
    fn weights<R: Real>(&self, at: usize) -> [R; 4] {
        let zero = R::splat(0.0);
        [
            R::of_batch(&self.data.batch::<R>(at).volume, at),
            zero,
            zero,
            zero,
        ]
    }
    fn point_xi(&self) -> &'static [[f64; 2]] {
        &CENTROID_XI
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
        self.data.batch::<R>(at).weighted.add_transpose(at, s, f);
    }
    #[inline(always)]
    fn add_hourglass<R: Real>(&self, at: usize, u: &Vector<R>, f: &mut Vector<R>) -> R {
        let d = self.data.batch::<R>(at);
        let (qx, qy) = self.hourglass_modes(at, u);
        let k = R::of_batch(&d.stiffness, at);
        for a in 0..4 {
            let g = R::of_batch(&d.gamma[a], at);
            f[2 * a] += k * qx * g;
            f[2 * a + 1] += k * qy * g;
        }
        hourglass_energy_of(k, qx, qy)
    }
    #[inline(always)]
    fn hourglass_energy<R: Real>(&self, at: usize, u: &Vector<R>) -> R {
        let (qx, qy) = self.hourglass_modes(at, u);
        hourglass_energy_of(R::of_batch(&self.data.batch::<R>(at).stiffness, at), qx, qy)
    }
    fn volume(&self, e: usize) -> f64 {
        self.weights::<f64>(e)[0]
    }
    fn heap_bytes(&self) -> usize {
        vec_bytes(&self.nodes) + self.data.heap_bytes()
    }
}

/// Gathers an element displacement vector from the global one (2 dofs per node).
#[inline(always)]
pub fn gather(nodes: [u32; 4], u: &[f64]) -> ElementVector {
    let mut ue = [0.0; 8];
    for (a, &n) in nodes.iter().enumerate() {
        let n = n as usize;
        ue[2 * a] = u[2 * n];
        ue[2 * a + 1] = u[2 * n + 1];
    }
    ue
}

/// Adds an element vector into the global one.
#[inline(always)]
pub fn scatter_add(nodes: [u32; 4], fe: &ElementVector, f: &mut [f64]) {
    for (a, &n) in nodes.iter().enumerate() {
        let n = n as usize;
        f[2 * n] += fe[2 * a];
        f[2 * n + 1] += fe[2 * a + 1];
    }
}

/// Lumped nodal masses, kg: each element gives its [`Formulation::nodal_masses`] (a quarter
/// of its mass to each node in plane strain).
pub fn lumped_masses<F: Formulation>(formulation: &F, n_nodes: usize, density: f64) -> Vec<f64> {
    let mut m = vec![0.0; n_nodes];
    for e in 0..formulation.n_elements() {
        let shares = formulation.nodal_masses(e, density);
        for (n, share) in formulation.nodes(e).into_iter().zip(shares) {
            m[n as usize] += share;
        }
    }
    m
}
