//! `host-sim digest RADAR_SCENARIO --pool`: the radar excerpt of [`super::orbital`] (its configuration,
//! restricted prior and `f32` scans) through the embedded pool of cluster trackers,
//! [`tracker_core::partition::ClusterPool`], exactly as the QEMU firmware's pool replay
//! (`firmware/qemu-m4/src/pool.rs`) does: every object of the prior its own cluster, exact splits (ε = 0).
//!
//! The text is the digest text of [`super::text_of`] with, per scan, the clusters of objects and their
//! hypotheses after the scan and [`ClusterPool::digest`]:
//!
//! ```text
//! scan 0 clusters 43 hypotheses 43 digest 1c0ffee15bad5eed
//! ```

use super::orbital;
use crate::scenario::ScenarioError;
use crate::scenario::v2::Scenario3d;
use nalgebra::SVector;
use std::fmt;
use tracker_core::partition::ClusterPool;
use tracker_core::sensor::ScanGeometry;
use tracker_core::{RadarNetwork, TwoBodyJ2, ssa_caps};

// The pool's capacities: the same list is in `firmware/qemu-m4/src/pool.rs`; keep the two in step.
/// Hypotheses per cluster.
pub const H: usize = 16;
/// Objects per hypothesis of a cluster.
pub const N: usize = 8;
/// Measurements per cluster and scan.
pub const Z: usize = 32;
/// Tracks per cluster.
pub const K: usize = 32;
/// Birth cells (the radar configuration's).
pub const B: usize = ssa_caps::BIRTH_CELLS;
/// Clusters (radar-leo's excerpt starts with 43).
pub const P: usize = 64;
/// Measurements per scan.
pub const L: usize = 64;

/// The embedded pool of radar cluster trackers.
pub type Pool = ClusterPool<f32, TwoBodyJ2<f32>, RadarNetwork<f32>, 6, 3, H, N, Z, K, B, P, L>;

/// What the pool did over the replayed scans (not part of the compared text).
#[derive(Debug, Default, Clone, Copy, PartialEq)]
pub struct Totals {
    /// Clusters merged away.
    pub merged: usize,
    /// Clusters born from the birth cluster.
    pub born: usize,
    /// New clusters made by splits.
    pub split: usize,
    /// The most clusters after a scan.
    pub most_clusters: usize,
    /// Scans the pool refused.
    pub errors: usize,
}

impl fmt::Display for Totals {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "merged {}, born {}, split {}, at most {} clusters, {} scans refused",
            self.merged, self.born, self.split, self.most_clusters, self.errors
        )
    }
}

/// Replays the first `scans` scans of the radar scenario `scenario` (all when `None`) through [`Pool`] and
/// returns the digest text the firmware prints, and what the pool did.
///
/// # Errors
/// As [`orbital::run`], and when the prior has more than one hypothesis or the pool refuses it.
pub fn run(scenario: &Scenario3d, scans: Option<usize>) -> Result<(String, Totals), ScenarioError> {
    let count = super::excerpt(scans, scenario.scans.len())?;
    let mut pool = pool(scenario, count)?;
    let mut totals = Totals::default();
    let text = super::text_of(count, ["clusters", "hypotheses"], |index| {
        let scan = &scenario.scans[index];
        let measurements: Vec<SVector<f32, 3>> =
            scan.measurements.iter().map(|z| orbital::measurement(scenario.measurement, z)).collect();
        let geometry = ScanGeometry { sensor: scan.sensor, time: scan.time, observer: None };
        let outcome = pool.step(&geometry, &measurements);
        match &outcome {
            Ok(report) => {
                totals.merged += report.merged;
                totals.born += report.born_clusters;
                totals.split += report.split;
                totals.most_clusters = totals.most_clusters.max(report.clusters);
            }
            Err(_) => totals.errors += 1,
        }
        (outcome.map(|report| (report.clusters, report.hypotheses)), pool.digest())
    });
    Ok((text, totals))
}

/// The pool for the first `count` scans of `scenario`, on the heap: [`orbital::config`] and the objects of
/// [`orbital::prior`] (one hypothesis), each its own cluster.
///
/// # Errors
/// As [`run`].
pub fn pool(scenario: &Scenario3d, count: usize) -> Result<Box<Pool>, ScenarioError> {
    orbital::radar_only(scenario)?;
    let config = orbital::config(scenario)?;
    let prior = orbital::prior(scenario, count)?;
    let [(_, objects)] = prior.as_slice() else {
        return Err(ScenarioError(format!(
            "prior: the pool replay takes one prior hypothesis; this scenario has {}",
            prior.len()
        )));
    };
    // Built in place on the heap, as the firmware's static: the pool is too large for a thread's stack.
    let mut pool = Box::new(Pool::empty(config.clone(), config.clone(), config.clone()));
    pool.reset_with(config, objects, scenario.prior.time, 0.0)
        .map_err(|e| ScenarioError(format!("pool configuration: {e}")))?;
    Ok(pool)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn on_large_stack(f: impl FnOnce() + Send + 'static) {
        std::thread::Builder::new().stack_size(64 << 20).spawn(f).expect("thread").join().expect("no panic");
    }

    #[test]
    fn pool_text_has_one_line_per_scan_and_repeats() {
        on_large_stack(|| {
            let simulation = crate::sim::presets::tiny_3d(1).expect("tiny-3d");
            let scenario = crate::scenario::from_simulation::to_scenario(&simulation).expect("scenario").0;
            let (text, _) = run(&scenario, Some(4)).expect("digest");
            let lines: Vec<&str> = text.lines().collect();
            assert_eq!(lines.len(), 5);
            assert!(lines[0].starts_with("scan 0 clusters "), "{text}");
            assert!(lines[4].starts_with("final scans 4 digest "));
            assert_eq!(run(&scenario, Some(4)).expect("digest").0, text);
        });
    }
}
