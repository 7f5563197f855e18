//! Reviewing what a run gave against another: `impact diff` of two runs (its input
//! refused where it cannot be compared, its moves listed), `impact verify --baseline` against
//! an earlier matrix, the snapshot text each case's results are pinned by, and the field's
//! rating of one history against another (ISO/TS 18571).

pub mod baseline;
pub mod diff;
pub mod diff_input;
pub mod diff_moves;
pub mod iso18571;
pub mod snapshot;
