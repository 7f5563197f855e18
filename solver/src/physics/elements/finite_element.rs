//! The three elements under finite deformation (updated Lagrangian, `ALGORITHM.md` section
//! 3c): [`UpdatedLagrangian`] wraps a small-strain formulation and replaces its response.
//!
//! Per integration point: the displacement gradient `G = du/dX` on the reference geometry the
//! element already stores, the point's step ([`kinematics::step`]: unrotated strain, rotation),
//! the material's unrotated Kirchhoff stress, rotated to the current frame, and the nodal
//! forces `w_ref P dN/dX` with `P = tau F^-T` (the current configuration's `w_cur B_cur^T
//! sigma`, written on the reference geometry: `dv = J dV`, `tau = J sigma`). Element by element:
//! - `q4-full`: four points as above.
//! - `q4-sri`: the F-bar method (de Souza Neto, Peric, Dutko & Owen 1996), the finite-strain
//!   form of B-bar: each point's in-plane `F` scaled to the centroid's area change,
//!   `F_bar = (J_c / J)^(1/2) F`; its virtual work gives the point's deviatoric forces
//!   (`tau - m I`, `m` the in-plane mean `(tau_xx + tau_yy) / 2`, on the point's current
//!   gradients) and the summed `w m` on the centroid's current gradients. At small strain it
//!   is B-bar with the in-plane mean: the small-strain `q4-sri` takes the three-dimensional
//!   mean (`zz` carrying the dilatation shift), so the two differ in how a point's
//!   deviatoric stress is split, at first order, by a term that vanishes in homogeneous
//!   fields.
//! - `q4-1pt`: the centroid, and the Flanagan-Belytschko hourglass forces of the small-strain
//!   element on the total displacements: `q = sum gamma_a u_a` vanishes for every field linear
//!   in `X` (a homogeneous deformation, a rigid rotation of any size: `sum gamma_a X_a = 0`),
//!   and under a rigid rotation `R` the modes, forces and energy are those of the unrotated
//!   element rotated by `R`, so the stiffness form is already the co-rotational one.

use crate::lanes::real::Real;
use crate::lanes::simd::Lanes;
use crate::physics::elements::element::{
    small_strain_response, Energy, Formulation, FullQ4, OnePointQ4, SelectiveQ4,
};
use crate::physics::elements::geometry::{PointGeometry, Vector};
use crate::physics::kinematics::{self, deformation, det, inverse_with, piola, Gradient, Memory};
use crate::physics::materials::material::{ConstitutiveModel, Response};

/// A small-strain element formulation under finite deformation.
pub struct UpdatedLagrangian<F>(pub F);

/// The element's finite-deformation response ([`UpdatedLagrangian`]).
pub trait FiniteResponse: Formulation {
    /// Internal forces and energies of `at` under finite deformation; the material keeps a
    /// memory ([`ConstitutiveModel::KEEPS_MEMORY`]).
    fn finite_response<M: ConstitutiveModel, R: Real>(
        &self,
        material: &M,
        at: usize,
        u: &Vector<R>,
        states: (&mut [M::Batch], R::Mask),
    ) -> (Vector<R>, Energy<R>);
}

/// One point's update from its gradient `g` (of `F_bar` for F-bar) and, in the
/// axisymmetric geometry, its hoop gradient `hoop` (`u_r / R`; `None` in plane strain): the
/// step from the point's memory, the material at the unrotated strain, the memory written
/// where `active` has the lane; the response's stress is the Kirchhoff stress in the current
/// frame, Pa (energy densities per reference volume, J/m^3), and `(I + g)^-1`.
#[inline(always)]
pub(crate) fn point_update<M: ConstitutiveModel, R: Real>(
    material: &M,
    (g, hoop): (&Gradient<R>, Option<R>),
    batch: &mut M::Batch,
    at: usize,
    active: R::Mask,
) -> (Response<R>, [R; 4]) {
    let memory = M::memory(batch).map_or(Memory::default(), |m| m.at::<R>(at));
    let mut step = kinematics::step(&memory, g);
    if let Some(hoop) = hoop {
        let before = M::memory(batch).map_or(R::splat(0.0), |m| m.hoop_at::<R>(at));
        step.strain[2] = kinematics::hoop_strain(memory.strain[2], before, hoop);
    }
    let mut r = material.update(&step.strain, batch, at, active);
    if let Some(m) = M::memory(batch) {
        let next = Memory {
            gradient: *g,
            strain: step.strain,
            hoop: R::splat(0.0),
        };
        m.store(at, &next, active);
        if let Some(hoop) = hoop {
            m.store_hoop(at, hoop, active);
        }
    }
    r.stress = step.rotation.apply(&r.stress);
    (r, step.inverse)
}

/// F-bar's factor `alpha = (J_c / J)^(1/2)` of the point `geometry` (its `J` from `u`, the
/// centroid's `j_c`) and the displacement gradient of `F_bar = alpha F`.
#[inline(always)]
fn f_bar<R: Real>(
    geometry: &PointGeometry<Lanes>,
    at: usize,
    u: &Vector<R>,
    j_c: R,
) -> (R, Gradient<R>) {
    let f_p = deformation(&geometry.gradient(at, u));
    let alpha = (j_c / det(&f_p)).sqrt();
    let g_bar = [
        f_p[0] * alpha - 1.0,
        f_p[1] * alpha,
        f_p[2] * alpha,
        f_p[3] * alpha - 1.0,
    ];
    (alpha, g_bar)
}

/// Adds a point's energy densities times its reference weight `w` (m^3) to `energy`.
#[inline(always)]
pub(crate) fn add_energy<M: ConstitutiveModel, R: Real>(
    energy: &mut Energy<R>,
    w: R,
    r: &Response<R>,
) {
    energy.strain += w * r.strain_energy_density;
    if M::HAS_STATES {
        energy.plastic_work += w * r.plastic_work_density;
    }
}

impl FiniteResponse for FullQ4 {
    #[inline(always)]
    fn finite_response<M: ConstitutiveModel, R: Real>(
        &self,
        material: &M,
        at: usize,
        u: &Vector<R>,
        (batches, active): (&mut [M::Batch], R::Mask),
    ) -> (Vector<R>, Energy<R>) {
        let mut f = [R::splat(0.0); 8];
        let mut energy = Energy::<R>::default();
        for (p, batch) in batches.iter_mut().enumerate().take(4) {
            let geometry = &self.points::<R>(at)[p];
            let w = geometry.det_j::<R>(at) * self.width;
            let g = geometry.gradient(at, u);
            let (r, inv) = point_update(material, (&g, None), batch, at, active);
            add_energy::<M, R>(&mut energy, w, &r);
            geometry.add_piola(at, w, &piola(&r.stress, &inv), &mut f);
        }
        (f, energy)
    }
}

impl FiniteResponse for SelectiveQ4 {
    #[inline(always)]
    fn finite_response<M: ConstitutiveModel, R: Real>(
        &self,
        material: &M,
        at: usize,
        u: &Vector<R>,
        (batches, active): (&mut [M::Batch], R::Mask),
    ) -> (Vector<R>, Energy<R>) {
        let centroid = self.centroid.batch::<R>(at);
        let f_c = deformation(&centroid.gradient(at, u));
        let j_c = det(&f_c);
        let inv_c = inverse_with(&f_c, R::splat(1.0) / j_c);
        let mut f = [R::splat(0.0); 8];
        let mut energy = Energy::<R>::default();
        let mut mean_total = R::splat(0.0);
        let points = self.full.points::<R>(at);
        // Each point's F-bar factor one point ahead: its division and square root then run
        // while the point before is updated, where in the point's own chain of factor, step,
        // return and forces they were waited on (the q4-sri finite kernel with every point
        // yielding, `impact-bench throughput --quick`: 60.2 -> 53.4 ns, min of 3 runs
        // interleaved with the previous binary; the whole step one point ahead, 16 vectors
        // carried instead of 5, was 7 % slower than the plain loop).
        let mut next = f_bar(&points[0], at, u, j_c);
        for (p, batch) in batches.iter_mut().enumerate().take(4) {
            let geometry = &points[p];
            let (alpha, g_bar) = next;
            if p + 1 < points.len() {
                next = f_bar(&points[p + 1], at, u, j_c);
            }
            let w = geometry.det_j::<R>(at) * self.full.width;
            let (r, inv_bar) = point_update(material, (&g_bar, None), batch, at, active);
            add_energy::<M, R>(&mut energy, w, &r);
            let tau = r.stress;
            let mean = (tau[0] + tau[1]) * 0.5;
            mean_total += w * mean;
            let deviator = [tau[0] - mean, tau[1] - mean, tau[2], tau[3]];
            // F^-1 = alpha F_bar^-1.
            let inv = kinematics::four(|c| inv_bar[c] * alpha);
            geometry.add_piola(at, w, &piola(&deviator, &inv), &mut f);
        }
        // The mean on the centroid's current gradients: P = m F_c^-T.
        let m = mean_total;
        let p_c = [m * inv_c[0], m * inv_c[2], m * inv_c[1], m * inv_c[3]];
        centroid.add_piola(at, &p_c, &mut f);
        (f, energy)
    }
}

impl FiniteResponse for OnePointQ4 {
    #[inline(always)]
    fn finite_response<M: ConstitutiveModel, R: Real>(
        &self,
        material: &M,
        at: usize,
        u: &Vector<R>,
        (batches, active): (&mut [M::Batch], R::Mask),
    ) -> (Vector<R>, Energy<R>) {
        let d = self.data.batch::<R>(at);
        let g = d.centroid.gradient(at, u);
        let (r, inv) = point_update(material, (&g, None), &mut batches[0], at, active);
        let mut energy = Energy::<R>::default();
        add_energy::<M, R>(&mut energy, R::of_batch(&d.volume, at), &r);
        let mut f = [R::splat(0.0); 8];
        d.weighted.add_piola(at, &piola(&r.stress, &inv), &mut f);
        energy.hourglass = self.add_hourglass(at, u, &mut f);
        (f, energy)
    }
}

impl<F: FiniteResponse> Formulation for UpdatedLagrangian<F> {
    const POINTS: usize = F::POINTS;
    /// The stiffness matrices and the elastic screen are small-strain shortcuts.
    const STIFFNESS_MATRIX_PAYS: bool = false;
    fn connectivity(&self) -> &[[u32; 4]] {
        self.0.connectivity()
    }
    #[inline(always)]
    fn shared<R: Real>(&self, at: usize, u: &Vector<R>) -> R {
        self.0.shared(at, u)
    }
    /// The small (linearised) strain: the probes' and the checks' measure; the response
    /// does not use it.
    #[inline(always)]
    fn strain<R: Real>(&self, at: usize, p: usize, u: &Vector<R>, shared: R) -> [R; 4] {
        self.0.strain(at, p, u, shared)
    }
    #[inline(always)]
    fn weights<R: Real>(&self, at: usize) -> [R; 4] {
        self.0.weights(at)
    }
    fn point_xi(&self) -> &'static [[f64; 2]] {
        self.0.point_xi()
    }
    #[inline(always)]
    fn add_point_forces<R: Real>(
        &self,
        at: usize,
        p: usize,
        s: &[R; 4],
        f: &mut Vector<R>,
        acc: &mut R,
    ) {
        self.0.add_point_forces(at, p, s, f, acc)
    }
    #[inline(always)]
    fn finish_forces<R: Real>(&self, at: usize, acc: R, f: &mut Vector<R>) {
        self.0.finish_forces(at, acc, f)
    }
    #[inline(always)]
    fn add_hourglass<R: Real>(&self, at: usize, u: &Vector<R>, f: &mut Vector<R>) -> R {
        self.0.add_hourglass(at, u, f)
    }
    #[inline(always)]
    fn hourglass_energy<R: Real>(&self, at: usize, u: &Vector<R>) -> R {
        self.0.hourglass_energy(at, u)
    }
    fn volume(&self, e: usize) -> f64 {
        self.0.volume(e)
    }
    fn nodal_masses(&self, e: usize, density: f64) -> [f64; 4] {
        self.0.nodal_masses(e, density)
    }
    fn heap_bytes(&self) -> usize {
        self.0.heap_bytes()
    }
    #[inline(always)]
    fn response<M: ConstitutiveModel, R: Real>(
        &self,
        material: &M,
        at: usize,
        u: &Vector<R>,
        states: (&mut [M::Batch], R::Mask),
    ) -> (Vector<R>, Energy<R>) {
        if M::KEEPS_MEMORY {
            self.0.finite_response(material, at, u, states)
        } else {
            small_strain_response(&self.0, material, at, u, states)
        }
    }
}
