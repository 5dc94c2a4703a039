//! The figures of `run` on a version 2 scenario: a plot per sensor in its own coordinates (azimuth /
//! elevation for radars and az/el stations, right ascension / declination for telescopes, range over time
//! for ranging stations), the expected number of objects and GOSPA over time.

use crate::error::Error;
use crate::pipeline::run_charts;
use crate::pipeline::world::ScanRecord;
use crate::plots::{self, Scale, Series, SkySeries};
use crate::scenario::v2::{Scenario3d, ShapeSpec};
use std::collections::BTreeMap;
use std::path::Path;

/// The outline of a field of view in (azimuth, elevation), radians, for the az/el sky plot.
fn fov_outline(shape: &ShapeSpec, mask_deg: f64) -> Vec<(f64, f64)> {
    const POINTS: usize = 72;
    let mask = mask_deg.to_radians();
    match *shape {
        ShapeSpec::Cone { azimuth_deg, elevation_deg, half_angle_deg } => {
            let (a0, e0, h) = (azimuth_deg.to_radians(), elevation_deg.to_radians(), half_angle_deg.to_radians());
            // Boresight b and two unit vectors across it, in (East, North, Up).
            let b = [e0.cos() * a0.sin(), e0.cos() * a0.cos(), e0.sin()];
            let u = [a0.cos(), -a0.sin(), 0.0];
            let v = [-e0.sin() * a0.sin(), -e0.sin() * a0.cos(), e0.cos()];
            (0..POINTS)
                .map(|i| {
                    let phi = i as f64 * std::f64::consts::TAU / POINTS as f64;
                    let d: Vec<f64> =
                        (0..3).map(|k| h.cos() * b[k] + h.sin() * (phi.cos() * u[k] + phi.sin() * v[k])).collect();
                    (d[0].atan2(d[1]), d[2].clamp(-1.0, 1.0).asin().max(mask))
                })
                .collect()
        }
        ShapeSpec::Box { azimuth_deg, half_width_deg, elevation_deg: [low, high] } => {
            let (a0, w) = (azimuth_deg.to_radians(), half_width_deg.to_radians());
            let (low, high) = (low.to_radians().max(mask), high.to_radians());
            let steps = POINTS / 2;
            let along = |el: f64, forward: bool| {
                (0..=steps).map(move |i| {
                    let f = i as f64 / steps as f64;
                    let f = if forward { f } else { 1.0 - f };
                    (tracker_core::sensor::wrap_angle(a0 - w + 2.0 * w * f), el)
                })
            };
            if w >= std::f64::consts::PI {
                // Every azimuth: the ring of the lowest elevation seen.
                return along(low, true).collect();
            }
            along(low, true).chain(along(high, false)).collect()
        }
    }
}

/// The names of a measurement's components, for its residual plot.
pub(super) fn component_names(kind: crate::scenario::v2::Measurement3dSpec) -> &'static [&'static str] {
    kind.components().0
}

/// One sensor's sky-plot truth: per object id, a point per scan of that sensor (`None` out of view).
pub(super) type SkyTruth = BTreeMap<u64, Vec<Option<(f64, f64)>>>;

/// A file-name stem from a sensor's name: letters, digits and `-`, others as `_`.
fn stem_of(name: &str) -> String {
    name.chars().map(|c| if c.is_ascii_alphanumeric() || c == '-' { c } else { '_' }).collect()
}

/// A ranging station's plot: range (km) against time (h), truth as lines (cut where out of view),
/// estimates as isolated markers.
fn range_plot(stem: &Path, title: &str, truth: &[SkySeries], estimates: &SkySeries) -> Result<(), Error> {
    let points = |series: &SkySeries| -> Vec<(f64, f64)> {
        series.points.iter().map(|p| p.unwrap_or((f64::NAN, f64::NAN))).collect()
    };
    let mut series: Vec<Series> = truth
        .iter()
        .enumerate()
        .map(|(i, t)| Series {
            name: if i == 0 { "truth in view".into() } else { String::new() },
            points: points(t),
            markers: false,
        })
        .collect();
    // A break after each estimate: markers, not a line through the tracks.
    let marks = estimates.points.iter().flatten().flat_map(|&p| [p, (f64::NAN, f64::NAN)]).collect();
    series.push(Series { name: "MAP estimates".into(), points: marks, markers: true });
    Ok(plots::plot_series(
        stem,
        title,
        "time since the epoch (h)",
        "range (km)",
        Scale::Linear,
        Scale::Linear,
        &series,
    )?)
}

pub(super) fn write_plots(
    scenario: &Scenario3d,
    records: &[ScanRecord],
    sky_truth: &[SkyTruth],
    sky_estimates: &[Vec<Option<(f64, f64)>>],
    out: &Path,
) -> Result<(), Error> {
    for (s, sensor) in scenario.sensors.iter().enumerate() {
        let truth: Vec<SkySeries> = sky_truth[s]
            .iter()
            .enumerate()
            .map(|(i, (id, points))| SkySeries { name: format!("object {id}"), points: points.clone(), color: Some(i) })
            .collect();
        let estimates = [SkySeries { name: "MAP estimates".into(), points: sky_estimates[s].clone(), color: None }];
        let stem = out.join(format!("sky_{s}_{}", stem_of(&sensor.name)));
        if scenario.kind(s).sky_in_range() {
            let title = format!("{}: range over time, truth in view and MAP estimates", sensor.name);
            range_plot(&stem, &title, &truth, &estimates[0])?;
        } else if scenario.kind(s).sky_in_ra_dec() {
            let title = format!("{}: right ascension / declination, truth in view and MAP estimates", sensor.name);
            plots::sky_plot_ra_dec(&stem, &title, &truth, &estimates, None)?;
        } else {
            let title = format!("{}: azimuth / elevation, truth in view and MAP estimates", sensor.name);
            let outline = fov_outline(&sensor.field_of_view.shape, sensor.field_of_view.min_elevation_deg);
            plots::sky_plot_az_el(&stem, &title, &truth, &estimates, Some(&outline))?;
        }
    }
    let hours = |r: &ScanRecord| r.time / 3600.0;
    run_charts::write(
        out,
        records,
        "time since the epoch (h)",
        hours,
        "GOSPA of the MAP estimates (3-D positions)",
        "GOSPA (km)",
    )
}
