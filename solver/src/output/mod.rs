//! Output: the files of a run written through a staging folder ([`files`], [`out_dir`]) and
//! the run's scalars, `summary.json` ([`summary`]).

pub mod files;
pub mod out_dir;
pub mod summary;

pub use files::*;
