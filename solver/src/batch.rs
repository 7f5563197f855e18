//! Batched element kernels: [`LANES`] elements at a time in struct-of-arrays form, every
//! lane doing the scalar kernel's arithmetic in the scalar kernel's order (see
//! [`crate::simd`] for the instruction sets and why the bits cannot change).
//!
//! A batch is [`LANES`] consecutive elements `b * LANES ..` inside one assembly chunk
//! ([`crate::assembly::CHUNK`] is a multiple of [`LANES`]); the last batch of a mesh may be
//! partial, its missing lanes padded with zero geometry and never written back. Per element
//! the energies are summed in element order exactly as the scalar chunk does.
//!
//! - The stress path: [`crate::element::response`] in lanes (strains, material update with
//!   the masked radial return, forces and hourglass), the scalar path's kernels instantiated
//!   with [`Lanes`], on each formulation's batch of geometry.
//! - The elastic screen of a plastic scene: lanes the screen proves elastic take `K_e u_e`;
//!   the others go through the stress path (inactive screened lanes keep their states).
//! - The stiffness product `K_e u_e` ([`linear_chunk`]) stays one element at a time: its 8
//!   rows are the vector (one AVX-512 register, two AVX2 ones), because lanes of different
//!   elements would need a gather per matrix entry where elements do not share `K_e`.
//!
//! Limits (measured and estimated on this project's 2-core AVX-512 Xeon, 2.7 GHz): a q4-sri
//! element-step with radial return at four points is ~700 flops, 24 of them divisions and 4
//! square roots that bit-identity forbids replacing (`x / 3.0` is not `x * (1/3)`); at the
//! AVX-512 divider's ~16 cycles per 8 divisions that alone is ~18 ns, so <= 30 ns is near
//! the floor. What remains above it (callgrind, AVX2 path: ~970 instructions per q4-sri
//! plastic element-step, over half of them moves) is the transposition between the
//! per-element storage (displacements, forces, plastic states as arrays of structs) and the
//! lanes: a batch-major state layout is the next step.

use crate::assembly::CHUNK;
use crate::elastic_screen::ElasticScreen;
use crate::element::{gather, response, ElementEnergy, ElementVector, Formulation};
use crate::material::ConstitutiveModel;
use crate::simd::{Kernel, Lanes, LANES};
use crate::stiffness::LinearKernel;

const _: () = assert!(CHUNK % LANES == 0, "batches must not straddle chunks");

/// The stress-path chunk kernel in batches (the elastic `screen` first where there is one):
/// forces of the chunk's elements from `first` into `forces`, their states updated, the
/// chunk's energies summed in element order.
pub struct StressPathChunk<'a, F: Formulation, M: ConstitutiveModel> {
    pub formulation: &'a F,
    pub material: &'a M,
    pub screen: Option<&'a ElasticScreen>,
    /// Nodal displacements, m.
    pub u: &'a [f64],
    pub first: usize,
    pub forces: &'a mut [ElementVector],
    pub states: &'a mut [M::State],
}

impl<F: Formulation, M: ConstitutiveModel> Kernel for StressPathChunk<'_, F, M> {
    type Output = ElementEnergy;
    #[inline(always)]
    fn run(self) -> ElementEnergy {
        let (formulation, material, u, first) =
            (self.formulation, self.material, self.u, self.first);
        let (forces, states) = (self.forces, self.states);
        let mut energy = ElementEnergy::default();
        for (k0, batch_forces) in (0..).step_by(LANES).zip(forces.chunks_mut(LANES)) {
            let e0 = first + k0;
            let mut elements = [[0.0; 8]; LANES];
            let mut active = [false; LANES];
            // Screened lanes' forces go straight to `batch_forces`, their energies here.
            let mut lane_energy = [ElementEnergy::default(); LANES];
            for (l, fe) in batch_forces.iter_mut().enumerate() {
                let e = gather(formulation.nodes(e0 + l), u);
                elements[l] = e;
                let lane_states = &states[(k0 + l) * F::POINTS..(k0 + l + 1) * F::POINTS];
                match self
                    .screen
                    .and_then(|s| s.element(formulation, material, e0 + l, &e, lane_states))
                {
                    Some((f, en)) => (*fe, lane_energy[l]) = (f, en),
                    None => active[l] = true,
                }
            }
            if active.iter().any(|&a| a) {
                // Into lanes only when some lane takes the stress path.
                let mut ue = [Lanes::splat(0.0); 8];
                for (l, e) in elements.iter().enumerate() {
                    for (j, &x) in e.iter().enumerate() {
                        ue[j].0[l] = x;
                    }
                }
                let lanes = (&mut *states, k0 * F::POINTS, active);
                let (f, en) = response(formulation, material, e0 / LANES, &ue, lanes);
                for (l, fe) in batch_forces.iter_mut().enumerate() {
                    if active[l] {
                        for (x, lanes) in fe.iter_mut().zip(&f) {
                            *x = lanes.0[l];
                        }
                        lane_energy[l] = en.lane(l);
                    }
                }
            }
            for en in &lane_energy[..batch_forces.len()] {
                energy += *en;
            }
        }
        energy
    }
}

/// The stiffness-product chunk kernel (`K_e u_e` element by element, each a vector over the
/// matrix rows).
pub struct LinearChunk<'a, F: Formulation> {
    pub kernel: &'a LinearKernel,
    pub formulation: &'a F,
    /// Nodal displacements, m.
    pub u: &'a [f64],
    pub first: usize,
    pub forces: &'a mut [ElementVector],
}

impl<F: Formulation> Kernel for LinearChunk<'_, F> {
    type Output = ElementEnergy;
    #[inline(always)]
    fn run(self) -> ElementEnergy {
        let mut energy = ElementEnergy::default();
        for (k, fe) in self.forces.iter_mut().enumerate() {
            let (force, en) = self
                .kernel
                .element(self.formulation, self.first + k, self.u);
            *fe = force;
            energy += en;
        }
        energy
    }
}
