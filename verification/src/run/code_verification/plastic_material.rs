//! The elastic-plastic material of the plasticity builtins, read from their parameters.

use crate::run::builtin_params::{param, Params};

/// The elastic-plastic material of the plasticity builtins (steel with linear hardening by
/// default), SI units.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PlasticMaterial {
    /// Pa
    pub youngs_modulus: f64,
    pub poisson_ratio: f64,
    /// kg/m^3
    pub density: f64,
    /// Pa
    pub yield_stress: f64,
    /// Tangent modulus after yield in uniaxial stress, Pa
    pub tangent_modulus: f64,
}

/// The [`PlasticMaterial`] parameters (or their defaults: 200 GPa, 0.3, 7850 kg/m^3,
/// 250 MPa, 20 GPa).
pub(crate) fn plastic_material(p: &Params) -> Result<PlasticMaterial, String> {
    Ok(PlasticMaterial {
        youngs_modulus: param(p, "youngs_modulus", 200e9)?,
        poisson_ratio: param(p, "poisson_ratio", 0.3)?,
        density: param(p, "density", 7850.0)?,
        yield_stress: param(p, "yield_stress", 250e6)?,
        tangent_modulus: param(p, "tangent_modulus", 20e9)?,
    })
}
