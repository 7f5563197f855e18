//! The mesh: the structured quadrilateral mesh of the plate, its boundary conditions, its
//! mid-span nodes and the probe points ([`plate`]).

pub mod plate;

pub use plate::*;
