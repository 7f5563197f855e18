//! The elements: the plane-strain 4-node quadrilaterals ([`element`], eqs. 13-15) on the
//! shape-function derivatives at a point ([`geometry`]) and at the centroid ([`centroid`]);
//! their hoop rows and ring weights in the axisymmetric geometry ([`axisymmetric`]); and the
//! same elements under finite deformation ([`finite_element`], [`finite_ring`]).

pub mod axisymmetric;
pub mod centroid;
pub mod element;
pub mod finite_element;
pub mod finite_ring;
pub mod geometry;
