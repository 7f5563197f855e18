//! A builtin's boundary-value problem for another code (issue 38). Some builtins compute, with
//! `impact`'s own element routines, a problem any finite-element code can solve: the patch
//! test is a mesh, a material and prescribed displacements. Such a builtin writes its problem
//! out ([`Problem`], `problem.json`); an adapter that can solve it writes the fields back
//! ([`Fields`], `fields.json`); the builtin's own evaluation turns the fields into the same
//! metrics it computes for `impact`, so the case's checks judge the other code as they judge
//! this one. The contract: `adapters/README.md`, "Problems".

use serde::{Deserialize, Serialize};

/// The problem kinds: [`STATIC`], every prescribed displacement and load applied at once and
/// equilibrium solved; [`STATIC_PATH`], the same problem followed along a path of load factors
/// (each a static equilibrium, the material's state carried from one to the next);
/// [`STATIC_CONTACT`], a [`STATIC`] problem in which a rigid cylinder is also pressed into the
/// section ([`ProblemIndenter`]).
pub const STATIC: &str = "static";
pub const STATIC_PATH: &str = "static path";
pub const STATIC_CONTACT: &str = "static contact";
/// Its geometries: a plane-strain section of a given width, or a section of a body of
/// revolution (nodes at `(r, z)`, `r >= 0` the distance from the axis).
pub const PLANE_STRAIN: &str = "plane strain";
pub const AXISYMMETRIC: &str = "axisymmetric";

/// `problem.json`: a small-strain problem on a given mesh, linear elastic or elasto-plastic,
/// one load step or a path of them.
#[derive(Debug, Clone, Serialize)]
pub struct Problem {
    /// [`STATIC`], [`STATIC_PATH`] or [`STATIC_CONTACT`].
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
    /// [`STATIC_PATH`] only: the factors (-) that scale every prescribed displacement and
    /// load, in the order they are applied (the first from the unloaded state); the fields are
    /// written at each.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub load_factors: Option<Vec<f64>>,
    /// [`STATIC_CONTACT`] only: the rigid cylinder pressed into the section.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub indenter: Option<ProblemIndenter>,
}

/// A rigid, frictionless cylinder, its axis out of the plane, pressed into a plane-strain
/// section: at the start its lowest point touches the surface at `touch`; in the problem's one
/// step it moves by `displacement`. The contact force on a node of the section is then its
/// internal force (`nodal_forces_N` of [`Fields`]): at a free node the section's elements
/// balance the contact alone.
#[derive(Debug, Clone, Serialize)]
pub struct ProblemIndenter {
    /// Radius, m.
    #[serde(rename = "radius_m")]
    pub radius: f64,
    /// The surface point (x, y) its lowest point touches at the start, m; its centre is
    /// `radius` above.
    #[serde(rename = "touch_m")]
    pub touch: [f64; 2],
    /// Its displacement (x, y), m.
    #[serde(rename = "displacement_m")]
    pub displacement: [f64; 2],
    /// The section's surface nodes it may touch, in order along the surface (0-based).
    pub surface_nodes: Vec<usize>,
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
                plasticity: None,
            },
            nodes_m: mesh.coords.clone(),
            elements: mesh
                .elements
                .iter()
                .map(|e| e.map(|n| n as usize))
                .collect(),
            prescribed_m,
            loads_n,
            load_factors: None,
            indenter: None,
        }
    }

    /// This problem with `indenter` pressed into it ([`STATIC_CONTACT`]).
    pub fn pressed_by(mut self, indenter: ProblemIndenter) -> Problem {
        self.problem = STATIC_CONTACT;
        self.indenter = Some(indenter);
        self
    }

    /// This problem followed along `load_factors` ([`STATIC_PATH`]) in a von Mises material
    /// with linear isotropic hardening.
    pub fn along_path(mut self, plasticity: ProblemPlasticity, load_factors: Vec<f64>) -> Problem {
        self.problem = STATIC_PATH;
        self.material.plasticity = Some(plasticity);
        self.load_factors = Some(load_factors);
        self
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

/// `(node, dof, value)` entries of the held dofs (`fixed_dofs[2 node + dof]`, as a plate mesh
/// marks them), each prescribed to `value(global dof)`, m.
pub fn held(fixed_dofs: &[bool], value: impl Fn(usize) -> f64) -> Vec<(usize, usize, f64)> {
    let dofs = fixed_dofs.iter().enumerate().filter(|(_, fixed)| **fixed);
    by_node(dofs.map(|(d, _)| (d, value(d))))
}

/// Isotropic linear elasticity, and plasticity when given.
#[derive(Debug, Clone, Serialize)]
pub struct ProblemMaterial {
    #[serde(rename = "youngs_modulus_Pa")]
    pub youngs_modulus: f64,
    pub poisson_ratio: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub plasticity: Option<ProblemPlasticity>,
}

/// Von Mises plasticity with linear isotropic hardening: the uniaxial stress-strain curve
/// yields at `yield_stress` and rises with slope `tangent_modulus` beyond (the flow stress
/// `yield_stress + H eps_p`, `H = E E_t / (E - E_t)`), Pa.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct ProblemPlasticity {
    #[serde(rename = "yield_stress_Pa")]
    pub yield_stress: f64,
    #[serde(rename = "tangent_modulus_Pa")]
    pub tangent_modulus: f64,
}

/// `fields.json`: the solved fields (of a [`STATIC_PATH`] problem, `{"steps": [..]}`, the
/// fields at each load factor in order).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Fields {
    /// Per node, `(u_x, u_y)`, m.
    #[serde(rename = "displacements_m")]
    pub displacements: Vec<[f64; 2]>,
    /// Per node, the internal force `(f_x, f_y)`, N: the reaction at a prescribed dof, the
    /// residual at a free one (under an indenter, its contact force); `null` when the code
    /// cannot give it (the checks that read it show *not produced*).
    #[serde(rename = "nodal_forces_N", default)]
    pub nodal_forces: Option<Vec<[f64; 2]>>,
    /// Per element, per integration point (the code's own points, any number),
    /// `(s_xx, s_yy, s_zz, s_xy)`, Pa.
    #[serde(rename = "point_stresses_Pa")]
    pub point_stresses: Vec<Vec<[f64; 4]>>,
    /// Per element, at the same points, the equivalent plastic strain (-) of a problem with
    /// plasticity; absent or `null` when the code cannot give it.
    #[serde(default)]
    pub point_eqps: Option<Vec<Vec<f64>>>,
}

/// `fields.json` of a [`STATIC_PATH`] problem.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PathFields {
    steps: Vec<Fields>,
}

impl Fields {
    /// Reads `fields.json`: one [`Fields`], or one per load factor of a [`STATIC_PATH`]
    /// problem; `Err` names the file and what does not fit `problem`.
    pub fn read(path: &std::path::Path, problem: &Problem) -> Result<Vec<Fields>, String> {
        let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
        let in_file = |e: String| format!("{}: {e}", path.display());
        let steps = match &problem.load_factors {
            None => vec![serde_json::from_str(&text).map_err(|e| in_file(e.to_string()))?],
            Some(factors) => {
                let f: PathFields =
                    serde_json::from_str(&text).map_err(|e| in_file(e.to_string()))?;
                if f.steps.len() != factors.len() {
                    return Err(in_file(format!(
                        "steps has {} entries for the problem's {} load factors",
                        f.steps.len(),
                        factors.len()
                    )));
                }
                f.steps
            }
        };
        for (k, f) in steps.iter().enumerate() {
            let step = match problem.load_factors {
                Some(_) => format!("steps[{k}]: "),
                None => String::new(),
            };
            f.fit(problem).map_err(|e| in_file(step + &e))?;
        }
        Ok(steps)
    }

    /// `Err` names what of these fields does not fit `problem` (counts, empty elements, a
    /// value that is not finite).
    fn fit(&self, problem: &Problem) -> Result<(), String> {
        let (nodes, elements) = (problem.nodes_m.len(), problem.elements.len());
        let forces = self.nodal_forces.as_ref().map_or(nodes, Vec::len);
        let eqps = self.point_eqps.as_ref().map_or(elements, Vec::len);
        let counts = [
            ("displacements_m", self.displacements.len(), nodes, "nodes"),
            ("nodal_forces_N", forces, nodes, "nodes"),
            (
                "point_stresses_Pa",
                self.point_stresses.len(),
                elements,
                "elements",
            ),
            ("point_eqps", eqps, elements, "elements"),
        ];
        for (key, got, want, what) in counts {
            if got != want {
                return Err(format!(
                    "{key} has {got} entries for the problem's {want} {what}"
                ));
            }
        }
        if let Some(k) = self.point_stresses.iter().position(Vec::is_empty) {
            return Err(format!("point_stresses_Pa: element {k} has no point"));
        }
        let points = |k: usize| self.point_stresses[k].len();
        if let Some((k, e)) =
            (self.point_eqps.iter().flatten().enumerate()).find(|(k, e)| e.len() != points(*k))
        {
            return Err(format!(
                "point_eqps: element {k} has {} values for its {} stress points",
                e.len(),
                points(k)
            ));
        }
        let numbers = self
            .displacements
            .iter()
            .chain(self.nodal_forces.iter().flatten())
            .flatten()
            .chain(self.point_stresses.iter().flatten().flatten())
            .chain(self.point_eqps.iter().flatten().flatten());
        if numbers.clone().any(|x| !x.is_finite()) {
            return Err("a value is not finite".into());
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    //! `Fields::read` against `problem.json`'s shape: what fits, and each misfit named.
    use super::*;

    /// One q4 element on the unit square, held at its bottom nodes, as a static problem.
    fn square() -> Problem {
        let mesh = impact_solver::mesh::Mesh {
            coords: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
            elements: vec![[0, 1, 2, 3]],
        };
        let held = by_node((0..4).map(|d| (d, 0.0)));
        Problem::plane_strain("q4-full", 1.0, (2e11, 0.3), &mesh, held, Vec::new())
    }

    fn one_step(eqps: &str) -> String {
        format!(
            r#"{{"displacements_m": [[0,0],[0,0],[0,0],[0,0]], "nodal_forces_N": null,
                "point_stresses_Pa": [[[1,2,3,4],[1,2,3,4]]]{eqps}}}"#
        )
    }

    /// `Fields::read` of `text`; its message without the path.
    fn read(problem: &Problem, text: &str) -> Result<Vec<Fields>, String> {
        static CALLS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
        let call = CALLS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let name = format!("fields-read-{}-{call}.json", std::process::id());
        let path = std::env::temp_dir().join(name);
        std::fs::write(&path, text).unwrap();
        let fields = Fields::read(&path, problem);
        std::fs::remove_file(&path).unwrap();
        fields.map_err(|e| e.rsplit(".json: ").next().unwrap().to_string())
    }

    #[test]
    fn a_static_problem_reads_one_set_of_fields() {
        let f = read(&square(), &one_step("")).unwrap();
        assert_eq!((f.len(), f[0].point_stresses[0].len()), (1, 2));
        assert!(f[0].nodal_forces.is_none() && f[0].point_eqps.is_none());
        let short = one_step("").replacen("[0,0],", "", 1);
        let e = read(&square(), &short).unwrap_err();
        assert_eq!(e, "displacements_m has 3 entries for the problem's 4 nodes");
    }

    #[test]
    fn a_path_reads_one_set_per_load_factor_and_names_the_step_that_misfits() {
        let plastic = ProblemPlasticity {
            yield_stress: 2.5e8,
            tangent_modulus: 2e10,
        };
        let path = square().along_path(plastic, vec![0.5, 1.0]);
        let json = serde_json::to_value(&path).unwrap();
        assert_eq!(json["problem"], "static path");
        assert_eq!(json["load_factors"], serde_json::json!([0.5, 1.0]));
        assert_eq!(json["material"]["plasticity"]["tangent_modulus_Pa"], 2e10);
        let good = one_step(r#", "point_eqps": [[0.0, 0.1]]"#);
        let f = read(&path, &format!(r#"{{"steps": [{good}, {good}]}}"#)).unwrap();
        assert_eq!(f[1].point_eqps, Some(vec![vec![0.0, 0.1]]));
        let e = read(&path, &format!(r#"{{"steps": [{good}]}}"#)).unwrap_err();
        assert_eq!(e, "steps has 1 entries for the problem's 2 load factors");
        let bad = one_step(r#", "point_eqps": [[0.0]]"#);
        let e = read(&path, &format!(r#"{{"steps": [{good}, {bad}]}}"#)).unwrap_err();
        assert_eq!(
            e,
            "steps[1]: point_eqps: element 0 has 1 values for its 2 stress points"
        );
        assert!(
            read(&path, &good).is_err(),
            "a path's fields need their steps"
        );
        let static_json = serde_json::to_value(square()).unwrap();
        assert!(static_json.get("load_factors").is_none());
        assert!(static_json["material"].get("plasticity").is_none());
    }
}
