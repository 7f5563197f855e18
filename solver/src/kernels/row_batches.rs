//! The scatter of a batch of [`LANES`] elements that lie side by side in one row of a
//! structured mesh: element `l` of the batch has the nodes `[b + l, b + l + 1, t + l + 1,
//! t + l]` (bottom nodes from `b`, top nodes from `t`), so the batch touches two runs of
//! `LANES + 1` consecutive nodes, and node `b + l` receives, in element order, local node 1
//! of element `l - 1` and then local node 0 of element `l` (the top run: local nodes 2 and
//! 3). Added as two vector sums per run, in that order, these are the additions of the
//! element-by-element scatter `f[n] += f_e[a]` in the same order: the same bits, without a
//! load, an add and a store per node and element, each waiting on the previous element's
//! store to the node they share.

use crate::lanes::heap::vec_bytes;
use crate::lanes::simd::{Lanes, LANES};
use crate::physics::elements::geometry::Vector;

/// Doubles in a run of `LANES + 1` nodes (x and y).
const RUN: usize = 2 * (LANES + 1);

/// Per batch of [`LANES`] elements: the first bottom and top node of its runs when it lies
/// in one row (see the module documentation), and whether the scatter may add it whole.
/// Found once from the connectivity; the kernels' gathers read it as the scatter does (one
/// load per batch). Checking the eight elements' nodes in the gather instead took ~80 scalar
/// instructions per batch: measured (2026-11-25, kprof, 80 x 16, 1 thread, interleaved),
/// q4-sri elastic 5.95-6.9 -> 5.2-5.5 ns per element-step, never-yielding 6.5 -> 5.9-6.1,
/// q4-1pt elastic 6.35-6.7 -> 6.1.
pub struct RowBatches {
    rows: Vec<Row>,
}

/// A batch's runs: first bottom and top node (`u32::MAX` when it is not a row batch), and
/// whether it has an excluded element (see [`RowBatches::new`]).
#[derive(Clone, Copy)]
struct Row {
    first: [u32; 2],
    excluded: bool,
}

const NONE: [u32; 2] = [u32::MAX; 2];

impl RowBatches {
    /// The row batches of `connectivity` (nodes counter-clockwise); those with an element for
    /// which `excluded(e)` holds are not scattered whole ([`RowBatches::scatter_runs`]).
    pub fn new(connectivity: &[[u32; 4]], excluded: impl Fn(usize) -> bool) -> RowBatches {
        let n = connectivity.len();
        let rows = (0..n.div_ceil(LANES))
            .map(|k| {
                let e0 = k * LANES;
                let full = e0 + LANES <= n;
                let first = full.then(|| row_of(|e| connectivity[e], e0)).flatten();
                Row {
                    first: first.unwrap_or(NONE),
                    excluded: first.is_some() && (e0..e0 + LANES).any(&excluded),
                }
            })
            .collect();
        RowBatches { rows }
    }

    /// The first bottom and top node of batch `batch`'s runs, if it lies in one row.
    #[inline(always)]
    pub fn runs(&self, batch: usize) -> Option<[usize; 2]> {
        let [b, t] = self.rows.get(batch)?.first;
        (b != u32::MAX).then_some([b as usize, t as usize])
    }

    /// [`RowBatches::runs`] of a batch the scatter adds whole (no excluded element).
    #[inline(always)]
    pub fn scatter_runs(&self, batch: usize) -> Option<[usize; 2]> {
        self.runs(batch).filter(|_| !self.rows[batch].excluded)
    }

    pub fn heap_bytes(&self) -> usize {
        vec_bytes(&self.rows)
    }
}

/// The first bottom and top node of the [`LANES`] elements from `e0` (`nodes(e)`: element
/// `e`'s nodes) when they lie in one row (see the module documentation), else `None`.
#[inline(always)]
pub fn row_of(nodes: impl Fn(usize) -> [u32; 4], e0: usize) -> Option<[u32; 2]> {
    let [b, _, _, t] = nodes(e0);
    let mut row = b.abs_diff(t) as usize > LANES;
    for l in 0..LANES as u32 {
        row &= nodes(e0 + l as usize) == [b + l, b + l + 1, t + l + 1, t + l];
    }
    row.then_some([b, t])
}

/// Adds a row batch's element `forces` (N; entry `2 a + c`: component `c` of local node
/// `a`, in lanes) to the nodal forces of its bottom `run` (`[0]`) or top run (`[1]`): the
/// `RUN` doubles (x, y per node) from the run's first node. The run's last node is not
/// stored: its sum so far (its force with the batch's last element added) is returned, to
/// be `carried` into the next row batch of the row, whose first node it is, or stored by the
/// caller ([`Pending`]). A vector load of the run just after a store of that one node
/// overlaps the store only in part, so the processor cannot forward it and waits for the
/// store to reach the cache (~15 % of the stiffness product's samples).
#[inline(always)]
pub fn add_run(
    f: &mut [f64],
    forces: &Vector<Lanes>,
    run: usize,
    carried: Option<[f64; 2]>,
) -> [f64; 2] {
    let f: &mut [f64; RUN] = f.try_into().expect("a run is LANES + 1 nodes");
    // Bottom: node l gets local node 1 of element l - 1 ("left"), then local node 0 of
    // element l ("right"); top: local nodes 2 and 3.
    let (left, right) = if run == 0 { (1, 0) } else { (2, 3) };
    // Entry 2 n + c of the run from local node `a` of element n - `shift`, +0 where there
    // is none: a nodal force is never -0 (it starts at +0, and x + y is -0 only for two -0),
    // so adding +0 leaves it unchanged.
    let from = |a: usize, shift: usize| -> [f64; RUN] {
        let mut run = [0.0; RUN];
        for (i, x) in run.iter_mut().enumerate() {
            if let Some(l) = (i / 2).checked_sub(shift).filter(|&l| l < LANES) {
                *x = forces[2 * a + i % 2].0[l];
            }
        }
        run
    };
    let (from_left, from_right) = (from(left, 1), from(right, 0));
    let mut sum = *f;
    if let Some(carried) = carried {
        sum[..2].copy_from_slice(&carried);
    }
    // One pass, left before right on every node.
    for ((x, l), r) in sum.iter_mut().zip(from_left).zip(from_right) {
        *x = *x + l + r;
    }
    f[..RUN - 2].copy_from_slice(&sum[..RUN - 2]);
    [sum[RUN - 2], sum[RUN - 1]]
}

/// The last node of a run (see [`add_run`]) and its force so far, N, not yet stored.
#[derive(Clone, Copy)]
pub struct Pending {
    pub node: usize,
    pub force: [f64; 2],
}

impl Pending {
    /// The force to carry into a run that starts at `first`, when this is its node.
    #[inline(always)]
    pub fn carried_to(pending: Option<Pending>, first: usize) -> Option<[f64; 2]> {
        pending.filter(|p| p.node == first).map(|p| p.force)
    }
}

#[cfg(test)]
mod tests {
    //! Reference: the element-by-element scatter in element order; bit for bit.
    use super::*;
    use crate::physics::elements::element::scatter_add;

    #[test]
    fn a_row_batch_adds_as_the_element_scatter() {
        // One row of 8 elements over nodes 0..=8 (bottom) and 20..=28 (top) of 30.
        let conn: Vec<[u32; 4]> = (0..8).map(|l| [l, l + 1, 21 + l, 20 + l]).collect();
        let rows = RowBatches::new(&conn, |_| false);
        assert_eq!(rows.runs(0), Some([0, 20]));
        let mut forces = [Lanes::splat(0.0); 8];
        for (i, lanes) in forces.iter_mut().enumerate() {
            for l in 0..LANES {
                // Magnitudes far apart, so that the order of the additions shows in the bits.
                lanes.0[l] = ((8 * i + l) as f64 * 0.77).sin() * 10f64.powi((i + l) as i32 % 7);
            }
        }
        let start: Vec<f64> = (0..60).map(|i| (i as f64 * 1.3).cos() * 1e-3).collect();
        let mut reference = start.clone();
        for (l, nodes) in conn.iter().enumerate() {
            let fe = std::array::from_fn(|i| forces[i].0[l]);
            scatter_add(*nodes, &fe, &mut reference);
        }
        let mut f = start;
        let last = add_run(&mut f[0..RUN], &forces, 0, None);
        f[RUN - 2..RUN].copy_from_slice(&last);
        let last = add_run(&mut f[40..40 + RUN], &forces, 1, None);
        f[40 + RUN - 2..40 + RUN].copy_from_slice(&last);
        assert_eq!(f.map_bits(), reference.map_bits());
    }

    #[test]
    fn batches_off_a_row_are_not_row_batches() {
        // A 5-wide mesh: its batches wrap around the row end.
        let conn: Vec<[u32; 4]> = (0..16)
            .map(|e| {
                let (i, j) = (e % 5, e / 5);
                let n = j * 6 + i;
                [n, n + 1, n + 7, n + 6]
            })
            .collect();
        let rows = RowBatches::new(&conn, |_| false);
        assert_eq!((rows.runs(0), rows.runs(1)), (None, None));
        // An excluded element, a partial batch.
        let row: Vec<[u32; 4]> = (0..12).map(|l| [l, l + 1, 31 + l, 30 + l]).collect();
        let rows = RowBatches::new(&row, |e| e == 3);
        assert_eq!((rows.scatter_runs(0), rows.scatter_runs(1)), (None, None));
        assert_eq!(rows.runs(0), Some([0, 30]), "a row still, for the gather");
        let rows = RowBatches::new(&row, |_| false);
        assert_eq!((rows.runs(0), rows.runs(1)), (Some([0, 30]), None));
        assert_eq!((rows.scatter_runs(0), rows.runs(2)), (Some([0, 30]), None));
    }

    trait Bits {
        fn map_bits(&self) -> Vec<u64>;
    }

    impl Bits for Vec<f64> {
        fn map_bits(&self) -> Vec<u64> {
            self.iter().map(|x| x.to_bits()).collect()
        }
    }
}
