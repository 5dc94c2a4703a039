//! The report of `soak`: health, tracking, truth and set-up of a long run.

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// The report of `host-sim soak`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SoakReport {
    /// The scenario (`planar`, `radar-leo`, `optical-geo`).
    pub scenario: String,
    /// Scans run.
    pub scans: u64,
    /// Seed.
    pub seed: u64,
    /// Non-finite values seen, summed over scans.
    pub nan_count: u64,
    /// Scans after which some value was not finite.
    pub non_finite_scans: u64,
    /// The first such scan (1-based).
    pub first_non_finite_scan: Option<u64>,
    /// Largest number of hypotheses.
    pub max_hypotheses: usize,
    /// Largest time per scan (ms).
    pub max_ms_per_scan: f64,
    /// Mean time per scan (ms).
    pub mean_ms_per_scan: f64,
    /// Median time per scan (ms).
    pub p50_ms_per_scan: f64,
    /// 99th percentile of the time per scan (ms).
    pub p99_ms_per_scan: f64,
    /// Largest over median time per scan.
    pub max_over_median: f64,
    /// Mean time per scan over the first tenth of the scans (ms).
    pub mean_ms_per_scan_first_tenth: f64,
    /// Mean time per scan over the last tenth of the scans (ms).
    pub mean_ms_per_scan_last_tenth: f64,
    /// Peak resident memory (VmHWM, KiB) after the first scan, when the system reports it.
    pub peak_resident_kib_start: Option<u64>,
    /// Peak resident memory (VmHWM, KiB) after the last scan.
    pub peak_resident_kib_end: Option<u64>,
    /// Tracks dropped for a numerical failure, summed.
    pub numerical_drops: u64,
    /// Objects within 10 km of their truth after the last scan (3-D soaks, whose objects live for the
    /// whole run): the MAP hypothesis holds the object's label with a position error below 10 km.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub objects_within_10km: Option<usize>,
    /// Mean normalised estimation error squared of the MAP tracks over every object-scan with a track
    /// (position and velocity; 6 for a consistent filter; docs/maths.md §8.6).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mean_nees: Option<f64>,
    /// Whether the objects stay tracked (3-D soaks, whose objects live for the whole run).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tracking: Option<SoakTracking>,
    /// Step errors by variant.
    pub errors_by_kind: BTreeMap<String, u64>,
    /// The first step error.
    pub first_error: Option<SoakError>,
    /// Track store high-water mark.
    pub track_store_high_water: usize,
    /// Track store capacity K.
    pub track_store_capacity: usize,
    /// Hypothesis capacity H.
    pub hypothesis_capacity: usize,
    /// Most measurements in a scan.
    pub max_measurements_per_scan: usize,
    /// Measurement capacity Z.
    pub measurement_capacity: usize,
    /// Measurements over the run.
    pub measurements: u64,
    /// Births beyond the object capacity, summed.
    pub births_beyond_object_capacity: u64,
    /// Children dropped for the track store, summed.
    pub children_dropped_for_store: u64,
    /// What the truth did.
    pub truth: SoakTruth,
    /// Expected number of objects at the end.
    pub final_expected_cardinality: f64,
    /// Mean |expected − true number of objects|.
    pub mean_abs_cardinality_error: f64,
    /// Largest |expected − true number of objects|.
    pub max_abs_cardinality_error: f64,
    /// Wall-clock time of the run (s).
    pub wall_seconds: f64,
    /// The scenario and tracker.
    pub setup: SoakSetup,
}

/// Whether a 3-D soak's objects stay tracked: an object is tracked at a scan when the MAP hypothesis holds
/// its label with a position within `error_bound_km` of the truth.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SoakTracking {
    /// The bound (km): the scenario's `evaluation.error_bound`.
    pub error_bound_km: f64,
    /// True objects (all alive for the whole run).
    pub objects: usize,
    /// Objects tracked after the last scan.
    pub final_tracked: usize,
    /// Fewest objects tracked after any scan.
    pub min_tracked: usize,
    /// The first scan (1-based) with that fewest.
    pub min_tracked_scan: u64,
    /// Mean number tracked over the scans.
    pub mean_tracked: f64,
    /// Mean number tracked over the last tenth of the scans.
    pub mean_tracked_last_tenth: f64,
    /// Object-scans with the object in the scan's field of view.
    pub in_view: u64,
    /// The fraction of them tracked after the scan.
    pub in_view_tracked_fraction: f64,
    /// The same over the last tenth of the scans.
    pub in_view_tracked_fraction_last_tenth: f64,
    /// Median MAP position error (km) over the objects after the last scan.
    pub final_median_position_error_km: f64,
    /// Labels missing from the MAP hypothesis after the last scan.
    pub final_missing_labels: usize,
    /// Detections dropped because their noisy value fell outside the field of view.
    pub dropped_outside_field_of_view: u64,
    /// Simulated time (days).
    pub simulated_days: f64,
    /// Mean NEES over the last tenth of the scans.
    pub mean_nees_last_tenth: Option<f64>,
    /// The share of scans whose mean NEES over the objects with a track lies within its two-sided 95 %
    /// χ² band (docs/maths.md §8.6).
    pub nees_scans_in_band_fraction: Option<f64>,
    /// That band for a scan holding every object.
    pub nees_band_all_objects: [f64; 2],
    /// Track-scans whose covariance was not positive definite (left out of the NEES).
    pub nees_undefined: u64,
    /// Every object's MAP position error (km) after the last scan, by object (none: no track).
    pub final_position_errors_km: Vec<Option<f64>>,
    /// Every object's NEES after the last scan (none: no track).
    pub final_nees: Vec<Option<f64>>,
    /// Scans since each object was last in a field of view (none: never).
    pub scans_since_in_view: Vec<Option<u64>>,
}

/// The first step error of a soak.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SoakError {
    /// Scan (1-based).
    pub scan: u64,
    /// The error's message.
    pub message: String,
}

/// The soak's true objects.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SoakTruth {
    /// Objects known to the prior.
    pub initial_objects: usize,
    /// Births.
    pub births: u64,
    /// Deaths.
    pub deaths: u64,
    /// Most objects alive at once.
    pub max_alive: usize,
    /// Objects alive at the end.
    pub final_alive: usize,
}

/// The soak's scenario and tracker, in words and numbers.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SoakSetup {
    /// The tracker.
    pub tracker: String,
    /// The motion model.
    pub motion: String,
    /// The sensor.
    pub sensor: String,
    /// Seconds between scans.
    pub scan_interval_s: f64,
    /// True birth probability per scan.
    pub birth_rate_per_scan: f64,
    /// True death probability per object and scan.
    pub death_rate_per_object_per_scan: f64,
    /// The tracker's α per cell.
    pub tracker_birth_probability_per_cell: f64,
    /// The tracker's birth cells.
    pub tracker_birth_cells: usize,
    /// The tracker's β.
    pub tracker_death_probability: f64,
}
