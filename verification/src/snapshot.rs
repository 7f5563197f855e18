//! Snapshot text of a case (filled in below).
