//! Uncertainty studies (issue 27): a study's declaration, read and validated here; the
//! Python package samples, runs and analyses it (`impact.uq`).

pub mod distribution;
pub mod study;
