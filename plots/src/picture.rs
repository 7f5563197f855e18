//! Every picture's layout: the chart on top, the legend in a strip of its own below it
//! (never over the data), and the two invisible marks the report's browser check reads,
//! `rect.data-area` (the chart's data area) and `rect.legend-box` (the legend's box).

use std::ops::Range;

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::style::{self, Entry};

/// The sizes of a picture in pixels: its width, the chart's height (the legend's strip goes
/// below it), and the margin around the chart and beside the legend.
#[derive(Debug, Clone, Copy)]
pub struct Picture {
    pub width: u32,
    pub chart_height: u32,
    pub margin: u32,
}

/// The pixel ranges (x, y) of a chart's data area, as plotters gives them.
pub type DataArea = (Range<i32>, Range<i32>);

/// A white area `SVGBackend` draws on.
pub type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;

impl Picture {
    /// The picture as SVG: the chart that `chart` draws on the top `chart_height` pixels
    /// (returning its data area), then the legend of `entries` in the strip below, and the
    /// marks of both.
    pub fn svg<E>(
        self,
        entries: &[Entry],
        chart: impl FnOnce(&Area) -> Result<DataArea, E>,
    ) -> Result<String, E>
    where
        E: From<DrawingAreaErrorKind<std::io::Error>>,
    {
        let labels: Vec<&str> = entries.iter().map(|e| e.label.as_str()).collect();
        let legend_width = self.width - 2 * self.margin;
        let legend_height = style::layout(&labels, legend_width).1;
        let height = self.chart_height + legend_height + self.margin;
        let mut text = String::new();
        let area;
        {
            let root = SVGBackend::with_string(&mut text, (self.width, height)).into_drawing_area();
            root.fill(&WHITE)?;
            let (chart_area, _) = root.split_vertically(self.chart_height);
            area = chart(&chart_area)?;
            root.present()?;
        }
        let legend = style::legend_svg(entries, self.margin, self.chart_height, legend_width);
        Ok(style::append(
            &text,
            &(style::data_area(area.0, area.1) + &legend),
        ))
    }
}
