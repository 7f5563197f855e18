//! The validated scene the solver runs ([`Scene`] and its parts), in SI units; read and
//! validated by [`crate::input::validate`] from the file's types ([`super::scene_file`]).

use std::fmt;
use std::path::PathBuf;

use crate::input::error::SourceLocation;
use crate::input::spans::FieldSpans;

use super::choices::{
    DtUpdate, ElementKind, Ends, Enforcement, Estimate, Geometry, Kinematics, MidSpanNode, Model,
};

#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// The file it came from (for messages).
    pub source: PathBuf,
    pub title: Option<String>,
    pub plate: Plate,
    pub material: Material,
    pub mesh: MeshSettings,
    pub load: Load,
    pub time: TimeSettings,
    pub output: OutputSettings,
    /// Where each field was written (for messages about values after validation).
    pub fields: FieldSpans,
    /// Inputs accepted that look wrong (units, options that do nothing here), in the order
    /// [`crate::input::plausibility::warnings`] finds them.
    pub warnings: Vec<Warning>,
    pub kinematics: Kinematics,
    pub geometry: Geometry,
}

/// Plate dimensions (m) and end supports.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plate {
    pub length: f64,
    pub width: f64,
    pub thickness: f64,
    pub ends: Ends,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    /// kg/m^3
    pub density: f64,
    /// Pa
    pub youngs_modulus: f64,
    pub poisson_ratio: f64,
    pub plasticity: Option<Plasticity>,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Plasticity {
    /// Initial (static) yield stress, Pa.
    pub yield_stress: f64,
    pub hardening: Hardening,
    /// The strain-rate law; `None`: rate-independent.
    pub rate: Option<RateLaw>,
}

#[derive(Debug, Clone, PartialEq)]
pub enum Hardening {
    /// Uniaxial tangent modulus after yield, Pa.
    Linear { tangent_modulus: f64 },
    /// (equivalent plastic strain, flow stress Pa), starting at (0, yield stress).
    Table(Vec<(f64, f64)>),
    /// `yield_stress + coefficient k^exponent` (Johnson-Cook's `A + B k^n`), Pa.
    Power { coefficient: f64, exponent: f64 },
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshSettings {
    pub nx: usize,
    pub ny: usize,
    pub element: ElementKind,
    pub model: Model,
    pub grading: f64,
    pub hourglass: f64,
    /// Interior-node shift as a fraction of the local element size, in [0, 0.4].
    pub distortion: f64,
}

#[derive(Debug, Clone, PartialEq)]
pub enum Load {
    /// The paper's coupling: the contact law at one node (eq. 21).
    Impactor(Impactor),
    /// The rigid nose in surface contact (`load.impactor.contact: surface`).
    SurfaceImpactor(SurfaceImpactor),
    Pulse(Pulse),
    Traction(Traction),
    /// The body flying onto the rigid wall y = 0.
    Wall(Wall),
}

/// The rigid planar wall y = 0 (`load: {wall}`): the body's initial velocity toward it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wall {
    /// m/s toward the wall (the body moves along -y)
    pub velocity: f64,
    /// The impact face's nodes never leave the wall (`load.wall.hold_face`).
    pub hold_face: bool,
    /// Coulomb's coefficient between the wall and the body (-), 0 frictionless.
    pub friction: f64,
}

/// The rigid nose in frictionless penalty contact with the plate's top surface (`contact:
/// surface`, `ALGORITHM.md` section 5b).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceContact {
    pub enforcement: Enforcement,
    /// Penalty stiffness of a node over its mass times its elements' largest eigenvalue (-);
    /// used by the penalty enforcement only.
    pub penalty_scale: f64,
}

impl SurfaceContact {
    pub const DEFAULT_PENALTY_SCALE: f64 = 0.1;
}

/// The impactor of the surface coupling: a rigid cylinder of radius `nose_radius` that moves
/// along y only, its force the sum of the penalty forces on the top-surface nodes.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceImpactor {
    /// kg, whole impactor
    pub mass: f64,
    /// m/s toward the plate
    pub velocity: f64,
    /// m
    pub nose_radius: f64,
    pub contact: SurfaceContact,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Impactor {
    /// kg, whole impactor
    pub mass: f64,
    /// m/s toward the plate
    pub velocity: f64,
    /// m
    pub nose_radius: f64,
    /// Pa
    pub youngs_modulus: f64,
    pub poisson_ratio: f64,
    pub contact_law: ContactLawChoice,
    pub indentation_datum: MidSpanNode,
    pub force_node: MidSpanNode,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ContactLawChoice {
    /// Hidden length of eq. (4), m.
    Paper { length_unit: f64 },
    /// Depth of the plate datum below the surface, m.
    Johnson { datum_depth: f64 },
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pulse {
    /// N, whole width
    pub force: f64,
    /// s
    pub duration: f64,
}

/// Uniform traction on the top surface, Pa, for `duration` s.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Traction {
    pub normal: f64,
    pub shear: f64,
    pub duration: f64,
}

#[derive(Debug, Clone, PartialEq)]
pub struct TimeSettings {
    pub end: End,
    pub dt: DtChoice,
    /// How the stable step is estimated (`time.dt.estimate`).
    pub dt_estimate: Estimate,
    /// When the stable step is estimated (`time.dt.update`).
    pub dt_update: DtUpdate,
    /// Where `time.dt` is written, for the stable-step error.
    pub dt_location: SourceLocation,
    pub allow_unstable_dt: bool,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum End {
    /// s
    At(f64),
    /// Stop `after` s after the contact force was last non-zero; never run past `limit` s.
    AfterContact { after: f64, limit: f64 },
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DtChoice {
    Cfl(f64),
    Fixed(f64),
}

#[derive(Debug, Clone, PartialEq)]
pub struct OutputSettings {
    /// s between history rows; `None` = every step.
    pub every: Option<f64>,
    /// Named points (x from the clamped end, y from the bottom), m, sorted by name.
    pub probes: Vec<(String, [f64; 2])>,
    /// s between VTK field files; `None` = no field output.
    pub fields_every: Option<f64>,
}

/// Default hard stop of `end: {after_contact}`, s.
pub const DEFAULT_TIME_LIMIT: f64 = 0.05;
/// Default Flanagan-Belytschko hourglass coefficient.
pub const DEFAULT_HOURGLASS: f64 = 0.05;

impl Scene {
    pub fn is_plastic(&self) -> bool {
        self.material.plasticity.is_some()
    }

    /// The plasticity's strain-rate law, if any.
    pub fn rate_law(&self) -> Option<&RateLaw> {
        self.material.plasticity.as_ref()?.rate.as_ref()
    }

    pub fn impactor(&self) -> Option<&Impactor> {
        match &self.load {
            Load::Impactor(i) => Some(i),
            Load::SurfaceImpactor(_) | Load::Pulse(_) | Load::Traction(_) | Load::Wall(_) => None,
        }
    }

    /// The rigid wall, if the scene flies onto one.
    pub fn wall(&self) -> Option<&Wall> {
        match &self.load {
            Load::Wall(w) => Some(w),
            _ => None,
        }
    }

    /// The surface coupling's impactor, if the scene has one.
    pub fn surface_impactor(&self) -> Option<&SurfaceImpactor> {
        match &self.load {
            Load::SurfaceImpactor(i) => Some(i),
            _ => None,
        }
    }

    /// The impactor's mass (kg) and initial velocity (m/s) under either coupling.
    pub fn impactor_motion(&self) -> Option<(f64, f64)> {
        match &self.load {
            Load::Impactor(i) => Some((i.mass, i.velocity)),
            Load::SurfaceImpactor(i) => Some((i.mass, i.velocity)),
            Load::Pulse(_) | Load::Traction(_) | Load::Wall(_) => None,
        }
    }
}

/// The validated rate law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RateLaw {
    /// Cowper-Symonds: the static flow stress times `1 + (rate / d)^(1/q)`.
    CowperSymonds {
        /// 1/s
        d: f64,
        /// Exponent (-).
        q: f64,
    },
    /// Johnson-Cook's rate and temperature factors (its `A + B k^n` is the static curve,
    /// [`crate::input::scene::Hardening::Power`]).
    JohnsonCook {
        /// Rate coefficient C (-).
        c: f64,
        /// 1/s; below it the rate factor is 1 (no softening by slow flow).
        reference_rate: f64,
        thermal: Option<Thermal>,
    },
}

/// Adiabatic heating and Johnson-Cook's thermal softening.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Thermal {
    /// T0, the material's temperature before the impact, K.
    pub initial_temperature: f64,
    /// Tr, Johnson-Cook's reference temperature of `T*` (the temperature of the tests the
    /// constants were fitted to), K; `initial_temperature` unless the scene gives it.
    pub reference_temperature: f64,
    /// Tm, K.
    pub melting_temperature: f64,
    /// c, J/(kg K).
    pub specific_heat: f64,
    /// beta, the fraction of the plastic work that heats (-).
    pub taylor_quinney: f64,
    /// Johnson-Cook's m (-).
    pub softening_exponent: f64,
}

impl RateLaw {
    /// The temperature model, if the law heats.
    pub fn thermal(&self) -> Option<&Thermal> {
        match self {
            RateLaw::JohnsonCook { thermal, .. } => thermal.as_ref(),
            RateLaw::CowperSymonds { .. } => None,
        }
    }
}

/// Johnson-Cook's static curve `A + B k^n`: (A Pa, B Pa, n).
pub type PowerCurve = (f64, f64, f64);

/// The 42CrMo4 steel of DynELA's Taylor bar sample (Pantale, DynELA v4 documentation,
/// "DynELA impact sample cases", its table of Johnson-Cook parameters: A = 806 MPa,
/// B = 614 MPa, n = 0.168, C = 0.0089, m = 1.1, reference rate 1 1/s, T0 = 20 C,
/// Tm = 1540 C, c = 460 J/(kg K), Taylor-Quinney 0.9; rho = 7830 kg/m^3, E = 206.9 GPa):
/// its static curve and its law with heating.
pub fn johnson_cook_42crmo4() -> (PowerCurve, RateLaw) {
    (
        (806e6, 614e6, 0.168),
        RateLaw::JohnsonCook {
            c: 0.0089,
            reference_rate: 1.0,
            thermal: Some(Thermal {
                initial_temperature: 293.15,
                reference_temperature: 293.15,
                melting_temperature: 1813.15,
                specific_heat: 460.0,
                taylor_quinney: 0.9,
                softening_exponent: 1.1,
            }),
        },
    )
}

/// One input that looks wrong.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Warning {
    pub location: SourceLocation,
    /// Dotted field name, e.g. `plate.length`.
    pub field: String,
    /// The value as read (or as written, for a quoted one).
    pub value: String,
    /// Why it looks wrong and what was probably meant.
    pub message: String,
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}: {} = {}: {}",
            self.location, self.field, self.value, self.message
        )
    }
}
