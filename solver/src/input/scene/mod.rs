//! The scene's types, in one place that imports nothing of the rest of [`crate::input`] but
//! its errors' locations and the fields' spans: the scene file as written
//! ([`scene_file`]: [`SceneFile`] and its parts, SI units; [`file_visitors`] reads `end:` and
//! `contact:`), the choices written by name ([`choices`]), and the validated scene the solver
//! runs ([`scene_types`]: [`Scene`] and its parts). Reading and validation
//! ([`crate::input::validate`]), estimates ([`crate::input::estimate`]) and warnings
//! ([`crate::input::plausibility`]) stand above them.

pub mod choices;
pub mod file_visitors;
pub mod scene_file;
pub mod scene_text;
pub mod scene_types;

pub use choices::*;
pub use scene_file::*;
pub use scene_types::*;
