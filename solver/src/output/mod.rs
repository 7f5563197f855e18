//! Output: the files of a run written through a staging folder ([`files`], [`out_dir`]),
//! around a run in memory ([`crate::run`]).

pub mod files;
pub mod out_dir;

/// `summary.json`, at its path before the run had its folder.
pub use crate::run::summary;
pub use files::*;
