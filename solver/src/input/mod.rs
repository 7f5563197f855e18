//! Input: the scene read from YAML and validated ([`scene`], its parser errors named by
//! [`yaml_field`]), overrides at the scene's dotted paths ([`overrides`]), the cost of a scene
//! estimated before anything is allocated ([`budget`]), a time step that makes no run
//! ([`time_step`]), and the errors every stage reports
//! ([`error`]).

pub mod budget;
pub mod error;
pub mod geometry;
pub mod overrides;
pub mod plausibility;
pub mod rate_law;
pub mod scene;
pub mod spans;
pub mod time_step;
pub mod yaml_field;
