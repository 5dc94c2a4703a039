//! Result figures for the tracker simulator: truth-vs-estimate snapshots, hypothesis-weight bar charts, line
//! charts (linear or log10 axes) and per-sensor sky plots (azimuth/elevation or right ascension/declination). Every
//! function writes both `<stem>.png` and `<stem>.svg`.
//!
//! Text is rendered with a vendored DejaVu Sans font (registered with plotters' `ab_glyph` backend), so no system
//! font libraries are needed. In snapshots, bar and line charts, points that cannot be drawn are skipped: non-finite
//! values, magnitudes above 1e300, and on log axes values outside [1e-150, 1e150] (including non-positive ones). Sky
//! plots instead refuse a non-finite angle with an error naming the series. Empty or degenerate data still yields a
//! valid, labelled figure.

use std::fmt::Display;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::element::ComposedElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::{FontStyle, register_font};

/// A figure that could not be drawn or written: a one-line message naming the file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PlotError(pub String);

impl std::fmt::Display for PlotError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for PlotError {}

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
/// Panels are 600x600 px with the legend in a strip below. Each panel's axes fit its points, its central body and its
/// sensor origin (the whole FOV only when there is nothing else); FOV lines are clipped to that view. Outside-bound
/// estimates are drawn as red stars.
pub fn plot_snapshots(stem: &Path, panels: &[SnapshotPanel]) -> Result<(), PlotError> {
    ensure_font_registered()?;
    write_png_and_svg(stem, &SnapshotFigure::new(panels)?)
}

/// Bar charts of hypothesis weights, one panel per snapshot (paper Fig. 6): x = hypothesis rank 1..n, y = weight in [0,1].
///
/// Weights are sorted into descending order (rank 1 = most likely); non-finite weights are dropped. The y axis grows
/// beyond [0, 1] only if a weight does. Panels are laid out like [`plot_snapshots`], about 500x420 px each.
pub fn plot_hypothesis_weights(stem: &Path, panels: &[(String, Vec<f64>)]) -> Result<(), PlotError> {
    ensure_font_registered()?;
    write_png_and_svg(stem, &WeightsFigure { panels })
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

// ---------------------------------------------------------------------------------------------------------------
// Shared machinery
// ---------------------------------------------------------------------------------------------------------------

const FONT: &str = "sans-serif";
const FONT_BYTES: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");

/// Largest magnitude drawn; keeps axis spans finite.
const MAX_PLOTTABLE: f64 = 1e300;
/// Log axes show values in [1/this, this]: plotters loops forever once an axis's end/start ratio overflows.
const MAX_LOG_PLOTTABLE: f64 = 1e150;
/// Largest canvas side in pixels, to refuse absurd allocations.
const MAX_CANVAS_SIDE: u32 = 30_000;
/// Panels per row in multi-panel figures.
const PANELS_PER_ROW: usize = 4;

/// Tableau 10: distinct series colours.
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
fn ensure_font_registered() -> Result<(), PlotError> {
    static REGISTERED: OnceLock<Result<(), PlotError>> = OnceLock::new();
    REGISTERED
        .get_or_init(|| {
            register_font(FONT, FontStyle::Normal, FONT_BYTES)
                .map_err(|_| PlotError("plots: the vendored DejaVuSans.ttf is not a valid font".to_string()))
        })
        .clone()
}

/// A figure that can be drawn on any plotters backend.
trait Figure {
    /// Canvas size in pixels (width, height).
    fn canvas_size(&self) -> (u32, u32);
    /// Draws onto a white canvas.
    fn draw_on<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError>;
}

fn to_message(error: impl Display) -> PlotError {
    PlotError(error.to_string())
}

/// `stem` + "." + `extension` (appended, so dots inside the stem survive).
fn path_with_extension(stem: &Path, extension: &str) -> PathBuf {
    let mut path = stem.as_os_str().to_owned();
    path.push(".");
    path.push(extension);
    PathBuf::from(path)
}

/// Renders `figure` to `<stem>.png` and `<stem>.svg`, creating the parent directory if needed.
fn write_png_and_svg(stem: &Path, figure: &impl Figure) -> Result<(), PlotError> {
    if stem.as_os_str().is_empty() {
        return Err(PlotError("plots: empty output path".to_string()));
    }
    let size = figure.canvas_size();
    if size.0 > MAX_CANVAS_SIDE || size.1 > MAX_CANVAS_SIDE {
        return Err(PlotError(format!(
            "plots: figure for {} would be {}x{} px, more than {MAX_CANVAS_SIDE} px per side (too many panels?)",
            stem.display(),
            size.0,
            size.1
        )));
    }
    if let Some(parent) = stem.parent().filter(|parent| !parent.as_os_str().is_empty()) {
        std::fs::create_dir_all(parent)
            .map_err(|e| PlotError(format!("plots: cannot create directory {}: {e}", parent.display())))?;
    }

    let png_path = path_with_extension(stem, "png");
    render(BitMapBackend::new(&png_path, size).into_drawing_area(), figure)
        .map_err(|e| PlotError(format!("plots: writing {} failed: {e}", png_path.display())))?;
    let svg_path = path_with_extension(stem, "svg");
    render(SVGBackend::new(&svg_path, size).into_drawing_area(), figure)
        .map_err(|e| PlotError(format!("plots: writing {} failed: {e}", svg_path.display())))
}

fn render<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, figure: &impl Figure) -> Result<(), PlotError> {
    root.fill(&WHITE).map_err(to_message)?;
    figure.draw_on(&root)?;
    root.present().map_err(to_message)
}

fn is_plottable(value: f64) -> bool {
    value.is_finite() && value.abs() <= MAX_PLOTTABLE
}

fn is_plottable_on(scale: Scale, value: f64) -> bool {
    match scale {
        Scale::Linear => is_plottable(value),
        Scale::Log10 => (1.0 / MAX_LOG_PLOTTABLE..=MAX_LOG_PLOTTABLE).contains(&value),
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
    if !value.is_finite() {
        return String::new();
    }
    if value == 0.0 {
        return "0".to_string();
    }
    let magnitude = value.abs().log10().floor();
    if !(-3.0..5.0).contains(&magnitude) {
        return format_scientific(&value);
    }
    let decimals = (5.0 - magnitude).clamp(0.0, 9.0) as usize;
    trim_decimal_zeros(&format!("{value:.decimals$}")).to_string()
}

/// `1e7`, `2.5e-4`: used for all ticks of log axes spanning many decades, so labels look alike.
fn format_scientific(value: &f64) -> String {
    let text = format!("{value:.4e}");
    let (mantissa, exponent) = text.split_once('e').unwrap_or((&text, "0"));
    format!("{}e{exponent}", trim_decimal_zeros(mantissa))
}

/// Tick formatter for an axis: scientific throughout for log axes spanning four or more decades.
fn tick_formatter(scale: Scale, range: &Range<f64>) -> fn(&f64) -> String {
    if scale == Scale::Log10 && (range.end / range.start).log10() >= 4.0 { format_scientific } else { format_tick }
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
    let limit = MAX_LOG_PLOTTABLE.log10() + 2.0;
    10f64.powf(low.clamp(-limit, limit))..10f64.powf(high.clamp(-limit, limit))
}

/// Grid for `count` panels in rows of at most [`PANELS_PER_ROW`] (at least one cell); returns (columns, rows).
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
fn draw_message<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, message: &str) -> Result<(), PlotError> {
    let (width, height) = area.dim_in_pixel();
    let style = centered_text(22).color(&RGBColor(110, 110, 110));
    area.draw(&Text::new(message.to_string(), (width as i32 / 2, height as i32 / 2), style)).map_err(to_message)
}

fn draw_panel_title<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, title: &str) -> Result<(), PlotError> {
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

/// A circle positioned in pixel offsets from a composed element's anchor.
type PixelCircle = Circle<(i32, i32), i32>;

/// A 2 px ring; two 1 px circles, because plotters' bitmap backend leaves gaps in thick circle outlines.
fn within_bound_marker<C, DB: DrawingBackend>(at: C) -> ComposedElement<C, DB, PixelCircle, PixelCircle> {
    let ring = |radius| Circle::new((0, 0), radius, WITHIN_BOUND_COLOR.stroke_width(1));
    EmptyElement::at(at) + ring(WITHIN_CIRCLE_RADIUS) + ring(WITHIN_CIRCLE_RADIUS - 1)
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
const LEGEND_TEXT_GAP: u32 = 8;
const LEGEND_PADDING: u32 = 12;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum LegendSymbol {
    Truth,
    WithinBound,
    OutsideBound,
    Fov,
    CentralBody,
    /// Sky plots: truth tracks, one colour per object.
    TruthTracks,
    /// Sky plots: MAP estimate markers.
    MapEstimate,
}

impl LegendSymbol {
    fn label(self) -> &'static str {
        match self {
            Self::Truth => "Truth",
            Self::WithinBound => "Estimate within bound",
            Self::OutsideBound => "Estimate outside bound",
            Self::Fov => "Sensor FOV",
            Self::CentralBody => "Central body",
            Self::TruthTracks => "Truth (one colour per object)",
            Self::MapEstimate => "MAP estimate",
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

/// Flows legend entries into lines no wider than `width`.
fn layout_legend(symbols: &[LegendSymbol], width: u32) -> Result<Vec<Vec<PlacedLegendEntry>>, PlotError> {
    let font = (FONT, LEGEND_FONT_SIZE).into_font();
    let mut lines = Vec::new();
    let mut line: Vec<PlacedLegendEntry> = Vec::new();
    let mut x = LEGEND_PADDING;
    for &symbol in symbols {
        let (text_width, _) = font.box_size(symbol.label()).map_err(to_message)?;
        let entry_width = LEGEND_SYMBOL_WIDTH + LEGEND_TEXT_GAP + text_width;
        if !line.is_empty() && x + entry_width > width.saturating_sub(LEGEND_PADDING) {
            lines.push(std::mem::take(&mut line));
            x = LEGEND_PADDING;
        }
        line.push(PlacedLegendEntry { symbol, x });
        x += entry_width + LEGEND_ENTRY_GAP;
    }
    lines.push(line);
    Ok(lines)
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

fn draw_snapshot_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    lines: &[Vec<PlacedLegendEntry>],
) -> Result<(), PlotError> {
    let text_style = TextStyle::from((FONT, LEGEND_FONT_SIZE).into_font()).pos(Pos::new(HPos::Left, VPos::Center));
    for (row, line) in lines.iter().enumerate() {
        let y = (LEGEND_PADDING + row as u32 * LEGEND_LINE_HEIGHT + LEGEND_LINE_HEIGHT / 2) as i32;
        for entry in line {
            let x = entry.x as i32;
            draw_legend_symbol(area, entry.symbol, x, y).map_err(to_message)?;
            // +2 px: plotters' ab_glyph text sits a little high in PNGs (SVG is centred by the viewer).
            let text_x = x + (LEGEND_SYMBOL_WIDTH + LEGEND_TEXT_GAP) as i32;
            area.draw(&Text::new(entry.symbol.label(), (text_x, y + 2), text_style.clone())).map_err(to_message)?;
        }
    }
    Ok(())
}

/// Draws `symbol` in the legend slot starting at `x`, vertically centred on `y`.
fn draw_legend_symbol<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    symbol: LegendSymbol,
    x: i32,
    y: i32,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let width = LEGEND_SYMBOL_WIDTH as i32;
    let center = (x + width / 2, y);
    match symbol {
        LegendSymbol::Truth => area.draw(&truth_marker(center)),
        LegendSymbol::WithinBound => area.draw(&within_bound_marker(center)),
        LegendSymbol::OutsideBound => area.draw(&(EmptyElement::at(center) + star_marker())),
        LegendSymbol::Fov => area.draw(&PathElement::new(vec![(x, y), (x + width, y)], FOV_COLOR.stroke_width(2))),
        LegendSymbol::TruthTracks => {
            let third = width / 3;
            for (piece, color) in PALETTE.iter().take(3).enumerate() {
                let from = x + piece as i32 * third;
                area.draw(&PathElement::new(vec![(from, y), (from + third, y)], color.stroke_width(SKY_TRUTH_WIDTH)))?;
            }
            Ok(())
        }
        LegendSymbol::MapEstimate => area.draw(&estimate_marker((x + width / 2, y), ESTIMATE_COLOR)),
        LegendSymbol::CentralBody => {
            let swatch = [(x + 4, y - 9), (x + width - 4, y + 9)];
            area.draw(&Rectangle::new(swatch, BODY_FILL.filled()))?;
            area.draw(&Rectangle::new(swatch, BODY_EDGE.stroke_width(1)))
        }
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
    // Unclipped ends are returned exactly, so consecutive pieces of a polyline can be rejoined.
    let start = if t0 == 0.0 { a } else { (a.0 + t0 * dx, a.1 + t0 * dy) };
    let end = if t1 == 1.0 { b } else { (a.0 + t1 * dx, a.1 + t1 * dy) };
    Some((start, end))
}

/// The visible pieces of a polyline, each still a polyline (so joins stay smooth).
fn clip_polyline(points: &[(f64, f64)], x: &Range<f64>, y: &Range<f64>) -> Vec<Vec<(f64, f64)>> {
    clip_polyline_with(points, |a, b| clip_segment(a, b, x, y))
}

/// A line segment's two ends.
type Segment = ((f64, f64), (f64, f64));

/// The pieces of a polyline that `clip` keeps of each segment, rejoined where a kept segment starts exactly where the
/// previous one ended.
fn clip_polyline_with(
    points: &[(f64, f64)],
    clip: impl Fn((f64, f64), (f64, f64)) -> Option<Segment>,
) -> Vec<Vec<(f64, f64)>> {
    let mut pieces: Vec<Vec<(f64, f64)>> = Vec::new();
    for pair in points.windows(2) {
        let Some((start, end)) = clip(pair[0], pair[1]) else { continue };
        match pieces.last_mut() {
            Some(piece) if piece.last() == Some(&start) => piece.push(end),
            _ => pieces.push(vec![start, end]),
        }
    }
    pieces
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
fn format_rank_tick(value: &f64) -> String {
    if (value - value.round()).abs() < 1e-6 { format!("{}", value.round() as i64) } else { String::new() }
}

/// (rank, weight) bars: drawable weights in descending order, ranks from 1.
fn ranked_bars(weights: &[f64]) -> Vec<(f64, f64)> {
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

// ---------------------------------------------------------------------------------------------------------------
// Sky plots
// ---------------------------------------------------------------------------------------------------------------

const SKY_TRUTH_WIDTH: u32 = 2;
const ESTIMATE_COLOR: RGBColor = BLACK;
const ESTIMATE_CROSS_SIZE: i32 = 4;
const ISOLATED_TRUTH_RADIUS: i32 = 2;
const SKY_GRID_COLOR: RGBColor = RGBColor(200, 200, 200);
const SKY_TITLE_HEIGHT: u32 = 50;
const SKY_POLAR_SIDE: u32 = 900;
const SKY_RA_DEC_SIZE: (u32, u32) = (1100, 800);
const SKY_FOOTNOTE_HEIGHT: u32 = 28;
/// Outline vertices are joined by this many straight pieces, interpolated in angle (so an azimuth/elevation box
/// keeps its arcs).
const OUTLINE_STEPS_PER_EDGE: usize = 24;
/// Half width of the narrowest right ascension / declination view, degrees (36 arcsec).
const MIN_SKY_HALF_SPAN_DEG: f64 = 0.01;
/// Polar sky plot view: the horizon is radius 1; labels sit outside it.
const POLAR_VIEW_HALF_SIDE: f64 = 1.2;

/// A truth series' colour and its visible polyline pieces, in plot coordinates.
type TruthLines = (RGBColor, Vec<Vec<(f64, f64)>>);
/// An estimate series' colour and its marker positions, in plot coordinates.
type EstimateMarks = (RGBColor, Vec<(f64, f64)>);

/// One object's (truth) or one track's (estimate) path on the sky, for [`sky_plot_az_el`] and [`sky_plot_ra_dec`].
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SkySeries {
    /// Name used in error messages (sky plots do not list series in the legend).
    pub name: String,
    /// (azimuth, elevation) or (right ascension, declination) in radians, in time order. `None` breaks a truth line:
    /// put one wherever the samples are not consecutive (a gap in time, another pass). In an estimate series a `None`
    /// is simply no marker.
    pub points: Vec<Option<(f64, f64)>>,
    /// Index into the 10-colour palette (taken modulo 10). `None`: a truth series takes its position in the slice, an
    /// estimate series is black.
    pub color: Option<usize>,
}

/// A polar sky plot of one sensor: azimuth around the circle (North up, East right, azimuth clockwise from North),
/// elevation as radius (90° at the centre, the horizon at the rim), rings at 0/30/60° elevation.
///
/// Truth series are drawn as thin lines (cut where a `None` breaks them and at the horizon: samples below it are not
/// drawn), estimates as crosses; `field_of_view` is an optional outline of (azimuth, elevation) vertices in radians,
/// drawn closed, consecutive vertices joined along the shorter way round in azimuth. Estimate points below the
/// horizon are counted in a footnote instead of drawn. Writes `<stem>.png` and `<stem>.svg` (900 px wide).
///
/// Errors: a non-finite angle or an elevation outside [-π/2, π/2] in any series or the outline (the message names
/// the series and point), or a file that cannot be written.
pub fn sky_plot_az_el(
    stem: &Path,
    title: &str,
    truth: &[SkySeries],
    estimates: &[SkySeries],
    field_of_view: Option<&[(f64, f64)]>,
) -> Result<(), PlotError> {
    check_sky_input(stem, SkyAxes::AzEl, truth, estimates, field_of_view)?;
    ensure_font_registered()?;
    write_png_and_svg(stem, &PolarSkyFigure::new(title, truth, estimates, field_of_view)?)
}

/// A right ascension / declination plot of one sensor, in degrees, zoomed to the truth and estimates with a small
/// margin (at least ±0.01°, so a cluster within 0.1° fills the view).
///
/// Right ascension increases to the right and is unwrapped about the data's circular mean, so data straddling
/// 0°/360° (or ±180°) stay together; tick labels are brought back into [0, 360). Truth lines are cut at `None` and
/// where consecutive points lie more than 180° apart after unwrapping. `field_of_view` (vertices in radians, drawn
/// closed) is clipped to the view, and framed only when there are no points. Writes `<stem>.png` and `<stem>.svg`
/// (1100 px wide).
///
/// Errors: as [`sky_plot_az_el`], with declination in place of elevation.
pub fn sky_plot_ra_dec(
    stem: &Path,
    title: &str,
    truth: &[SkySeries],
    estimates: &[SkySeries],
    field_of_view: Option<&[(f64, f64)]>,
) -> Result<(), PlotError> {
    check_sky_input(stem, SkyAxes::RaDec, truth, estimates, field_of_view)?;
    ensure_font_registered()?;
    write_png_and_svg(stem, &RaDecFigure::new(title, truth, estimates, field_of_view)?)
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum SkyAxes {
    AzEl,
    RaDec,
    LonLat,
}

impl SkyAxes {
    fn names(self) -> (&'static str, &'static str) {
        match self {
            Self::AzEl => ("azimuth", "elevation"),
            Self::RaDec => ("right ascension", "declination"),
            Self::LonLat => ("longitude", "latitude"),
        }
    }
}

/// Every angle finite and every elevation / declination within [-π/2, π/2]; the error names the first bad point.
fn check_sky_input(
    stem: &Path,
    axes: SkyAxes,
    truth: &[SkySeries],
    estimates: &[SkySeries],
    field_of_view: Option<&[(f64, f64)]>,
) -> Result<(), PlotError> {
    let (first, second) = axes.names();
    let check = |what: &dyn Fn() -> String, index: usize, (a, b): (f64, f64)| {
        let problem = if !a.is_finite() || !b.is_finite() {
            format!("{first}/{second} ({a}, {b}) rad is not finite")
        } else if b.abs() > std::f64::consts::FRAC_PI_2 {
            format!("{second} {b} rad is outside [-pi/2, pi/2]")
        } else {
            return Ok(());
        };
        Err(PlotError(format!("plots: sky plot {}: {} point {index}: {problem}", stem.display(), what())))
    };
    for (kind, list) in [("truth", truth), ("estimate", estimates)] {
        for (series_index, series) in list.iter().enumerate() {
            let what = || {
                if series.name.is_empty() {
                    format!("{kind} series #{series_index}")
                } else {
                    format!("{kind} series \"{}\"", series.name)
                }
            };
            for (index, point) in series.points.iter().enumerate() {
                if let Some(point) = point {
                    check(&what, index, *point)?;
                }
            }
        }
    }
    for (index, &point) in field_of_view.unwrap_or(&[]).iter().enumerate() {
        check(&|| "field of view outline".to_string(), index, point)?;
    }
    Ok(())
}

fn truth_color(series: &SkySeries, index: usize) -> RGBColor {
    PALETTE[series.color.unwrap_or(index) % PALETTE.len()]
}

fn estimate_color(series: &SkySeries) -> RGBColor {
    series.color.map_or(ESTIMATE_COLOR, |index| PALETTE[index % PALETTE.len()])
}

fn estimate_marker<C>(at: C, color: RGBColor) -> Cross<C, i32> {
    Cross::new(at, ESTIMATE_CROSS_SIZE, color.stroke_width(2))
}

/// `angle` brought into [-π, π).
fn wrap_angle(angle: f64) -> f64 {
    (angle + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI
}

/// The closed outline with each edge split into [`OUTLINE_STEPS_PER_EDGE`] pieces, the first angle interpolated
/// along the shorter way round; the first angle is left unwrapped (callers project or unwrap it).
fn densified_outline(outline: &[(f64, f64)]) -> Vec<(f64, f64)> {
    if outline.len() < 2 {
        return outline.to_vec();
    }
    let mut points = Vec::with_capacity(outline.len() * OUTLINE_STEPS_PER_EDGE + 1);
    for (index, &(a0, b0)) in outline.iter().enumerate() {
        let (a1, b1) = outline[(index + 1) % outline.len()];
        let da = wrap_angle(a1 - a0);
        for step in 0..OUTLINE_STEPS_PER_EDGE {
            let t = step as f64 / OUTLINE_STEPS_PER_EDGE as f64;
            points.push((a0 + t * da, b0 + t * (b1 - b0)));
        }
    }
    points.push(points[0]);
    points
}

/// Splits a series at `None` into runs of consecutive points.
fn sky_runs(points: &[Option<(f64, f64)>]) -> Vec<Vec<(f64, f64)>> {
    points
        .split(Option::is_none)
        .map(|run| run.iter().flatten().copied().collect::<Vec<_>>())
        .filter(|run| !run.is_empty())
        .collect()
}

/// Draws truth polylines (isolated points as dots) and estimate crosses on a chart.
fn draw_sky_content<DB, X, Y>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<X, Y>>,
    truth: &[TruthLines],
    estimates: &[EstimateMarks],
    field_of_view: &[Vec<(f64, f64)>],
) -> Result<(), PlotError>
where
    DB: DrawingBackend,
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    chart
        .draw_series(field_of_view.iter().map(|piece| PathElement::new(piece.clone(), FOV_COLOR.stroke_width(2))))
        .map_err(to_message)?;
    for (color, pieces) in truth {
        let style = color.stroke_width(SKY_TRUTH_WIDTH);
        chart
            .draw_series(
                pieces.iter().filter(|piece| piece.len() > 1).map(|piece| PathElement::new(piece.clone(), style)),
            )
            .map_err(to_message)?;
        chart
            .draw_series(
                pieces
                    .iter()
                    .filter(|piece| piece.len() == 1)
                    .map(|piece| Circle::new(piece[0], ISOLATED_TRUTH_RADIUS, color.filled())),
            )
            .map_err(to_message)?;
    }
    for (color, points) in estimates {
        chart.draw_series(points.iter().map(|&point| estimate_marker(point, *color))).map_err(to_message)?;
    }
    Ok(())
}

/// Legend entries of a sky plot, and a footnote strip when there is one.
fn sky_legend(has_field_of_view: bool, width: u32) -> Result<Vec<Vec<PlacedLegendEntry>>, PlotError> {
    let mut symbols = vec![LegendSymbol::TruthTracks, LegendSymbol::MapEstimate];
    if has_field_of_view {
        symbols.push(LegendSymbol::Fov);
    }
    layout_legend(&symbols, width)
}

fn legend_height(lines: &[Vec<PlacedLegendEntry>]) -> u32 {
    lines.len() as u32 * LEGEND_LINE_HEIGHT + 2 * LEGEND_PADDING
}

fn draw_footnote<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, text: &str) -> Result<(), PlotError> {
    let (width, height) = area.dim_in_pixel();
    let style = centered_text(16).color(&RGBColor(90, 90, 90));
    area.draw(&Text::new(text.to_string(), (width as i32 / 2, height as i32 / 2), style)).map_err(to_message)
}

/// (x, y) of the polar sky projection: radius 1 - elevation / 90°, North up, East right.
fn polar_projection(azimuth: f64, elevation: f64) -> (f64, f64) {
    let radius = 1.0 - elevation / std::f64::consts::FRAC_PI_2;
    (radius * azimuth.sin(), radius * azimuth.cos())
}

fn inside_horizon((x, y): (f64, f64)) -> bool {
    x * x + y * y <= 1.0
}

/// The part of segment `a`-`b` inside the horizon circle (radius 1); None when both ends are below the horizon
/// (the projection of such a chord says nothing about the sky).
fn clip_to_horizon(a: (f64, f64), b: (f64, f64)) -> Option<Segment> {
    let (a_in, b_in) = (inside_horizon(a), inside_horizon(b));
    if a_in && b_in {
        return Some((a, b));
    }
    if !a_in && !b_in {
        return None;
    }
    // |a + t d|^2 = 1: t^2 (d.d) + 2 t (a.d) + (a.a - 1) = 0, one root in [0, 1] since one end is inside.
    let d = (b.0 - a.0, b.1 - a.1);
    let (qa, qb, qc) = (d.0 * d.0 + d.1 * d.1, a.0 * d.0 + a.1 * d.1, a.0 * a.0 + a.1 * a.1 - 1.0);
    let root = (qb * qb - qa * qc).max(0.0).sqrt();
    let t = if a_in { (-qb + root) / qa } else { (-qb - root) / qa }.clamp(0.0, 1.0);
    let crossing = (a.0 + t * d.0, a.1 + t * d.1);
    Some(if a_in { (a, crossing) } else { (crossing, b) })
}

struct PolarSkyFigure<'a> {
    title: &'a str,
    truth: Vec<TruthLines>,
    estimates: Vec<EstimateMarks>,
    field_of_view: Vec<Vec<(f64, f64)>>,
    estimates_below_horizon: usize,
    legend_lines: Vec<Vec<PlacedLegendEntry>>,
}

impl<'a> PolarSkyFigure<'a> {
    fn new(
        title: &'a str,
        truth: &[SkySeries],
        estimates: &[SkySeries],
        field_of_view: Option<&[(f64, f64)]>,
    ) -> Result<Self, PlotError> {
        let project_run = |run: &[(f64, f64)]| run.iter().map(|&(az, el)| polar_projection(az, el)).collect::<Vec<_>>();
        let visible = |run: Vec<(f64, f64)>| -> Vec<Vec<(f64, f64)>> {
            if run.len() == 1 {
                return if inside_horizon(run[0]) { vec![run] } else { Vec::new() };
            }
            clip_polyline_with(&run, clip_to_horizon)
        };
        let truth = truth
            .iter()
            .enumerate()
            .map(|(index, series)| {
                let pieces = sky_runs(&series.points).iter().flat_map(|run| visible(project_run(run))).collect();
                (truth_color(series, index), pieces)
            })
            .collect();
        let mut estimates_below_horizon = 0;
        let estimates = estimates
            .iter()
            .map(|series| {
                let projected = project_run(&series.points.iter().flatten().copied().collect::<Vec<_>>());
                let shown: Vec<_> = projected.into_iter().filter(|&point| inside_horizon(point)).collect();
                estimates_below_horizon += series.points.iter().flatten().count() - shown.len();
                (estimate_color(series), shown)
            })
            .collect();
        let field_of_view =
            field_of_view.map_or_else(Vec::new, |outline| visible(project_run(&densified_outline(outline))));
        let legend_lines = sky_legend(!field_of_view.is_empty(), SKY_POLAR_SIDE)?;
        Ok(Self { title, truth, estimates, field_of_view, estimates_below_horizon, legend_lines })
    }

    fn footnote(&self) -> Option<String> {
        (self.estimates_below_horizon > 0)
            .then(|| format!("{} MAP estimate point(s) below the horizon not shown", self.estimates_below_horizon))
    }
}

impl Figure for PolarSkyFigure<'_> {
    fn canvas_size(&self) -> (u32, u32) {
        let footnote = if self.footnote().is_some() { SKY_FOOTNOTE_HEIGHT } else { 0 };
        (SKY_POLAR_SIDE, SKY_TITLE_HEIGHT + SKY_POLAR_SIDE + legend_height(&self.legend_lines) + footnote)
    }

    fn draw_on<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError> {
        let (title_area, rest) = root.split_vertically(SKY_TITLE_HEIGHT);
        let (plot_area, rest) = rest.split_vertically(SKY_POLAR_SIDE);
        let (legend_area, footnote_area) = rest.split_vertically(legend_height(&self.legend_lines));
        title_area
            .draw(&Text::new(
                self.title.to_string(),
                (SKY_POLAR_SIDE as i32 / 2, SKY_TITLE_HEIGHT as i32 / 2 + 4),
                centered_text(26),
            ))
            .map_err(to_message)?;
        let view = -POLAR_VIEW_HALF_SIDE..POLAR_VIEW_HALF_SIDE;
        let mut chart = ChartBuilder::on(&plot_area)
            .margin(CHART_MARGIN)
            .build_cartesian_2d(view.clone(), view)
            .map_err(to_message)?;
        draw_polar_grid(&mut chart)?;
        draw_sky_content(&mut chart, &self.truth, &self.estimates, &self.field_of_view)?;
        draw_snapshot_legend(&legend_area, &self.legend_lines)?;
        if let Some(footnote) = self.footnote() {
            draw_footnote(&footnote_area, &footnote)?;
        }
        Ok(())
    }
}

/// Elevation rings at 0/30/60°, azimuth spokes every 30° with their labels, N/E/S/W.
fn draw_polar_grid<DB, X, Y>(chart: &mut ChartContext<'_, DB, Cartesian2d<X, Y>>) -> Result<(), PlotError>
where
    DB: DrawingBackend,
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    let degrees = |value: f64| value.to_radians();
    for elevation in [0.0, 30.0, 60.0] {
        let mut ring = circle_polygon(1.0 - elevation / 90.0);
        ring.push(ring[0]);
        let style = if elevation == 0.0 { BLACK.stroke_width(2) } else { SKY_GRID_COLOR.stroke_width(1) };
        chart.draw_series(std::iter::once(PathElement::new(ring, style))).map_err(to_message)?;
        let label_at = polar_projection(degrees(15.0), degrees(elevation + 2.5));
        chart
            .draw_series(std::iter::once(Text::new(
                format!("{elevation:.0}°"),
                label_at,
                centered_text(14).color(&RGBColor(110, 110, 110)),
            )))
            .map_err(to_message)?;
    }
    for step in 0..12 {
        let azimuth = degrees(f64::from(step) * 30.0);
        let spoke = vec![(0.0, 0.0), polar_projection(azimuth, 0.0)];
        chart
            .draw_series(std::iter::once(PathElement::new(spoke, SKY_GRID_COLOR.stroke_width(1))))
            .map_err(to_message)?;
        let (label, size, radius) = match step {
            0 => ("N".to_string(), 24, 1.1),
            3 => ("E".to_string(), 24, 1.1),
            6 => ("S".to_string(), 24, 1.1),
            9 => ("W".to_string(), 24, 1.1),
            _ => (format!("{}°", step * 30), 15, 1.09),
        };
        let at = (radius * azimuth.sin(), radius * azimuth.cos());
        chart.draw_series(std::iter::once(Text::new(label, at, centered_text(size)))).map_err(to_message)?;
    }
    chart
        .draw_series(std::iter::once(Text::new(
            "90°".to_string(),
            (0.0, -0.04),
            centered_text(14).color(&RGBColor(110, 110, 110)),
        )))
        .map_err(to_message)?;
    Ok(())
}

/// Right ascension (unwrapped, degrees) / declination (degrees) data and the view that frames it.
struct RaDecView {
    truth: Vec<TruthLines>,
    estimates: Vec<EstimateMarks>,
    field_of_view: Vec<Vec<(f64, f64)>>,
    x: Range<f64>,
    y: Range<f64>,
}

/// Circular mean of the right ascensions in [0, 2π) radians (so a cluster near ±180° is labelled around 180°); π when
/// they have no clear mean (none, or evenly spread).
fn circular_mean(angles: impl Iterator<Item = f64>) -> f64 {
    let (mut sin_sum, mut cos_sum, mut count) = (0.0, 0.0, 0usize);
    for angle in angles {
        sin_sum += angle.sin();
        cos_sum += angle.cos();
        count += 1;
    }
    let resultant = sin_sum.hypot(cos_sum);
    if count == 0 || resultant < 1e-9 * count as f64 {
        std::f64::consts::PI
    } else {
        sin_sum.atan2(cos_sum).rem_euclid(std::f64::consts::TAU)
    }
}

/// Axis around `data` with 8 % padding and at least ±[`MIN_SKY_HALF_SPAN_DEG`].
fn sky_axis(data: Option<Range<f64>>, fallback: Range<f64>) -> Range<f64> {
    let data = data.unwrap_or(fallback);
    let center = data.start / 2.0 + data.end / 2.0;
    let half = ((data.end - data.start) / 2.0 * 1.08).max(MIN_SKY_HALF_SPAN_DEG);
    center - half..center + half
}

impl RaDecView {
    fn new(truth: &[SkySeries], estimates: &[SkySeries], field_of_view: Option<&[(f64, f64)]>) -> Self {
        let all_points = || truth.iter().chain(estimates).flat_map(|series| series.points.iter().flatten());
        let outline = field_of_view.unwrap_or(&[]);
        let mean = if all_points().next().is_some() {
            circular_mean(all_points().map(|&(ra, _)| ra))
        } else {
            circular_mean(outline.iter().map(|&(ra, _)| ra))
        };
        let to_degrees = |(ra, dec): (f64, f64)| ((mean + wrap_angle(ra - mean)).to_degrees(), dec.to_degrees());
        // Cut where consecutive points cross the seam opposite the mean.
        let split_at_seam = |run: Vec<(f64, f64)>| -> Vec<Vec<(f64, f64)>> {
            let mut pieces: Vec<Vec<(f64, f64)>> = Vec::new();
            for point in run {
                match pieces.last_mut() {
                    Some(piece) if piece.last().is_some_and(|last: &(f64, f64)| (point.0 - last.0).abs() <= 180.0) => {
                        piece.push(point);
                    }
                    _ => pieces.push(vec![point]),
                }
            }
            pieces
        };
        let truth: Vec<_> = truth
            .iter()
            .enumerate()
            .map(|(index, series)| {
                let pieces = sky_runs(&series.points)
                    .into_iter()
                    .flat_map(|run| split_at_seam(run.into_iter().map(to_degrees).collect()))
                    .collect();
                (truth_color(series, index), pieces)
            })
            .collect();
        let estimates: Vec<_> = estimates
            .iter()
            .map(|series| (estimate_color(series), series.points.iter().flatten().map(|&p| to_degrees(p)).collect()))
            .collect();
        let outline: Vec<(f64, f64)> = densified_outline(outline).into_iter().map(to_degrees).collect();

        let mut bounds = None;
        let data_points = truth.iter().flat_map(|(_, pieces): &(_, Vec<Vec<_>>)| pieces.iter().flatten());
        for &(x, y) in data_points.chain(estimates.iter().flat_map(|(_, points): &(_, Vec<_>)| points)) {
            Bounds::include(&mut bounds, x, y);
        }
        if bounds.is_none() {
            for &(x, y) in &outline {
                Bounds::include(&mut bounds, x, y);
            }
        }
        let x = sky_axis(bounds.as_ref().map(|b| b.x.clone()), 0.0..360.0);
        let y = sky_axis(bounds.map(|b| b.y), -90.0..90.0);
        let field_of_view =
            split_at_seam(outline).iter().flat_map(|piece| clip_polyline(piece, &x, &y)).collect::<Vec<_>>();
        Self { truth, estimates, field_of_view, x, y }
    }
}

/// Right ascension tick: the unwrapped value brought back into [0, 360).
fn format_ra_tick(value: &f64) -> String {
    let wrapped = value.rem_euclid(360.0);
    // rem_euclid can round up to exactly 360 for tiny negative values.
    format_tick(&if wrapped >= 360.0 { 0.0 } else { wrapped })
}

struct RaDecFigure<'a> {
    title: &'a str,
    view: RaDecView,
    legend_lines: Vec<Vec<PlacedLegendEntry>>,
}

impl<'a> RaDecFigure<'a> {
    fn new(
        title: &'a str,
        truth: &[SkySeries],
        estimates: &[SkySeries],
        field_of_view: Option<&[(f64, f64)]>,
    ) -> Result<Self, PlotError> {
        let view = RaDecView::new(truth, estimates, field_of_view);
        let legend_lines = sky_legend(!view.field_of_view.is_empty(), SKY_RA_DEC_SIZE.0)?;
        Ok(Self { title, view, legend_lines })
    }
}

impl Figure for RaDecFigure<'_> {
    fn canvas_size(&self) -> (u32, u32) {
        (SKY_RA_DEC_SIZE.0, SKY_RA_DEC_SIZE.1 + legend_height(&self.legend_lines))
    }

    fn draw_on<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError> {
        let (chart_area, legend_area) = root.split_vertically(SKY_RA_DEC_SIZE.1);
        let view = &self.view;
        let mut chart = ChartBuilder::on(&chart_area)
            .caption(self.title, (FONT, 28))
            .margin(20)
            .x_label_area_size(60)
            .y_label_area_size(95)
            .build_cartesian_2d(view.x.clone(), view.y.clone())
            .map_err(to_message)?;
        chart
            .configure_mesh()
            .x_desc("Right ascension [deg]")
            .y_desc("Declination [deg]")
            .x_labels(8)
            .y_labels(8)
            .x_label_formatter(&format_ra_tick)
            .y_label_formatter(&format_tick)
            .label_style((FONT, 17))
            .axis_desc_style((FONT, 20))
            .light_line_style(BLACK.mix(0.04))
            .bold_line_style(BLACK.mix(0.14))
            .draw()
            .map_err(to_message)?;
        draw_sky_content(&mut chart, &view.truth, &view.estimates, &view.field_of_view)?;
        draw_snapshot_legend(&legend_area, &self.legend_lines)
    }
}

/// Ground-track plot size (equirectangular: 360° × 180° in a 2:1 plot area plus margins).
const GROUND_TRACK_SIZE: (u32, u32) = (1400, 800);

/// A ground-track plot: (longitude, latitude) in radians of truth series (lines) and estimates (crosses) on an
/// equirectangular map, longitude −180…180° to the right, latitude −90…90° up. Truth lines are cut at `None` and
/// where consecutive points are more than 180° apart in longitude (the antimeridian). Writes `<stem>.png` and
/// `<stem>.svg` (1400 px wide).
///
/// Errors: a non-finite angle or a latitude outside [-π/2, π/2] (the message names the series and point), or a
/// file that cannot be written.
pub fn ground_tracks(stem: &Path, title: &str, truth: &[SkySeries], estimates: &[SkySeries]) -> Result<(), PlotError> {
    check_sky_input(stem, SkyAxes::LonLat, truth, estimates, None)?;
    ensure_font_registered()?;
    write_png_and_svg(stem, &GroundTrackFigure::new(title, truth, estimates)?)
}

struct GroundTrackFigure<'a> {
    title: &'a str,
    truth: Vec<TruthLines>,
    estimates: Vec<EstimateMarks>,
    legend_lines: Vec<Vec<PlacedLegendEntry>>,
}

impl<'a> GroundTrackFigure<'a> {
    fn new(title: &'a str, truth: &[SkySeries], estimates: &[SkySeries]) -> Result<Self, PlotError> {
        let to_degrees = |(lon, lat): (f64, f64)| (wrap_angle(lon).to_degrees(), lat.to_degrees());
        let truth = truth
            .iter()
            .enumerate()
            .map(|(index, series)| {
                let mut pieces: Vec<Vec<(f64, f64)>> = Vec::new();
                for run in sky_runs(&series.points) {
                    let mut piece: Vec<(f64, f64)> = Vec::new();
                    for point in run.into_iter().map(to_degrees) {
                        if piece.last().is_some_and(|last| (point.0 - last.0).abs() > 180.0) {
                            pieces.push(std::mem::take(&mut piece));
                        }
                        piece.push(point);
                    }
                    pieces.push(piece);
                }
                (truth_color(series, index), pieces)
            })
            .collect();
        let estimates = estimates
            .iter()
            .map(|series| (estimate_color(series), series.points.iter().flatten().map(|&p| to_degrees(p)).collect()))
            .collect();
        let legend_lines = sky_legend(false, GROUND_TRACK_SIZE.0)?;
        Ok(Self { title, truth, estimates, legend_lines })
    }
}

impl Figure for GroundTrackFigure<'_> {
    fn canvas_size(&self) -> (u32, u32) {
        (GROUND_TRACK_SIZE.0, GROUND_TRACK_SIZE.1 + legend_height(&self.legend_lines))
    }

    fn draw_on<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError> {
        let (chart_area, legend_area) = root.split_vertically(GROUND_TRACK_SIZE.1);
        let mut chart = ChartBuilder::on(&chart_area)
            .caption(self.title, (FONT, 28))
            .margin(20)
            .x_label_area_size(60)
            .y_label_area_size(95)
            .build_cartesian_2d(-180.0..180.0, -90.0..90.0)
            .map_err(to_message)?;
        chart
            .configure_mesh()
            .x_desc("Longitude [deg]")
            .y_desc("Latitude (geocentric) [deg]")
            .x_labels(13)
            .y_labels(7)
            .x_label_formatter(&format_tick)
            .y_label_formatter(&format_tick)
            .label_style((FONT, 17))
            .axis_desc_style((FONT, 20))
            .light_line_style(BLACK.mix(0.04))
            .bold_line_style(BLACK.mix(0.14))
            .draw()
            .map_err(to_message)?;
        draw_sky_content(&mut chart, &self.truth, &self.estimates, &[])?;
        draw_snapshot_legend(&legend_area, &self.legend_lines)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const PNG_SIGNATURE: [u8; 8] = [0x89, b'P', b'N', b'G', b'\r', b'\n', 0x1a, b'\n'];

    /// A fresh directory under the system temp dir, removed when dropped.
    struct TestDir(PathBuf);

    impl TestDir {
        fn new(test_name: &str) -> Self {
            let path = std::env::temp_dir().join(format!("plots-test-{}-{test_name}", std::process::id()));
            let _ = std::fs::remove_dir_all(&path);
            std::fs::create_dir_all(&path).expect("create test dir");
            Self(path)
        }

        fn stem(&self, name: &str) -> PathBuf {
            self.0.join(name)
        }
    }

    impl Drop for TestDir {
        fn drop(&mut self) {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }

    /// Checks both files exist and look like a PNG and an SVG; returns the PNG's (width, height).
    fn assert_png_and_svg(stem: &Path) -> (u32, u32) {
        let png = std::fs::read(path_with_extension(stem, "png")).expect("png written");
        assert!(png.len() > 100, "png too small");
        assert_eq!(png[..8], PNG_SIGNATURE);
        let svg = std::fs::read_to_string(path_with_extension(stem, "svg")).expect("svg written");
        assert!(svg.contains("<svg"));
        let be_u32 = |at: usize| u32::from_be_bytes(png[at..at + 4].try_into().expect("4 bytes"));
        (be_u32(16), be_u32(20))
    }

    fn example_panel(title: &str) -> SnapshotPanel {
        let truth: Vec<[f64; 2]> =
            (0..5).map(|i| f64::from(i) * 0.6).map(|a| [42_164.0 * a.cos(), 42_164.0 * a.sin()]).collect();
        SnapshotPanel {
            title: title.to_string(),
            estimates_within_bound: truth.iter().take(3).map(|p| [p[0] + 300.0, p[1] - 200.0]).collect(),
            estimates_outside_bound: truth.iter().skip(3).map(|p| [p[0] + 5_000.0, p[1]]).collect(),
            truth,
            fov: Some(FovLines {
                origin: [6_378.137, 0.0],
                look_direction: 0.8,
                half_angle: 0.25,
                max_range: 60_000.0,
            }),
            unit: "km".to_string(),
            central_body_radius: Some(6_378.137),
        }
    }

    fn series(name: &str, points: Vec<(f64, f64)>, markers: bool) -> Series {
        Series { name: name.to_string(), points, markers }
    }

    #[test]
    fn snapshots_normal_data() {
        let dir = TestDir::new("snapshots-normal");
        let stem = dir.stem("snapshots");
        plot_snapshots(&stem, &[example_panel("k = 1"), example_panel("k = 2")]).unwrap();
        let (width, height) = assert_png_and_svg(&stem);
        assert_eq!(width, 2 * SNAPSHOT_PANEL_SIDE);
        assert!(height > SNAPSHOT_PANEL_SIDE, "legend strip below the panels");
    }

    #[test]
    fn snapshots_wrap_after_four_panels() {
        let dir = TestDir::new("snapshots-wrap");
        let stem = dir.stem("wrapped");
        let panels: Vec<_> = (0..5).map(|k| example_panel(&format!("k = {k}"))).collect();
        plot_snapshots(&stem, &panels).unwrap();
        let (width, height) = assert_png_and_svg(&stem);
        assert_eq!(width, 4 * SNAPSHOT_PANEL_SIDE);
        assert!(height > 2 * SNAPSHOT_PANEL_SIDE);
    }

    #[test]
    fn snapshots_empty_data() {
        let dir = TestDir::new("snapshots-empty");
        plot_snapshots(&dir.stem("no_panels"), &[]).unwrap();
        assert_png_and_svg(&dir.stem("no_panels"));
        plot_snapshots(&dir.stem("empty_panel"), &[SnapshotPanel::default()]).unwrap();
        assert_png_and_svg(&dir.stem("empty_panel"));
        let fov_only = SnapshotPanel { fov: example_panel("").fov, ..SnapshotPanel::default() };
        plot_snapshots(&dir.stem("fov_only"), &[fov_only]).unwrap();
        assert_png_and_svg(&dir.stem("fov_only"));
    }

    #[test]
    fn snapshots_single_point() {
        let dir = TestDir::new("snapshots-single");
        let at_origin = SnapshotPanel { truth: vec![[0.0, 0.0]], ..SnapshotPanel::default() };
        let far_away = SnapshotPanel { estimates_outside_bound: vec![[4.2e4, -1.0e3]], ..SnapshotPanel::default() };
        plot_snapshots(&dir.stem("single"), &[at_origin, far_away]).unwrap();
        assert_png_and_svg(&dir.stem("single"));
    }

    #[test]
    fn snapshots_skip_nan_and_inf() {
        let dir = TestDir::new("snapshots-nan");
        let mut panel = example_panel("with NaN");
        panel.truth.push([f64::NAN, 1.0]);
        panel.estimates_within_bound.push([f64::INFINITY, 0.0]);
        panel.estimates_outside_bound.push([1.0, f64::NEG_INFINITY]);
        let broken_fov = SnapshotPanel {
            truth: vec![[f64::NAN, f64::NAN]],
            fov: Some(FovLines { origin: [0.0, 0.0], look_direction: f64::NAN, half_angle: 0.1, max_range: 1.0 }),
            central_body_radius: Some(f64::NAN),
            ..SnapshotPanel::default()
        };
        plot_snapshots(&dir.stem("nan"), &[panel, broken_fov]).unwrap();
        assert_png_and_svg(&dir.stem("nan"));
    }

    #[test]
    fn weights_normal_data() {
        let dir = TestDir::new("weights-normal");
        let panels = vec![
            ("k = 1".to_string(), vec![0.7, 0.2, 0.1]),
            ("k = 2".to_string(), (1..=40).map(|i| 0.5_f64.powi(i)).collect()),
        ];
        plot_hypothesis_weights(&dir.stem("weights"), &panels).unwrap();
        let (width, _) = assert_png_and_svg(&dir.stem("weights"));
        assert_eq!(width, 2 * WEIGHT_PANEL_SIZE.0);
    }

    #[test]
    fn weights_are_ranked_in_descending_order() {
        let bars = ranked_bars(&[0.1, f64::NAN, 0.6, 0.3, f64::INFINITY]);
        assert_eq!(bars, vec![(1.0, 0.6), (2.0, 0.3), (3.0, 0.1)]);
        assert!(ranked_bars(&[]).is_empty());
    }

    #[test]
    fn weights_empty_single_and_nan() {
        let dir = TestDir::new("weights-edge");
        plot_hypothesis_weights(&dir.stem("no_panels"), &[]).unwrap();
        assert_png_and_svg(&dir.stem("no_panels"));
        plot_hypothesis_weights(&dir.stem("no_weights"), &[("empty".to_string(), vec![])]).unwrap();
        assert_png_and_svg(&dir.stem("no_weights"));
        plot_hypothesis_weights(&dir.stem("single"), &[("one".to_string(), vec![1.0])]).unwrap();
        assert_png_and_svg(&dir.stem("single"));
        let odd = vec![f64::NAN, 0.5, f64::INFINITY, 1.7, -0.2];
        plot_hypothesis_weights(&dir.stem("nan"), &[("odd".to_string(), odd), ("all NaN".to_string(), vec![f64::NAN])])
            .unwrap();
        assert_png_and_svg(&dir.stem("nan"));
    }

    #[test]
    fn series_normal_data() {
        let dir = TestDir::new("series-normal");
        let truth = series("Truth", (0..50).map(|k| (f64::from(k), if k < 20 { 3.0 } else { 5.0 })).collect(), false);
        let estimate = series("Estimate", (0..50).map(|k| (f64::from(k), 3.0 + f64::from(k) / 25.0)).collect(), true);
        plot_series(
            &dir.stem("series"),
            "Objects",
            "Time [s]",
            "Count",
            Scale::Linear,
            Scale::Linear,
            &[truth, estimate],
        )
        .unwrap();
        assert_eq!(assert_png_and_svg(&dir.stem("series")), LINE_CHART_SIZE);
    }

    #[test]
    fn series_empty_data() {
        let dir = TestDir::new("series-empty");
        for (x_scale, y_scale) in [(Scale::Linear, Scale::Linear), (Scale::Log10, Scale::Log10)] {
            let stem = dir.stem(&format!("empty_{x_scale:?}_{y_scale:?}"));
            plot_series(&stem, "No series", "x", "y", x_scale, y_scale, &[]).unwrap();
            assert_png_and_svg(&stem);
            let stem = dir.stem(&format!("empty_points_{x_scale:?}_{y_scale:?}"));
            plot_series(&stem, "Empty series", "x", "y", x_scale, y_scale, &[series("nothing", vec![], true)]).unwrap();
            assert_png_and_svg(&stem);
        }
    }

    #[test]
    fn series_single_point() {
        let dir = TestDir::new("series-single");
        for (x_scale, y_scale) in [(Scale::Linear, Scale::Linear), (Scale::Log10, Scale::Log10)] {
            let stem = dir.stem(&format!("single_{x_scale:?}"));
            plot_series(&stem, "One point", "x", "y", x_scale, y_scale, &[series("one", vec![(5.0, 5.0)], false)])
                .unwrap();
            assert_png_and_svg(&stem);
        }
        let stem = dir.stem("constant");
        let flat = series("flat", vec![(1.0, 0.0), (2.0, 0.0), (3.0, 0.0)], false);
        plot_series(&stem, "Flat zero", "x", "y", Scale::Linear, Scale::Linear, &[flat]).unwrap();
        assert_png_and_svg(&stem);
    }

    #[test]
    fn series_skip_nan_inf_and_non_positive_on_log_axes() {
        let dir = TestDir::new("series-nan");
        let points = vec![(0.0, 1.0), (1.0, f64::NAN), (2.0, 3.0), (f64::INFINITY, 4.0), (4.0, -5.0), (5.0, 6.0)];
        let noisy = series("noisy", points, true);
        let all_nan = series("all NaN", vec![(f64::NAN, f64::NAN); 3], false);
        for (x_scale, y_scale) in [(Scale::Linear, Scale::Linear), (Scale::Log10, Scale::Log10)] {
            let stem = dir.stem(&format!("nan_{x_scale:?}"));
            plot_series(&stem, "NaN", "x", "y", x_scale, y_scale, &[noisy.clone(), all_nan.clone()]).unwrap();
            assert_png_and_svg(&stem);
        }
        let only_non_positive = series("negative", vec![(-1.0, -1.0), (0.0, 0.0)], false);
        let stem = dir.stem("non_positive_log");
        plot_series(&stem, "Nothing positive", "x", "y", Scale::Log10, Scale::Log10, &[only_non_positive]).unwrap();
        assert_png_and_svg(&stem);
    }

    #[test]
    fn series_log_scales_with_wide_range() {
        let dir = TestDir::new("series-log");
        let children: Vec<f64> = (1..=33).map(|e| 10_f64.powi(e)).collect();
        let timing = series("time", children.iter().map(|&n| (n, 1e-6 * n.powf(0.05))).collect(), true);
        let linear = series("linear", children.iter().map(|&n| (n, 1e-9 * n)).collect(), false);
        let stem = dir.stem("loglog");
        plot_series(&stem, "Timing", "Possible children", "Time [s]", Scale::Log10, Scale::Log10, &[timing, linear])
            .unwrap();
        assert_png_and_svg(&stem);
        let stem = dir.stem("semilog");
        let decay = series("decay", (0..20).map(|k| (f64::from(k), 10_f64.powi(-k))).collect(), false);
        plot_series(&stem, "Semi-log", "k", "value", Scale::Linear, Scale::Log10, &[decay]).unwrap();
        assert_png_and_svg(&stem);
    }

    #[test]
    fn series_extreme_magnitudes_do_not_hang_or_panic() {
        let dir = TestDir::new("series-extreme");
        let extreme = series("extreme", vec![(-1e300, 1e-300), (1e300, 1e300), (f64::MAX, f64::MIN_POSITIVE)], false);
        let near = series("near", vec![(1e9, 1.0), (1e9 + 1e-7, 1.0 + 1e-12)], false);
        let log_limits = series("log limits", vec![(1e-150, 1e150), (1e150, 1e-150), (1e-300, 1e300)], true);
        for (x_scale, y_scale) in
            [(Scale::Linear, Scale::Linear), (Scale::Linear, Scale::Log10), (Scale::Log10, Scale::Log10)]
        {
            let stem = dir.stem(&format!("extreme_{x_scale:?}_{y_scale:?}"));
            plot_series(
                &stem,
                "Extreme",
                "x",
                "y",
                x_scale,
                y_scale,
                &[extreme.clone(), near.clone(), log_limits.clone()],
            )
            .unwrap();
            assert_png_and_svg(&stem);
        }
    }

    #[test]
    fn unwritable_destination_is_an_error() {
        let dir = TestDir::new("unwritable");
        let blocker = dir.stem("blocker");
        std::fs::write(&blocker, b"a file, not a directory").unwrap();
        let error = plot_series(&blocker.join("chart"), "t", "x", "y", Scale::Linear, Scale::Linear, &[]).unwrap_err();
        assert!(error.0.contains("blocker"), "message names the path: {error}");
        assert!(plot_hypothesis_weights(Path::new(""), &[]).is_err());
    }

    #[test]
    fn absurd_panel_counts_are_refused() {
        let dir = TestDir::new("too-many");
        let panels = vec![SnapshotPanel::default(); 400];
        let error = plot_snapshots(&dir.stem("huge"), &panels).unwrap_err();
        assert!(error.0.contains("px"), "{error}");
    }

    #[test]
    fn output_paths_append_extensions() {
        assert_eq!(path_with_extension(Path::new("out/run.v2/gospa"), "png"), PathBuf::from("out/run.v2/gospa.png"));
        assert_eq!(path_with_extension(Path::new("fig.final"), "svg"), PathBuf::from("fig.final.svg"));
    }

    #[test]
    fn tick_labels_are_short() {
        assert_eq!(format_tick(&0.0), "0");
        assert_eq!(format_tick(&0.30000000000000004), "0.3");
        assert_eq!(format_tick(&-20_000.0), "-20000");
        assert_eq!(format_tick(&1.0000000000000001e7), "1e7");
        assert_eq!(format_tick(&2.5e-4), "2.5e-4");
        assert_eq!(format_scientific(&1000.0), "1e3");
        assert_eq!(format_rank_tick(&3.0), "3");
        assert_eq!(format_rank_tick(&2.5), "");
    }

    #[test]
    fn axes_are_widened_and_padded() {
        let single = linear_axis(Some(5.0..5.0));
        assert!(single.start < 5.0 && single.end > 5.0);
        let zero = linear_axis(Some(0.0..0.0));
        assert!(zero.start < 0.0 && zero.end > 0.0);
        let padded = linear_axis(Some(0.0..10.0));
        assert!(padded.start < 0.0 && padded.end > 10.0);
        assert_eq!(linear_axis(None), 0.0..1.0);

        // Log axes always contain a power of ten.
        for data in [2.0..8.0, 3.0..3.0, 1e1..1e33, 0.02..0.03] {
            let axis = log_axis(Some(data.clone()));
            assert!(axis.start < data.start && axis.end > data.end, "{axis:?} frames {data:?}");
            assert!(axis.end.log10().floor() >= axis.start.log10().ceil(), "{axis:?} holds a power of ten");
        }
    }

    #[test]
    fn snapshot_axes_have_equal_units_per_pixel() {
        let bounds = Bounds { x: -10.0..30.0, y: 0.0..5.0 };
        let (x, y) = equal_aspect_ranges(Some(bounds), (500, 400));
        let (x_per_pixel, y_per_pixel) = ((x.end - x.start) / 500.0, (y.end - y.start) / 400.0);
        assert!((x_per_pixel - y_per_pixel).abs() < 1e-12 * x_per_pixel);
        assert!(x.start < -10.0 && x.end > 30.0 && y.start < 0.0 && y.end > 5.0);
        let (x, y) = equal_aspect_ranges(Some(Bounds::around(7.0, 7.0)), (500, 500));
        assert!(x.start < 7.0 && x.end > 7.0 && y.start < 7.0 && y.end > 7.0);
    }

    #[test]
    fn segments_and_polylines_are_clipped_to_the_view() {
        let (x, y) = (0.0..10.0, 0.0..10.0);
        assert_eq!(clip_segment((-5.0, 5.0), (15.0, 5.0), &x, &y), Some(((0.0, 5.0), (10.0, 5.0))));
        assert_eq!(clip_segment((1.0, 1.0), (2.0, 2.0), &x, &y), Some(((1.0, 1.0), (2.0, 2.0))));
        assert_eq!(clip_segment((-5.0, -5.0), (-1.0, 20.0), &x, &y), None);
        let pieces =
            clip_polyline(&[(-1.0, 5.0), (2.0, 5.0), (4.0, 6.0), (20.0, 6.0), (20.0, 8.0), (5.0, 8.0)], &x, &y);
        assert_eq!(pieces, vec![vec![(0.0, 5.0), (2.0, 5.0), (4.0, 6.0), (10.0, 6.0)], vec![(10.0, 8.0), (5.0, 8.0)]]);
    }

    /// A LEO pass from NNE over a near-zenith point (88°) to SSW, its azimuth wrapping through ±π, with a gap.
    fn leo_pass() -> SkySeries {
        let points = (0..=120)
            .map(|k| {
                let t = f64::from(k) / 120.0;
                let azimuth = wrap_angle(0.1 - t * (std::f64::consts::PI + 0.2));
                let elevation = 88_f64.to_radians() * (std::f64::consts::PI * t).sin();
                (!(40..45).contains(&k)).then_some((azimuth, elevation))
            })
            .collect();
        SkySeries { name: "leo 1".to_string(), points, color: None }
    }

    /// Every fifth point of `truth`, offset by `offset` radians in both angles.
    fn estimates_of(truth: &SkySeries, offset: f64) -> SkySeries {
        let points = truth.points.iter().step_by(5).map(|p| p.map(|(a, b)| (a + offset, b - offset.abs()))).collect();
        SkySeries { name: format!("track of {}", truth.name), points, color: None }
    }

    /// Five GEO objects within 0.1° around RA = 180°, right ascensions given on both sides of ±180°.
    fn geo_cluster() -> Vec<SkySeries> {
        (0..5)
            .map(|object| {
                let points = (0..60)
                    .map(|k| {
                        let ra = (179.96 + 0.02 * f64::from(object) + 0.0005 * f64::from(k)).to_radians();
                        let ra = if object % 2 == 0 { wrap_angle(ra) } else { ra };
                        Some((ra, (-5.0 + 0.01 * f64::from(object)).to_radians()))
                    })
                    .collect();
                SkySeries { name: format!("geo {object}"), points, color: None }
            })
            .collect()
    }

    #[test]
    fn polar_projection_puts_north_up_and_east_right() {
        let close = |a: (f64, f64), b: (f64, f64)| (a.0 - b.0).abs() < 1e-12 && (a.1 - b.1).abs() < 1e-12;
        assert!(close(polar_projection(0.0, 0.0), (0.0, 1.0)), "north on the rim, up");
        assert!(close(polar_projection(std::f64::consts::FRAC_PI_2, 0.0), (1.0, 0.0)), "east right");
        assert!(close(polar_projection(1.0, std::f64::consts::FRAC_PI_2), (0.0, 0.0)), "zenith at the centre");
        assert!(close(polar_projection(std::f64::consts::PI, std::f64::consts::FRAC_PI_6), (0.0, -2.0 / 3.0)));
        // Consecutive samples either side of azimuth ±π stay neighbours in the projection.
        let near_south = std::f64::consts::PI - 0.001;
        let (a, b) = (polar_projection(near_south, 0.2), polar_projection(-near_south, 0.2));
        assert!((a.0 - b.0).hypot(a.1 - b.1) < 0.01);
    }

    #[test]
    fn lines_are_cut_at_the_horizon() {
        let (inside, outside) = ((0.0, 0.5), (0.0, 1.5));
        let (start, end) = clip_to_horizon(inside, outside).unwrap();
        assert_eq!(start, inside);
        assert!((end.1 - 1.0).abs() < 1e-12 && end.0.abs() < 1e-12);
        let (start, _) = clip_to_horizon(outside, inside).unwrap();
        assert!((start.1 - 1.0).abs() < 1e-12);
        // A chord between two points below the horizon is not drawn, even through the sky.
        assert_eq!(clip_to_horizon((0.0, 1.2), (0.0, -1.2)), None);
    }

    #[test]
    fn sky_az_el_leo_pass_through_zenith() {
        let dir = TestDir::new("sky-az-el");
        let truth = vec![leo_pass(), SkySeries { color: Some(3), ..estimates_of(&leo_pass(), 0.3) }];
        let estimates = vec![estimates_of(&truth[0], 0.01), estimates_of(&truth[0], -0.2)];
        let box_outline = [(-0.6, 0.2), (0.6, 0.2), (0.6, 1.2), (-0.6, 1.2)];
        let stem = dir.stem("az_el");
        sky_plot_az_el(&stem, "Radar 1: azimuth/elevation", &truth, &estimates, Some(&box_outline)).unwrap();
        let (width, height) = assert_png_and_svg(&stem);
        assert_eq!(width, SKY_POLAR_SIDE);
        assert!(height > SKY_POLAR_SIDE);

        // The estimates 0.2 rad below the truth put some points under the horizon: counted, not drawn.
        let figure = PolarSkyFigure::new("t", &truth, &estimates, Some(&box_outline)).unwrap();
        assert!(figure.estimates_below_horizon > 0 && figure.footnote().is_some());
        // The gap and the cut at the horizon split the first truth series; no piece leaves the horizon circle.
        assert!(figure.truth[0].1.len() >= 2);
        for &(x, y) in figure.truth.iter().flat_map(|(_, pieces)| pieces.iter().flatten()) {
            assert!(x.hypot(y) <= 1.0 + 1e-12);
        }

        sky_plot_az_el(&dir.stem("empty"), "Nothing", &[], &[], None).unwrap();
        assert_png_and_svg(&dir.stem("empty"));
    }

    #[test]
    fn sky_ra_dec_geo_cluster_near_180_zooms_in() {
        let dir = TestDir::new("sky-ra-dec");
        let truth = geo_cluster();
        let estimates: Vec<_> = truth.iter().map(|series| estimates_of(series, 1e-5)).collect();
        let stare = [(178.0_f64, -6.0_f64), (-178.0, -6.0), (-178.0, -4.0), (178.0, -4.0)]
            .map(|(ra, dec)| (ra.to_radians(), dec.to_radians()));
        let stem = dir.stem("ra_dec");
        sky_plot_ra_dec(&stem, "Telescope: RA/Dec", &truth, &estimates, Some(&stare)).unwrap();
        assert_png_and_svg(&stem);

        // The view spans the cluster (0.11° wide in RA) across ±180°, not the whole circle.
        let view = RaDecView::new(&truth, &estimates, Some(&stare));
        assert!(view.x.start < 179.96 && view.x.end > 180.07 && view.x.end - view.x.start < 0.3, "{:?}", view.x);
        assert!(view.y.start < -5.0 && view.y.end > -4.96 && view.y.end - view.y.start < 0.2, "{:?}", view.y);
        assert!(view.truth.iter().all(|(_, pieces)| pieces.len() == 1), "no line cut at ±180°");
        assert!(view.field_of_view.is_empty(), "the 4° field of view lies outside the zoomed view");

        // With no points the view frames the field of view, which straddles RA = 180° too.
        let empty = RaDecView::new(&[], &[], Some(&stare));
        assert!(empty.x.start < 178.0 && empty.x.end > 182.0 && empty.x.end - empty.x.start < 5.0, "{:?}", empty.x);
        assert_eq!(empty.field_of_view.len(), 1, "the whole closed outline, uncut at ±180°");
        sky_plot_ra_dec(&dir.stem("empty"), "Nothing", &[], &[], None).unwrap();
        assert_png_and_svg(&dir.stem("empty"));
    }

    #[test]
    fn sky_ra_dec_wraps_at_zero_and_cuts_at_the_seam() {
        let near_zero = SkySeries {
            name: "near 0".to_string(),
            points: [359.9_f64, 359.95, 0.0, 0.05].iter().map(|ra| Some((ra.to_radians(), 0.0))).collect(),
            color: None,
        };
        let view = RaDecView::new(&[near_zero], &[], None);
        assert!(view.x.end - view.x.start < 1.0, "{:?}", view.x);
        assert_eq!(view.truth[0].1.len(), 1);
        assert_eq!(format_ra_tick(&360.02), "0.02");
        assert_eq!(format_ra_tick(&-0.5), "359.5");

        // A circumpolar path covers all right ascensions: the line is cut where it crosses the seam.
        let around = SkySeries {
            name: "around the pole".to_string(),
            points: (0..=36).map(|k| Some((f64::from(k * 10).to_radians(), 89_f64.to_radians()))).collect(),
            color: None,
        };
        let view = RaDecView::new(&[around], &[], None);
        assert!(view.truth[0].1.len() >= 2);
        for piece in &view.truth[0].1 {
            assert!(piece.windows(2).all(|pair| (pair[1].0 - pair[0].0).abs() <= 180.0));
        }
    }

    #[test]
    fn sky_plots_refuse_bad_angles_and_unwritable_paths() {
        let dir = TestDir::new("sky-errors");
        let mut bad = leo_pass();
        bad.name = "leo 7".to_string();
        bad.points[3] = Some((f64::NAN, 0.3));
        for ra_dec in [false, true] {
            let plot = if ra_dec { sky_plot_ra_dec } else { sky_plot_az_el };
            let stem = dir.stem(&format!("bad_{ra_dec}"));
            let error = plot(&stem, "t", &[leo_pass()], std::slice::from_ref(&bad), None).unwrap_err();
            assert!(error.0.contains("estimate series \"leo 7\" point 3"), "{error}");
            assert!(!path_with_extension(&stem, "png").exists(), "nothing written on bad input");

            let too_high = SkySeries { points: vec![Some((0.0, 1.6))], ..SkySeries::default() };
            let error = plot(&stem, "t", &[too_high], &[], None).unwrap_err();
            assert!(error.0.contains("truth series #0 point 0") && error.0.contains("outside"), "{error}");

            let error = plot(&stem, "t", &[], &[], Some(&[(0.0, 0.1), (f64::INFINITY, 0.2)])).unwrap_err();
            assert!(error.0.contains("field of view outline point 1"), "{error}");

            let blocker = dir.stem(&format!("blocker_{ra_dec}"));
            std::fs::write(&blocker, b"a file, not a directory").unwrap();
            let error = plot(&blocker.join("sky"), "t", &[leo_pass()], &[], None).unwrap_err();
            assert!(error.0.contains("blocker"), "message names the path: {error}");
        }
    }

    #[test]
    fn ground_tracks_cut_at_the_antimeridian_and_refuse_bad_latitudes() {
        let dir = TestDir::new("ground-tracks");
        // An inclined orbit's track over 1.5 revolutions: longitude drifting west, crossing ±180°.
        let track = SkySeries {
            name: "leo".to_string(),
            points: (0..=135)
                .map(|k| {
                    let u = f64::from(k) * 4_f64.to_radians();
                    Some((u - 0.02 * f64::from(k), (53_f64.to_radians().sin() * u.sin()).asin()))
                })
                .collect(),
            color: None,
        };
        ensure_font_registered().unwrap();
        let figure = GroundTrackFigure::new("t", std::slice::from_ref(&track), &[]).unwrap();
        assert!(figure.truth[0].1.len() >= 2, "cut at the antimeridian");
        for piece in &figure.truth[0].1 {
            assert!(piece.windows(2).all(|pair| (pair[1].0 - pair[0].0).abs() <= 180.0));
            assert!(piece.iter().all(|p| (-180.0..180.0).contains(&p.0) && p.1.abs() <= 53.0 + 1e-9));
        }
        let stem = dir.stem("ground");
        let estimates = [SkySeries { name: "map".into(), points: vec![Some((0.1, 0.2))], color: None }];
        ground_tracks(&stem, "ground tracks", &[track], &estimates).unwrap();
        assert_png_and_svg(&stem);
        let too_high = SkySeries { points: vec![Some((0.0, 1.6))], ..SkySeries::default() };
        let error = ground_tracks(&dir.stem("bad"), "t", &[too_high], &[]).unwrap_err();
        assert!(error.0.contains("latitude") && error.0.contains("outside"), "{error}");
    }
}
