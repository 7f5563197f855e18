//! The `plastic-bar-wave` builtin: the elastic-plastic uniaxial-strain wave. A plate whose
//! ends are rollers (u_x = 0: every point is in uniaxial strain, eps_xx = eps_zz = 0) is
//! loaded on its top surface by a uniform normal traction step `tau` above the Hugoniot
//! elastic limit; the solver's own time loop (`impact_solver::simulate`, scene built here)
//! sends an elastic precursor and a slower plastic wave down through the thickness.
//!
//! The reference is written here from E, nu, rho, sigma_y and E_t (not from the solver's
//! material code; the derivation is in the case's README,
//! `verification/cases/order-of-accuracy/plastic-bar-wave/README.md`):
//! - precursor speed `c_e = sqrt((lambda + 2 mu) / rho)`, amplitude the Hugoniot elastic
//!   limit `sigma_HEL = (lambda + 2 mu) sigma_y / (2 mu) = (1 - nu) / (1 - 2 nu) sigma_y`;
//! - plastic wave speed `c_p = sqrt(M_t / rho)`, `M_t = K + 4/3 G_t`,
//!   `G_t = mu H / (3 mu + H)`, `H = E E_t / (E - E_t)`; the stress behind it is `tau`;
//! - the loaded surface moves at `v = sigma_HEL / (rho c_e) + (tau - sigma_HEL) / (rho c_p)`.
//!
//! Measured: the arrival times (first crossing of half the jump) at two probes a known
//! distance apart give each front's speed whatever the start-up offset; the precursor's
//! plateau between the two arrivals at the deeper probe; the plateau behind the plastic
//! front before the precursor's reflection from the free bottom returns; the surface
//! velocity as the least-squares slope of the top node's displacement.

use std::collections::BTreeMap;

use impact_solver::History;
use serde_json::Value;

use super::plastic_material::{plastic_material, PlasticMaterial};
use super::scene_text::run_scene_text;
use crate::definition::run_data::RunData;
use crate::run::builtin_params::param;

type Params = BTreeMap<String, Value>;

/// The material, the load and the closed-form wave structure, SI units.
#[derive(Debug, Clone, Copy)]
struct Bar {
    material: PlasticMaterial,
    /// Traction on the top surface, Pa (compressive).
    traction: f64,
}

/// The closed-form two-wave structure.
#[derive(Debug, Clone, Copy)]
struct Waves {
    /// m/s
    elastic_speed: f64,
    /// m/s
    plastic_speed: f64,
    /// Pa
    hel: f64,
    /// m/s
    surface_velocity: f64,
}

impl Bar {
    fn waves(&self) -> Waves {
        let m = &self.material;
        let (e, nu, rho) = (m.youngs_modulus, m.poisson_ratio, m.density);
        let lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
        let mu = e / (2.0 * (1.0 + nu));
        let bulk = lambda + 2.0 * mu / 3.0;
        let h = e * m.tangent_modulus / (e - m.tangent_modulus);
        let g_t = mu * h / (3.0 * mu + h);
        let m_t = bulk + 4.0 / 3.0 * g_t;
        let elastic_speed = ((lambda + 2.0 * mu) / rho).sqrt();
        let plastic_speed = (m_t / rho).sqrt();
        let hel = (lambda + 2.0 * mu) * m.yield_stress / (2.0 * mu);
        let surface_velocity =
            hel / (rho * elastic_speed) + (self.traction - hel) / (rho * plastic_speed);
        Waves {
            elastic_speed,
            plastic_speed,
            hel,
            surface_velocity,
        }
    }
}

/// Thickness of the plate (the wave's path), m.
const THICKNESS: f64 = 0.1;
/// Length between the roller ends, m (the field is uniform along it).
const LENGTH: f64 = 0.01;
/// Probe depths below the loaded surface as fractions of the thickness (before their
/// element-row rounding): the precursor's reflection from the free bottom reaches the deeper
/// one at (2 - 0.6) h / c_e, after the plastic front (0.6 h / c_p) by ~10 us.
const DEPTHS: [f64; 2] = [0.2, 0.6];

/// The scene: one element wide (half model, `nx` = 1: the roller end and the symmetry plane
/// hold every u_x, a 1-D bar in uniaxial strain), `ny` through the thickness, the time step
/// `dy / c_e` (Courant number 1 of the bar: the elastic precursor is exact at the nodes, as
/// in wave-speed/strip's bar; above the 2-D element estimate, hence `allow_unstable_dt`), the
/// solver's `model_*` material (a negative control may change it), history every step.
fn scene(bar: &Bar, model: (f64, f64, f64), ny: usize, element: &str) -> String {
    let dy = THICKNESS / ny as f64;
    // Each probe sits just above the lower Gauss row of its element row, so its nearest
    // integration point is unambiguous; both at the same place in their rows, so their
    // distance is an exact number of rows.
    let probes: Vec<String> = DEPTHS
        .iter()
        .enumerate()
        .map(|(k, f)| {
            let row = ((1.0 - f) * ny as f64).round();
            let y = (row + 0.3) * dy;
            format!("P{k}: {{x: {}, y: {y}}}", 0.3 * LENGTH)
        })
        .collect();
    let w = bar.waves();
    let end = 0.95 * 2.0 * THICKNESS / w.elastic_speed;
    let model_bar = Bar {
        material: PlasticMaterial {
            youngs_modulus: model.2,
            ..bar.material
        },
        ..*bar
    };
    let dt = dy / model_bar.waves().elastic_speed;
    format!(
        "plate: {{length: {LENGTH}, width: 1.0, thickness: {THICKNESS}, ends: roller}}\n\
         material: {{density: {rho}, youngs_modulus: {e}, poisson_ratio: {nu},\n  \
           plasticity: {{yield_stress: {sy}, hardening: {{linear: {et}}}}}}}\n\
         mesh: {{nx: 1, ny: {ny}, element: {element}, model: half}}\n\
         load: {{traction: {{normal: {tau}, duration: 1.0}}}}\n\
         time: {{end: {end}, dt: {{fixed: {dt}}}, allow_unstable_dt: true}}\n\
         output: {{probes: {{{probes}}}}}\n",
        rho = bar.material.density,
        e = model.2,
        nu = bar.material.poisson_ratio,
        sy = model.0,
        et = model.1,
        tau = bar.traction,
        probes = probes.join(", "),
    )
}

/// Depth below the top surface of probe `k`'s integration point, m: the row's lower Gauss
/// point, `dy (1/2 - 1/(2 sqrt 3))` above the row's bottom.
fn probe_depth(k: usize, ny: usize) -> f64 {
    let dy = THICKNESS / ny as f64;
    let row = ((1.0 - DEPTHS[k]) * ny as f64).round();
    THICKNESS - (row + 0.5 - 0.5 / 3f64.sqrt()) * dy
}

/// First time the compressive stress `s` reaches `level`, linearly interpolated, s.
fn arrival(t: &[f64], s: &[f64], level: f64) -> Option<f64> {
    (1..t.len())
        .find(|&i| s[i] >= level)
        .map(|i| t[i - 1] + (level - s[i - 1]) / (s[i] - s[i - 1]) * (t[i] - t[i - 1]))
}

/// Mean of `s` over the rows with `from <= t <= to`.
fn mean_between(t: &[f64], s: &[f64], from: f64, to: f64) -> Option<f64> {
    let v: Vec<f64> = (0..t.len())
        .filter(|&i| t[i] >= from && t[i] <= to)
        .map(|i| s[i])
        .collect();
    (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64)
}

/// Least-squares slope of `u` against `t` over `from <= t <= to`.
fn slope_between(t: &[f64], u: &[f64], from: f64, to: f64) -> Option<f64> {
    let idx: Vec<usize> = (0..t.len())
        .filter(|&i| t[i] >= from && t[i] <= to)
        .collect();
    if idx.len() < 2 {
        return None;
    }
    let n = idx.len() as f64;
    let (mt, mu) = idx
        .iter()
        .fold((0.0, 0.0), |(a, b), &i| (a + t[i] / n, b + u[i] / n));
    let (num, den) = idx.iter().fold((0.0, 0.0), |(a, b), &i| {
        (a + (t[i] - mt) * (u[i] - mu), b + (t[i] - mt).powi(2))
    });
    Some(num / den)
}

/// The measured wave structure from the run's history.
fn measure(history: &History, bar: &Bar, ny: usize) -> Result<BTreeMap<String, f64>, String> {
    let col = |name: &str| {
        history
            .column(name)
            .ok_or_else(|| format!("plastic-bar-wave: no column {name}"))
    };
    let t = col("time_s")?;
    // Compression positive.
    let s: Vec<Vec<f64>> = (0..DEPTHS.len())
        .map(|k| col(&format!("P{k}_syy_Pa")).map(|c| c.iter().map(|x| -x).collect()))
        .collect::<Result<_, _>>()?;
    let w = bar.waves();
    let missing = |what: &str| format!("plastic-bar-wave: no {what} in the history");
    let (d0, d1) = (probe_depth(0, ny), probe_depth(1, ny));
    let (hel_half, plastic_half) = (0.5 * w.hel, 0.5 * (w.hel + bar.traction));
    let te = |k: usize| arrival(&t, &s[k], hel_half).ok_or_else(|| missing("precursor"));
    let tp = |k: usize| arrival(&t, &s[k], plastic_half).ok_or_else(|| missing("plastic front"));
    let (te0, te1, tp0, tp1) = (te(0)?, te(1)?, tp(0)?, tp(1)?);
    let mut m = BTreeMap::new();
    m.insert("elastic_speed_mps".into(), (d1 - d0) / (te1 - te0));
    let plastic_speed = (d1 - d0) / (tp1 - tp0);
    m.insert("plastic_speed_mps".into(), plastic_speed);
    m.insert(
        "plastic_speed_relative_error".into(),
        (plastic_speed / w.plastic_speed - 1.0).abs(),
    );
    // The precursor's plateau: the middle half between the closed-form arrivals at the
    // deeper probe.
    let (ae, ap) = (d1 / w.elastic_speed, d1 / w.plastic_speed);
    let hel = mean_between(&t, &s[1], ae + 0.25 * (ap - ae), ap - 0.25 * (ap - ae))
        .ok_or_else(|| missing("precursor plateau"))?;
    m.insert("precursor_stress_Pa".into(), hel);
    // Behind the plastic front until the reflection from the free bottom returns.
    let reflected = (2.0 * THICKNESS - d1) / w.elastic_speed;
    let behind = mean_between(&t, &s[1], ap + 0.3 * (reflected - ap), reflected - 0.5e-6)
        .ok_or_else(|| missing("plastic plateau"))?;
    m.insert("plastic_plateau_stress_Pa".into(), behind);
    let top = col("top_uy_m")?;
    let until = 2.0 * THICKNESS / w.elastic_speed;
    let v = slope_between(&t, &top, 0.2 * until, 0.9 * until)
        .ok_or_else(|| missing("surface motion"))?;
    m.insert("surface_velocity_mps".into(), -v);
    m.insert("elastic_speed_closed_form_mps".into(), w.elastic_speed);
    m.insert("plastic_speed_closed_form_mps".into(), w.plastic_speed);
    m.insert("hel_closed_form_Pa".into(), w.hel);
    m.insert("traction_Pa".into(), bar.traction);
    m.insert(
        "surface_velocity_closed_form_mps".into(),
        w.surface_velocity,
    );
    Ok(m)
}

pub fn plastic_bar_wave(p: &Params) -> Result<RunData, String> {
    let mut bar = Bar {
        material: plastic_material(p)?,
        traction: 0.0,
    };
    bar.traction = param(p, "traction_over_hel", 2.0)? * bar.waves().hel;
    // The solver's material (a negative control may change it).
    let model = (
        param(p, "model_yield_stress", bar.material.yield_stress)?,
        param(p, "model_tangent_modulus", bar.material.tangent_modulus)?,
        param(p, "model_youngs_modulus", bar.material.youngs_modulus)?,
    );
    let ny = param(p, "ny", 400.0)? as usize;
    let element = match p.get("element") {
        None => "q4-sri",
        Some(v) => v.as_str().ok_or("param element: not a string")?,
    };
    let text = scene(&bar, model, ny, element);
    let o = run_scene_text(
        &text,
        "(builtin plastic-bar-wave)",
        &mut impact_solver::Quiet,
    )?;
    let m = measure(&o.history, &bar, ny)?;
    let mut metrics = m;
    metrics.insert(
        "max_energy_balance_error".into(),
        o.summary.max_energy_balance_error,
    );
    Ok(RunData::with_history(metrics, o.history))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn metrics(extra: &[(&str, f64)]) -> BTreeMap<String, f64> {
        let mut p = Params::new();
        p.insert("ny".into(), Value::from(1600));
        for (k, v) in extra {
            p.insert(k.to_string(), Value::from(*v));
        }
        plastic_bar_wave(&p).unwrap().metrics
    }

    fn rel(m: &BTreeMap<String, f64>, a: &str, b: &str) -> f64 {
        m[a] / m[b] - 1.0
    }

    /// Negative controls for the case's checks (tolerances as in its case.yaml): a material
    /// that never yields, a perfectly plastic one (E_t = 0 in place of 20 GPa) and a plate
    /// twice as stiff each fail at least one check the right model passes.
    #[test]
    fn wrong_models_fail_the_checks() {
        let right = metrics(&[]);
        let speed = |m: &BTreeMap<String, f64>| {
            rel(m, "plastic_speed_mps", "plastic_speed_closed_form_mps")
        };
        let surface = |m: &BTreeMap<String, f64>| {
            rel(
                m,
                "surface_velocity_mps",
                "surface_velocity_closed_form_mps",
            )
        };
        let hel = |m: &BTreeMap<String, f64>| rel(m, "precursor_stress_Pa", "hel_closed_form_Pa");
        assert!(speed(&right).abs() < 0.012, "{right:?}");
        assert!(surface(&right).abs() < 0.009, "{right:?}");
        assert!(hel(&right).abs() < 1e-9, "{right:?}");
        let never = metrics(&[("model_yield_stress", 1e12)]);
        assert!(hel(&never) > 0.5 && speed(&never) > 0.2, "{never:?}");
        let perfect = metrics(&[("model_tangent_modulus", 0.0)]);
        assert!(speed(&perfect) < -0.025, "{perfect:?}");
        assert!(surface(&perfect) > 0.015, "{perfect:?}");
        let stiff = metrics(&[("model_youngs_modulus", 400e9)]);
        assert!(
            rel(&stiff, "elastic_speed_mps", "elastic_speed_closed_form_mps") > 0.4,
            "{stiff:?}"
        );
    }
}
