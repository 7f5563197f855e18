//! The look every plot shares (the report's SVG plots and the benchmarks' work-precision
//! plots): one colour per curve name in every plot (a fixed map for the quantities the
//! report plots, a hash of the name for the rest), each readable on white (contrast at least
//! 3:1, the WCAG 2.1 non-text contrast, 1.4.11; no yellow), and the legend in a strip of its
//! own below the chart, never over the data. The SVG carries two invisible marks the
//! report's browser check reads: `rect.data-area` (the chart's data area) and
//! `rect.legend-box` (the legend's box); sizes in pixels.

use plotters::style::RGBColor;

/// The curve colours, every one with a contrast of at least 3:1 on white (measured: 3.8 for
/// the olive to 7.7 for the indigo; Palette99's yellow, which the plots used, has 1.3).
pub const PALETTE: [RGBColor; 10] = [
    RGBColor(0x1f, 0x77, 0xb4), // blue
    RGBColor(0xd6, 0x27, 0x28), // red
    RGBColor(0x1a, 0x7a, 0x1a), // green
    RGBColor(0x94, 0x67, 0xbd), // purple
    RGBColor(0x8c, 0x56, 0x4b), // brown
    RGBColor(0xc2, 0x18, 0x5b), // pink
    RGBColor(0xb3, 0x59, 0x00), // orange
    RGBColor(0x00, 0x83, 0x8f), // teal
    RGBColor(0x39, 0x49, 0xab), // indigo
    RGBColor(0x6b, 0x8e, 0x23), // olive
];

/// Fits, fronts and other guides: black.
pub const GUIDE: RGBColor = RGBColor(0, 0, 0);

/// The quantities the report plots by name (history columns as [`crate::line_plot::column_axis`]
/// names them), each with its own palette slot so that no two of them share a colour.
const FIXED: [(&str, usize); 9] = [
    ("impactor kinetic", 0),
    ("plate kinetic", 1),
    ("strain energy", 2),
    ("contact energy", 3),
    ("plastic work", 4),
    ("external work", 8),
    ("contact force", 6),
    ("energy balance error", 7),
    ("runs", 0),
];

/// Curve names that start with one of these are guides (black): fitted slopes, fronts.
const GUIDES: [&str; 2] = ["slope p", "Pareto front"];

/// FNV-1a of the name: the palette slot of a name the fixed map does not know.
fn slot_of(name: &str) -> usize {
    let h = name.bytes().fold(0xcbf2_9ce4_8422_2325u64, |h, b| {
        (h ^ b as u64).wrapping_mul(0x0100_0000_01b3)
    });
    (h % PALETTE.len() as u64) as usize
}

/// The colour of each curve of one plot, by name: a quantity of the fixed map its slot, a
/// guide black, any other name its hashed slot; when that slot is taken in this plot, the
/// next free one (so a name keeps its colour in every plot where no other name claims it
/// first; a plot with more names than colours repeats them).
pub fn colours(names: &[&str]) -> Vec<RGBColor> {
    let mut used = [false; PALETTE.len()];
    names
        .iter()
        .map(|name| {
            if GUIDES.iter().any(|g| name.starts_with(g)) {
                return GUIDE;
            }
            let base = FIXED
                .iter()
                .find(|(n, _)| n == name)
                .map_or_else(|| slot_of(name), |(_, i)| *i);
            let slot = (0..PALETTE.len())
                .map(|k| (base + k) % PALETTE.len())
                .find(|&s| !used[s])
                .unwrap_or(base);
            used[slot] = true;
            PALETTE[slot]
        })
        .collect()
}

/// How a legend entry shows its curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Mark {
    Line,
    Dashed,
    /// A shaded band (e.g. the round-off level).
    Band,
}

/// One legend entry.
#[derive(Debug, Clone)]
pub struct Entry {
    pub label: String,
    pub colour: RGBColor,
    pub mark: Mark,
}

/// The legend entries of the curves of one plot (label, mark), each in its colour by name
/// ([`colours`]).
pub fn entries(curves: &[(&str, Mark)]) -> Vec<Entry> {
    let names: Vec<&str> = curves.iter().map(|c| c.0).collect();
    curves
        .iter()
        .zip(colours(&names))
        .map(|(&(label, mark), colour)| Entry {
            label: label.to_string(),
            colour,
            mark,
        })
        .collect()
}

/// Legend text size, row height, the width of a character at that size (an upper estimate
/// for sans-serif: DejaVu Sans averages ~6.3 px at 11 px), the curve sample and the gap
/// between columns, in pixels.
const FONT_PX: u32 = 11;
const ROW_PX: u32 = 16;
const CHAR_PX: u32 = 7;
const SAMPLE_PX: u32 = 22;
const GAP_PX: u32 = 16;
/// Padding inside the legend box, pixels.
const PAD_PX: u32 = 4;

/// Where each entry goes in a strip `width` pixels wide: entries in columns of equal width
/// (the widest entry's), row by row; (x, y) of each entry's top-left corner relative to the
/// strip, and the strip's height.
pub fn layout(labels: &[&str], width: u32) -> (Vec<(u32, u32)>, u32) {
    if labels.is_empty() {
        return (Vec::new(), 0);
    }
    let widest = labels
        .iter()
        .map(|l| l.chars().count() as u32)
        .max()
        .unwrap_or(0);
    let column = SAMPLE_PX + 6 + CHAR_PX * widest + GAP_PX;
    let columns = (width.saturating_sub(2 * PAD_PX) / column).clamp(1, labels.len() as u32);
    let rows = (labels.len() as u32).div_ceil(columns);
    let at = (0..labels.len() as u32)
        .map(|i| {
            (
                PAD_PX + (i % columns) * column,
                PAD_PX + (i / columns) * ROW_PX,
            )
        })
        .collect();
    (at, rows * ROW_PX + 2 * PAD_PX)
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

fn hex(c: RGBColor) -> String {
    format!("#{:02x}{:02x}{:02x}", c.0, c.1, c.2)
}

/// The legend as SVG elements in the strip whose top-left corner is (`x0`, `y0`), `width`
/// wide: a `rect.legend-box` around the entries, then each entry's mark and label.
pub fn legend_svg(entries: &[Entry], x0: u32, y0: u32, width: u32) -> String {
    let labels: Vec<&str> = entries.iter().map(|e| e.label.as_str()).collect();
    let (at, height) = layout(&labels, width);
    if entries.is_empty() {
        return String::new();
    }
    let mut s = format!(
        "<g class=\"legend\"><rect class=\"legend-box\" x=\"{x0}\" y=\"{y0}\" width=\"{width}\" height=\"{height}\" fill=\"#ffffff\" stroke=\"#999999\"/>"
    );
    for (e, (x, y)) in entries.iter().zip(at) {
        let (x, y) = (x0 + x, y0 + y + ROW_PX / 2);
        let c = hex(e.colour);
        s += &match e.mark {
            Mark::Line => format!("<line x1=\"{x}\" y1=\"{y}\" x2=\"{}\" y2=\"{y}\" stroke=\"{c}\" stroke-width=\"2\"/>", x + SAMPLE_PX),
            Mark::Dashed => format!("<line x1=\"{x}\" y1=\"{y}\" x2=\"{}\" y2=\"{y}\" stroke=\"{c}\" stroke-width=\"2\" stroke-dasharray=\"6,4\"/>", x + SAMPLE_PX),
            Mark::Band => format!("<rect x=\"{x}\" y=\"{}\" width=\"{SAMPLE_PX}\" height=\"10\" fill=\"{c}\" fill-opacity=\"0.25\"/>", y - 5),
        };
        s += &format!(
            "<text x=\"{}\" y=\"{y}\" font-family=\"sans-serif\" font-size=\"{FONT_PX}\" dominant-baseline=\"middle\" fill=\"#000000\">{}</text>",
            x + SAMPLE_PX + 6,
            escape(&e.label)
        );
    }
    s + "</g>"
}

/// The chart's data area (pixel ranges of the plotting area) as an invisible `rect.data-area`.
pub fn data_area(x: std::ops::Range<i32>, y: std::ops::Range<i32>) -> String {
    format!(
        "<rect class=\"data-area\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"none\"/>",
        x.start,
        y.start,
        x.end - x.start,
        y.end - y.start
    )
}

/// `svg` with `extra` inserted before its closing tag.
pub fn append(svg: &str, extra: &str) -> String {
    match svg.rfind("</svg>") {
        Some(i) => format!("{}{extra}{}", &svg[..i], &svg[i..]),
        None => svg.to_string(),
    }
}

/// The attributes x, y, width, height of the first `<rect class="{class}" ...>` in `svg`.
pub fn marked_rect(svg: &str, class: &str) -> Option<[f64; 4]> {
    let start = svg.find(&format!("<rect class=\"{class}\""))?;
    let tag = &svg[start..start + svg[start..].find('>')?];
    let attr = |name: &str| -> Option<f64> {
        let at = tag.find(&format!(" {name}=\""))? + name.len() + 3;
        tag[at..at + tag[at..].find('"')?].parse().ok()
    };
    Some([attr("x")?, attr("y")?, attr("width")?, attr("height")?])
}

/// Whether two rectangles [x, y, width, height] overlap (touching edges do not).
pub fn overlap(a: [f64; 4], b: [f64; 4]) -> bool {
    a[0] < b[0] + b[2] && b[0] < a[0] + a[2] && a[1] < b[1] + b[3] && b[1] < a[1] + a[3]
}

#[cfg(test)]
mod tests {
    //! The shared plot look: every colour readable on white (WCAG 2.1 contrast, 1.4.11: at
    //! least 3:1; Palette99's yellow, which the plots used, has 1.3 and fails), one colour per
    //! name whatever the plot, and the legend laid out beside nothing but itself.
    use super::*;

    /// WCAG 2.1 contrast ratio of `c` on white.
    fn contrast_on_white(c: RGBColor) -> f64 {
        let lin = |v: u8| {
            let v = v as f64 / 255.0;
            if v <= 0.03928 {
                v / 12.92
            } else {
                ((v + 0.055) / 1.055).powf(2.4)
            }
        };
        let l = 0.2126 * lin(c.0) + 0.7152 * lin(c.1) + 0.0722 * lin(c.2);
        1.05 / (l + 0.05)
    }

    #[test]
    fn every_colour_reads_on_white_and_yellow_would_not() {
        for c in PALETTE {
            assert!(
                contrast_on_white(c) >= 3.0,
                "{c:?}: {}",
                contrast_on_white(c)
            );
        }
        // The wrong palette: plotters' Palette99 yellow (255, 225, 25) has 1.3.
        assert!(contrast_on_white(RGBColor(255, 225, 25)) < 3.0);
    }

    #[test]
    fn a_name_keeps_its_colour_from_plot_to_plot() {
        // The old plots coloured by position: "plate kinetic" was the second colour in one
        // plot and the first in another.
        let a = colours(&["impactor kinetic", "plate kinetic", "strain energy"]);
        let b = colours(&["plate kinetic", "contact energy"]);
        assert_eq!(a[1], b[0]);
        let c = colours(&["q4-sri", "q4-full"]);
        let d = colours(&["q4-full", "q4-1pt", "q4-sri"]);
        assert_eq!((c[0], c[1]), (d[2], d[0]));
        // The fixed quantities never share a colour among themselves.
        let fixed: Vec<&str> = FIXED
            .iter()
            .filter(|f| f.0 != "runs")
            .map(|f| f.0)
            .collect();
        let cs = colours(&fixed);
        for i in 0..cs.len() {
            for j in 0..i {
                assert_ne!(cs[i], cs[j], "{} and {}", fixed[i], fixed[j]);
            }
        }
        assert_eq!(colours(&["slope p = 2.00"]), [GUIDE]);
    }

    #[test]
    fn entries_stay_inside_their_strip_and_apart() {
        let labels = [
            "impactor kinetic",
            "plate kinetic",
            "ref: paper/figure-5",
            "a",
        ];
        let (at, height) = layout(&labels, 560);
        let column = SAMPLE_PX + 6 + CHAR_PX * 19 + GAP_PX;
        for (i, (x, y)) in at.iter().enumerate() {
            assert!(x + column <= 560 && y + ROW_PX <= height, "{i}: {x},{y}");
            for (x2, y2) in &at[..i] {
                assert!(x.abs_diff(*x2) >= column || y.abs_diff(*y2) >= ROW_PX);
            }
        }
        assert_eq!(layout(&[], 560).1, 0);
    }

    #[test]
    fn marked_rects_read_back_and_overlap_is_strict() {
        let svg = append("<svg></svg>", &data_area(10..110, 20..220));
        assert_eq!(
            marked_rect(&svg, "data-area"),
            Some([10.0, 20.0, 100.0, 200.0])
        );
        assert!(marked_rect(&svg, "legend-box").is_none());
        assert!(overlap([0.0, 0.0, 10.0, 10.0], [5.0, 5.0, 10.0, 10.0]));
        assert!(!overlap([0.0, 0.0, 10.0, 10.0], [0.0, 10.0, 10.0, 10.0]));
    }
}
