//! Builtin computations, a registry by name: unit checks of the solver's public contact,
//! impactor and element API, and the solver against closed-form reference solutions (beam
//! theory, modal superposition, plane waves: `impact_analytical`). Each returns named metrics
//! (and histories) for the checks to read. The code-verification builtins
//! (`crate::run::code_verification`) are found through the same names.

use crate::definition::run_data::RunData;
use crate::run::builtin_params::Params;

mod beam_bending;
mod contact_law;
mod impactor;
mod modal_beam;
mod patch;
mod plane_wave;

type Builtin = fn(&Params) -> Result<RunData, String>;

/// Every builtin of this module by the name a case's `builtin:` gives.
const REGISTRY: [(&str, Builtin); 6] = [
    ("hertz-law", contact_law::hertz_law),
    ("impactor-kinematics", impactor::impactor_kinematics),
    ("patch", patch::patch),
    ("beam-bending", beam_bending::beam_bending),
    ("modal-beam", modal_beam::modal_beam),
    ("plane-wave", plane_wave::plane_wave),
];

/// The names a case may give, the code-verification builtins included.
pub fn names() -> impl Iterator<Item = &'static str> + Clone {
    REGISTRY
        .iter()
        .map(|(n, _)| *n)
        .chain(crate::run::code_verification::NAMES)
}

/// Runs the builtin `name` with its parameters; its metrics and histories name it and them.
pub fn run(name: &str, p: &Params) -> Result<RunData, String> {
    let mut d = match REGISTRY.iter().find(|(n, _)| *n == name) {
        Some((_, builtin)) => builtin(p),
        None => crate::run::code_verification::run(name, p)
            .unwrap_or_else(|| Err(format!("unknown builtin {name:?}"))),
    }?;
    d.info.insert("builtin".into(), name.to_string());
    for (k, v) in p {
        d.info.insert(format!("param {k}"), v.to_string());
    }
    Ok(d)
}
