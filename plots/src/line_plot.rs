//! SVG line plots for the report and the baseline comparison (plotters, self-contained SVG
//! strings): computed curves solid, references dashed, long histories downsampled. Axes carry
//! engineering tick labels with their unit (`800 J`, `0.8 kJ`, `1.5 ms`), never the same
//! label twice; curves that would sit on the zero line beside a much larger one get a panel
//! of their own ([`svg_panels`]).

use plotters::coord::ranged1d::Ranged;
use plotters::coord::types::RangedCoordf64;

use crate::picture::{Area, DataArea, Picture};
use crate::style::{self, Entry, Mark};

/// One curve: legend label, (x, y) points, dashed (a reference) or solid (computed).
pub type Series = (String, Vec<(f64, f64)>, bool);

/// Tick labels per axis (the hint plotters gets; it draws at most this many).
const TICKS: usize = 6;

/// An axis: what it shows and the SI unit of its values (empty: dimensionless).
#[derive(Debug, Clone, Copy)]
pub struct Axis<'a> {
    pub name: &'a str,
    pub unit: &'a str,
}

impl<'a> Axis<'a> {
    pub fn new(name: &'a str, unit: &'a str) -> Axis<'a> {
        Axis { name, unit }
    }
}

/// A history column's axis from its name's unit suffix (`contact_force_N` -> "contact force",
/// N); a column without a known suffix keeps its name, dimensionless.
pub fn column_axis(column: &str) -> (String, &'static str) {
    const SUFFIXES: [(&str, &str); 8] = [
        ("_mps", "m/s"),
        ("_Ns", "N s"),
        ("_Pa", "Pa"),
        ("_kg", "kg"),
        ("_N", "N"),
        ("_J", "J"),
        ("_m", "m"),
        ("_s", "s"),
    ];
    for (suffix, unit) in SUFFIXES {
        if let Some(stem) = column.strip_suffix(suffix) {
            return (stem.replace('_', " "), unit);
        }
    }
    (column.replace('_', " "), "")
}

/// What a quantity in `unit` is called on an axis that shows several columns.
pub fn quantity_of(unit: &str) -> &'static str {
    match unit {
        "J" => "energy",
        "N" => "force",
        "m" => "displacement",
        "s" => "time",
        "Pa" => "stress",
        "m/s" => "velocity",
        "N s" => "impulse",
        _ => "",
    }
}

/// SI prefixes by power of 1000, from 1e-12 to 1e12.
const PREFIXES: [&str; 9] = ["p", "n", "µ", "m", "", "k", "M", "G", "T"];

/// The label of each tick of an axis spanning `lo..hi` in `unit`: an SI prefix chosen by the
/// largest magnitude (`0.8 kJ`), dimensionless values in engineering notation (`2.5e-6`),
/// and the fewest decimals that keep the ticks plotters draws (its key points for the
/// same range) distinct.
pub fn tick_labels(lo: f64, hi: f64, unit: &str) -> impl Fn(&f64) -> String {
    let mag = lo.abs().max(hi.abs());
    let exp3 = if mag > 0.0 && mag.is_finite() {
        ((mag.log10() / 3.0).floor() as i32).clamp(-4, 4)
    } else {
        0
    };
    // A dimensionless axis of ordinary size needs no exponent.
    let exp3 = if unit.is_empty() && (-1..=1).contains(&exp3) && mag < 1e4 {
        0
    } else {
        exp3
    };
    let scale = 10f64.powi(-3 * exp3);
    let suffix = match (unit.is_empty(), exp3) {
        (true, 0) => String::new(),
        (true, e) => format!("e{}", 3 * e),
        (false, e) => format!(" {}{unit}", PREFIXES[(e + 4) as usize]),
    };
    let ticks: Vec<f64> = RangedCoordf64::from(lo..hi).key_points(TICKS);
    let label = move |v: f64, d: usize| {
        let s = format!("{:.*}", d, v * scale);
        // "-0", "0.00" and "-0.00" read as zero.
        if s.chars().all(|c| c == '0' || c == '.' || c == '-') {
            "0".to_string()
        } else {
            s
        }
    };
    let decimals = (0..=9)
        .find(|&d| {
            let mut l: Vec<String> = ticks.iter().map(|&v| label(v, d)).collect();
            l.dedup();
            l.len() == ticks.len()
        })
        .unwrap_or(9);
    // Zero needs no exponent ("0", not "0e-6"); with a unit it keeps it ("0 ms").
    let exponent_only = unit.is_empty();
    move |v: &f64| match label(*v, decimals) {
        l if l == "0" && exponent_only => l,
        l => format!("{l}{suffix}"),
    }
}

/// What a plot shows besides its curves: a fixed y range (instead of the data's, e.g. one
/// that does not zoom into round-off) and a shaded horizontal band (from, to, legend label).
#[derive(Debug, Clone, Default)]
pub struct Frame {
    pub y_range: Option<(f64, f64)>,
    pub band: Option<(f64, f64, String)>,
}

/// An SVG line plot (references dashed) as a string, or a note when it cannot be drawn.
pub fn svg_plot(title: &str, x: Axis, y: Axis, series: &[Series]) -> String {
    svg_plot_framed(title, x, y, series, &Frame::default())
}

/// [`svg_plot`] with the y range and band of `frame`.
pub fn svg_plot_framed(title: &str, x: Axis, y: Axis, series: &[Series], frame: &Frame) -> String {
    match try_plot(title, x, y, series, frame) {
        Ok(s) => s,
        Err(e) => format!("<p class=\"small\">plot {title:?} not drawn: {e}</p>"),
    }
}

/// The largest |y| of a curve (0 for none).
fn peak(s: &Series) -> f64 {
    s.1.iter()
        .map(|p| p.1.abs())
        .filter(|v| v.is_finite())
        .fold(0.0, f64::max)
}

/// [`svg_plot`], or more panels when some curves stay below 1/20 of the largest curve's peak
/// (they would sit on its zero line): the large curves, then the small ones on their own
/// scale, titled so, and the same again among the small ones (three panels at most).
/// (title, svg) per panel.
pub fn svg_panels(title: &str, x: Axis, y: Axis, series: &[Series]) -> Vec<(String, String)> {
    let mut out = Vec::new();
    let mut rest = series.to_vec();
    let mut panel_title = title.to_string();
    loop {
        let largest = rest.iter().map(peak).fold(0.0, f64::max);
        let (small, large): (Vec<Series>, Vec<Series>) =
            rest.iter().cloned().partition(|s| peak(s) < largest / 20.0);
        if small.is_empty() || large.is_empty() || out.len() == 2 {
            out.push((panel_title.clone(), svg_plot(&panel_title, x, y, &rest)));
            return out;
        }
        out.push((panel_title.clone(), svg_plot(&panel_title, x, y, &large)));
        panel_title = if out.len() == 1 {
            format!("{title}: the curves near zero, on their own scale")
        } else {
            format!("{title}: the smallest curves, on their own scale")
        };
        rest = small;
    }
}

/// The data's bounding box (x0, x1, y0, y1), widened where it is flat and padded by 5 % in y.
fn bounds(series: &[Series]) -> Result<(f64, f64, f64, f64), String> {
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    let pts = series.iter().flat_map(|s| s.1.iter());
    for p in pts.filter(|p| p.0.is_finite() && p.1.is_finite()) {
        x0 = x0.min(p.0);
        x1 = x1.max(p.0);
        y0 = y0.min(p.1);
        y1 = y1.max(p.1);
    }
    if !(x0.is_finite() && y0.is_finite()) {
        return Err("no data".into());
    }
    if x1 <= x0 {
        x1 = x0 + 1.0;
    }
    if y1 <= y0 {
        let pad = if y0 == 0.0 { 1.0 } else { 0.05 * y0.abs() };
        y0 -= pad;
        y1 += pad;
    }
    let pad = 0.05 * (y1 - y0);
    Ok((x0, x1, y0 - pad, y1 + pad))
}

/// The picture's sizes: the chart 560 x 340 pixels, the legend's strip below it.
const PICTURE: Picture = Picture {
    width: 560,
    chart_height: 340,
    margin: 8,
};

/// The legend entries of `series` (references dashed) and the band's, coloured by name.
fn legend_entries(series: &[Series], frame: &Frame) -> Vec<Entry> {
    let curves: Vec<(&str, Mark)> = series
        .iter()
        .map(|s| (s.0.as_str(), if s.2 { Mark::Dashed } else { Mark::Line }))
        .collect();
    let mut entries = style::entries(&curves);
    if let Some((_, _, label)) = &frame.band {
        entries.push(Entry {
            label: label.clone(),
            colour: BAND,
            mark: Mark::Band,
        });
    }
    entries
}

/// The band's colour (drawn at 25 % opacity).
const BAND: plotters::style::RGBColor = plotters::style::RGBColor(0x80, 0x80, 0x80);

fn try_plot(
    title: &str,
    x: Axis,
    y: Axis,
    series: &[Series],
    frame: &Frame,
) -> Result<String, Box<dyn std::error::Error>> {
    let (x0, x1, mut y0, mut y1) = bounds(series)?;
    if let Some((lo, hi)) = frame.y_range {
        (y0, y1) = (lo, hi);
    }
    let entries = legend_entries(series, frame);
    PICTURE.svg(&entries, |area| {
        chart(
            area,
            title,
            (x, y),
            (x0..x1, y0..y1),
            series,
            &entries,
            frame,
        )
    })
}

/// The chart: axes with their tick labels, the band, each curve in its entry's colour
/// (dashed references; the points of a short computed curve marked); its data area.
fn chart(
    area: &Area,
    title: &str,
    (x, y): (Axis, Axis),
    (xs, ys): (std::ops::Range<f64>, std::ops::Range<f64>),
    series: &[Series],
    entries: &[Entry],
    frame: &Frame,
) -> Result<DataArea, Box<dyn std::error::Error>> {
    use plotters::prelude::*;
    let xfmt = tick_labels(xs.start, xs.end, x.unit);
    let yfmt = tick_labels(ys.start, ys.end, y.unit);
    // A long title gets a smaller font rather than running off the plot.
    let title_size = (15.0f64).min(1000.0 / title.chars().count().max(1) as f64);
    let (x0, x1, y0, y1) = (xs.start, xs.end, ys.start, ys.end);
    let mut chart = ChartBuilder::on(area)
        .caption(title, ("sans-serif", title_size.max(9.0)))
        .margin(PICTURE.margin)
        .margin_right(30)
        .x_label_area_size(34)
        .y_label_area_size(76)
        .build_cartesian_2d(xs, ys)?;
    chart
        .configure_mesh()
        .x_desc(x.name)
        .y_desc(y.name)
        .x_labels(TICKS)
        .y_labels(TICKS)
        .x_label_formatter(&xfmt)
        .y_label_formatter(&yfmt)
        .draw()?;
    if let Some((lo, hi, _)) = &frame.band {
        chart.draw_series(std::iter::once(Rectangle::new(
            [(x0, lo.max(y0)), (x1, hi.min(y1))],
            BAND.mix(0.25).filled(),
        )))?;
    }
    for ((_, data, dashed), entry) in series.iter().zip(entries) {
        let color = entry.colour.to_rgba();
        let data: Vec<(f64, f64)> = downsample(data, 1200);
        if *dashed {
            chart.draw_series(DashedLineSeries::new(data, 6, 4, color.stroke_width(2)))?;
        } else {
            chart.draw_series(LineSeries::new(data.clone(), color.stroke_width(1)))?;
            if data.len() <= 12 {
                chart.draw_series(data.iter().map(|p| Circle::new(*p, 3, color.filled())))?;
            }
        }
    }
    Ok(chart.plotting_area().get_pixel_range())
}

fn downsample(d: &[(f64, f64)], n: usize) -> Vec<(f64, f64)> {
    if d.len() <= n {
        return d.to_vec();
    }
    let step = d.len().div_ceil(n);
    let mut v: Vec<(f64, f64)> = d.iter().step_by(step).copied().collect();
    if let Some(last) = d.last() {
        v.push(*last);
    }
    v
}

#[cfg(test)]
mod tests {
    //! The tick labels (issue 13, "a report that reads right"): engineering units, never the
    //! same label twice; the panels for curves that sit on zero.
    use super::*;

    fn labels(lo: f64, hi: f64, unit: &str) -> Vec<String> {
        let f = tick_labels(lo, hi, unit);
        RangedCoordf64::from(lo..hi)
            .key_points(TICKS)
            .iter()
            .map(|v| f(v))
            .collect()
    }

    #[test]
    fn ticks_carry_engineering_units() {
        let f = tick_labels(0.0, 900.0, "J");
        assert_eq!(f(&800.0), "800 J");
        let f = tick_labels(0.0, 1600.0, "J");
        assert_eq!(f(&800.0), "0.8 kJ");
        assert_eq!(f(&1600.0), "1.6 kJ");
        assert_eq!(labels(0.0, 3.0e-3, "s"), ["0 ms", "1 ms", "2 ms", "3 ms"]);
        assert_eq!(labels(0.0, 1.2e-3, "s"), ["0 ms", "0.5 ms", "1.0 ms"]);
        assert_eq!(labels(0.0, 4.0e-6, "")[0], "0");
        assert_eq!(labels(-2.0e-6, 0.0, "m")[1], "-1.5 µm");
        assert_eq!(labels(0.0, 4.0e-6, "")[2], "2e-6");
        assert_eq!(labels(-0.6, 0.0, "")[0], "-0.5");
        // The old axis printed "-2.340" four times here.
        assert_eq!(labels(-2.34002, -2.33998, "")[1], "-2.34001");
    }

    #[test]
    fn ticks_are_distinct_even_on_a_narrow_range_far_from_zero() {
        // The old labels printed "-2.340" four times on such an axis.
        for (lo, hi, unit) in [
            (-2.34002, -2.33998, ""),
            (-2.3401, -2.3399, ""),
            (799.9999, 800.0001, "J"),
            (0.0, 3.0e-3, "s"),
            (1.0e-9, 1.3e-9, "m"),
            (0.0, 1.0, ""),
            (-1.0e5, 2.5e5, "N"),
        ] {
            let l = labels(lo, hi, unit);
            let mut d = l.clone();
            d.sort();
            d.dedup();
            assert!(l.len() >= 2, "{lo}..{hi}: {l:?}");
            assert_eq!(d.len(), l.len(), "{lo}..{hi}: repeated labels {l:?}");
        }
    }

    #[test]
    fn columns_name_their_quantity_and_unit() {
        assert_eq!(
            column_axis("contact_force_N"),
            ("contact force".to_string(), "N")
        );
        assert_eq!(
            column_axis("impactor_velocity_mps"),
            ("impactor velocity".to_string(), "m/s")
        );
        assert_eq!(
            column_axis("energy_balance_error"),
            ("energy balance error".to_string(), "")
        );
        assert_eq!(quantity_of("J"), "energy");
    }

    #[test]
    fn curves_on_the_zero_line_get_their_own_panel() {
        let curve = |a: f64| (0..50).map(|i| (i as f64, a * (i as f64).sin())).collect();
        let big: Series = ("literal".into(), curve(0.1), false);
        let small: Series = ("elastic".into(), curve(1e-6), false);
        let axis = Axis::new("time", "s");
        let panels = svg_panels("Energy balance error", axis, axis, &[big.clone(), small]);
        assert_eq!(panels.len(), 2);
        assert!(panels[1].0.contains("on their own scale"), "{panels:?}");
        assert!(panels[1].1.contains("elastic") && !panels[1].1.contains("literal"));
        assert_eq!(svg_panels("one", axis, axis, &[big.clone()]).len(), 1);
        // Three scales (0.1, 3e-4, 1e-6, as the literal pairing, the pulse and the impacts):
        // three panels, the smallest curve alone in the last.
        let middle: Series = ("pulse".into(), curve(3e-4), false);
        let tiny: Series = ("plastic".into(), curve(1e-6), false);
        let panels = svg_panels("balance", axis, axis, &[big, middle, tiny]);
        assert_eq!(
            panels.len(),
            3,
            "{:?}",
            panels.iter().map(|p| &p.0).collect::<Vec<_>>()
        );
        assert!(panels[2].0.contains("the smallest curves") && panels[2].1.contains("plastic"));
        assert!(!panels[2].1.contains("pulse"));
    }

    #[test]
    fn the_legend_sits_below_the_data_area_never_on_it() {
        // Eight curves with long names: the old legend (plotters' own, inside the chart's
        // upper right) covered a third of the data area.
        let series: Vec<Series> = (0..8)
            .map(|k| {
                let d = (0..40).map(|i| (i as f64, (k * i) as f64)).collect();
                (
                    format!("ref: reference-data/curve-{k}/history"),
                    d,
                    k % 2 == 0,
                )
            })
            .collect();
        let axis = Axis::new("time", "s");
        let svg = svg_plot("eight curves", axis, axis, &series);
        let data = style::marked_rect(&svg, "data-area").expect("data area marked");
        let legend = style::marked_rect(&svg, "legend-box").expect("legend marked");
        assert!(!style::overlap(data, legend), "{data:?} {legend:?}");
        assert!(legend[1] >= PICTURE.chart_height as f64, "{legend:?}");
        // Inside the picture: its height covers the legend.
        let height: f64 = svg
            .split("height=\"")
            .nth(1)
            .and_then(|h| h.split('"').next())
            .and_then(|h| h.parse().ok())
            .unwrap();
        assert!(legend[1] + legend[3] <= height, "{legend:?} in {height}");
        // Every label is in the legend, and a dashed curve's sample is dashed.
        assert!(svg.contains("ref: reference-data/curve-7/history"));
        assert!(svg.contains("stroke-dasharray=\"6,4\""));
        // A band gets its own legend entry.
        let frame = Frame {
            y_range: Some((-17.0, -6.0)),
            band: Some((-17.0, -12.0, "round-off".into())),
        };
        let svg = svg_plot_framed("band", axis, axis, &series[..1], &frame);
        assert!(svg.contains(">round-off</text>"), "{svg}");
    }
}
