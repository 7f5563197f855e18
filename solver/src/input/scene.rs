//! The scene: what to simulate, read from YAML (SI units) and validated.
//!
//! [`SceneFile`] mirrors the YAML (unknown keys, wrong types, missing fields and duplicate
//! keys are refused by the parser with line and column); [`Scene`] is the validated scene the
//! solver runs. Every field, its unit and its default are documented on [`SceneFile`]'s parts
//! and in the README.

use std::cell::RefCell;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::Deserialize;
use serde_saphyr::Spanned;

use crate::input::error::{shown, Error, Result, SourceLocation};
use crate::input::geometry::{self, Geometry};
use crate::input::overrides::Overrides;
use crate::input::plausibility::Warning;
use crate::input::rate_law::{RateFile, RateLaw};
use crate::input::spans::FieldSpans;

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

/// How the plate deforms: small strains and rotations (the paper's model, eqs. 13-16), or
/// finite deformation (updated Lagrangian, Green-Naghdi rate: `ALGORITHM.md` section 3c).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Kinematics {
    #[default]
    Small,
    Finite,
}

impl Kinematics {
    /// The name in scenes and summaries.
    pub fn name(self) -> &'static str {
        match self {
            Kinematics::Small => "small",
            Kinematics::Finite => "finite",
        }
    }

    pub fn is_small(&self) -> bool {
        *self == Kinematics::Small
    }
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

/// How the ends of the plate (x = 0 and x = L) are held.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Ends {
    /// `u_x = u_y = 0` (the paper).
    #[default]
    Clamped,
    /// `u_x = 0`, `u_y` free (plane P waves through the thickness).
    Roller,
    /// `u_y = 0`, `u_x` free (plane S waves through the thickness).
    Slider,
    /// No support: the end (the rim in the axisymmetric geometry) is a free surface (a body
    /// in flight, e.g. a bar onto a rigid wall).
    Free,
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
/// rate: {...}}`; `rate` optional ([`crate::input::rate_law`]); with `rate: {johnson_cook}`
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

/// The element formulation; its YAML names are [`ElementKind::name`], read by [`FromStr`].
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(try_from = "String", into = "&'static str")]
pub enum ElementKind {
    /// 2x2 Gauss (locks in bending and under plastic flow; kept for comparison).
    Q4Full,
    /// Selective-reduced integration / B-bar: deviatoric 2x2, volumetric 1 point.
    #[default]
    Q4Sri,
    /// One point with Flanagan-Belytschko hourglass control.
    Q4OnePoint,
}

impl ElementKind {
    pub const ALL: [ElementKind; 3] = [
        ElementKind::Q4Full,
        ElementKind::Q4Sri,
        ElementKind::Q4OnePoint,
    ];

    /// The name in scenes, summaries and reports.
    pub fn name(self) -> &'static str {
        match self {
            ElementKind::Q4Full => "q4-full",
            ElementKind::Q4Sri => "q4-sri",
            ElementKind::Q4OnePoint => "q4-1pt",
        }
    }
}

/// The one parser of element names.
impl std::str::FromStr for ElementKind {
    type Err = String;
    fn from_str(name: &str) -> std::result::Result<Self, String> {
        ElementKind::ALL
            .into_iter()
            .find(|k| k.name() == name)
            .ok_or_else(|| {
                let known: Vec<String> = ElementKind::ALL
                    .iter()
                    .map(|k| format!("`{}`", k.name()))
                    .collect();
                format!(
                    "unknown variant `{name}`, expected one of {}",
                    known.join(", ")
                )
            })
    }
}

impl TryFrom<String> for ElementKind {
    type Error = String;
    fn try_from(name: String) -> std::result::Result<Self, String> {
        name.parse()
    }
}

impl From<ElementKind> for &'static str {
    fn from(kind: ElementKind) -> &'static str {
        kind.name()
    }
}

/// Half plate with a symmetry plane at mid-span, or the full plate.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Model {
    #[default]
    Half,
    Full,
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

/// How the surface coupling keeps the nodes out of the nose.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Enforcement {
    /// Predictor-corrector: the forces that put the predicted nodes back on the surface.
    #[default]
    Kinematic,
    /// A spring `k_i` on each node that penetrates.
    Penalty,
}

impl<'de> Deserialize<'de> for ContactFile {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        d.deserialize_any(ContactVisitor)
    }
}

/// Reads `nodal`, `surface` or `{surface: {...}}` with plain-word errors.
struct ContactVisitor;

impl<'de> serde::de::Visitor<'de> for ContactVisitor {
    type Value = ContactFile;
    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("`nodal`, `surface` or `{surface: {penalty_scale: ...}}`")
    }
    fn visit_str<E: serde::de::Error>(self, v: &str) -> std::result::Result<ContactFile, E> {
        match v {
            "nodal" => Ok(ContactFile::Nodal),
            "surface" => Ok(ContactFile::Surface(SurfaceFile::default())),
            other => Err(E::custom(format!(
                "unknown contact `{other}`, expected `nodal`, `surface` or `{{surface: {{penalty_scale: ...}}}}`"
            ))),
        }
    }
    fn visit_map<A: serde::de::MapAccess<'de>>(
        self,
        mut map: A,
    ) -> std::result::Result<ContactFile, A::Error> {
        use serde::de::Error as _;
        let Some(key) = map.next_key::<String>()? else {
            return Err(A::Error::custom(
                "expected `{surface: {penalty_scale: ...}}`",
            ));
        };
        if key != "surface" {
            return Err(A::Error::custom(format!(
                "unknown contact `{key}`, expected `surface: {{penalty_scale: ...}}`"
            )));
        }
        let options: Option<SurfaceFile> = map.next_value()?;
        if let Some(extra) = map.next_key::<String>()? {
            return Err(A::Error::custom(format!(
                "`{extra}` next to `surface`: give one contact"
            )));
        }
        Ok(ContactFile::Surface(options.unwrap_or_default()))
    }
}

#[derive(Debug, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum ContactLawFile {
    /// Eq. (4) with its hidden length `length_unit` (m): 1.0 = evaluated in metres.
    Paper { length_unit: Num },
    /// Johnson's dimensionally consistent 2-D line contact, plate datum at `datum_depth` (m).
    Johnson { datum_depth: Num },
}

/// A node on the mid-span line.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum MidSpanNode {
    #[default]
    MidPlane,
    TopSurface,
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

impl<'de> Deserialize<'de> for EndFile {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        d.deserialize_any(EndVisitor)
    }
}

/// Reads `end:` with plain-word errors (an untagged enum would say "did not match any
/// variant").
struct EndVisitor;

impl<'de> serde::de::Visitor<'de> for EndVisitor {
    type Value = EndFile;
    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a number of seconds or {after_contact: seconds}")
    }
    fn visit_f64<E: serde::de::Error>(self, v: f64) -> std::result::Result<EndFile, E> {
        Ok(EndFile::At(v))
    }
    fn visit_i64<E: serde::de::Error>(self, v: i64) -> std::result::Result<EndFile, E> {
        Ok(EndFile::At(v as f64))
    }
    fn visit_u64<E: serde::de::Error>(self, v: u64) -> std::result::Result<EndFile, E> {
        Ok(EndFile::At(v as f64))
    }
    fn visit_str<E: serde::de::Error>(self, v: &str) -> std::result::Result<EndFile, E> {
        match v.trim().parse::<f64>() {
            // `inf`/`nan` in quotes are words here, as YAML's .inf/.nan are (refused by name).
            Ok(x) if x.is_finite() => Ok(EndFile::At(x)),
            _ => Err(E::custom(format!(
                "`{v}` is not a number: expected a number of seconds or {{after_contact: seconds}}"
            ))),
        }
    }
    fn visit_bool<E: serde::de::Error>(self, v: bool) -> std::result::Result<EndFile, E> {
        Err(E::custom(format!(
            "`{v}` is not a number: expected a number of seconds or {{after_contact: seconds}}"
        )))
    }
    fn visit_unit<E: serde::de::Error>(self) -> std::result::Result<EndFile, E> {
        Err(E::custom(
            "no value: expected a number of seconds or {after_contact: seconds}",
        ))
    }
    fn visit_none<E: serde::de::Error>(self) -> std::result::Result<EndFile, E> {
        self.visit_unit()
    }
    fn visit_seq<A: serde::de::SeqAccess<'de>>(
        self,
        _: A,
    ) -> std::result::Result<EndFile, A::Error> {
        Err(serde::de::Error::custom(
            "a list: expected a number of seconds or {after_contact: seconds}",
        ))
    }
    fn visit_map<A: serde::de::MapAccess<'de>>(
        self,
        map: A,
    ) -> std::result::Result<EndFile, A::Error> {
        let a = AfterContactFile::deserialize(serde::de::value::MapAccessDeserializer::new(map))?;
        Ok(EndFile::AfterContact(a))
    }
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

/// When the stable step is estimated (`time.dt.update`; `ALGORITHM.md` section 6b).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum DtUpdate {
    /// Once, on the mesh as made: the step is fixed for the run (the paper's model).
    #[default]
    Once,
    /// At every step, on the deformed mesh (finite deformation): `time.dt.cfl` times the
    /// estimate at the start scaled by the deformed elements' ratio.
    EveryStep,
}

impl DtUpdate {
    /// The name in scenes and summaries.
    pub fn name(self) -> &'static str {
        match self {
            DtUpdate::Once => "once",
            DtUpdate::EveryStep => "every-step",
        }
    }
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

// ---------------------------------------------------------------------------------------
// The validated scene.

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

/// Which estimate of the largest eigenvalue sets the stable step (`time.dt.estimate`; see
/// `stable_step`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Estimate {
    /// The element eigenvalue bound.
    #[default]
    Element,
    /// Power iteration on the assembled operator, the contact spring included.
    Global,
}

impl Estimate {
    pub fn name(self) -> &'static str {
        match self {
            Estimate::Element => "element",
            Estimate::Global => "global",
        }
    }
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
    /// Reads and validates a scene file.
    pub fn from_file(path: &Path) -> Result<Scene> {
        Scene::from_file_with(path, &Overrides::new())
    }

    /// Reads a scene file, applies `overrides` (see [`Scene::from_yaml_with`]) and validates.
    pub fn from_file_with(path: &Path, overrides: &Overrides) -> Result<Scene> {
        let text = std::fs::read_to_string(path).map_err(|source| Error::ReadScene {
            path: path.to_path_buf(),
            source,
        })?;
        Scene::from_yaml_with(&text, overrides, path)
    }

    /// Parses and validates YAML text; `source` names it in messages.
    pub fn from_yaml(text: &str, source: &Path) -> Result<Scene> {
        let file: SceneFile = parse(text, source)?;
        let mut scene = Validator::new(source).scene(file)?;
        scene.warnings = crate::input::plausibility::warnings(&scene, Some(text));
        Ok(scene)
    }

    /// Parses YAML text, sets each override at its dotted path of the scene (e.g.
    /// `load.impactor.mass`, `time.dt.cfl`) and validates the result with the same rules as
    /// a scene file. The text itself must be a valid scene; an override the rules refuse
    /// gives [`Error::Override`], naming the override and carrying the rule's message.
    pub fn from_yaml_with(text: &str, overrides: &Overrides, source: &Path) -> Result<Scene> {
        let base = Scene::from_yaml(text, source)?;
        if overrides.is_empty() {
            return Ok(base);
        }
        let tree: serde_json::Value = parse(text, source)?;
        let merged = |keys: &mut dyn Iterator<Item = (&String, &serde_json::Value)>| {
            let mut tree = tree.clone();
            for (key, value) in keys {
                crate::input::overrides::set(&mut tree, key, value)?;
            }
            let json = serde_json::to_string_pretty(&tree).map_err(|e| e.to_string())?;
            let file: SceneFile = parse(&json, source).map_err(|e| without_location(&e))?;
            Validator::new(source)
                .scene(file)
                .map_err(|e| without_location(&e))
        };
        let refused = match merged(&mut overrides.iter()) {
            Ok(scene) => return Ok(with_locations_of(scene, &base, overrides, text)),
            Err(message) => message,
        };
        // Name the first override the rules refuse on its own; else the combination.
        for (key, value) in overrides {
            if let Err(message) = merged(&mut std::iter::once((key, value))) {
                return Err(Error::Override {
                    file: source.to_path_buf(),
                    key: key.clone(),
                    value: value.to_string(),
                    message,
                });
            }
        }
        Err(Error::Override {
            file: source.to_path_buf(),
            key: overrides.keys().cloned().collect::<Vec<_>>().join(", "),
            value: "(together)".into(),
            message: refused,
        })
    }

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

/// The name of `ends` in scenes.
fn ends_name(ends: Ends) -> &'static str {
    match ends {
        Ends::Clamped => "clamped",
        Ends::Roller => "roller",
        Ends::Slider => "slider",
        Ends::Free => "free",
    }
}

/// Parses YAML text into `T`, with the parser's line and column.
fn parse<T: serde::de::DeserializeOwned>(text: &str, source: &Path) -> Result<T> {
    serde_saphyr::from_str(text).map_err(|e| {
        let (line, column) = e
            .location()
            .map(|l| (l.line(), l.column()))
            .unwrap_or((0, 0));
        let (line, column, message) = crate::input::yaml_field::describe(
            text,
            &crate::input::yaml_field::parser_words(&e.to_string()),
            line,
            column,
        );
        Error::ParseScene {
            location: SourceLocation {
                file: source.to_path_buf(),
                line,
                column,
            },
            message,
        }
    })
}

/// A message about the merged tree, whose lines and columns are not the file's.
fn without_location(e: &Error) -> String {
    match e {
        Error::ParseScene { message, .. } => message.clone(),
        Error::InvalidScene(v) => format!("{} = {}: {}", v.field, v.value, v.allowed),
        other => other.to_string(),
    }
}

/// The scene of the merged tree, pointing at the file where the file still holds the value,
/// its warnings found again on the merged values.
fn with_locations_of(mut scene: Scene, base: &Scene, overrides: &Overrides, text: &str) -> Scene {
    let dt_overridden = overrides
        .keys()
        .any(|k| k == "time" || k.starts_with("time.dt"));
    scene.time.dt_location = if dt_overridden {
        SourceLocation::file(&base.source)
    } else {
        base.time.dt_location.clone()
    };
    let keys: Vec<&str> = overrides.keys().map(String::as_str).collect();
    scene.fields = FieldSpans::relocated(&scene.fields, &base.fields, &keys, &base.source);
    scene.warnings = crate::input::plausibility::warnings(&scene, Some(text));
    scene
}

pub(super) struct Validator<'a> {
    source: &'a Path,
    /// Where each field read so far was written.
    spans: RefCell<FieldSpans>,
}

/// A validation rule: what a value must satisfy, in words.
#[derive(Clone, Copy)]
pub(super) struct Rule {
    pub(super) allowed: &'static str,
    pub(super) ok: fn(f64) -> bool,
}

pub(super) const POSITIVE: Rule = Rule {
    allowed: "must be a finite number > 0",
    ok: |v| v.is_finite() && v > 0.0,
};
pub(super) const NON_NEGATIVE: Rule = Rule {
    allowed: "must be a finite number >= 0",
    ok: |v| v.is_finite() && v >= 0.0,
};
const POISSON: Rule = Rule {
    allowed: "must lie in (-1, 0.5) (exclusive)",
    ok: |v| v > -1.0 && v < 0.5,
};
/// Eq. (4)'s hidden length: the unit of length the paper's law is read in. Any unit of
/// length anyone means lies between a micrometre and a kilometre; beyond 1.3e154 m its square
/// overflows and the law's constants become inf (a run that stopped with NaN energies).
const LENGTH_UNIT: Rule = Rule {
    allowed: "must lie in [1e-6, 1e3] m (the unit of length eq. (4) is read in: 1 for metres, 0.001 for millimetres)",
    ok: |v| (1e-6..=1e3).contains(&v),
};
const CFL: Rule = Rule {
    allowed: "must lie in (0, 1] (fraction of the stable step)",
    ok: |v| v > 0.0 && v <= 1.0,
};
const CFL_UNCHECKED: Rule = Rule {
    allowed: "must be a finite number > 0",
    ok: |v| v.is_finite() && v > 0.0,
};

impl<'a> Validator<'a> {
    fn new(source: &'a Path) -> Validator<'a> {
        Validator {
            source,
            spans: RefCell::new(FieldSpans::default()),
        }
    }

    fn at<T>(&self, spanned: &Spanned<T>) -> SourceLocation {
        SourceLocation::of(self.source, spanned)
    }

    /// Notes where `field` was written (and its value, when a number).
    fn read<T>(&self, spanned: &Spanned<T>, field: &str) {
        self.read_number(spanned, field, None);
    }

    fn read_number<T>(&self, spanned: &Spanned<T>, field: &str, value: Option<f64>) {
        self.read_value(spanned, field, value, false);
    }

    fn read_value<T>(&self, spanned: &Spanned<T>, field: &str, value: Option<f64>, positive: bool) {
        self.spans
            .borrow_mut()
            .insert(field, self.at(spanned), value, positive);
    }

    pub(super) fn check(&self, value: &Num, field: &str, rule: Rule) -> Result<f64> {
        self.read_value(value, field, Some(value.value), !(rule.ok)(0.0));
        if (rule.ok)(value.value) {
            Ok(value.value)
        } else {
            Err(Error::invalid(
                self.at(value),
                field,
                shown(value.value),
                rule.allowed,
            ))
        }
    }

    pub(super) fn fail<T, U>(
        &self,
        at: &Spanned<T>,
        field: &str,
        value: impl std::fmt::Display,
        allowed: impl Into<String>,
    ) -> Result<U> {
        Err(Error::invalid(self.at(at), field, value, allowed))
    }

    fn scene(&self, file: SceneFile) -> Result<Scene> {
        let plate = Plate {
            length: self.check(&file.plate.length, "plate.length", POSITIVE)?,
            width: self.check(&file.plate.width, "plate.width", POSITIVE)?,
            thickness: self.check(&file.plate.thickness, "plate.thickness", POSITIVE)?,
            ends: file
                .plate
                .ends
                .as_ref()
                .map_or_else(Ends::default, |e| e.value),
        };
        let material = self.material(file.material)?;
        let mesh = self.mesh(&file.mesh)?;
        let load = self.load(file.load, &plate)?;
        let time = self.time(&file.time, file.kinematics)?;
        if let Load::Wall(_) = load {
            self.wall_scene(&file.plate, &file.mesh, &file.time)?;
        }
        let output = self.output(&file.output, &plate)?;
        let choices = geometry::Choices {
            model: mesh.model,
            load: &load,
            estimate: time.dt_estimate,
        };
        let geometry = geometry::validated(file.geometry.as_ref(), self.source, choices)?;
        Ok(Scene {
            source: self.source.to_path_buf(),
            title: file.title,
            plate,
            material,
            mesh,
            load,
            time,
            output,
            fields: self.spans.take(),
            warnings: Vec::new(),
            kinematics: file.kinematics,
            geometry,
        })
    }

    fn material(&self, m: MaterialFile) -> Result<Material> {
        let youngs_modulus = self.check(&m.youngs_modulus, "material.youngs_modulus", POSITIVE)?;
        let plasticity = match m.plasticity {
            None => None,
            Some(p) => Some(self.plasticity(&p, youngs_modulus)?),
        };
        Ok(Material {
            density: self.check(&m.density, "material.density", POSITIVE)?,
            youngs_modulus,
            poisson_ratio: self.check(&m.poisson_ratio, "material.poisson_ratio", POISSON)?,
            plasticity,
        })
    }

    fn plasticity(&self, p: &Spanned<PlasticityFile>, youngs_modulus: f64) -> Result<Plasticity> {
        let (rate, power) = match &p.value.rate {
            None => (None, None),
            Some(r) => {
                let (law, power) = self.rate_law(&r.value)?;
                (Some(law), power)
            }
        };
        if let Some((a, b, n)) = power {
            return self.johnson_cook_curve(p, rate, (a, b, n));
        }
        let missing = |key: &str| {
            self.fail(
                p,
                &format!("material.plasticity.{key}"),
                "missing",
                "needed unless rate: {johnson_cook: {A, B, n, ...}} gives the flow curve",
            )
        };
        let Some(ys) = &p.value.yield_stress else {
            return missing("yield_stress");
        };
        let Some(h) = &p.value.hardening else {
            return missing("hardening");
        };
        let yield_stress = self.check(ys, "material.plasticity.yield_stress", POSITIVE)?;
        Ok(Plasticity {
            yield_stress,
            hardening: self.hardening(h, yield_stress, youngs_modulus)?,
            rate,
        })
    }

    /// Johnson-Cook's flow curve `A + B k^n`: `yield_stress` and `hardening` must be absent.
    fn johnson_cook_curve(
        &self,
        p: &Spanned<PlasticityFile>,
        rate: Option<RateLaw>,
        (a, b, n): (f64, f64, f64),
    ) -> Result<Plasticity> {
        let given = [
            (
                "yield_stress",
                p.value.yield_stress.as_ref().map(|v| self.at(v)),
            ),
            ("hardening", p.value.hardening.as_ref().map(|v| self.at(v))),
        ];
        if let Some((key, Some(at))) = given.into_iter().find(|(_, at)| at.is_some()) {
            return Err(Error::invalid(
                at,
                &format!("material.plasticity.{key}"),
                "given",
                "must be left out with rate: {johnson_cook}: A, B and n are the flow curve",
            ));
        }
        Ok(Plasticity {
            yield_stress: a,
            hardening: Hardening::Power {
                coefficient: b,
                exponent: n,
            },
            rate,
        })
    }

    fn hardening(
        &self,
        h: &Spanned<HardeningFile>,
        yield_stress: f64,
        youngs_modulus: f64,
    ) -> Result<Hardening> {
        let field = "material.plasticity.hardening";
        match &h.value {
            HardeningFile::Linear(et) => {
                self.read_number(et, &format!("{field}.linear"), Some(et.value));
                let (at, et) = (et, &et.value);
                if !(et.is_finite() && *et >= 0.0 && *et < youngs_modulus) {
                    return self.fail(
                        at,
                        &format!("{field}.linear"),
                        shown(*et),
                        format!(
                            "tangent modulus must lie in [0, youngs_modulus = {youngs_modulus:e}) Pa"
                        ),
                    );
                }
                Ok(Hardening::Linear {
                    tangent_modulus: *et,
                })
            }
            HardeningFile::Table(rows) => self.hardening_table(h, rows, yield_stress),
        }
    }

    fn hardening_table(
        &self,
        at: &Spanned<HardeningFile>,
        rows: &[[f64; 2]],
        yield_stress: f64,
    ) -> Result<Hardening> {
        let field = "material.plasticity.hardening.table";
        let show = |r: &[f64; 2]| format!("[{:e}, {:e}]", r[0], r[1]);
        let Some(first) = rows.first() else {
            return self.fail(
                at,
                field,
                "[]",
                "needs at least one [eqps, flow stress] row",
            );
        };
        if first[0] != 0.0 || (first[1] - yield_stress).abs() > 1e-9 * yield_stress {
            return self.fail(
                at,
                &format!("{field}[0]"),
                show(first),
                format!("must be [0, yield_stress] = [0, {yield_stress:e}]"),
            );
        }
        for (k, pair) in rows.windows(2).enumerate() {
            let (a, b) = (pair[0], pair[1]);
            if !(b[0].is_finite() && b[1].is_finite() && b[0] > a[0] && b[1] >= a[1]) {
                return self.fail(
                    at,
                    &format!("{field}[{}]", k + 1),
                    show(&b),
                    format!(
                        "rows must have increasing plastic strain and non-decreasing stress (previous row {})",
                        show(&a)
                    ),
                );
            }
        }
        Ok(Hardening::Table(
            rows.iter().map(|r| (r[0], r[1])).collect(),
        ))
    }

    fn mesh(&self, m: &MeshFile) -> Result<MeshSettings> {
        self.read_number(&m.nx, "mesh.nx", Some(m.nx.value as f64));
        self.read_number(&m.ny, "mesh.ny", Some(m.ny.value as f64));
        let nx = m.nx.value;
        if !(1..=100_000).contains(&nx) {
            return self.fail(&m.nx, "mesh.nx", nx, "must be an integer in [1, 100000]");
        }
        let ny = m.ny.value;
        if !(2..=10_000).contains(&ny) || ny % 2 != 0 {
            return self.fail(
                &m.ny,
                "mesh.ny",
                ny,
                "must be an even integer in [2, 10000] (the mid-plane must be a row of nodes)",
            );
        }
        if m.model == Model::Full && nx % 2 != 0 {
            return self.fail(
                &m.nx,
                "mesh.nx",
                nx,
                "must be even for model: full (mid-span must be a column of nodes)",
            );
        }
        let grading = match &m.grading {
            None => 1.0,
            Some(g) => self.check(
                g,
                "mesh.grading",
                Rule {
                    allowed: "must lie in [1, 1000] (largest / smallest element length)",
                    ok: |v| (1.0..=1000.0).contains(&v),
                },
            )?,
        };
        let hourglass = match &m.hourglass {
            None => DEFAULT_HOURGLASS,
            Some(h) => self.check(
                h,
                "mesh.hourglass",
                Rule {
                    allowed: "must lie in (0, 1]",
                    ok: |v| v > 0.0 && v <= 1.0,
                },
            )?,
        };
        let distortion = match &m.distortion {
            None => 0.0,
            Some(d) => self.check(
                d,
                "mesh.distortion",
                Rule {
                    allowed: "must lie in [0, 0.4] (fraction of the local element size)",
                    ok: |v| (0.0..=0.4).contains(&v),
                },
            )?,
        };
        Ok(MeshSettings {
            nx: nx as usize,
            ny: ny as usize,
            element: m.element,
            model: m.model,
            grading,
            hourglass,
            distortion,
        })
    }

    fn load(&self, load: LoadFile, plate: &Plate) -> Result<Load> {
        Ok(match load {
            LoadFile::Traction(t) => {
                let finite = Rule {
                    allowed: "must be a finite number (Pa)",
                    ok: f64::is_finite,
                };
                let normal = match &t.normal {
                    Some(v) => self.check(v, "load.traction.normal", finite)?,
                    None => 0.0,
                };
                let shear = match &t.shear {
                    Some(v) => self.check(v, "load.traction.shear", finite)?,
                    None => 0.0,
                };
                if normal == 0.0 && shear == 0.0 {
                    return self.fail(
                        &t.duration,
                        "load.traction",
                        "normal = shear = 0",
                        "needs a non-zero normal or shear traction (Pa)",
                    );
                }
                Load::Traction(Traction {
                    normal,
                    shear,
                    duration: self.check(&t.duration, "load.traction.duration", POSITIVE)?,
                })
            }
            LoadFile::Pulse(p) => Load::Pulse(Pulse {
                force: self.check(&p.force, "load.pulse.force", NON_NEGATIVE)?,
                duration: self.check(&p.duration, "load.pulse.duration", POSITIVE)?,
            }),
            LoadFile::Impactor(i) => self.impactor(&i, plate)?,
            LoadFile::Wall(w) => Load::Wall(Wall {
                velocity: self.check(&w.velocity, "load.wall.velocity", POSITIVE)?,
            }),
        })
    }

    /// What the wall needs of the rest of the scene: a free body (`plate.ends: free`), the
    /// half model (the symmetry line is the bar's axis or mid-plane: the full model has no
    /// x support with free ends) and a fixed end time (the wall force may touch zero while
    /// the bar still rolls on the wall: `after_contact` could stop a run early).
    fn wall_scene(&self, plate: &PlateFile, mesh: &MeshFile, time: &TimeFile) -> Result<()> {
        let why_free = "must be `free` with load: {wall}: the body flies onto the wall and nothing holds it (clamped, roller and slider ends would pin it in the air)";
        match &plate.ends {
            Some(e) if e.value != Ends::Free => {
                return self.fail(e, "plate.ends", ends_name(e.value), why_free)
            }
            None => {
                return self.fail(
                    &plate.length,
                    "plate.ends",
                    "clamped (the default)",
                    why_free,
                )
            }
            Some(_) => {}
        }
        if mesh.model == Model::Full {
            return self.fail(
                &mesh.nx,
                "mesh.model",
                "full",
                "must be `half` with load: {wall}: the symmetry line is the bar's axis (axisymmetric) or mid-plane, and the full model's free ends leave x unsupported",
            );
        }
        if let EndFile::AfterContact(_) = time.end.value {
            return self.fail(
                &time.end,
                "time.end",
                "{after_contact}",
                "must be a time (s) with load: {wall}: the wall force may pass through zero while the bar is still on the wall, so after_contact could stop the run early",
            );
        }
        Ok(())
    }

    /// `load.impactor` under its coupling: the nodal one's law and nodes, or the surface
    /// one's options; the other coupling's keys are refused.
    fn impactor(&self, i: &ImpactorFile, plate: &Plate) -> Result<Load> {
        let f = |name: &str| format!("load.impactor.{name}");
        let (mass, velocity, nose_radius) = (
            self.check(&i.mass, &f("mass"), POSITIVE)?,
            self.check(&i.velocity, &f("velocity"), POSITIVE)?,
            self.check(&i.nose_radius, &f("nose_radius"), POSITIVE)?,
        );
        let surface = match &i.contact {
            Some(Spanned {
                value: ContactFile::Surface(options),
                ..
            }) => options,
            _ => {
                return Ok(Load::Impactor(Impactor {
                    mass,
                    velocity,
                    nose_radius,
                    youngs_modulus: self.required(
                        &i.youngs_modulus,
                        i,
                        "youngs_modulus",
                        "Pa",
                        POSITIVE,
                    )?,
                    poisson_ratio: self.required(
                        &i.poisson_ratio,
                        i,
                        "poisson_ratio",
                        "-",
                        POISSON,
                    )?,
                    contact_law: self.contact_law(i, plate)?,
                    indentation_datum: i
                        .indentation_datum
                        .as_ref()
                        .map_or_else(MidSpanNode::default, |d| d.value),
                    force_node: i
                        .force_node
                        .as_ref()
                        .or(i.indentation_datum.as_ref())
                        .map_or_else(MidSpanNode::default, |d| d.value),
                }))
            }
        };
        self.refuse_nodal_keys(i)?;
        let enforcement = surface
            .enforcement
            .as_ref()
            .map_or_else(Enforcement::default, |e| e.value);
        let penalty_scale = match &surface.penalty_scale {
            None => SurfaceContact::DEFAULT_PENALTY_SCALE,
            Some(v) if enforcement == Enforcement::Kinematic => {
                return self.fail(
                    v,
                    &f("contact.surface.penalty_scale"),
                    shown(v.value),
                    "is the penalty enforcement's: give `enforcement: penalty` with it, or remove it (the kinematic enforcement has no stiffness)",
                )
            }
            Some(v) => self.check(
                v,
                &f("contact.surface.penalty_scale"),
                Rule {
                    allowed: "must be a number in (0, 1] (the penalty stiffness of a node over its mass times its elements' largest eigenvalue; 1 shortens the stable step by 1/sqrt(2))",
                    ok: |x| x > 0.0 && x <= 1.0,
                },
            )?,
        };
        Ok(Load::SurfaceImpactor(SurfaceImpactor {
            mass,
            velocity,
            nose_radius,
            contact: SurfaceContact {
                enforcement,
                penalty_scale,
            },
        }))
    }

    /// A key the nodal coupling needs (`unit` for the message): missing is an error at the
    /// impactor's `mass`.
    fn required(
        &self,
        value: &Option<Num>,
        i: &ImpactorFile,
        key: &str,
        unit: &str,
        rule: Rule,
    ) -> Result<f64> {
        let field = format!("load.impactor.{key}");
        match value {
            Some(v) => self.check(v, &field, rule),
            None => self.fail(
                &i.mass,
                &field,
                "missing",
                format!("the nodal contact coupling (the default `contact: nodal`) needs the nose's {key} ({unit}); or use `contact: surface`, whose nose is rigid"),
            ),
        }
    }

    /// The surface coupling's nose is rigid and its force comes from the top surface: the
    /// nodal coupling's keys would do nothing, so they are refused.
    fn refuse_nodal_keys(&self, i: &ImpactorFile) -> Result<()> {
        let why = "belongs to the nodal coupling; with `contact: surface` the nose is rigid and its force comes from the plate's top surface: remove it";
        let given: [(&str, Option<SourceLocation>); 5] = [
            (
                "youngs_modulus",
                i.youngs_modulus.as_ref().map(|v| self.at(v)),
            ),
            (
                "poisson_ratio",
                i.poisson_ratio.as_ref().map(|v| self.at(v)),
            ),
            ("contact_law", i.contact_law.as_ref().map(|v| self.at(v))),
            (
                "indentation_datum",
                i.indentation_datum.as_ref().map(|v| self.at(v)),
            ),
            ("force_node", i.force_node.as_ref().map(|v| self.at(v))),
        ];
        match given.into_iter().find_map(|(k, at)| at.map(|at| (k, at))) {
            Some((key, at)) => Err(Error::invalid(
                at,
                format!("load.impactor.{key}"),
                "given",
                why,
            )),
            None => Ok(()),
        }
    }

    /// The nodal coupling's contact law (eq. 4 or Johnson's), required.
    fn contact_law(&self, i: &ImpactorFile, plate: &Plate) -> Result<ContactLawChoice> {
        let f = |name: &str| format!("load.impactor.{name}");
        let Some(law) = &i.contact_law else {
            return self.fail(
                &i.mass,
                &f("contact_law"),
                "missing",
                "the nodal contact coupling (the default `contact: nodal`) needs `contact_law: {paper: {length_unit: m}}` or `{johnson: {datum_depth: m}}`; or use `contact: surface`",
            );
        };
        Ok(match &law.value {
            ContactLawFile::Paper { length_unit } => ContactLawChoice::Paper {
                length_unit: self.check(
                    length_unit,
                    &f("contact_law.paper.length_unit"),
                    LENGTH_UNIT,
                )?,
            },
            ContactLawFile::Johnson { datum_depth } => {
                let depth =
                    self.check(datum_depth, &f("contact_law.johnson.datum_depth"), POSITIVE)?;
                if depth > plate.thickness {
                    return self.fail(
                        datum_depth,
                        &f("contact_law.johnson.datum_depth"),
                        shown(depth),
                        format!(
                            "must not exceed the plate thickness {} m",
                            shown(plate.thickness)
                        ),
                    );
                }
                ContactLawChoice::Johnson { datum_depth: depth }
            }
        })
    }

    fn time(&self, t: &TimeFile, kinematics: Kinematics) -> Result<TimeSettings> {
        let limit = match &t.limit {
            None => DEFAULT_TIME_LIMIT,
            Some(l) => self.check(l, "time.limit", POSITIVE)?,
        };
        let end = match &t.end.value {
            EndFile::At(v) => {
                self.read_value(&t.end, "time.end", Some(*v), true);
                if !(v.is_finite() && *v > 0.0) {
                    return self.fail(&t.end, "time.end", shown(*v), POSITIVE.allowed);
                }
                End::At(*v)
            }
            EndFile::AfterContact(a) => End::AfterContact {
                after: self.check(&a.after_contact, "time.end.after_contact", NON_NEGATIVE)?,
                limit,
            },
        };
        if let Some(allow) = &t.allow_unstable_dt {
            self.read(allow, "time.allow_unstable_dt");
        }
        let allow_unstable_dt = t.allow_unstable_dt.as_ref().is_some_and(|a| a.value);
        let dt_location = self.at(&t.dt);
        let dt = match (&t.dt.value.cfl, &t.dt.value.fixed) {
            (Some(c), None) => {
                let rule = if allow_unstable_dt { CFL_UNCHECKED } else { CFL };
                DtChoice::Cfl(self.check(c, "time.dt.cfl", rule)?)
            }
            (None, Some(d)) => DtChoice::Fixed(self.check(d, "time.dt.fixed", POSITIVE)?),
            (c, _) => {
                return self.fail(
                    &t.dt,
                    "time.dt",
                    if c.is_some() { "both cfl and fixed" } else { "neither cfl nor fixed" },
                    "takes exactly one of cfl (a fraction of the stable estimate) or fixed (s), and optionally estimate: element | global",
                )
            }
        };
        let dt_update =
            t.dt.value
                .update
                .as_ref()
                .map_or(DtUpdate::Once, |u| u.value);
        if let Some(update) =
            t.dt.value
                .update
                .as_ref()
                .filter(|u| u.value == DtUpdate::EveryStep)
        {
            let why = match (dt, kinematics) {
                (DtChoice::Fixed(_), _) => Some("a fixed step is never re-estimated: give time.dt.cfl (a fraction of the stable estimate) with update: every-step"),
                (_, Kinematics::Small) => Some("under small kinematics the mesh keeps its shape, so its stable step is the one at the start: use update: once, or kinematics: finite"),
                _ => None,
            };
            if let Some(why) = why {
                return self.fail(update, "time.dt.update", "every-step", why);
            }
        }
        Ok(TimeSettings {
            end,
            dt,
            dt_estimate: t.dt.value.estimate,
            dt_update,
            dt_location,
            allow_unstable_dt,
        })
    }

    fn output(&self, o: &OutputFile, plate: &Plate) -> Result<OutputSettings> {
        let every = match &o.every {
            None => None,
            Some(e) => Some(self.check(e, "output.every", POSITIVE)?),
        };
        let fields_every = match &o.fields {
            None => None,
            Some(f) => Some(self.check(&f.every, "output.fields.every", POSITIVE)?),
        };
        let mut probes = Vec::with_capacity(o.probes.len());
        for (name, p) in &o.probes {
            let valid_name = !name.is_empty()
                && name
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
            if !valid_name {
                return self.fail(
                    &p.x,
                    "output.probes",
                    format!("{name:?}"),
                    "probe names use letters, digits, '_' and '-' only",
                );
            }
            let x = p.x.value;
            let y = p.y.value;
            self.read_number(&p.x, &format!("output.probes.{name}.x"), Some(x));
            self.read_number(&p.y, &format!("output.probes.{name}.y"), Some(y));
            if !(x.is_finite() && (0.0..=plate.length).contains(&x)) {
                return self.fail(
                    &p.x,
                    &format!("output.probes.{name}.x"),
                    shown(x),
                    format!("must lie in [0, plate.length = {}] m", shown(plate.length)),
                );
            }
            if !(y.is_finite() && (0.0..=plate.thickness).contains(&y)) {
                return self.fail(
                    &p.y,
                    &format!("output.probes.{name}.y"),
                    shown(y),
                    format!(
                        "must lie in [0, plate.thickness = {}] m",
                        shown(plate.thickness)
                    ),
                );
            }
            probes.push((name.clone(), [x, y]));
        }
        Ok(OutputSettings {
            every,
            probes,
            fields_every,
        })
    }
}

impl SourceLocation {
    /// A location naming only the file.
    pub fn file(path: &Path) -> SourceLocation {
        SourceLocation {
            file: path.to_path_buf(),
            line: 0,
            column: 0,
        }
    }

    /// Where the parser found `spanned` in `path`.
    pub fn of<T>(path: &Path, spanned: &Spanned<T>) -> SourceLocation {
        SourceLocation {
            file: path.to_path_buf(),
            line: spanned.referenced.line(),
            column: spanned.referenced.column(),
        }
    }
}
