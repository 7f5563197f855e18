//! The materials: linear elasticity and von Mises plasticity ([`material`], eq. 16), its
//! rate-dependent form ([`rate_plasticity`]), and the materials under finite deformation
//! ([`finite_material`]).

pub mod finite_material;
pub mod material;
pub mod rate_plasticity;
