//! `geometry: plane-strain | axisymmetric`: the scenes the axisymmetric geometry cannot run
//! (refused with the field, the value and the way out).
//!
//! In the axisymmetric geometry the half model's section is a diametral half-section of a
//! round plate: its clamped end `x = 0` is the rim, its symmetry line `x = length / 2` the
//! axis, so the plate's radius is `length / 2` and a point's radius is `r = length / 2 - x`
//! (`ALGORITHM.md` section 3d). Forces, masses and energies are those of the whole ring (N, kg,
//! J over 2 pi rad), as Abaqus reports them; `plate.width` is not used.

use serde_saphyr::Spanned;

use crate::input::error::{Error, Result, SourceLocation};
use crate::input::scene::{Estimate, Geometry, Load, Model};

/// The scene's parts the geometry must agree with.
pub struct Choices<'a> {
    pub model: Model,
    pub load: &'a Load,
    pub estimate: Estimate,
}

/// The geometry of `written` (absent: plane strain), or the error naming what the
/// axisymmetric geometry cannot run with (`source`: the scene file).
pub fn validated(
    written: Option<&Spanned<Geometry>>,
    source: &std::path::Path,
    choices: Choices,
) -> Result<Geometry> {
    let Some(spanned) = written else {
        return Ok(Geometry::PlaneStrain);
    };
    let geometry = spanned.value;
    if geometry == Geometry::PlaneStrain {
        return Ok(geometry);
    }
    let refuse = |allowed: &str| {
        Err(Error::invalid(
            SourceLocation::of(source, spanned),
            "geometry",
            geometry.name(),
            allowed,
        ))
    };
    if choices.model != Model::Half {
        return refuse("axisymmetric needs mesh.model: half (the half-section from the clamped rim at x = 0 to the axis at x = length / 2)");
    }
    if choices.estimate == Estimate::Global {
        return refuse("axisymmetric runs with time.dt.estimate: element (the global estimate's stiffness products drop rigid translations, and a radial translation of a ring is not rigid)");
    }
    match choices.load {
        Load::Impactor(_) => refuse("axisymmetric needs load.impactor.contact: surface (the nodal coupling's contact law is the plane-strain line law; the surface coupling's nose, revolved, is a sphere)"),
        Load::Traction(_) => refuse("axisymmetric runs an impactor with contact: surface or a pulse on the axis; a traction load is plane-strain only for now"),
        Load::SurfaceImpactor(_) | Load::Pulse(_) | Load::Wall(_) => Ok(geometry),
    }
}
