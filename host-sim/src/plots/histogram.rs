//! Histograms of counts over whole-number values (e.g. how many clusters hold k objects), one bar per value.

use super::figure::{
    FONT, Figure, PALETTE, PlotError, ensure_font_registered, format_tick, to_message, write_png_and_svg,
};
use super::line_chart::LINE_CHART_SIZE;
use super::weights::format_rank_tick;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

const BAR_HALF_WIDTH: f64 = 0.4;

/// The foot of the bars on the log axis: below a count of 1.
const BASE: f64 = 0.5;

/// A histogram of `counts`, (value, count) with whole-number values, 1200x800 px; the y axis is log10 (a
/// count of 1 next to thousands stays visible), the x axis at least 8 wide.
pub fn histogram(
    stem: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    counts: &[(u64, u64)],
) -> Result<(), PlotError> {
    ensure_font_registered()?;
    write_png_and_svg(stem, &Histogram { title, x_label, y_label, counts })
}

struct Histogram<'a> {
    title: &'a str,
    x_label: &'a str,
    y_label: &'a str,
    counts: &'a [(u64, u64)],
}

impl Figure for Histogram<'_> {
    fn canvas_size(&self) -> (u32, u32) {
        LINE_CHART_SIZE
    }

    fn draw_on<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError> {
        let low = self.counts.iter().map(|c| c.0).min().unwrap_or(0) as f64;
        let high = self.counts.iter().map(|c| c.0).max().unwrap_or(1) as f64;
        let top = self.counts.iter().map(|c| c.1).max().unwrap_or(1).max(1) as f64;
        let x_range = low.min(1.0) - 0.5..high.max(low + 7.0) + 0.5;
        let y_range = (BASE..top * 2.0).log_scale();
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
            .x_labels(20)
            .x_label_formatter(&format_rank_tick)
            .y_label_formatter(&format_tick)
            .label_style((FONT, 17))
            .axis_desc_style((FONT, 20))
            .disable_x_mesh()
            .bold_line_style(BLACK.mix(0.14))
            .draw()
            .map_err(to_message)?;
        let color = PALETTE[0];
        chart
            .draw_series(self.counts.iter().map(|&(value, count)| {
                let x = value as f64;
                Rectangle::new([(x - BAR_HALF_WIDTH, BASE), (x + BAR_HALF_WIDTH, count as f64)], color.filled())
            }))
            .map_err(to_message)?;
        Ok(())
    }
}
