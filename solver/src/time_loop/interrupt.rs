//! A stop request (SIGINT, SIGTERM) the time loop polls: the command line's signal handler
//! sets it, the loop stops at its next poll with [`crate::Error::Interrupted`], and the
//! output code removes the staging folder.

use std::sync::atomic::{AtomicBool, Ordering};

static STOP: AtomicBool = AtomicBool::new(false);

/// Asks running loops to stop (async-signal-safe: one atomic store).
pub fn request_stop() {
    STOP.store(true, Ordering::SeqCst);
}

/// Whether a stop was requested.
pub fn stop_requested() -> bool {
    STOP.load(Ordering::Relaxed)
}

/// Steps between polls of the stop request (a relaxed atomic load: free at this rate).
pub const POLL_EVERY: u64 = 256;
