//! The physics: the elements ([`element`], eqs. 13-15, on the shape-function derivatives of
//! [`geometry`] and [`centroid`]), the materials ([`material`], eq. 16, and its rate-dependent
//! form [`rate_plasticity`]), the rigid impactor
//! ([`impactor`], eqs. 19-20), its contact law and the solve of eq. (21) ([`contact`], with the
//! reasons a solve fails in [`contact_failure`]), the rigid nose in surface contact
//! ([`nose_contact`]), the rigid planar wall a body flies onto ([`rigid_wall`]), and
//! prescribed loads ([`load`]). Finite deformation: the kinematics of a
//! point ([`kinematics`]), the elements ([`finite_element`]) and materials ([`finite_material`])
//! that use it. The axisymmetric geometry: the elements' hoop rows and ring weights
//! ([`axisymmetric`]), under finite deformation too ([`finite_ring`]).

pub mod axisymmetric;
pub mod centroid;
pub mod contact;
pub mod contact_failure;
pub mod element;
pub mod finite_element;
pub mod finite_material;
pub mod finite_ring;
pub mod geometry;
pub mod impactor;
pub mod kinematics;
pub mod load;
pub mod material;
pub mod nose_contact;
pub mod rate_plasticity;
pub mod rigid_wall;
