//! Saying what a run is doing: on a terminal a bar (a spinner while the model is set up, then
//! the simulated time), elsewhere (a file, a pipe, CI logs) a plain line when the loop starts
//! and then every 10 s; nothing when quiet.

use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// How progress is shown.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ProgressMode {
    /// A live bar on stderr (a terminal).
    Bar,
    /// Plain periodic lines on stderr.
    Lines,
    /// Nothing.
    Off,
}

/// Seconds between plain lines at least.
pub const LINE_EVERY: Duration = Duration::from_secs(10);

/// The progress of one run.
pub struct Progress {
    mode: ProgressMode,
    bar: Option<ProgressBar>,
    started: Instant,
    last_line: Option<Instant>,
}

impl Progress {
    /// Starts showing the set-up phase (`what`: e.g. "1280 elements").
    pub fn start(mode: ProgressMode, what: &str) -> Progress {
        let bar = (mode == ProgressMode::Bar).then(|| {
            let bar = ProgressBar::with_draw_target(Some(1000), ProgressDrawTarget::stderr());
            bar.set_style(
                ProgressStyle::with_template("{spinner} setting up {msg} ({elapsed})")
                    .unwrap_or_else(|_| ProgressStyle::default_spinner()),
            );
            bar.set_message(what.to_string());
            bar.enable_steady_tick(Duration::from_millis(120));
            bar
        });
        if mode == ProgressMode::Lines {
            eprintln!("simulate: setting up {what}");
        }
        Progress {
            mode,
            bar,
            started: Instant::now(),
            last_line: None,
        }
    }

    /// The loop has reached `time` of `end` s.
    pub fn at(&mut self, time: f64, end: f64) {
        let permille = if end > 0.0 {
            (1000.0 * time / end).round().clamp(0.0, 1000.0) as u64
        } else {
            1000
        };
        if let Some(bar) = &self.bar {
            if self.last_line.is_none() {
                bar.disable_steady_tick();
                bar.set_style(
                    ProgressStyle::with_template("{bar:40} {percent:>3}% {msg} ({elapsed})")
                        .unwrap_or_else(|_| ProgressStyle::default_bar()),
                );
                self.last_line = Some(Instant::now());
            }
            bar.set_position(permille);
            bar.set_message(format!("t = {:.4} of {:.4} ms", time * 1e3, end * 1e3));
        } else if self.mode == ProgressMode::Lines {
            let due = match self.last_line {
                None => true,
                Some(when) => when.elapsed() >= LINE_EVERY,
            };
            if due {
                eprintln!(
                    "simulate: {:>3}% t = {:.4} of {:.4} ms ({:.1} s)",
                    permille / 10,
                    time * 1e3,
                    end * 1e3,
                    self.started.elapsed().as_secs_f64()
                );
                self.last_line = Some(Instant::now());
            }
        }
    }

    /// Clears the bar (the summary follows).
    pub fn finish(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}
