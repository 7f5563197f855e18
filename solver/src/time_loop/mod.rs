//! The time loop and its recorder: the model factory ([`model`]) of the plate model
//! ([`plate_model`]) with its internal forces compiled once ([`internal_forces`]); the
//! central-difference loop ([`integrator`], eqs. 8-12 with 19-21) and its steps (`stepper.rs`,
//! the nodal updates in `nodal_update.rs`), its stable step ([`stable_step`], eq. 15, and
//! [`step_size`]), the energy balance ([`energy`]), the surface coupling of the rigid nose
//! ([`surface_coupling`]), what it records ([`history`]) and when ([`schedule`]), and how it
//! is watched and stopped ([`observer`], [`progress`], [`interrupt`]).

pub mod any_model;
pub mod energy;
pub mod history;
pub mod integrator;
pub mod internal_forces;
pub mod interrupt;
pub mod model;
mod nodal_update;
pub mod observer;
pub mod plate_model;
pub mod progress;
pub mod schedule;
pub mod stable_step;
pub mod step_size;
mod stepper;
pub mod surface_coupling;
