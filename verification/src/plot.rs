//! SVG line plots for the report and the baseline comparison (plotters, self-contained SVG
//! strings): computed curves solid, references dashed, long histories downsampled.

/// One curve: legend label, (x, y) points, dashed (a reference) or solid (computed).
pub type Series = (String, Vec<(f64, f64)>, bool);

/// An SVG line plot (references dashed) as a string, or a note when it cannot be drawn.
pub fn svg_plot(title: &str, xlabel: &str, ylabel: &str, series: &[Series]) -> String {
    match try_plot(title, xlabel, ylabel, series) {
        Ok(s) => s,
        Err(e) => format!("<p class=\"small\">plot {title:?} not drawn: {e}</p>"),
    }
}

fn try_plot(title: &str, xlabel: &str, ylabel: &str, series: &[Series]) -> Result<String, String> {
    use plotters::prelude::*;
    let pts = series
        .iter()
        .flat_map(|s| s.1.iter())
        .filter(|p| p.0.is_finite() && p.1.is_finite());
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for p in pts {
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
    let mut text = String::new();
    {
        let root = SVGBackend::with_string(&mut text, (560, 340)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 15))
            .margin(8)
            .x_label_area_size(32)
            .y_label_area_size(62)
            .build_cartesian_2d(x0..x1, (y0 - pad)..(y1 + pad))
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .x_desc(xlabel)
            .y_desc(ylabel)
            .x_labels(6)
            .y_labels(6)
            .x_label_formatter(&|v| format!("{v:.3}"))
            .y_label_formatter(&|v| format!("{v:.3}"))
            .draw()
            .map_err(|e| e.to_string())?;
        for (i, (label, data, dashed)) in series.iter().enumerate() {
            let color = Palette99::pick(i).to_rgba();
            let data: Vec<(f64, f64)> = downsample(data, 1200);
            if *dashed {
                chart
                    .draw_series(DashedLineSeries::new(data, 6, 4, color.stroke_width(2)))
                    .map_err(|e| e.to_string())?
                    .label(label.clone())
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], color));
            } else {
                chart
                    .draw_series(LineSeries::new(data.clone(), color.stroke_width(1)))
                    .map_err(|e| e.to_string())?
                    .label(label.clone())
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], color));
                if data.len() <= 12 {
                    chart
                        .draw_series(data.iter().map(|p| Circle::new(*p, 3, color.filled())))
                        .map_err(|e| e.to_string())?;
                }
            }
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .label_font(("sans-serif", 11))
            .draw()
            .map_err(|e| e.to_string())?;
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(text)
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
