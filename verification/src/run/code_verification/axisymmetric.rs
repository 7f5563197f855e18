//! The `axisymmetric` builtin: the closed forms of the axisymmetric geometry (`geometry:
//! axisymmetric`, `solver/ALGORITHM.md` section 3d) for one element, through the solver's own
//! element formulation ([`Axisymmetric`]):
//! - **patch test**: `u_r = a r`, `u_z = b z` (the constant-strain state of a ring; a field
//!   with `u_z` linear in `r` is not in equilibrium without body force) on a distorted 2 x 2
//!   patch away from the axis and on one whose edge lies on it: the exact constant stress at
//!   every integration point and no force on the free interior node;
//! - **uniform radial expansion** of a solid disk through its axis (rim displaced by `U`,
//!   bottom held axially, top free; distorted mapped mesh), static: `u_r = U r / R`,
//!   `u_z = -2 lambda / (lambda + 2 mu) (U / R) z`, exact in the element space;
//! - **Lame's thick-walled cylinder** (inner radius `a`, outer `b`, internal pressure `p`,
//!   `u_z = 0`: a long cylinder in plane strain), static: `u_r = (1 + nu) p a^2 / (E (b^2 -
//!   a^2)) ((1 - 2 nu) r + b^2 / r)` (Timoshenko & Goodier, *Theory of Elasticity*, section 33),
//!   the nodal error on 4, 8, 16 and 32 elements through the wall and its observed order;
//! - **its plastic limit pressure** `p_L = (2 / sqrt 3) sigma_y ln(b / a)` (Hill, *The
//!   Mathematical Theory of Plasticity*, ch. V), perfectly plastic von Mises, by the shared
//!   quasi-static push of `collapse.rs` (the reaction over `2 pi a h`: the work-conjugate of the
//!   inner radial displacement for a uniform pressure on the whole ring).
//!
//! Static solves assemble the element stiffness (`element_stiffness`, through the element's
//! response) densely and solve by Cholesky. Wrong model `plane: true`: the same section in
//! plane strain (the geometry forgotten); it fails the patch stresses, the expansion and Lame.

use std::collections::BTreeMap;

use impact_solver::axisymmetric::{Axisymmetric, RingElement};
use impact_solver::element::{
    element_response, element_stiffness, gather, scatter_add, Formulation, FullQ4, OnePointQ4,
    SelectiveQ4,
};
use impact_solver::material::{Elastic, VonMises};
use impact_solver::mesh::{Mesh, PlateMesh};
use impact_solver::scene::{ElementKind, Hardening, Material, Plasticity};
use serde_json::Value;

use super::collapse::{march, plateau, Push};
use super::driver::{distorted_patch, mapped_mesh};
use super::space_time::element;
use super::thick_cylinder::pressure_history;
use crate::definition::run_data::RunData;
use crate::run::builtin_params::param;

type Params = BTreeMap<String, Value>;

const E: f64 = 200e9;
const NU: f64 = 0.3;
const KAPPA: f64 = 0.05;

/// `body` with the `kind` element on `mesh` about the axis at `axis` (m): the ring's, or with
/// `plane` the plane-strain element (unit width) of the same section.
macro_rules! on_section {
    ($kind:expr, $plane:expr, $mesh:expr, $axis:expr, $f:ident => $body:expr) => {{
        let p_modulus = Elastic::new(E, NU).p_modulus();
        let error = |e: impact_solver::input::error::Error| e.to_string();
        match ($kind, $plane) {
            (ElementKind::Q4Full, false) => {
                let $f = ring::<FullQ4>($mesh, $axis, p_modulus)?;
                $body
            }
            (ElementKind::Q4Sri, false) => {
                let $f = ring::<SelectiveQ4>($mesh, $axis, p_modulus)?;
                $body
            }
            (ElementKind::Q4OnePoint, false) => {
                let $f = ring::<OnePointQ4>($mesh, $axis, p_modulus)?;
                $body
            }
            (ElementKind::Q4Full, true) => {
                let $f = FullQ4::new($mesh, 1.0).map_err(error)?;
                $body
            }
            (ElementKind::Q4Sri, true) => {
                let $f = SelectiveQ4::new($mesh, 1.0).map_err(error)?;
                $body
            }
            (ElementKind::Q4OnePoint, true) => {
                let $f = OnePointQ4::new($mesh, 1.0, KAPPA, p_modulus).map_err(error)?;
                $body
            }
        }
    }};
}

fn ring<F: RingElement>(mesh: &Mesh, axis: f64, p_modulus: f64) -> Result<Axisymmetric<F>, String>
where
    Axisymmetric<F>: Formulation,
{
    Axisymmetric::<F>::new(mesh, axis, KAPPA, p_modulus).map_err(|e| e.to_string())
}

/// The ring's constant-strain field about the axis at `axis` (m): `u_r = a r`, `u_z = b z`
/// on the section's nodes (`u_x = -u_r`, r = axis - x), m.
pub(super) fn patch_field(mesh: &Mesh, axis: f64) -> Vec<f64> {
    mesh.coords
        .iter()
        .flat_map(|x| [-PATCH_STRAIN.0 * (axis - x[0]), PATCH_STRAIN.1 * x[1]])
        .collect()
}

/// The patch field's strains `(a, b)`: `e_rr = e_tt = a`, `e_zz = b`.
const PATCH_STRAIN: (f64, f64) = (1.0e-3, -6.0e-4);

/// The patch test's (free-node force / largest force component, when the nodal `forces` are
/// given (two per node, N); largest stress error / largest exact stress) from them and the
/// stresses at every integration point (Pa, the section's order `[xx, yy, zz (hoop), xy]`).
pub(super) fn patch_metrics(
    forces: Option<&[f64]>,
    stresses: impl Iterator<Item = [f64; 4]>,
) -> (Option<f64>, f64) {
    let (a, b) = PATCH_STRAIN;
    let exact = Elastic::new(E, NU).stress_of(&[a, b, a, 0.0]);
    let scale = exact.iter().fold(0.0_f64, |m, s| m.max(s.abs()));
    let mut stress_error = 0.0_f64;
    for s in stresses {
        for c in 0..4 {
            stress_error = stress_error.max((s[c] - exact[c]).abs() / scale);
        }
    }
    let force = forces.map(|forces| {
        let largest = forces.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        forces[8].hypot(forces[9]) / largest
    });
    (force, stress_error)
}

/// The patch test about the axis at `axis` (m), through `f` ([`patch_metrics`]).
fn patch<F: Formulation>(f: &F, mesh: &Mesh, axis: f64) -> (f64, f64) {
    let elastic = Elastic::new(E, NU);
    let u = patch_field(mesh, axis);
    let mut forces = vec![0.0; u.len()];
    let mut stresses = Vec::new();
    for e in 0..f.n_elements() {
        let ue = gather(f.nodes(e), &u);
        let (fe, _) = element_response(f, &elastic, e, &ue, &mut [(); 4]);
        scatter_add(f.nodes(e), &fe, &mut forces);
        let strains = f.strains(e, &ue);
        stresses.extend(strains.iter().take(F::POINTS).map(|s| elastic.stress_of(s)));
    }
    let (force, stress) = patch_metrics(Some(&forces), stresses.into_iter());
    (force.unwrap_or(f64::NAN), stress)
}

/// The static solution of `f` on `n_nodes` nodes: `prescribed` dofs with their values (m),
/// `loads` (dof, N) on the others.
fn solve_static<F: Formulation>(
    f: &F,
    n_nodes: usize,
    prescribed: &BTreeMap<usize, f64>,
    loads: &[(usize, f64)],
) -> Result<Vec<f64>, String> {
    let elastic = Elastic::new(E, NU);
    let ndof = 2 * n_nodes;
    let mut k = nalgebra::DMatrix::<f64>::zeros(ndof, ndof);
    for e in 0..f.n_elements() {
        let ke = element_stiffness(f, &elastic, e);
        let nodes = f.nodes(e);
        for i in 0..8 {
            for j in 0..8 {
                let (gi, gj) = (
                    2 * nodes[i / 2] as usize + i % 2,
                    2 * nodes[j / 2] as usize + j % 2,
                );
                k[(gi, gj)] += 0.5 * (ke[i][j] + ke[j][i]);
            }
        }
    }
    let free: Vec<usize> = (0..ndof).filter(|d| !prescribed.contains_key(d)).collect();
    let mut rhs = nalgebra::DVector::<f64>::zeros(free.len());
    for &(dof, load) in loads {
        if let Some(i) = free.iter().position(|&d| d == dof) {
            rhs[i] += load;
        }
    }
    for (i, &d) in free.iter().enumerate() {
        for (&p, &value) in prescribed {
            rhs[i] -= k[(d, p)] * value;
        }
    }
    let reduced = nalgebra::DMatrix::from_fn(free.len(), free.len(), |i, j| k[(free[i], free[j])]);
    let Some(cholesky) = reduced.clone().cholesky() else {
        let eig = reduced.symmetric_eigenvalues();
        return Err(format!(
            "axisymmetric: the stiffness of {} free dofs is not positive definite (eigenvalues {:e} to {:e} N/m)",
            free.len(),
            eig.min(),
            eig.max()
        ));
    };
    let solution = cholesky.solve(&rhs);
    let mut u = vec![0.0; ndof];
    for (&p, &value) in prescribed {
        u[p] = value;
    }
    for (i, &d) in free.iter().enumerate() {
        u[d] = solution[i];
    }
    Ok(u)
}

/// The solid disk's radius and height (m) and its rim's radial displacement (m).
pub(super) const DISK: (f64, f64, f64) = (0.05, 0.02, 1.0e-5);

/// The solid disk (axis at `x = radius`, [`DISK`]) on its distorted mapped mesh and its held
/// dofs: the rim displaced radially, the axis held radially, the bottom axially.
pub(super) fn expansion_setup() -> Result<(PlateMesh, BTreeMap<usize, f64>), String> {
    let (radius, height, disp) = DISK;
    let mesh = mapped_mesh(radius, height, 8, 4, 0.05)?;
    let (nx, n_nodes) = (8, mesh.mesh.n_nodes());
    let mut prescribed = BTreeMap::new();
    for n in 0..n_nodes {
        let (i, j) = (n % (nx + 1), n / (nx + 1));
        if i == 0 {
            prescribed.insert(2 * n, -disp);
        }
        if i == nx {
            prescribed.insert(2 * n, 0.0);
        }
        if j == 0 {
            prescribed.insert(2 * n + 1, 0.0);
        }
    }
    Ok((mesh, prescribed))
}

/// The largest nodal error of the section's displacements `u` (m) against the uniform
/// expansion, over the rim's displacement.
pub(super) fn expansion_error(mesh: &PlateMesh, u: &[f64]) -> f64 {
    let (radius, _, disp) = DISK;
    let elastic = Elastic::new(E, NU);
    let axial = -2.0 * elastic.lambda / elastic.p_modulus() * disp / radius;
    let mut error = 0.0_f64;
    for (n, x) in mesh.mesh.coords.iter().enumerate() {
        let exact = [-disp * (radius - x[0]) / radius, axial * x[1]];
        for c in 0..2 {
            error = error.max((u[2 * n + c] - exact[c]).abs() / disp);
        }
    }
    error
}

/// The solid disk expanded by its rim: the largest nodal error over the rim's displacement.
fn expansion(kind: ElementKind, plane: bool) -> Result<f64, String> {
    let (mesh, prescribed) = expansion_setup()?;
    let n_nodes = mesh.mesh.n_nodes();
    let u = on_section!(kind, plane, &mesh.mesh, DISK.0, f => solve_static(&f, n_nodes, &prescribed, &[])?);
    Ok(expansion_error(&mesh, &u))
}

/// The nodes of the inner face (`i = nr`) of a wall of `nr` x 2 elements.
fn inner_face(nr: usize) -> impl Iterator<Item = usize> {
    (0..3).map(move |j| nr + j * (nr + 1))
}

/// Lame's cylinder: inner and outer radius (m), internal pressure (Pa).
pub(super) const LAME: (f64, f64, f64) = (0.01, 0.02, 100e6);

/// The Lame cylinder ([`LAME`]) on `nr` elements through the wall, two rows, height
/// (b - a) / 8 (x from the outer surface, x = 0 at r = b, to the inner: the axis at x = b):
/// the mesh, every axial dof held, and the pressure on the inner face as the whole ring's
/// force (2 pi a h p) on its three nodes, 1:2:1, along -x (dof, N).
pub(super) fn lame_setup(
    nr: usize,
) -> Result<(PlateMesh, BTreeMap<usize, f64>, Vec<(usize, f64)>), String> {
    let (a, b, pressure) = LAME;
    let height = (b - a) / 8.0;
    let mesh = mapped_mesh(b - a, height, nr, 2, 0.0)?;
    let n_nodes = mesh.mesh.n_nodes();
    let prescribed: BTreeMap<usize, f64> = (0..n_nodes).map(|n| (2 * n + 1, 0.0)).collect();
    let total = std::f64::consts::TAU * a * height * pressure;
    let loads: Vec<(usize, f64)> = inner_face(nr)
        .zip([0.25, 0.5, 0.25])
        .map(|(n, share)| (2 * n, -share * total))
        .collect();
    Ok((mesh, prescribed, loads))
}

/// The largest nodal radial error of the section's displacements `u` (m) against Lame's
/// solution, over the largest exact radial displacement.
pub(super) fn lame_error(mesh: &PlateMesh, u: &[f64]) -> f64 {
    let (a, b, pressure) = LAME;
    let c = (1.0 + NU) * pressure * a * a / (E * (b * b - a * a));
    let exact = |r: f64| c * ((1.0 - 2.0 * NU) * r + b * b / r);
    let (mut error, mut largest) = (0.0_f64, 0.0_f64);
    for (n, x) in mesh.mesh.coords.iter().enumerate() {
        let r = b - x[0];
        error = error.max((-u[2 * n] - exact(r)).abs());
        largest = largest.max(exact(r).abs());
    }
    error / largest
}

/// The Lame cylinder on `nr` elements through the wall: [`lame_error`].
fn lame(kind: ElementKind, plane: bool, nr: usize) -> Result<f64, String> {
    let (mesh, prescribed, loads) = lame_setup(nr)?;
    let n_nodes = mesh.mesh.n_nodes();
    // A section without the ring's hoop stiffness has a free radial translation here (every
    // u_z held, no radial support): no solution, an infinite error.
    let Ok(u) = on_section!(kind, plane, &mesh.mesh, LAME.1, f => solve_static(&f, n_nodes, &prescribed, &loads))
    else {
        return Ok(f64::INFINITY);
    };
    Ok(lame_error(&mesh, &u))
}

/// The limit pressure on `nr` elements through the wall over `(2 / sqrt 3) sigma_y ln 2`, and
/// the push's rows (time s, pressure Pa, inner displacement m).
fn limit(kind: ElementKind, plane: bool, nr: usize) -> Result<(f64, Vec<[f64; 3]>), String> {
    let (a, b, sy, rho) = (0.01, 0.02, 250e6, 7850.0);
    let height = (b - a) / 8.0;
    let mut mesh = mapped_mesh(b - a, height, nr, 2, 0.0)?;
    let n_nodes = mesh.mesh.n_nodes();
    for n in 0..n_nodes {
        mesh.fixed_dofs[2 * n] = false;
        mesh.fixed_dofs[2 * n + 1] = true;
    }
    let closed = 2.0 / 3f64.sqrt() * sy * (b / a).ln();
    let mu = E / (2.0 * (1.0 + NU));
    let transit = (b - a) / (E / rho).sqrt();
    let push = Push {
        dofs: inner_face(nr).map(|n| (2 * n, -1.0)).collect(),
        total: 20.0 * closed * a / (2.0 * mu),
        duration: 40.0 * transit,
    };
    let material = VonMises::new(&Material {
        density: rho,
        youngs_modulus: E,
        poisson_ratio: NU,
        plasticity: Some(Plasticity {
            yield_stress: sy,
            hardening: Hardening::Linear {
                tangent_modulus: 0.0,
            },
            rate: None,
        }),
    })
    .ok_or("axisymmetric: not a plastic material")?;
    let mut rows =
        on_section!(kind, plane, &mesh.mesh, b, f => march(&mesh, f, material, rho, &push));
    let area = match plane {
        false => std::f64::consts::TAU * a * height,
        true => height,
    };
    for r in &mut rows {
        r[1] /= area;
    }
    Ok((plateau(&rows) / closed, rows))
}

pub fn axisymmetric(p: &Params) -> Result<RunData, String> {
    let kind = element(p)?;
    let plane = p.get("plane").and_then(Value::as_bool).unwrap_or(false);
    let nr = param(p, "limit_nr", 8.0)? as usize;
    let mut m = BTreeMap::new();
    let mesh = distorted_patch();
    let (force, stress) = on_section!(kind, plane, &mesh, 0.03, f => patch(&f, &mesh, 0.03));
    m.insert("patch_free_node_force_rel".into(), force);
    m.insert("patch_stress_max_rel_error".into(), stress);
    let (force, stress) = on_section!(kind, plane, &mesh, 0.02, f => patch(&f, &mesh, 0.02));
    m.insert("patch_on_axis_free_node_force_rel".into(), force);
    m.insert("patch_on_axis_stress_max_rel_error".into(), stress);
    m.insert("expansion_max_rel_error".into(), expansion(kind, plane)?);
    let errors = [4, 8, 16, 32].map(|nr| lame(kind, plane, nr));
    let errors: Vec<f64> = errors.into_iter().collect::<Result<_, _>>()?;
    for (nr, error) in [4, 8, 16, 32].iter().zip(&errors) {
        m.insert(format!("lame_error_nr{nr}"), *error);
    }
    m.insert("lame_order".into(), (errors[2] / errors[3]).log2());
    let (ratio, rows) = limit(kind, plane, nr)?;
    m.insert("limit_pressure_ratio".into(), ratio);
    Ok(RunData::with_history(m, pressure_history(&rows)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn metrics(element: &str, plane: bool) -> BTreeMap<String, f64> {
        let params: Params = serde_json::from_value(serde_json::json!({
            "element": element, "plane": plane, "limit_nr": 4
        }))
        .unwrap();
        axisymmetric(&params).unwrap().metrics
    }

    #[test]
    fn the_ring_passes_and_the_plane_section_fails() {
        for element in ["q4-full", "q4-sri", "q4-1pt"] {
            let ring = metrics(element, false);
            println!("{element}: {ring:?}");
            let plane = metrics(element, true);
            println!("{element} plane: {plane:?}");
            assert!(ring["patch_free_node_force_rel"] < 1e-12, "{element}");
            assert!(
                ring["patch_on_axis_free_node_force_rel"] < 1e-12,
                "{element}"
            );
            assert!(ring["patch_stress_max_rel_error"] < 1e-12, "{element}");
            assert!(ring["expansion_max_rel_error"] < 1e-10, "{element}");
            assert!(plane["patch_stress_max_rel_error"] > 0.1, "{element}");
            assert!(plane["expansion_max_rel_error"] > 0.1, "{element}");
            assert!(plane["lame_error_nr16"] > 0.1, "{element}");
        }
    }

    /// impact's fields of a section solved with `u` (m, two per node) through `f`, written as
    /// another code writes them about the axis (`r = axis - x`).
    fn fields_about_axis<F: Formulation>(f: &F, u: &[f64]) -> crate::codes::problem::Fields {
        let elastic = Elastic::new(E, NU);
        let mut forces = vec![0.0; u.len()];
        let mut stresses = Vec::new();
        for e in 0..f.n_elements() {
            let ue = gather(f.nodes(e), u);
            let (fe, _) = element_response(f, &elastic, e, &ue, &mut [(); 4]);
            scatter_add(f.nodes(e), &fe, &mut forces);
            let strains = f.strains(e, &ue);
            let points = strains.iter().take(F::POINTS).map(|s| elastic.stress_of(s));
            stresses.push(points.map(|[xx, yy, zz, xy]| [xx, yy, zz, -xy]).collect());
        }
        let radial = |v: &[f64]| v.chunks(2).map(|c| [-c[0], c[1]]).collect();
        crate::codes::problem::Fields {
            point_eqps: None,
            displacements: radial(u),
            nodal_forces: Some(radial(&forces)),
            point_stresses: stresses,
        }
    }

    /// The problem form (`super::super::axisymmetric_problems`) against the builtin: impact's
    /// own solution of each section, written about the axis as another code writes it, gives
    /// the builtin's metrics bit for bit (the limit pressure apart, impact's own push); the
    /// problems hold what the builtin holds, turned radial.
    #[test]
    fn impact_s_own_fields_about_the_axis_give_the_builtin_s_metrics() -> Result<(), String> {
        use super::super::axisymmetric_problems::{from_fields, problems};
        let element = "q4-sri";
        let p: Params =
            serde_json::from_value(serde_json::json!({"element": element, "limit_nr": 4})).unwrap();
        let kind = super::element(&p).unwrap();
        let builtin = axisymmetric(&p).unwrap().metrics;
        let patch = distorted_patch();
        let mut fields = Vec::new();
        for axis in [0.03, 0.02] {
            let u = patch_field(&patch, axis);
            fields.push(on_section!(kind, false, &patch, axis, f => fields_about_axis(&f, &u)));
        }
        let (disk, held) = expansion_setup().unwrap();
        let n = disk.mesh.n_nodes();
        fields.push(on_section!(kind, false, &disk.mesh, DISK.0, f => {
            let u = solve_static(&f, n, &held, &[])?;
            fields_about_axis(&f, &u)
        }));
        for nr in [4, 8, 16, 32] {
            let (wall, held, loads) = lame_setup(nr).unwrap();
            let n = wall.mesh.n_nodes();
            fields.push(on_section!(kind, false, &wall.mesh, LAME.1, f => {
                let u = solve_static(&f, n, &held, &loads)?;
                fields_about_axis(&f, &u)
            }));
        }
        let evaluated = from_fields(&p, &fields).unwrap().metrics;
        assert_eq!(evaluated.len(), builtin.len() - 1, "{evaluated:?}");
        for (k, v) in &evaluated {
            assert_eq!(builtin[k].to_bits(), v.to_bits(), "{k}");
        }
        let problems = problems(&p).unwrap();
        assert_eq!(problems.len(), fields.len());
        let (label, expansion) = &problems[2];
        assert_eq!(*label, "expansion");
        // The rim (x = 0, r = R) pushed out by the builtin's -x displacement: +r.
        assert!(
            expansion.prescribed_m.contains(&(0, 0, DISK.2)),
            "{:?}",
            expansion.prescribed_m
        );
        assert_eq!(expansion.nodes_m[0], [DISK.0, 0.0]);
        assert_eq!(expansion.geometry, crate::codes::problem::AXISYMMETRIC);
        Ok(())
    }
}
