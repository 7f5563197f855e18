//! Input: the scene read from YAML and validated ([`scene`], its parser errors named by
//! [`yaml_field`]), overrides at the scene's dotted paths ([`overrides`]), the cost of a scene
//! estimated before anything is allocated ([`budget`]), and the errors every stage reports
//! ([`error`]).

pub mod budget;
pub mod error;
pub mod overrides;
pub mod scene;
pub mod yaml_field;
