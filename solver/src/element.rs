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

use crate::error::{Error, Result};
use crate::material::{ConstitutiveModel, Elastic, Strain, Stress};
use crate::mesh::Mesh;
use crate::point_lanes::{PointLanes, VectorLanes};
use crate::simd::{Lanes, LANES};

pub type ElementVector = [f64; 8];

const G: f64 = 0.577_350_269_189_625_8; // 1/sqrt(3)
/// Natural coordinates of the nodes and of the 2x2 Gauss points (same ordering).
const NODE_XI: [[f64; 2]; 4] = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];
const GAUSS_XI: [[f64; 2]; 4] = [[-G, -G], [G, -G], [G, G], [-G, G]];

/// Shape function values at natural coordinates.
pub fn shape(xi: [f64; 2]) -> [f64; 4] {
    NODE_XI.map(|n| 0.25 * (1.0 + xi[0] * n[0]) * (1.0 + xi[1] * n[1]))
}

/// Cartesian shape-function derivatives and det J at a point of the element.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PointGeometry {
    /// dN_a/dx, 1/m
    pub dndx: [f64; 4],
    /// dN_a/dy, 1/m
    pub dndy: [f64; 4],
    /// det J, m^2 per unit natural area
    pub det_j: f64,
}

impl PointGeometry {
    pub fn at(coords: &[[f64; 2]; 4], xi: [f64; 2]) -> PointGeometry {
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

    /// Small strain `[xx, yy, 0, gamma_xy]` of an element displacement vector.
    #[inline(always)]
    pub fn strain(&self, u: &ElementVector) -> Strain {
        let (mut xx, mut yy, mut xy) = (0.0, 0.0, 0.0);
        for a in 0..4 {
            let (ux, uy) = (u[2 * a], u[2 * a + 1]);
            xx += self.dndx[a] * ux;
            yy += self.dndy[a] * uy;
            xy += self.dndy[a] * ux + self.dndx[a] * uy;
        }
        [xx, yy, 0.0, xy]
    }

    /// Volumetric strain `div u`.
    #[inline(always)]
    pub fn dilatation(&self, u: &ElementVector) -> f64 {
        (0..4)
            .map(|a| self.dndx[a] * u[2 * a] + self.dndy[a] * u[2 * a + 1])
            .sum()
    }

    /// Adds `w B^T s` (in-plane stress components) to `f`.
    #[inline(always)]
    pub fn add_divergence(&self, w: f64, s: &Stress, f: &mut ElementVector) {
        for a in 0..4 {
            f[2 * a] += w * (self.dndx[a] * s[0] + self.dndy[a] * s[3]);
            f[2 * a + 1] += w * (self.dndy[a] * s[1] + self.dndx[a] * s[3]);
        }
    }
}

/// Energy contributions of one element in one step, J.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ElementEnergy {
    pub strain: f64,
    pub plastic_work: f64,
    pub hourglass: f64,
}

impl std::ops::AddAssign for ElementEnergy {
    fn add_assign(&mut self, o: ElementEnergy) {
        self.strain += o.strain;
        self.plastic_work += o.plastic_work;
        self.hourglass += o.hourglass;
    }
}

/// An element formulation over a whole mesh (geometry precomputed per element).
pub trait Formulation: Sync {
    /// Integration points that carry material state (4 or 1).
    const POINTS: usize;
    /// Whether an elastic run is faster with precomputed element stiffness matrices than
    /// with the stress path (measured by `impact-bench throughput`: not for one point).
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
    /// Strain at each integration point (the first `POINTS` entries are used).
    fn strains(&self, e: usize, u: &ElementVector) -> [Strain; 4];
    /// Integration weight of each point: det J * W (m^3).
    fn weights(&self, e: usize) -> [f64; 4];
    /// Natural coordinates of each integration point.
    fn point_xi(&self) -> &'static [[f64; 2]];
    /// Nodal forces `sum_p w_p B_p^T s_p` of the point stresses.
    fn forces(&self, e: usize, stresses: &[Stress; 4]) -> ElementVector;
    /// Adds hourglass forces to `f`, returns the hourglass energy (J).
    #[inline(always)]
    fn add_hourglass(&self, _e: usize, _u: &ElementVector, _f: &mut ElementVector) -> f64 {
        0.0
    }
    /// Hourglass energy (J) of element `e` at `u`, without forces.
    #[inline(always)]
    fn hourglass_energy(&self, _e: usize, _u: &ElementVector) -> f64 {
        0.0
    }
    /// Element volume (area * W), m^3.
    fn volume(&self, e: usize) -> f64;
    /// [`Formulation::strains`] of batch `b` (elements `b * LANES ..`, [`crate::batch`]):
    /// point x component x lanes.
    fn strains_lanes(&self, b: usize, u: &VectorLanes) -> [[Lanes; 4]; 4];
    /// [`Formulation::weights`] of batch `b`: point x lanes, m^3.
    fn weights_lanes(&self, b: usize) -> [Lanes; 4];
    /// [`Formulation::forces`] of batch `b` (stresses point x component x lanes).
    fn forces_lanes(&self, b: usize, stresses: &[[Lanes; 4]; 4]) -> VectorLanes;
    /// [`Formulation::add_hourglass`] of batch `b`: the hourglass energy per lane, J.
    #[inline(always)]
    fn add_hourglass_lanes(&self, _b: usize, _u: &VectorLanes, _f: &mut VectorLanes) -> Lanes {
        Lanes::splat(0.0)
    }
}

/// The lanes of `points` (at most [`LANES`]; missing lanes are zero).
fn lanes_of(points: &[PointGeometry]) -> PointLanes {
    let mut g = PointLanes::default();
    for (l, p) in points.iter().enumerate() {
        for a in 0..4 {
            g.dndx[a].0[l] = p.dndx[a];
            g.dndy[a].0[l] = p.dndy[a];
        }
        g.det_j.0[l] = p.det_j;
    }
    g
}

/// The lane geometry of `per_element` in batches of [`LANES`] elements.
fn batches<T: Copy, G>(per_element: &[T], lanes: impl Fn(&[T]) -> G) -> Vec<G> {
    per_element.chunks(LANES).map(lanes).collect()
}

/// Internal nodal forces and energies of element `e`, updating its material states.
#[inline(always)]
pub fn element_response<F: Formulation, M: ConstitutiveModel>(
    formulation: &F,
    material: &M,
    e: usize,
    u: &ElementVector,
    states: &mut [M::State],
) -> (ElementVector, ElementEnergy) {
    let strains = formulation.strains(e, u);
    let w = formulation.weights(e);
    let mut stresses = [[0.0; 4]; 4];
    let mut energy = ElementEnergy::default();
    for p in 0..F::POINTS {
        let r = material.update(&strains[p], &mut states[p]);
        stresses[p] = r.stress;
        energy.strain += w[p] * r.strain_energy_density;
        energy.plastic_work += w[p] * r.plastic_work_density;
    }
    let mut f = formulation.forces(e, &stresses);
    energy.hourglass = formulation.add_hourglass(e, u, &mut f);
    (f, energy)
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
    let m = 0.25 * density * formulation.volume(e);
    let a = nalgebra::SMatrix::<f64, 8, 8>::from_fn(|i, j| 0.5 * (k[i][j] + k[j][i]) / m);
    a.symmetric_eigenvalues().max()
}

fn gauss_geometry(mesh: &Mesh, e: usize) -> Result<[PointGeometry; 4]> {
    let c = mesh.element_coords(e);
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

/// Centroid derivatives with the element's exact area (sum of the 2x2 det J).
fn centroid_geometry(mesh: &Mesh, e: usize) -> Result<(PointGeometry, f64)> {
    let area = gauss_geometry(mesh, e)?.iter().map(|g| g.det_j).sum();
    Ok((PointGeometry::at(&mesh.element_coords(e), [0.0, 0.0]), area))
}

/// 2x2 Gauss quadrature of the plain displacement-based element.
pub struct FullQ4 {
    nodes: Vec<[u32; 4]>,
    points: Vec<[PointGeometry; 4]>,
    /// The Gauss points per batch of [`LANES`] elements.
    point_lanes: Vec<[PointLanes; 4]>,
    width: f64,
}

impl FullQ4 {
    pub fn new(mesh: &Mesh, width: f64) -> Result<FullQ4> {
        let points: Vec<[PointGeometry; 4]> = (0..mesh.elements.len())
            .map(|e| gauss_geometry(mesh, e))
            .collect::<Result<_>>()?;
        Ok(FullQ4 {
            nodes: mesh.elements.clone(),
            point_lanes: batches(&points, |b| {
                std::array::from_fn(|p| lanes_of(&b.iter().map(|g| g[p]).collect::<Vec<_>>()))
            }),
            points,
            width,
        })
    }
}

impl Formulation for FullQ4 {
    const POINTS: usize = 4;
    fn connectivity(&self) -> &[[u32; 4]] {
        &self.nodes
    }
    #[inline(always)]
    fn strains(&self, e: usize, u: &ElementVector) -> [Strain; 4] {
        let g = &self.points[e];
        [
            g[0].strain(u),
            g[1].strain(u),
            g[2].strain(u),
            g[3].strain(u),
        ]
    }
    #[inline(always)]
    fn weights(&self, e: usize) -> [f64; 4] {
        self.points[e].map(|g| g.det_j * self.width)
    }
    fn point_xi(&self) -> &'static [[f64; 2]] {
        &GAUSS_XI
    }
    #[inline(always)]
    fn forces(&self, e: usize, s: &[Stress; 4]) -> ElementVector {
        let mut f = [0.0; 8];
        for (p, g) in self.points[e].iter().enumerate() {
            g.add_divergence(g.det_j * self.width, &s[p], &mut f);
        }
        f
    }
    fn volume(&self, e: usize) -> f64 {
        self.weights(e).iter().sum()
    }
    #[inline(always)]
    fn strains_lanes(&self, b: usize, u: &VectorLanes) -> [[Lanes; 4]; 4] {
        // Loops, not `array::map`: its closure may stay out of line, compiled for the
        // baseline instruction set (see `crate::simd::Kernel`).
        let mut strains = [[Lanes::splat(0.0); 4]; 4];
        for (s, g) in strains.iter_mut().zip(&self.point_lanes[b]) {
            *s = g.strain(u);
        }
        strains
    }
    #[inline(always)]
    fn weights_lanes(&self, b: usize) -> [Lanes; 4] {
        let mut w = [Lanes::splat(0.0); 4];
        for (w, g) in w.iter_mut().zip(&self.point_lanes[b]) {
            *w = g.det_j * self.width;
        }
        w
    }
    #[inline(always)]
    fn forces_lanes(&self, b: usize, s: &[[Lanes; 4]; 4]) -> VectorLanes {
        let mut f = [Lanes::splat(0.0); 8];
        for (p, g) in self.point_lanes[b].iter().enumerate() {
            g.add_divergence(g.det_j * self.width, &s[p], &mut f);
        }
        f
    }
}

/// Selective-reduced integration (B-bar): 2x2 deviatoric, centroid volumetric.
pub struct SelectiveQ4 {
    full: FullQ4,
    centroid: Vec<PointGeometry>,
    centroid_lanes: Vec<PointLanes>,
}

impl SelectiveQ4 {
    pub fn new(mesh: &Mesh, width: f64) -> Result<SelectiveQ4> {
        let centroid: Vec<PointGeometry> = (0..mesh.elements.len())
            .map(|e| centroid_geometry(mesh, e).map(|c| c.0))
            .collect::<Result<_>>()?;
        Ok(SelectiveQ4 {
            full: FullQ4::new(mesh, width)?,
            centroid_lanes: batches(&centroid, lanes_of),
            centroid,
        })
    }
}

impl Formulation for SelectiveQ4 {
    const POINTS: usize = 4;
    fn connectivity(&self) -> &[[u32; 4]] {
        self.full.connectivity()
    }
    /// B-bar strain: the point's volumetric part replaced by the centroid's, `zz` carrying
    /// the shift so that the trace is the centroid dilatation.
    #[inline(always)]
    fn strains(&self, e: usize, u: &ElementVector) -> [Strain; 4] {
        let centroid_dilatation = self.centroid[e].dilatation(u);
        self.full.strains(e, u).map(|s| {
            let shift = (centroid_dilatation - s[0] - s[1]) / 3.0;
            [s[0] + shift, s[1] + shift, shift, s[3]]
        })
    }
    #[inline(always)]
    fn weights(&self, e: usize) -> [f64; 4] {
        self.full.weights(e)
    }
    fn point_xi(&self) -> &'static [[f64; 2]] {
        &GAUSS_XI
    }
    #[inline(always)]
    fn forces(&self, e: usize, s: &[Stress; 4]) -> ElementVector {
        let mut f = [0.0; 8];
        let c = &self.centroid[e];
        let mut mean_total = 0.0;
        for (p, g) in self.full.points[e].iter().enumerate() {
            let w = g.det_j * self.full.width;
            let mean = (s[p][0] + s[p][1] + s[p][2]) / 3.0;
            mean_total += w * mean;
            for a in 0..4 {
                f[2 * a] += w * (g.dndx[a] * (s[p][0] - mean) + g.dndy[a] * s[p][3]);
                f[2 * a + 1] += w * (g.dndy[a] * (s[p][1] - mean) + g.dndx[a] * s[p][3]);
            }
        }
        for a in 0..4 {
            f[2 * a] += mean_total * c.dndx[a];
            f[2 * a + 1] += mean_total * c.dndy[a];
        }
        f
    }
    fn volume(&self, e: usize) -> f64 {
        self.full.volume(e)
    }
    #[inline(always)]
    fn strains_lanes(&self, b: usize, u: &VectorLanes) -> [[Lanes; 4]; 4] {
        let centroid_dilatation = self.centroid_lanes[b].dilatation(u);
        let mut strains = self.full.strains_lanes(b, u);
        for s in &mut strains {
            let shift = (centroid_dilatation - s[0] - s[1]) / 3.0;
            *s = [s[0] + shift, s[1] + shift, shift, s[3]];
        }
        strains
    }
    #[inline(always)]
    fn weights_lanes(&self, b: usize) -> [Lanes; 4] {
        self.full.weights_lanes(b)
    }
    /// [`SelectiveQ4::forces`] in lanes.
    #[inline(always)]
    fn forces_lanes(&self, b: usize, s: &[[Lanes; 4]; 4]) -> VectorLanes {
        let mut f = [Lanes::splat(0.0); 8];
        let c = &self.centroid_lanes[b];
        let mut mean_total = Lanes::splat(0.0);
        for (p, g) in self.full.point_lanes[b].iter().enumerate() {
            let w = g.det_j * self.full.width;
            let mean = (s[p][0] + s[p][1] + s[p][2]) / 3.0;
            mean_total += w * mean;
            for a in 0..4 {
                f[2 * a] += w * (g.dndx[a] * (s[p][0] - mean) + g.dndy[a] * s[p][3]);
                f[2 * a + 1] += w * (g.dndy[a] * (s[p][1] - mean) + g.dndx[a] * s[p][3]);
            }
        }
        for a in 0..4 {
            f[2 * a] += mean_total * c.dndx[a];
            f[2 * a + 1] += mean_total * c.dndy[a];
        }
        f
    }
}

/// One-point quadrature with Flanagan-Belytschko hourglass control.
pub struct OnePointQ4 {
    nodes: Vec<[u32; 4]>,
    centroid: Vec<PointGeometry>,
    volume: Vec<f64>,
    /// Hourglass base vectors gamma_a (dimensionless).
    gamma: Vec<[f64; 4]>,
    /// Hourglass stiffness, N/m.
    stiffness: Vec<f64>,
    /// Per batch of [`LANES`] elements: the centroid, volume, gamma and stiffness in lanes.
    lanes: Vec<OnePointLanes>,
}

/// [`OnePointQ4`]'s data of one batch in lanes.
#[derive(Debug, Clone, Copy, Default)]
struct OnePointLanes {
    centroid: PointLanes,
    volume: Lanes,
    gamma: [Lanes; 4],
    stiffness: Lanes,
}

const HOURGLASS_H: [f64; 4] = [1.0, -1.0, 1.0, -1.0];

impl OnePointQ4 {
    /// Hourglass mode amplitudes `q_x = gamma . u_x`, `q_y = gamma . u_y`, m.
    #[inline(always)]
    fn hourglass_modes(&self, e: usize, u: &ElementVector) -> (f64, f64) {
        let g = &self.gamma[e];
        let (mut qx, mut qy) = (0.0, 0.0);
        for a in 0..4 {
            qx += g[a] * u[2 * a];
            qy += g[a] * u[2 * a + 1];
        }
        (qx, qy)
    }
}
const CENTROID_XI: [[f64; 2]; 1] = [[0.0, 0.0]];

impl OnePointQ4 {
    /// `kappa`: hourglass coefficient; `p_modulus`: lambda + 2 mu, Pa.
    pub fn new(mesh: &Mesh, width: f64, kappa: f64, p_modulus: f64) -> Result<OnePointQ4> {
        let n = mesh.elements.len();
        let mut q = OnePointQ4 {
            nodes: mesh.elements.clone(),
            centroid: Vec::with_capacity(n),
            volume: Vec::with_capacity(n),
            gamma: Vec::with_capacity(n),
            stiffness: Vec::with_capacity(n),
            lanes: Vec::new(),
        };
        for e in 0..n {
            let (c, area) = centroid_geometry(mesh, e)?;
            let xy = mesh.element_coords(e);
            let hx: f64 = (0..4).map(|a| HOURGLASS_H[a] * xy[a][0]).sum();
            let hy: f64 = (0..4).map(|a| HOURGLASS_H[a] * xy[a][1]).sum();
            let gamma: [f64; 4] =
                std::array::from_fn(|a| 0.25 * (HOURGLASS_H[a] - hx * c.dndx[a] - hy * c.dndy[a]));
            let bb: f64 = (0..4).map(|a| c.dndx[a].powi(2) + c.dndy[a].powi(2)).sum();
            q.stiffness.push(kappa * p_modulus * area * width * bb);
            q.volume.push(area * width);
            q.gamma.push(gamma);
            q.centroid.push(c);
        }
        q.lanes = (0..n.div_ceil(LANES))
            .map(|b| {
                let es = b * LANES..(b * LANES + LANES).min(n);
                let mut g = OnePointLanes {
                    centroid: lanes_of(&q.centroid[es.clone()]),
                    ..Default::default()
                };
                for (l, e) in es.enumerate() {
                    g.volume.0[l] = q.volume[e];
                    g.stiffness.0[l] = q.stiffness[e];
                    for a in 0..4 {
                        g.gamma[a].0[l] = q.gamma[e][a];
                    }
                }
                g
            })
            .collect();
        Ok(q)
    }
}

impl Formulation for OnePointQ4 {
    const POINTS: usize = 1;
    const STIFFNESS_MATRIX_PAYS: bool = false;
    fn connectivity(&self) -> &[[u32; 4]] {
        &self.nodes
    }
    #[inline(always)]
    fn strains(&self, e: usize, u: &ElementVector) -> [Strain; 4] {
        let s = self.centroid[e].strain(u);
        [s, s, s, s]
    }
    #[inline(always)]
    fn weights(&self, e: usize) -> [f64; 4] {
        [self.volume[e], 0.0, 0.0, 0.0]
    }
    fn point_xi(&self) -> &'static [[f64; 2]] {
        &CENTROID_XI
    }
    #[inline(always)]
    fn forces(&self, e: usize, s: &[Stress; 4]) -> ElementVector {
        let mut f = [0.0; 8];
        self.centroid[e].add_divergence(self.volume[e], &s[0], &mut f);
        f
    }
    #[inline(always)]
    fn add_hourglass(&self, e: usize, u: &ElementVector, f: &mut ElementVector) -> f64 {
        let (g, k) = (&self.gamma[e], self.stiffness[e]);
        let (qx, qy) = self.hourglass_modes(e, u);
        for a in 0..4 {
            f[2 * a] += k * qx * g[a];
            f[2 * a + 1] += k * qy * g[a];
        }
        0.5 * k * (qx * qx + qy * qy)
    }
    #[inline(always)]
    fn hourglass_energy(&self, e: usize, u: &ElementVector) -> f64 {
        let (qx, qy) = self.hourglass_modes(e, u);
        0.5 * self.stiffness[e] * (qx * qx + qy * qy)
    }
    fn volume(&self, e: usize) -> f64 {
        self.volume[e]
    }
    #[inline(always)]
    fn strains_lanes(&self, b: usize, u: &VectorLanes) -> [[Lanes; 4]; 4] {
        let s = self.lanes[b].centroid.strain(u);
        [s, s, s, s]
    }
    #[inline(always)]
    fn weights_lanes(&self, b: usize) -> [Lanes; 4] {
        let zero = Lanes::splat(0.0);
        [self.lanes[b].volume, zero, zero, zero]
    }
    #[inline(always)]
    fn forces_lanes(&self, b: usize, s: &[[Lanes; 4]; 4]) -> VectorLanes {
        let mut f = [Lanes::splat(0.0); 8];
        let g = &self.lanes[b];
        g.centroid.add_divergence(g.volume, &s[0], &mut f);
        f
    }
    /// [`OnePointQ4::add_hourglass`] in lanes.
    #[inline(always)]
    fn add_hourglass_lanes(&self, b: usize, u: &VectorLanes, f: &mut VectorLanes) -> Lanes {
        let g = &self.lanes[b];
        let (mut qx, mut qy) = (Lanes::splat(0.0), Lanes::splat(0.0));
        for a in 0..4 {
            qx += g.gamma[a] * u[2 * a];
            qy += g.gamma[a] * u[2 * a + 1];
        }
        let k = g.stiffness;
        for a in 0..4 {
            f[2 * a] += k * qx * g.gamma[a];
            f[2 * a + 1] += k * qy * g.gamma[a];
        }
        let energy = 0.5 * k * (qx * qx + qy * qy);
        energy
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

/// Lumped (row-sum) nodal masses, kg: each element gives a quarter of its mass to each node.
pub fn lumped_masses<F: Formulation>(formulation: &F, n_nodes: usize, density: f64) -> Vec<f64> {
    let mut m = vec![0.0; n_nodes];
    for e in 0..formulation.n_elements() {
        let share = 0.25 * density * formulation.volume(e);
        for n in formulation.nodes(e) {
            m[n as usize] += share;
        }
    }
    m
}
