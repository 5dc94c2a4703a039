//! Ground tracks: truth and estimated sub-satellite points on a longitude/latitude map.

use super::figure::{FONT, Figure, PlotError, ensure_font_registered, format_tick, to_message, write_png_and_svg};
use super::legend::{PlacedLegendEntry, draw_snapshot_legend};
use super::sky::{
    EstimateMarks, SkyAxes, SkySeries, TruthLines, check_sky_input, draw_sky_content, estimate_color, legend_height,
    sky_legend, sky_runs, truth_color,
};
use crate::sim::vector::wrap_angle;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

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

pub(crate) struct GroundTrackFigure<'a> {
    title: &'a str,
    pub(super) truth: Vec<TruthLines>,
    estimates: Vec<EstimateMarks>,
    legend_lines: Vec<Vec<PlacedLegendEntry>>,
}

impl<'a> GroundTrackFigure<'a> {
    pub(super) fn new(title: &'a str, truth: &[SkySeries], estimates: &[SkySeries]) -> Result<Self, PlotError> {
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
