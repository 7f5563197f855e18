//! The `hertz-law` builtin: the solver's line-contact laws (ALGORITHM.md section 5) through
//! its public API: round trips, monotonicity, slopes, the zero branch, the maximum, the stored
//! energy, and eq. (4) in millimetres against the closed form of `impact_analytical`.

use std::collections::BTreeMap;

use impact_analytical::hertz_line;
use impact_solver::contact::{solve_contact_force, LineContactLaw};
use impact_solver::scene::{ContactLawChoice, Impactor, Material, MidSpanNode};

use crate::definition::run_data::RunData;
use crate::run::builtin_params::Params;

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

pub(super) fn hertz_law(_: &Params) -> Result<RunData, String> {
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
        let mm = hertz_line::paper_alpha(p_si * 1e-3, STEEL_E * 1e-6, STEEL_NU, NOSE_R * 1e3, 1.0);
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
    m.insert("pstar_paper_mm_N_per_m".into(), si.max_force_per_width());
    m.insert(
        "pstar_paper_mm_closed_form".into(),
        hertz_line::paper_max_force_per_width(STEEL_E, STEEL_NU, NOSE_R, 1e-3),
    );
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
