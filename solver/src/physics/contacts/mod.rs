//! The contacts: the rigid line nose's contact law at one node and the solve of eq. (21)
//! ([`contact`], with the reasons a solve fails in [`contact_failure`]), the rigid nose in
//! surface contact with the plate's top surface ([`nose_contact`]), and the rigid planar wall
//! a body flies onto ([`rigid_wall`]); the kinetic energy the kinematic contacts take out
//! ([`impulse_ledger`]).

pub mod contact;
pub mod contact_failure;
pub mod impulse_ledger;
pub mod nose_contact;
pub mod rigid_wall;
