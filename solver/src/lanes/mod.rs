//! The numbers the kernels compute in: `f64` on the scalar reference path and [`simd::Lanes`]
//! on the batched path, written once over [`real::Real`]; the instruction set chosen at run time
//! ([`simd`]); `ln`, `exp` and `pow` written once for both ([`transcendental`]), and the cube
//! root of a ratio near 1 ([`cube_root`]); and the heap the model's arrays hold ([`heap`]).

#[cfg(test)]
mod accuracy;
pub mod cube_root;
pub mod heap;
pub mod real;
pub mod simd;
pub mod transcendental;
