//! A team of persistent threads for the time loop's element work: the threads are started once
//! per model and wait between steps by spinning briefly and then parking, so a step hands its
//! work over with a few atomic operations instead of a fork/join through a task queue (rayon's
//! injection and wake-up cost 10-50 us, more than a whole step of the default 80 x 16 mesh).
//!
//! [`Team::run`] calls `job(part)` for every `part` in `0..size` and returns when all parts are
//! done. The parts are claimed in order by whoever comes first, the calling thread included
//! (part 0 is its own): a worker that is off its core when a job starts (on a busy machine,
//! for a scheduler slice of milliseconds) leaves its part to the caller, who then runs it
//! itself instead of waiting, so such a step costs about what one thread would take. What a
//! part computes is the caller's: it must depend only on `part` (never on which thread runs
//! it or when), which is what keeps results bit-identical for every team size and whoever
//! runs which part (see [`crate::kernels::assembly`]).

use std::cell::UnsafeCell;
use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::Arc;
use std::thread::{self, JoinHandle};
use std::time::Duration;

/// A part of a job: `job(part)` (as stored while the leader waits: see `Shared::job`).
type Job = dyn Fn(usize) + Sync + 'static;

/// Spins (each a `spin_loop` hint, ~10-50 ns) a waiting worker makes before it parks: about
/// 0.3-1.5 ms, far longer than the serial part of a step (nodal updates, contact, history:
/// ~10-20 us at 80 x 16), so a running model's workers never sleep, and short enough that an
/// idle team soon stops burning a core.
const SPINS_BEFORE_PARKING: u32 = 1 << 15;

/// How long a parked worker sleeps before it looks again (a missed wake-up costs this).
const PARK_TIMEOUT: Duration = Duration::from_millis(1);

/// The job number in the high 32 bits of [`Shared::state`], the next unclaimed part in the
/// low 32 (team sizes are far below 2^32: [`crate::kernels::thread_count::max_threads`]).
const EPOCH_SHIFT: u32 = 32;
const PART_MASK: u64 = (1 << EPOCH_SHIFT) - 1;

struct Shared {
    /// The current job's number and its next unclaimed part (see [`EPOCH_SHIFT`]), written
    /// by the leader to start a job and advanced by every claim ([`claim`]).
    state: AtomicU64,
    /// Parts of the current job finished.
    finished: AtomicUsize,
    /// The current job: a borrowed closure, valid while the leader waits in [`Team::run`].
    job: UnsafeCell<Option<*const Job>>,
    /// Set once, when the team is dropped.
    quit: AtomicBool,
    /// A part of the current job panicked on a worker.
    panicked: AtomicBool,
}

// SAFETY: `job` is written only by the leader while no part of a job is claimed and
// unfinished (between a job's end, which the leader observes through `finished`, and the next
// job's start, which publishes it with Release ordering through `state`); a worker reads it
// only after a successful claim of a part of that job (Acquire), while the leader still waits
// for the part. The closure it points to is `Sync`.
unsafe impl Sync for Shared {}
unsafe impl Send for Shared {}

/// Claims the next part of job `epoch` of `size` parts: `None` once every part is claimed or
/// the job is over (a newer one started).
fn claim(state: &AtomicU64, epoch: u64, size: usize) -> Option<usize> {
    let mut now = state.load(Ordering::Acquire);
    loop {
        let part = (now & PART_MASK) as usize;
        if now >> EPOCH_SHIFT != epoch || part >= size {
            return None;
        }
        match state.compare_exchange_weak(now, now + 1, Ordering::AcqRel, Ordering::Acquire) {
            Ok(_) => return Some(part),
            Err(seen) => now = seen,
        }
    }
}

/// Persistent threads that run jobs of `size` parts (see the module documentation).
pub struct Team {
    shared: Arc<Shared>,
    workers: Vec<JoinHandle<()>>,
}

impl Team {
    /// A team of `size` (>= 1) parts: the caller plus `size - 1` started threads.
    pub fn new(size: usize) -> Team {
        let shared = Arc::new(Shared {
            state: AtomicU64::new(0),
            finished: AtomicUsize::new(0),
            job: UnsafeCell::new(None),
            quit: AtomicBool::new(false),
            panicked: AtomicBool::new(false),
        });
        let workers = (1..size.max(1))
            .map(|part| {
                let shared = Arc::clone(&shared);
                thread::Builder::new()
                    .name(format!("impact-worker-{part}"))
                    .spawn(move || work(&shared, size))
                    .expect("the operating system starts a worker thread")
            })
            .collect();
        Team { shared, workers }
    }

    /// Parts per job (threads including the caller's).
    pub fn size(&self) -> usize {
        self.workers.len() + 1
    }

    /// Runs `job(part)` for `part` in `0..self.size()` (part 0 here, the others by whoever
    /// claims them first) and returns when every part has finished. A panic in any part is
    /// raised here after all parts are done.
    pub fn run<'a>(&self, job: &'a (dyn Fn(usize) + Sync + 'a)) {
        let size = self.size();
        if size == 1 {
            return job(0);
        }
        // SAFETY: the pointer outlives its use: this function does not return before every
        // part has finished (the wait below), and no worker reads it afterwards without
        // claiming a part of a newer job.
        let erased: *const Job =
            unsafe { std::mem::transmute::<&'a (dyn Fn(usize) + Sync + 'a), &'static Job>(job) };
        unsafe { *self.shared.job.get() = Some(erased) };
        self.shared.finished.store(0, Ordering::Relaxed);
        // The job number wraps after 2^32 jobs (the workers look for a change, not a rise).
        let epoch = ((self.shared.state.load(Ordering::Relaxed) >> EPOCH_SHIFT) + 1) & PART_MASK;
        // Part 0 claimed by the caller as the job starts.
        self.shared
            .state
            .store((epoch << EPOCH_SHIFT) | 1, Ordering::Release);
        for w in &self.workers {
            w.thread().unpark();
        }
        let mut mine = catch_unwind(AssertUnwindSafe(|| job(0)));
        self.shared.finished.fetch_add(1, Ordering::Release);
        while let Some(part) = claim(&self.shared.state, epoch, size) {
            let r = catch_unwind(AssertUnwindSafe(|| job(part)));
            self.shared.finished.fetch_add(1, Ordering::Release);
            if mine.is_ok() {
                mine = r;
            }
        }
        let mut spins = 0u32;
        while self.shared.finished.load(Ordering::Acquire) < size {
            spins = spins.wrapping_add(1);
            if spins % 256 == 0 {
                thread::yield_now();
            } else {
                std::hint::spin_loop();
            }
        }
        if let Err(payload) = mine {
            resume_unwind(payload);
        }
        if self.shared.panicked.swap(false, Ordering::Relaxed) {
            panic!("a worker thread panicked in the element loop");
        }
    }
}

impl Drop for Team {
    fn drop(&mut self) {
        self.shared.quit.store(true, Ordering::Release);
        for w in self.workers.drain(..) {
            w.thread().unpark();
            let _ = w.join();
        }
    }
}

/// A worker's life in a team of `size`: wait for a new job, claim and run its parts while
/// any is left, until the team is dropped.
fn work(shared: &Shared, size: usize) {
    let mut seen = 0u64;
    loop {
        let mut spins = 0u32;
        let epoch = loop {
            if shared.quit.load(Ordering::Acquire) {
                return;
            }
            let epoch = shared.state.load(Ordering::Acquire) >> EPOCH_SHIFT;
            if epoch != seen {
                break epoch;
            }
            if spins < SPINS_BEFORE_PARKING {
                spins += 1;
                // Give the core away now and then: on a machine with more runnable threads
                // than cores, a pure spin would hold the core the leader needs.
                if spins % 256 == 0 {
                    thread::yield_now();
                } else {
                    std::hint::spin_loop();
                }
            } else {
                thread::park_timeout(PARK_TIMEOUT);
            }
        };
        seen = epoch;
        while let Some(part) = claim(&shared.state, epoch, size) {
            // SAFETY: see `Shared`; the part of this job was claimed with Acquire after the
            // leader published the job, and the leader waits for it.
            let job = unsafe { (*shared.job.get()).expect("a job is published with its epoch") };
            let job: &Job = unsafe { &*job };
            if catch_unwind(AssertUnwindSafe(|| job(part))).is_err() {
                shared.panicked.store(true, Ordering::Relaxed);
            }
            shared.finished.fetch_add(1, Ordering::Release);
        }
    }
}

thread_local! {
    /// Threads a model built on this thread may use ([`with_threads`]).
    static THREADS: std::cell::Cell<Option<usize>> = const { std::cell::Cell::new(None) };
}

/// Runs `f` with models built on this thread using up to `threads` (>= 1) threads.
pub fn with_threads<T>(threads: usize, f: impl FnOnce() -> T) -> T {
    /// Puts the earlier setting back when `f` returns or unwinds.
    struct Restore(Option<usize>);
    impl Drop for Restore {
        fn drop(&mut self) {
            THREADS.with(|t| t.set(self.0));
        }
    }
    let _restore = Restore(THREADS.with(|t| t.replace(Some(threads.max(1)))));
    f()
}

/// Threads a model built here may use: the count set by [`with_threads`]; else 1 on a rayon
/// pool's worker thread (the caller already runs things in parallel there, e.g. the
/// verification matrix's runs: a team per run would oversubscribe the cores); else the
/// rayon global pool's size (the command line's `--threads`, by default the cores).
pub fn threads_here() -> usize {
    THREADS.with(|t| t.get()).unwrap_or_else(|| {
        if rayon::current_thread_index().is_some() {
            1
        } else {
            rayon::current_num_threads()
        }
    })
}

/// Splits `0..n` into `parts` contiguous ranges of sizes differing by at most one, the
/// larger ones first: part `p`'s range.
pub fn part_range(n: usize, parts: usize, p: usize) -> std::ops::Range<usize> {
    let (base, extra) = (n / parts, n % parts);
    let start = p * base + p.min(extra);
    start..start + base + usize::from(p < extra)
}

#[cfg(test)]
mod tests {
    //! The team against a plain loop over the parts: every part runs exactly once per job
    //! (whoever claims it), jobs do not overlap, borrowed data is seen, panics reach the
    //! caller; the claims against hand-made job states. Wrong models these fail: a claim
    //! without the job number (a late worker would run a part of the next job with the old
    //! closure: the stale-job assertion), a part handed out twice (the counts).
    use super::*;
    use std::sync::Mutex;

    #[test]
    fn every_part_runs_once_per_job_and_jobs_do_not_overlap() {
        for size in 1..=4 {
            let team = Team::new(size);
            assert_eq!(team.size(), size);
            let counts: Vec<AtomicUsize> = (0..size).map(|_| AtomicUsize::new(0)).collect();
            for job in 0..2000 {
                team.run(&|p| {
                    // Every part of the previous job finished before this one started.
                    assert_eq!(counts[p].load(Ordering::Relaxed), job);
                    counts[p].fetch_add(1, Ordering::Relaxed);
                });
                for c in &counts {
                    assert_eq!(c.load(Ordering::Relaxed), job + 1);
                }
            }
        }
    }

    #[test]
    fn parts_are_claimed_once_in_order_and_only_for_the_current_job() {
        // Job 7 of 3 parts, part 0 the caller's at the start.
        let state = AtomicU64::new((7 << EPOCH_SHIFT) | 1);
        assert_eq!(claim(&state, 6, 3), None, "a stale job claims nothing");
        assert_eq!(claim(&state, 7, 3), Some(1));
        assert_eq!(claim(&state, 7, 3), Some(2));
        assert_eq!(claim(&state, 7, 3), None, "every part claimed");
        assert_eq!(claim(&state, 7, 3), None);
        state.store(8 << EPOCH_SHIFT | 1, Ordering::Relaxed);
        assert_eq!(claim(&state, 7, 3), None, "the job is over");
        assert_eq!(claim(&state, 8, 3), Some(1));
    }

    #[test]
    fn a_job_borrows_and_fills_disjoint_parts_of_a_buffer() {
        let team = Team::new(3);
        let n = 1000;
        let out: Vec<Mutex<Vec<usize>>> = (0..3).map(|_| Mutex::new(Vec::new())).collect();
        let input: Vec<usize> = (0..n).collect();
        team.run(&|p| {
            let mut mine = out[p].lock().unwrap();
            mine.extend(input[part_range(n, 3, p)].iter().map(|x| 2 * x));
        });
        let all: Vec<usize> = out
            .into_iter()
            .flat_map(|m| m.into_inner().unwrap())
            .collect();
        assert_eq!(all, (0..n).map(|x| 2 * x).collect::<Vec<_>>());
    }

    #[test]
    fn a_worker_panic_reaches_the_caller_and_the_team_goes_on() {
        let team = Team::new(2);
        let r = catch_unwind(AssertUnwindSafe(|| {
            team.run(&|p| assert!(p != 1, "part 1 fails"));
        }));
        assert!(r.is_err());
        let ran = AtomicUsize::new(0);
        team.run(&|_| {
            ran.fetch_add(1, Ordering::Relaxed);
        });
        assert_eq!(ran.load(Ordering::Relaxed), 2);
    }

    /// Hand-off cost (`cargo test --release -- --ignored --nocapture handoff`): not a check.
    #[test]
    #[ignore]
    fn handoff() {
        for size in [1, 2] {
            let team = Team::new(size);
            let n = 20000;
            let started = std::time::Instant::now();
            for _ in 0..n {
                team.run(&|p| {
                    std::hint::black_box(p);
                });
            }
            let ns = started.elapsed().as_nanos() as f64 / n as f64;
            println!("team of {size}: {ns:.0} ns per empty job");
        }
    }

    #[test]
    fn with_threads_sets_the_count_for_its_call_only_even_when_it_panics() {
        let outside = threads_here();
        assert_eq!(with_threads(3, threads_here), 3);
        let r = catch_unwind(|| with_threads(5, || panic!("a run fails")));
        assert!(r.is_err());
        assert_eq!(threads_here(), outside);
    }

    #[test]
    fn part_ranges_cover_everything_once_in_order() {
        for n in [0, 1, 5, 64, 1281] {
            for parts in 1..=5 {
                let ranges: Vec<_> = (0..parts).map(|p| part_range(n, parts, p)).collect();
                assert_eq!(ranges[0].start, 0);
                assert_eq!(ranges[parts - 1].end, n);
                for w in ranges.windows(2) {
                    assert_eq!(w[0].end, w[1].start);
                    assert!(w[0].len() >= w[1].len() && w[0].len() <= w[1].len() + 1);
                }
            }
        }
    }
}
