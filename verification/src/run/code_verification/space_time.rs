//! The `mms-space` and `mms-time` builtins: observed orders of the manufactured
//! elastodynamics problem ([`super::manufactured`]) under mesh refinement at a fixed CFL
//! (space and time errors both O(h^2): formal order 2) and under time-step halving on a fixed
//! mesh (formal order 2 of central differences).

use std::collections::BTreeMap;

use impact_solver::material::Elastic;
use impact_solver::scene::ElementKind;
use impact_solver::History;
use serde_json::Value;

use super::driver::{self, mapped_mesh, weighted_l2, Steps};
use super::manufactured::Manufactured;
use super::orders::{difference_orders, largest_step, pair_orders};
use crate::definition::run_data::RunData;
use crate::run::builtin_params::{param, param_levels};

type Params = BTreeMap<String, Value>;

/// Strip 200 mm x 50 mm of steel; meshes 4 n x n (square elements before the mapping).
const LENGTH: f64 = 0.2;
const HEIGHT: f64 = 0.05;
const ASPECT: usize = 4;

pub(crate) fn element(p: &Params) -> Result<ElementKind, String> {
    let name = p.get("element").and_then(Value::as_str).unwrap_or("q4-sri");
    [
        ElementKind::Q4Full,
        ElementKind::Q4Sri,
        ElementKind::Q4OnePoint,
    ]
    .into_iter()
    .find(|k| k.name() == name)
    .ok_or_else(|| format!("param element: {name:?} is not q4-full, q4-sri or q4-1pt"))
}

/// The problem: steel (E 207 GPa, nu 0.3, 7850 kg/m^3) and a forcing frequency equal to the
/// first longitudinal frequency of the strip `pi c_P / L`, run for one period. The solver's
/// material gets `modulus_scale` x E (1 by default; a negative control: a model that is
/// wrong by a fraction must lose the order).
fn problem(p: &Params) -> Result<(Manufactured, Elastic), String> {
    let (e, nu, rho) = (207e9, param(p, "poisson_ratio", 0.3)?, 7850.0);
    let c_p = (e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu) * rho)).sqrt();
    let ms = Manufactured::new(
        LENGTH,
        HEIGHT,
        e,
        nu,
        rho,
        std::f64::consts::PI * c_p / LENGTH,
    )?;
    Ok((ms, Elastic::new(e * param(p, "modulus_scale", 1.0)?, nu)))
}

/// A history whose rows are refinement levels: `time_s` holds log2 of the refinement
/// (0 at the coarsest), then the observed orders (attached to the finer level of each pair or
/// triplet) and the formal order, for the report's order plot.
fn order_history(columns: &[&str], rows: Vec<Vec<f64>>) -> History {
    History {
        columns: columns.iter().map(|s| s.to_string()).collect(),
        values: rows.into_iter().flatten().collect(),
    }
}

pub fn space(p: &Params) -> Result<RunData, String> {
    let kind = element(p)?;
    let (ms, elastic) = problem(p)?;
    let levels = param_levels(p, "levels", &[4, 8, 16, 32])?;
    let cfl = param(p, "cfl", 0.5)?;
    let eps = param(p, "distortion", 0.03)?;
    if levels.len() < 3 || levels.windows(2).any(|w| w[1] != 2 * w[0]) {
        return Err("param levels: at least three, each twice the previous".into());
    }
    let mut m = BTreeMap::new();
    let (mut l2, mut mx) = (Vec::new(), Vec::new());
    for &ny in &levels {
        let mesh = mapped_mesh(LENGTH, HEIGHT, ASPECT * ny, ny, eps)?;
        let r = driver::run(&ms, &elastic, &mesh, kind, Steps::Cfl(cfl))?;
        m.insert(format!("l2_error_ny{ny}"), r.l2_error);
        m.insert(format!("max_error_ny{ny}"), r.max_error);
        m.insert(format!("steps_ny{ny}"), r.steps as f64);
        l2.push(r.l2_error);
        mx.push(r.max_error);
    }
    let (p_l2, p_max) = (pair_orders(&l2, 2.0), pair_orders(&mx, 2.0));
    for (k, w) in levels.windows(2).enumerate() {
        m.insert(format!("order_l2_ny{}_ny{}", w[0], w[1]), p_l2[k]);
        m.insert(format!("order_max_ny{}_ny{}", w[0], w[1]), p_max[k]);
    }
    let last = p_l2.len() - 1;
    m.insert("order_l2_finest".into(), p_l2[last]);
    m.insert("order_max_finest".into(), p_max[last]);
    m.insert("order_l2_largest_step".into(), largest_step(&p_l2));
    m.insert("order_max_largest_step".into(), largest_step(&p_max));
    m.insert(
        "order_largest_step".into(),
        largest_step(&p_l2).max(largest_step(&p_max)),
    );
    let rows = (0..p_l2.len())
        .map(|k| vec![(k + 1) as f64, p_l2[k], p_max[k], 2.0])
        .collect();
    let mut histories = BTreeMap::new();
    histories.insert(
        String::new(),
        order_history(
            &[
                "time_s",
                "observed_order_l2",
                "observed_order_max",
                "formal_order",
            ],
            rows,
        ),
    );
    Ok(RunData {
        metrics: m,
        histories,
        ..Default::default()
    })
}

pub fn time(p: &Params) -> Result<RunData, String> {
    let kind = element(p)?;
    let (ms, elastic) = problem(p)?;
    let ny = param(p, "ny", 16.0)? as usize;
    let cfl = param(p, "cfl", 0.8)?;
    let halvings = param(p, "halvings", 3.0)? as u32;
    let eps = param(p, "distortion", 0.03)?;
    if halvings < 3 {
        return Err("param halvings: at least 3 (two triplets)".into());
    }
    let mesh = mapped_mesh(LENGTH, HEIGHT, ASPECT * ny, ny, eps)?;
    let base = driver::run(&ms, &elastic, &mesh, kind, Steps::Cfl(cfl))?;
    let mut finals = vec![base.final_displacement.clone()];
    for k in 1..=halvings {
        let r = driver::run(&ms, &elastic, &mesh, kind, Steps::Count(base.steps << k))?;
        finals.push(r.final_displacement);
    }
    let amplitude = weighted_l2(&finals[0], &base.mass, |_, x| x).max(f64::MIN_POSITIVE);
    let diffs: Vec<f64> = finals
        .windows(2)
        .map(|w| weighted_l2(&w[0], &base.mass, |d, x| x - w[1][d]) / amplitude)
        .collect();
    let orders = difference_orders(&diffs, 2.0);
    let mut m = BTreeMap::new();
    for (k, d) in diffs.iter().enumerate() {
        m.insert(format!("difference_dt{}_dt{}", 1 << k, 1 << (k + 1)), *d);
    }
    for (k, o) in orders.iter().enumerate() {
        m.insert(
            format!("order_dt{}_dt{}_dt{}", 1 << k, 1 << (k + 1), 1 << (k + 2)),
            *o,
        );
    }
    m.insert("order_finest".into(), orders[orders.len() - 1]);
    m.insert("order_largest_step".into(), largest_step(&orders));
    m.insert("dt_over_critical".into(), base.dt / base.dt_critical);
    m.insert("base_steps".into(), base.steps as f64);
    let rows = (0..orders.len())
        .map(|k| vec![(k + 2) as f64, orders[k], 2.0])
        .collect();
    let mut histories = BTreeMap::new();
    histories.insert(
        String::new(),
        order_history(&["time_s", "observed_order", "formal_order"], rows),
    );
    Ok(RunData {
        metrics: m,
        histories,
        ..Default::default()
    })
}
