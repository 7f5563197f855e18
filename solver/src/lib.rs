//! Explicit-dynamics solver for a clamped plate hit by a rigid line-nose impactor, after
//! Dokko & Kim (2004): 2-D plane strain, 4-node quads with lumped mass, central differences,
//! Hertz line contact solved each step, von Mises plasticity, energy bookkeeping.
//!
//! Read `ALGORITHM.md` (next to this crate's `Cargo.toml`) for the exact contract. The folders
//! follow the pipeline: [`input`] (the scene, validated; its cost estimated), [`mesh`],
//! [`lanes`] (the number types of the kernels, scalar and batched), [`physics`] (elements,
//! materials, impactor, contact, loads), [`kernels`] (the batched element kernels and their
//! assembly on threads), [`time_loop`] (the model factory, the
//! central-difference loop, its stable step, energies and recorder), [`run`] (a run in memory,
//! [`simulate`], and its `summary.json`), [`output`] (the files of a run).

pub mod input;
pub mod kernels;
pub mod lanes;
pub mod mesh;
pub mod output;
pub mod physics;
pub mod run;
pub mod time_loop;

// The modules' paths before the solver was grouped into folders, kept for the other crates.
pub use input::{budget, error, overrides, scene, yaml_field};
pub use kernels::{assembly, batch, elastic_screen, row_batches, stiffness, workers};
pub use lanes::{heap, real, simd};
pub use output::out_dir;
pub use physics::{
    axisymmetric, centroid, contact, contact_failure, element, finite_element, finite_material,
    geometry, impactor, kinematics, load, material, rate_plasticity,
};
pub use run::summary;
pub use time_loop::{
    any_model, energy, history, integrator, internal_forces, interrupt, model, progress,
    stable_step,
};

pub use input::error::{Error, Result};
pub use input::scene::Scene;
pub use run::summary::{Summary, WallSummary};
pub use run::{simulate, simulate_into, simulate_on, simulate_within, Outcome};
pub use time_loop::history::{History, HistorySink};
pub use time_loop::observer::{Observer, Quiet};
