//! Builtin computations: unit checks of the solver's public contact, impactor and element
//! API against closed forms, and closed-form reference solutions (beam theory, modal
//! superposition). Each returns named metrics (and histories) for the checks to read; the
//! closed forms are written here independently of the solver's code.

use std::collections::BTreeMap;

use impact_solver::contact::{solve_contact_force, LineContactLaw};
use impact_solver::element::{
    element_max_eigenvalue, element_response, gather, lumped_masses, scatter_add, Formulation,
};
use impact_solver::impactor::RigidImpactor;
use impact_solver::material::Elastic;
use impact_solver::mesh::{Mesh, PlateMesh};
use impact_solver::model::AnyFormulation;
use impact_solver::scene::{
    ContactLawChoice, ElementKind, Impactor, Material, MeshSettings, MidSpanNode, Model, Plate,
    DEFAULT_HOURGLASS,
};
use impact_solver::with_formulation;
use impact_solver::History;
use serde_json::Value;

use crate::data::RunData;

pub const NAMES: [&str; 6] = [
    "hertz-law",
    "impactor-kinematics",
    "patch",
    "beam-bending",
    "modal-beam",
    "plane-wave",
];

type Params = BTreeMap<String, Value>;

fn p_f64(p: &Params, k: &str, default: f64) -> Result<f64, String> {
    match p.get(k) {
        None => Ok(default),
        Some(v) => v
            .as_f64()
            .ok_or_else(|| format!("param {k}: {v} is not a number")),
    }
}

fn p_str<'a>(p: &'a Params, k: &str, default: &'a str) -> Result<&'a str, String> {
    match p.get(k) {
        None => Ok(default),
        Some(v) => v
            .as_str()
            .ok_or_else(|| format!("param {k}: {v} is not a string")),
    }
}

fn element_kind(name: &str) -> Result<ElementKind, String> {
    name.parse().map_err(|e| format!("param element: {e}"))
}

pub fn run(name: &str, p: &Params) -> Result<RunData, String> {
    let mut d = match name {
        "hertz-law" => hertz_law(p),
        "impactor-kinematics" => impactor_kinematics(p),
        "patch" => patch(p),
        "beam-bending" => beam_bending(p),
        "modal-beam" => modal_beam(p),
        "plane-wave" => plane_wave(p),
        o => crate::code_verification::run(o, p)
            .unwrap_or_else(|| Err(format!("unknown builtin {o:?}"))),
    }?;
    d.info.insert("builtin".into(), name.to_string());
    for (k, v) in p {
        d.info.insert(format!("param {k}"), v.to_string());
    }
    Ok(d)
}

// ---------------------------------------------------------------------------------------
// Contact law (ALGORITHM.md section 5) through the solver's public API.

const STEEL_E: f64 = 207e9;
const STEEL_NU: f64 = 0.3;
const NOSE_R: f64 = 0.010;
const WIDTH: f64 = 0.2;

fn law(choice: ContactLawChoice) -> LineContactLaw {
    let impactor = Impactor {
        mass: 18.0,
        velocity: 10.0,
        nose_radius: NOSE_R,
        youngs_modulus: STEEL_E,
        poisson_ratio: STEEL_NU,
        contact_law: choice,
        indentation_datum: MidSpanNode::MidPlane,
        force_node: MidSpanNode::MidPlane,
    };
    let plate = Material {
        density: 7850.0,
        youngs_modulus: STEEL_E,
        poisson_ratio: STEEL_NU,
        plasticity: None,
    };
    LineContactLaw::new(&impactor, &plate, WIDTH)
}

fn laws() -> Vec<(&'static str, LineContactLaw)> {
    vec![
        ("paper-m", law(ContactLawChoice::Paper { length_unit: 1.0 })),
        (
            "paper-mm",
            law(ContactLawChoice::Paper { length_unit: 1e-3 }),
        ),
        (
            "johnson",
            law(ContactLawChoice::Johnson { datum_depth: 0.010 }),
        ),
    ]
}

/// Eq. (4) as printed, evaluated in a consistent unit system given in the arguments: force
/// per width `p`, moduli `e`, radius `r`, hidden length `l` (all in that system's units).
fn paper_alpha_in_units(p: f64, e: f64, nu_s: f64, r: f64, l: f64) -> f64 {
    let pi = std::f64::consts::PI;
    let c = (1.0 - nu_s * nu_s) / (pi * e) + 1.0 / (pi * e);
    p * c * (1.0 - (p * r * c / (l * l)).ln())
}

fn hertz_law(_: &Params) -> Result<RunData, String> {
    let mut m = BTreeMap::new();
    let fracs = [
        1e-12, 1e-9, 1e-6, 1e-4, 1e-3, 0.01, 0.05, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99, 0.999,
    ];
    let mut round_trip: f64 = 0.0;
    let mut coupled_round_trip: f64 = 0.0;
    let mut monotone_violations = 0.0;
    let mut slope_fd: f64 = 0.0;
    let mut min_slope_ratio = f64::INFINITY;
    let mut zero_branch: f64 = 0.0;
    let mut beyond_ok = 1.0;
    let mut slope_at_max: f64 = 0.0;
    let mut energy_rel: f64 = 0.0;
    for (_, law) in laws() {
        let p_star = law.max_force_per_width();
        let f_star = p_star * law.width;
        for fr in fracs {
            let f = fr * f_star;
            let alpha = law.alpha(f / law.width);
            let back = law
                .force_for(alpha)
                .ok_or("force_for failed below the maximum")?;
            round_trip = round_trip.max(((back - f) / f).abs());
            // Eq. (21) with the impactor's own compliance dt^2/(6m), dt = 1e-7 s, m = 18 kg.
            let extra = 1e-14 / (6.0 * 18.0);
            let back = solve_contact_force(&law, extra, alpha + extra * f)
                .map_err(|_| "eq. (21) failed below the maximum")?;
            coupled_round_trip = coupled_round_trip.max(((back - f) / f).abs());
        }
        // Monotonic on (0, P*): 400 log-spaced points.
        let n = 400;
        let mut prev = 0.0;
        for i in 0..n {
            let p = p_star * 10f64.powf(-12.0 * (1.0 - i as f64 / (n - 1) as f64)) * (1.0 - 1e-6);
            let a = law.alpha(p);
            if a <= prev {
                monotone_violations += 1.0;
            }
            prev = a;
            if p < 0.999 * p_star {
                min_slope_ratio = min_slope_ratio.min(law.alpha_slope(p) / law.b);
            }
        }
        for fr in [1e-6, 1e-3, 0.1, 0.5, 0.9] {
            let p = fr * p_star;
            let h = 1e-6 * p;
            let fd = (law.alpha(p + h) - law.alpha(p - h)) / (2.0 * h);
            slope_fd = slope_fd.max((fd / law.alpha_slope(p) - 1.0).abs());
        }
        for af in [0.0, -0.0, -1e-15, -1e-9, -1e-3] {
            let f = solve_contact_force(&law, 1e-15, af)
                .map_err(|_| "zero branch returned an error")?;
            zero_branch = zero_branch.max(f.abs());
        }
        let too_deep = 1.01 * law.max_indentation();
        let reported = law.force_for(too_deep).is_none()
            && matches!(solve_contact_force(&law, 0.0, too_deep), Err(e) if e.available < e.required);
        if !reported {
            beyond_ok = 0.0;
        }
        slope_at_max = slope_at_max.max((law.alpha_slope(p_star) / law.b).abs());
        // Stored energy = integral of F d(alpha), trapezoidal on a fine non-uniform grid.
        let fmax = 0.8 * f_star;
        let steps = 100_000;
        let (mut work, mut prev) = (0.0, (0.0, 0.0));
        for i in 1..=steps {
            let f = fmax * (i as f64 / steps as f64).powi(2);
            let a = law.alpha(f / law.width);
            work += 0.5 * (f + prev.0) * (a - prev.1);
            prev = (f, a);
        }
        energy_rel = energy_rel.max((work / law.energy(fmax) - 1.0).abs());
    }
    m.insert("round_trip_max_rel".into(), round_trip);
    m.insert("eq21_round_trip_max_rel".into(), coupled_round_trip);
    m.insert("monotone_violations".into(), monotone_violations);
    m.insert("min_slope_over_b_below_max".into(), min_slope_ratio);
    m.insert("slope_fd_max_rel".into(), slope_fd);
    m.insert("zero_branch_max_force_N".into(), zero_branch);
    m.insert("beyond_maximum_reported".into(), beyond_ok);
    m.insert("slope_at_maximum_over_b".into(), slope_at_max);
    m.insert("energy_integral_max_rel".into(), energy_rel);

    // Unit consistency: the paper law with the hidden length fixed at 1 mm, evaluated here
    // in N-mm units, equals the solver's SI value x 1000.
    let si = law(ContactLawChoice::Paper { length_unit: 1e-3 });
    let mut unit: f64 = 0.0;
    for p_si in [1e3, 1e5, 1e6, 1e7] {
        let mm = paper_alpha_in_units(p_si * 1e-3, STEEL_E * 1e-6, STEEL_NU, NOSE_R * 1e3, 1.0);
        let si_in_mm = 1e3 * si.alpha(p_si);
        unit = unit.max((mm / si_in_mm - 1.0).abs());
        // The same numbers read with l = 1 in both systems differ: the hidden length matters.
    }
    m.insert("unit_mm_vs_m_max_rel".into(), unit);
    let si_m = law(ContactLawChoice::Paper { length_unit: 1.0 });
    m.insert(
        "alpha_l1m_over_l1mm_at_1e6".into(),
        si_m.alpha(1e6) / si.alpha(1e6),
    );
    // The law's maximum, closed form P* = l^2 / (r c) for the paper law.
    let pi = std::f64::consts::PI;
    let c = (1.0 - STEEL_NU * STEEL_NU) / (pi * STEEL_E) + 1.0 / (pi * STEEL_E);
    m.insert("pstar_paper_mm_N_per_m".into(), si.max_force_per_width());
    m.insert("pstar_paper_mm_closed_form".into(), 1e-6 / (NOSE_R * c));
    for (name, l) in laws() {
        for p in [1e5, 1e6, 1e7] {
            m.insert(format!("alpha_{name}_at_{p:e}_m"), l.alpha(p));
        }
    }
    Ok(RunData {
        metrics: m,
        ..Default::default()
    })
}

fn impactor_kinematics(_: &Params) -> Result<RunData, String> {
    let mut m = BTreeMap::new();
    // Constant force F: v = v0 - F t / m, x = v0 t - F t^2 / (2m).
    let (mass, v0, f, dt, n) = (18.0, 10.0, 1.5e5, 1e-7, 1000);
    let mut imp = RigidImpactor::new(mass, v0);
    for _ in 0..n {
        imp.advance(dt, f, f);
    }
    let t = n as f64 * dt;
    let v = v0 - f / mass * t;
    let x = v0 * t - 0.5 * f / mass * t * t;
    m.insert(
        "constant_velocity_rel".into(),
        ((imp.velocity - v) / v0).abs(),
    );
    m.insert(
        "constant_displacement_rel".into(),
        ((imp.displacement - x) / x).abs(),
    );
    // Linear force F = k t: v = v0 - k t^2 / (2m), x = v0 t - k t^3 / (6m).
    let (mass, v0, k, dt, n) = (10.0, 5.0, 3e9, 1e-7, 2000);
    let mut imp = RigidImpactor::new(mass, v0);
    for i in 0..n {
        imp.advance(dt, k * i as f64 * dt, k * (i + 1) as f64 * dt);
    }
    let t = n as f64 * dt;
    let v = v0 - k * t * t / (2.0 * mass);
    let x = v0 * t - k * t * t * t / (6.0 * mass);
    m.insert(
        "linear_velocity_rel".into(),
        ((imp.velocity - v) / v0).abs(),
    );
    m.insert(
        "linear_displacement_rel".into(),
        ((imp.displacement - x) / x).abs(),
    );
    // A quadratic force is not linear in a step: the update is then only second order;
    // the error must be visible (this guards against a check that cannot fail).
    let (mass, v0, q, dt, n) = (10.0, 5.0, 1e13, 1e-6, 200);
    let mut imp = RigidImpactor::new(mass, v0);
    for i in 0..n {
        let (t0, t1) = (i as f64 * dt, (i + 1) as f64 * dt);
        imp.advance(dt, q * t0 * t0, q * t1 * t1);
    }
    let t = n as f64 * dt;
    let v = v0 - q * t * t * t / (3.0 * mass);
    m.insert(
        "quadratic_velocity_rel".into(),
        ((imp.velocity - v) / v0).abs(),
    );
    Ok(RunData {
        metrics: m,
        ..Default::default()
    })
}

// ---------------------------------------------------------------------------------------
// Elements.

fn formulation(
    kind: ElementKind,
    mesh: &Mesh,
    width: f64,
    elastic: &Elastic,
) -> Result<AnyFormulation, String> {
    AnyFormulation::new(kind, mesh, width, DEFAULT_HOURGLASS, elastic).map_err(|e| e.to_string())
}

/// Internal forces of the whole mesh at `u`, and the max stress error against `exact`.
fn assemble<F: Formulation>(
    f: &F,
    elastic: &Elastic,
    u: &[f64],
    exact: Option<&[f64; 4]>,
) -> (Vec<f64>, f64) {
    let mut out = vec![0.0; u.len()];
    let mut stress_err: f64 = 0.0;
    for e in 0..f.n_elements() {
        let nodes = f.nodes(e);
        let ue = gather(nodes, u);
        let mut states = [(); 4];
        let (fe, _) = element_response(f, elastic, e, &ue, &mut states);
        scatter_add(nodes, &fe, &mut out);
        if let Some(s) = exact {
            let scale = s.iter().map(|x| x.abs()).fold(0.0, f64::max);
            for strain in f.strains(e, &ue).iter().take(F::POINTS) {
                let st = elastic.stress_of(strain);
                for c in 0..4 {
                    stress_err = stress_err.max((st[c] - s[c]).abs() / scale);
                }
            }
        }
    }
    (out, stress_err)
}

/// A distorted 2x2 patch on [0, 0.02]^2: edge mid-nodes moved along the edges, the interior
/// node moved off-centre (MacNeal-Harder style). Node 4 is the only interior (free) node.
fn distorted_patch() -> Mesh {
    let coords = vec![
        [0.0, 0.0],
        [0.0085, 0.0],
        [0.02, 0.0],
        [0.0, 0.0115],
        [0.0123, 0.0082],
        [0.02, 0.0093],
        [0.0, 0.02],
        [0.0106, 0.02],
        [0.02, 0.02],
    ];
    let elements = vec![[0, 1, 4, 3], [1, 2, 5, 4], [3, 4, 7, 6], [4, 5, 8, 7]];
    Mesh { coords, elements }
}

fn patch(p: &Params) -> Result<RunData, String> {
    let kind = element_kind(p_str(p, "element", "q4-sri")?)?;
    let (e_mod, nu, rho, width) = (207e9, 0.3, 7850.0, 0.2);
    let elastic = Elastic::new(e_mod, nu);
    let mesh = distorted_patch();
    let form = formulation(kind, &mesh, width, &elastic)?;
    // Linear field u = a + G x with a general constant strain.
    let g = [[1.0e-3, 4.0e-4], [-2.0e-4, -6.0e-4]];
    let field = |x: [f64; 2]| {
        [
            1e-5 + g[0][0] * x[0] + g[0][1] * x[1],
            -2e-5 + g[1][0] * x[0] + g[1][1] * x[1],
        ]
    };
    let u: Vec<f64> = mesh.coords.iter().flat_map(|&x| field(x)).collect();
    let strain = [g[0][0], g[1][1], 0.0, g[0][1] + g[1][0]];
    let exact = elastic.stress_of(&strain);
    let free = 4usize;
    let (f, stress_err) = with_formulation!(&form, x => assemble(x, &elastic, &u, Some(&exact)));
    let boundary_max = (0..mesh.coords.len())
        .filter(|&n| n != free)
        .map(|n| f[2 * n].hypot(f[2 * n + 1]))
        .fold(0.0, f64::max);
    let mut m = BTreeMap::new();
    m.insert(
        "free_node_force_rel".into(),
        f[2 * free].hypot(f[2 * free + 1]) / boundary_max,
    );
    m.insert("stress_max_rel_error".into(), stress_err);
    // Global equilibrium of the boundary forces (sum of nodal forces = 0).
    let (sx, sy): (f64, f64) =
        (0..mesh.coords.len()).fold((0.0, 0.0), |a, n| (a.0 + f[2 * n], a.1 + f[2 * n + 1]));
    m.insert("force_sum_rel".into(), sx.hypot(sy) / boundary_max);

    // Uniform strain rate: boundary nodes follow v = G x / T; the free node, integrated by
    // central differences with its lumped mass, must stay on the linear field.
    let masses = with_formulation!(&form, x => lumped_masses(x, mesh.coords.len(), rho));
    let lambda_max = with_formulation!(&form, x => (0..x.n_elements()).map(|e| element_max_eigenvalue(x, &elastic, rho, e)).fold(0.0, f64::max));
    let dt = 0.5 * 2.0 / lambda_max.sqrt();
    let steps = 2000;
    let t_end = steps as f64 * dt;
    let rate = |x: [f64; 2], t: f64| {
        let s = t / t_end;
        let v = field(x);
        [v[0] * s, v[1] * s]
    };
    let mut u = vec![0.0; 2 * mesh.coords.len()];
    let x4 = mesh.coords[free];
    let mut v4 = [field(x4)[0] / t_end, field(x4)[1] / t_end];
    let mut dev: f64 = 0.0;
    for n in 0..steps {
        let t = n as f64 * dt;
        for (i, &x) in mesh.coords.iter().enumerate() {
            if i != free {
                let r = rate(x, t);
                u[2 * i] = r[0];
                u[2 * i + 1] = r[1];
            }
        }
        let (f, _) = with_formulation!(&form, x => assemble(x, &elastic, &u, None));
        for c in 0..2 {
            v4[c] += -f[2 * free + c] / masses[free] * dt;
            u[2 * free + c] += v4[c] * dt;
        }
        let r = rate(x4, t + dt);
        dev = dev.max((u[2 * free] - r[0]).hypot(u[2 * free + 1] - r[1]));
    }
    let scale = field(x4)[0].hypot(field(x4)[1]);
    m.insert("rate_free_node_deviation_rel".into(), dev / scale);
    Ok(RunData {
        metrics: m,
        ..Default::default()
    })
}

/// Banded symmetric positive definite solve (Cholesky), half-bandwidth `bw`.
fn banded_solve(
    n: usize,
    bw: usize,
    k: &BTreeMap<(usize, usize), f64>,
    rhs: &[f64],
) -> Result<Vec<f64>, String> {
    // l[i][j - i + bw] for j in [i - bw, i].
    let w = bw + 1;
    let mut a = vec![0.0; n * w];
    for (&(i, j), &v) in k {
        if j <= i && i - j <= bw {
            a[i * w + (j + bw - i)] += v;
        }
    }
    for i in 0..n {
        let j0 = i.saturating_sub(bw);
        for j in j0..=i {
            let mut s = a[i * w + (j + bw - i)];
            let k0 = j0.max(j.saturating_sub(bw));
            for kk in k0..j {
                s -= a[i * w + (kk + bw - i)] * a[j * w + (kk + bw - j)];
            }
            if i == j {
                if s <= 0.0 {
                    return Err(format!("stiffness not positive definite at dof {i}"));
                }
                a[i * w + bw] = s.sqrt();
            } else {
                a[i * w + (j + bw - i)] = s / a[j * w + bw];
            }
        }
    }
    let mut y = rhs.to_vec();
    for i in 0..n {
        let j0 = i.saturating_sub(bw);
        let mut s = y[i];
        for j in j0..i {
            s -= a[i * w + (j + bw - i)] * y[j];
        }
        y[i] = s / a[i * w + bw];
    }
    for i in (0..n).rev() {
        let mut s = y[i];
        for j in i + 1..(i + bw + 1).min(n) {
            s -= a[j * w + (i + bw - j)] * y[j];
        }
        y[i] = s / a[i * w + bw];
    }
    Ok(y)
}

/// Static clamped-clamped beam (half model: clamp at x = 0, symmetry at mid-span) with a
/// total load F at mid-span shared over the mid-span nodes; against beam theory.
fn beam_bending(p: &Params) -> Result<RunData, String> {
    let kind = element_kind(p_str(p, "element", "q4-sri")?)?;
    let length = p_f64(p, "length", 0.8)?;
    let thickness = p_f64(p, "thickness", 0.02)?;
    let width = p_f64(p, "width", 0.2)?;
    let nx = p_f64(p, "nx", 80.0)? as usize;
    let ny = p_f64(p, "ny", 4.0)? as usize;
    let force = p_f64(p, "force", 1.0e4)?;
    let (e_mod, nu) = (
        p_f64(p, "youngs_modulus", 207e9)?,
        p_f64(p, "poisson_ratio", 0.3)?,
    );
    let elastic = Elastic::new(e_mod, nu);
    // Mesh settings from a minimal scene, so that fields the solver adds keep their defaults.
    let base = impact_solver::Scene::from_yaml(
        "plate: {length: 1.0, width: 1.0, thickness: 0.1}\nmaterial: {density: 1.0, youngs_modulus: 1.0, poisson_ratio: 0.3}\nmesh: {nx: 2, ny: 2}\nload: {pulse: {force: 1.0, duration: 1.0}}\ntime: {end: 1.0, dt: {cfl: 0.5}}\n",
        std::path::Path::new("(builtin beam-bending)"),
    )
    .map_err(|e| e.to_string())?;
    // Plate likewise (the solver may add fields: their defaults come from the scene).
    let plate = Plate {
        length,
        width,
        thickness,
        ..base.plate
    };
    let settings = MeshSettings {
        nx,
        ny,
        element: kind,
        model: Model::Half,
        ..base.mesh
    };
    let pm = PlateMesh::new(&plate, &settings);
    let form = formulation(kind, &pm.mesh, width, &elastic)?;
    // Renumber dofs column by column (x-major) for a narrow band.
    let node_of = |n: usize| {
        let (i, j) = (n % (nx + 1), n / (nx + 1));
        i * (ny + 1) + j
    };
    let ndof = 2 * pm.mesh.n_nodes();
    let dof = |n: usize, c: usize| 2 * node_of(n) + c;
    let mut k: BTreeMap<(usize, usize), f64> = BTreeMap::new();
    with_formulation!(&form, x => {
        for e in 0..x.n_elements() {
            let ke = impact_solver::element::element_stiffness(x, &elastic, e);
            let nodes = x.nodes(e);
            for a in 0..8 {
                for b in 0..8 {
                    let (i, j) = (dof(nodes[a / 2] as usize, a % 2), dof(nodes[b / 2] as usize, b % 2));
                    *k.entry((i, j)).or_insert(0.0) += 0.5 * (ke[a][b] + ke[b][a]);
                }
            }
        }
    });
    let mut rhs = vec![0.0; ndof];
    // Half the load on the half model, as a uniform shear traction over the mid-span face.
    for j in 0..=ny {
        let n = nx + j * (nx + 1);
        let share = if j == 0 || j == ny { 0.5 } else { 1.0 } / ny as f64;
        rhs[dof(n, 1)] -= 0.5 * force * share;
    }
    for n in 0..pm.mesh.n_nodes() {
        for c in 0..2 {
            if pm.fixed_dofs[2 * n + c] {
                let d = dof(n, c);
                k.retain(|&(i, j), _| i != d && j != d);
                k.insert((d, d), 1.0);
                rhs[d] = 0.0;
            }
        }
    }
    let bw = 2 * (ny + 2) + 1;
    let u = banded_solve(ndof, bw, &k, &rhs)?;
    let deflection = -u[dof(pm.mid, 1)];
    let e_prime = e_mod / (1.0 - nu * nu);
    let inertia = width * thickness.powi(3) / 12.0;
    let eb = force * length.powi(3) / (192.0 * e_prime * inertia);
    let shear = force * length / (4.0 * (5.0 / 6.0) * elastic.mu * width * thickness);
    let nu_p = nu / (1.0 - nu);
    // Parasitic shear of a bilinear quad of length a under a curvature k: gamma = k a xi / 2,
    // energy G k^2 a^2 / 24 per volume against the bending energy E' k^2 h^2 / 24 averaged
    // over the depth h: ratio (1 - nu') (a/h)^2 / 2 in plane strain, whatever the layers.
    let a_over_h = (0.5 * length / nx as f64) / thickness;
    let locking = 1.0 / (1.0 + 0.5 * (1.0 - nu_p) * a_over_h * a_over_h);
    // One-point elements carry a constant strain per layer: the bending stiffness of ny
    // layers is (1 - 1/ny^2) of the exact one (hourglass control adds a little back).
    let one_point = 1.0 / (1.0 - 1.0 / (ny * ny) as f64);
    let mut m = BTreeMap::new();
    m.insert("deflection_m".into(), deflection);
    m.insert("euler_bernoulli_m".into(), eb);
    m.insert("timoshenko_m".into(), eb + shear);
    m.insert("ratio_to_timoshenko".into(), deflection / (eb + shear));
    m.insert("q4_locking_estimate".into(), locking);
    m.insert("one_point_layer_estimate".into(), one_point);
    Ok(RunData {
        metrics: m,
        ..Default::default()
    })
}

/// Roots of cos x cosh x = 1 (clamped-clamped beam), the first `n`.
fn clamped_roots(n: usize) -> Vec<f64> {
    (1..=n)
        .map(|k| {
            let mut x = (k as f64 + 0.5) * std::f64::consts::PI;
            for _ in 0..50 {
                // g(x) = cos x - 1/cosh x, well scaled for large x.
                let g = x.cos() - 1.0 / x.cosh();
                let dg = -x.sin() + x.tanh() / x.cosh();
                let step = g / dg;
                x -= step;
                if step.abs() < 1e-15 * x {
                    break;
                }
            }
            x
        })
        .collect()
}

/// Clamped-clamped mode shape at xi = x / L (stable for large roots).
fn clamped_mode(root: f64, xi: f64) -> f64 {
    let (s, c, sh) = (root.sin(), root.cos(), root.sinh());
    let one_minus_sigma = (-(-root).exp() - s + c) / (sh - s);
    let sigma = 1.0 - one_minus_sigma;
    let z = root * xi;
    (-z).exp() + one_minus_sigma * z.sinh() - z.cos() + sigma * z.sin()
}

/// Euler-Bernoulli clamped-clamped beam (plane strain modulus) under a rectangular pulse at
/// mid-span: modal superposition, mid-span deflection history (negative = down).
fn modal_beam(p: &Params) -> Result<RunData, String> {
    let length = p_f64(p, "length", 0.8)?;
    let thickness = p_f64(p, "thickness", 0.02)?;
    let width = p_f64(p, "width", 0.2)?;
    let (e_mod, nu, rho) = (
        p_f64(p, "youngs_modulus", 207e9)?,
        p_f64(p, "poisson_ratio", 0.3)?,
        p_f64(p, "density", 7850.0)?,
    );
    let force = p_f64(p, "force", 86.5e3)?;
    let duration = p_f64(p, "duration", 1e-3)?;
    let end = p_f64(p, "end", 4e-3)?;
    let every = p_f64(p, "every", 1e-6)?;
    let n_modes = p_f64(p, "modes", 40.0)? as usize;
    let e_prime = e_mod / (1.0 - nu * nu);
    let ei = e_prime * width * thickness.powi(3) / 12.0;
    let rho_a = rho * width * thickness;
    let roots = clamped_roots(n_modes);
    // Modal masses by Simpson's rule on 4000 intervals.
    let modes: Vec<(f64, f64, f64)> = roots
        .iter()
        .map(|&r| {
            let n = 4000;
            let mut s = 0.0;
            for i in 0..=n {
                let w = if i == 0 || i == n {
                    1.0
                } else if i % 2 == 1 {
                    4.0
                } else {
                    2.0
                };
                s += w * clamped_mode(r, i as f64 / n as f64).powi(2);
            }
            let mass = rho_a * length * s / (3.0 * n as f64);
            let omega = r * r / (length * length) * (ei / rho_a).sqrt();
            (omega, clamped_mode(r, 0.5), mass)
        })
        .collect();
    let rows = (end / every).round() as usize;
    let mut values = Vec::with_capacity(2 * (rows + 1));
    for i in 0..=rows {
        let t = i as f64 * every;
        let mut w = 0.0;
        for &(om, phi, mass) in &modes {
            let amp = force * phi * phi / (mass * om * om);
            let on = 1.0 - (om * t).cos();
            let off = if t >= duration {
                1.0 - (om * (t - duration)).cos()
            } else {
                0.0
            };
            w += amp * (on - off);
        }
        values.extend([t, -w]);
    }
    let mut m = BTreeMap::new();
    let static_defl = force * length.powi(3) / (192.0 * ei);
    m.insert("static_deflection_m".into(), static_defl);
    m.insert(
        "first_period_s".into(),
        2.0 * std::f64::consts::PI / modes[0].0,
    );
    m.insert(
        "min_mid_uy_m".into(),
        values
            .iter()
            .skip(1)
            .step_by(2)
            .copied()
            .fold(f64::INFINITY, f64::min),
    );
    // The static limit of the series (sum of amp) must equal the closed form.
    let series_static: f64 = modes
        .iter()
        .map(|&(om, phi, mass)| force * phi * phi / (mass * om * om))
        .sum();
    m.insert("series_static_m".into(), series_static);
    let mut histories = BTreeMap::new();
    histories.insert(
        String::new(),
        History {
            columns: vec!["time_s".into(), "mid_uy_m".into()],
            values,
        },
    );
    Ok(RunData {
        metrics: m,
        histories,
        ..Default::default()
    })
}

/// A plane-strain plane wave through the thickness (the `plane-wave` builtin and the
/// work-precision benchmark): `wave` "p" (roller ends, 1 MPa normal traction step on the top
/// surface) or "s" (slider ends, 1 MPa shear traction step), full model 4 x `ny` of
/// `element` through h = 20 mm, run for 8 us at `cfl`, probe M at mid-depth. The speed comes
/// from the momentum balance of the layer above the probe at depth d:
/// int_0^T (tau - sigma(d, t)) dt = tau d / c once the front has passed and before its
/// reflection returns, whatever the numerical dispersion of the front.
pub struct PlaneWave {
    /// The probe's stress column whose deficit gives the speed (M_syy_Pa or M_sxy_Pa), and
    /// the sign that makes the 1 MPa traction positive in it.
    column: &'static str,
    sign: f64,
    pub ny: usize,
    pub scene: impact_solver::Scene,
    /// The closed-form speed, m/s: c_P = sqrt((lambda + 2 mu)/rho) or c_S = sqrt(mu/rho).
    pub exact_mps: f64,
}

const WAVE_H: f64 = 0.02;

impl PlaneWave {
    pub fn new(wave: &str, ny: usize, element: ElementKind, cfl: f64) -> Result<Self, String> {
        let (e, nu, rho, h): (f64, f64, f64, f64) = (207e9, 0.3, 7850.0, WAVE_H);
        let lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
        let mu = e / (2.0 * (1.0 + nu));
        let (column, sign, ends, traction, exact_mps) = match wave {
            "p" => (
                "M_syy_Pa",
                -1.0,
                "roller",
                "normal: 1.0e6",
                ((lambda + 2.0 * mu) / rho).sqrt(),
            ),
            "s" => ("M_sxy_Pa", 1.0, "slider", "shear: 1.0e6", (mu / rho).sqrt()),
            o => return Err(format!("wave {o:?}: expected p or s")),
        };
        let text = format!(
            "plate: {{length: 0.2, width: 0.2, thickness: {h}, ends: {ends}}}\n\
             material: {{density: {rho}, youngs_modulus: {e}, poisson_ratio: {nu}}}\n\
             mesh: {{nx: 4, ny: {ny}, element: {}, model: full}}\n\
             load: {{traction: {{{traction}, duration: 1.0}}}}\n\
             time: {{end: 8.0e-6, dt: {{cfl: {cfl}}}}}\n\
             output: {{probes: {{M: {{x: 0.1, y: 0.01}}}}}}\n",
            element.name()
        );
        let scene =
            impact_solver::Scene::from_yaml(&text, std::path::Path::new("(builtin plane-wave)"))
                .map_err(|e| e.to_string())?;
        Ok(PlaneWave {
            column,
            sign,
            ny,
            scene,
            exact_mps,
        })
    }

    /// The measured speed, m/s, from the momentum deficit of the layer above the probe:
    /// `int_0^T (tau - sigma(d, t)) dt = tau d / c` before the reflection returns.
    pub fn measured_speed(&self, history: &impact_solver::History) -> Result<f64, String> {
        // The probe (y = h/2) lies in the element row just below mid-depth; the stress of that
        // row is the force between its node rows, so the depth is its centre's.
        let (h, dy) = (WAVE_H, WAVE_H / self.ny as f64);
        let depth = h - (0.5 * h - 0.5 * dy);
        let until = 0.97 * (2.0 * h - depth) / self.exact_mps;
        let deficit = history
            .time_integral(self.column, until, |s| 1.0 - self.sign * s / 1e6)
            .ok_or_else(|| format!("no column {}", self.column))?;
        Ok(depth / deficit)
    }
}

fn plane_wave(p: &Params) -> Result<RunData, String> {
    let element = element_kind(p_str(p, "element", "q4-sri")?)?;
    let problem = PlaneWave::new(
        p_str(p, "wave", "p")?,
        p_f64(p, "ny", 80.0)? as usize,
        element,
        p_f64(p, "cfl", 0.5)?,
    )?;
    let o = impact_solver::simulate(&problem.scene, &mut impact_solver::Quiet)
        .map_err(|e| e.to_string())?;
    let c = problem.measured_speed(&o.history)?;
    let exact = problem.exact_mps;
    let mut m = BTreeMap::new();
    m.insert("speed_mps".into(), c);
    m.insert("closed_form_mps".into(), exact);
    m.insert("relative_error".into(), (c / exact - 1.0).abs());
    m.insert(
        "max_energy_balance_error".into(),
        o.summary.max_energy_balance_error,
    );
    let mut histories = BTreeMap::new();
    histories.insert(String::new(), o.history);
    Ok(RunData {
        metrics: m,
        histories,
        ..Default::default()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clamped_roots_match_the_tabulated_values() {
        let r = clamped_roots(4);
        for (a, b) in r
            .iter()
            .zip([4.730040745, 7.853204624, 10.99560784, 14.13716549])
        {
            assert!((a - b).abs() < 1e-8, "{a} vs {b}");
        }
        // Normalisation of this mode form: integral of phi^2 over [0, 1] is 1.
        for &root in &clamped_roots(30) {
            let n = 4000;
            let s: f64 = (0..=n)
                .map(|i| {
                    let w = if i == 0 || i == n {
                        1.0
                    } else if i % 2 == 1 {
                        4.0
                    } else {
                        2.0
                    };
                    w * clamped_mode(root, i as f64 / n as f64).powi(2)
                })
                .sum::<f64>()
                / (3.0 * n as f64);
            assert!((s - 1.0).abs() < 1e-6, "{root}: {s}");
        }
    }

    #[test]
    fn banded_cholesky_solves_a_tridiagonal_system() {
        let n = 5;
        let mut k = BTreeMap::new();
        for i in 0..n {
            k.insert((i, i), 2.0);
            if i + 1 < n {
                k.insert((i + 1, i), -1.0);
                k.insert((i, i + 1), -1.0);
            }
        }
        let x = banded_solve(n, 1, &k, &[1.0, 0.0, 0.0, 0.0, 1.0]).unwrap();
        for v in x {
            assert!((v - 1.0).abs() < 1e-12);
        }
    }
}
