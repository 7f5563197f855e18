//! Batched element kernels: [`LANES`] elements at a time in struct-of-arrays form, every
//! lane doing the scalar kernel's arithmetic in the scalar kernel's order (see
//! [`crate::lanes::simd`] for the instruction sets and why the bits cannot change).
//!
//! A batch is [`LANES`] consecutive elements `b * LANES ..` inside one assembly chunk
//! ([`crate::kernels::assembly::CHUNK`] is a multiple of [`LANES`]); the last batch of a mesh may be
//! partial, its missing lanes padded with zero geometry and never written back. The energies
//! are summed per lane and then in lane order, as the scalar chunk sums them
//! ([`Energy::lane_total`]).
//!
//! Everything stays in lanes from the gather of the displacements to the forces: the
//! displacements are loaded by index (one gather per vector; a batch in one row of a
//! structured mesh as two contiguous runs), the material states are stored batch-major (one
//! [`ConstitutiveModel::Batch`] per point of a batch), and the forces are written as whole
//! batches ([`BatchForces`]) that the assembly scatters.
//!
//! - The stress path: [`crate::physics::elements::element::response`] in lanes (strains, material update with
//!   the masked radial return, forces and hourglass), the scalar path's kernels instantiated
//!   with [`Lanes`], on each formulation's batch of geometry.
//! - The elastic screen of a plastic scene: a chunk whose every point is virgin and every
//!   element below the screen's bound is done by the screen alone ([`ScreenedChunk`], its own
//!   kernel, the forces scattered in it); in another chunk, `K_e u_e` in lanes for each batch
//!   with a virgin lane: lanes the screen proves elastic take it, the others the stress path
//!   (the screened lanes' states are not written), chosen per lane.
//! - The stiffness product `K_e u_e` ([`LinearChunk`]) in lanes, over the batch's matrices
//!   stored in lanes ([`LinearKernel`]).
//!
//! Limits (this project's machine: an AMD EPYC of family 25 model 17, Zen 4, 2.6 GHz; its
//! two 256-bit FMA/multiply pipes and two 256-bit add pipes retire one 512-bit multiply and
//! one 512-bit add per cycle, 16 flops per cycle or ~42 GFLOP/s, the same with or without
//! FMA when multiplies and adds are balanced): a q4-sri element-step with radial return at
//! four points is ~660 flops (counted from the kernels), with 4 divisions and 4 square roots
//! per element left after divisions by constants became products (see [`crate::lanes::real`]); the
//! stiffness product is ~115 (48 products and sums: node 0's two columns are skipped); the
//! one-point elastic stress path ~110 (49 products, 62 sums and differences per batch in its
//! loop, half of them the hourglass control's).
//! Measured (2026-11-25, 1 thread, 80 x 16, `impact-bench throughput`): 29.3 ns, 5.1-5.3 ns
//! and 4.7 ns, 22.5, 22 and 23 GFLOP/s, about half of that peak. In the profiles (perf,
//! cpu-clock samples) the rest is register spills and reloads (~12 % of the yielding
//! kernel), the latency of each point's square root and division (~9 %), and the row scatter
//! (~20 % of the stiffness product's time, ~30 % of the one-point stress path's, which
//! scatters in a kernel of its own).

use std::ops::Range;

use crate::kernels::assembly::{BatchForces, Scatter, CHUNK};
use crate::kernels::elastic_screen::ElasticScreen;
use crate::kernels::row_batches::RowBatches;
use crate::kernels::stiffness::LinearKernel;
use crate::lanes::real::Real;
use crate::lanes::simd::{each_lane, Kernel, Lanes, Mask, LANES};
use crate::physics::elements::element::{response, ElementEnergy, Energy, Formulation};
use crate::physics::elements::geometry::Vector;
use crate::physics::materials::material::ConstitutiveModel;

const _: () = assert!(CHUNK % LANES == 0, "batches must not straddle chunks");

/// The displacement vectors (m) of the elements `e0 ..` (`lanes` of them, at most [`LANES`];
/// the missing lanes hold node 0's) in lanes. Each vector is loaded whole by index (one
/// gather instruction where the processor has one): lanes written one by one into memory
/// and then read as a vector stall the load until the stores retire.
#[inline(always)]
fn gather_lanes<F: Formulation>(
    formulation: &F,
    rows: &RowBatches,
    e0: usize,
    lanes: usize,
    u: &[f64],
) -> Vector<Lanes> {
    if lanes == LANES {
        if let Some(ue) = rows.runs(e0 / LANES).and_then(|runs| row_lanes(runs, u)) {
            return ue;
        }
    }
    let mut dof = [[0usize; LANES]; 4];
    for l in 0..lanes {
        for (a, &n) in formulation.nodes(e0 + l).iter().enumerate() {
            dof[a][l] = 2 * n as usize;
        }
    }
    // Every index is checked once here, so the loads below need no check of their own and
    // vectorise.
    let highest = dof.iter().flatten().copied().max().unwrap_or(0);
    assert!(highest + 1 < u.len(), "node beyond the displacement vector");
    let mut ue = [Lanes::splat(0.0); 8];
    for (a, dof) in dof.iter().enumerate() {
        for l in 0..LANES {
            // SAFETY: dof[l] + 1 <= highest + 1 < u.len() (asserted above).
            unsafe {
                ue[2 * a].0[l] = *u.get_unchecked(dof[l]);
                ue[2 * a + 1].0[l] = *u.get_unchecked(dof[l] + 1);
            }
        }
    }
    ue
}

/// [`gather_lanes`] of a full batch that lies in one row of a structured mesh, its two
/// `runs` of nodes from their first (element `l`'s nodes are `[b + l, b + l + 1, t + l + 1,
/// t + l]`; see [`crate::kernels::row_batches`]): each run is one contiguous slice of `u`, loaded
/// whole and split into lanes by shuffles instead of eight gathers. `None` if a run is not
/// in `u`.
#[inline(always)]
fn row_lanes([b, t]: [usize; 2], u: &[f64]) -> Option<Vector<Lanes>> {
    let (b, t) = (2 * b, 2 * t);
    const RUN: usize = 2 * (LANES + 1);
    let bottom: &[f64; RUN] = u.get(b..b + RUN)?.try_into().ok()?;
    let top: &[f64; RUN] = u.get(t..t + RUN)?.try_into().ok()?;
    // Local node a, component c: from the bottom run at node l (a = 0) or l + 1 (a = 1),
    // from the top run at node l + 1 (a = 2) or l (a = 3).
    let from =
        |run: &[f64; RUN], shift: usize, c: usize| Lanes(each_lane(|l| run[2 * (l + shift) + c]));
    Some([
        from(bottom, 0, 0),
        from(bottom, 0, 1),
        from(bottom, 1, 0),
        from(bottom, 1, 1),
        from(top, 1, 0),
        from(top, 1, 1),
        from(top, 0, 0),
        from(top, 0, 1),
    ])
}

/// Adds the energies of the first `lanes` lanes to the per-lane partial sums `partial`
/// (see [`Energy::lane_total`]).
#[inline(always)]
fn add_lanes(partial: &mut Energy<Lanes>, energy: &Energy<Lanes>, lanes: usize) {
    if lanes == LANES {
        *partial += *energy;
    } else {
        for l in 0..lanes {
            partial.add_to_lane(l, energy.lane(l));
        }
    }
}

/// The lanes of `lanes` (a mask) whose points have all never yielded: `point_states`, one
/// batch of states per point of batch `b`.
#[inline(always)]
fn virgin_lanes<M: ConstitutiveModel>(
    material: &M,
    point_states: &[M::Batch],
    b: usize,
    lanes: Mask,
) -> Mask {
    let mut virgin = lanes;
    for batch in point_states {
        virgin = Lanes::and(virgin, material.virgin::<Lanes>(batch, b));
    }
    virgin
}

/// Whether `mask` holds each of the first `lanes` lanes.
#[inline(always)]
fn every_lane(mask: Mask, lanes: usize) -> bool {
    !Lanes::any(Lanes::and(Mask::first(lanes), Lanes::not(mask)))
}

/// The stress-path chunk kernel in batches (the elastic `screen` first where there is one):
/// forces of the chunk's `elements` into their batches `forces`, their states updated, the
/// chunk's energies summed per lane ([`Energy::lane_total`]).
pub struct StressPathChunk<'a, F: Formulation, M: ConstitutiveModel> {
    pub formulation: &'a F,
    pub material: &'a M,
    pub screen: Option<&'a ElasticScreen>,
    /// The mesh's row batches (for the gathers).
    pub rows: &'a RowBatches,
    /// Nodal displacements, m.
    pub u: &'a [f64],
    pub elements: Range<usize>,
    pub forces: &'a mut [BatchForces],
    /// The chunk's material states, `POINTS` batches per batch of elements.
    pub states: &'a mut [M::Batch],
}

impl<F: Formulation, M: ConstitutiveModel> Kernel for StressPathChunk<'_, F, M> {
    type Output = ElementEnergy;
    #[inline(always)]
    fn run(self) -> ElementEnergy {
        let (formulation, material, u) = (self.formulation, self.material, self.u);
        let (forces, states, first) = (self.forces, self.states, self.elements.start);
        let mut energy = Energy::<Lanes>::default();
        for (k0, batch_forces) in (0..self.elements.len()).step_by(LANES).zip(forces) {
            let (e0, lanes) = (first + k0, (self.elements.len() - k0).min(LANES));
            let b = e0 / LANES;
            let ue = gather_lanes(formulation, self.rows, e0, lanes, u);
            let mut active = Mask::first(lanes);
            // The screened lanes: virgin (every point) and below the screen's bound.
            // (No product when no lane is virgin: yielded elements never take it.)
            let mut screened = None;
            // A material without states never yields and has no screen: the branch is not
            // compiled for it (its code changed the elastic stress path's registers).
            if let Some(screen) = self.screen.filter(|_| M::HAS_STATES) {
                let point_states = &states[k0 / LANES * F::POINTS..][..F::POINTS];
                let virgin = virgin_lanes(material, point_states, b, active);
                if Lanes::any(virgin) {
                    let (f, en, below) = screen.product_in_stress_path(formulation, b, &ue);
                    active = Lanes::and(active, Lanes::not(Lanes::and(virgin, below)));
                    screened = Some((f, en));
                }
            }
            let (f, en) = match screened {
                Some(screened) if !Lanes::any(active) => screened,
                _ => {
                    let batches = &mut states[k0 / LANES * F::POINTS..][..F::POINTS];
                    let lanes_states = (batches, active);
                    let (mut f, mut en) = response(formulation, material, b, &ue, lanes_states);
                    if let Some((fk, ek)) = screened {
                        let screened_lanes = Lanes::not(active);
                        for (x, k) in f.iter_mut().zip(fk) {
                            *x = Lanes::select(screened_lanes, k, *x);
                        }
                        en = Energy::select(screened_lanes, ek, en);
                    }
                    (f, en)
                }
            };
            *batch_forces = f;
            add_lanes(&mut energy, &en, lanes);
        }
        energy.lane_total()
    }
}

/// The elastic screen for a whole chunk, a kernel of its own (its code kept out of the
/// stress path's, whose registers it changes): when every point of the chunk is virgin and
/// every element below the screen's bound, the chunk's forces are the screen's `K_e u_e`
/// (the bits the stress path's screen gives them), scattered, and its energies returned;
/// otherwise `None`, with nothing scattered and no state touched (the caller runs the stress
/// path). The checks read the states first, so a chunk with a yielded point costs little.
pub struct ScreenedChunk<'a, F: Formulation, M: ConstitutiveModel> {
    pub screen: &'a ElasticScreen,
    pub formulation: &'a F,
    pub material: &'a M,
    /// Nodal displacements, m.
    pub u: &'a [f64],
    pub elements: Range<usize>,
    pub forces: &'a mut [BatchForces],
    /// The chunk's material states, `POINTS` batches per batch of elements.
    pub states: &'a [M::Batch],
    /// Where the forces go, once computed.
    pub scatter: &'a Scatter<'a>,
}

impl<F: Formulation, M: ConstitutiveModel> Kernel for ScreenedChunk<'_, F, M> {
    type Output = Option<ElementEnergy>;
    #[inline(always)]
    fn run(self) -> Option<ElementEnergy> {
        let (formulation, first, n) = (self.formulation, self.elements.start, self.elements.len());
        let batches = || (0..n).step_by(LANES).map(|k0| (k0, (n - k0).min(LANES)));
        for (k0, lanes) in batches() {
            let point_states = &self.states[k0 / LANES * F::POINTS..][..F::POINTS];
            let b = (first + k0) / LANES;
            let virgin = virgin_lanes(self.material, point_states, b, Mask::first(lanes));
            if !every_lane(virgin, lanes) {
                return None;
            }
        }
        let mut energy = Energy::<Lanes>::default();
        for ((k0, lanes), batch_forces) in batches().zip(&mut *self.forces) {
            let ue = gather_lanes(formulation, self.scatter.rows(), first + k0, lanes, self.u);
            let (f, en, below) = self.screen.product(formulation, (first + k0) / LANES, &ue);
            if !every_lane(below, lanes) {
                return None;
            }
            *batch_forces = f;
            add_lanes(&mut energy, &en, lanes);
        }
        let nodes = |e| formulation.nodes(e);
        self.scatter.chunk(self.elements, self.forces, nodes);
        Some(energy.lane_total())
    }
}

/// The stiffness-product chunk kernel (`K_e u_e`, in lanes).
pub struct LinearChunk<'a, F: Formulation> {
    pub kernel: &'a LinearKernel,
    pub formulation: &'a F,
    /// Nodal displacements, m.
    pub u: &'a [f64],
    pub elements: Range<usize>,
    pub forces: &'a mut [BatchForces],
    /// Where the forces go, once computed.
    pub scatter: &'a Scatter<'a>,
}

impl<F: Formulation> Kernel for LinearChunk<'_, F> {
    type Output = ElementEnergy;
    #[inline(always)]
    fn run(self) -> ElementEnergy {
        let (formulation, u, first) = (self.formulation, self.u, self.elements.start);
        let mut energy = Energy::<Lanes>::default();
        for (k0, batch_forces) in (0..self.elements.len())
            .step_by(LANES)
            .zip(&mut *self.forces)
        {
            let (e0, lanes) = (first + k0, (self.elements.len() - k0).min(LANES));
            let ue = gather_lanes(formulation, self.scatter.rows(), e0, lanes, u);
            let (f, en) = self.kernel.product(formulation, e0 / LANES, &ue);
            *batch_forces = f;
            add_lanes(&mut energy, &en, lanes);
        }
        let nodes = |e| formulation.nodes(e);
        self.scatter.chunk(self.elements, self.forces, nodes);
        energy.lane_total()
    }
}
