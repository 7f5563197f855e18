//! The scene's choices: the enumerations written by name in a scene file (`kebab-case` or
//! `snake_case` words) and kept as they are in the validated [`super::Scene`].

use std::borrow::Cow;

use schemars::{json_schema, JsonSchema, Schema, SchemaGenerator};
use serde::Deserialize;

/// How the plate deforms: small strains and rotations (the paper's model, eqs. 13-16), or
/// finite deformation (updated Lagrangian, Green-Naghdi rate: `ALGORITHM.md` section 3c).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, serde::Serialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum Kinematics {
    /// Small strains and rotations (the paper's model).
    #[default]
    Small,
    /// Finite deformation: updated Lagrangian, Green-Naghdi rate.
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

/// How the ends of the plate (x = 0 and x = L) are held.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, serde::Serialize, JsonSchema)]
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

/// The element formulation; its YAML names are [`ElementKind::name`], read by
/// [`std::str::FromStr`].
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
    /// What the element is, in words (the schema's description of its name).
    pub fn description(self) -> &'static str {
        match self {
            ElementKind::Q4Full => "2x2 Gauss (locks in bending and under plastic flow; kept for comparison).",
            ElementKind::Q4Sri => "Selective-reduced integration / B-bar: deviatoric 2x2, volumetric 1 point (the default).",
            ElementKind::Q4OnePoint => "One point with Flanagan-Belytschko hourglass control (`mesh.hourglass`).",
        }
    }

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

/// The element names, each with what it is: the schema's allowed words.
impl JsonSchema for ElementKind {
    fn schema_name() -> Cow<'static, str> {
        "ElementKind".into()
    }

    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        let kinds: Vec<serde_json::Value> = ElementKind::ALL
            .iter()
            .map(|k| serde_json::json!({"type": "string", "const": k.name(), "description": k.description()}))
            .collect();
        json_schema!({
            "description": "The element formulation: a 4-node quadrilateral.",
            "oneOf": kinds,
        })
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
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, serde::Serialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum Model {
    /// Half the plate, with a symmetry plane at mid-span.
    #[default]
    Half,
    /// The whole plate.
    Full,
}

/// How the surface coupling keeps the nodes out of the nose.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, serde::Serialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum Enforcement {
    /// Predictor-corrector: the forces that put the predicted nodes back on the surface.
    #[default]
    Kinematic,
    /// A spring `k_i` on each node that penetrates.
    Penalty,
}

/// A node on the mid-span line.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, serde::Serialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum MidSpanNode {
    /// The node on the mid-plane.
    #[default]
    MidPlane,
    /// The node on the top surface.
    TopSurface,
}

/// When the stable step is estimated (`time.dt.update`; `ALGORITHM.md` section 6b).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, JsonSchema)]
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

/// Which estimate of the largest eigenvalue sets the stable step (`time.dt.estimate`; see
/// `stable_step`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, JsonSchema)]
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

/// The section modelled: a slice of a plate of width `plate.width` (plane strain, the paper's
/// model), or the half-section of a round plate whose axis is the mid-span line.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, serde::Serialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum Geometry {
    /// A slice of a plate of width `plate.width` in plane strain (the paper's model).
    #[default]
    PlaneStrain,
    /// The half-section of a round plate whose axis is the mid-span line.
    Axisymmetric,
}

impl Geometry {
    /// The name in scenes and summaries.
    pub fn name(self) -> &'static str {
        match self {
            Geometry::PlaneStrain => "plane-strain",
            Geometry::Axisymmetric => "axisymmetric",
        }
    }

    pub fn is_plane_strain(&self) -> bool {
        *self == Geometry::PlaneStrain
    }
}
