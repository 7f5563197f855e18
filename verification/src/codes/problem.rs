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
/// Its geometries: a plane-strain section of a given width, or a section of a body of
/// revolution (nodes at `(r, z)`, `r >= 0` the distance from the axis).
pub const PLANE_STRAIN: &str = "plane strain";
pub const AXISYMMETRIC: &str = "axisymmetric";

/// `problem.json`: a linear elastic, small-strain problem on a given mesh, one load step.
#[derive(Debug, Clone, Serialize)]
pub struct Problem {
    /// [`STATIC`]: every prescribed displacement applied at once, equilibrium solved.
    pub problem: &'static str,
    /// [`PLANE_STRAIN`] or [`AXISYMMETRIC`]. In the axisymmetric geometry, `x` is the radius
    /// `r`, `y` the axial coordinate `z`, dof 0 radial, forces (loads and nodal forces) the
    /// whole ring's, and the stresses `(s_rr, s_zz, s_tt, s_rz)` (the hoop stress third).
    pub geometry: &'static str,
    /// `impact`'s element name (`q4-full`, `q4-sri`, `q4-1pt`): the adapter names its own
    /// nearest element, or refuses.
    pub element: String,
    /// Out-of-plane thickness of a plane-strain section, m: forces are the whole width's
    /// (none in the axisymmetric geometry).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub width_m: Option<f64>,
    pub material: ProblemMaterial,
    /// Node coordinates, m.
    pub nodes_m: Vec<[f64; 2]>,
    /// Each element's four nodes (0-based, counter-clockwise).
    pub elements: Vec<[usize; 4]>,
    /// `(node, dof, value)`: displacement `value` (m) of `dof` (0 = x, 1 = y) of `node`.
    pub prescribed_m: Vec<(usize, usize, f64)>,
    /// `(node, dof, value)`: force `value` (N, the whole width's) on a free `dof` of `node`.
    #[serde(rename = "loads_N")]
    pub loads_n: Vec<(usize, usize, f64)>,
}

impl Problem {
    /// A static plane-strain problem of `element` on `mesh` (its elements counter-clockwise),
    /// `width_m` thick, of Young's modulus (Pa) and Poisson's ratio `elastic`, with its
    /// prescribed displacements and loads (`(node, dof, value)`, m and N).
    pub fn plane_strain(
        element: &str,
        width_m: f64,
        (youngs_modulus, poisson_ratio): (f64, f64),
        mesh: &impact_solver::mesh::Mesh,
        prescribed_m: Vec<(usize, usize, f64)>,
        loads_n: Vec<(usize, usize, f64)>,
    ) -> Problem {
        Problem {
            problem: STATIC,
            geometry: PLANE_STRAIN,
            element: element.to_string(),
            width_m: Some(width_m),
            material: ProblemMaterial {
                youngs_modulus,
                poisson_ratio,
            },
            nodes_m: mesh.coords.clone(),
            elements: mesh
                .elements
                .iter()
                .map(|e| e.map(|n| n as usize))
                .collect(),
            prescribed_m,
            loads_n,
        }
    }
}

impl Problem {
    /// The static problem of `element` on the section `mesh` of a body of revolution about
    /// the axis `x = axis` (m), `u_r = -u_x`: nodes at `(r, z) = (axis - x, y)`, each element's
    /// nodes reordered to stay counter-clockwise, the x components of the prescribed
    /// displacements and of the loads (the whole ring's) turned radial.
    pub fn about_axis(
        element: &str,
        elastic: (f64, f64),
        (mesh, axis): (&impact_solver::mesh::Mesh, f64),
        prescribed_m: Vec<(usize, usize, f64)>,
        loads_n: Vec<(usize, usize, f64)>,
    ) -> Problem {
        let radial = |v: Vec<(usize, usize, f64)>| -> Vec<(usize, usize, f64)> {
            v.into_iter()
                .map(|(n, d, x)| (n, d, if d == 0 { -x } else { x }))
                .collect()
        };
        let mut p = Problem::plane_strain(
            element,
            1.0,
            elastic,
            mesh,
            radial(prescribed_m),
            radial(loads_n),
        );
        p.geometry = AXISYMMETRIC;
        p.width_m = None;
        p.nodes_m = mesh.coords.iter().map(|x| [axis - x[0], x[1]]).collect();
        p.elements = p
            .elements
            .iter()
            .map(|&[a, b, c, d]| [a, d, c, b])
            .collect();
        p
    }
}

impl Fields {
    /// The fields of a problem [`Problem::about_axis`] made, back on the section: the nodal
    /// displacements and forces (when given), two per node (`u_x = -u_r`, `f_x = -f_r`), and the stresses
    /// at every point in the section's order `[xx, yy, zz (hoop), xy]` (`s_xy = -s_rz`).
    pub fn on_section(&self) -> (Vec<f64>, Option<Vec<f64>>, Vec<[f64; 4]>) {
        let flat = |v: &[[f64; 2]]| -> Vec<f64> { v.iter().flat_map(|&[r, z]| [-r, z]).collect() };
        let stresses = self
            .point_stresses
            .iter()
            .flatten()
            .map(|&[rr, zz, tt, rz]| [rr, zz, tt, -rz])
            .collect();
        let forces = self.nodal_forces.as_deref().map(flat);
        (flat(&self.displacements), forces, stresses)
    }
}

/// `(node, dof, value)` entries, as [`Problem`] holds them, of values by global dof
/// (`2 node + dof`, as the harness's own solvers index them).
pub fn by_node(dofs: impl IntoIterator<Item = (usize, f64)>) -> Vec<(usize, usize, f64)> {
    dofs.into_iter().map(|(d, v)| (d / 2, d % 2, v)).collect()
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
    /// residual at a free one; `null` when the code cannot give it (the checks that read it
    /// show *not produced*).
    #[serde(rename = "nodal_forces_N", default)]
    pub nodal_forces: Option<Vec<[f64; 2]>>,
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
        let forces = f.nodal_forces.as_ref().map_or(nodes, Vec::len);
        let counts = [
            ("displacements_m", f.displacements.len(), nodes, "nodes"),
            ("nodal_forces_N", forces, nodes, "nodes"),
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
            .chain(f.nodal_forces.iter().flatten())
            .flatten()
            .chain(f.point_stresses.iter().flatten().flatten());
        if numbers.clone().any(|x| !x.is_finite()) {
            return Err(format!("{}: a value is not finite", path.display()));
        }
        Ok(f)
    }
}
