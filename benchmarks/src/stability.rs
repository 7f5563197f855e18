//! Stress tests of numerical stability: a CFL sweep on uniform, graded and distorted meshes
//! (elastic and plastic, with contact), the measured critical CFL ratio, and extreme but
//! valid inputs. Every run must either stay bounded (energy balance and impulse identity
//! within their bounds) or stop with a clear error: a silent blow-up is a failure.

use std::path::Path;

use impact_solver::scene::{DtChoice, End, Hardening, Load};
use impact_solver::stable_step::Estimate;
use impact_solver::{simulate, Error, Quiet, Scene};

use crate::common::{markdown_table, paper, write_csv};

/// Energy balance bound of an accurate run (1 %: coarse meshes, cfl up to 1).
const BALANCE_BOUND: f64 = 1e-2;
/// Beyond this the energy is not accounted for: a blow-up (the solver's own guard for
/// energy-consistent scenes is the same 10 %).
const BLOW_UP: f64 = 0.1;

/// One run's row: its status, the largest energy balance error and the impulse identity's
/// error (both relative; None when the run stopped before the end, so there are none),
/// and a note (steps run, or where and why it stopped).
struct Outcome {
    status: &'static str,
    balance: Option<f64>,
    impulse_error: Option<f64>,
    note: String,
}

impl Outcome {
    /// The two error cells: the values, or for a run that did not finish what happened
    /// instead (a stopped run has no end-of-run errors; "NaN" read as a computed value).
    fn error_cells(&self) -> [String; 2] {
        match (self.balance, self.impulse_error) {
            (Some(b), Some(i)) => [format!("{b:.2e}"), format!("{i:.1e}")],
            _ => [
                format!("none ({})", self.status),
                format!("none ({})", self.status),
            ],
        }
    }
}

fn attempt(scene: &Scene) -> Outcome {
    match simulate(scene, &mut Quiet) {
        Ok(o) => {
            let s = &o.summary;
            let finite = o.history.values.iter().all(|x| x.is_finite());
            let impulse_error = s.impulse_momentum_error.unwrap_or(0.0);
            let e = s.max_energy_balance_error;
            let status = if !finite || e >= BLOW_UP || impulse_error >= 1e-9 {
                "UNBOUNDED"
            } else if e < BALANCE_BOUND {
                "bounded"
            } else {
                "coarse" // bounded, but the discretisation error exceeds 1 %
            };
            Outcome {
                status,
                balance: Some(s.max_energy_balance_error),
                impulse_error: Some(impulse_error),
                note: format!("{} steps", s.n_steps),
            }
        }
        Err(Error::Run { step, time_s, what }) => Outcome {
            status: "stopped",
            balance: None,
            impulse_error: None,
            note: format!(
                "stopped at t = {time_s:.3e} s (step {step}): {}",
                stop_reason(&what)
            ),
        },
        Err(e) => Outcome {
            status: "refused",
            balance: None,
            impulse_error: None,
            note: e.to_string(),
        },
    }
}

/// A stop's reason in a few words: the solver's "unstable" stops are a blow-up caught (the
/// energy balance or the contact law left its bound), other stops keep their first clause.
fn stop_reason(what: &str) -> String {
    let first = what.split(':').next().unwrap_or(what);
    if first.trim() == "unstable" {
        "blow-up caught by the solver (unstable)".to_string()
    } else {
        first.to_string()
    }
}

fn small(plastic: bool, mesh: &str) -> Scene {
    let mut s = paper(plastic);
    s.mesh.nx = 20;
    s.mesh.ny = 4;
    match mesh {
        "graded" => s.mesh.grading = 4.0,
        "distorted" => s.mesh.distortion = 0.3,
        _ => {}
    }
    s.output.every = Some(1e-4);
    s.time.allow_unstable_dt = true;
    s
}

/// Whether a run at `cfl` stays stable for 5000 steps.
fn stable_at(base: &Scene, cfl: f64) -> bool {
    let mut s = base.clone();
    s.time.dt = DtChoice::Cfl(cfl);
    let dt_guess = simulate(
        &{
            let mut probe = s.clone();
            probe.time.end = End::At(1e-12);
            probe
        },
        &mut Quiet,
    )
    .map(|o| o.summary.dt)
    .unwrap_or(1e-7);
    s.time.end = End::At(5000.0 * dt_guess);
    matches!(attempt(&s).status, "bounded")
}

/// Bisection of the critical ratio (CFL fraction of `base`'s estimate) between a stable and
/// an unstable CFL.
fn critical_ratio(base: &Scene, quick: bool) -> String {
    let (mut lo, mut hi) = (0.5, 4.0);
    if stable_at(base, hi) {
        return "> 4".into();
    }
    if !stable_at(base, lo) {
        return "< 0.5".into();
    }
    for _ in 0..(if quick { 4 } else { 10 }) {
        let mid = 0.5 * (lo + hi);
        if stable_at(base, mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    format!("{lo:.3} .. {hi:.3}")
}

pub fn run(out: &Path, quick: bool) -> anyhow::Result<()> {
    let cfls: Vec<f64> = if quick {
        vec![0.3, 0.9, 1.2]
    } else {
        (1..=13).map(|i| i as f64 / 10.0).collect()
    };
    let mut rows = Vec::new();
    let mut violations = 0;
    let mut critical = Vec::new();
    for mesh in ["uniform", "graded", "distorted"] {
        for plastic in [false, true] {
            let base = small(plastic, mesh);
            for &cfl in &cfls {
                let mut s = base.clone();
                s.time.dt = DtChoice::Cfl(cfl);
                let o = attempt(&s);
                let [balance, impulse] = o.error_cells();
                if cfl < 1.0 && o.status != "bounded" {
                    violations += 1;
                }
                rows.push(vec![
                    mesh.into(),
                    if plastic { "plastic" } else { "elastic" }.into(),
                    format!("{cfl:.1}"),
                    o.status.into(),
                    balance,
                    impulse,
                    o.note,
                ]);
            }
            for estimate in [Estimate::Element, Estimate::Global] {
                let mut b = base.clone();
                b.time.dt_estimate = estimate;
                critical.push(vec![
                    mesh.into(),
                    if plastic { "plastic" } else { "elastic" }.into(),
                    estimate.name().into(),
                    critical_ratio(&b, quick),
                ]);
            }
        }
    }
    let header = [
        "mesh",
        "material",
        "cfl",
        "status",
        "max_balance_error",
        "impulse_error",
        "note",
    ];
    write_csv(&out.join("stability-cfl.csv"), &header, &rows)?;
    let mut md = String::from("## CFL sweep (20x4 mesh, impact with contact, 3 ms)\n\n");
    md += &markdown_table(&header, &rows);
    md += &format!("\nRuns below cfl 1.0 not bounded: {violations}\n\n## Measured critical ratio (stable for 5000 steps)\n\n");
    md += &markdown_table(&["mesh", "material", "estimate", "critical cfl"], &critical);
    let extreme = extreme_inputs(quick);
    let eheader = [
        "case",
        "status",
        "max_balance_error",
        "impulse_error",
        "note",
    ];
    write_csv(&out.join("stability-extreme.csv"), &eheader, &extreme)?;
    md += "\n## Extreme but valid inputs (20x4 mesh unless said)\n\nStatus: `bounded` (energy balance < 1 %, impulse identity to round-off), `coarse` (bounded, balance 1-10 %: the time step resolves the event coarsely), `stopped` (a clear error), `UNBOUNDED` (a silent blow-up: a failure).\n\n";
    md += &markdown_table(&eheader, &extreme);
    std::fs::write(out.join("stability.md"), &md)?;
    println!("{md}");
    let silent = rows
        .iter()
        .chain(extreme.iter())
        .filter(|r| r.iter().any(|c| c == "UNBOUNDED"))
        .count();
    anyhow::ensure!(
        violations == 0,
        "{violations} runs below cfl 1 were not bounded"
    );
    anyhow::ensure!(
        silent == 0,
        "{silent} runs ended unbounded without an error"
    );
    Ok(())
}

fn extreme_inputs(quick: bool) -> Vec<Vec<String>> {
    let mut cases: Vec<(String, Scene)> = Vec::new();
    let impactor = |f: &dyn Fn(&mut impact_solver::scene::Impactor)| {
        let mut s = small(true, "uniform");
        s.time.dt = DtChoice::Cfl(0.8);
        if let Load::Impactor(i) = &mut s.load {
            f(i);
        }
        s
    };
    for v in [0.01, 100.0] {
        cases.push((format!("velocity {v} m/s"), impactor(&|i| i.velocity = v)));
    }
    for m in [0.01, 1000.0] {
        cases.push((format!("mass {m} kg"), impactor(&|i| i.mass = m)));
    }
    for r in [1e-4, 1.0] {
        cases.push((
            format!("nose radius {r} m"),
            impactor(&|i| i.nose_radius = r),
        ));
    }
    for (name, e) in [
        ("very soft plate E = 1 GPa", 1e9),
        ("very stiff plate E = 2 TPa", 2e12),
    ] {
        let mut s = impactor(&|_| {});
        s.material.youngs_modulus = e;
        if let Some(p) = &mut s.material.plasticity {
            p.hardening = Hardening::Linear {
                tangent_modulus: 0.0075 * e,
            };
        }
        cases.push((name.into(), s));
    }
    for (name, nx, ny) in [
        ("element aspect 10 (long)", 4, 8),
        ("element aspect 10 (tall)", 40, 2),
    ] {
        let mut s = impactor(&|_| {});
        s.mesh.nx = nx;
        s.mesh.ny = ny;
        cases.push((name.into(), s));
    }
    for (name, et) in [
        ("zero hardening", 0.0),
        ("strong hardening E_t = E/2", 103.5e9),
    ] {
        let mut s = impactor(&|_| {});
        if let Some(p) = &mut s.material.plasticity {
            p.hardening = Hardening::Linear {
                tangent_modulus: et,
            };
        }
        cases.push((name.into(), s));
    }
    let steps = if quick { 100_000.0 } else { 1_000_000.0 };
    let mut long = paper(false);
    long.mesh.nx = 10;
    long.mesh.ny = 2;
    long.output.every = Some(1e-3);
    long.time.dt = DtChoice::Fixed(5e-7);
    long.time.end = End::At(steps * 5e-7);
    cases.push((format!("long run, {steps:.0} steps (10x2, elastic)"), long));
    cases
        .into_iter()
        .map(|(name, scene)| {
            let o = attempt(&scene);
            let [balance, impulse] = o.error_cells();
            vec![name, o.status.into(), balance, impulse, o.note]
        })
        .collect()
}

#[cfg(test)]
mod tests {
    //! A run that stops prints what happened, not NaN (the page printed "NaN | NaN" for the
    //! stopped runs of the CFL sweep and the extreme inputs).
    use super::*;

    #[test]
    fn a_stopped_run_says_where_and_why_not_nan() {
        let mut s = small(false, "uniform");
        s.time.dt = DtChoice::Cfl(1.2);
        let o = attempt(&s);
        assert_eq!(o.status, "stopped");
        assert_eq!(o.error_cells(), ["none (stopped)", "none (stopped)"]);
        assert!(
            o.note.starts_with("stopped at t = ") && o.note.contains("(step "),
            "{}",
            o.note
        );
        assert!(o.note.contains("blow-up caught"), "{}", o.note);
        let bounded = Outcome {
            status: "bounded",
            balance: Some(2.42e-5),
            impulse_error: Some(6.0e-15),
            note: String::new(),
        };
        assert_eq!(bounded.error_cells(), ["2.42e-5", "6.0e-15"]);
    }
}
