//! Closed-form reference solutions of the impact solver's problems, one file each with its
//! source and a checked constructor. They are written independently of the solver's code: the
//! verification harness (its builtins) and the benchmarks compare the solver against them.
//! The one dependency on the solver is for the plane-wave problem's scene and history.
//!
//! - [`plane_wave`]: plane-strain P and S wave speeds, and the plane-wave problem that
//!   measures them (harness builtin `plane-wave`, work-precision benchmark `wave-p`).
//! - [`beam`]: static clamped-clamped beam under a central load (Euler-Bernoulli, shear).
//! - [`modal_beam`]: the same beam under a rectangular pulse, by modal superposition.
//! - [`timoshenko_modal`]: natural frequencies of a Timoshenko beam (clamped or pinned ends).
//! - [`hertz_line`]: the paper's line-contact law, eq. (4), in any consistent units.
//! - [`rigid_plastic`]: rigid-plastic bounds of a clamped beam struck by a mass (Jones).

pub mod beam;
pub mod hertz_line;
pub mod modal_beam;
pub mod plane_wave;
pub mod rigid_plastic;
pub mod timoshenko_modal;

/// `Ok(x)` when `x` is finite and > 0, else the message naming `what`.
pub(crate) fn positive(what: &str, x: f64) -> Result<f64, String> {
    if x.is_finite() && x > 0.0 {
        Ok(x)
    } else {
        Err(format!("{what} = {x}: must be a finite number > 0"))
    }
}

/// `Ok(nu)` for a Poisson ratio in (-1, 0.5).
pub(crate) fn poisson(nu: f64) -> Result<f64, String> {
    if nu > -1.0 && nu < 0.5 {
        Ok(nu)
    } else {
        Err(format!("poisson_ratio = {nu}: must be in (-1, 0.5)"))
    }
}
