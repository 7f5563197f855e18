//! Whether a step's element loop runs on the team of threads or on the calling thread alone
//! (issue 28: threads that never make a run slower).
//!
//! On a busy machine (the other core taken) a team's worker is often off its core when the
//! leader hands it a part. The leader then runs the part itself ([`crate::kernels::workers`]:
//! parts are claimed by whoever comes first), which bounds that case near the one-thread
//! time; before parts were claimed it waited a scheduler slice for the worker (measured on
//! the paper's plastic scene, 1.27-1.41 s on two threads against 0.48-0.83 s on one). What
//! claiming leaves is a worker preempted in the middle of its part, and the spinning worker
//! taking time from the loaded machine. So the team also measures itself against one thread: the steps go in blocks of [`BLOCK`] element-loop
//! passes (one per time step), each timed from the start of its first pass to the start of
//! the next block's (the whole steps, the leader's serial work included). The run's first
//! block runs alone (the reference); after two team blocks, and then now and then, one block
//! runs alone (a probe) and is compared with the team block before it, per pass. When alone
//! was faster the loop falls back to one thread, and tries the team again after a back-off
//! (a block on the team compared with the alone block before it), because a machine's load
//! comes and goes (another program's compilation ends) and a long run should not lose the
//! team's gain for good. A team block is cut short once it has taken longer than the last
//! alone block took whole: a try under load costs at most that, and a load that starts
//! mid-run is seen within a block (a probe follows at once).
//!
//! Alone, the calling thread assembles the whole mesh as one thread does
//! ([`crate::kernels::assembly`]: the team's parts add the same terms in the same order), so a
//! switch changes who computes, never the arithmetic, and the results stay bit-identical
//! whatever the timings decide (only the speed depends on them).

use std::cell::Cell;
use std::time::Instant;

/// Element-loop passes (steps) per timed block: 128 steps of the paper's 80 x 16 plastic
/// scene take 3-4 ms, several scheduler ticks, so that one block's time averages over the
/// moments a worker is off its core (a shorter block is decided by one preemption).
pub const BLOCK: u32 = 128;

/// Team blocks after the first (alone: the reference) before the first probe.
const FIRST_PROBE_AFTER: u32 = 2;

/// Team blocks between probes after the first: doubling from this while the team keeps
/// winning, up to [`TEAM_INTERVAL_MAX`]. Idle, a probe costs a block at the one-thread speed
/// (1.35x slower on the paper scene): the reference and the probes at blocks 3, 6, 11, 20,
/// 37, 70, 135 of the 173-block run cost ~1.6 % of the team's time.
const TEAM_INTERVAL_FIRST: u32 = 2;
const TEAM_INTERVAL_MAX: u32 = 64;

/// Alone blocks before the team is tried again after a fallback: doubling from this after
/// every try the team loses, up to [`RETRY_INTERVAL_MAX`]. Loaded, a try costs at most one
/// alone block's time (the try is cut short once it has taken that long, see
/// [`Fallback::team_now`]): tries after 8, 16, 32 and 64 blocks and the first team block cost
/// at most ~3 % of the paper run.
const RETRY_INTERVAL_FIRST: u32 = 8;
const RETRY_INTERVAL_MAX: u32 = 128;

/// What decides between the team and one thread.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Policy {
    /// Time the team against one thread and take the faster (the default).
    Measure,
    /// Always the team (benchmarks of the team itself).
    Never,
    /// As if one thread were always faster: falls back at the first probe and tries the team
    /// again on the back-off schedule, losing every try (tests: a run that switches back and
    /// forth must keep the one-thread run's bits).
    Always,
}

impl Policy {
    /// The environment variable the command line and the Python package read
    /// ([`Policy::from_env`]); documented for tests and benchmarks.
    pub const ENV: &'static str = "IMPACT_THREADS_FALLBACK";

    /// [`Policy::ENV`]'s value: unset or `measure`, `never`, `always`; anything else is
    /// refused with a message naming the variable, the value and what is allowed.
    pub fn from_env() -> Result<Policy, String> {
        match std::env::var(Self::ENV) {
            Err(std::env::VarError::NotPresent) => Ok(Policy::Measure),
            Ok(v) if v == "measure" => Ok(Policy::Measure),
            Ok(v) if v == "never" => Ok(Policy::Never),
            Ok(v) if v == "always" => Ok(Policy::Always),
            Ok(v) => Err(Self::refusal(&format!("{v:?}"))),
            Err(std::env::VarError::NotUnicode(v)) => Err(Self::refusal(&format!("{v:?}"))),
        }
    }

    fn refusal(value: &str) -> String {
        format!(
            "{} = {value}: must be measure (the default: fall back to one thread when the team of threads is measured slower), never or always (for tests and benchmarks)",
            Self::ENV
        )
    }
}

thread_local! {
    /// The policy of the teams built on this thread ([`with_policy`]).
    static POLICY: Cell<Policy> = const { Cell::new(Policy::Measure) };
}

/// Runs `f` with the teams built on this thread under `policy` (else [`Policy::Measure`]).
pub fn with_policy<T>(policy: Policy, f: impl FnOnce() -> T) -> T {
    /// Puts the earlier policy back when `f` returns or unwinds.
    struct Restore(Policy);
    impl Drop for Restore {
        fn drop(&mut self) {
            POLICY.with(|p| p.set(self.0));
        }
    }
    let _restore = Restore(POLICY.with(|p| p.replace(policy)));
    f()
}

/// The policy of a team built here.
pub fn policy_here() -> Policy {
    POLICY.with(Cell::get)
}

/// What a run that fell back reports (`summary.json`'s `threads_fallback`).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Report {
    /// The team's threads (the caller's included).
    pub threads: usize,
    /// Steps whose element loop ran on one thread after a fallback (the probes not counted).
    pub steps_on_one_thread: u64,
    /// The last fallback's comparison: a step on the team and a step alone, wall time, s.
    pub team_step_s: f64,
    pub one_thread_step_s: f64,
}

impl Report {
    /// The line the command line prints, for a run of `steps` steps.
    pub fn note(&self, steps: u64) -> String {
        format!(
            "note: the element loop's {} threads were slower than one on this busy machine ({:.1} us against {:.1} us per step): {} of {steps} steps ran on one thread (the same results; summary.json: threads_fallback)",
            self.threads,
            1e6 * self.team_step_s,
            1e6 * self.one_thread_step_s,
            self.steps_on_one_thread,
        )
    }
}

/// Where the schedule is.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Phase {
    /// The run's first block, alone: the reference the team's first blocks are held to.
    Reference,
    /// On the team; a probe after `left` more blocks, the next interval `interval`.
    Team { left: u32, interval: u32 },
    /// A probe block alone; on the team again after it, `interval` blocks to the next probe.
    ProbeAlone { interval: u32 },
    /// Fallen back; the team tried after `left` more blocks, the next interval `interval`.
    Alone { left: u32, interval: u32 },
    /// A try on the team; alone again after it, `interval` blocks to the next try.
    ProbeTeam { interval: u32 },
}

impl Phase {
    fn on_team(self) -> bool {
        matches!(self, Phase::Team { .. } | Phase::ProbeTeam { .. })
    }
}

/// The schedule of one team (see the module documentation).
#[derive(Debug)]
pub struct Fallback {
    policy: Policy,
    threads: usize,
    phase: Phase,
    /// Passes into the current block, and when it started.
    in_block: u32,
    block_started: Option<Instant>,
    /// The last block's wall time per pass on the team and alone, s.
    team_rate: Option<f64>,
    alone_rate: Option<f64>,
    report: Option<Report>,
}

impl Fallback {
    /// The schedule of a team of `threads` under `policy`.
    pub fn new(threads: usize, policy: Policy) -> Fallback {
        Fallback {
            policy,
            threads,
            phase: Phase::Reference,
            in_block: 0,
            block_started: None,
            team_rate: None,
            alone_rate: None,
            report: None,
        }
    }

    /// Called at the start of every element-loop pass: whether this pass runs on the team.
    /// Reads the clock at every pass on the team (~25 ns against a step's ~20 us), once per
    /// block alone; allocates nothing. A team block is cut short as soon as it has taken
    /// longer than the last alone block took for all its passes (under [`Policy::Measure`]):
    /// on a busy machine a team step can take a scheduler slice (1 ms against 60 us alone,
    /// measured), and a whole block of them would cost more than the fallback saves.
    pub fn team_now(&mut self) -> bool {
        if self.policy == Policy::Never {
            return true;
        }
        let on_team = self.phase.on_team();
        let started = *self.block_started.get_or_insert_with(Instant::now);
        if self.in_block == BLOCK || (on_team && self.in_block > 0) {
            let now = Instant::now();
            let elapsed = (now - started).as_secs_f64();
            let budget = self.alone_rate.map(|a| a * f64::from(BLOCK));
            let overran =
                on_team && self.policy == Policy::Measure && budget.is_some_and(|b| elapsed > b);
            if self.in_block == BLOCK || overran {
                self.block_done(elapsed / f64::from(self.in_block), overran);
                self.in_block = 0;
                self.block_started = Some(now);
            }
        }
        self.in_block += 1;
        if let (Phase::Alone { .. }, Some(r)) = (self.phase, &mut self.report) {
            r.steps_on_one_thread += 1;
        }
        self.phase.on_team()
    }

    /// What to report: `None` unless the loop fell back at least once.
    pub fn report(&self) -> Option<Report> {
        self.report
    }

    /// The block that just ended took `rate` s per pass (`overran`: a team block cut short):
    /// the next block's phase.
    fn block_done(&mut self, rate: f64, overran: bool) {
        if self.phase.on_team() {
            self.team_rate = Some(rate);
        } else {
            self.alone_rate = Some(rate);
        }
        let alone_faster = match (self.policy, self.alone_rate, self.team_rate) {
            (Policy::Always, _, _) => true,
            (_, Some(alone), Some(team)) => alone < team,
            _ => false,
        };
        self.phase = match self.phase {
            Phase::Reference => Phase::Team {
                left: FIRST_PROBE_AFTER,
                interval: TEAM_INTERVAL_FIRST,
            },
            // Slower than the last alone block: probe now (the reference may be old).
            Phase::Team { interval, .. } if overran => Phase::ProbeAlone { interval },
            Phase::Team { left, interval } if left > 1 => Phase::Team {
                left: left - 1,
                interval,
            },
            Phase::Team { interval, .. } => Phase::ProbeAlone { interval },
            Phase::ProbeAlone { .. } if alone_faster => self.fall_back(),
            Phase::ProbeAlone { interval } => Phase::Team {
                left: interval,
                interval: (2 * interval).min(TEAM_INTERVAL_MAX),
            },
            Phase::Alone { left, interval } if left > 1 => Phase::Alone {
                left: left - 1,
                interval,
            },
            Phase::Alone { interval, .. } => Phase::ProbeTeam { interval },
            Phase::ProbeTeam { interval } if overran || alone_faster => Phase::Alone {
                left: interval,
                interval: (2 * interval).min(RETRY_INTERVAL_MAX),
            },
            Phase::ProbeTeam { .. } => Phase::Team {
                left: TEAM_INTERVAL_FIRST,
                interval: 2 * TEAM_INTERVAL_FIRST,
            },
        };
    }

    /// Falls back after a probe found one thread faster: records the comparison.
    fn fall_back(&mut self) -> Phase {
        let steps = self.report.map_or(0, |r| r.steps_on_one_thread);
        self.report = Some(Report {
            threads: self.threads,
            steps_on_one_thread: steps,
            team_step_s: self.team_rate.unwrap_or(0.0),
            one_thread_step_s: self.alone_rate.unwrap_or(0.0),
        });
        Phase::Alone {
            left: RETRY_INTERVAL_FIRST,
            interval: 2 * RETRY_INTERVAL_FIRST,
        }
    }
}

#[cfg(test)]
mod tests {
    //! The schedule against hand-made block rates (the clock stands aside: `block_done` is
    //! fed directly, a team block marked overrun as `team_now` would cut it): a team that
    //! wins every probe stays on, a team that loses falls back and is tried again on the
    //! back-off schedule, and returns when it wins again. Wrong models these fail: the team
    //! kept whatever it measures (today's spinning team: the loaded test sees every block on
    //! the team), the comparison the wrong way round (the idle test falls back at block 3),
    //! no retry (the load-goes test stays alone), retries without back-off (the loaded test
    //! sees a try every 9 blocks).
    use super::*;

    /// Runs `blocks` blocks whose rates `rate(on_team, block)` gives; the phases' team flags.
    fn schedule(policy: Policy, blocks: u32, rate: impl Fn(bool, u32) -> f64) -> Vec<bool> {
        let mut f = Fallback::new(2, policy);
        (0..blocks)
            .map(|b| {
                let team = f.phase.on_team();
                let r = rate(team, b);
                let overran = team && policy == Policy::Measure && f.alone_rate < Some(r);
                f.block_done(r, overran);
                team
            })
            .collect()
    }

    fn indices(flags: &[bool], team: bool) -> Vec<usize> {
        (0..flags.len()).filter(|&b| flags[b] == team).collect()
    }

    #[test]
    fn a_team_that_is_faster_is_probed_ever_more_rarely_and_kept() {
        // Idle: the team 1.35x faster (the paper scene's gain).
        let flags = schedule(
            Policy::Measure,
            173,
            |team, _| if team { 1.0 } else { 1.35 },
        );
        assert_eq!(indices(&flags, false), [0, 3, 6, 11, 20, 37, 70, 135]);
    }

    #[test]
    fn a_slower_team_falls_back_at_once_and_is_tried_again_with_back_off() {
        // Loaded: the team 2.5x slower than one thread: every team block is cut short.
        let flags = schedule(Policy::Measure, 173, |team, _| if team { 2.5 } else { 1.0 });
        // Block 1 overruns, 2 probes alone, then tries after 8, 16, 32, 64 blocks.
        assert_eq!(indices(&flags, true), [1, 11, 28, 61, 126]);
    }

    #[test]
    fn the_team_returns_when_the_load_goes() {
        // Loaded for the first 20 blocks, idle after: the try at block 11 loses, the one at
        // block 28 wins and the team stays (probes on the idle schedule after it).
        let flags = schedule(Policy::Measure, 60, |team, b| match (team, b < 20) {
            (true, true) => 2.5,
            (true, false) => 1.0,
            (false, _) => 1.35,
        });
        assert!(flags[11] && flags[28] && flags[29..].iter().filter(|t| !**t).count() <= 3);
        assert_eq!(
            indices(&flags, false)[..10],
            [0, 2, 3, 4, 5, 6, 7, 8, 9, 10]
        );
    }

    #[test]
    fn always_falls_back_and_never_stays_on_the_team() {
        let flags = schedule(Policy::Always, 173, |team, _| if team { 1.0 } else { 9.0 });
        assert_eq!(indices(&flags, true), [1, 2, 12, 29, 62, 127]);
    }

    #[test]
    fn never_runs_every_pass_on_the_team_and_reports_nothing() {
        let mut f = Fallback::new(2, Policy::Never);
        assert!((0..10 * BLOCK).all(|_| f.team_now()));
        assert_eq!(f.report(), None);
    }

    #[test]
    fn the_passes_of_a_fallback_are_counted() {
        let mut f = Fallback::new(2, Policy::Always);
        let passes = 13 * BLOCK;
        let on_team = (0..passes).filter(|_| f.team_now()).count() as u32;
        // Block 0 alone (the reference), 1-2 on the team, 3 a probe alone, 4-11 fallen back,
        // 12 a try on the team.
        assert_eq!(on_team, 3 * BLOCK);
        let r = f.report().unwrap();
        assert_eq!(r.steps_on_one_thread, u64::from(8 * BLOCK));
        assert!(r.team_step_s > 0.0 && r.one_thread_step_s > 0.0, "{r:?}");
    }

    #[test]
    fn a_team_block_slower_than_the_alone_block_is_cut_short() {
        // The clock itself: the alone reference block's passes sleep 1 us (~60 us measured,
        // ~8 ms the block); team passes of 10 ms each overrun it after a pass or two, and the
        // probe alone follows at once (a block never cut would take 128 team passes).
        let mut f = Fallback::new(2, Policy::Measure);
        let pass = |us: u64| std::thread::sleep(std::time::Duration::from_micros(us));
        for _ in 0..BLOCK {
            assert!(!f.team_now());
            pass(1);
        }
        let mut team_passes = 0;
        while f.team_now() {
            team_passes += 1;
            pass(10_000);
        }
        assert!(team_passes < BLOCK / 2, "{team_passes}");
        assert!(matches!(f.phase, Phase::ProbeAlone { .. }), "{:?}", f.phase);
    }

    #[test]
    fn the_variable_takes_three_words_and_refuses_others() {
        assert!(Policy::refusal("\"sometimes\"")
            .starts_with("IMPACT_THREADS_FALLBACK = \"sometimes\": must be measure (the default"));
    }
}
