//! The `probe-point` builtin: what a scene's probes report, against the stress recomputed in
//! the harness at the point a probe is documented to read (README: "the integration point
//! nearest a named point, in the element containing it"; x mirrored into the half model).
//!
//! An elastic example impact (q4-full or q4-1pt, half model) runs as a user runs it, with
//! probes at points chosen inside elements away from their points' bisectors (one mirrored from
//! the other half), history every step and field frames every 50 us. At each frame the harness
//! finds, from the mesh's coordinates alone, the element holding the (folded) probe point and
//! its nearest integration point (2 x 2 Gauss or the centroid), and computes the plane-strain
//! elastic stress `D B(xi) u` there from the frame's nodal displacements (small strain,
//! `szz = lambda (exx + eyy)`; written here, not the solver's element code). Over a bending
//! plate the field is, to first order, linear through the thickness and along the span, so the
//! value identifies the point: the same recomputation at the element's other points and at the
//! same point of its four neighbours (what a probe reading a wrong point would report) is
//! reported as `wrong_point_error_min`, the smallest over the probes of the largest, over the
//! frames, difference from the right point's value.
//!
//! Metrics are relative to the largest stress component the probes see over the frames (Pa).

use std::collections::BTreeMap;

use impact_solver::integrator::{FieldFrame, Observer};
use impact_solver::material::Stress;
use serde_json::Value;

use super::scene_text::run_scene_text;
use crate::definition::run_data::RunData;
use crate::run::builtin_params::param;

/// The probes (m, x from the clamped end, y from the bottom): inside the elements of the
/// 40 x 8 half mesh of the 200 x 20 mm plate (5 x 2.5 mm elements), off their points'
/// bisectors; C is mirrored from the other half (x > 0.1 m).
const PROBES: [(&str, [f64; 2]); 3] = [
    ("A", [0.0962, 0.0031]),
    ("B", [0.0414, 0.0168]),
    ("C", [0.1211, 0.0186]),
];

fn scene_text(element: &str) -> String {
    let probes: Vec<String> = PROBES
        .iter()
        .map(|(n, p)| format!("{n}: {{x: {}, y: {}}}", p[0], p[1]))
        .collect();
    format!(
        "plate: {{length: 0.2, width: 0.2, thickness: 0.02}}\n\
         material: {{density: 7850.0, youngs_modulus: 207.0e9, poisson_ratio: 0.3}}\n\
         mesh: {{nx: 40, ny: 8, element: {element}, model: half}}\n\
         load:\n  impactor: {{mass: 18.0, velocity: 10.0, nose_radius: 0.010, youngs_modulus: 207.0e9, \
         poisson_ratio: 0.3, contact_law: {{paper: {{length_unit: 1.0}}}}}}\n\
         time: {{end: 4.0e-4, dt: {{cfl: 0.8}}}}\n\
         output: {{probes: {{{}}}, fields: {{every: 5.0e-5}}}}\n",
        probes.join(", ")
    )
}

/// Keeps every field frame's time (s) and nodal displacements (m).
#[derive(Default)]
struct Frames(Vec<(f64, Vec<[f64; 2]>)>);

impl Observer for Frames {
    fn wants_fields(&self) -> bool {
        true
    }
    fn fields(&mut self, frame: FieldFrame) -> impact_solver::Result<()> {
        self.0.push((frame.time, frame.displacement));
        Ok(())
    }
}

/// Plane-strain elastic stress `[xx, yy, zz, xy]` (Pa) at `xi` of the element with node
/// coordinates `c` (m, counter-clockwise from (-1, -1)) and displacements `u` (m).
fn stress_at(c: &[[f64; 2]; 4], u: &[[f64; 2]; 4], xi: [f64; 2], (lam, mu): (f64, f64)) -> Stress {
    let s = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];
    let dxi: [f64; 4] = std::array::from_fn(|a| 0.25 * s[a][0] * (1.0 + xi[1] * s[a][1]));
    let deta: [f64; 4] = std::array::from_fn(|a| 0.25 * s[a][1] * (1.0 + xi[0] * s[a][0]));
    let j = |d: &[f64; 4], k: usize| (0..4).map(|a| d[a] * c[a][k]).sum::<f64>();
    let (j11, j12, j21, j22) = (j(&dxi, 0), j(&dxi, 1), j(&deta, 0), j(&deta, 1));
    let det = j11 * j22 - j12 * j21;
    let (mut exx, mut eyy, mut gxy) = (0.0, 0.0, 0.0);
    for a in 0..4 {
        let dx = (j22 * dxi[a] - j12 * deta[a]) / det;
        let dy = (-j21 * dxi[a] + j11 * deta[a]) / det;
        exx += dx * u[a][0];
        eyy += dy * u[a][1];
        gxy += dy * u[a][0] + dx * u[a][1];
    }
    let tr = lam * (exx + eyy);
    [tr + 2.0 * mu * exx, tr + 2.0 * mu * eyy, tr, mu * gxy]
}

/// Physical position of `xi` in the element with node coordinates `c`, m.
fn position(c: &[[f64; 2]; 4], xi: [f64; 2]) -> [f64; 2] {
    let s = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];
    let n: [f64; 4] =
        std::array::from_fn(|a| 0.25 * (1.0 + xi[0] * s[a][0]) * (1.0 + xi[1] * s[a][1]));
    [0, 1].map(|k| (0..4).map(|a| n[a] * c[a][k]).sum())
}

/// Parameter: `element` (`q4-full`, the default, or `q4-1pt`).
pub fn probe_point(p: &BTreeMap<String, Value>) -> Result<RunData, String> {
    let element = p
        .get("element")
        .and_then(Value::as_str)
        .unwrap_or("q4-full");
    let points: Vec<[f64; 2]> = match element {
        "q4-full" => {
            let g = 1.0 / 3f64.sqrt();
            vec![[-g, -g], [g, -g], [g, g], [-g, g]]
        }
        "q4-1pt" => vec![[0.0, 0.0]],
        other => {
            return Err(format!(
                "param element: {other}, expected q4-full or q4-1pt"
            ))
        }
    };
    let (e, nu) = (207e9, 0.3);
    let lame = (
        e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)),
        e / (2.0 * (1.0 + nu)),
    );
    let length = param(p, "length", 0.2)?;
    let mut frames = Frames::default();
    let out = run_scene_text(&scene_text(element), "probe-point", &mut frames)?;
    let mesh = &out.mesh.mesh;
    let h = &out.history;
    let times = h.column("time_s").ok_or("probe-point: no time_s column")?;
    // The element holding a point and its neighbours: found from the coordinates alone.
    let contains = |e: usize, x: [f64; 2]| {
        let c = mesh.element_coords(e);
        let (lo, hi) = (c[0], c[2]);
        (lo[0]..=hi[0]).contains(&x[0]) && (lo[1]..=hi[1]).contains(&x[1])
    };
    let (mut err, mut scale, mut wrong_min) = (0.0f64, 0.0f64, f64::INFINITY);
    for (name, at) in PROBES {
        let x = [
            if at[0] > length / 2.0 {
                length - at[0]
            } else {
                at[0]
            },
            at[1],
        ];
        let elem = (0..mesh.elements.len())
            .find(|&e| contains(e, x))
            .ok_or(format!("probe-point: no element holds {name}"))?;
        let c = mesh.element_coords(elem);
        let dist = |xi: &[f64; 2]| {
            let q = position(&c, *xi);
            (q[0] - x[0]).powi(2) + (q[1] - x[1]).powi(2)
        };
        let right = (0..points.len())
            .min_by(|&a, &b| dist(&points[a]).total_cmp(&dist(&points[b])))
            .unwrap_or(0);
        // Candidates a wrong probe could read: (element, point), the right one first.
        let size = [c[2][0] - c[0][0], c[2][1] - c[0][1]];
        let mut candidates = vec![(elem, right)];
        candidates.extend((0..points.len()).filter(|&q| q != right).map(|q| (elem, q)));
        for d in [[-1.0, 0.0], [1.0, 0.0], [0.0, -1.0], [0.0, 1.0]] {
            let y = [x[0] + d[0] * size[0], x[1] + d[1] * size[1]];
            if let Some(n) = (0..mesh.elements.len()).find(|&e| contains(e, y)) {
                candidates.push((n, right));
            }
        }
        let cols = ["sxx", "syy", "szz", "sxy"].map(|k| h.column(&format!("{name}_{k}_Pa")));
        let mut wrong = vec![0.0f64; candidates.len()];
        for (t, disp) in &frames.0 {
            let row = times
                .iter()
                .position(|s| (s - t).abs() <= 1e-12 * t.max(1e-30))
                .ok_or(format!("probe-point: no history row at {t} s"))?;
            let sig: Vec<Stress> = candidates
                .iter()
                .map(|&(e, q)| {
                    let u = mesh.elements[e].map(|n| disp[n as usize]);
                    stress_at(&mesh.element_coords(e), &u, points[q], lame)
                })
                .collect();
            for k in 0..4 {
                let probe = cols[k]
                    .as_ref()
                    .ok_or("probe-point: a probe column is missing")?[row];
                err = err.max((probe - sig[0][k]).abs());
                scale = scale.max(sig[0][k].abs());
                for (w, s) in wrong.iter_mut().zip(&sig).skip(1) {
                    *w = w.max((s[k] - sig[0][k]).abs());
                }
            }
        }
        wrong_min = wrong[1..].iter().fold(wrong_min, |a, &b| a.min(b));
    }
    let metrics = BTreeMap::from([
        ("probe_error".to_string(), err / scale),
        ("wrong_point_error_min".to_string(), wrong_min / scale),
        ("stress_scale_Pa".to_string(), scale),
        ("frames".to_string(), frames.0.len() as f64),
    ]);
    Ok(RunData {
        metrics,
        ..Default::default()
    })
}
