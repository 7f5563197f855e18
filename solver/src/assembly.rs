//! Assembly of element forces into nodal forces (eq. 13), on one thread or several, with
//! results bit-identical for any thread count: elements are processed in fixed chunks of
//! [`CHUNK`], each chunk's energies summed in element order, the chunk sums added in chunk
//! order, and the nodal forces scattered sequentially in element order. Threads only change
//! who computes a chunk, never the arithmetic.

use rayon::prelude::*;

use crate::element::{scatter_add, ElementEnergy, ElementVector};

/// Elements per task.
pub const CHUNK: usize = 64;

/// Meshes with fewer elements run on one thread. Measured on this 2-core machine (with the
/// other core partly busy): two threads pay off only for the plastic stress path, 1.15x at
/// 5120 and 20480 elements; at 1280 elements the hand-off per step costs more than it saves,
/// and the elastic kernels (a stiffness product, ~25 ns per element) never gained.
pub const PARALLEL_MIN_ELEMENTS: usize = 4096;

/// Buffers of the chunked assembly (allocated once, reused every step).
#[derive(Debug, Clone)]
pub struct Assembly {
    element_forces: Vec<ElementVector>,
    chunk_energy: Vec<ElementEnergy>,
    parallel: bool,
}

impl Assembly {
    /// `parallel`: whether chunks may run on several threads (the rayon pool decides how many).
    pub fn new(n_elements: usize, parallel: bool) -> Assembly {
        Assembly {
            element_forces: vec![[0.0; 8]; n_elements],
            chunk_energy: vec![ElementEnergy::default(); n_elements.div_ceil(CHUNK)],
            parallel,
        }
    }

    /// The default for a mesh: parallel when the kernel is costly (`costly_kernel`: the
    /// plastic stress path), the mesh is large enough and there is more than one thread.
    pub fn for_mesh(n_elements: usize, costly_kernel: bool) -> Assembly {
        Assembly::new(
            n_elements,
            costly_kernel
                && n_elements >= PARALLEL_MIN_ELEMENTS
                && rayon::current_num_threads() > 1,
        )
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
        if self.parallel {
            self.element_forces
                .par_chunks_mut(CHUNK)
                .zip(self.chunk_energy.par_iter_mut())
                .zip(states.par_chunks_mut(CHUNK * points.max(1)))
                .enumerate()
                .for_each(|(c, ((forces, energy), states))| *energy = chunk(c, forces, states));
        } else {
            for (c, ((forces, energy), states)) in self
                .element_forces
                .chunks_mut(CHUNK)
                .zip(self.chunk_energy.iter_mut())
                .zip(states.chunks_mut(CHUNK * points.max(1)))
                .enumerate()
            {
                *energy = chunk(c, forces, states);
            }
        }
        f.fill(0.0);
        for (e, fe) in self.element_forces.iter().enumerate() {
            scatter_add(nodes(e), fe, f);
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
