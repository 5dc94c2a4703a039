//! The figures of `run` on a planar scenario: truth against the MAP estimates at four points of the run,
//! the hypothesis weights there, the expected number of objects and GOSPA over the run.

use super::truth_positions;
use crate::error::Error;
use crate::pipeline::run_charts;
use crate::pipeline::snapshot::{HypothesisOut, Snapshot, TrackOut};
use crate::pipeline::world::ScanRecord;
use crate::plots::{self, FovLines, SnapshotPanel};
use crate::scenario::{FieldOfViewSpec, Scenario};
use std::path::Path;

/// The fractions of the run at which snapshots are plotted (paper 003 Figs. 6, 8-10).
pub const SNAPSHOT_FRACTIONS: [f64; 4] = [0.10, 0.50, 0.75, 1.00];

/// The scan index at a fraction of a run of `scans` scans.
pub fn scan_at(fraction: f64, scans: usize) -> usize {
    ((fraction * scans as f64).ceil() as usize).clamp(1, scans.max(1)) - 1
}

fn fov_lines(scenario: &Scenario) -> Option<FovLines> {
    match scenario.sensor.field_of_view {
        FieldOfViewSpec::Sector { origin, look_direction_deg, field_of_view_deg, max_range } => Some(FovLines {
            origin,
            look_direction: look_direction_deg.to_radians(),
            half_angle: field_of_view_deg.to_radians() / 2.0,
            max_range,
        }),
        _ => None,
    }
}

fn is_ssa(scenario: &Scenario) -> bool {
    matches!(scenario.motion, crate::scenario::MotionSpec::TwoBody { .. })
}

/// The part of `snapshot` that the run plots use: every hypothesis's weight, the MAP hypothesis's tracks.
pub(super) fn map_and_weights(snapshot: &Snapshot) -> Snapshot {
    let tracks: Vec<TrackOut> = snapshot.map_tracks().into_iter().cloned().collect();
    let hypotheses = snapshot
        .hypotheses
        .iter()
        .enumerate()
        .map(|(i, h)| HypothesisOut {
            weight: h.weight,
            log_weight: h.log_weight,
            tracks: if i == 0 { (0..tracks.len()).collect() } else { vec![] },
        })
        .collect();
    Snapshot { hypotheses, tracks }
}

pub(super) fn write_run_plots(
    scenario: &Scenario,
    records: &[ScanRecord],
    snapshots: &[(usize, Snapshot, Vec<bool>)],
    out: &Path,
) -> Result<(), Error> {
    let n = records.len().max(1);
    let unit = if is_ssa(scenario) { "km" } else { "" };
    let panels: Vec<SnapshotPanel> = snapshots
        .iter()
        .map(|(k, snapshot, within)| {
            let map = snapshot.map_tracks();
            let (mut inside, mut outside) = (vec![], vec![]);
            for (i, t) in map.iter().enumerate() {
                // Without truth every estimate is drawn as within the bound.
                if within.get(i).copied().unwrap_or(true) {
                    inside.push([t.mean[0], t.mean[1]])
                } else {
                    outside.push([t.mean[0], t.mean[1]])
                }
            }
            SnapshotPanel {
                title: format!("{:.0}% (scan {}): truth vs MAP", 100.0 * (*k + 1) as f64 / n as f64, k),
                truth: truth_positions(scenario, *k).unwrap_or_default().iter().map(|t| t.1).collect(),
                estimates_within_bound: inside,
                estimates_outside_bound: outside,
                fov: fov_lines(scenario),
                unit: unit.to_string(),
                central_body_radius: is_ssa(scenario).then_some(crate::sim::planar::EARTH_RADIUS),
            }
        })
        .collect();
    plots::plot_snapshots(&out.join("truth_vs_map"), &panels)?;
    let weights: Vec<(String, Vec<f64>)> = snapshots
        .iter()
        .map(|(k, s, _)| {
            (
                format!("{:.0}% (scan {k})", 100.0 * (*k + 1) as f64 / n as f64),
                s.hypotheses.iter().map(|h| h.weight).collect(),
            )
        })
        .collect();
    plots::plot_hypothesis_weights(&out.join("hypothesis_weights"), &weights)?;
    let percent = |r: &ScanRecord| 100.0 * (r.scan + 1) as f64 / n as f64;
    run_charts::write(
        out,
        records,
        "run completed (%)",
        percent,
        "GOSPA of the MAP estimates",
        &format!("GOSPA ({unit})"),
    )
}
