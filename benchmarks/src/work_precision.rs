//! Work-precision: the error against wall time, for every element, mesh level and CFL
//! fraction, on the paper's case (reconstructed plate: elastic and elasto-plastic Table 1
//! impacts, the 86.5 kN pulse) and the plane-strain P wave. The reference of each paper problem
//! is computed once, untimed, with `q4-sri` on a mesh twice as fine as the finest timed level
//! at CFL 0.3; its own error is estimated from its difference to the finest timed `q4-sri` run
//! (Richardson, order 2) and reported beside it. The wave's reference is analytical: the
//! closed-form P-wave speed, against the speed measured by the momentum deficit of the layer
//! above a mid-depth probe (the verification builtin `plane-wave`).

use std::path::Path;

use impact_solver::scene::{DtChoice, ElementKind};
use impact_solver::{simulate, History, Outcome, Quiet, Scene};
use plotters::prelude::*;

use impact_analytical::plane_wave::PlaneWave;

use crate::common::{markdown_table, paper, pulse, timed, write_csv};

const ELEMENTS: [ElementKind; 3] = [
    ElementKind::Q4Full,
    ElementKind::Q4Sri,
    ElementKind::Q4OnePoint,
];

struct Problem {
    name: &'static str,
    scene: Scene,
    /// `true`: error of the mid-span displacement history (L2 relative to its peak);
    /// `false`: largest relative error of impulse, final velocity, max displacement.
    history_metric: bool,
}

/// One timed configuration of a problem.
struct Config {
    problem: &'static str,
    element: ElementKind,
    mesh: String,
    cfl: f64,
}

impl Config {
    /// Appends the CSV row (problem, element, mesh, cfl, dt s, error, setup s, loop s) and
    /// returns the plot point (error, total wall time s).
    fn record(
        &self,
        rows: &mut Vec<Vec<String>>,
        dt: f64,
        error: f64,
        setup: f64,
        time_loop: f64,
    ) -> (f64, f64) {
        rows.push(vec![
            self.problem.to_string(),
            self.element.name().to_string(),
            self.mesh.clone(),
            format!("{}", self.cfl),
            format!("{dt:.6e}"),
            format!("{error:.4e}"),
            format!("{setup:.4e}"),
            format!("{time_loop:.4e}"),
        ]);
        (error.max(1e-12), (setup + time_loop).max(1e-6))
    }
}

/// The plane-strain P wave through the 20 mm thickness, 4 x ny elements (ny = `levels`):
/// relative error of the measured speed against c_P.
fn wave_rows(
    elements: &[ElementKind],
    levels: &[usize],
    cfls: &[f64],
    repeats: usize,
    rows: &mut Vec<Vec<String>>,
) -> anyhow::Result<Vec<Series>> {
    let mut series = Vec::new();
    for &element in elements {
        for &cfl in cfls {
            let mut points = Vec::new();
            for &ny in levels {
                let wave = PlaneWave::new("p", ny, element, cfl).map_err(anyhow::Error::msg)?;
                let (setup, time_loop, o) = timed(&wave.scene, repeats)?;
                let speed = wave
                    .measured_speed(&o.history)
                    .map_err(anyhow::Error::msg)?;
                let e = (speed / wave.exact_mps - 1.0).abs();
                let config = Config {
                    problem: "wave-p",
                    element,
                    mesh: format!("4x{}", wave.ny),
                    cfl,
                };
                points.push(config.record(rows, o.summary.dt, e, setup, time_loop));
            }
            series.push((format!("{} cfl {cfl}", element.name()), points));
        }
    }
    Ok(series)
}

fn with(scene: &Scene, element: ElementKind, (nx, ny): (usize, usize), cfl: f64) -> Scene {
    let mut s = scene.clone();
    s.mesh.element = element;
    s.mesh.nx = nx;
    s.mesh.ny = ny;
    s.time.dt = DtChoice::Cfl(cfl);
    s.output.probes.clear();
    s
}

/// Linear interpolation of a history column at time `t`.
fn interpolate(times: &[f64], values: &[f64], t: f64) -> f64 {
    let i = times.partition_point(|&x| x <= t).clamp(1, times.len() - 1);
    let (t0, t1) = (times[i - 1], times[i]);
    let w = if t1 > t0 {
        ((t - t0) / (t1 - t0)).clamp(0.0, 1.0)
    } else {
        0.0
    };
    values[i - 1] * (1.0 - w) + values[i] * w
}

fn history_error(run: &History, reference: &History) -> f64 {
    let col = |h: &History, c: &str| h.column(c).expect("history column");
    let (rt, rv) = (col(reference, "time_s"), col(reference, "mid_uy_m"));
    let (t, v) = (col(run, "time_s"), col(run, "mid_uy_m"));
    let peak = rv.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let sq: f64 = t
        .iter()
        .zip(&v)
        .map(|(t, v)| (v - interpolate(&rt, &rv, *t)).powi(2))
        .sum();
    (sq / t.len() as f64).sqrt() / peak
}

fn robust(o: &Outcome) -> [f64; 3] {
    let s = &o.summary;
    [
        s.impulse,
        s.final_impactor_velocity.unwrap_or(0.0),
        s.max_plate_displacement,
    ]
}

fn error(problem: &Problem, run: &Outcome, reference: &Outcome) -> f64 {
    if problem.history_metric {
        history_error(&run.history, &reference.history)
    } else {
        robust(run)
            .iter()
            .zip(robust(reference))
            .map(|(a, b)| ((a - b) / b).abs())
            .fold(0.0, f64::max)
    }
}

pub fn run(out: &Path, quick: bool) -> anyhow::Result<()> {
    let levels: &[(usize, usize)] = if quick {
        &[(10, 2), (20, 4)]
    } else {
        &[(10, 2), (20, 4), (40, 8), (80, 16)]
    };
    let cfls: &[f64] = if quick { &[0.9] } else { &[0.3, 0.6, 0.9] };
    let repeats = if quick { 1 } else { 2 };
    let problems = [
        Problem {
            name: "impact-elastic",
            scene: paper(false),
            history_metric: false,
        },
        Problem {
            name: "impact-plastic",
            scene: paper(true),
            history_metric: false,
        },
        Problem {
            name: "pulse-elastic",
            scene: pulse(),
            history_metric: true,
        },
    ];
    let finest = *levels.last().expect("levels");
    let mut rows = Vec::new();
    let mut reference_rows = Vec::new();
    for p in &problems {
        let reference_level = (2 * finest.0, 2 * finest.1);
        let reference = simulate(
            &with(&p.scene, ElementKind::Q4Sri, reference_level, 0.3),
            &mut Quiet,
        )?;
        let finest_sri = simulate(&with(&p.scene, ElementKind::Q4Sri, finest, 0.3), &mut Quiet)?;
        let own_error = error(p, &finest_sri, &reference) / 3.0;
        reference_rows.push(vec![
            p.name.to_string(),
            format!("q4-sri {}x{} cfl 0.3", reference_level.0, reference_level.1),
            format!("{own_error:.2e}"),
        ]);
        let mut series = Vec::new();
        for element in ELEMENTS {
            for &cfl in cfls {
                let mut points = Vec::new();
                for &level in levels {
                    let scene = with(&p.scene, element, level, cfl);
                    let (setup, time_loop, o) = timed(&scene, repeats)?;
                    let e = error(p, &o, &reference);
                    let config = Config {
                        problem: p.name,
                        element,
                        mesh: format!("{}x{}", level.0, level.1),
                        cfl,
                    };
                    points.push(config.record(&mut rows, o.summary.dt, e, setup, time_loop));
                }
                series.push((format!("{} cfl {cfl}", element.name()), points));
            }
        }
        plot(
            &out.join(format!("work-precision-{}.svg", p.name)),
            p.name,
            if p.history_metric {
                Axis::History
            } else {
                Axis::Robust
            },
            &series,
        )?;
        println!("{}: {}", p.name, pareto_summary(&rows, p.name));
    }
    // The wave's levels: elements through the thickness (80 is the wave suite's default mesh).
    let wave_levels: &[usize] = if quick { &[10, 20] } else { &[10, 20, 40, 80] };
    let wave_series = wave_rows(&ELEMENTS, wave_levels, cfls, repeats, &mut rows)?;
    plot(
        &out.join("work-precision-wave-p.svg"),
        "wave-p",
        Axis::WaveSpeed,
        &wave_series,
    )?;
    println!("wave-p: {}", pareto_summary(&rows, "wave-p"));
    reference_rows.push(vec![
        "wave-p".to_string(),
        "closed-form c_P = sqrt((lambda + 2 mu) / rho) (analytical)".to_string(),
        "0".to_string(),
    ]);
    let header = [
        "problem", "element", "mesh", "cfl", "dt_s", "error", "setup_s", "loop_s",
    ];
    write_csv(&out.join("work-precision.csv"), &header, &rows)?;
    let rheader = ["problem", "reference", "estimated_reference_error"];
    write_csv(
        &out.join("work-precision-references.csv"),
        &rheader,
        &reference_rows,
    )?;
    println!("{}", markdown_table(&rheader, &reference_rows));
    Ok(())
}

/// The configurations on the Pareto front (no other is both faster and more accurate).
fn pareto_summary(rows: &[Vec<String>], problem: &str) -> String {
    let pts: Vec<(&Vec<String>, f64, f64)> = rows
        .iter()
        .filter(|r| r[0] == problem)
        .map(|r| {
            let e: f64 = r[5].parse().unwrap_or(f64::INFINITY);
            let t: f64 = r[6].parse::<f64>().unwrap_or(0.0) + r[7].parse::<f64>().unwrap_or(0.0);
            (r, e, t)
        })
        .collect();
    let mut front: Vec<_> = pts
        .iter()
        .filter(|(_, e, t)| {
            !pts.iter()
                .any(|(_, e2, t2)| (e2 < e && t2 <= t) || (e2 <= e && t2 < t))
        })
        .collect();
    front.sort_by(|a, b| a.2.total_cmp(&b.2));
    let names: Vec<String> = front
        .iter()
        .map(|(r, e, t)| format!("{} {} cfl {} (error {e:.1e}, {t:.3} s)", r[1], r[2], r[3]))
        .collect();
    format!("Pareto front: {}", names.join("; "))
}

type Series = (String, Vec<(f64, f64)>);

/// What the error axis of a plot measures.
#[derive(Clone, Copy)]
enum Axis {
    Robust,
    History,
    WaveSpeed,
}

fn plot(path: &Path, title: &str, axis: Axis, series: &[Series]) -> anyhow::Result<()> {
    let all = series.iter().flat_map(|s| s.1.iter());
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, 0.0f64, f64::INFINITY, 0.0f64);
    for &(x, y) in all {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    let root = SVGBackend::new(path, (760, 520)).into_drawing_area();
    root.fill(&WHITE)?;
    let xlabel = match axis {
        Axis::History => "error: RMS of mid-span displacement history / its peak",
        Axis::Robust => "error: max relative error of impulse, final velocity, max displacement",
        Axis::WaveSpeed => "error: |measured P-wave speed / closed form - 1|",
    };
    let mut chart = ChartBuilder::on(&root)
        .caption(format!("work-precision: {title}"), ("sans-serif", 18))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(
            (x0 / 1.5..x1 * 1.5).log_scale(),
            (y0 / 1.5..y1 * 1.5).log_scale(),
        )?;
    chart
        .configure_mesh()
        .x_desc(xlabel)
        .y_desc("wall time, s (min of repeats)")
        .x_label_formatter(&|v| format!("{v:.0e}"))
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .draw()?;
    for (i, (name, points)) in series.iter().enumerate() {
        let color = Palette99::pick(i).to_rgba();
        chart
            .draw_series(LineSeries::new(
                points.iter().copied(),
                color.stroke_width(2),
            ))?
            .label(name)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 16, y)], color.stroke_width(2))
            });
        chart.draw_series(points.iter().map(|&p| Circle::new(p, 3, color.filled())))?;
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperRight)
        .draw()?;
    root.present()?;
    Ok(())
}
