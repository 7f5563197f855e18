//! A builtin's boundary-value problem for another code (issue 38). Some builtins compute, with
//! `impact`'s own element routines, a problem any finite-element code can solve: the patch
//! test is a mesh, a material and prescribed displacements. Such a builtin writes its problem
//! out ([`Problem`], `problem.json`); an adapter that can solve it writes the fields back
//! ([`Fields`], `fields.json`); the builtin's own evaluation turns the fields into the same
//! metrics it computes for `impact`, so the case's checks judge the other code as they judge
//! this one. The contract: `adapters/README.md`, "Problems".

use serde::{Deserialize, Serialize};

/// The problem kind this contract defines so far.
pub const STATIC: &str = "static";
/// Its one geometry so far.
pub const PLANE_STRAIN: &str = "plane strain";

/// `problem.json`: a linear elastic, small-strain problem on a given mesh, one load step.
#[derive(Debug, Clone, Serialize)]
pub struct Problem {
    /// [`STATIC`]: every prescribed displacement applied at once, equilibrium solved.
    pub problem: &'static str,
    /// [`PLANE_STRAIN`].
    pub geometry: &'static str,
    /// `impact`'s element name (`q4-full`, `q4-sri`, `q4-1pt`): the adapter names its own
    /// nearest element, or refuses.
    pub element: String,
    /// Out-of-plane thickness of the section, m: forces are the whole width's.
    pub width_m: f64,
    pub material: ProblemMaterial,
    /// Node coordinates, m.
    pub nodes_m: Vec<[f64; 2]>,
    /// Each element's four nodes (0-based, counter-clockwise).
    pub elements: Vec<[usize; 4]>,
    /// `(node, dof, value)`: displacement `value` (m) of `dof` (0 = x, 1 = y) of `node`.
    pub prescribed_m: Vec<(usize, usize, f64)>,
}

/// Isotropic linear elasticity.
#[derive(Debug, Clone, Serialize)]
pub struct ProblemMaterial {
    #[serde(rename = "youngs_modulus_Pa")]
    pub youngs_modulus: f64,
    pub poisson_ratio: f64,
}

/// `fields.json`: the solved fields.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Fields {
    /// Per node, `(u_x, u_y)`, m.
    #[serde(rename = "displacements_m")]
    pub displacements: Vec<[f64; 2]>,
    /// Per node, the internal force `(f_x, f_y)`, N: the reaction at a prescribed dof, the
    /// residual at a free one.
    #[serde(rename = "nodal_forces_N")]
    pub nodal_forces: Vec<[f64; 2]>,
    /// Per element, per integration point (the code's own points, any number),
    /// `(s_xx, s_yy, s_zz, s_xy)`, Pa.
    #[serde(rename = "point_stresses_Pa")]
    pub point_stresses: Vec<Vec<[f64; 4]>>,
}

impl Fields {
    /// Reads `fields.json`; `Err` names the file and what does not fit `problem`.
    pub fn read(path: &std::path::Path, problem: &Problem) -> Result<Fields, String> {
        let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
        let f: Fields =
            serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
        let (nodes, elements) = (problem.nodes_m.len(), problem.elements.len());
        let counts = [
            ("displacements_m", f.displacements.len(), nodes, "nodes"),
            ("nodal_forces_N", f.nodal_forces.len(), nodes, "nodes"),
            (
                "point_stresses_Pa",
                f.point_stresses.len(),
                elements,
                "elements",
            ),
        ];
        for (key, got, want, what) in counts {
            if got != want {
                return Err(format!(
                    "{}: {key} has {got} entries for the problem's {want} {what}",
                    path.display()
                ));
            }
        }
        if let Some(k) = f.point_stresses.iter().position(Vec::is_empty) {
            return Err(format!(
                "{}: point_stresses_Pa: element {k} has no point",
                path.display()
            ));
        }
        let numbers = f
            .displacements
            .iter()
            .chain(&f.nodal_forces)
            .flatten()
            .chain(f.point_stresses.iter().flatten().flatten());
        if numbers.clone().any(|x| !x.is_finite()) {
            return Err(format!("{}: a value is not finite", path.display()));
        }
        Ok(f)
    }
}
