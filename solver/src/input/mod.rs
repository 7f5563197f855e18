//! Input, from the ground up: the errors every stage reports ([`error`]) and where each
//! field was written ([`spans`]); the scene's types ([`scene`]: the file as written and the
//! validated scene, importing nothing else of this folder); the scene read, overridden at its
//! dotted paths ([`overrides`]) and validated ([`validate`], its parser errors named by
//! [`yaml_field`]); the cost of a scene estimated before anything is allocated ([`estimate`]:
//! [`budget`], [`time_step`]); the inputs that look wrong ([`plausibility`]); and the
//! scene's JSON Schema and Markdown reference, generated from its types ([`schema`]).

pub mod error;
pub mod estimate;
pub mod overrides;
pub mod plausibility;
pub mod scene;
pub mod schema;
pub mod spans;
pub mod validate;
pub mod yaml_field;

// The modules' paths before the scene's types, their validation and the estimates had their
// folders, kept for the other crates.
pub use estimate::{budget, time_step};

/// The strain-rate law's types (`material.plasticity.rate`), at their path before the
/// scene's types had their folder.
pub mod rate_law {
    pub use super::scene::{
        johnson_cook_42crmo4, CowperSymondsFile, JohnsonCookFile, PowerCurve, RateFile, RateLaw,
        Thermal, ThermalFile,
    };
}

/// `geometry: plane-strain | axisymmetric`, at its path before the scene's types had their
/// folder.
pub mod geometry {
    pub use super::scene::Geometry;
    pub use super::validate::geometry::{validated, Choices};
}
