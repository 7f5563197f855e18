//! A team of persistent threads for the time loop's element work: the threads are started once
//! per model and wait between steps by spinning briefly and then parking, so a step hands its
//! work over with two atomic operations instead of a fork/join through a task queue (rayon's
//! injection and wake-up cost 10-50 us, more than a whole step of the default 80 x 16 mesh).
//!
//! [`Team::run`] calls `job(part)` for every `part` in `0..size`, part 0 on the calling thread,
//! and returns when all parts are done. What a part computes is the caller's: it must depend
//! only on `part` (never on which thread runs it or when), which is what keeps results
//! bit-identical for every team size (see [`crate::kernels::assembly`]).

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

struct Shared {
    /// Job number, incremented by the leader to start a job.
    epoch: AtomicU64,
    /// Workers that finished the current job.
    finished: AtomicUsize,
    /// The current job: a borrowed closure, valid while the leader waits in [`Team::run`].
    job: UnsafeCell<Option<*const Job>>,
    /// Set once, when the team is dropped.
    quit: AtomicBool,
    /// A part of the current job panicked on a worker.
    panicked: AtomicBool,
}

// SAFETY: `job` is written only by the leader while no worker reads it (between a job's end,
// which the leader observes through `finished`, and the next `epoch` increment, which
// publishes it with Release ordering); workers read it after observing the new epoch with
// Acquire ordering. The closure it points to is `Sync`.
unsafe impl Sync for Shared {}
unsafe impl Send for Shared {}

/// Persistent threads that run jobs of `size` parts (see the module documentation).
pub struct Team {
    shared: Arc<Shared>,
    workers: Vec<JoinHandle<()>>,
}

impl Team {
    /// A team of `size` (>= 1) parts: the caller plus `size - 1` started threads.
    pub fn new(size: usize) -> Team {
        let shared = Arc::new(Shared {
            epoch: AtomicU64::new(0),
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
                    .spawn(move || work(&shared, part))
                    .expect("the operating system starts a worker thread")
            })
            .collect();
        Team { shared, workers }
    }

    /// Parts per job (threads including the caller's).
    pub fn size(&self) -> usize {
        self.workers.len() + 1
    }

    /// Runs `job(part)` for `part` in `0..self.size()` (part 0 here) and returns when every
    /// part has finished. A panic in any part is raised here after all parts are done.
    pub fn run<'a>(&self, job: &'a (dyn Fn(usize) + Sync + 'a)) {
        if self.workers.is_empty() {
            return job(0);
        }
        // SAFETY: the pointer outlives its use: this function does not return before every
        // worker has finished the job (the wait below), and no worker reads it afterwards
        // without a new epoch.
        let erased: *const Job =
            unsafe { std::mem::transmute::<&'a (dyn Fn(usize) + Sync + 'a), &'static Job>(job) };
        unsafe { *self.shared.job.get() = Some(erased) };
        self.shared.finished.store(0, Ordering::Relaxed);
        self.shared.epoch.fetch_add(1, Ordering::Release);
        for w in &self.workers {
            w.thread().unpark();
        }
        let mine = catch_unwind(AssertUnwindSafe(|| job(0)));
        let mut spins = 0u32;
        while self.shared.finished.load(Ordering::Acquire) < self.workers.len() {
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

/// A worker's life: wait for a new epoch, run its part, report, until the team is dropped.
fn work(shared: &Shared, part: usize) {
    let mut seen = 0u64;
    loop {
        let mut spins = 0u32;
        loop {
            if shared.quit.load(Ordering::Acquire) {
                return;
            }
            let epoch = shared.epoch.load(Ordering::Acquire);
            if epoch != seen {
                seen = epoch;
                break;
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
        }
        // SAFETY: see `Shared`; the epoch was observed with Acquire after the leader's write.
        let job = unsafe { (*shared.job.get()).expect("a job is published with its epoch") };
        let job: &Job = unsafe { &*job };
        if catch_unwind(AssertUnwindSafe(|| job(part))).is_err() {
            shared.panicked.store(true, Ordering::Relaxed);
        }
        shared.finished.fetch_add(1, Ordering::Release);
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
    //! The team against a plain loop over the parts: every part runs exactly once per job,
    //! jobs do not overlap, borrowed data is seen, panics reach the caller.
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
