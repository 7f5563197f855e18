//! Heap memory a model holds, in bytes (issue 12's "<= 300 bytes per element"): the
//! capacities of its arrays, counted by each part ([`crate::time_loop::plate_model::PlateModel::heap_bytes`]).

/// Heap bytes of `v`: its capacity times the element size.
pub fn vec_bytes<T>(v: &Vec<T>) -> usize {
    v.capacity() * std::mem::size_of::<T>()
}
