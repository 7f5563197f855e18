//! The history streamed to disk (`impact simulate --out`, issue 13) against the history held
//! in memory (the library's runs, the reference):
//! - the streamed `history.csv` equals, byte for byte, the in-memory history written with
//!   `write_history` (an impact scene with a probe, and a pulse scene), and no spill file is
//!   left behind;
//! - memory does not grow with the run's length when streamed: measured with a counting
//!   allocator, the peak heap of a run with a row every step grows by less than 1 % of its
//!   rows' bytes from one length to ten times that length, while the in-memory run's peak
//!   grows by at least its rows' bytes (so the measurement can fail);
//! - no allocation in the time loop: the streamed run of ten times the steps makes at most a
//!   handful more allocations (a per-step allocation would add tens of thousands).

use std::alloc::{GlobalAlloc, Layout, System};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

use impact_solver::output::{simulate_scene_to_dir_with, write_history, RunOptions};
use impact_solver::{simulate, Quiet, Scene};

/// Counts the bytes on the heap and their peak since the last [`reset_peak`].
struct Counting;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);
static CALLS: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        CALLS.fetch_add(1, Ordering::SeqCst);
        let live = LIVE.fetch_add(layout.size(), Ordering::SeqCst) + layout.size();
        PEAK.fetch_max(live, Ordering::SeqCst);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        LIVE.fetch_sub(layout.size(), Ordering::SeqCst);
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// The tests of this file one at a time (the allocator counts every thread).
static SERIAL: Mutex<()> = Mutex::new(());

fn reset_peak() -> usize {
    let live = LIVE.load(Ordering::SeqCst);
    PEAK.store(live, Ordering::SeqCst);
    live
}

const ELASTIC: &str = include_str!("../../verification/scenes/example-elastic.yaml");
const PULSE: &str = include_str!("../../verification/scenes/paper-pulse-plastic.yaml");

fn scene(text: &str, nx: usize, ny: usize) -> Scene {
    let mut s = Scene::from_yaml(text, Path::new("stream.yaml")).unwrap();
    s.mesh.nx = nx;
    s.mesh.ny = ny;
    s.output.fields_every = None;
    s
}

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!(
        "impact-history-stream-{}-{name}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&d);
    d
}

fn to_dir(scene: &Scene, out: &Path, keep_history: bool) -> impact_solver::Outcome {
    let options = RunOptions {
        keep_history,
        ..RunOptions::default()
    };
    simulate_scene_to_dir_with(scene, out, &options, &mut |_| {}).unwrap()
}

#[test]
fn the_streamed_history_csv_equals_the_in_memory_one_byte_for_byte() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    for (name, text) in [("impact", ELASTIC), ("pulse", PULSE)] {
        let mut s = scene(text, 20, 4);
        s.output.every = None; // a row every step: thousands of rows
        let d = dir(name);
        let streamed = to_dir(&s, &d.join("streamed"), false);
        let kept = to_dir(&s, &d.join("kept"), true);
        let memory = simulate(&s, &mut Quiet).unwrap();
        assert!(streamed.history.values.is_empty(), "{name}: rows held");
        assert_eq!(streamed.history.columns, memory.history.columns);
        assert!(memory.history.n_rows() > 1000, "{name}");
        assert_eq!(kept.history, memory.history, "{name}");
        write_history(&memory.history, &d.join("memory.csv")).unwrap();
        let reference = std::fs::read(d.join("memory.csv")).unwrap();
        for run in ["streamed", "kept"] {
            let csv = std::fs::read(d.join(run).join("history.csv")).unwrap();
            assert!(csv == reference, "{name}: {run} history.csv differs");
            let names: Vec<_> = std::fs::read_dir(d.join(run))
                .unwrap()
                .map(|e| e.unwrap().file_name())
                .collect();
            assert_eq!(names.len(), 2, "{name}: {run} holds {names:?}");
        }
        assert_eq!(streamed.summary.max_von_mises, memory.summary.max_von_mises);
        assert_eq!(streamed.summary.impulse, memory.summary.impulse);
        let _ = std::fs::remove_dir_all(&d);
    }
}

/// Peak heap growth (bytes) of a run of `end` s, streamed or held, its rows x columns, and the
/// allocations it made.
fn peak_growth(end: f64, keep_history: bool, out: &Path) -> (usize, usize, usize) {
    let calls = CALLS.load(Ordering::SeqCst);
    let mut s = scene(ELASTIC, 10, 2);
    s.output.every = None;
    s.time.end = impact_solver::scene::End::At(end);
    let before = reset_peak();
    let outcome = to_dir(&s, out, keep_history);
    let growth = PEAK.load(Ordering::SeqCst) - before;
    let calls = CALLS.load(Ordering::SeqCst) - calls;
    let text = std::fs::read_to_string(out.join("history.csv")).unwrap();
    let values = (text.lines().count() - 1) * outcome.history.columns.len();
    (growth, values, calls)
}

#[test]
fn a_streamed_history_holds_no_rows_in_memory_however_long_the_run() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let d = dir("memory");
    let (short_streamed, short_values, short_calls) = peak_growth(2.0e-3, false, &d.join("a"));
    let (long_streamed, long_values, long_calls) = peak_growth(2.0e-2, false, &d.join("b"));
    let (short_held, _, _) = peak_growth(2.0e-3, true, &d.join("c"));
    let (long_held, _, _) = peak_growth(2.0e-2, true, &d.join("d"));
    let _ = std::fs::remove_dir_all(&d);
    let added_bytes = 8 * (long_values - short_values);
    eprintln!(
        "peak heap growth: streamed {short_streamed} -> {long_streamed} B, held {short_held} -> {long_held} B, {added_bytes} B more of rows; allocations of the streamed runs {short_calls} -> {long_calls}"
    );
    assert!(added_bytes > 1_000_000, "{added_bytes} bytes: too short");
    // Held in memory, the longer run's peak carries its extra rows (the check can fail).
    assert!(
        long_held >= short_held + added_bytes,
        "held: {short_held} -> {long_held} bytes for {added_bytes} more bytes of rows"
    );
    // Streamed, the peak does not follow the rows (1 %: allocator and buffer noise).
    assert!(
        long_streamed < short_streamed + added_bytes / 100,
        "streamed: {short_streamed} -> {long_streamed} bytes for {added_bytes} more bytes of rows"
    );
    // No allocation in the loop: ten times the steps (tens of thousands more) allocate at most a
    // few times more (a contact interval's entry; 2 measured).
    assert!(
        long_calls <= short_calls + 8,
        "streamed: {short_calls} -> {long_calls} allocations"
    );
}
