//! The three elements of the axisymmetric geometry under finite deformation
//! (`ALGORITHM.md` section 3e): [`FiniteResponse`] for [`Axisymmetric`], so that
//! [`crate::physics::elements::finite_element::UpdatedLagrangian`] runs them.
//!
//! The deformation gradient of a ring is block diagonal: the section's in-plane `F` (2 x 2)
//! and the hoop stretch `F_theta = r / R = 1 + u_r / R` (`R` the point's reference radius).
//! The hoop direction is principal and never rotates, so the polar rotation is the in-plane
//! one; the unrotated hoop strain takes the midpoint increment `dF_theta / F_theta,mid`
//! ([`kinematics::hoop_strain`]), the in-plane strain the plane step. The forces are the
//! virtual work `int P : dF dV_ref` on the ring's reference weights `2 pi R det J`: the
//! in-plane `P = tau F^-T` on the point's reference gradients and the hoop entry
//! `P_theta = tau_theta / F_theta` on the hoop row `d(u_r / R)/du_{x,a} = -N_a / R`.
//! - `q4-full`: the four points as above.
//! - `q4-sri`: F-bar with the ring's volume change (de Souza Neto et al. 1996, the
//!   three-dimensional form): `F_bar = (J_bar / J)^(1/3) F` at each point (hoop included),
//!   `J = det F F_theta` the point's and `J_bar = V / V_ref` the element's (2 x 2 Gauss on
//!   `r det J` is exact for the bilinear element, so `V = sum w J` is its current ring
//!   volume). Its virtual work splits into the deviatoric stress on the point's current
//!   gradients and the weighted mean stress `m = tr tau / 3` on `dV / V`, with `dV = sum w J
//!   tr(dF F^-1)`. At small strain this is the small-strain ring's B-bar on the mean
//!   dilatation, the same split (three-dimensional mean).
//! - `q4-1pt`: the ring-volume mean displacement gradient and hoop gradient (the
//!   small-strain element's mean operators), one stress for the element, and the plane
//!   element's hourglass forces on the total displacements (as in plane strain).

use crate::lanes::cube_root::cube_root;
use crate::lanes::real::{Real, THIRD};
use crate::physics::elements::axisymmetric::Axisymmetric;
use crate::physics::elements::element::{Energy, Formulation, FullQ4, OnePointQ4, SelectiveQ4};
use crate::physics::elements::finite_element::{add_energy, point_update, FiniteResponse};
use crate::physics::elements::geometry::Vector;
use crate::physics::kinematics::{self, deformation, det, piola};
use crate::physics::materials::material::ConstitutiveModel;

impl FiniteResponse for Axisymmetric<FullQ4> {
    #[inline(always)]
    fn finite_response<M: ConstitutiveModel, R: Real>(
        &self,
        material: &M,
        at: usize,
        u: &Vector<R>,
        (batches, active): (&mut [M::Batch], R::Mask),
    ) -> (Vector<R>, Energy<R>) {
        let ring = self.ring::<R>(at);
        let mut f = [R::splat(0.0); 8];
        let mut energy = Energy::<R>::default();
        for (p, batch) in batches.iter_mut().enumerate().take(4) {
            let geometry = &self.plane.points::<R>(at)[p];
            let w = ring.weight(p, at);
            let g = geometry.gradient(at, u);
            let hoop = ring.hoop_strain(p, at, u);
            let (r, inv) = point_update(material, (&g, Some(hoop)), batch, at, active);
            add_energy::<M, R>(&mut energy, w, &r);
            geometry.add_piola(at, w, &piola(&r.stress, &inv), &mut f);
            ring.add_hoop_forces(p, at, w * r.stress[2] / (hoop + 1.0), &mut f);
        }
        (f, energy)
    }
}

impl FiniteResponse for Axisymmetric<SelectiveQ4> {
    #[inline(always)]
    fn finite_response<M: ConstitutiveModel, R: Real>(
        &self,
        material: &M,
        at: usize,
        u: &Vector<R>,
        (batches, active): (&mut [M::Batch], R::Mask),
    ) -> (Vector<R>, Energy<R>) {
        let ring = self.ring::<R>(at);
        let points = self.plane.full.points::<R>(at);
        let (zero, one) = (R::splat(0.0), R::splat(1.0));
        // Each point's F, hoop stretch and volume change; the element's reference and
        // current ring volumes.
        let (mut f_p, mut stretch, mut j_p) = ([[zero; 4]; 4], [one; 4], [one; 4]);
        let (mut v_ref, mut v_cur) = (zero, zero);
        for p in 0..4 {
            f_p[p] = deformation(&points[p].gradient(at, u));
            stretch[p] = ring.hoop_strain(p, at, u) + 1.0;
            j_p[p] = det(&f_p[p]) * stretch[p];
            let w = ring.weight::<R>(p, at);
            v_ref += w;
            v_cur += w * j_p[p];
        }
        let j_bar = v_cur / v_ref;
        let mut f = [zero; 8];
        let mut energy = Energy::<R>::default();
        let mut mean_total = zero;
        let mut inverses = [[zero; 4]; 4];
        for (p, batch) in batches.iter_mut().enumerate().take(4) {
            let w = ring.weight(p, at);
            // The cube root on the lanes, its ratio near 1 (lanes::cube_root): libm's cbrt
            // lane by lane took 10 % of a copper Taylor bar's run; the power exp(ln(x) / 3)
            // on the lanes made the axisymmetric finite q4-sri kernel 122 ns against 109 ns.
            let alpha = cube_root(j_bar / j_p[p]);
            let g = &f_p[p];
            let g_bar = [
                g[0] * alpha - 1.0,
                g[1] * alpha,
                g[2] * alpha,
                g[3] * alpha - 1.0,
            ];
            let hoop_bar = stretch[p] * alpha - 1.0;
            let (r, inv_bar) = point_update(material, (&g_bar, Some(hoop_bar)), batch, at, active);
            add_energy::<M, R>(&mut energy, w, &r);
            let tau = r.stress;
            let mean = (tau[0] + tau[1] + tau[2]) * THIRD;
            mean_total += w * mean;
            let deviator = [tau[0] - mean, tau[1] - mean, tau[2] - mean, tau[3]];
            // F^-1 = alpha F_bar^-1.
            inverses[p] = kinematics::four(|c| inv_bar[c] * alpha);
            points[p].add_piola(at, w, &piola(&deviator, &inverses[p]), &mut f);
            ring.add_hoop_forces(p, at, w * deviator[2] / stretch[p], &mut f);
        }
        // The mean on the element's volume change: (sum w m / V) dV/du, dV/du = sum w J
        // (F^-T : grad N, and 1 / F_theta on the hoop row).
        let scale = mean_total / v_cur;
        for (p, inv) in inverses.iter().enumerate() {
            let c = scale * ring.weight::<R>(p, at) * j_p[p];
            points[p].add_piola(at, c, &[inv[0], inv[2], inv[1], inv[3]], &mut f);
            ring.add_hoop_forces(p, at, c / stretch[p], &mut f);
        }
        (f, energy)
    }
}

impl FiniteResponse for Axisymmetric<OnePointQ4> {
    #[inline(always)]
    fn finite_response<M: ConstitutiveModel, R: Real>(
        &self,
        material: &M,
        at: usize,
        u: &Vector<R>,
        (batches, active): (&mut [M::Batch], R::Mask),
    ) -> (Vector<R>, Energy<R>) {
        let ring = self.ring::<R>(at);
        let (g, hoop) = ring.mean_gradient(at, u);
        let (r, inv) = point_update(material, (&g, Some(hoop)), &mut batches[0], at, active);
        let w = self.weights::<R>(at)[0];
        let mut energy = Energy::<R>::default();
        add_energy::<M, R>(&mut energy, w, &r);
        let mut f = [R::splat(0.0); 8];
        let p_theta = r.stress[2] / (hoop + 1.0);
        ring.add_mean_piola(at, w, (&piola(&r.stress, &inv), p_theta), &mut f);
        energy.hourglass = self.plane.add_hourglass(at, u, &mut f);
        (f, energy)
    }
}
