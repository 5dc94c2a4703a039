//! What a run's tracker did not take, in `summary.json`: the tracks the core dropped for a numerical
//! failure (`numerical_drops`) and the scans it refused for their input (`refused_scans`).

use serde::{Deserialize, Serialize};

/// `numerical_drops` of `summary.json`: every track the core dropped for a numerical failure
/// (tracker-core's `NumericalFailure::DropTrack`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct NumericalDropsSummary {
    /// Tracks dropped over the run.
    pub count: usize,
    /// Per scan with drops: the first dropped track (in the core's track-store order) and why, and how many
    /// were dropped at that scan.
    pub tracks: Vec<NumericalDrop>,
}

/// One scan's numerical drops.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NumericalDrop {
    /// Scan index.
    pub scan: usize,
    /// Scan time (s).
    pub time: f64,
    /// The first track dropped at this scan (the core names one per scan).
    pub label: u32,
    /// Why it was dropped (the core's numerical error).
    pub reason: String,
    /// Tracks dropped at this scan, this one included.
    pub dropped: usize,
}

/// `refused_scans` of `summary.json`: the scans the core refused for their input (a measurement outside
/// the field of view or not finite, more measurements than the capacity). The tracker is unchanged by a
/// refused scan, the run goes on, and the next scan's gap is measured from the last accepted scan.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct RefusedScans {
    /// Scans refused.
    pub count: usize,
    /// Per refused scan, in scan order.
    pub reasons: Vec<RefusedScan>,
}

/// One refused scan.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RefusedScan {
    /// Scan index.
    pub scan: usize,
    /// Scan time (s).
    pub time: f64,
    /// The scan's sensor name (`null` for planar scenarios, which have one unnamed sensor).
    pub sensor: Option<String>,
    /// The core's message.
    pub reason: String,
}
