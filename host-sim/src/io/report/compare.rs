//! `compare.json` of `compare`: the bounded tracker against the unbounded reference, planar and 3-D.

use serde::{Deserialize, Serialize};

/// `compare.json`: the figures printed by `host-sim compare`, and the per-scan records.
// `flatten` does not combine with `deny_unknown_fields`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CompareReport {
    /// The figures over the run.
    #[serde(flatten)]
    pub summary: CompareSummary,
    /// One record per scan.
    pub per_scan: Vec<CompareScan>,
}

/// The figures of `compare.json` over the run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CompareSummary {
    /// Scenario name.
    pub scenario: String,
    /// The bounded tracker.
    pub bounded_tracker: String,
    /// Its capacity profile.
    pub profile: String,
    /// Number of scans.
    pub scans: usize,
    /// Mean over scans of the reference's mass on the bounded tracker's hypotheses.
    pub mean_captured_mass: f64,
    /// Its smallest value.
    pub min_captured_mass: f64,
    /// Mean L1 distance between the weights.
    pub mean_weight_l1: f64,
    /// Fraction of scans whose MAP hypotheses agree.
    pub map_agreement: f64,
    /// The bounded tracker's figures.
    pub bounded: CompareSide,
    /// The reference's figures.
    pub reference: CompareSide,
}

/// One tracker's figures in `compare.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompareSide {
    /// Tracker name.
    pub tracker: String,
    /// Mean GOSPA; `null` without truth.
    pub mean_gospa: Option<f64>,
    /// Mean time per scan (ms).
    pub mean_ms_per_scan: f64,
    /// Largest time per scan (ms).
    pub max_ms_per_scan: f64,
    /// The reference only: scans at which its memory budget forced pruning.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub budget_reached_scans: Option<Vec<usize>>,
}

/// One scan of `compare.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompareScan {
    /// Scan index.
    pub scan: usize,
    /// Scan time (s).
    pub time: f64,
    /// The reference's mass on the bounded tracker's hypotheses.
    pub captured_mass: f64,
    /// Σ |w_bounded − w_reference|.
    pub weight_l1: f64,
    /// Whether the bounded MAP hypothesis has the reference's largest weight.
    pub map_agreement: bool,
    /// Hypotheses of the bounded tracker.
    pub bounded_hypotheses: usize,
    /// Hypotheses of the reference.
    pub reference_hypotheses: usize,
    /// Time of the bounded tracker (ms).
    pub bounded_ms: f64,
    /// Time of the reference (ms).
    pub reference_ms: f64,
    /// The bounded tracker's error, when it rejected the scan.
    pub bounded_error: Option<String>,
    /// The reference's error, when it rejected the scan.
    pub reference_error: Option<String>,
}

/// `compare.json` of `host-sim compare` on a version 2 (3-D) file: the bounded tracker against the unbounded
/// reference, scan by scan (`exactness::compare_scans`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Compare3dSummary {
    /// The bounded tracker (`homht` or `rfisst`).
    pub tracker: String,
    /// Its capacity profile.
    pub profile: String,
    /// Sensors of the scenario.
    pub sensors: usize,
    /// Scans compared.
    pub scans: usize,
    /// Fraction of scans whose MAP hypotheses agree.
    pub map_agreement: f64,
    /// Smallest captured mass (the reference's mass on the bounded tracker's hypotheses).
    pub min_captured_mass: f64,
    /// Mean captured mass.
    pub mean_captured_mass: f64,
    /// Largest weight L1 distance.
    pub max_weight_l1: f64,
    /// Largest |w_core(MAP) − w_reference| relative to the reference's MAP weight.
    pub max_map_weight_difference: f64,
    /// Smallest captured mass the bounded tracker reported itself.
    pub min_core_captured_mass: f64,
    /// Scans the bounded tracker rejected.
    pub core_rejected_scans: usize,
    /// Scans the reference rejected.
    pub reference_rejected_scans: usize,
}
