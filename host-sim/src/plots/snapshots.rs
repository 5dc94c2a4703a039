//! Snapshots: truth against estimates (with their bounds) in the plane, a panel per scan, with the field of view and the central body.

use super::clip::{circle_polygon, clip_polyline};
use super::figure::{
    Bounds, CHART_MARGIN, FONT, Figure, PlotError, canvas_side, draw_message, draw_panel_title, ensure_font_registered,
    format_tick, is_plottable, panel_areas, panel_grid, to_message, write_png_and_svg,
};
use super::legend::{
    BODY_EDGE, BODY_FILL, FOV_COLOR, LEGEND_LINE_HEIGHT, LEGEND_PADDING, LegendSymbol, PlacedLegendEntry,
    draw_snapshot_legend, layout_legend, star_marker, truth_marker, within_bound_marker,
};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::ops::Range;
use std::path::Path;

/// The sensor's field of view drawn as two boundary rays and an arc: origin, boresight direction (radians from +x),
/// half angle (radians), max range. Same units as the points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FovLines {
    /// Sensor position.
    pub origin: [f64; 2],
    /// Boresight direction, radians counter-clockwise from +x.
    pub look_direction: f64,
    /// Half opening angle, radians.
    pub half_angle: f64,
    /// Length of the boundary rays and radius of the arc.
    pub max_range: f64,
}

/// One panel of a truth-vs-estimate snapshot (paper figures: truth positions, and the MAP hypothesis's estimates:
/// estimates within the error bound as green circles, outside it as red stars).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SnapshotPanel {
    /// Panel caption, e.g. "k = 10".
    pub title: String,
    /// True object positions.
    pub truth: Vec<[f64; 2]>,
    /// Estimated positions within the error bound of their truth.
    pub estimates_within_bound: Vec<[f64; 2]>,
    /// Estimated positions outside the error bound (or unmatched).
    pub estimates_outside_bound: Vec<[f64; 2]>,
    /// Sensor field of view, if any.
    pub fov: Option<FovLines>,
    /// Axis unit label, e.g. "km".
    pub unit: String,
    /// Optional central body radius to draw as a circle at the origin (e.g. Earth, 6378.137 km); None for none.
    pub central_body_radius: Option<f64>,
}

/// Writes the panels side by side (one row, up to 4 panels; more wrap to further rows), equal aspect ratio per panel,
/// a legend: truth (blue dots), within bound (green circles), outside bound (red stars/crosses), FOV (black lines).
///
/// Panels are 600x600 px with the legend in a strip below. Each panel's axes fit its points, its central body and its
/// sensor origin (the whole FOV only when there is nothing else); FOV lines are clipped to that view. Outside-bound
/// estimates are drawn as red stars.
pub fn plot_snapshots(stem: &Path, panels: &[SnapshotPanel]) -> Result<(), PlotError> {
    ensure_font_registered()?;
    write_png_and_svg(stem, &SnapshotFigure::new(panels)?)
}

pub(crate) const SNAPSHOT_PANEL_SIDE: u32 = 600;

pub(crate) const PANEL_TITLE_HEIGHT: u32 = 40;

pub(crate) const X_LABEL_AREA: u32 = 50;

const Y_LABEL_AREA: u32 = 85;

struct SnapshotFigure<'a> {
    panels: &'a [SnapshotPanel],
    legend_lines: Vec<Vec<PlacedLegendEntry>>,
    width: u32,
    panels_height: u32,
}

impl<'a> SnapshotFigure<'a> {
    fn new(panels: &'a [SnapshotPanel]) -> Result<Self, PlotError> {
        let (columns, rows) = panel_grid(panels.len());
        let width = canvas_side(columns, SNAPSHOT_PANEL_SIDE);
        let panels_height = canvas_side(rows, SNAPSHOT_PANEL_SIDE);

        let mut symbols = vec![LegendSymbol::Truth, LegendSymbol::WithinBound, LegendSymbol::OutsideBound];
        if panels.iter().any(|panel| panel.fov.is_some()) {
            symbols.push(LegendSymbol::Fov);
        }
        if panels.iter().any(|panel| panel.central_body_radius.is_some()) {
            symbols.push(LegendSymbol::CentralBody);
        }
        let legend_lines = layout_legend(&symbols, width)?;
        Ok(Self { panels, legend_lines, width, panels_height })
    }
}

impl Figure for SnapshotFigure<'_> {
    fn canvas_size(&self) -> (u32, u32) {
        let legend_height = self.legend_lines.len() as u32 * LEGEND_LINE_HEIGHT + 2 * LEGEND_PADDING;
        (self.width, self.panels_height.saturating_add(legend_height))
    }

    fn draw_on<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError> {
        let (panels_area, legend_area) = root.split_vertically(self.panels_height);
        if self.panels.is_empty() {
            draw_message(&panels_area, "No snapshot panels")?;
        }
        for (panel, area) in self.panels.iter().zip(panel_areas(&panels_area, self.panels.len())) {
            draw_snapshot_panel(&area, panel)?;
        }
        draw_snapshot_legend(&legend_area, &self.legend_lines)
    }
}

fn plottable_point(point: &[f64; 2]) -> Option<(f64, f64)> {
    (is_plottable(point[0]) && is_plottable(point[1])).then_some((point[0], point[1]))
}

fn plottable_points(points: &[[f64; 2]]) -> Vec<(f64, f64)> {
    points.iter().filter_map(plottable_point).collect()
}

fn valid_fov(fov: &Option<FovLines>) -> Option<FovLines> {
    let fov = (*fov)?;
    let valid = plottable_point(&fov.origin).is_some()
        && fov.look_direction.is_finite()
        && fov.half_angle.is_finite()
        && is_plottable(fov.max_range)
        && fov.max_range > 0.0;
    valid.then_some(FovLines { half_angle: fov.half_angle.abs().min(std::f64::consts::PI), ..fov })
}

fn valid_body_radius(radius: Option<f64>) -> Option<f64> {
    radius.filter(|&r| is_plottable(r) && r > 0.0)
}

/// The FOV outline as polylines: the two boundary rays and the arc at max range.
fn fov_polylines(fov: &FovLines) -> Vec<Vec<(f64, f64)>> {
    const ARC_SEGMENTS: usize = 96;
    let [ox, oy] = fov.origin;
    let at_angle = |angle: f64| (ox + fov.max_range * angle.cos(), oy + fov.max_range * angle.sin());
    let first = fov.look_direction - fov.half_angle;
    let last = fov.look_direction + fov.half_angle;
    let arc = (0..=ARC_SEGMENTS).map(|i| at_angle(first + (last - first) * i as f64 / ARC_SEGMENTS as f64)).collect();
    vec![vec![(ox, oy), at_angle(first)], vec![(ox, oy), at_angle(last)], arc]
}

/// Bounds that must be visible in a snapshot panel.
fn snapshot_bounds(panel: &SnapshotPanel) -> Option<Bounds> {
    let mut bounds = None;
    let points = [&panel.truth, &panel.estimates_within_bound, &panel.estimates_outside_bound];
    for (x, y) in points.into_iter().flat_map(|points| plottable_points(points)) {
        Bounds::include(&mut bounds, x, y);
    }
    if let Some(radius) = valid_body_radius(panel.central_body_radius) {
        Bounds::include(&mut bounds, -radius, -radius);
        Bounds::include(&mut bounds, radius, radius);
    }
    if let Some(fov) = valid_fov(&panel.fov) {
        Bounds::include(&mut bounds, fov.origin[0], fov.origin[1]);
        // With nothing else to frame, show the whole FOV.
        if bounds.as_ref().is_some_and(|b| b.x.start == b.x.end && b.y.start == b.y.end) {
            for (x, y) in fov_polylines(&fov).into_iter().flatten() {
                Bounds::include(&mut bounds, x, y);
            }
        }
    }
    bounds
}

/// Axis ranges with equal data units per pixel on both axes, framing `bounds` with a margin.
pub(crate) fn equal_aspect_ranges(bounds: Option<Bounds>, plot_pixels: (u32, u32)) -> (Range<f64>, Range<f64>) {
    let bounds = bounds.unwrap_or(Bounds { x: -1.0..1.0, y: -1.0..1.0 });
    let center = (bounds.x.start / 2.0 + bounds.x.end / 2.0, bounds.y.start / 2.0 + bounds.y.end / 2.0);
    let mut half = (bounds.x.end / 2.0 - bounds.x.start / 2.0, bounds.y.end / 2.0 - bounds.y.start / 2.0);
    let magnitude = center.0.abs().max(center.1.abs());
    if half.0.max(half.1) <= magnitude * 1e-9 || half.0.max(half.1) < f64::MIN_POSITIVE {
        let widened = if magnitude == 0.0 { 1.0 } else { magnitude * 0.05 };
        half = (widened, widened);
    }
    let (width, height) = (f64::from(plot_pixels.0.max(1)), f64::from(plot_pixels.1.max(1)));
    let units_per_pixel = (2.0 * half.0 / width).max(2.0 * half.1 / height) * 1.08;
    let (half_x, half_y) = (units_per_pixel * width / 2.0, units_per_pixel * height / 2.0);
    (center.0 - half_x..center.0 + half_x, center.1 - half_y..center.1 + half_y)
}

fn axis_caption(axis: &str, unit: &str) -> String {
    if unit.is_empty() { axis.to_string() } else { format!("{axis} [{unit}]") }
}

fn draw_snapshot_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    panel: &SnapshotPanel,
) -> Result<(), PlotError> {
    let (title_area, chart_area) = area.split_vertically(PANEL_TITLE_HEIGHT);
    draw_panel_title(&title_area, &panel.title)?;

    let (width, height) = chart_area.dim_in_pixel();
    let plot_pixels =
        (width.saturating_sub(2 * CHART_MARGIN + Y_LABEL_AREA), height.saturating_sub(2 * CHART_MARGIN + X_LABEL_AREA));
    let (x_range, y_range) = equal_aspect_ranges(snapshot_bounds(panel), plot_pixels);
    let mut chart = ChartBuilder::on(&chart_area)
        .margin(CHART_MARGIN)
        .x_label_area_size(X_LABEL_AREA)
        .y_label_area_size(Y_LABEL_AREA)
        .build_cartesian_2d(x_range.clone(), y_range.clone())
        .map_err(to_message)?;
    chart
        .configure_mesh()
        .x_desc(axis_caption("x", &panel.unit))
        .y_desc(axis_caption("y", &panel.unit))
        .x_labels(6)
        .y_labels(6)
        .x_label_formatter(&format_tick)
        .y_label_formatter(&format_tick)
        .label_style((FONT, 15))
        .axis_desc_style((FONT, 17))
        .max_light_lines(0)
        .bold_line_style(BLACK.mix(0.12))
        .draw()
        .map_err(to_message)?;

    if let Some(radius) = valid_body_radius(panel.central_body_radius) {
        let outline = circle_polygon(radius);
        chart.draw_series(std::iter::once(Polygon::new(outline.clone(), BODY_FILL.filled()))).map_err(to_message)?;
        let mut closed = outline;
        closed.push(closed[0]);
        chart.draw_series(std::iter::once(PathElement::new(closed, BODY_EDGE.stroke_width(1)))).map_err(to_message)?;
    }

    if let Some(fov) = valid_fov(&panel.fov) {
        let visible_pieces = fov_polylines(&fov)
            .iter()
            .flat_map(|polyline| clip_polyline(polyline, &x_range, &y_range))
            .collect::<Vec<_>>();
        chart
            .draw_series(visible_pieces.into_iter().map(|piece| PathElement::new(piece, FOV_COLOR.stroke_width(2))))
            .map_err(to_message)?;
    }

    // Estimates first so the small truth dots stay visible on top.
    chart
        .draw_series(plottable_points(&panel.estimates_within_bound).into_iter().map(within_bound_marker))
        .map_err(to_message)?;
    chart
        .draw_series(
            plottable_points(&panel.estimates_outside_bound)
                .into_iter()
                .map(|point| EmptyElement::at(point) + star_marker()),
        )
        .map_err(to_message)?;
    chart.draw_series(plottable_points(&panel.truth).into_iter().map(truth_marker)).map_err(to_message)?;
    Ok(())
}
