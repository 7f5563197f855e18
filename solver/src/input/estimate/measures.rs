//! What the estimates are made of, from the validated scene alone: the P-wave speed and the
//! smallest element (the stable step's estimate), the inputs beyond any physical magnitude
//! ([`EXTREME`]), and counts and byte sizes in words for messages.

use crate::input::error::shown;
use crate::input::scene::{Material, Model, Scene};

/// The plane-strain P-wave speed `sqrt(E (1 - nu) / (rho (1 + nu) (1 - 2 nu)))`, m/s.
pub(crate) fn p_wave_speed(m: &Material) -> f64 {
    let nu = m.poisson_ratio;
    (m.youngs_modulus * (1.0 - nu) / (m.density * (1.0 + nu) * (1.0 - 2.0 * nu))).sqrt()
}

/// Smallest element length along x, m (mid-span for graded meshes).
pub(crate) fn smallest_element_length(scene: &Scene) -> f64 {
    let half_elements = match scene.mesh.model {
        Model::Half => scene.mesh.nx,
        Model::Full => scene.mesh.nx / 2,
    }
    .max(1) as f64;
    let half_length = 0.5 * scene.plate.length;
    let grading = scene.mesh.grading;
    if half_elements <= 1.0 || grading == 1.0 {
        return half_length / half_elements;
    }
    // Geometric sizes r^i, i = 0..n-1, r = grading^(-1/(n-1)): the last (r^(n-1) = 1/grading)
    // over their sum.
    let r = grading.powf(-1.0 / (half_elements - 1.0));
    let total = (1.0 - r.powf(half_elements)) / (1.0 - r);
    half_length / grading / total
}

/// `1.0e9`, `12 345` style counts: exact below a million, otherwise 3 digits.
pub fn count(x: f64) -> String {
    if x < 1.0e6 {
        format!("{x:.0}")
    } else {
        format!("{x:.2e}")
    }
}

/// Bytes in kB, MB, GB, TB (powers of 1000), 3 significant digits: `900 GB`, `23.1 GB`.
pub fn bytes(b: f64) -> String {
    let (x, unit) = scaled(b);
    let digits = if x >= 100.0 || unit == "B" {
        0
    } else if x >= 10.0 {
        1
    } else {
        2
    };
    format!("{x:.digits$} {unit}")
}

/// A `--max-memory` value at least `b`: two significant digits rounded up, `990G`.
pub fn limit_above(b: f64) -> String {
    let (x, unit) = scaled(b);
    let step = if x >= 10.0 { 1.0 } else { 0.1 };
    let up = ((x / step).ceil() * step * 10.0).round() / 10.0;
    format!("{up}{}", unit.trim_end_matches('B'))
}

fn scaled(b: f64) -> (f64, &'static str) {
    let units = ["B", "kB", "MB", "GB", "TB", "PB"];
    let mut x = b;
    let mut u = 0;
    while x >= 1000.0 && u + 1 < units.len() {
        x /= 1000.0;
        u += 1;
    }
    (x, units[u])
}

/// SI values of this problem lie between ~1e-12 (time steps, s) and ~1e13 (moduli, Pa); an
/// input beyond 1e-30 .. 1e30 in magnitude is a typo, and products of two such numbers leave
/// double precision (inf, NaN).
pub const EXTREME: (f64, f64) = (1.0e-30, 1.0e30);

/// The numbers beyond [`EXTREME`] in magnitude: above 1e30, or below 1e-30 for a quantity
/// the scene requires to be > 0 (a quantity that may be 0, such as a Poisson's ratio or a
/// probe's coordinate, may be as small as it likes), in field order.
pub fn extreme_fields(scene: &Scene) -> Vec<(String, f64)> {
    let (tiny, huge) = EXTREME;
    scene
        .fields
        .iter()
        .filter_map(|(field, read)| {
            let x = read.value?;
            let a = x.abs();
            (a > huge || (read.positive && a < tiny)).then(|| (field.to_string(), x))
        })
        .collect()
}

/// [`extreme_fields`] as `field = value`, for a run whose numbers overflowed (inf or NaN).
pub fn extreme_inputs(scene: &Scene) -> Vec<String> {
    extreme_fields(scene)
        .into_iter()
        .map(|(field, x)| format!("{field} = {}", shown(x)))
        .collect()
}
