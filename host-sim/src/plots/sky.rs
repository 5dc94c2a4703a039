//! Sky plots of one sensor: truth tracks, estimates and the field of view in azimuth/elevation (polar) or right ascension/declination.

use super::clip::{Segment, circle_polygon, clip_polyline, clip_polyline_with};
use super::figure::{
    Bounds, CHART_MARGIN, FONT, Figure, PALETTE, PlotError, centered_text, ensure_font_registered, format_tick,
    to_message, write_png_and_svg,
};
use super::legend::{
    ESTIMATE_COLOR, FOV_COLOR, LEGEND_LINE_HEIGHT, LEGEND_PADDING, LegendSymbol, PlacedLegendEntry, SKY_TRUTH_WIDTH,
    draw_snapshot_legend, estimate_marker, layout_legend,
};
use crate::sim::vector::wrap_angle;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::ops::Range;
use std::path::Path;

const ISOLATED_TRUTH_RADIUS: i32 = 2;

const SKY_GRID_COLOR: RGBColor = RGBColor(200, 200, 200);

const SKY_TITLE_HEIGHT: u32 = 50;

pub(crate) const SKY_POLAR_SIDE: u32 = 900;

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
pub(crate) type TruthLines = (RGBColor, Vec<Vec<(f64, f64)>>);

/// An estimate series' colour and its marker positions, in plot coordinates.
pub(crate) type EstimateMarks = (RGBColor, Vec<(f64, f64)>);

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
pub(crate) enum SkyAxes {
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
pub(crate) fn check_sky_input(
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

pub(crate) fn truth_color(series: &SkySeries, index: usize) -> RGBColor {
    PALETTE[series.color.unwrap_or(index) % PALETTE.len()]
}

pub(crate) fn estimate_color(series: &SkySeries) -> RGBColor {
    series.color.map_or(ESTIMATE_COLOR, |index| PALETTE[index % PALETTE.len()])
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
pub(crate) fn sky_runs(points: &[Option<(f64, f64)>]) -> Vec<Vec<(f64, f64)>> {
    points
        .split(Option::is_none)
        .map(|run| run.iter().flatten().copied().collect::<Vec<_>>())
        .filter(|run| !run.is_empty())
        .collect()
}

/// Draws truth polylines (isolated points as dots) and estimate crosses on a chart.
pub(crate) fn draw_sky_content<DB, X, Y>(
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
pub(crate) fn sky_legend(has_field_of_view: bool, width: u32) -> Result<Vec<Vec<PlacedLegendEntry>>, PlotError> {
    let mut symbols = vec![LegendSymbol::TruthTracks, LegendSymbol::MapEstimate];
    if has_field_of_view {
        symbols.push(LegendSymbol::Fov);
    }
    layout_legend(&symbols, width)
}

pub(crate) fn legend_height(lines: &[Vec<PlacedLegendEntry>]) -> u32 {
    lines.len() as u32 * LEGEND_LINE_HEIGHT + 2 * LEGEND_PADDING
}

fn draw_footnote<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, text: &str) -> Result<(), PlotError> {
    let (width, height) = area.dim_in_pixel();
    let style = centered_text(16).color(&RGBColor(90, 90, 90));
    area.draw(&Text::new(text.to_string(), (width as i32 / 2, height as i32 / 2), style)).map_err(to_message)
}

/// (x, y) of the polar sky projection: radius 1 - elevation / 90°, North up, East right.
pub(crate) fn polar_projection(azimuth: f64, elevation: f64) -> (f64, f64) {
    let radius = 1.0 - elevation / std::f64::consts::FRAC_PI_2;
    (radius * azimuth.sin(), radius * azimuth.cos())
}

fn inside_horizon((x, y): (f64, f64)) -> bool {
    x * x + y * y <= 1.0
}

/// The part of segment `a`-`b` inside the horizon circle (radius 1); None when both ends are below the horizon
/// (the projection of such a chord says nothing about the sky).
pub(crate) fn clip_to_horizon(a: (f64, f64), b: (f64, f64)) -> Option<Segment> {
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

pub(crate) struct PolarSkyFigure<'a> {
    title: &'a str,
    pub(super) truth: Vec<TruthLines>,
    estimates: Vec<EstimateMarks>,
    field_of_view: Vec<Vec<(f64, f64)>>,
    pub(super) estimates_below_horizon: usize,
    legend_lines: Vec<Vec<PlacedLegendEntry>>,
}

impl<'a> PolarSkyFigure<'a> {
    pub(super) fn new(
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

    pub(super) fn footnote(&self) -> Option<String> {
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
pub(crate) struct RaDecView {
    pub(super) truth: Vec<TruthLines>,
    estimates: Vec<EstimateMarks>,
    pub(super) field_of_view: Vec<Vec<(f64, f64)>>,
    pub(super) x: Range<f64>,
    pub(super) y: Range<f64>,
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
    pub(super) fn new(truth: &[SkySeries], estimates: &[SkySeries], field_of_view: Option<&[(f64, f64)]>) -> Self {
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
pub(crate) fn format_ra_tick(value: &f64) -> String {
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
