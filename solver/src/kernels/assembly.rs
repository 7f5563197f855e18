//! Assembly of element forces into nodal forces (eq. 13), on one thread or several, with
//! results bit-identical for any thread count: elements are processed in fixed chunks of
//! [`CHUNK`], each chunk's energies summed as per-lane partial sums in element order, added in
//! lane order ([`Energy::lane_total`]), the chunk sums added in chunk order, and every nodal
//! force summed over its elements in element order from 0. Each chunk's forces are scattered
//! as soon as the chunk is done (from a chunk-sized buffer, still in cache), so no
//! per-element force array is kept. With a [`Team`], each part scatters
//! directly into the nodes whose elements are all its own; a node shared by two parts is
//! summed after the job from the kept forces of its elements, in element order: the same
//! additions in the same order. Threads only change who computes a chunk or a node, never
//! the arithmetic. While the team is measured slower than one thread ([`Fallback`]), the
//! calling thread runs the whole mesh as one part, as on one thread: the same additions in the
//! same order, so the same bits, without the shared nodes' second pass (running the team's
//! parts one after another instead cost ~4 % per step on the paper's plastic scene: 2026-11-26,
//! 0.670 against 0.644 s, minimum of 10 interleaved).

use std::ops::Range;

use crate::kernels::fallback::{self, Fallback};
use crate::kernels::row_batches::{add_run, Pending, RowBatches};
use crate::kernels::workers::{part_range, threads_here, Team};
use crate::lanes::heap::vec_bytes;
use crate::lanes::simd::{Kernel, Lanes, LANES};
use crate::physics::elements::element::{ElementEnergy, ElementVector, Energy};
use crate::physics::elements::geometry::Vector;

/// Elements per task.
pub const CHUNK: usize = 64;

/// Batches of [`LANES`] elements per chunk.
const BATCHES: usize = CHUNK / LANES;

/// Meshes with fewer elements run on one thread (see [`Assembly::for_mesh`]). Measured
/// (2026-11-23, this 2-core machine idle, paper plastic scene, batched kernels, wall time of
/// 1 / 2 threads): 20 x 4 (80 elements) 0.042-0.053 / 0.048-0.074 s, no gain; 40 x 8 (320)
/// 0.25-0.37 / 0.19-0.27 s, 1.3x; 80 x 16 (1280) 2.2-3.0 / 1.49-1.60 s, 1.45-1.9x. The
/// elastic stiffness product did not gain at 40 x 8 to 160 x 32 (1.0-1.3x slower: the step is
/// the nodal loops'), so only the plastic stress path runs on several threads.
pub const PARALLEL_MIN_ELEMENTS: usize = 256;

/// The force vectors (N) of a batch of [`LANES`] consecutive elements, in lanes: how the
/// kernels leave them (batch-major, so the batched kernels store whole registers).
pub type BatchForces = Vector<Lanes>;

/// One chunk's forces: the kernels' output, scattered before the next chunk.
type ChunkForces = [BatchForces; BATCHES];

/// Buffers of the chunked assembly (allocated once, reused every step), and the team of
/// threads when it runs on several.
pub struct Assembly {
    n_elements: usize,
    /// Per part (thread), the chunk it is on.
    scratch: Vec<ChunkForces>,
    chunk_energy: Vec<ElementEnergy>,
    parallel: Option<Parallel>,
    /// The row batches of the whole mesh as one part (on one thread, and while a team is
    /// fallen back; [`Parallel::rows`] on the team).
    rows: RowBatches,
}

/// What the assembly on several threads needs besides the buffers.
struct Parallel {
    team: Team,
    /// Per step: on the team, or the whole mesh on the calling thread.
    fallback: Fallback,
    /// The row batches the team's parts scatter whole (those without an element on a
    /// shared node).
    rows: RowBatches,
    /// Per node: whether elements of two or more parts meet at it.
    shared: Vec<bool>,
    /// Per element: its slot in `kept` when it has a shared node, else `u32::MAX`.
    slot: Vec<u32>,
    /// The forces of the elements with a shared node (by slot), N.
    kept: Vec<ElementVector>,
    /// The shared nodes and, per shared node, its entries in `kept` in element order.
    shared_nodes: NodeEntries,
}

impl Parallel {
    fn new(connectivity: &[[u32; 4]], n_nodes: usize, threads: usize) -> Parallel {
        let n_chunks = connectivity.len().div_ceil(CHUNK);
        // The part of each node's elements, or Some(None) once two parts meet at it.
        let mut part_of: Vec<Option<Option<usize>>> = vec![None; n_nodes];
        for part in 0..threads {
            for e in part_elements(n_chunks, connectivity.len(), threads, part) {
                for &n in &connectivity[e] {
                    let slot = &mut part_of[n as usize];
                    *slot = match *slot {
                        None => Some(Some(part)),
                        Some(Some(p)) if p == part => Some(Some(part)),
                        _ => Some(None),
                    };
                }
            }
        }
        let shared: Vec<bool> = part_of.iter().map(|p| *p == Some(None)).collect();
        let mut slot = vec![u32::MAX; connectivity.len()];
        let mut n_kept = 0;
        for (e, nodes) in connectivity.iter().enumerate() {
            if nodes.iter().any(|&n| shared[n as usize]) {
                slot[e] = n_kept;
                n_kept += 1;
            }
        }
        let shared_nodes = NodeEntries::new(connectivity, n_nodes, |n| shared[n], |e| slot[e]);
        // A batch with an element on a shared node goes element by element.
        let rows = RowBatches::new(connectivity, |e| slot[e] != u32::MAX);
        Parallel {
            team: Team::new(threads),
            fallback: Fallback::new(threads, fallback::policy_here()),
            rows,
            shared,
            slot,
            kept: vec![[0.0; 8]; n_kept as usize],
            shared_nodes,
        }
    }
}

/// The elements of part `part` of `parts`: whole chunks, contiguous.
fn part_elements(n_chunks: usize, n_elements: usize, parts: usize, part: usize) -> Range<usize> {
    let chunks = part_range(n_chunks, parts, part);
    (chunks.start * CHUNK).min(n_elements)..(chunks.end * CHUNK).min(n_elements)
}

/// Where a chunk's forces go: every node straight into `f`, or, on several threads, only the
/// nodes not `shared`, the forces of the elements with a `slot` copied into `kept`. The chunk
/// kernel calls [`Scatter::chunk`] itself (or through [`ScatterChunk`]), so that the scatter
/// is compiled for the kernel's instruction set (the row batches' vector sums in AVX-512).
pub struct Scatter<'a> {
    f: &'a Disjoint<f64>,
    /// The batches that lie in one row and have no shared node: added a batch at a time.
    rows: &'a RowBatches,
    shared: Option<(&'a [bool], &'a [u32], &'a Disjoint<ElementVector>)>,
}

/// [`Scatter::chunk`] as a [`Kernel`], to run it compiled for an instruction set apart from
/// the kernel that computed the forces (see the stress path in `PlateModel::internal_forces`).
pub struct ScatterChunk<'a, N> {
    pub scatter: &'a Scatter<'a>,
    pub elements: Range<usize>,
    pub forces: &'a [BatchForces],
    /// Element `e`'s nodes.
    pub nodes: N,
}

impl<N: Fn(usize) -> [u32; 4]> Kernel for ScatterChunk<'_, N> {
    type Output = ();
    #[inline(always)]
    fn run(self) {
        self.scatter.chunk(self.elements, self.forces, self.nodes);
    }
}

impl<'a> Scatter<'a> {
    /// The mesh's row batches (for the kernels' gathers: [`RowBatches::runs`]).
    pub fn rows(&self) -> &'a RowBatches {
        self.rows
    }

    /// Scatters the forces `forces` of the chunk's `elements` (`nodes(e)`: element `e`'s
    /// nodes), in element order: a row batch at once ([`add_run`]; the last node of each of
    /// its runs kept in a register for the next row batch of the row, [`Pending`]), the
    /// others element by element.
    #[inline(always)]
    pub fn chunk(
        &self,
        elements: Range<usize>,
        forces: &[BatchForces],
        nodes: impl Fn(usize) -> [u32; 4],
    ) {
        let mut pending: [Option<Pending>; 2] = [None; 2];
        for (k0, batch) in (0..elements.len()).step_by(LANES).zip(forces) {
            let e0 = elements.start + k0;
            if let Some(runs) = self.rows.scatter_runs(e0 / LANES) {
                // Every pending node the batch does not continue is stored first: it may be
                // a node of the batch's other run (a row one batch wide).
                let carried = [0, 1].map(|run| Pending::carried_to(pending[run], runs[run]));
                for (pending, carried) in pending.iter_mut().zip(carried) {
                    if carried.is_none() {
                        self.store(pending.take());
                    }
                }
                for ((run, first), pending) in runs.into_iter().enumerate().zip(&mut pending) {
                    let carried = carried[run];
                    // SAFETY: a row batch has no shared node: its nodes are its part's.
                    let f = unsafe { self.f.slice(2 * first..2 * first + 2 * (LANES + 1)) };
                    let force = add_run(f, batch, run, carried);
                    *pending = Some(Pending {
                        node: first + LANES,
                        force,
                    });
                }
                continue;
            }
            pending.iter_mut().for_each(|p| self.store(p.take()));
            for l in 0..(elements.len() - k0).min(LANES) {
                let mut fe: ElementVector = [0.0; 8];
                for (x, lanes) in fe.iter_mut().zip(batch) {
                    *x = lanes.0[l];
                }
                self.element(e0 + l, &fe, nodes(e0 + l));
            }
        }
        pending.iter_mut().for_each(|p| self.store(p.take()));
    }

    /// Stores a run's `pending` last node.
    #[inline(always)]
    fn store(&self, pending: Option<Pending>) {
        if let Some(Pending { node, force }) = pending {
            // SAFETY: the node is a row batch's, so its part's (see `chunk`).
            unsafe { self.f.slice(2 * node..2 * node + 2) }.copy_from_slice(&force);
        }
    }

    /// Scatters element `e`'s forces `fe` (N) to its `nodes`.
    #[inline(always)]
    fn element(&self, e: usize, fe: &ElementVector, nodes: [u32; 4]) {
        let shared = match self.shared {
            Some((shared, slot, kept)) if slot[e] != u32::MAX => {
                // SAFETY: an element's slot is written by the part that owns the element.
                unsafe { kept.slice(slot[e] as usize..slot[e] as usize + 1)[0] = *fe };
                Some(shared)
            }
            _ => None,
        };
        for (a, &n) in nodes.iter().enumerate() {
            let n = n as usize;
            if shared.is_some_and(|s| s[n]) {
                continue;
            }
            // SAFETY: a node not shared has all its elements in this part (or there is
            // one part), so only this part writes it.
            let f = unsafe { self.f.slice(2 * n..2 * n + 2) };
            f[0] += fe[2 * a];
            f[1] += fe[2 * a + 1];
        }
    }
}

impl Assembly {
    /// Buffers for the elements `connectivity` over `n_nodes` nodes; `threads` > 1 starts a
    /// team of that many threads (the caller's included) that assembles in parallel.
    pub fn new(connectivity: &[[u32; 4]], n_nodes: usize, threads: usize) -> Assembly {
        let n_elements = connectivity.len();
        Assembly {
            n_elements,
            scratch: vec![[[Lanes::splat(0.0); 8]; BATCHES]; threads.max(1)],
            chunk_energy: vec![ElementEnergy::default(); n_elements.div_ceil(CHUNK)],
            parallel: (threads > 1).then(|| Parallel::new(connectivity, n_nodes, threads)),
            rows: RowBatches::new(connectivity, |_| false),
        }
    }

    /// The default for a mesh: on [`threads_here`] threads (the command line's `--threads`)
    /// when the kernel is costly (`costly_kernel`: the plastic stress path) and the mesh has at
    /// least [`PARALLEL_MIN_ELEMENTS`], else on one thread.
    pub fn for_mesh(connectivity: &[[u32; 4]], n_nodes: usize, costly_kernel: bool) -> Assembly {
        let threads = if costly_kernel && connectivity.len() >= PARALLEL_MIN_ELEMENTS {
            threads_here()
        } else {
            1
        };
        Assembly::new(connectivity, n_nodes, threads)
    }

    /// Heap bytes of the buffers and of the parallel assembly's node lists.
    pub fn heap_bytes(&self) -> usize {
        let parallel = self.parallel.as_ref().map_or(0, |p| {
            p.rows.heap_bytes()
                + vec_bytes(&p.shared)
                + vec_bytes(&p.slot)
                + vec_bytes(&p.kept)
                + p.shared_nodes.heap_bytes()
        });
        vec_bytes(&self.scratch) + vec_bytes(&self.chunk_energy) + self.rows.heap_bytes() + parallel
    }

    /// Threads the assembly runs on.
    pub fn threads(&self) -> usize {
        self.parallel.as_ref().map_or(1, |p| p.team.size())
    }

    /// What the team's fallback to one thread did: `None` unless it fell back.
    pub fn threads_fallback(&self) -> Option<fallback::Report> {
        self.parallel.as_ref().and_then(|p| p.fallback.report())
    }

    /// Computes every element's forces with `chunk_kernel(elements of the chunk, their
    /// batches of forces, their states, scatter)` (states: `points` per batch of [`LANES`]
    /// elements; the kernel scatters the forces with `scatter.chunk` and returns the chunk's
    /// energies summed as [`Energy::lane_total`] sums them) into `f` (overwritten) and
    /// returns the summed energies.
    pub fn assemble<S: Send>(
        &mut self,
        states: &mut [S],
        points: usize,
        chunk_kernel: impl Fn(Range<usize>, &mut [BatchForces], &mut [S], &Scatter) -> ElementEnergy
            + Sync,
        f: &mut [f64],
    ) -> ElementEnergy {
        let n_elements = self.n_elements;
        let per_chunk = BATCHES * points.max(1);
        // The chunk `c`'s elements, their batches in `forces` and their states.
        let chunk = |c: usize, forces: &mut ChunkForces, states: &mut [S], scatter: &Scatter| {
            let elements = c * CHUNK..((c + 1) * CHUNK).min(n_elements);
            let batches = elements.len().div_ceil(LANES);
            chunk_kernel(elements, &mut forces[..batches], states, scatter)
        };
        f.fill(0.0);
        let out = Disjoint::new(f);
        let energies = Disjoint::new(&mut self.chunk_energy);
        let states = Disjoint::new(states);
        let scratch = Disjoint::new(&mut self.scratch);
        let n_chunks = energies.len;
        // Part `part` of `parts`: its chunks in order, each scattered at once.
        let part_job = |part: usize, parts: usize, scatter: &Scatter| {
            // SAFETY: a part's chunks (energies, states) and its scratch are its own.
            let forces = unsafe { &mut scratch.slice(part..part + 1)[0] };
            for c in part_range(n_chunks, parts, part) {
                let s = (c * per_chunk).min(states.len)..((c + 1) * per_chunk).min(states.len);
                let energy = chunk(c, forces, unsafe { states.slice(s) }, scatter);
                unsafe { energies.slice(c..c + 1)[0] = energy };
            }
        };
        let on_team = self
            .parallel
            .as_mut()
            .is_some_and(|p| p.fallback.team_now());
        match &mut self.parallel {
            Some(parallel) if on_team => {
                let kept = Disjoint::new(&mut parallel.kept);
                let scatter = Scatter {
                    f: &out,
                    rows: &parallel.rows,
                    shared: Some((&parallel.shared, &parallel.slot, &kept)),
                };
                let team = &parallel.team;
                team.run(&|part| part_job(part, team.size(), &scatter));
                let kept = &parallel.kept;
                parallel.shared_nodes.sum_into(f, |slot, i| kept[slot][i]);
            }
            // One thread, or the team fallen back: the whole mesh as one part (the same
            // additions in the same order as the team's parts and their shared nodes).
            _ => part_job(
                0,
                1,
                &Scatter {
                    f: &out,
                    rows: &self.rows,
                    shared: None,
                },
            ),
        }
        let mut total = ElementEnergy::default();
        for &en in &self.chunk_energy {
            total += en;
        }
        total
    }
}

/// The scalar chunk kernel: `kernel(e, states of e's batch)` element by element over
/// `elements` (starting at a multiple of [`LANES`]; `points` states per batch), each force
/// into its lane of `forces`, then scattered (`nodes(e)`: element `e`'s nodes); energies
/// summed as the batched kernels sum them ([`Energy::lane_total`]).
#[inline(always)]
pub fn each_element<S>(
    (elements, forces, states, scatter): (Range<usize>, &mut [BatchForces], &mut [S], &Scatter),
    points: usize,
    nodes: impl Fn(usize) -> [u32; 4],
    kernel: impl Fn(usize, &mut [S]) -> (ElementVector, ElementEnergy),
) -> ElementEnergy {
    let mut energy = Energy::<Lanes>::default();
    for (k, e) in elements.clone().enumerate() {
        let batch = k / LANES;
        let (force, en) = kernel(e, &mut states[batch * points..(batch + 1) * points]);
        for (lanes, x) in forces[batch].iter_mut().zip(force) {
            lanes.0[k % LANES] = x;
        }
        energy.add_to_lane(k % LANES, en);
    }
    scatter.chunk(elements, forces, nodes);
    energy.lane_total()
}

/// Some nodes and, per node, the entries of the element forces that act on it, in element
/// order (compressed rows): the gather form of the scatter `f[node] += fe[local node]` over
/// the elements in order.
struct NodeEntries {
    nodes: Vec<u32>,
    /// Node `nodes[k]`'s entries are `entries[start[k]..start[k + 1]]`.
    start: Vec<u32>,
    /// `4 slot + a`: local node `a` of the element kept at `slot`.
    entries: Vec<u32>,
}

impl NodeEntries {
    /// The nodes `n` with `wanted(n)`, each element `e` at `slot(e)`.
    fn new(
        connectivity: &[[u32; 4]],
        n_nodes: usize,
        wanted: impl Fn(usize) -> bool,
        slot: impl Fn(usize) -> u32,
    ) -> NodeEntries {
        let mut per_node: Vec<Vec<u32>> = vec![Vec::new(); n_nodes];
        for (e, element) in connectivity.iter().enumerate() {
            for (a, &n) in element.iter().enumerate() {
                if wanted(n as usize) {
                    per_node[n as usize].push(4 * slot(e) + a as u32);
                }
            }
        }
        let mut out = NodeEntries {
            nodes: Vec::new(),
            start: vec![0],
            entries: Vec::new(),
        };
        for (n, entries) in per_node.iter().enumerate().filter(|(n, _)| wanted(*n)) {
            out.nodes.push(n as u32);
            out.entries.extend(entries);
            out.start.push(out.entries.len() as u32);
        }
        out
    }

    fn heap_bytes(&self) -> usize {
        vec_bytes(&self.nodes) + vec_bytes(&self.start) + vec_bytes(&self.entries)
    }

    /// Sets each node's force `(x, y)` in `f` to the sum of its entries in element order,
    /// starting from 0 as the scatter does (`entry(slot, i)`: force entry `i` of the element
    /// at `slot`).
    fn sum_into(&self, f: &mut [f64], entry: impl Fn(usize, usize) -> f64) {
        for (k, &n) in self.nodes.iter().enumerate() {
            let (mut fx, mut fy) = (0.0, 0.0);
            for &sa in &self.entries[self.start[k] as usize..self.start[k + 1] as usize] {
                let (slot, a) = (sa as usize / 4, sa as usize % 4);
                fx += entry(slot, 2 * a);
                fy += entry(slot, 2 * a + 1);
            }
            f[2 * n as usize] = fx;
            f[2 * n as usize + 1] = fy;
        }
    }
}

/// A mutable slice handed to the parts of a team job, each taking a range no other part
/// takes (the caller's promise at every [`Disjoint::slice`]).
struct Disjoint<T> {
    ptr: *mut T,
    len: usize,
}

// SAFETY: parts only ever reach disjoint ranges (see `slice`), and `T` may be sent.
unsafe impl<T: Send> Sync for Disjoint<T> {}

impl<T> Disjoint<T> {
    fn new(slice: &mut [T]) -> Disjoint<T> {
        Disjoint {
            ptr: slice.as_mut_ptr(),
            len: slice.len(),
        }
    }

    /// The elements `range` (within `0..len`).
    ///
    /// # Safety
    /// No other live reference (from another call) overlaps `range`, and the slice this was
    /// made from outlives the use.
    #[allow(clippy::mut_from_ref)]
    unsafe fn slice(&self, range: std::ops::Range<usize>) -> &mut [T] {
        assert!(range.start <= range.end && range.end <= self.len);
        std::slice::from_raw_parts_mut(self.ptr.add(range.start), range.end - range.start)
    }
}

#[cfg(test)]
mod tests {
    //! The parallel assembly against the sequential one (the reference: scatter in element
    //! order on one thread): bit-identical nodal forces, energies and states for 1 to 4
    //! threads, on a mesh whose element count is not a multiple of the chunk.
    use super::*;
    use crate::physics::elements::element::scatter_add;

    /// A 13 x 11 structured mesh (143 elements, 168 nodes), counter-clockwise nodes, and one
    /// more node on no element (its force must come out 0 on every path).
    fn grid() -> (Vec<[u32; 4]>, usize) {
        grid_of(13, 11)
    }

    /// An `nx` x `ny` structured mesh and one more node on no element.
    fn grid_of(nx: u32, ny: u32) -> (Vec<[u32; 4]>, usize) {
        let id = |i: u32, j: u32| j * (nx + 1) + i;
        let conn = (0..ny)
            .flat_map(|j| {
                (0..nx).map(move |i| [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)])
            })
            .collect();
        (conn, ((nx + 1) * (ny + 1) + 1) as usize)
    }

    /// A kernel with irregular values and a per-point state it counts up.
    fn kernel(e: usize, states: &mut [u64]) -> (ElementVector, ElementEnergy) {
        for s in states.iter_mut() {
            *s += e as u64 + 1;
        }
        let f = std::array::from_fn(|i| ((e * 8 + i) as f64 * 0.7312).sin() * 1e3 / 3.0);
        let energy = ElementEnergy {
            strain: (e as f64).sqrt() / 7.0,
            plastic_work: (e as f64 * 0.1).cos() / 3.0,
            hourglass: 1.0 / (e as f64 + 3.0),
        };
        (f, energy)
    }

    fn assembled(threads: usize) -> (Vec<u64>, Vec<u64>, [u64; 3]) {
        assembled_on(grid(), threads)
    }

    fn assembled_on(
        (conn, n_nodes): (Vec<[u32; 4]>, usize),
        threads: usize,
    ) -> (Vec<u64>, Vec<u64>, [u64; 3]) {
        let mut assembly = Assembly::new(&conn, n_nodes, threads);
        assert_eq!(assembly.threads(), threads);
        let mut states = vec![0u64; 4 * conn.len().div_ceil(LANES)];
        let mut f = vec![f64::NAN; 2 * n_nodes];
        let mut energy = ElementEnergy::default();
        for _ in 0..3 {
            energy = assembly.assemble(
                &mut states,
                4,
                |elements, forces, states, scatter| {
                    each_element((elements, forces, states, scatter), 4, |e| conn[e], kernel)
                },
                &mut f,
            );
        }
        let bits = [energy.strain, energy.plastic_work, energy.hourglass].map(f64::to_bits);
        (f.iter().map(|x| x.to_bits()).collect(), states, bits)
    }

    #[test]
    fn the_assembly_adds_as_the_element_scatter_in_element_order() {
        // Rows of 8, 16 and 24 (every batch in a row: the row scatter, a row's last node
        // carried to the next batch of the row; one batch per row: the top run's last node
        // is the next bottom run's last) and of 13 (batches across rows: element by
        // element), on 1 to 3 threads (the shared nodes' batches go element by element).
        for (nx, ny) in [(8, 5), (16, 9), (13, 11), (24, 3)] {
            let (conn, n_nodes) = grid_of(nx, ny);
            let mut reference = vec![0.0; 2 * n_nodes];
            for (e, &nodes) in conn.iter().enumerate() {
                scatter_add(nodes, &kernel(e, &mut [0; 4]).0, &mut reference);
            }
            let reference: Vec<u64> = reference.iter().map(|x| x.to_bits()).collect();
            let rows = RowBatches::new(&conn, |_| false);
            let row_batches = (0..conn.len() / LANES)
                .filter(|&b| rows.scatter_runs(b).is_some())
                .count();
            let every = row_batches == conn.len() / LANES;
            assert!(row_batches > 0 && every == (nx % 8 == 0), "{nx} x {ny}");
            for threads in 1..=3 {
                let (f, _, _) = assembled_on((conn.clone(), n_nodes), threads);
                assert_eq!(f, reference, "{nx} x {ny} on {threads} threads");
            }
        }
    }

    #[test]
    fn energies_are_summed_per_lane_then_per_chunk() {
        // The documented order (Energy::lane_total): per chunk, element e into partial sum
        // e mod LANES in element order, the partial sums in lane order, the chunks in order.
        let (conn, _) = grid();
        let energies: Vec<ElementEnergy> =
            (0..conn.len()).map(|e| kernel(e, &mut [0; 4]).1).collect();
        let mut expected = ElementEnergy::default();
        for chunk in energies.chunks(CHUNK) {
            let mut partial = [ElementEnergy::default(); LANES];
            for (k, &en) in chunk.iter().enumerate() {
                partial[k % LANES] += en;
            }
            let mut total = ElementEnergy::default();
            for p in partial {
                total += p;
            }
            expected += total;
        }
        let bits = |en: ElementEnergy| [en.strain, en.plastic_work, en.hourglass].map(f64::to_bits);
        // The data tell the orders apart: one sum in element order has other bits.
        let mut in_element_order = ElementEnergy::default();
        for &en in &energies {
            in_element_order += en;
        }
        assert_ne!(bits(in_element_order), bits(expected));
        for threads in 1..=3 {
            assert_eq!(assembled(threads).2, bits(expected), "{threads} threads");
        }
    }

    #[test]
    fn every_thread_count_gives_the_sequential_bits() {
        let one = assembled(1);
        assert!(one.0.iter().all(|&b| f64::from_bits(b).is_finite()));
        assert_eq!(one.0[one.0.len() - 2..], [0.0f64.to_bits(); 2]);
        for threads in 2..=4 {
            assert_eq!(assembled(threads), one, "{threads} threads");
        }
    }

    /// Every pass's forces (bits) and the states after `passes` passes on `threads` threads
    /// under `policy`, and the fallback's report.
    fn passes_under(
        policy: fallback::Policy,
        threads: usize,
        passes: u32,
    ) -> (Vec<Vec<u64>>, Vec<u64>, Option<fallback::Report>) {
        let (conn, n_nodes) = grid();
        let mut assembly = fallback::with_policy(policy, || Assembly::new(&conn, n_nodes, threads));
        let mut states = vec![0u64; 4 * conn.len().div_ceil(LANES)];
        let mut f = vec![f64::NAN; 2 * n_nodes];
        let forces = (0..passes)
            .map(|_| {
                assembly.assemble(
                    &mut states,
                    4,
                    |elements, forces, states, scatter| {
                        each_element((elements, forces, states, scatter), 4, |e| conn[e], kernel)
                    },
                    &mut f,
                );
                f.iter().map(|x| x.to_bits()).collect()
            })
            .collect();
        (forces, states, assembly.threads_fallback())
    }

    #[test]
    fn a_team_that_falls_back_and_returns_keeps_the_one_thread_bits_at_every_pass() {
        // Policy::Always: block 0 alone (the reference), 1-2 on the team, 3 a probe alone,
        // 4-11 fallen back, 12 a try on the team, 13 alone: every kind of pass, both switches.
        let passes = 14 * fallback::BLOCK;
        let (one, one_states, none) = passes_under(fallback::Policy::Always, 1, passes);
        assert_eq!(none, None, "one thread has no team to fall back from");
        for threads in 2..=3 {
            let (f, states, report) = passes_under(fallback::Policy::Always, threads, passes);
            assert!(f == one && states == one_states, "{threads} threads");
            let report = report.expect("fell back");
            assert_eq!(report.threads, threads);
            assert_eq!(report.steps_on_one_thread, u64::from(9 * fallback::BLOCK));
        }
        // The measured default on this small mesh may decide either way; its bits are the same.
        let (f, states, _) = passes_under(fallback::Policy::Measure, 2, passes);
        assert!(f == one && states == one_states);
    }

    #[test]
    fn the_gather_adds_each_node_in_element_order() {
        // 2 x 2 elements around node 4; its x contributions in element order are 1, 1e-16,
        // 1e-16, -1: summed in that order 0, in another order 2.2e-16.
        let conn = [[0, 1, 4, 3], [1, 2, 5, 4], [3, 4, 7, 6], [4, 5, 8, 7]];
        let local_of_4 = [2, 3, 1, 0];
        let parts = [1.0, 1e-16, 1e-16, -1.0];
        let mut forces = [[0.0; 8]; 4];
        for e in 0..4 {
            forces[e][2 * local_of_4[e]] = parts[e];
        }
        let entries = NodeEntries::new(&conn, 9, |_| true, |e| e as u32);
        let mut f = [f64::NAN; 18];
        entries.sum_into(&mut f, |slot, i| forces[slot][i]);
        assert_eq!(f[8], 0.0);
        assert_ne!(((parts[3] + parts[1]) + parts[2]) + parts[0], 0.0);
        let mut scattered = [0.0; 18];
        for (e, fe) in forces.iter().enumerate() {
            scatter_add(conn[e], fe, &mut scattered);
        }
        assert_eq!(f.map(f64::to_bits), scattered.map(f64::to_bits));
    }
}
