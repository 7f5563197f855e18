//! The `finite-strain-path` builtin: homogeneous finite deformation of a block through the
//! solver's elements and materials (`kinematics: finite`, or `small` as the wrong model),
//! against closed forms. Every node of a distorted 4 x 4 mesh is moved to `x = F(s) X` at
//! each of `steps` steps (`s` from 0 to 1): no inertia, only the element kernels (gradient,
//! the Green-Naghdi step, the material, the forces `w_ref P dN/dX`).
//!
//! Paths and their references (written here, from the mechanics, not from the solver):
//! - `rotation`: a uniaxial-strain stretch (elastic, 20 % of the steps), then a rigid rotation
//!   through `angle` rad: the Cauchy stress is the stretched one rotated, `R sigma_1 R^T`,
//!   and the strain energy does not change (objectivity).
//! - `simple-shear`: `F = [[1, gamma], [0, 1]]` to `gamma`. The Green-Naghdi rate's unrotated
//!   strain has a closed form (with `tan(beta) = gamma / 2`, `R` the rotation by `-beta`):
//!   `e^_xx = -e^_yy = 2 ln(cos beta)`, `e^_xy = 2 beta - tan(beta)` (tensor shear; from
//!   `R^T D R` integrated in `beta`). Elastic: Dienes' (1979) stresses
//!   `sigma_xx = -sigma_yy = 4 mu [cos(2 beta) ln(cos beta) + beta sin(2 beta) - sin^2(beta)]`,
//!   `sigma_xy = 2 mu cos(2 beta) [2 beta - 2 tan(2 beta) ln(cos beta) - tan(beta)]`.
//!   Elastic-plastic (linear hardening): an independent radial return ([`ReferenceJ2`])
//!   driven along that strain path in [`REFERENCE_STEPS`] steps, rotated by `R`.
//! - `compression`: uniaxial strain `F = diag(1, lambda)` to `lambda = stretch`: no rotation,
//!   so the unrotated strain is the logarithmic one, `e = ln(lambda)` in `yy`, and with linear
//!   hardening (plastic modulus `H`) the Kirchhoff stress has the closed form of uniaxial
//!   strain: `q = min(2 mu |e|, sigma_y + H k)`, `k = (2 mu |e| - sigma_y) / (3 mu + H)` past
//!   yield, `tau_yy = K e + sign(e) 2/3 q`, `tau_xx = tau_zz = K e - sign(e) q / 3`; the true
//!   (Cauchy) stress is `tau / lambda`.
//!
//! In the axisymmetric geometry (`geometry: axisymmetric`; the block's right edge is the axis,
//! so its elements touch it, and each node moves to `r = lambda_r R`), where a homogeneous
//! field has the hoop stretch equal to the radial one:
//! - `radial-expansion`: `lambda_r = lambda_theta = 1 + (stretch - 1) s`, `lambda_z = 1`;
//! - `upsetting`: `lambda_z = 1 + (stretch - 1) s`, `lambda_r = lambda_theta = lambda_z^-1/2`
//!   (isochoric: the large compression of a billet).
//!   Both are proportional paths in principal axes that never rotate: the unrotated strain is
//!   the logarithmic one `(ln lambda_r, ln lambda_z, ln lambda_theta)`, and one radial return
//!   from the virgin state gives the Kirchhoff stress exactly (linear hardening, a fixed
//!   direction); the Cauchy stress is `tau / J`, `J = lambda_r^2 lambda_z`. The top face's
//!   axial force is `sigma_zz pi r^2` on the current radius `r = lambda_r R` (whole ring).
//!
//! Metrics: the largest stress error over the path (relative to the largest reference stress),
//! the spread over the points (a homogeneous field must stay homogeneous), the strain energy
//! change (rotation), and the right edge's force resultant against `sigma n l` on the current
//! edge (`n l = (1, -gamma) H` in simple shear): small kinematics puts it on the reference
//! edge.

use std::collections::BTreeMap;

use impact_solver::axisymmetric::{Axisymmetric, RingElement};
use impact_solver::element::{Formulation, FullQ4, OnePointQ4, SelectiveQ4};
use impact_solver::finite_element::{FiniteResponse, UpdatedLagrangian};
use impact_solver::finite_material::Finite;
use impact_solver::input::geometry::Geometry;
use impact_solver::integrator::PlateModel;
use impact_solver::material::{ConstitutiveModel, Elastic, Stress, VonMises};
use impact_solver::mesh::PlateMesh;
use impact_solver::model::AnyFormulation;
use impact_solver::scene::{ElementKind, Hardening, Material, Plasticity};
use serde_json::Value;

use super::driver::mapped_mesh;
use super::plastic_material::{plastic_material, PlasticMaterial};
use super::space_time::element;
use crate::definition::run_data::RunData;
use crate::run::builtin_params::{param, param_geometry};

type Params = BTreeMap<String, Value>;

/// Steps of the reference radial return along the closed-form strain path.
const REFERENCE_STEPS: usize = 200_000;
/// Block side, m.
const SIDE: f64 = 0.01;

#[derive(Debug, Clone, Copy, PartialEq)]
enum Path {
    Rotation { angle: f64, stretch: f64 },
    SimpleShear { gamma: f64 },
    Compression { stretch: f64 },
    RadialExpansion { stretch: f64 },
    Upsetting { stretch: f64 },
}

impl Path {
    fn of(p: &Params) -> Result<Path, String> {
        match p
            .get("path")
            .and_then(Value::as_str)
            .unwrap_or("simple-shear")
        {
            "rotation" => Ok(Path::Rotation {
                angle: param(p, "angle", 2.0)?,
                stretch: param(p, "stretch", 1.001)?,
            }),
            "simple-shear" => Ok(Path::SimpleShear {
                gamma: param(p, "gamma", 10.0)?,
            }),
            "compression" => Ok(Path::Compression {
                stretch: param(p, "stretch", 0.5)?,
            }),
            "radial-expansion" => Ok(Path::RadialExpansion {
                stretch: param(p, "stretch", 1.5)?,
            }),
            "upsetting" => Ok(Path::Upsetting {
                stretch: param(p, "stretch", 0.5)?,
            }),
            other => Err(format!(
                "param path: {other:?} is not rotation, simple-shear, compression, radial-expansion or upsetting"
            )),
        }
    }

    /// Whether the path is one of the axisymmetric geometry's.
    fn is_ring(self) -> bool {
        matches!(self, Path::RadialExpansion { .. } | Path::Upsetting { .. })
    }

    /// The rotation path's stretch along x and angle (rad) at `s`.
    fn stretch_and_angle(angle: f64, stretch: f64, s: f64) -> (f64, f64) {
        if s < 0.2 {
            (1.0 + (stretch - 1.0) * s / 0.2, 0.0)
        } else {
            (stretch, angle * (s - 0.2) / 0.8)
        }
    }

    /// `F` at `s` in [0, 1], row-major, and the path's variable there (the angle, gamma or
    /// the logarithmic strain).
    fn deformation(self, s: f64) -> ([f64; 4], f64) {
        match self {
            Path::Rotation { angle, stretch } => {
                let (a, theta) = Path::stretch_and_angle(angle, stretch, s);
                let (sn, c) = theta.sin_cos();
                ([c * a, -sn, sn * a, c], theta)
            }
            Path::SimpleShear { gamma } => ([1.0, gamma * s, 0.0, 1.0], gamma * s),
            Path::Compression { stretch } => {
                let l = 1.0 + (stretch - 1.0) * s;
                ([1.0, 0.0, 0.0, l], l.ln())
            }
            Path::RadialExpansion { stretch } => {
                let l = 1.0 + (stretch - 1.0) * s;
                ([l, 0.0, 0.0, 1.0], l.ln())
            }
            Path::Upsetting { stretch } => {
                let l = 1.0 + (stretch - 1.0) * s;
                ([1.0 / l.sqrt(), 0.0, 0.0, l], l.ln())
            }
        }
    }
}

/// One recorded step: the path's variable, the Cauchy stress of point 0 of element 0 (Pa), the
/// largest difference of any point's from it (Pa), the strain energy (J), the right edge's
/// force resultant and the top face's axial force (N).
#[derive(Debug, Clone, Copy)]
struct Row {
    /// The path parameter in [0, 1].
    s: f64,
    x: f64,
    stress: Stress,
    spread: f64,
    strain_energy: f64,
    edge: [f64; 2],
    top: f64,
    /// The left edge's x force (the ring's outer face, N).
    outer: f64,
}

/// Moves every node to `F(s) (X - origin) + origin` in `steps` steps, recording each (`origin`
/// on the x axis, m: 0 in plane strain, the axis in the ring).
fn drive<F: Formulation, M: ConstitutiveModel>(
    mut model: PlateModel<F, M>,
    mesh: &PlateMesh,
    (path, origin): (Path, f64),
    steps: usize,
) -> Vec<Row> {
    let coords = &mesh.mesh.coords;
    let right = coords.iter().map(|p| p[0]).fold(f64::MIN, f64::max);
    let top = coords.iter().map(|p| p[1]).fold(f64::MIN, f64::max);
    let left = coords.iter().map(|p| p[0]).fold(f64::MAX, f64::min);
    let mut u = vec![0.0; 2 * coords.len()];
    let mut f = vec![0.0; u.len()];
    let mut rows = Vec::with_capacity(steps + 1);
    for k in 0..=steps {
        let s = k as f64 / steps as f64;
        let (g, x) = path.deformation(s);
        for (n, p) in coords.iter().enumerate() {
            let x = p[0] - origin;
            u[2 * n] = (g[0] - 1.0) * x + g[1] * p[1];
            u[2 * n + 1] = g[2] * x + (g[3] - 1.0) * p[1];
        }
        let energy = model.internal_forces(&u, &mut f);
        let stress = model.point_stress(0, 0, &u);
        let mut spread: f64 = 0.0;
        for e in 0..model.formulation.n_elements() {
            for p in 0..F::POINTS {
                let s = model.point_stress(e, p, &u);
                for c in 0..4 {
                    spread = spread.max((s[c] - stress[c]).abs());
                }
            }
        }
        let (mut edge, mut top_force, mut outer) = ([0.0; 2], 0.0, 0.0);
        for (n, p) in coords.iter().enumerate() {
            if (p[0] - right).abs() < 1e-12 * right {
                edge[0] += f[2 * n];
                edge[1] += f[2 * n + 1];
            }
            if (p[1] - top).abs() < 1e-12 * top {
                top_force += f[2 * n + 1];
            }
            if (p[0] - left).abs() < 1e-12 * right {
                outer += f[2 * n];
            }
        }
        rows.push(Row {
            s,
            x,
            stress,
            spread,
            strain_energy: energy.strain,
            edge,
            top: top_force,
            outer,
        });
    }
    rows
}

/// The solver's von Mises material (linear hardening; `elastic`: a yield stress no path
/// reaches).
fn solver_material(m: &PlasticMaterial, elastic: bool) -> VonMises {
    VonMises::new(&Material {
        density: m.density,
        youngs_modulus: m.youngs_modulus,
        poisson_ratio: m.poisson_ratio,
        plasticity: Some(Plasticity {
            yield_stress: if elastic { 1e300 } else { m.yield_stress },
            hardening: Hardening::Linear {
                tangent_modulus: m.tangent_modulus,
            },
            rate: None,
        }),
    })
    .expect("a rate-independent plastic material")
}

/// An independent radial return (plane strain, von Mises, linear isotropic hardening) for the
/// reference paths: plastic strain (tensor shear, `zz` included) and equivalent plastic strain.
struct ReferenceJ2 {
    mu: f64,
    bulk: f64,
    yield_stress: f64,
    /// Plastic modulus H, Pa.
    hardening: f64,
    plastic: [f64; 4],
    eqps: f64,
}

impl ReferenceJ2 {
    fn new(m: &PlasticMaterial, elastic: bool) -> ReferenceJ2 {
        let (e, nu, et) = (m.youngs_modulus, m.poisson_ratio, m.tangent_modulus);
        ReferenceJ2 {
            mu: e / (2.0 * (1.0 + nu)),
            bulk: e / (3.0 * (1.0 - 2.0 * nu)),
            yield_stress: if elastic {
                f64::INFINITY
            } else {
                m.yield_stress
            },
            hardening: e * et / (e - et),
            plastic: [0.0; 4],
            eqps: 0.0,
        }
    }

    /// The stress `[xx, yy, zz, xy]` (Pa) at the total strain `e` (tensor shear), updating
    /// the plastic state (backward Euler).
    fn stress(&mut self, e: [f64; 4]) -> [f64; 4] {
        let el: [f64; 4] = std::array::from_fn(|c| e[c] - self.plastic[c]);
        let vol = el[0] + el[1] + el[2];
        let mut s = [0.0; 4];
        for c in 0..3 {
            s[c] = 2.0 * self.mu * (el[c] - vol / 3.0);
        }
        s[3] = 2.0 * self.mu * el[3];
        let norm = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2] + 2.0 * s[3] * s[3]).sqrt();
        let q = (1.5f64).sqrt() * norm;
        let over = q - (self.yield_stress + self.hardening * self.eqps);
        if over > 0.0 {
            let dk = over / (3.0 * self.mu + self.hardening);
            for c in 0..4 {
                let n = 1.5 * s[c] / q;
                self.plastic[c] += dk * n;
                s[c] -= 2.0 * self.mu * dk * n;
            }
            self.eqps += dk;
        }
        let p = self.bulk * vol;
        [s[0] + p, s[1] + p, s[2] + p, s[3]]
    }
}

/// `R t R^T` for the rotation by `theta` (tensor shear).
fn rotated(t: [f64; 4], theta: f64) -> [f64; 4] {
    let (s, c) = theta.sin_cos();
    let (cc, ss, cs) = (c * c, s * s, c * s);
    [
        cc * t[0] + ss * t[1] - 2.0 * cs * t[3],
        ss * t[0] + cc * t[1] + 2.0 * cs * t[3],
        t[2],
        cs * (t[0] - t[1]) + (cc - ss) * t[3],
    ]
}

/// The Green-Naghdi unrotated strain of simple shear at `gamma` (tensor shear) and the
/// rotation angle `-beta`.
fn shear_strain_path(gamma: f64) -> ([f64; 4], f64) {
    let beta = (gamma / 2.0).atan();
    let l = 2.0 * beta.cos().ln();
    ([l, -l, 0.0, 2.0 * beta - beta.tan()], -beta)
}

/// Dienes' (1979) elastic Green-Naghdi stresses of simple shear at `gamma`, Pa.
fn dienes_green_naghdi(mu: f64, gamma: f64) -> [f64; 4] {
    let beta = (gamma / 2.0).atan();
    let (lc, s2, c2) = (beta.cos().ln(), (2.0 * beta).sin(), (2.0 * beta).cos());
    let xx = 4.0 * mu * (c2 * lc + beta * s2 - beta.sin().powi(2));
    let xy = 2.0 * mu * c2 * (2.0 * beta - 2.0 * (2.0 * beta).tan() * lc - beta.tan());
    [xx, -xx, 0.0, xy]
}

/// The reference Cauchy stress at each row, in order.
fn reference(path: Path, m: &PlasticMaterial, elastic: bool, rows: &[Row]) -> Vec<[f64; 4]> {
    let el = Elastic::new(m.youngs_modulus, m.poisson_ratio);
    match path {
        Path::Rotation { angle, stretch } => rows
            .iter()
            .map(|r| {
                // The elastic uniaxial strain along x (the closed form's yy and xx swapped),
                // rotated.
                let (a, theta) = Path::stretch_and_angle(angle, stretch, r.s);
                let t = uniaxial_strain(m, true, a.ln());
                rotated([t[1] / a, t[0] / a, t[2] / a, 0.0], theta)
            })
            .collect(),
        Path::SimpleShear { .. } if elastic => rows
            .iter()
            .map(|r| dienes_green_naghdi(el.mu, r.x))
            .collect(),
        Path::SimpleShear { .. } => {
            let mut j2 = ReferenceJ2::new(m, false);
            let mut out = Vec::with_capacity(rows.len());
            let last = rows.last().map_or(0.0, |r| r.x);
            let mut k = 0usize;
            for r in rows {
                // March the reference to this row's gamma.
                let target = (r.x / last * REFERENCE_STEPS as f64).round() as usize;
                let mut s = [0.0; 4];
                while k <= target {
                    let (e, _) = shear_strain_path(last * k as f64 / REFERENCE_STEPS as f64);
                    s = j2.stress(e);
                    k += 1;
                }
                let (_, theta) = shear_strain_path(r.x);
                out.push(rotated(s, theta));
            }
            out
        }
        Path::Compression { .. } => rows
            .iter()
            .map(|r| uniaxial_strain(m, elastic, r.x).map(|t| t / r.x.exp()))
            .collect(),
        Path::RadialExpansion { .. } | Path::Upsetting { .. } => rows
            .iter()
            .map(|r| {
                let (g, _) = path.deformation(r.s);
                let (radial, axial) = (g[0], g[3]);
                let e = [radial.ln(), axial.ln(), radial.ln(), 0.0];
                let j = radial * radial * axial;
                ReferenceJ2::new(m, elastic).stress(e).map(|t| t / j)
            })
            .collect(),
    }
}

/// The Kirchhoff stress of uniaxial strain `e` in `yy` (linear hardening), Pa.
fn uniaxial_strain(m: &PlasticMaterial, elastic: bool, e: f64) -> [f64; 4] {
    let j2 = ReferenceJ2::new(m, elastic);
    let two_mu_e = 2.0 * j2.mu * e.abs();
    let q = if two_mu_e <= j2.yield_stress {
        two_mu_e
    } else {
        let k = (two_mu_e - j2.yield_stress) / (3.0 * j2.mu + j2.hardening);
        j2.yield_stress + j2.hardening * k
    };
    let (p, sign) = (j2.bulk * e, e.signum());
    [
        p - sign * q / 3.0,
        p + sign * 2.0 * q / 3.0,
        p - sign * q / 3.0,
        0.0,
    ]
}

pub fn finite_strain_path(p: &Params) -> Result<RunData, String> {
    let path = Path::of(p)?;
    let material = plastic_material(p)?;
    let elastic = p.get("material").and_then(Value::as_str) != Some("plastic");
    let finite = match p
        .get("kinematics")
        .and_then(Value::as_str)
        .unwrap_or("finite")
    {
        "finite" => true,
        "small" => false,
        other => {
            return Err(format!(
                "param kinematics: {other:?} is not small or finite"
            ))
        }
    };
    let steps = param(p, "steps", 2000.0)? as usize;
    let mesh = mapped_mesh(SIDE, SIDE, 4, 4, 0.1)?;
    let kind = element(p)?;
    let ring = param_geometry(p, Geometry::PlaneStrain)? == Geometry::Axisymmetric;
    if ring != path.is_ring() {
        return Err(format!("param path: {path:?} does not run in this geometry (radial-expansion and upsetting are the axisymmetric geometry's, the others plane strain's)"));
    }
    // The ring's axis: the block's right edge.
    let axis = mesh
        .mesh
        .coords
        .iter()
        .map(|c| c[0])
        .fold(f64::MIN, f64::max);
    let e = Elastic::new(material.youngs_modulus, material.poisson_ratio);
    let rows = |steps| -> Result<Vec<Row>, String> {
        let m = solver_material(&material, elastic);
        let rho = material.density;
        if ring {
            let how = RingRun {
                mesh: &mesh,
                axis,
                p_modulus: e.p_modulus(),
                finite,
            };
            return match kind {
                ElementKind::Q4Full => how.rows::<FullQ4, _>(m, rho, (path, steps)),
                ElementKind::Q4Sri => how.rows::<SelectiveQ4, _>(m, rho, (path, steps)),
                ElementKind::Q4OnePoint => how.rows::<OnePointQ4, _>(m, rho, (path, steps)),
            };
        }
        let any =
            AnyFormulation::new(kind, &mesh.mesh, 1.0, 0.05, &e).map_err(|e| e.to_string())?;
        Ok(impact_solver::with_formulation!(any, f => if finite {
            drive(PlateModel::new(UpdatedLagrangian(f), Finite(m), &mesh, rho), &mesh, (path, 0.0), steps)
        } else {
            drive(PlateModel::new(f, m, &mesh, rho), &mesh, (path, 0.0), steps)
        }))
    };
    let fine = rows(steps)?;
    let coarse = rows(steps / 2)?;
    let error = |rows: &[Row]| {
        let refs = reference(path, &material, elastic, rows);
        let scale = refs.iter().flatten().fold(0.0f64, |a, b| a.max(b.abs()));
        let worst = rows
            .iter()
            .zip(&refs)
            .flat_map(|(r, s)| (0..4).map(move |c| (r.stress[c] - s[c]).abs()))
            .fold(0.0f64, f64::max);
        (worst / scale, refs, scale)
    };
    let (err_fine, refs, scale) = error(&fine);
    let (err_coarse, _, _) = error(&coarse);
    let mut m = BTreeMap::new();
    m.insert("stress_error".into(), err_fine);
    m.insert("stress_error_half_steps".into(), err_coarse);
    m.insert("observed_order".into(), (err_coarse / err_fine).log2());
    let spread = fine.iter().map(|r| r.spread).fold(0.0f64, f64::max);
    m.insert("spread".into(), spread / scale);
    m.insert("reference_scale_Pa".into(), scale);
    insert_path_metrics(&mut m, (path, axis), &fine);
    Ok(RunData::with_history(m, history(path, &fine, &refs, e.mu)))
}

/// How the block runs in the axisymmetric geometry: about the axis at `axis` (m).
struct RingRun<'a> {
    mesh: &'a PlateMesh,
    axis: f64,
    /// Pa (the one-point element's hourglass stiffness).
    p_modulus: f64,
    finite: bool,
}

impl RingRun<'_> {
    /// The rows of `path` in `steps` steps with the ring element `E` and the material `m`
    /// (density `rho`, kg/m^3).
    fn rows<E: RingElement, M: ConstitutiveModel>(
        &self,
        m: M,
        rho: f64,
        (path, steps): (Path, usize),
    ) -> Result<Vec<Row>, String>
    where
        Axisymmetric<E>: FiniteResponse,
    {
        let f = Axisymmetric::<E>::new(&self.mesh.mesh, self.axis, 0.05, self.p_modulus)
            .map_err(|e| e.to_string())?;
        let how = (path, self.axis);
        Ok(if self.finite {
            let model = PlateModel::new(UpdatedLagrangian(f), Finite(m), self.mesh, rho);
            drive(model, self.mesh, how, steps)
        } else {
            drive(PlateModel::new(f, m, self.mesh, rho), self.mesh, how, steps)
        })
    }
}

/// Metrics of one path: the strain energy change under the rotation; the right edge's force
/// against the current edge's `sigma n l` (and the reference edge's, the small-strain answer);
/// in the ring the top face's force against `sigma_zz` on its current area (`outer_radius`,
/// m, the block's reference radius).
fn insert_path_metrics(
    m: &mut BTreeMap<String, f64>,
    (path, outer_radius): (Path, f64),
    rows: &[Row],
) {
    let last = rows[rows.len() - 1];
    match path {
        Path::Rotation { .. } => {
            let stretched = rows[rows.iter().position(|r| r.s >= 0.2).unwrap_or(0)];
            m.insert(
                "strain_energy_change".into(),
                (last.strain_energy - stretched.strain_energy).abs() / stretched.strain_energy,
            );
        }
        Path::SimpleShear { gamma } => {
            let s = last.stress;
            let current = [(s[0] - gamma * s[3]) * SIDE, (s[3] - gamma * s[1]) * SIDE];
            let size = (current[0].hypot(current[1])).max(f64::MIN_POSITIVE);
            let miss = (last.edge[0] - current[0]).hypot(last.edge[1] - current[1]);
            m.insert("edge_force_error".into(), miss / size);
        }
        Path::Compression { .. } => {}
        Path::RadialExpansion { .. } | Path::Upsetting { .. } => {
            // The top face's current area: the block's outer radius (its left edge, from the
            // axis at its right edge) stretched.
            let (g, _) = path.deformation(last.s);
            let relative = |got: f64, expected: f64| {
                (got - expected).abs() / expected.abs().max(f64::MIN_POSITIVE)
            };
            let radius = g[0] * outer_radius;
            let area = std::f64::consts::PI * radius * radius;
            m.insert(
                "top_force_error".into(),
                relative(last.top, last.stress[1] * area),
            );
            // The outer face (outward normal -x): -sigma_rr 2 pi r h on its current area.
            let face = std::f64::consts::TAU * radius * g[3] * SIDE;
            m.insert(
                "outer_force_error".into(),
                relative(last.outer, -last.stress[0] * face),
            );
        }
    }
}

/// The history: the path's variable (in `time_s`, the plots' x), the computed and reference
/// `xx` and `xy` stresses, and for simple shear the Jaumann rate's `mu sin(gamma)`.
fn history(path: Path, rows: &[Row], refs: &[[f64; 4]], mu: f64) -> impact_solver::History {
    let mut columns: Vec<String> = [
        "time_s",
        "sxx_Pa",
        "sxx_reference_Pa",
        "syy_Pa",
        "syy_reference_Pa",
        "sxy_Pa",
        "sxy_reference_Pa",
    ]
    .map(String::from)
    .to_vec();
    let shear = matches!(path, Path::SimpleShear { .. });
    if shear {
        columns.push("sxy_jaumann_Pa".into());
    }
    let every = (rows.len() / 400).max(1);
    let mut values = Vec::new();
    for (r, s) in rows.iter().zip(refs).step_by(every) {
        values.extend([r.x, r.stress[0], s[0], r.stress[1], s[1], r.stress[3], s[3]]);
        if shear {
            values.push(mu * r.x.sin());
        }
    }
    impact_solver::History { columns, values }
}

#[cfg(test)]
mod tests {
    //! The references' own identities, and the wrong models the case's checks fail.
    use super::*;

    fn run(extra: &[(&str, Value)]) -> BTreeMap<String, f64> {
        let mut p = Params::new();
        p.insert("steps".into(), Value::from(400));
        for (k, v) in extra {
            p.insert(k.to_string(), v.clone());
        }
        finite_strain_path(&p).unwrap().metrics
    }

    /// Dienes' stresses are the unrotated strain path's elastic stresses rotated (two
    /// writings of one closed form agree to round-off).
    #[test]
    fn dienes_is_the_rotated_unrotated_path() {
        let mu = 80e9;
        for gamma in [0.3, 2.0, 10.0] {
            let (e, theta) = shear_strain_path(gamma);
            let s = rotated(e.map(|x| 2.0 * mu * x), theta);
            let d = dienes_green_naghdi(mu, gamma);
            for c in [0, 1, 3] {
                assert!((s[c] - d[c]).abs() < 1e-12 * mu, "{gamma}: {s:?} {d:?}");
            }
        }
    }

    /// Small kinematics fails every path: the rotation leaves a stress error of order one,
    /// the simple shear's stress grows linearly (mu gamma) and its edge force sits on the
    /// reference edge.
    #[test]
    fn small_kinematics_fails_the_checks() {
        let small = Value::from("small");
        let rot = run(&[
            ("path", Value::from("rotation")),
            ("kinematics", small.clone()),
        ]);
        assert!(rot["stress_error"] > 0.1, "{rot:?}");
        let shear = run(&[("kinematics", small)]);
        assert!(
            shear["stress_error"] > 0.5 && shear["edge_force_error"] > 0.5,
            "{shear:?}"
        );
        let right = run(&[("path", Value::from("rotation"))]);
        assert!(right["stress_error"] < 1e-10, "{right:?}");
    }

    /// In the ring, small kinematics misses both paths by order one (measured at 2000 steps:
    /// radial expansion to 1.5, stress 1.77, top force 0.56; plastic upsetting to 0.5, stress
    /// 5.87, top force 0.50), and finite kinematics passes them. (Two slips measured by
    /// editing the solver, 2026-11-26: the hoop stress on the hoop row without `/ F_t`
    /// leaves the stresses exact but misses the outer face's force by 7.6e-2; the hoop strain
    /// left at zero misses the stress by 0.55.)
    #[test]
    fn small_kinematics_fails_the_ring_paths() {
        let ring = Value::from("axisymmetric");
        for (path, material) in [("radial-expansion", "elastic"), ("upsetting", "plastic")] {
            let of = |kinematics: &str| {
                run(&[
                    ("path", Value::from(path)),
                    ("material", Value::from(material)),
                    ("geometry", ring.clone()),
                    ("kinematics", Value::from(kinematics)),
                ])
            };
            let small = of("small");
            assert!(
                small["stress_error"] > 0.5 && small["top_force_error"] > 0.4,
                "{path}: {small:?}"
            );
            let finite = of("finite");
            assert!(
                finite["stress_error"] < 1e-5 && finite["outer_force_error"] < 1e-12,
                "{path}: {finite:?}"
            );
        }
    }

    /// A plane path in the ring, or a ring path in plane strain, is an error that says so.
    #[test]
    fn a_path_in_the_wrong_geometry_is_refused() {
        let mut p = Params::new();
        p.insert("path".into(), Value::from("upsetting"));
        let e = finite_strain_path(&p).unwrap_err();
        assert!(e.contains("axisymmetric"), "{e}");
        p.insert("path".into(), Value::from("compression"));
        p.insert("geometry".into(), Value::from("axisymmetric"));
        assert!(finite_strain_path(&p).is_err());
    }
}
