//! Scatter plots: named sets of points on linear axes, one colour each, no lines.

use super::figure::{
    Bounds, FONT, Figure, PALETTE, PlotError, ensure_font_registered, format_tick, is_plottable, linear_axis,
    to_message, write_png_and_svg,
};
use super::line_chart::{LINE_CHART_SIZE, Series};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

const POINT_RADIUS: i32 = 2;

/// A scatter plot of `series` (their `points`; `markers` is ignored: every point is a dot), 1200x800 px;
/// points that cannot be drawn are skipped; the legend names the series with a name.
pub fn scatter(stem: &Path, title: &str, x_label: &str, y_label: &str, series: &[Series]) -> Result<(), PlotError> {
    ensure_font_registered()?;
    write_png_and_svg(stem, &Scatter { title, x_label, y_label, series })
}

struct Scatter<'a> {
    title: &'a str,
    x_label: &'a str,
    y_label: &'a str,
    series: &'a [Series],
}

impl Figure for Scatter<'_> {
    fn canvas_size(&self) -> (u32, u32) {
        LINE_CHART_SIZE
    }

    fn draw_on<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError> {
        let drawable = |s: &Series| -> Vec<(f64, f64)> {
            s.points.iter().copied().filter(|&(x, y)| is_plottable(x) && is_plottable(y)).collect()
        };
        let points: Vec<Vec<(f64, f64)>> = self.series.iter().map(drawable).collect();
        let mut bounds = None;
        for &(x, y) in points.iter().flatten() {
            Bounds::include(&mut bounds, x, y);
        }
        let x_range = linear_axis(bounds.as_ref().map(|b| b.x.clone()));
        let y_range = linear_axis(bounds.as_ref().map(|b| b.y.clone()));
        let mut chart = ChartBuilder::on(root)
            .caption(self.title, (FONT, 28))
            .margin(20)
            .x_label_area_size(60)
            .y_label_area_size(95)
            .build_cartesian_2d(x_range, y_range)
            .map_err(to_message)?;
        chart
            .configure_mesh()
            .x_desc(self.x_label)
            .y_desc(self.y_label)
            .x_label_formatter(&format_tick)
            .y_label_formatter(&format_tick)
            .label_style((FONT, 17))
            .axis_desc_style((FONT, 20))
            .light_line_style(BLACK.mix(0.04))
            .bold_line_style(BLACK.mix(0.14))
            .draw()
            .map_err(to_message)?;
        let mut any_label = false;
        for (index, (series, points)) in self.series.iter().zip(&points).enumerate() {
            let color = PALETTE[index % PALETTE.len()];
            let dots = chart
                .draw_series(points.iter().map(|&p| Circle::new(p, POINT_RADIUS, color.mix(0.6).filled())))
                .map_err(to_message)?;
            if !series.name.is_empty() {
                any_label = true;
                dots.label(series.name.as_str()).legend(move |(x, y)| Circle::new((x + 12, y), 5, color.filled()));
            }
        }
        if any_label {
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::UpperLeft)
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
