//! The physics: the elements ([`elements`]), the materials ([`materials`]) and the contacts
//! ([`contacts`]), on the kinematics of a point they share ([`kinematics`]: the finite
//! deformation's gradient, rotation and strain), with the rigid impactor ([`impactor`], eqs.
//! 19-20) and the prescribed loads ([`load`]).

pub mod contacts;
pub mod elements;
pub mod impactor;
pub mod kinematics;
pub mod load;
pub mod materials;

// The modules' paths before the physics was grouped into folders, kept for the other crates.
pub use contacts::{contact, contact_failure, nose_contact, rigid_wall};
pub use elements::{axisymmetric, centroid, element, finite_element, finite_ring, geometry};
pub use materials::{finite_material, material, rate_plasticity};
