//! Reviewing what a run gave against another: `impact diff` of two runs (its input
//! refused where it cannot be compared, its moves listed), `impact verify --baseline` against
//! an earlier matrix, and the snapshot text each case's results are pinned by.

pub mod baseline;
pub mod diff;
pub mod diff_input;
pub mod diff_moves;
pub mod snapshot;
