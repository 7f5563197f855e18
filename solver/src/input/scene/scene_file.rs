//! The scene file as written: the YAML document's types ([`SceneFile`] and its parts), in SI
//! units. Unknown keys, wrong types, missing fields and duplicate keys are refused by the parser
//! with line and column; every field, its unit and its default are documented here, and these
//! documents are the descriptions of the scene's JSON Schema ([`crate::input::schema`]).
//! `end:` and `contact:` are read by hand-written visitors (`file_visitors.rs`) for plain-word
//! errors; their schemas are written beside them.

use std::collections::BTreeMap;

use schemars::JsonSchema;
use serde::Deserialize;
use serde_saphyr::Spanned;

use super::choices::{
    DtUpdate, ElementKind, Ends, Enforcement, Estimate, Geometry, Kinematics, MidSpanNode, Model,
};
use super::scene_types::{SurfaceContact, DEFAULT_HOURGLASS, DEFAULT_TIME_LIMIT};

type Num = Spanned<f64>;
type Int = Spanned<i64>;

/// A scene: what to simulate, in SI units (`plate`, `material`, `mesh`, `load`, `time`, and
/// optionally `output`, `kinematics`, `geometry`, `title`).
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(title = "Impact solver scene")]
pub struct SceneFile {
    /// Optional title, for reports (no unit). Default: none.
    #[serde(default)]
    pub title: Option<String>,
    /// The plate: its length, width and thickness (m) and how its ends are held.
    pub plate: PlateFile,
    /// The plate's material: density, elastic constants and optional plasticity.
    pub material: MaterialFile,
    /// The mesh of the plate: elements along and through it, element kind, model.
    pub mesh: MeshFile,
    /// What loads the plate: exactly one of `impactor`, `pulse`, `traction` or `wall`.
    pub load: LoadFile,
    /// When the run ends and its time step.
    pub time: TimeFile,
    /// What is recorded: history interval, probes, field output. Default: a history row every
    /// step, no probe, no field output.
    #[serde(default)]
    pub output: OutputFile,
    /// How the plate deforms (no unit): `small` strains and rotations (the paper's model) or
    /// `finite` deformation. Default: `small`.
    #[serde(default)]
    pub kinematics: Kinematics,
    /// The section modelled (no unit): `plane-strain` (a slice of width `plate.width`, the
    /// paper's model) or `axisymmetric` (the half-section of a round plate). Default:
    /// `plane-strain`.
    #[serde(default)]
    #[schemars(with = "Option<Geometry>")]
    #[schemars(extend("default" = Geometry::default()))]
    pub geometry: Option<Spanned<Geometry>>,
}

/// `plate: {length, width, thickness, ends}`, lengths in m; `length` is clamp to clamp,
/// results are totals over `width`.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PlateFile {
    /// Plate length from end to end (clamp to clamp), m; > 0. In the axisymmetric geometry the
    /// plate's diameter.
    #[schemars(with = "f64")]
    pub length: Num,
    /// Plate width (out of plane), m; > 0. Results are totals over it (not used in the
    /// axisymmetric geometry).
    #[schemars(with = "f64")]
    pub width: Num,
    /// Plate thickness, m; > 0.
    #[schemars(with = "f64")]
    pub thickness: Num,
    /// How the two ends (x = 0 and x = length) are held (no unit). Default: `clamped`.
    #[serde(default)]
    #[schemars(with = "Option<Ends>")]
    #[schemars(extend("default" = Ends::default()))]
    pub ends: Option<Spanned<Ends>>,
}

/// `material`: `density` kg/m^3, `youngs_modulus` Pa, `poisson_ratio` (-), optional `plasticity`.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MaterialFile {
    /// Density, kg/m^3; > 0.
    #[schemars(with = "f64")]
    pub density: Num,
    /// Young's modulus, Pa; > 0.
    #[schemars(with = "f64")]
    pub youngs_modulus: Num,
    /// Poisson's ratio (-), in (-1, 0.5).
    #[schemars(with = "f64")]
    pub poisson_ratio: Num,
    /// Von Mises plasticity: the flow curve and an optional strain-rate law. Default: none (an
    /// elastic plate).
    #[serde(default)]
    #[schemars(with = "Option<PlasticityFile>")]
    pub plasticity: Option<Spanned<PlasticityFile>>,
}

/// `plasticity: {yield_stress: Pa, hardening: {linear: E_t Pa} | {table: [[eqps, Pa], ...]},
/// rate: {...}}`; `rate` optional (its law: [`RateFile`]); with `rate: {johnson_cook}`
/// the flow curve is Johnson-Cook's and `yield_stress` and `hardening` are left out.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PlasticityFile {
    /// Initial (static) yield stress, Pa; > 0. Needed unless `rate: {johnson_cook}` gives the
    /// flow curve (then left out).
    #[serde(default)]
    #[schemars(with = "Option<f64>")]
    pub yield_stress: Option<Num>,
    /// The flow curve after yield (Pa): `{linear: tangent modulus}` or `{table: [[eqps,
    /// stress], ...]}`. Needed unless `rate: {johnson_cook}` gives the flow curve.
    #[serde(default)]
    #[schemars(with = "Option<HardeningFile>")]
    pub hardening: Option<Spanned<HardeningFile>>,
    /// The strain-rate law of the flow stress: `cowper_symonds` or `johnson_cook`. Default:
    /// none (rate-independent, the paper's model).
    #[serde(default)]
    #[schemars(with = "Option<RateFile>")]
    pub rate: Option<Spanned<RateFile>>,
}

/// The flow curve after yield: one key naming its form.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum HardeningFile {
    /// Tangent modulus of the uniaxial curve after yield, Pa, in [0, youngs_modulus) (0 =
    /// perfectly plastic).
    Linear(#[schemars(with = "f64")] Num),
    /// Piecewise-linear flow stress against equivalent plastic strain: rows `[eqps (-), flow
    /// stress Pa]`, the first `[0, yield_stress]`, strain increasing, stress non-decreasing,
    /// flat after the last row.
    Table(Vec<[f64; 2]>),
}

/// `mesh: {nx, ny, element, model, grading, hourglass, distortion}`.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MeshFile {
    /// Elements along the modelled length (-), an integer in [1, 100000]; even for `model:
    /// full`.
    #[schemars(with = "i64")]
    pub nx: Int,
    /// Elements through the thickness (-), an even integer in [2, 10000] (the mid-plane is a
    /// row of nodes).
    #[schemars(with = "i64")]
    pub ny: Int,
    /// The element formulation (no unit). Default: `q4-sri`.
    #[serde(default)]
    pub element: ElementKind,
    /// Half plate with a symmetry plane at mid-span, or the full plate (no unit). Default:
    /// `half`.
    #[serde(default)]
    #[schemars(with = "Model")]
    #[schemars(extend("default" = Model::default()))]
    pub model: Option<Spanned<Model>>,
    /// Largest over smallest element length along x (-), in [1, 1000], the smallest at
    /// mid-span. Default: 1 (uniform).
    #[serde(default)]
    #[schemars(with = "Option<f64>")]
    #[schemars(extend("default" = 1.0))]
    pub grading: Option<Num>,
    /// Flanagan-Belytschko hourglass stiffness coefficient kappa of `q4-1pt` (-), in (0, 1].
    /// Default: 0.05.
    #[serde(default)]
    #[schemars(with = "Option<f64>")]
    #[schemars(extend("default" = DEFAULT_HOURGLASS))]
    pub hourglass: Option<Num>,
    /// Reproducible random shift of the interior nodes, as a fraction of the local element
    /// size (-), in [0, 0.4] (robustness and stability studies). Default: 0.
    #[serde(default)]
    #[schemars(with = "Option<f64>")]
    #[schemars(extend("default" = 0.0))]
    pub distortion: Option<Num>,
}

impl MeshFile {
    /// `model` as given, or its default (`half`).
    pub fn model(&self) -> Model {
        self.model.as_ref().map_or(Model::default(), |m| m.value)
    }
}

/// What loads the plate: exactly one key naming the load.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum LoadFile {
    /// A rigid line-nose impactor striking the plate at mid-span.
    Impactor(ImpactorFile),
    /// A rectangular force pulse, downward on the top mid-span node.
    Pulse(PulseFile),
    /// A uniform traction on the whole top surface, rectangular in time.
    Traction(TractionFile),
    /// The whole body flying onto a rigid, frictionless wall at y = 0 (`plate.ends: free`).
    Wall(WallFile),
}

/// `wall: {velocity: m/s}`: the whole body starts at `velocity` toward a rigid, frictionless
/// wall in the plane y = 0 that its bottom face touches at t = 0 (`ALGORITHM.md` section 5c);
/// needs `plate.ends: free`.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct WallFile {
    /// Initial velocity of the whole body toward the wall, m/s; > 0.
    #[schemars(with = "f64")]
    pub velocity: Num,
    /// Hold the impact face (the nodes at y = 0) on the wall for the whole run, free to slide
    /// (no unit): the boundary `u_y = 0` of DynELA's and Abaqus' Taylor decks, in place of a
    /// wall the face may leave. Default: false (unilateral).
    #[serde(default)]
    #[schemars(with = "Option<bool>")]
    #[schemars(extend("default" = false))]
    pub hold_face: Option<Spanned<bool>>,
    /// Coulomb's friction coefficient between the wall and the body (-; >= 0): a held
    /// node's tangential force at most `friction` times its normal force. Default: 0
    /// (frictionless).
    #[serde(default)]
    #[schemars(with = "Option<f64>")]
    #[schemars(extend("default" = 0.0))]
    pub friction: Option<Num>,
}

/// `impactor`: rigid line-nose body. `mass` kg (whole impactor, whole width), `velocity` m/s
/// toward the plate, `nose_radius` m; `contact` the coupling (default `nodal`: the paper's
/// contact law at one node, which needs `youngs_modulus` Pa, `poisson_ratio` (-) of the nose and
/// `contact_law`; `surface`: the rigid nose in penalty contact with the plate's top surface).
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ImpactorFile {
    /// Mass of the whole impactor (over the whole width), kg; > 0.
    #[schemars(with = "f64")]
    pub mass: Num,
    /// Initial velocity toward the plate, m/s; > 0.
    #[schemars(with = "f64")]
    pub velocity: Num,
    /// Radius of the nose, m; > 0.
    #[schemars(with = "f64")]
    pub nose_radius: Num,
    /// Young's modulus of the nose, Pa; > 0. Needed by the nodal coupling (`contact: nodal`,
    /// the default), refused with `contact: surface`.
    #[serde(default)]
    #[schemars(with = "Option<f64>")]
    pub youngs_modulus: Option<Num>,
    /// Poisson's ratio of the nose (-), in (-1, 0.5). Needed by the nodal coupling, refused
    /// with `contact: surface`.
    #[serde(default)]
    #[schemars(with = "Option<f64>")]
    pub poisson_ratio: Option<Num>,
    /// The nodal coupling's contact law: `{paper: {length_unit: m}}` (eq. 4) or `{johnson:
    /// {datum_depth: m}}`. Needed by the nodal coupling, refused with `contact: surface`.
    #[serde(default)]
    #[schemars(with = "Option<ContactLawFile>")]
    pub contact_law: Option<Spanned<ContactLawFile>>,
    /// The mid-span node the indentation is read from (no unit), nodal coupling only.
    /// Default: `mid-plane`.
    #[serde(default)]
    #[schemars(with = "Option<MidSpanNode>")]
    #[schemars(extend("default" = MidSpanNode::default()))]
    pub indentation_datum: Option<Spanned<MidSpanNode>>,
    /// The mid-span node the contact force acts on (no unit), nodal coupling only. Default:
    /// `indentation_datum` (energy-consistent).
    #[serde(default)]
    #[schemars(with = "Option<MidSpanNode>")]
    pub force_node: Option<Spanned<MidSpanNode>>,
    /// How the nose meets the plate (no unit): `nodal` (the paper's law at one node), `surface`
    /// (the rigid nose in contact with the top surface) or `{surface: {enforcement,
    /// penalty_scale}}`. Default: `nodal`.
    #[serde(default)]
    #[schemars(with = "Option<ContactFile>")]
    #[schemars(extend("default" = "nodal"))]
    pub contact: Option<Spanned<ContactFile>>,
}

/// How the nose meets the plate: `nodal` (the paper's law at one node) or `surface` (with its
/// options as `{surface: {...}}`).
#[derive(Debug)]
pub enum ContactFile {
    Nodal,
    Surface(SurfaceFile),
}

/// `surface: {enforcement, penalty_scale}`: `kinematic` (default) or `penalty`; with
/// `penalty`, the stiffness of each top-surface node as a fraction of its mass times the
/// largest eigenvalue of its elements (default 0.1, in (0, 1]).
#[derive(Debug, Default, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SurfaceFile {
    /// How the nodes are kept out of the nose (no unit). Default: `kinematic`.
    #[serde(default)]
    #[schemars(with = "Option<Enforcement>")]
    #[schemars(extend("default" = Enforcement::default()))]
    pub enforcement: Option<Spanned<Enforcement>>,
    /// Penalty stiffness of a top-surface node over its mass times its elements' largest
    /// eigenvalue (-), in (0, 1]; only with `enforcement: penalty`. Default: 0.1.
    #[serde(default)]
    #[schemars(with = "Option<f64>")]
    #[schemars(extend("default" = SurfaceContact::DEFAULT_PENALTY_SCALE))]
    pub penalty_scale: Option<Num>,
}

/// The nodal coupling's contact law: one key naming it.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum ContactLawFile {
    /// Eq. (4) of the paper with its hidden length.
    Paper {
        /// The unit of length eq. (4) is evaluated in, m, in [1e-6, 1e3]: 1 for metres, 0.001
        /// for millimetres.
        #[schemars(with = "f64")]
        length_unit: Num,
    },
    /// Johnson's dimensionally consistent 2-D line contact.
    Johnson {
        /// Depth of the plate datum below the top surface, m; > 0 and at most the plate
        /// thickness.
        #[schemars(with = "f64")]
        datum_depth: Num,
    },
}

/// `pulse: {force: N (whole width), duration: s}`: rectangular, downward on the top
/// mid-span node.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PulseFile {
    /// Force over the whole width, N; >= 0.
    #[schemars(with = "f64")]
    pub force: Num,
    /// Duration of the pulse from t = 0, s; > 0.
    #[schemars(with = "f64")]
    pub duration: Num,
}

/// `traction: {normal: Pa, shear: Pa, duration: s}`: uniform on the whole top surface,
/// rectangular in time; `normal` positive pushes down, `shear` positive pulls toward +x.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct TractionFile {
    /// Normal traction, Pa, positive pushing down; finite. Default: 0 (not both 0 with
    /// `shear`).
    #[serde(default)]
    #[schemars(with = "Option<f64>")]
    #[schemars(extend("default" = 0.0))]
    pub normal: Option<Num>,
    /// Shear traction, Pa, positive pulling toward +x; finite. Default: 0.
    #[serde(default)]
    #[schemars(with = "Option<f64>")]
    #[schemars(extend("default" = 0.0))]
    pub shear: Option<Num>,
    /// Duration of the traction from t = 0, s; > 0.
    #[schemars(with = "f64")]
    pub duration: Num,
}

/// `time: {end, dt, limit, allow_unstable_dt}`.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct TimeFile {
    /// When the run ends: a time, s (> 0), or `{after_contact: s}`: that long after the
    /// contact force was last non-zero.
    #[schemars(with = "EndFile")]
    pub end: Spanned<EndFile>,
    /// The time step: `{cfl: fraction}` of the stable estimate or `{fixed: s}`, with the
    /// estimate and when it is made.
    #[schemars(with = "DtFile")]
    pub dt: Spanned<DtFile>,
    /// Hard stop of `end: {after_contact}`, s; > 0. Default: 0.05.
    #[serde(default)]
    #[schemars(with = "Option<f64>")]
    #[schemars(extend("default" = DEFAULT_TIME_LIMIT))]
    pub limit: Option<Num>,
    /// Accept a step above the stable estimate (no unit; stability studies only). Default:
    /// false.
    #[serde(default)]
    #[schemars(with = "Option<bool>")]
    #[schemars(extend("default" = false))]
    pub allow_unstable_dt: Option<Spanned<bool>>,
}

/// `end: s` or `end: {after_contact: s}` (a quoted number reads as the number, as
/// everywhere in a scene).
#[derive(Debug, Clone)]
pub enum EndFile {
    /// End time, s.
    At(f64),
    /// Stop this long (s) after the contact force was last non-zero.
    AfterContact(AfterContactFile),
}

/// `{after_contact: s}`: the run stops that long after the contact force was last non-zero
/// (never past `time.limit`).
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct AfterContactFile {
    /// Time after the contact force was last non-zero, s; >= 0.
    #[schemars(with = "f64")]
    pub after_contact: Num,
}

/// `dt: {cfl: c | fixed: s, estimate: element | global, update: once | every-step}` (exactly
/// one of `cfl`, `fixed`).
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DtFile {
    /// The step as a fraction of the stable estimate (-), in (0, 1] (any > 0 with
    /// `allow_unstable_dt`). Exactly one of `cfl` and `fixed`.
    #[serde(default)]
    #[schemars(with = "Option<f64>")]
    pub cfl: Option<Num>,
    /// A fixed time step, s; > 0, at most the stable estimate unless `allow_unstable_dt`.
    /// Exactly one of `cfl` and `fixed`.
    #[serde(default)]
    #[schemars(with = "Option<f64>")]
    pub fixed: Option<Num>,
    /// Which estimate of the stable step (no unit). Default: `element`.
    #[serde(default)]
    #[schemars(extend("default" = Estimate::default().name()))]
    pub estimate: Estimate,
    /// When the stable step is estimated (no unit): `once` at the start, or `every-step` on the
    /// deformed mesh (`kinematics: finite` with `cfl` only). Default: `every-step` for a
    /// `kinematics: finite` body on the `wall` with `cfl` (its elements are crushed), else
    /// `once`; write `update: once` to keep a step fixed there.
    #[serde(default)]
    #[schemars(with = "Option<DtUpdate>")]
    pub update: Option<Spanned<DtUpdate>>,
}

/// `output: {every: s, probes: {NAME: {x: m, y: m}}, fields: {every: s}}`.
#[derive(Debug, Default, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct OutputFile {
    /// Time between history rows, s; > 0. Default: a row every step.
    #[serde(default)]
    #[schemars(with = "Option<f64>")]
    pub every: Option<Num>,
    /// Named points whose stress is recorded in the history (names of letters, digits, `_`
    /// and `-`), each `{x: m, y: m}`. Default: none.
    #[serde(default)]
    pub probes: BTreeMap<String, ProbeFile>,
    /// VTK field output: `{every: s}` between frames. Default: none.
    #[serde(default)]
    pub fields: Option<FieldsFile>,
}

/// A probe: a point of the plate whose stress (and rate and temperature, for a rate-dependent
/// material) the history records.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ProbeFile {
    /// Distance from the clamped end x = 0, m, in [0, plate.length] (mirrored in the half
    /// model).
    #[schemars(with = "f64")]
    pub x: Num,
    /// Height from the bottom surface, m, in [0, plate.thickness].
    #[schemars(with = "f64")]
    pub y: Num,
}

/// VTK field output (`fields.pvd` and `fields/`).
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FieldsFile {
    /// Time between field frames, s; > 0.
    #[schemars(with = "f64")]
    pub every: Num,
}

/// `rate:` as written: one key naming the law (`ALGORITHM.md` section 4b).
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum RateFile {
    /// Cowper-Symonds: the static flow stress times `1 + (rate / D)^(1/q)`.
    CowperSymonds(CowperSymondsFile),
    /// Johnson-Cook: `[A + B k^n] [1 + C ln(rate / reference_rate)] [1 - T*^m]`, replacing
    /// `yield_stress` and `hardening`.
    JohnsonCook(JohnsonCookFile),
}

/// `cowper_symonds: {D: 1/s, q: -}`.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CowperSymondsFile {
    /// The rate constant D, 1/s; > 0.
    #[serde(rename = "D")]
    #[schemars(with = "f64")]
    pub d: Num,
    /// The exponent q (-); > 0.
    #[schemars(with = "f64")]
    pub q: Num,
}

/// `johnson_cook: {A, B, n, C, reference_rate, m, thermal}`.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct JohnsonCookFile {
    /// Static yield stress at the reference temperature, Pa; > 0.
    #[serde(rename = "A")]
    #[schemars(with = "f64")]
    pub a: Num,
    /// Hardening coefficient, Pa; >= 0.
    #[serde(rename = "B")]
    #[schemars(with = "f64")]
    pub b: Num,
    /// Hardening exponent (-); > 0.
    #[schemars(with = "f64")]
    pub n: Num,
    /// Rate coefficient (-); >= 0.
    #[serde(rename = "C")]
    #[schemars(with = "f64")]
    pub c: Num,
    /// Reference equivalent plastic strain rate, 1/s; > 0 (below it the rate factor is 1).
    #[schemars(with = "f64")]
    pub reference_rate: Num,
    /// Thermal softening exponent (-); > 0, needed with `thermal`. Default: none.
    #[serde(default)]
    #[schemars(with = "Option<f64>")]
    pub m: Option<Num>,
    /// Adiabatic heating and thermal softening. Default: none (no heating).
    #[serde(default)]
    #[schemars(with = "Option<ThermalFile>")]
    pub thermal: Option<Spanned<ThermalFile>>,
}

/// `thermal: {initial_temperature: K, melting_temperature: K, specific_heat: J/(kg K),
/// taylor_quinney: -, reference_temperature: K}`.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ThermalFile {
    /// Initial temperature T0, K; > 0. Also Johnson-Cook's reference temperature of `T*`
    /// unless `reference_temperature` is given.
    #[schemars(with = "f64")]
    pub initial_temperature: Num,
    /// Johnson-Cook's reference temperature Tr of `T* = (T - Tr) / (Tm - Tr)`, K; at most
    /// `initial_temperature`. The temperature of the tests the constants were fitted to (room
    /// temperature, usually). Optional, default `initial_temperature` (a preheated shot starts
    /// softened, `T*` above 0; a shot colder than the fit is not modelled).
    #[serde(default)]
    #[schemars(with = "Option<f64>")]
    pub reference_temperature: Option<Num>,
    /// Melting temperature Tm, K; above `initial_temperature`.
    #[schemars(with = "f64")]
    pub melting_temperature: Num,
    /// Specific heat c, J/(kg K); > 0.
    #[schemars(with = "f64")]
    pub specific_heat: Num,
    /// Taylor-Quinney coefficient beta (-), the fraction of the plastic work that heats, in
    /// [0, 1].
    #[schemars(with = "f64")]
    pub taylor_quinney: Num,
}
