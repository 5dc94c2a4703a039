//! What every figure shares: the font, the palette, writing PNG and SVG, plottable values, axes and ticks, panel grids.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::{FontStyle, register_font};
use std::fmt::Display;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// A figure that could not be drawn or written: a one-line message naming the file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PlotError(pub String);

impl std::fmt::Display for PlotError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for PlotError {}

impl From<crate::Error> for PlotError {
    fn from(e: crate::Error) -> Self {
        PlotError(e.to_string())
    }
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

pub(crate) const FONT: &str = "sans-serif";

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
pub(crate) const PALETTE: [RGBColor; 10] = [
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
pub(crate) fn ensure_font_registered() -> Result<(), PlotError> {
    static REGISTERED: OnceLock<Result<(), PlotError>> = OnceLock::new();
    REGISTERED
        .get_or_init(|| {
            register_font(FONT, FontStyle::Normal, FONT_BYTES)
                .map_err(|_| PlotError("plots: the vendored DejaVuSans.ttf is not a valid font".to_string()))
        })
        .clone()
}

/// A figure that can be drawn on any plotters backend.
pub(crate) trait Figure {
    /// Canvas size in pixels (width, height).
    fn canvas_size(&self) -> (u32, u32);
    /// Draws onto a white canvas.
    fn draw_on<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), PlotError>;
}

pub(crate) fn to_message(error: impl Display) -> PlotError {
    PlotError(error.to_string())
}

/// `stem` + "." + `extension` (appended, so dots inside the stem survive).
pub(crate) fn path_with_extension(stem: &Path, extension: &str) -> PathBuf {
    let mut path = stem.as_os_str().to_owned();
    path.push(".");
    path.push(extension);
    PathBuf::from(path)
}

/// Renders `figure` to `<stem>.png` and `<stem>.svg`, creating the parent directory if needed.
pub(crate) fn write_png_and_svg(stem: &Path, figure: &impl Figure) -> Result<(), PlotError> {
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

    // Both through crate::io::atomic: rendered beside the target, renamed only onto a regular file.
    let png_path = path_with_extension(stem, "png");
    let failed = |path: &Path, e: PlotError| PlotError(format!("plots: writing {} failed: {e}", path.display()));
    crate::io::atomic::write_via_path(&png_path, |temp| {
        render(BitMapBackend::new(temp, size).into_drawing_area(), figure).map_err(|e| failed(&png_path, e))
    })?;
    let svg_path = path_with_extension(stem, "svg");
    let mut svg = String::new();
    render(SVGBackend::with_string(&mut svg, size).into_drawing_area(), figure).map_err(|e| failed(&svg_path, e))?;
    Ok(crate::io::atomic::write(&svg_path, svg)?)
}

fn render<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, figure: &impl Figure) -> Result<(), PlotError> {
    root.fill(&WHITE).map_err(to_message)?;
    figure.draw_on(&root)?;
    root.present().map_err(to_message)
}

pub(crate) fn is_plottable(value: f64) -> bool {
    value.is_finite() && value.abs() <= MAX_PLOTTABLE
}

pub(crate) fn is_plottable_on(scale: Scale, value: f64) -> bool {
    match scale {
        Scale::Linear => is_plottable(value),
        Scale::Log10 => (1.0 / MAX_LOG_PLOTTABLE..=MAX_LOG_PLOTTABLE).contains(&value),
    }
}

/// Axis-aligned bounding box of the data that must be visible.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Bounds {
    pub(super) x: Range<f64>,
    pub(super) y: Range<f64>,
}

impl Bounds {
    pub(super) fn around(x: f64, y: f64) -> Self {
        Self { x: x..x, y: y..y }
    }

    pub(super) fn include(bounds: &mut Option<Bounds>, x: f64, y: f64) {
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
pub(crate) fn format_tick(value: &f64) -> String {
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
pub(crate) fn format_scientific(value: &f64) -> String {
    let text = format!("{value:.4e}");
    let (mantissa, exponent) = text.split_once('e').unwrap_or((&text, "0"));
    format!("{}e{exponent}", trim_decimal_zeros(mantissa))
}

/// Tick formatter for an axis: scientific throughout for log axes spanning four or more decades.
pub(crate) fn tick_formatter(scale: Scale, range: &Range<f64>) -> fn(&f64) -> String {
    if scale == Scale::Log10 && (range.end / range.start).log10() >= 4.0 { format_scientific } else { format_tick }
}

fn trim_decimal_zeros(text: &str) -> &str {
    if text.contains('.') { text.trim_end_matches('0').trim_end_matches('.') } else { text }
}

/// Linear axis covering `data` with 5 % padding; empty or degenerate spans are widened.
pub(crate) fn linear_axis(data: Option<Range<f64>>) -> Range<f64> {
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
pub(crate) fn log_axis(data: Option<Range<f64>>) -> Range<f64> {
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
pub(crate) fn panel_grid(count: usize) -> (usize, usize) {
    let columns = count.clamp(1, PANELS_PER_ROW);
    (columns, count.max(1).div_ceil(columns))
}

pub(crate) fn canvas_side(panels: usize, panel_side: u32) -> u32 {
    u32::try_from(panels).ok().and_then(|n| n.checked_mul(panel_side)).unwrap_or(u32::MAX)
}

pub(crate) fn centered_text(size: u32) -> TextStyle<'static> {
    TextStyle::from((FONT, size).into_font()).pos(Pos::new(HPos::Center, VPos::Center))
}

/// Writes a centred grey message, used when there is nothing to plot.
pub(crate) fn draw_message<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, message: &str) -> Result<(), PlotError> {
    let (width, height) = area.dim_in_pixel();
    let style = centered_text(22).color(&RGBColor(110, 110, 110));
    area.draw(&Text::new(message.to_string(), (width as i32 / 2, height as i32 / 2), style)).map_err(to_message)
}

pub(crate) fn draw_panel_title<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    title: &str,
) -> Result<(), PlotError> {
    let (width, height) = area.dim_in_pixel();
    area.draw(&Text::new(title.to_string(), (width as i32 / 2, height as i32 / 2), centered_text(22)))
        .map_err(to_message)
}

/// Splits `root` into a grid and returns the first `count` cells in reading order.
pub(crate) fn panel_areas<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    count: usize,
) -> Vec<DrawingArea<DB, Shift>> {
    let (columns, rows) = panel_grid(count);
    root.split_evenly((rows, columns)).into_iter().take(count).collect()
}

pub(crate) const CHART_MARGIN: u32 = 14;
