//! Uncertainty studies (issue 27): a study's declaration, read and validated here; the
//! Python package samples, runs and analyses it (`impact.uq`).

pub mod based_on;
pub mod declaration;
pub mod distribution;
pub mod outputs;
pub mod sampling;
pub mod scenes;
pub mod study;
