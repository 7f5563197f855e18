//! Batched element kernels: [`LANES`] elements at a time in struct-of-arrays form, every
//! lane doing the scalar kernel's arithmetic in the scalar kernel's order (see
//! [`crate::simd`] for the instruction sets and why the bits cannot change).
//!
//! A batch is [`LANES`] consecutive elements `b * LANES ..` inside one assembly chunk
//! ([`crate::assembly::CHUNK`] is a multiple of [`LANES`]); the last batch of a mesh may be
//! partial, its missing lanes padded with zero geometry and never written back. Per element
//! the energies are summed in element order exactly as the scalar chunk does.
//!
//! - The stress path ([`element_response_lanes`]): strains, material update
//!   ([`ConstitutiveModel::update_lanes`], masked radial return), forces and hourglass, all
//!   in lanes, from each formulation's lane geometry ([`crate::point_lanes::PointLanes`]).
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
use crate::element::{gather, ElementEnergy, ElementVector, Formulation};
use crate::material::ConstitutiveModel;
use crate::point_lanes::VectorLanes;
use crate::simd::{Kernel, Lanes, Mask, LANES};
use crate::stiffness::LinearKernel;

const _: () = assert!(CHUNK % LANES == 0, "batches must not straddle chunks");

/// Element energies of a batch, J per lane.
#[derive(Debug, Clone, Copy, Default)]
pub struct EnergyLanes {
    pub strain: Lanes,
    pub plastic_work: Lanes,
    pub hourglass: Lanes,
}

impl EnergyLanes {
    #[inline(always)]
    pub fn lane(&self, l: usize) -> ElementEnergy {
        ElementEnergy {
            strain: self.strain.0[l],
            plastic_work: self.plastic_work.0[l],
            hourglass: self.hourglass.0[l],
        }
    }
}

/// [`crate::element::element_response`] for batch `b` in lanes: forces (dof x lanes) and
/// energies, updating the states of the `active` lanes (`states`: the chunk's, lane `l`'s
/// points from `first_state + l * POINTS`).
#[inline(always)]
pub fn element_response_lanes<F: Formulation, M: ConstitutiveModel>(
    formulation: &F,
    material: &M,
    b: usize,
    u: &VectorLanes,
    states: &mut [M::State],
    first_state: usize,
    active: &Mask,
) -> (VectorLanes, EnergyLanes) {
    let strains = formulation.strains_lanes(b, u);
    let w = formulation.weights_lanes(b);
    let mut stresses = [[Lanes::splat(0.0); 4]; 4];
    let mut energy = EnergyLanes::default();
    for p in 0..F::POINTS {
        let r = material.update_lanes(&strains[p], states, first_state + p, F::POINTS, active);
        stresses[p] = r.stress;
        energy.strain += w[p] * r.strain_energy_density;
        energy.plastic_work += w[p] * r.plastic_work_density;
    }
    let mut f = formulation.forces_lanes(b, &stresses);
    energy.hourglass = formulation.add_hourglass_lanes(b, u, &mut f);
    (f, energy)
}

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
        let StressPathChunk {
            formulation,
            material,
            screen,
            u,
            first,
            forces,
            states,
        } = self;
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
                match screen.and_then(|s| s.element(formulation, material, e0 + l, &e, lane_states))
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
                let (first_state, b) = (k0 * F::POINTS, e0 / LANES);
                let (f, en) = element_response_lanes(
                    formulation,
                    material,
                    b,
                    &ue,
                    states,
                    first_state,
                    &active,
                );
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
