//! The project's SVG plots, for the verification report (`impact report`, `impact verify
//! --baseline`) and the benchmarks' work-precision plots (`impact-bench`): the look they
//! share (one colour per curve name, the legend in a strip below the chart), the frame of a
//! picture (the chart above, the legend below, the marks the report's browser check reads),
//! and the report's line plots with engineering tick labels.

pub mod line_plot;
pub mod picture;
pub mod style;
