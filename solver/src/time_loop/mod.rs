//! The time loop and its recorder: the model factory ([`model`]), the central-difference loop
//! ([`integrator`], eqs. 8-12 with 19-21) and the model's internal forces compiled once
//! ([`internal_forces`]), its stable step ([`stable_step`], eq. 15), the energy balance
//! ([`energy`]), the surface coupling of the rigid nose ([`surface_coupling`]), what it records
//! ([`history`]) and when ([`schedule`]), and how it is watched and stopped ([`progress`],
//! [`interrupt`]).

pub mod energy;
pub mod history;
pub mod integrator;
pub mod internal_forces;
pub mod interrupt;
pub mod model;
pub mod progress;
pub mod schedule;
pub mod stable_step;
pub mod step_size;
pub mod surface_coupling;
