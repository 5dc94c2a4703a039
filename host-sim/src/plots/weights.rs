//! Hypothesis-weight bar charts: a panel per scan, the weights ranked.

use super::figure::{
    CHART_MARGIN, FONT, Figure, PlotError, canvas_side, draw_message, draw_panel_title, ensure_font_registered,
    format_tick, is_plottable, linear_axis, panel_areas, panel_grid, to_message, write_png_and_svg,
};
use super::snapshots::{PANEL_TITLE_HEIGHT, X_LABEL_AREA};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// Bar charts of hypothesis weights, one panel per snapshot (paper Fig. 6): x = hypothesis rank 1..n, y = weight in [0,1].
///
/// Weights are sorted into descending order (rank 1 = most likely); non-finite weights are dropped. The y axis grows
/// beyond [0, 1] only if a weight does. Panels are laid out like [`plot_snapshots`], about 500x420 px each.
pub fn plot_hypothesis_weights(stem: &Path, panels: &[(String, Vec<f64>)]) -> Result<(), PlotError> {
    ensure_font_registered()?;
    write_png_and_svg(stem, &WeightsFigure { panels })
}

pub(crate) const WEIGHT_PANEL_SIZE: (u32, u32) = (500, 420);

const BAR_COLOR: RGBColor = RGBColor(31, 119, 180);

const BAR_HALF_WIDTH: f64 = 0.38;

struct WeightsFigure<'a> {
    panels: &'a [(String, Vec<f64>)],
}

impl Figure for WeightsFigure<'_> {
    fn canvas_size(&self) -> (u32, u32) {
        let (columns, rows) = panel_grid(self.panels.len());
        (canvas_side(columns, WEIGHT_PANEL_SIZE.0), canvas_side(rows, WEIGHT_PANEL_SIZE.1))
    }

    fn draw_on<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError> {
        if self.panels.is_empty() {
            return draw_message(root, "No hypothesis weights");
        }
        for ((title, weights), area) in self.panels.iter().zip(panel_areas(root, self.panels.len())) {
            draw_weights_panel(&area, title, weights)?;
        }
        Ok(())
    }
}

/// Prints integer ticks only (ranks), leaving fractional ticks unlabelled.
pub(crate) fn format_rank_tick(value: &f64) -> String {
    if (value - value.round()).abs() < 1e-6 { format!("{}", value.round() as i64) } else { String::new() }
}

/// (rank, weight) bars: drawable weights in descending order, ranks from 1.
pub(crate) fn ranked_bars(weights: &[f64]) -> Vec<(f64, f64)> {
    let mut ranked: Vec<f64> = weights.iter().copied().filter(|&weight| is_plottable(weight)).collect();
    ranked.sort_by(|a, b| b.total_cmp(a));
    ranked.into_iter().enumerate().map(|(index, weight)| ((index + 1) as f64, weight)).collect()
}

fn draw_weights_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    title: &str,
    weights: &[f64],
) -> Result<(), PlotError> {
    let (title_area, chart_area) = area.split_vertically(PANEL_TITLE_HEIGHT);
    draw_panel_title(&title_area, title)?;

    let bars = ranked_bars(weights);
    let rank_count = bars.len().max(1);
    let low = bars.iter().map(|&(_, w)| w).fold(0.0, f64::min);
    let high = bars.iter().map(|&(_, w)| w).fold(1.0, f64::max);
    let y_range = if low < 0.0 || high > 1.0 { linear_axis(Some(low..high)) } else { 0.0..1.05 };

    let mut chart = ChartBuilder::on(&chart_area)
        .margin(CHART_MARGIN)
        .x_label_area_size(X_LABEL_AREA)
        .y_label_area_size(70)
        .build_cartesian_2d(0.5..rank_count as f64 + 0.5, y_range)
        .map_err(to_message)?;
    chart
        .configure_mesh()
        .x_desc("Hypothesis rank")
        .y_desc("Weight")
        .x_labels(rank_count.min(10))
        .y_labels(6)
        .x_label_formatter(&format_rank_tick)
        .y_label_formatter(&format_tick)
        .label_style((FONT, 15))
        .axis_desc_style((FONT, 17))
        .disable_x_mesh()
        .max_light_lines(0)
        .bold_line_style(BLACK.mix(0.12))
        .draw()
        .map_err(to_message)?;
    chart
        .draw_series(bars.into_iter().map(|(rank, weight)| {
            Rectangle::new([(rank - BAR_HALF_WIDTH, 0.0), (rank + BAR_HALF_WIDTH, weight)], BAR_COLOR.filled())
        }))
        .map_err(to_message)?;
    Ok(())
}
