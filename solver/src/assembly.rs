//! Assembly of element forces into nodal forces (eq. 13), on one thread or several, with
//! results bit-identical for any thread count: elements are processed in fixed chunks of
//! [`CHUNK`], each chunk's energies summed in element order, the chunk sums added in chunk
//! order, and every nodal force summed over its elements in element order (sequentially by
//! scattering, or, with a [`Team`], by gathering per node over contiguous node ranges: the
//! same additions in the same order). Threads only change who computes a chunk or a node,
//! never the arithmetic.

use crate::element::{scatter_add, ElementEnergy, ElementVector};
use crate::heap::vec_bytes;
use crate::workers::{part_range, threads_here, Team};

/// Elements per task.
pub const CHUNK: usize = 64;

/// Meshes with fewer elements run on one thread (see [`Assembly::for_mesh`]). Measured
/// (2026-11-23, this 2-core machine idle, paper plastic scene, batched kernels, wall time of
/// 1 / 2 threads): 20 x 4 (80 elements) 0.042-0.053 / 0.048-0.074 s, no gain; 40 x 8 (320)
/// 0.25-0.37 / 0.19-0.27 s, 1.3x; 80 x 16 (1280) 2.2-3.0 / 1.49-1.60 s, 1.45-1.9x. The
/// elastic stiffness product did not gain at 40 x 8 to 160 x 32 (1.0-1.3x slower: the step is
/// the nodal loops'), so only the plastic stress path runs on several threads.
pub const PARALLEL_MIN_ELEMENTS: usize = 256;

/// Buffers of the chunked assembly (allocated once, reused every step), and the team of
/// threads when it runs on several.
pub struct Assembly {
    element_forces: Vec<ElementVector>,
    chunk_energy: Vec<ElementEnergy>,
    parallel: Option<Parallel>,
}

/// What the assembly on several threads needs besides the buffers.
struct Parallel {
    team: Team,
    incidence: NodeIncidence,
    /// Per part: the nodes all of whose elements are in the part's elements (it sums them
    /// in the same job, one hand-off per assembly).
    own_nodes: Vec<Vec<u32>>,
    /// Nodes with elements in two or more parts (or in none: their sum is 0), summed by the
    /// caller after the job. With `own_nodes` every node is written every step.
    shared_nodes: Vec<u32>,
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
        let mut own_nodes = vec![Vec::new(); threads];
        let mut shared_nodes = Vec::new();
        for (n, part) in part_of.iter().enumerate() {
            match part {
                Some(Some(p)) => own_nodes[*p].push(n as u32),
                Some(None) | None => shared_nodes.push(n as u32),
            }
        }
        Parallel {
            team: Team::new(threads),
            incidence: NodeIncidence::new(connectivity, n_nodes),
            own_nodes,
            shared_nodes,
        }
    }
}

/// The elements of part `part` of `parts`: whole chunks, contiguous.
fn part_elements(
    n_chunks: usize,
    n_elements: usize,
    parts: usize,
    part: usize,
) -> std::ops::Range<usize> {
    let chunks = part_range(n_chunks, parts, part);
    (chunks.start * CHUNK).min(n_elements)..(chunks.end * CHUNK).min(n_elements)
}

impl Assembly {
    /// Buffers for the elements `connectivity` over `n_nodes` nodes; `threads` > 1 starts a
    /// team of that many threads (the caller's included) that assembles in parallel.
    pub fn new(connectivity: &[[u32; 4]], n_nodes: usize, threads: usize) -> Assembly {
        let n_elements = connectivity.len();
        Assembly {
            element_forces: vec![[0.0; 8]; n_elements],
            chunk_energy: vec![ElementEnergy::default(); n_elements.div_ceil(CHUNK)],
            parallel: (threads > 1).then(|| Parallel::new(connectivity, n_nodes, threads)),
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
            let own: usize = p.own_nodes.iter().map(vec_bytes).sum();
            vec_bytes(&p.incidence.start)
                + vec_bytes(&p.incidence.entries)
                + own
                + vec_bytes(&p.shared_nodes)
        });
        vec_bytes(&self.element_forces) + vec_bytes(&self.chunk_energy) + parallel
    }

    /// Threads the assembly runs on.
    pub fn threads(&self) -> usize {
        self.parallel.as_ref().map_or(1, |p| p.team.size())
    }

    /// Computes every element's forces with `chunk_kernel(first element, forces of the chunk,
    /// states of the chunk)` (states: `points` per element; the kernel returns the chunk's
    /// energies summed in element order), scatters them into `f` (overwritten) and returns
    /// the summed energies.
    pub fn assemble<S: Send>(
        &mut self,
        states: &mut [S],
        points: usize,
        nodes: impl Fn(usize) -> [u32; 4] + Sync,
        chunk_kernel: impl Fn(usize, &mut [ElementVector], &mut [S]) -> ElementEnergy + Sync,
        f: &mut [f64],
    ) -> ElementEnergy {
        let chunk = |c: usize, forces: &mut [ElementVector], states: &mut [S]| {
            chunk_kernel(c * CHUNK, forces, states)
        };
        let per_chunk = CHUNK * points.max(1);
        match &self.parallel {
            Some(parallel) => {
                let (team, incidence) = (&parallel.team, &parallel.incidence);
                let n_elements = self.element_forces.len();
                let forces = Disjoint::new(&mut self.element_forces);
                let energies = Disjoint::new(&mut self.chunk_energy);
                let states = Disjoint::new(states);
                let out = Disjoint::new(f);
                let n_chunks = energies.len;
                team.run(&|part| {
                    let elements = part_elements(n_chunks, n_elements, team.size(), part);
                    let chunks = part_range(n_chunks, team.size(), part);
                    // SAFETY: the part's chunks (their forces, energies and states) and its
                    // own nodes' dofs belong to this part only.
                    let (fe, en, st) = unsafe {
                        (
                            forces.slice(elements.clone()),
                            energies.slice(chunks.clone()),
                            states.slice(
                                (chunks.start * per_chunk).min(states.len)
                                    ..(chunks.end * per_chunk).min(states.len),
                            ),
                        )
                    };
                    for (k, c) in chunks.enumerate() {
                        let e = (k * CHUNK)..((k + 1) * CHUNK).min(fe.len());
                        let s = (k * per_chunk).min(st.len())..((k + 1) * per_chunk).min(st.len());
                        en[k] = chunk(c, &mut fe[e], &mut st[s]);
                    }
                    for &n in &parallel.own_nodes[part] {
                        let n = n as usize;
                        let (fx, fy) = incidence.node(n, |e| &fe[e - elements.start]);
                        // SAFETY: an own node belongs to this part only.
                        unsafe { out.slice(2 * n..2 * n + 2) }.copy_from_slice(&[fx, fy]);
                    }
                });
                for &n in &parallel.shared_nodes {
                    let n = n as usize;
                    let (fx, fy) = incidence.node(n, |e| &self.element_forces[e]);
                    f[2 * n] = fx;
                    f[2 * n + 1] = fy;
                }
            }
            None => {
                for (c, ((forces, energy), states)) in self
                    .element_forces
                    .chunks_mut(CHUNK)
                    .zip(self.chunk_energy.iter_mut())
                    .zip(states.chunks_mut(per_chunk))
                    .enumerate()
                {
                    *energy = chunk(c, forces, states);
                }
                f.fill(0.0);
                for (e, fe) in self.element_forces.iter().enumerate() {
                    scatter_add(nodes(e), fe, f);
                }
            }
        }
        let mut total = ElementEnergy::default();
        for &en in &self.chunk_energy {
            total += en;
        }
        total
    }
}

/// The scalar chunk kernel: `kernel(e, states of e)` element by element, energies summed in
/// element order (`first`: the chunk's first element).
#[inline(always)]
pub fn each_element<S>(
    first: usize,
    forces: &mut [ElementVector],
    states: &mut [S],
    points: usize,
    kernel: impl Fn(usize, &mut [S]) -> (ElementVector, ElementEnergy),
) -> ElementEnergy {
    let mut energy = ElementEnergy::default();
    for (k, fe) in forces.iter_mut().enumerate() {
        let (force, en) = kernel(first + k, &mut states[k * points..(k + 1) * points]);
        *fe = force;
        energy += en;
    }
    energy
}

/// Per node, the element force entries that act on it, in element order (compressed rows):
/// the gather form of the scatter `f[node] += fe[local node]` over the elements in order.
struct NodeIncidence {
    /// Node `n`'s entries are `entries[start[n]..start[n + 1]]`.
    start: Vec<u32>,
    /// `4 e + a`: element `e`'s local node `a`.
    entries: Vec<u32>,
}

impl NodeIncidence {
    fn new(connectivity: &[[u32; 4]], n_nodes: usize) -> NodeIncidence {
        let mut count = vec![0u32; n_nodes + 1];
        for nodes in connectivity {
            for &n in nodes {
                count[n as usize + 1] += 1;
            }
        }
        for n in 0..n_nodes {
            count[n + 1] += count[n];
        }
        let start = count.clone();
        let mut next = count;
        let mut entries = vec![0u32; 4 * connectivity.len()];
        for (e, nodes) in connectivity.iter().enumerate() {
            for (a, &n) in nodes.iter().enumerate() {
                entries[next[n as usize] as usize] = (4 * e + a) as u32;
                next[n as usize] += 1;
            }
        }
        NodeIncidence { start, entries }
    }

    /// The force `(x, y)` on node `n`: the sum of its element entries in element order,
    /// starting from 0 as the scatter does (`forces_of(e)`: element `e`'s force vector).
    #[inline(always)]
    fn node<'f>(&self, n: usize, forces_of: impl Fn(usize) -> &'f ElementVector) -> (f64, f64) {
        let (mut fx, mut fy) = (0.0, 0.0);
        for &ea in &self.entries[self.start[n] as usize..self.start[n + 1] as usize] {
            let (e, a) = (ea as usize / 4, ea as usize % 4);
            let fe = forces_of(e);
            fx += fe[2 * a];
            fy += fe[2 * a + 1];
        }
        (fx, fy)
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

    /// A 13 x 11 structured mesh (143 elements, 168 nodes), counter-clockwise nodes, and one
    /// more node on no element (its force must come out 0 on every path).
    fn grid() -> (Vec<[u32; 4]>, usize) {
        let (nx, ny) = (13u32, 11u32);
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
        let (conn, n_nodes) = grid();
        let mut assembly = Assembly::new(&conn, n_nodes, threads);
        assert_eq!(assembly.threads(), threads);
        let mut states = vec![0u64; 4 * conn.len()];
        let mut f = vec![f64::NAN; 2 * n_nodes];
        let mut energy = ElementEnergy::default();
        for _ in 0..3 {
            energy = assembly.assemble(
                &mut states,
                4,
                |e| conn[e],
                |first, forces, states| each_element(first, forces, states, 4, kernel),
                &mut f,
            );
        }
        let bits = [energy.strain, energy.plastic_work, energy.hourglass].map(f64::to_bits);
        (f.iter().map(|x| x.to_bits()).collect(), states, bits)
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
        let incidence = NodeIncidence::new(&conn, 9);
        let mut f = [f64::NAN; 18];
        for n in 0..9 {
            (f[2 * n], f[2 * n + 1]) = incidence.node(n, |e| &forces[e]);
        }
        assert_eq!(f[8], 0.0);
        assert_ne!(((parts[3] + parts[1]) + parts[2]) + parts[0], 0.0);
        let mut scattered = [0.0; 18];
        for (e, fe) in forces.iter().enumerate() {
            scatter_add(conn[e], fe, &mut scattered);
        }
        assert_eq!(f.map(f64::to_bits), scattered.map(f64::to_bits));
    }
}
