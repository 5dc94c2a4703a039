//! Result figures for the tracker simulator: truth-vs-estimate snapshots, hypothesis-weight bar charts and line
//! charts (linear or log10 axes). Every function writes both `<stem>.png` and `<stem>.svg`.
//!
//! Text is rendered with a vendored DejaVu Sans font (registered with plotters' `ab_glyph` backend), so no system
//! font libraries are needed. Non-finite values (and values beyond ±1e300, or non-positive values on log axes) are
//! skipped; empty or degenerate data still yields a valid, labelled figure.

use std::fmt::Display;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::{FontStyle, register_font};

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

/// Axis scale.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Scale {
    /// Evenly spaced values.
    #[default]
    Linear,
    /// Evenly spaced decades; only positive values are shown.
    Log10,
}

/// Writes the panels side by side (one row, up to 4 panels; more wrap to further rows), equal aspect ratio per panel,
/// a legend: truth (blue dots), within bound (green circles), outside bound (red stars/crosses), FOV (black lines).
///
/// Each panel's axes fit its points, its central body and its sensor origin; FOV lines are clipped to that view.
pub fn plot_snapshots(stem: &Path, panels: &[SnapshotPanel]) -> Result<(), String> {
    ensure_font_registered()?;
    write_png_and_svg(stem, &SnapshotFigure::new(panels)?)
}

/// Bar charts of hypothesis weights, one panel per snapshot (paper Fig. 6): x = hypothesis rank 1..n, y = weight in [0,1].
///
/// Panels are laid out like [`plot_snapshots`]; non-finite weights leave their bar out.
pub fn plot_hypothesis_weights(stem: &Path, panels: &[(String, Vec<f64>)]) -> Result<(), String> {
    ensure_font_registered()?;
    write_png_and_svg(stem, &WeightsFigure { panels })
}

/// A line chart of several series with a legend (used for expected number of objects over time, GOSPA over time,
/// and a log-log timing plot of children generation time vs number of possible children). With Log10 scales, points
/// with non-positive coordinates are skipped.
pub fn plot_series(
    stem: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    x_scale: Scale,
    y_scale: Scale,
    series: &[Series],
) -> Result<(), String> {
    ensure_font_registered()?;
    write_png_and_svg(stem, &LineChart { title, x_label, y_label, x_scale, y_scale, series })
}

// ---------------------------------------------------------------------------------------------------------------
// Shared machinery
// ---------------------------------------------------------------------------------------------------------------

const FONT: &str = "sans-serif";
const FONT_BYTES: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");

/// Largest magnitude drawn; keeps axis spans finite.
const MAX_PLOTTABLE: f64 = 1e300;
/// Largest canvas side in pixels, to refuse absurd allocations.
const MAX_CANVAS_SIDE: u32 = 30_000;
/// Panels per row in multi-panel figures.
const PANELS_PER_ROW: usize = 4;

/// Tableau 10: distinct, colour-blind-friendly series colours.
const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

/// Registers the vendored font once per process under the family name plotters uses by default.
fn ensure_font_registered() -> Result<(), String> {
    static REGISTERED: OnceLock<Result<(), String>> = OnceLock::new();
    REGISTERED
        .get_or_init(|| {
            register_font(FONT, FontStyle::Normal, FONT_BYTES)
                .map_err(|_| "plots: the vendored DejaVuSans.ttf is not a valid font".to_string())
        })
        .clone()
}

/// A figure that can be drawn on any plotters backend.
trait Figure {
    /// Canvas size in pixels (width, height).
    fn canvas_size(&self) -> (u32, u32);
    /// Draws onto a white canvas.
    fn draw_on<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String>;
}

fn to_message(error: impl Display) -> String {
    error.to_string()
}

/// `stem` + "." + `extension` (appended, so dots inside the stem survive).
fn path_with_extension(stem: &Path, extension: &str) -> PathBuf {
    let mut path = stem.as_os_str().to_owned();
    path.push(".");
    path.push(extension);
    PathBuf::from(path)
}

fn write_png_and_svg(stem: &Path, figure: &impl Figure) -> Result<(), String> {
    if stem.as_os_str().is_empty() {
        return Err("plots: empty output path".to_string());
    }
    if let Some(parent) = stem.parent().filter(|parent| !parent.as_os_str().is_empty()) {
        std::fs::create_dir_all(parent)
            .map_err(|e| format!("plots: cannot create directory {}: {e}", parent.display()))?;
    }
    let size = figure.canvas_size();
    if size.0 > MAX_CANVAS_SIDE || size.1 > MAX_CANVAS_SIDE {
        return Err(format!(
            "plots: figure for {} would be {}x{} px, more than {MAX_CANVAS_SIDE} px per side (too many panels?)",
            stem.display(),
            size.0,
            size.1
        ));
    }

    let png_path = path_with_extension(stem, "png");
    let png_result = (|| {
        let root = BitMapBackend::new(&png_path, size).into_drawing_area();
        root.fill(&WHITE).map_err(to_message)?;
        figure.draw_on(&root)?;
        root.present().map_err(to_message)
    })();
    png_result.map_err(|e| format!("plots: writing {} failed: {e}", png_path.display()))?;

    let svg_path = path_with_extension(stem, "svg");
    let svg_result = (|| {
        let root = SVGBackend::new(&svg_path, size).into_drawing_area();
        root.fill(&WHITE).map_err(to_message)?;
        figure.draw_on(&root)?;
        root.present().map_err(to_message)
    })();
    svg_result.map_err(|e| format!("plots: writing {} failed: {e}", svg_path.display()))
}

fn is_plottable(value: f64) -> bool {
    value.is_finite() && value.abs() <= MAX_PLOTTABLE
}

fn is_plottable_on(scale: Scale, value: f64) -> bool {
    match scale {
        Scale::Linear => is_plottable(value),
        Scale::Log10 => is_plottable(value) && value >= 1.0 / MAX_PLOTTABLE,
    }
}

/// Axis-aligned bounding box of the data that must be visible.
#[derive(Debug, Clone, PartialEq)]
struct Bounds {
    x: Range<f64>,
    y: Range<f64>,
}

impl Bounds {
    fn around(x: f64, y: f64) -> Self {
        Self { x: x..x, y: y..y }
    }

    fn include(bounds: &mut Option<Bounds>, x: f64, y: f64) {
        match bounds {
            None => *bounds = Some(Self::around(x, y)),
            Some(b) => {
                b.x = b.x.start.min(x)..b.x.end.max(x);
                b.y = b.y.start.min(y)..b.y.end.max(y);
            }
        }
    }
}

/// Tick labels: plain decimals for moderate magnitudes, `1.5e7` style otherwise, never float noise.
fn format_tick(value: &f64) -> String {
    let value = *value;
    if value == 0.0 || !value.is_finite() {
        return if value.is_nan() { String::new() } else { "0".to_string() };
    }
    let magnitude = value.abs().log10().floor();
    if !(-3.0..5.0).contains(&magnitude) {
        let text = format!("{value:.4e}");
        let (mantissa, exponent) = text.split_once('e').unwrap_or((&text, "0"));
        return format!("{}e{exponent}", trim_decimal_zeros(mantissa));
    }
    let decimals = (5.0 - magnitude).clamp(0.0, 9.0) as usize;
    trim_decimal_zeros(&format!("{value:.decimals$}")).to_string()
}

fn trim_decimal_zeros(text: &str) -> &str {
    if text.contains('.') { text.trim_end_matches('0').trim_end_matches('.') } else { text }
}

/// Linear axis covering `data` with 5 % padding; empty or degenerate spans are widened.
fn linear_axis(data: Option<Range<f64>>) -> Range<f64> {
    let Some(data) = data else { return 0.0..1.0 };
    let center = data.start / 2.0 + data.end / 2.0;
    let half_span = data.end / 2.0 - data.start / 2.0;
    let half_span = if half_span <= center.abs() * 1e-9 || half_span < f64::MIN_POSITIVE {
        if center == 0.0 { 1.0 } else { center.abs() * 0.05 }
    } else {
        half_span * 1.05
    };
    center - half_span..center + half_span
}

/// Log10 axis covering positive `data` with a little padding, always containing at least one power of ten.
fn log_axis(data: Option<Range<f64>>) -> Range<f64> {
    let Some(data) = data else { return 1.0..10.0 };
    let (mut low, mut high) = (data.start.log10(), data.end.log10());
    let span = high - low;
    if span < 1e-9 {
        low -= 0.5;
        high += 0.5;
    } else {
        low -= span * 0.03;
        high += span * 0.03;
    }
    // plotters only labels powers of ten (and their multiples inside a decade): make sure one is in view.
    if high.floor() < low.ceil() {
        low = low.floor();
        high = high.ceil();
    }
    let limit = MAX_PLOTTABLE.log10();
    10f64.powf(low.clamp(-limit, limit))..10f64.powf(high.clamp(-limit, limit))
}

/// Lays out `count` panels of `panel_size` in rows of at most [`PANELS_PER_ROW`]; returns (columns, rows).
fn panel_grid(count: usize) -> (usize, usize) {
    let columns = count.clamp(1, PANELS_PER_ROW);
    (columns, count.max(1).div_ceil(columns))
}

fn canvas_side(panels: usize, panel_side: u32) -> u32 {
    u32::try_from(panels).ok().and_then(|n| n.checked_mul(panel_side)).unwrap_or(u32::MAX)
}

fn centered_text(size: u32) -> TextStyle<'static> {
    TextStyle::from((FONT, size).into_font()).pos(Pos::new(HPos::Center, VPos::Center))
}

/// Writes a centred grey message, used when there is nothing to plot.
fn draw_message<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, message: &str) -> Result<(), String> {
    let (width, height) = area.dim_in_pixel();
    let style = centered_text(22).color(&RGBColor(110, 110, 110));
    area.draw(&Text::new(message.to_string(), (width as i32 / 2, height as i32 / 2), style)).map_err(to_message)
}

fn draw_panel_title<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, title: &str) -> Result<(), String> {
    let (width, height) = area.dim_in_pixel();
    area.draw(&Text::new(title.to_string(), (width as i32 / 2, height as i32 / 2), centered_text(22)))
        .map_err(to_message)
}

/// Splits `root` into a grid and returns the first `count` cells in reading order.
fn panel_areas<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, count: usize) -> Vec<DrawingArea<DB, Shift>> {
    let (columns, rows) = panel_grid(count);
    root.split_evenly((rows, columns)).into_iter().take(count).collect()
}

// ---------------------------------------------------------------------------------------------------------------
// Markers
// ---------------------------------------------------------------------------------------------------------------

const TRUTH_COLOR: RGBColor = RGBColor(20, 80, 220);
const WITHIN_BOUND_COLOR: RGBColor = RGBColor(0, 150, 40);
const OUTSIDE_BOUND_COLOR: RGBColor = RGBColor(220, 20, 20);
const FOV_COLOR: RGBColor = BLACK;
const BODY_FILL: RGBColor = RGBColor(215, 225, 235);
const BODY_EDGE: RGBColor = RGBColor(120, 130, 145);

const TRUTH_DOT_RADIUS: i32 = 4;
const WITHIN_CIRCLE_RADIUS: i32 = 8;
const STAR_OUTER_RADIUS: f64 = 10.0;

/// Filled five-pointed star (pixel offsets from its centre, y down), to be placed with `EmptyElement::at(..) +`.
fn star_marker() -> Polygon<(i32, i32)> {
    let vertices: Vec<(i32, i32)> = (0..10)
        .map(|i| {
            let radius = if i % 2 == 0 { STAR_OUTER_RADIUS } else { STAR_OUTER_RADIUS * 0.42 };
            let angle = -std::f64::consts::FRAC_PI_2 + f64::from(i) * std::f64::consts::PI / 5.0;
            ((radius * angle.cos()).round() as i32, (radius * angle.sin()).round() as i32)
        })
        .collect();
    Polygon::new(vertices, OUTSIDE_BOUND_COLOR.filled())
}

fn truth_marker<C>(at: C) -> Circle<C, i32> {
    Circle::new(at, TRUTH_DOT_RADIUS, TRUTH_COLOR.filled())
}

fn within_bound_marker<C>(at: C) -> Circle<C, i32> {
    Circle::new(at, WITHIN_CIRCLE_RADIUS, WITHIN_BOUND_COLOR.stroke_width(2))
}

// ---------------------------------------------------------------------------------------------------------------
// Snapshots
// ---------------------------------------------------------------------------------------------------------------

const SNAPSHOT_PANEL_SIDE: u32 = 600;
const PANEL_TITLE_HEIGHT: u32 = 40;
const CHART_MARGIN: u32 = 14;
const X_LABEL_AREA: u32 = 50;
const Y_LABEL_AREA: u32 = 85;
const LEGEND_FONT_SIZE: u32 = 18;
const LEGEND_LINE_HEIGHT: u32 = 32;
const LEGEND_SYMBOL_WIDTH: u32 = 34;
const LEGEND_ENTRY_GAP: u32 = 34;
const LEGEND_PADDING: u32 = 12;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum LegendSymbol {
    Truth,
    WithinBound,
    OutsideBound,
    Fov,
    CentralBody,
}

impl LegendSymbol {
    fn label(self) -> &'static str {
        match self {
            Self::Truth => "Truth",
            Self::WithinBound => "Estimate within bound",
            Self::OutsideBound => "Estimate outside bound",
            Self::Fov => "Sensor FOV",
            Self::CentralBody => "Central body",
        }
    }
}

/// A legend entry placed at pixel offset `x` within its line.
struct PlacedLegendEntry {
    symbol: LegendSymbol,
    x: u32,
}

struct SnapshotFigure<'a> {
    panels: &'a [SnapshotPanel],
    legend_lines: Vec<Vec<PlacedLegendEntry>>,
    width: u32,
    panels_height: u32,
}

impl<'a> SnapshotFigure<'a> {
    fn new(panels: &'a [SnapshotPanel]) -> Result<Self, String> {
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

/// Flows legend entries into lines no wider than `width`.
fn layout_legend(symbols: &[LegendSymbol], width: u32) -> Result<Vec<Vec<PlacedLegendEntry>>, String> {
    let font = (FONT, LEGEND_FONT_SIZE).into_font();
    let mut lines: Vec<Vec<PlacedLegendEntry>> = vec![Vec::new()];
    let mut x = LEGEND_PADDING;
    for &symbol in symbols {
        let (text_width, _) = font.box_size(symbol.label()).map_err(to_message)?;
        let entry_width = LEGEND_SYMBOL_WIDTH + 8 + text_width;
        if x > LEGEND_PADDING && x + entry_width > width.saturating_sub(LEGEND_PADDING) {
            lines.push(Vec::new());
            x = LEGEND_PADDING;
        }
        lines.last_mut().expect("lines starts non-empty").push(PlacedLegendEntry { symbol, x });
        x += entry_width + LEGEND_ENTRY_GAP;
    }
    Ok(lines)
}

impl Figure for SnapshotFigure<'_> {
    fn canvas_size(&self) -> (u32, u32) {
        let legend_height = self.legend_lines.len() as u32 * LEGEND_LINE_HEIGHT + 2 * LEGEND_PADDING;
        (self.width, self.panels_height.saturating_add(legend_height))
    }

    fn draw_on<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
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

fn draw_snapshot_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    lines: &[Vec<PlacedLegendEntry>],
) -> Result<(), String> {
    let text_style = TextStyle::from((FONT, LEGEND_FONT_SIZE).into_font()).pos(Pos::new(HPos::Left, VPos::Center));
    for (row, line) in lines.iter().enumerate() {
        let y = (LEGEND_PADDING + row as u32 * LEGEND_LINE_HEIGHT + LEGEND_LINE_HEIGHT / 2) as i32;
        for entry in line {
            let x = entry.x as i32;
            let symbol_center = (x + LEGEND_SYMBOL_WIDTH as i32 / 2, y);
            let drawn = match entry.symbol {
                LegendSymbol::Truth => area.draw(&truth_marker(symbol_center)),
                LegendSymbol::WithinBound => area.draw(&within_bound_marker(symbol_center)),
                LegendSymbol::OutsideBound => area.draw(&(EmptyElement::at(symbol_center) + star_marker())),
                LegendSymbol::Fov => area.draw(&PathElement::new(
                    vec![(x, y), (x + LEGEND_SYMBOL_WIDTH as i32, y)],
                    FOV_COLOR.stroke_width(2),
                )),
                LegendSymbol::CentralBody => area.draw(&Rectangle::new(
                    [(x + 4, y - 9), (x + LEGEND_SYMBOL_WIDTH as i32 - 4, y + 9)],
                    BODY_FILL.filled(),
                )),
            };
            drawn.map_err(to_message)?;
            if entry.symbol == LegendSymbol::CentralBody {
                area.draw(&Rectangle::new(
                    [(x + 4, y - 9), (x + LEGEND_SYMBOL_WIDTH as i32 - 4, y + 9)],
                    BODY_EDGE.stroke_width(1),
                ))
                .map_err(to_message)?;
            }
            let label = Text::new(entry.symbol.label(), (x + LEGEND_SYMBOL_WIDTH as i32 + 8, y), text_style.clone());
            area.draw(&label).map_err(to_message)?;
        }
    }
    Ok(())
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

fn circle_polygon(radius: f64) -> Vec<(f64, f64)> {
    const SEGMENTS: usize = 180;
    (0..SEGMENTS)
        .map(|i| {
            let angle = std::f64::consts::TAU * i as f64 / SEGMENTS as f64;
            (radius * angle.cos(), radius * angle.sin())
        })
        .collect()
}

/// Clips segment `a`-`b` to the view rectangle (Liang–Barsky); None if it lies entirely outside.
fn clip_segment(a: (f64, f64), b: (f64, f64), x: &Range<f64>, y: &Range<f64>) -> Option<((f64, f64), (f64, f64))> {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
    for (p, q) in [(-dx, a.0 - x.start), (dx, x.end - a.0), (-dy, a.1 - y.start), (dy, y.end - a.1)] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
            if t0 > t1 {
                return None;
            }
        }
    }
    Some(((a.0 + t0 * dx, a.1 + t0 * dy), (a.0 + t1 * dx, a.1 + t1 * dy)))
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
fn equal_aspect_ranges(bounds: Option<Bounds>, plot_pixels: (u32, u32)) -> (Range<f64>, Range<f64>) {
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

fn draw_snapshot_panel<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, panel: &SnapshotPanel) -> Result<(), String> {
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
        .light_line_style(WHITE)
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
        let visible_segments: Vec<_> = fov_polylines(&fov)
            .iter()
            .flat_map(|polyline| polyline.windows(2).map(|pair| (pair[0], pair[1])))
            .filter_map(|(a, b)| clip_segment(a, b, &x_range, &y_range))
            .collect();
        chart
            .draw_series(
                visible_segments.into_iter().map(|(a, b)| PathElement::new(vec![a, b], FOV_COLOR.stroke_width(2))),
            )
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

// ---------------------------------------------------------------------------------------------------------------
// Hypothesis weights
// ---------------------------------------------------------------------------------------------------------------

const WEIGHT_PANEL_SIZE: (u32, u32) = (500, 420);
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

    fn draw_on<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
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
fn format_rank_tick(value: &f64) -> String {
    if (value - value.round()).abs() < 1e-6 { format!("{}", value.round() as i64) } else { String::new() }
}

fn draw_weights_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    title: &str,
    weights: &[f64],
) -> Result<(), String> {
    let (title_area, chart_area) = area.split_vertically(PANEL_TITLE_HEIGHT);
    draw_panel_title(&title_area, title)?;

    let bars: Vec<(f64, f64)> = weights
        .iter()
        .enumerate()
        .filter(|(_, weight)| is_plottable(**weight))
        .map(|(index, &weight)| ((index + 1) as f64, weight))
        .collect();
    let rank_count = weights.len().max(1);
    let low = bars.iter().map(|&(_, w)| w).fold(0.0, f64::min);
    let high = bars.iter().map(|&(_, w)| w).fold(1.0, f64::max);
    let y_range = if low < 0.0 || high > 1.0 { linear_axis(Some(low..high)) } else { 0.0..1.0 };

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
        .light_line_style(WHITE)
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

// ---------------------------------------------------------------------------------------------------------------
// Line charts
// ---------------------------------------------------------------------------------------------------------------

const LINE_CHART_SIZE: (u32, u32) = (1200, 800);
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
                let mut runs = vec![Vec::new()];
                for &(x, y) in &series.points {
                    if is_plottable_on(self.x_scale, x) && is_plottable_on(self.y_scale, y) {
                        runs.last_mut().expect("runs starts non-empty").push((x, y));
                    } else if runs.last().is_some_and(|run| !run.is_empty()) {
                        runs.push(Vec::new());
                    }
                }
                runs.retain(|run| !run.is_empty());
                runs
            })
            .collect()
    }
}

impl Figure for LineChart<'_> {
    fn canvas_size(&self) -> (u32, u32) {
        LINE_CHART_SIZE
    }

    fn draw_on<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
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
        let content = LineChartContent { chart: self, runs: &runs, legend_position };
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
}

impl LineChartContent<'_> {
    fn draw<DB, X, Y>(&self, root: &DrawingArea<DB, Shift>, x_spec: X, y_spec: Y) -> Result<(), String>
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
            .x_label_formatter(&format_tick)
            .y_label_formatter(&format_tick)
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
