//! Line charts of named series on linear or log10 axes, the legend in the emptiest corner.

use super::figure::{
    Bounds, FONT, Figure, PALETTE, PlotError, Scale, ensure_font_registered, is_plottable_on, linear_axis, log_axis,
    tick_formatter, to_message, write_png_and_svg,
};
use plotters::coord::Shift;
use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::prelude::*;
use std::ops::Range;
use std::path::Path;

/// One named line series.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Series {
    /// Legend label; an empty name gets no legend entry.
    pub name: String,
    /// (x, y) points in drawing order; invalid points break the line.
    pub points: Vec<(f64, f64)>,
    /// draw markers at points as well as the line
    pub markers: bool,
}

/// A line chart of several series with a legend (used for expected number of objects over time, GOSPA over time,
/// and a log-log timing plot of children generation time vs number of possible children). With Log10 scales, points
/// with non-positive coordinates are skipped.
///
/// The chart is 1200x800 px. Series take colours from a fixed 10-colour palette in order (cycling after ten); invalid
/// points break a line, and isolated points get a marker. The legend goes in the corner with the fewest points.
pub fn plot_series(
    stem: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    x_scale: Scale,
    y_scale: Scale,
    series: &[Series],
) -> Result<(), PlotError> {
    ensure_font_registered()?;
    write_png_and_svg(stem, &LineChart { title, x_label, y_label, x_scale, y_scale, series })
}

pub(crate) const LINE_CHART_SIZE: (u32, u32) = (1200, 800);

const LINE_WIDTH: u32 = 2;

const MARKER_RADIUS: i32 = 4;

struct LineChart<'a> {
    title: &'a str,
    x_label: &'a str,
    y_label: &'a str,
    x_scale: Scale,
    y_scale: Scale,
    series: &'a [Series],
}

impl LineChart<'_> {
    /// Each series split into runs of drawable points (an invalid point breaks the line).
    fn drawable_runs(&self) -> Vec<Vec<Vec<(f64, f64)>>> {
        self.series
            .iter()
            .map(|series| {
                let mut runs = Vec::new();
                let mut run = Vec::new();
                for &(x, y) in &series.points {
                    if is_plottable_on(self.x_scale, x) && is_plottable_on(self.y_scale, y) {
                        run.push((x, y));
                    } else if !run.is_empty() {
                        runs.push(std::mem::take(&mut run));
                    }
                }
                if !run.is_empty() {
                    runs.push(run);
                }
                runs
            })
            .collect()
    }
}

impl Figure for LineChart<'_> {
    fn canvas_size(&self) -> (u32, u32) {
        LINE_CHART_SIZE
    }

    fn draw_on<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError> {
        let runs = self.drawable_runs();
        let mut bounds = None;
        for &(x, y) in runs.iter().flatten().flatten() {
            Bounds::include(&mut bounds, x, y);
        }
        let axis = |scale: Scale, data: Option<Range<f64>>| match scale {
            Scale::Linear => linear_axis(data),
            Scale::Log10 => log_axis(data),
        };
        let x_range = axis(self.x_scale, bounds.as_ref().map(|b| b.x.clone()));
        let y_range = axis(self.y_scale, bounds.as_ref().map(|b| b.y.clone()));
        let legend_position = emptiest_corner(&runs, self, &x_range, &y_range);
        let x_tick_format = tick_formatter(self.x_scale, &x_range);
        let y_tick_format = tick_formatter(self.y_scale, &y_range);
        let content = LineChartContent { chart: self, runs: &runs, legend_position, x_tick_format, y_tick_format };
        match (self.x_scale, self.y_scale) {
            (Scale::Linear, Scale::Linear) => content.draw(root, x_range, y_range),
            (Scale::Linear, Scale::Log10) => content.draw(root, x_range, y_range.log_scale()),
            (Scale::Log10, Scale::Linear) => content.draw(root, x_range.log_scale(), y_range),
            (Scale::Log10, Scale::Log10) => content.draw(root, x_range.log_scale(), y_range.log_scale()),
        }
    }
}

/// Position of `value` along an axis as a fraction of its length.
fn axis_fraction(scale: Scale, range: &Range<f64>, value: f64) -> f64 {
    match scale {
        Scale::Linear => (value - range.start) / (range.end - range.start),
        Scale::Log10 => (value / range.start).log10() / (range.end / range.start).log10(),
    }
}

/// The plot corner with the fewest data points, so the legend hides as little as possible.
fn emptiest_corner(
    runs: &[Vec<Vec<(f64, f64)>>],
    chart: &LineChart,
    x_range: &Range<f64>,
    y_range: &Range<f64>,
) -> SeriesLabelPosition {
    let corners = [
        (SeriesLabelPosition::UpperRight, true, true),
        (SeriesLabelPosition::UpperLeft, false, true),
        (SeriesLabelPosition::LowerRight, true, false),
        (SeriesLabelPosition::LowerLeft, false, false),
    ];
    let in_corner = |&(x, y): &(f64, f64), right: bool, upper: bool| {
        let fx = axis_fraction(chart.x_scale, x_range, x);
        let fy = axis_fraction(chart.y_scale, y_range, y);
        (if right { fx > 0.55 } else { fx < 0.45 }) && (if upper { fy > 0.55 } else { fy < 0.45 })
    };
    corners
        .iter()
        .min_by_key(|&&(_, right, upper)| {
            runs.iter().flatten().flatten().filter(|p| in_corner(p, right, upper)).count()
        })
        .map_or(SeriesLabelPosition::UpperRight, |(position, _, _)| position.clone())
}

struct LineChartContent<'a> {
    chart: &'a LineChart<'a>,
    runs: &'a [Vec<Vec<(f64, f64)>>],
    legend_position: SeriesLabelPosition,
    x_tick_format: fn(&f64) -> String,
    y_tick_format: fn(&f64) -> String,
}

impl LineChartContent<'_> {
    fn draw<DB, X, Y>(&self, root: &DrawingArea<DB, Shift>, x_spec: X, y_spec: Y) -> Result<(), PlotError>
    where
        DB: DrawingBackend,
        X: AsRangedCoord<Value = f64>,
        Y: AsRangedCoord<Value = f64>,
        X::CoordDescType: ValueFormatter<f64>,
        Y::CoordDescType: ValueFormatter<f64>,
    {
        let mut chart = ChartBuilder::on(root)
            .caption(self.chart.title, (FONT, 28))
            .margin(20)
            .x_label_area_size(60)
            .y_label_area_size(95)
            .build_cartesian_2d(x_spec, y_spec)
            .map_err(to_message)?;
        chart
            .configure_mesh()
            .x_desc(self.chart.x_label)
            .y_desc(self.chart.y_label)
            .x_labels(10)
            .y_labels(10)
            .x_label_formatter(&self.x_tick_format)
            .y_label_formatter(&self.y_tick_format)
            .label_style((FONT, 17))
            .axis_desc_style((FONT, 20))
            .light_line_style(BLACK.mix(0.04))
            .bold_line_style(BLACK.mix(0.14))
            .draw()
            .map_err(to_message)?;

        let mut any_label = false;
        for (index, (series, runs)) in self.chart.series.iter().zip(self.runs).enumerate() {
            let color = PALETTE[index % PALETTE.len()];
            let line_style = color.stroke_width(LINE_WIDTH);
            let lines = chart
                .draw_series(
                    runs.iter().filter(|run| run.len() > 1).map(|run| PathElement::new(run.clone(), line_style)),
                )
                .map_err(to_message)?;
            if !series.name.is_empty() {
                any_label = true;
                let markers = series.markers;
                lines.label(series.name.as_str()).legend(move |(x, y)| {
                    // A zero-radius circle hides inside the line, keeping one element type for both cases.
                    let marker_radius = if markers { MARKER_RADIUS } else { 0 };
                    EmptyElement::at((x, y))
                        + PathElement::new(vec![(0, 0), (24, 0)], line_style)
                        + Circle::new((12, 0), marker_radius, color.filled())
                });
            }
            // Isolated points would be invisible as lines, so they always get a marker.
            let marked_points =
                runs.iter().filter(|run| series.markers || run.len() == 1).flat_map(|run| run.iter().copied());
            chart
                .draw_series(marked_points.map(|point| Circle::new(point, MARKER_RADIUS, color.filled())))
                .map_err(to_message)?;
        }

        if any_label {
            chart
                .configure_series_labels()
                .position(self.legend_position.clone())
                .margin(12)
                .label_font((FONT, 18))
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK.mix(0.4))
                .draw()
                .map_err(to_message)?;
        }
        Ok(())
    }
}
