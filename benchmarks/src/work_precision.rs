//! Work-precision: the error against wall time, for every element, mesh level and CFL
//! fraction, on the paper's case (reconstructed plate: elastic and elasto-plastic Table 1
//! impacts, the 86.5 kN pulse) and the plane-strain P wave. The reference of each paper problem
//! is `q4-sri` on a mesh twice as fine as the finest timed level at CFL 0.3, computed once,
//! untimed, before any timed run (the elastic ones two at a time), or read from the output
//! folder where this binary left it (`impact-bench references`: `references.rs`). Its own
//! error is estimated from its difference to the finest timed `q4-sri` run at that CFL (that
//! run's outcome, not a second run; Richardson, order 2) and reported beside it. Every
//! configuration is timed by the minimum of its runs (no separate warm-up run), with the
//! number of runs and their spread in the CSV. The wave's reference is analytical: the
//! closed-form P-wave speed, against the speed measured by the momentum deficit of the layer
//! above a mid-depth probe (the verification builtin `plane-wave`).

use std::path::Path;

use impact_solver::scene::{DtChoice, ElementKind};
use impact_solver::{simulate, Outcome, Quiet, Scene};
use plotters::prelude::*;

use impact_analytical::plane_wave::PlaneWave;

use impact_plots::picture::{Area, DataArea, Picture};
use impact_plots::style::{self, Entry, Mark};

use crate::common::{markdown_table, paper, pulse, timed, write_csv, Timing};
use crate::pareto;
use crate::references::{load_or_compute, Measured, Schedule};

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
    /// Appends the CSV row (problem, element, mesh, cfl, dt s, error, setup s, loop s, timed
    /// runs, loop spread) and returns the plot point (error, total wall time s).
    fn record(&self, rows: &mut Vec<Vec<String>>, t: &Timing, error: f64) -> (f64, f64) {
        rows.push(vec![
            self.problem.to_string(),
            self.element.name().to_string(),
            self.mesh.clone(),
            format!("{}", self.cfl),
            format!("{:.6e}", t.outcome.summary.dt),
            format!("{error:.4e}"),
            format!("{:.4e}", t.setup),
            format!("{:.4e}", t.time_loop),
            format!("{}", t.runs),
            format!("{:.3}", t.spread),
        ]);
        (error.max(1e-12), (t.setup + t.time_loop).max(1e-6))
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
                let t = timed(&wave.scene, repeats)?;
                let speed = wave
                    .measured_speed(&t.outcome.history)
                    .map_err(anyhow::Error::msg)?;
                let e = (speed / wave.exact_mps - 1.0).abs();
                let config = Config {
                    problem: "wave-p",
                    element,
                    mesh: format!("4x{}", wave.ny),
                    cfl,
                };
                points.push(config.record(rows, &t, e));
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

fn history_error(run: &Measured, reference: &Measured) -> f64 {
    let (rt, rv) = (&reference.time_s, &reference.mid_uy_m);
    let peak = rv.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let sq: f64 = run
        .time_s
        .iter()
        .zip(&run.mid_uy_m)
        .map(|(t, v)| (v - interpolate(rt, rv, *t)).powi(2))
        .sum();
    (sq / run.time_s.len() as f64).sqrt() / peak
}

fn error(problem: &Problem, run: &Outcome, reference: &Measured) -> f64 {
    let run = Measured::of(run);
    if problem.history_metric {
        history_error(&run, reference)
    } else {
        run.robust
            .iter()
            .zip(reference.robust)
            .map(|(a, b)| ((a - b) / b).abs())
            .fold(0.0, f64::max)
    }
}

/// The sizes of a run: `--quick` (CI) or the default.
pub struct Sizes {
    /// Meshes (nx, ny) of the paper problems.
    levels: &'static [(usize, usize)],
    /// Elements through the thickness of the wave (4 x ny meshes; 80 is the wave suite's
    /// default mesh).
    wave_levels: &'static [usize],
    cfls: &'static [f64],
    /// Timed runs per configuration (short ones more: [`timed`]); the minimum is kept.
    repeats: usize,
}

impl Sizes {
    pub fn new(quick: bool) -> Sizes {
        if quick {
            Sizes {
                levels: &[(10, 2), (20, 4)],
                wave_levels: &[10, 20],
                cfls: &[0.9],
                repeats: 1,
            }
        } else {
            Sizes {
                levels: &[(10, 2), (20, 4), (40, 8), (80, 16)],
                wave_levels: &[10, 20, 40, 80],
                cfls: &[0.3, 0.6, 0.9],
                repeats: 2,
            }
        }
    }

    /// For meta.json: "meshes 10x2, 20x4 (wave 4x10, 4x20); CFL 0.9; 1 timed run (short
    /// runs more)".
    pub fn describe(&self) -> String {
        let meshes: Vec<String> = self
            .levels
            .iter()
            .map(|(x, y)| format!("{x}x{y}"))
            .collect();
        let wave: Vec<String> = self.wave_levels.iter().map(|y| format!("4x{y}")).collect();
        let cfls: Vec<String> = self.cfls.iter().map(|c| c.to_string()).collect();
        format!(
            "meshes {} (wave {}); CFL {}; {} timed run{} (short runs more)",
            meshes.join(", "),
            wave.join(", "),
            cfls.join(", "),
            self.repeats,
            if self.repeats == 1 { "" } else { "s" }
        )
    }
}

/// The CFL fraction of the references, and of the finest timed `q4-sri` run their own error
/// is estimated from.
const REFERENCE_CFL: f64 = 0.3;

/// The reference of each problem: `q4-sri` twice as fine as the finest level of `sizes`, at
/// [`REFERENCE_CFL`], untimed, from `out` when this binary wrote it there (see
/// [`references`](crate::references)), and the mesh level it used.
fn references(
    out: &Path,
    problems: &[Problem],
    sizes: &Sizes,
    schedule: Schedule,
) -> anyhow::Result<(Vec<Measured>, (usize, usize))> {
    let finest = *sizes.levels.last().expect("levels");
    let level = (2 * finest.0, 2 * finest.1);
    let scenes: Vec<(&str, Scene)> = problems
        .iter()
        .map(|p| {
            let scene = with(&p.scene, ElementKind::Q4Sri, level, REFERENCE_CFL);
            (p.name, scene)
        })
        .collect();
    Ok((load_or_compute(out, &scenes, schedule)?, level))
}

/// `impact-bench references`: the references alone, untimed, written to `out` for a later
/// work-precision run there (the main job runs this beside the verification matrix).
pub fn write_references(out: &Path, quick: bool) -> anyhow::Result<()> {
    let (done, level) = references(out, &problems(), &Sizes::new(quick), Schedule::Beside)?;
    println!(
        "work-precision references: {} on q4-sri {}x{} cfl {REFERENCE_CFL} in {}",
        done.len(),
        level.0,
        level.1,
        out.display()
    );
    Ok(())
}

/// The timed configurations of one problem (every element, CFL and level, each against
/// `reference`) as CSV rows and plot series, and the outcome of the finest `q4-sri` run at
/// [`REFERENCE_CFL`] (None when the sizes do not time it).
fn problem_runs(
    p: &Problem,
    reference: &Measured,
    sizes: &Sizes,
    rows: &mut Vec<Vec<String>>,
) -> anyhow::Result<(Vec<Series>, Option<Outcome>)> {
    let finest = *sizes.levels.last().expect("levels");
    let mut series = Vec::new();
    let mut finest_sri = None;
    for element in ELEMENTS {
        for &cfl in sizes.cfls {
            let mut points = Vec::new();
            for &level in sizes.levels {
                let t = timed(&with(&p.scene, element, level, cfl), sizes.repeats)?;
                let config = Config {
                    problem: p.name,
                    element,
                    mesh: format!("{}x{}", level.0, level.1),
                    cfl,
                };
                points.push(config.record(rows, &t, error(p, &t.outcome, reference)));
                if element == ElementKind::Q4Sri && level == finest && cfl == REFERENCE_CFL {
                    finest_sri = Some(t.outcome);
                }
            }
            series.push((format!("{} cfl {cfl}", element.name()), points));
        }
    }
    Ok((series, finest_sri))
}

/// The paper problems of the benchmark.
fn problems() -> [Problem; 3] {
    [
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
    ]
}

pub fn run(out: &Path, quick: bool) -> anyhow::Result<()> {
    let sizes = Sizes::new(quick);
    let problems = problems();
    let finest = *sizes.levels.last().expect("levels");
    let (references, reference_level) = references(out, &problems, &sizes, Schedule::Alone)?;
    let mut rows = Vec::new();
    let mut reference_rows = Vec::new();
    for (p, reference) in problems.iter().zip(&references) {
        let (series, finest_sri) = problem_runs(p, reference, &sizes, &mut rows)?;
        // The finest q4-sri run at the references' CFL, timed above when the sizes have it.
        let finest_sri = match finest_sri {
            Some(o) => o,
            None => simulate(
                &with(&p.scene, ElementKind::Q4Sri, finest, REFERENCE_CFL),
                &mut Quiet,
            )?,
        };
        let own_error = error(p, &finest_sri, reference) / 3.0;
        reference_rows.push(vec![
            p.name.to_string(),
            format!(
                "q4-sri {}x{} cfl {REFERENCE_CFL}",
                reference_level.0, reference_level.1
            ),
            format!("{own_error:.2e}"),
        ]);
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
    let wave_series = wave_rows(
        &ELEMENTS,
        sizes.wave_levels,
        sizes.cfls,
        sizes.repeats,
        &mut rows,
    )?;
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
        "problem",
        "element",
        "mesh",
        "cfl",
        "dt_s",
        "error",
        "setup_s",
        "loop_s",
        "runs",
        "loop_spread",
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
    let mine: Vec<&Vec<String>> = rows.iter().filter(|r| r[0] == problem).collect();
    let points: Vec<(f64, f64)> = mine
        .iter()
        .map(|r| {
            let e: f64 = r[5].parse().unwrap_or(f64::INFINITY);
            let t: f64 = r[6].parse::<f64>().unwrap_or(0.0) + r[7].parse::<f64>().unwrap_or(0.0);
            (e, t)
        })
        .collect();
    let names: Vec<String> = pareto::front(&points)
        .into_iter()
        .map(|i| {
            let (r, (e, t)) = (mine[i], points[i]);
            format!("{} {} cfl {} (error {e:.1e}, {t:.3} s)", r[1], r[2], r[3])
        })
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

/// The picture's sizes: the chart 760 x 520 pixels, the legend's strip below it.
const PICTURE: Picture = Picture {
    width: 760,
    chart_height: 520,
    margin: 12,
};

/// The legend entries: each configuration in its colour by name (the report's palette,
/// readable on white), then the Pareto front in black.
fn legend_entries(series: &[Series]) -> Vec<Entry> {
    let curves: Vec<(&str, Mark)> = series.iter().map(|s| (s.0.as_str(), Mark::Line)).collect();
    let mut entries = style::entries(&curves);
    entries.push(Entry {
        label: "Pareto front (no other is faster and more accurate)".into(),
        colour: style::GUIDE,
        mark: Mark::Line,
    });
    entries
}

/// The work-precision plot as SVG: log error against log wall time, each configuration's
/// curve, the Pareto front, the legend in a strip below the chart (never over the data).
fn plot_svg(title: &str, axis: Axis, series: &[Series]) -> anyhow::Result<String> {
    let entries = legend_entries(series);
    PICTURE.svg(&entries, |area| chart(area, title, axis, series, &entries))
}

/// The chart of [`plot_svg`]: its log axes, the curves in their entries' colours, the
/// Pareto front; its data area.
fn chart(
    area: &Area,
    title: &str,
    axis: Axis,
    series: &[Series],
    entries: &[Entry],
) -> anyhow::Result<DataArea> {
    let all = series.iter().flat_map(|s| s.1.iter());
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, 0.0f64, f64::INFINITY, 0.0f64);
    for &(x, y) in all {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    let xlabel = match axis {
        Axis::History => "error: RMS of mid-span displacement history / its peak",
        Axis::Robust => "error: max relative error of impulse, final velocity, max displacement",
        Axis::WaveSpeed => "error: |measured P-wave speed / closed form - 1|",
    };
    let mut chart = ChartBuilder::on(area)
        .caption(format!("work-precision: {title}"), ("sans-serif", 18))
        .margin(PICTURE.margin)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(
            (x0 / 1.5..x1 * 1.5)
                .log_scale()
                .with_key_points(log_ticks(x0 / 1.5, x1 * 1.5)),
            (y0 / 1.5..y1 * 1.5)
                .log_scale()
                .with_key_points(log_ticks(y0 / 1.5, y1 * 1.5)),
        )?;
    chart
        .configure_mesh()
        .x_desc(xlabel)
        .y_desc("wall time, s (min of the timed runs)")
        .x_label_formatter(&|v| tick_label(*v))
        .y_label_formatter(&|v| tick_label(*v))
        .draw()?;
    for ((_, points), entry) in series.iter().zip(entries) {
        let color = entry.colour.to_rgba();
        chart.draw_series(LineSeries::new(
            points.iter().copied(),
            color.stroke_width(2),
        ))?;
        chart.draw_series(points.iter().map(|&p| Circle::new(p, 3, color.filled())))?;
    }
    // The Pareto front over all configurations: fastest to most accurate.
    let points: Vec<(f64, f64)> = series.iter().flat_map(|s| s.1.iter().copied()).collect();
    let front: Vec<(f64, f64)> = pareto::front(&points)
        .into_iter()
        .map(|i| points[i])
        .collect();
    chart.draw_series(LineSeries::new(front, BLACK.stroke_width(1)))?;
    Ok(chart.plotting_area().get_pixel_range())
}

fn plot(path: &Path, title: &str, axis: Axis, series: &[Series]) -> anyhow::Result<()> {
    std::fs::write(path, plot_svg(title, axis, series)?)?;
    Ok(())
}

/// Tick positions on a log axis from `lo` to `hi`: the coarsest of 1, 1-2-5 and
/// 1-1.5-2-3-5-7 per decade that gives at least four ticks (plotters' own log key points give
/// two on the one or two decades a quick run's times span).
fn log_ticks(lo: f64, hi: f64) -> Vec<f64> {
    const MANTISSAS: [&[f64]; 3] = [&[1.0], &[1.0, 2.0, 5.0], &[1.0, 1.5, 2.0, 3.0, 5.0, 7.0]];
    let ticks = |m: &[f64]| -> Vec<f64> {
        let (d0, d1) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
        (d0..=d1)
            .flat_map(|d| m.iter().map(move |k| k * 10f64.powi(d)))
            .filter(|v| (lo..=hi).contains(v))
            .collect()
    };
    let mut best = Vec::new();
    for m in MANTISSAS {
        best = ticks(m);
        if best.len() >= 4 {
            break;
        }
    }
    best
}

/// A tick's value with the digits it needs: 2e-2, 1.5e-3.
fn tick_label(v: f64) -> String {
    let rounded: f64 = format!("{v:.1e}").parse().unwrap_or(v);
    format!("{rounded:e}")
}

#[cfg(test)]
mod tests {
    use super::{log_ticks, plot_svg, style, tick_label, Axis, Series};

    /// The legend sits in its strip below the chart: the old one, plotters' own in the upper
    /// right, covered a third of the data area of a quick run's plot.
    #[test]
    fn the_legend_is_below_the_data_area() {
        let series: Vec<Series> = [
            "q4-sri cfl 0.3",
            "q4-sri cfl 0.9",
            "q4-full cfl 0.3",
            "q4-1pt cfl 0.9",
        ]
        .iter()
        .enumerate()
        .map(|(k, name)| {
            let pts = (1..5)
                .map(|i| (1e-3 * i as f64, 1e-2 / (i + k) as f64))
                .collect();
            (name.to_string(), pts)
        })
        .collect();
        let svg = plot_svg("impact elastic", Axis::Robust, &series).unwrap();
        let data = style::marked_rect(&svg, "data-area").unwrap();
        let legend = style::marked_rect(&svg, "legend-box").unwrap();
        assert!(!style::overlap(data, legend), "{data:?} {legend:?}");
        assert!(svg.contains(">Pareto front (no other is faster and more accurate)</text>"));
    }

    #[test]
    fn log_ticks_give_at_least_four_on_a_short_range() {
        // A quick run's wall times: 3 ms to 40 ms. 1-2-5 gives 5, 10, 20 ms: three; the
        // finer set gives seven.
        let t = log_ticks(3e-3, 4e-2);
        assert!(t.len() >= 4, "{t:?}");
        assert!(t.iter().all(|v| (3e-3..=4e-2).contains(v)));
        let labels: Vec<String> = t.iter().map(|&v| tick_label(v)).collect();
        assert_eq!(
            labels,
            ["3e-3", "5e-3", "7e-3", "1e-2", "1.5e-2", "2e-2", "3e-2"]
        );
        // Six decades: one tick per decade is enough.
        assert_eq!(log_ticks(1e-6, 1.0).len(), 7);
    }

    /// Both axes take these ticks: on the error axis plotters' own key points printed with
    /// one digit gave the same label twice ("1e-1" at 0.1 and 0.15).
    #[test]
    fn tick_labels_are_distinct_on_every_range() {
        for (lo, hi) in [(0.05, 0.3), (1e-3, 2e-3), (7e-4, 0.12), (1e-9, 0.1)] {
            let labels: Vec<String> = log_ticks(lo, hi).iter().map(|&v| tick_label(v)).collect();
            let mut distinct = labels.clone();
            distinct.dedup();
            assert_eq!(distinct, labels, "{lo:e}..{hi:e}");
            assert!(labels.len() >= 2, "{lo:e}..{hi:e}: {labels:?}");
        }
    }
}
