//! When the recorder writes: the output steps of `output.every` (history rows) and
//! `output.fields.every` (field frames), `steps_to(k every, dt)` for k = 1, 2, ...

pub(crate) use crate::input::estimate::time_step::steps_to;
use crate::input::scene::DtUpdate;

/// A schedule of output steps every `every` s (every step when `None`): step 0 and the steps
/// `steps_to(k every, dt)`, k = 1, 2, ..., each once; or, for a run whose step changes
/// ([`Schedule::in_time`]), the first step at or past each `k every` (within 1e-9 of a step).
pub(crate) struct Schedule {
    every: Option<f64>,
    next: u64,
    /// For [`Schedule::in_time`]: the next output time, s.
    next_time: Option<f64>,
}

impl Schedule {
    pub(crate) fn new(every: Option<f64>) -> Schedule {
        Schedule {
            every,
            next: 0,
            next_time: None,
        }
    }

    /// The schedule of `every` for a run whose step is `update`d: on the step count when the
    /// step is fixed ([`Schedule::new`]), on the steps' times when it changes
    /// ([`Schedule::in_time`]).
    pub(crate) fn of(every: Option<f64>, update: DtUpdate) -> Schedule {
        match update {
            DtUpdate::Once => Schedule::new(every),
            DtUpdate::EveryStep => Schedule::in_time(every),
        }
    }

    /// A schedule read on the steps' times, for steps of changing size.
    pub(crate) fn in_time(every: Option<f64>) -> Schedule {
        Schedule {
            next_time: Some(0.0),
            ..Schedule::new(every)
        }
    }

    /// Whether step `n` at `t` (s; `dt` its step, s) is due; advances past it.
    pub(crate) fn due_at(&mut self, n: u64, t: f64, dt: f64) -> bool {
        match (self.every, self.next_time) {
            (Some(every), Some(next)) => {
                if t < next - 1e-9 * dt {
                    return false;
                }
                let after = (((t + 1e-9 * dt) / every).floor() + 1.0) * every;
                // An interval below the time's resolution: every step is due.
                self.next_time = Some(if after.is_finite() && after > t {
                    after
                } else {
                    t
                });
                true
            }
            _ => self.due(n, dt),
        }
    }

    /// Whether step `n` is due; advances past it.
    pub(crate) fn due(&mut self, n: u64, dt: f64) -> bool {
        let Some(every) = self.every else { return true };
        if n < self.next {
            return false;
        }
        self.next = first_output_after(n, every, dt);
        true
    }
}

/// The first output step after step `n`: `output_step(k)` for the smallest k with
/// `output_step(k) > n`, which is what advancing k one interval at a time finds (the k it
/// stopped at last time has `output_step(k) <= n`, and `output_step` never decreases in k:
/// every operation in it is monotonic). Found from the estimate k = floor((n + 1e-9) dt /
/// every) + 1 by doubling steps to a bracket and halving it, a few evaluations whatever the
/// interval. When even the largest k does not pass `n` (an interval below ~1e-19 of the run),
/// every step is due: `n + 1`.
fn first_output_after(n: u64, every: f64, dt: f64) -> u64 {
    let passes = |k: u64| output_step(k, every, dt) > n;
    let guess = (((n as f64 + 1e-9) * dt / every).floor() + 1.0) as u64;
    // lo does not pass (k = 0 never does: step 0), hi does.
    let (mut lo, mut hi) = (0, guess);
    let mut stride = 1_u64;
    if passes(guess) {
        while hi > 0 {
            let k = hi.saturating_sub(stride);
            if !passes(k) {
                lo = k;
                break;
            }
            hi = k;
            stride = stride.saturating_mul(2);
        }
    } else {
        lo = guess;
        loop {
            if lo == u64::MAX {
                return n + 1;
            }
            let k = lo.saturating_add(stride);
            if passes(k) {
                hi = k;
                break;
            }
            lo = k;
            stride = stride.saturating_mul(2);
        }
    }
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if passes(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    output_step(hi, every, dt)
}

/// The `k`-th output step, `steps_to(k every, dt)`.
fn output_step(k: u64, every: f64, dt: f64) -> u64 {
    #[cfg(test)]
    tests::EVALUATIONS.with(|c| c.set(c.get() + 1));
    steps_to(k as f64 * every, dt)
}

#[cfg(test)]
mod tests {
    //! The schedule gives the output steps of the loop that advances `k` one at a time (kept
    //! here as the reference), for the time steps and output intervals of the scenes and for
    //! awkward ones, and finds each next output step in a few evaluations of `steps_to` however
    //! many intervals fit in a step (`output.every: 1e-15` once made a short run take an hour).
    use super::*;
    use std::cell::Cell;

    thread_local! {
        /// Calls of `output_step` on this thread.
        pub(super) static EVALUATIONS: Cell<u64> = const { Cell::new(0) };
    }

    /// The output steps among `0..steps` of the loop that advances `k` one at a time.
    fn reference(every: f64, dt: f64, steps: u64) -> Vec<u64> {
        let (mut next, mut k, mut due) = (0_u64, 0_u64, Vec::new());
        for n in 0..steps {
            if n < next {
                continue;
            }
            while next <= n {
                k += 1;
                next = steps_to(k as f64 * every, dt);
            }
            due.push(n);
        }
        due
    }

    fn scheduled(every: f64, dt: f64, steps: u64) -> Vec<u64> {
        let mut s = Schedule::new(Some(every));
        (0..steps).filter(|&n| s.due(n, dt)).collect()
    }

    #[test]
    fn output_steps_are_those_of_the_one_interval_at_a_time_loop() {
        // dt of the example scenes (cfl 0.8 and others), fixed steps, and intervals that are
        // round multiples of the step, fractions of it, or unrelated to it.
        let dts: [f64; 6] = [
            5.617089176900743e-7,
            4.75e-7,
            1.0e-7,
            2.3e-8,
            1.0e-9,
            3.0e-7,
        ];
        for dt in dts {
            for every in [1.0e-6, 1.0e-4, 2.5e-5, 1.0e-7, 3.0e-7, 7.0e-9, 1.0e-12] {
                for every in [every, dt, 2.0 * dt, 10.0 * dt, 0.1 * dt, 3.0 * dt / 7.0] {
                    // The reference evaluates ~dt / every times a step: fewer steps then.
                    let steps = (2.0e6 / (dt / every).max(100.0)).max(20.0) as u64;
                    assert_eq!(
                        scheduled(every, dt, steps),
                        reference(every, dt, steps),
                        "every {every:e} s, dt {dt:e} s"
                    );
                }
            }
        }
    }

    #[test]
    fn output_steps_match_the_reference_for_random_intervals_and_steps() {
        // A fixed xorshift sequence: log-uniform dt in [1e-9, 1e-6] s and every in
        // [dt / 1000, 1e5 dt], the same draws on every run.
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut uniform = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..400 {
            let dt = 10f64.powf(-9.0 + 3.0 * uniform());
            let every = dt * 10f64.powf(-3.0 + 8.0 * uniform());
            assert_eq!(
                scheduled(every, dt, 3000),
                reference(every, dt, 3000),
                "every {every:e} s, dt {dt:e} s"
            );
        }
    }

    #[test]
    fn in_time_the_first_step_at_or_past_each_interval_is_due() {
        // Steps of 0.3, 0.3, 0.7, 0.2, 1.1, ... s (times 0, 0.3, 0.6, 1.3, 1.5, 2.6, 2.9, 3.0)
        // with rows every 1 s: t = 0, then the first at or past 1, 2 and 3 s.
        let times = [0.0, 0.3, 0.6, 1.3, 1.5, 2.6, 2.9, 3.0];
        let mut s = Schedule::in_time(Some(1.0));
        let due: Vec<f64> = times
            .iter()
            .enumerate()
            .filter(|&(n, &t)| s.due_at(n as u64, t, 0.1))
            .map(|(_, &t)| t)
            .collect();
        assert_eq!(due, [0.0, 1.3, 2.6, 3.0]);
        // Every step without an interval, and under one below the times' resolution.
        for every in [None, Some(1e-300)] {
            let mut s = Schedule::in_time(every);
            assert!(times
                .iter()
                .enumerate()
                .all(|(n, &t)| s.due_at(n as u64, t, 0.1)));
        }
    }

    #[test]
    fn a_tiny_interval_costs_a_few_evaluations_per_step() {
        // 10^6 intervals in each step: the one-at-a-time loop evaluates 10^6 times a step.
        let (every, dt) = (1.0e-15, 1.0e-9);
        let mut s = Schedule::new(Some(every));
        EVALUATIONS.with(|c| c.set(0));
        let due = (0..10).filter(|&n| s.due(n, dt)).count();
        let evaluations = EVALUATIONS.with(Cell::get);
        assert_eq!(due, 10, "every step is due");
        assert!(
            evaluations <= 10 * 140,
            "{evaluations} evaluations for 10 steps"
        );
        // Far into a run, and past what the step counter's intervals can reach.
        for (every, n) in [(1.0e-15, 1_000_000_000_000), (1.0e-300, 5)] {
            let mut s = Schedule::new(Some(every));
            EVALUATIONS.with(|c| c.set(0));
            assert!(s.due(n, dt) && !s.due(n, dt) && s.due(n + 1, dt));
            let evaluations = EVALUATIONS.with(Cell::get);
            assert!(
                evaluations <= 2 * 140,
                "{evaluations} evaluations, every {every:e} s"
            );
        }
    }
}
