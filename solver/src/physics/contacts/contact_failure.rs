//! Why eq. (21) had no root, in the user's terms: an instability that shows up first in the
//! contact solve is reported as an instability (with its evidence), and an impact that needs
//! more than the contact law's maximum force names that maximum, the input that exceeds it
//! and the alternative that runs it.

use crate::input::error::shown;
use crate::input::scene::{ContactLawChoice, Impactor, Scene};
use crate::physics::contacts::contact::{BeyondMaximum, LineContactLaw};

/// Energy balance error above which a run that fails in the contact solve is taken to have
/// gone unstable first: stable runs stay below 1e-2 (`impact-bench stability`).
pub const DRIFTED_BALANCE_ERROR: f64 = 0.05;

/// The state of the run when the contact solve failed.
pub struct Failure<'a> {
    pub scene: &'a Scene,
    pub impactor: &'a Impactor,
    pub law: &'a LineContactLaw,
    pub beyond: BeyondMaximum,
    /// Energy balance error of the step, -.
    pub balance_error: f64,
    /// s
    pub dt: f64,
    /// s
    pub dt_critical: f64,
}

impl Failure<'_> {
    /// The message of [`crate::Error::Run`].
    pub fn explain(&self) -> String {
        let b = &self.beyond;
        let ratio = self.dt / self.dt_critical;
        let unstable_evidence = if b.required > self.scene.plate.thickness {
            Some(format!(
                "the step asks for an indentation of {:.3e} m, more than the plate thickness {:.3e} m",
                b.required, self.scene.plate.thickness
            ))
        } else if self.balance_error > DRIFTED_BALANCE_ERROR {
            Some(format!(
                "the energy balance error had already reached {:.3e}",
                self.balance_error
            ))
        } else if ratio > 1.0 {
            Some(format!(
                "dt = {:.6e} s is {ratio:.3} of the stable estimate",
                self.dt
            ))
        } else {
            None
        };
        if let Some(evidence) = unstable_evidence {
            return format!(
                "unstable: {evidence} (dt = {:.6e} s, {ratio:.3} of the stable estimate {:.6e} s); the solution grows without a physical source, so the contact law could not follow. Lower time.dt, or check the impactor's mass ({:.3e} kg) and the mesh",
                self.dt, self.dt_critical, self.impactor.mass
            );
        }
        let i = self.impactor;
        let kinetic = 0.5 * i.mass * i.velocity * i.velocity;
        let stored = self.law.energy(b.max_force);
        let law = match i.contact_law {
            ContactLawChoice::Paper { length_unit } => format!(
                "the paper's contact law, eq. (4) (see reference-data/paper/README.md) with length_unit {} m and nose_radius {} m,",
                shown(length_unit),
                shown(i.nose_radius)
            ),
            ContactLawChoice::Johnson { datum_depth } => format!(
                "the johnson contact law with datum_depth {} m and nose_radius {} m",
                shown(datum_depth),
                shown(i.nose_radius)
            ),
        };
        let alternative = match i.contact_law {
            ContactLawChoice::Paper { .. } => {
                let datum_depth = 0.5 * self.scene.plate.thickness;
                let johnson = Impactor {
                    contact_law: ContactLawChoice::Johnson { datum_depth },
                    ..i.clone()
                };
                let j = LineContactLaw::new(&johnson, &self.scene.material, self.law.width);
                format!(
                    "load.impactor.contact_law: {{johnson: {{datum_depth: {}}}}} (its maximum for this scene is {:.3e} N), a larger length_unit, or a softer impact",
                    shown(datum_depth),
                    j.width * j.max_force_per_width()
                )
            }
            ContactLawChoice::Johnson { .. } => {
                "a larger nose_radius, a softer impact, or a finer mesh under the nose".to_string()
            }
        };
        format!(
            "the impact needs more force than {law} can give (eq. (21) has no root): its maximum is {:.3e} N (at an indentation of {:.3e} m), and this step needs an indentation of {:.3e} m. The input that exceeds it: the impactor's {} kg at {} m/s carries {kinetic:.3e} J, while the law stores at most {stored:.3e} J up to its maximum. Use {alternative}",
            b.max_force, b.available, b.required, shown(i.mass), shown(i.velocity)
        )
    }
}

/// Impactor mass below this fraction of the plate mass under the nose is called light.
pub const LIGHT_IMPACTOR: f64 = 1.0e-3;

/// For an instability message: the cause when the impactor is far lighter than the plate
/// column under its nose (the explicit rigid-impactor coupling is then unstable at the
/// plate's step), empty otherwise.
pub fn light_impactor_cause(scene: &Scene) -> String {
    let Some(i) = scene.impactor() else {
        return String::new();
    };
    let column = scene.material.density
        * scene.plate.thickness
        * crate::input::estimate::measures::smallest_element_length(scene)
        * scene.plate.width;
    if i.mass >= LIGHT_IMPACTOR * column {
        return String::new();
    }
    format!(
        ". Cause: the impactor's mass {:.3e} kg is {:.1e} of the {:.3e} kg plate column under its nose; so light a rigid impactor bounces within one step (the explicit contact coupling is not stable): give load.impactor.mass a physical value",
        i.mass,
        i.mass / column,
        column
    )
}
