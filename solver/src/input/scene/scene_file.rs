//! The scene file as written: the YAML document's types ([`SceneFile`] and its parts).
//! Unknown keys, wrong types, missing fields and duplicate keys are refused by the parser with
//! line and column; every field, its unit and its default are documented here. `end:` and
//! `contact:` are read by hand-written visitors (`file_visitors.rs`) for plain-word errors.

use std::collections::BTreeMap;

use serde::Deserialize;
use serde_saphyr::Spanned;

use super::choices::{
    DtUpdate, ElementKind, Ends, Enforcement, Estimate, Geometry, Kinematics, MidSpanNode, Model,
};

type Num = Spanned<f64>;
type Int = Spanned<i64>;

/// The YAML document as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// Optional title, for reports.
    #[serde(default)]
    pub title: Option<String>,
    pub plate: PlateFile,
    pub material: MaterialFile,
    pub mesh: MeshFile,
    pub load: LoadFile,
    pub time: TimeFile,
    #[serde(default)]
    pub output: OutputFile,
    /// `small` (default: the paper's model) or `finite`.
    #[serde(default)]
    pub kinematics: Kinematics,
    /// `plane-strain` (default: the paper's model) or `axisymmetric`.
    #[serde(default)]
    pub geometry: Option<Spanned<Geometry>>,
}

/// `plate: {length, width, thickness, ends}`, lengths in m; `length` is clamp to clamp,
/// results are totals over `width`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlateFile {
    pub length: Num,
    pub width: Num,
    pub thickness: Num,
    /// Support of the two ends (default clamped).
    #[serde(default)]
    pub ends: Option<Spanned<Ends>>,
}

/// `material`: `density` kg/m^3, `youngs_modulus` Pa, `poisson_ratio` (-), optional `plasticity`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialFile {
    pub density: Num,
    pub youngs_modulus: Num,
    pub poisson_ratio: Num,
    #[serde(default)]
    pub plasticity: Option<Spanned<PlasticityFile>>,
}

/// `plasticity: {yield_stress: Pa, hardening: {linear: E_t Pa} | {table: [[eqps, Pa], ...]},
/// rate: {...}}`; `rate` optional (its law: [`RateFile`]); with `rate: {johnson_cook}`
/// the flow curve is Johnson-Cook's and `yield_stress` and `hardening` are left out.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlasticityFile {
    #[serde(default)]
    pub yield_stress: Option<Num>,
    #[serde(default)]
    pub hardening: Option<Spanned<HardeningFile>>,
    #[serde(default)]
    pub rate: Option<Spanned<RateFile>>,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum HardeningFile {
    /// Tangent modulus of the uniaxial curve after yield, Pa (0 = perfectly plastic).
    Linear(Num),
    /// Piecewise-linear flow stress (Pa) against equivalent plastic strain (-).
    Table(Vec<[f64; 2]>),
}

/// `mesh: {nx, ny, element, model, grading, hourglass, distortion}`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshFile {
    /// Elements along the modelled length.
    pub nx: Int,
    /// Elements through the thickness (even, >= 2).
    pub ny: Int,
    #[serde(default)]
    pub element: ElementKind,
    #[serde(default)]
    pub model: Model,
    /// Largest / smallest element length along x, smallest at mid-span (default 1: uniform).
    #[serde(default)]
    pub grading: Option<Num>,
    /// Flanagan-Belytschko hourglass stiffness coefficient for `q4-1pt` (default 0.05).
    #[serde(default)]
    pub hourglass: Option<Num>,
    /// Deterministic random shift of interior nodes, as a fraction of the local element size
    /// (default 0; for robustness and stability studies).
    #[serde(default)]
    pub distortion: Option<Num>,
}

#[derive(Debug, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum LoadFile {
    Impactor(ImpactorFile),
    Pulse(PulseFile),
    Traction(TractionFile),
    Wall(WallFile),
}

/// `wall: {velocity: m/s}`: the whole body starts at `velocity` toward a rigid, frictionless
/// wall in the plane y = 0 that its bottom face touches at t = 0 (`ALGORITHM.md` section 5c);
/// needs `plate.ends: free`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WallFile {
    pub velocity: Num,
}

/// `impactor`: rigid line-nose body. `mass` kg (whole impactor, whole width), `velocity` m/s
/// toward the plate, `nose_radius` m; `contact` the coupling (default `nodal`: the paper's
/// contact law at one node, which needs `youngs_modulus` Pa, `poisson_ratio` (-) of the nose and
/// `contact_law`; `surface`: the rigid nose in penalty contact with the plate's top surface).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ImpactorFile {
    pub mass: Num,
    pub velocity: Num,
    pub nose_radius: Num,
    #[serde(default)]
    pub youngs_modulus: Option<Num>,
    #[serde(default)]
    pub poisson_ratio: Option<Num>,
    #[serde(default)]
    pub contact_law: Option<Spanned<ContactLawFile>>,
    #[serde(default)]
    pub indentation_datum: Option<Spanned<MidSpanNode>>,
    /// Node the contact force acts on; defaults to `indentation_datum`.
    #[serde(default)]
    pub force_node: Option<Spanned<MidSpanNode>>,
    /// `nodal` (default) | `surface` | `{surface: {penalty_scale}}`.
    #[serde(default)]
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
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SurfaceFile {
    #[serde(default)]
    pub enforcement: Option<Spanned<Enforcement>>,
    #[serde(default)]
    pub penalty_scale: Option<Num>,
}

#[derive(Debug, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum ContactLawFile {
    /// Eq. (4) with its hidden length `length_unit` (m): 1.0 = evaluated in metres.
    Paper { length_unit: Num },
    /// Johnson's dimensionally consistent 2-D line contact, plate datum at `datum_depth` (m).
    Johnson { datum_depth: Num },
}

/// `pulse: {force: N (whole width), duration: s}`: rectangular, downward on the top
/// mid-span node.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PulseFile {
    pub force: Num,
    pub duration: Num,
}

/// `traction: {normal: Pa, shear: Pa, duration: s}`: uniform on the whole top surface,
/// rectangular in time; `normal` positive pushes down, `shear` positive pulls toward +x.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TractionFile {
    #[serde(default)]
    pub normal: Option<Num>,
    #[serde(default)]
    pub shear: Option<Num>,
    pub duration: Num,
}

/// `time: {end, dt, limit, allow_unstable_dt}`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TimeFile {
    pub end: Spanned<EndFile>,
    pub dt: Spanned<DtFile>,
    /// Hard stop for `end: {after_contact}`, s (default 0.05).
    #[serde(default)]
    pub limit: Option<Num>,
    /// Accept a step above the stable estimate (stability studies only; default false).
    #[serde(default)]
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

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AfterContactFile {
    pub after_contact: Num,
}

/// `dt: {cfl: c | fixed: s, estimate: element | global, update: once | every-step}` (exactly
/// one of `cfl`, `fixed`).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DtFile {
    /// Fraction of the stable estimate.
    #[serde(default)]
    pub cfl: Option<Num>,
    /// Time step, s.
    #[serde(default)]
    pub fixed: Option<Num>,
    /// Which estimate of the stable step (default `element`).
    #[serde(default)]
    pub estimate: Estimate,
    /// When the stable step is estimated (default `once`, at the start).
    #[serde(default)]
    pub update: Option<Spanned<DtUpdate>>,
}

/// `output: {every: s, probes: {NAME: {x: m, y: m}}, fields: {every: s}}`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputFile {
    /// Time between history rows, s (default: every step).
    #[serde(default)]
    pub every: Option<Num>,
    #[serde(default)]
    pub probes: BTreeMap<String, ProbeFile>,
    #[serde(default)]
    pub fields: Option<FieldsFile>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProbeFile {
    pub x: Num,
    pub y: Num,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FieldsFile {
    pub every: Num,
}

/// `rate:` as written: one key naming the law.
#[derive(Debug, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum RateFile {
    CowperSymonds(CowperSymondsFile),
    JohnsonCook(JohnsonCookFile),
}

/// `cowper_symonds: {D: 1/s, q: -}`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CowperSymondsFile {
    #[serde(rename = "D")]
    pub d: Num,
    pub q: Num,
}

/// `johnson_cook: {A, B, n, C, reference_rate, m, thermal}`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JohnsonCookFile {
    /// Static yield stress at the reference temperature, Pa.
    #[serde(rename = "A")]
    pub a: Num,
    /// Hardening coefficient, Pa.
    #[serde(rename = "B")]
    pub b: Num,
    /// Hardening exponent (-).
    pub n: Num,
    /// Rate coefficient (-).
    #[serde(rename = "C")]
    pub c: Num,
    /// Reference equivalent plastic strain rate, 1/s.
    pub reference_rate: Num,
    /// Thermal softening exponent (-); needed with `thermal`.
    #[serde(default)]
    pub m: Option<Num>,
    #[serde(default)]
    pub thermal: Option<Spanned<ThermalFile>>,
}

/// `thermal: {initial_temperature: K, melting_temperature: K, specific_heat: J/(kg K),
/// taylor_quinney: -}`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ThermalFile {
    pub initial_temperature: Num,
    pub melting_temperature: Num,
    pub specific_heat: Num,
    pub taylor_quinney: Num,
}
