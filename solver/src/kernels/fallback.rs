//! Whether a step's element loop runs on the team of threads or on the calling thread alone
//! (issue 28: threads that never make a run slower).
//!
//! On a busy machine (the other core taken) a team's worker is often off its core when the
//! leader hands it a part, and the leader then waits a scheduler slice for it: measured on
//! the paper's plastic scene, 1.27-1.41 s on two threads against 0.48-0.83 s on one. So the
//! team measures itself against one thread: the steps go in blocks of [`BLOCK`] element-loop
//! passes (one per time step), each block timed as a whole (one clock reading per block, from
//! the start of its first pass to the start of the next block's: the whole steps, the
//! leader's serial work included). Now and then one block runs alone (a probe) and is
//! compared with the team block before it; when alone was faster the loop falls back to one
//! thread, and tries the team again after a back-off (a probe block on the team compared
//! with the alone block before it), because a machine's load comes and goes (another
//! program's compilation ends) and a long run should not lose the team's gain for good.
//!
//! The parts of a job are the same whoever runs them: alone, the calling thread runs the
//! team's parts one after another ([`crate::kernels::assembly`]), so a switch changes only who
//! computes a part, never the arithmetic, and the results stay bit-identical whatever the
//! timings decide (only the speed depends on them).

use std::cell::Cell;
use std::time::Instant;

/// Element-loop passes (steps) per timed block: 128 steps of the paper's 80 x 16 plastic
/// scene take 3-4 ms, several scheduler ticks, so that one block's time averages over the
/// moments a worker is off its core (a shorter block is decided by one preemption).
pub const BLOCK: u32 = 128;

/// Team blocks before the first probe: the first block starts the workers and warms their
/// caches, and is not compared.
const FIRST_PROBE_AFTER: u32 = 2;

/// Team blocks between probes after the first: doubling from this while the team keeps
/// winning, up to [`TEAM_INTERVAL_MAX`]. Idle, a probe costs a block at the one-thread speed
/// (1.35x slower on the paper scene): probes at blocks 2, 5, 10, 19, 36, 69, 134 of the
/// 173-block run cost ~1.5 % of the team's time.
const TEAM_INTERVAL_FIRST: u32 = 2;
const TEAM_INTERVAL_MAX: u32 = 64;

/// Alone blocks before the team is tried again after a fallback: doubling from this after
/// every try the team loses, up to [`RETRY_INTERVAL_MAX`]. Loaded, a try costs a block at
/// the team's loaded speed (~2-3x slower than alone): tries after 8, 16, 32 and 64 blocks,
/// plus the team's first blocks, cost ~5 % of the paper run; later ones ~1 %.
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
    /// Passes into the current block.
    in_block: u32,
    block_started: Option<Instant>,
    /// The last whole block's time on the team and alone, s.
    last_team_s: Option<f64>,
    last_alone_s: Option<f64>,
    report: Option<Report>,
}

impl Fallback {
    /// The schedule of a team of `threads` under `policy`.
    pub fn new(threads: usize, policy: Policy) -> Fallback {
        Fallback {
            policy,
            threads,
            phase: Phase::Team {
                left: FIRST_PROBE_AFTER,
                interval: TEAM_INTERVAL_FIRST,
            },
            in_block: 0,
            block_started: None,
            last_team_s: None,
            last_alone_s: None,
            report: None,
        }
    }

    /// Called at the start of every element-loop pass: whether this pass runs on the team.
    /// Reads the clock once per [`BLOCK`] passes; allocates nothing.
    pub fn team_now(&mut self) -> bool {
        if self.policy == Policy::Never {
            return true;
        }
        if self.in_block == 0 {
            let now = Instant::now();
            if let Some(started) = self.block_started {
                self.block_done((now - started).as_secs_f64());
            }
            self.block_started = Some(now);
        }
        self.in_block = (self.in_block + 1) % BLOCK;
        if let (Phase::Alone { .. }, Some(r)) = (self.phase, &mut self.report) {
            r.steps_on_one_thread += 1;
        }
        self.phase.on_team()
    }

    /// What to report: `None` unless the loop fell back at least once.
    pub fn report(&self) -> Option<Report> {
        self.report
    }

    /// The block that just ended took `seconds`: the next block's phase.
    fn block_done(&mut self, seconds: f64) {
        if self.phase.on_team() {
            self.last_team_s = Some(seconds);
        } else {
            self.last_alone_s = Some(seconds);
        }
        let alone_faster = match (self.policy, self.last_alone_s, self.last_team_s) {
            (Policy::Always, _, _) => true,
            (_, Some(alone), Some(team)) => alone < team,
            _ => false,
        };
        self.phase = match self.phase {
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
            Phase::ProbeTeam { interval } if alone_faster => Phase::Alone {
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
        let per_step = |s: Option<f64>| s.unwrap_or(f64::NAN) / f64::from(BLOCK);
        let steps = self.report.map_or(0, |r| r.steps_on_one_thread);
        self.report = Some(Report {
            threads: self.threads,
            steps_on_one_thread: steps,
            team_step_s: per_step(self.last_team_s),
            one_thread_step_s: per_step(self.last_alone_s),
        });
        Phase::Alone {
            left: RETRY_INTERVAL_FIRST,
            interval: 2 * RETRY_INTERVAL_FIRST,
        }
    }
}

#[cfg(test)]
mod tests {
    //! The schedule against hand-made block times (the clock stands aside: `block_done` is
    //! fed directly): a team that wins every probe stays on, a team that loses falls back
    //! and is tried again on the back-off schedule, and returns when it wins again. Wrong
    //! models these fail: the team kept whatever it measures (today's spinning team: the
    //! loaded test sees every block on the team), the comparison the wrong way round (the
    //! idle test falls back at block 2), no retry (the load-goes test stays alone), retries
    //! without back-off (the loaded test sees a try every 9 blocks).
    use super::*;

    /// Runs `blocks` blocks whose times `time(on_team, block)` gives; the phases' team flags.
    fn schedule(policy: Policy, blocks: u32, time: impl Fn(bool, u32) -> f64) -> Vec<bool> {
        let mut f = Fallback::new(2, policy);
        (0..blocks)
            .map(|b| {
                let team = f.phase.on_team();
                f.block_done(time(team, b));
                team
            })
            .collect()
    }

    /// The blocks (indices) that ran alone.
    fn alone(flags: &[bool]) -> Vec<usize> {
        (0..flags.len()).filter(|&b| !flags[b]).collect()
    }

    #[test]
    fn a_team_that_is_faster_is_probed_ever_more_rarely_and_kept() {
        // Idle: the team 1.35x faster (the paper scene's gain).
        let flags = schedule(
            Policy::Measure,
            173,
            |team, _| if team { 1.0 } else { 1.35 },
        );
        assert_eq!(alone(&flags), [2, 5, 10, 19, 36, 69, 134]);
    }

    #[test]
    fn a_slower_team_falls_back_and_is_tried_again_with_back_off() {
        // Loaded: the team 2.5x slower than one thread.
        let mut f = Fallback::new(2, Policy::Measure);
        let mut flags = Vec::new();
        for _ in 0..173 {
            let team = f.phase.on_team();
            flags.push(team);
            f.block_done(if team { 2.5 } else { 1.0 });
        }
        let on_team: Vec<usize> = (0..flags.len()).filter(|&b| flags[b]).collect();
        // Blocks 0-1 on the team, the probe 2 alone, then tries after 8, 16, 32, 64 blocks.
        assert_eq!(on_team, [0, 1, 11, 28, 61, 126]);
        let r = f.report().expect("fell back");
        assert_eq!(
            (r.threads, r.team_step_s, r.one_thread_step_s),
            (2, 2.5 / 128.0, 1.0 / 128.0)
        );
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
        let alone_blocks = alone(&flags);
        assert!(flags[11] && flags[28] && flags[29..].iter().filter(|t| !**t).count() <= 3);
        assert_eq!(alone_blocks[..9], [2, 3, 4, 5, 6, 7, 8, 9, 10]);
    }

    #[test]
    fn always_falls_back_and_never_stays_on_the_team() {
        let flags = schedule(Policy::Always, 173, |team, _| if team { 1.0 } else { 9.0 });
        let on_team: Vec<usize> = (0..flags.len()).filter(|&b| flags[b]).collect();
        assert_eq!(on_team, [0, 1, 11, 28, 61, 126]);
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
        let passes = 12 * BLOCK;
        let on_team = (0..passes).filter(|_| f.team_now()).count() as u32;
        // Blocks 0, 1 and 11 on the team, block 2 a probe alone, 3-10 fallen back.
        assert_eq!(on_team, 3 * BLOCK);
        assert_eq!(
            f.report().unwrap().steps_on_one_thread,
            u64::from(8 * BLOCK)
        );
    }

    #[test]
    fn the_variable_takes_three_words_and_refuses_others() {
        assert!(Policy::refusal("\"sometimes\"")
            .starts_with("IMPACT_THREADS_FALLBACK = \"sometimes\": must be measure (the default"));
    }
}
