//! `catalogue.json` of `experiment catalogue`: per network its tracker's figures.

use serde::{Deserialize, Serialize};

/// `catalogue.json` of `experiment catalogue`: a catalogue seen by two radars and a telescope, each
/// network tracked by its own R-FISST tracker (one tracker takes one measurement type).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CatalogueReport {
    /// `catalogue`.
    pub experiment: String,
    /// Seed.
    pub seed: u64,
    /// Objects in the catalogue (every one in both trackers' truth).
    pub objects: usize,
    /// Objects missing from the prior (the same in both scenarios).
    pub missing_from_prior: usize,
    /// Births: objects missing from the prior that some sensor detected, each counted once.
    pub births_total: usize,
    /// Births that at least one tracker confirmed, each counted once.
    pub births_confirmed: usize,
    /// GOSPA (km) averaged over every scan of both trackers.
    pub mean_gospa: f64,
    /// Wall-clock ms per scan, averaged over every accepted scan of both trackers.
    pub mean_ms_per_scan: f64,
    /// The slowest scan of both trackers (ms).
    pub max_ms_per_scan: f64,
    /// Per tracker.
    pub details: Vec<CatalogueTracker>,
}

/// One tracker of `experiment catalogue`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CatalogueTracker {
    /// `radars` or `telescope`: its run directory.
    pub network: String,
    /// Its sensors.
    pub sensors: Vec<String>,
    /// Seconds between two scans of one sensor.
    pub scan_interval_s: f64,
    /// Scans.
    pub scans: usize,
    /// Catalogue objects with at least one detection.
    pub objects_seen: usize,
    /// Launch-train objects with at least one detection.
    pub train_seen: usize,
    /// Launch-train objects confirmed.
    pub train_confirmed: usize,
    /// Births: objects missing from the prior (detected or not).
    pub births_total: usize,
    /// Births with at least one detection.
    pub births_detected: usize,
    /// Births confirmed.
    pub births_confirmed: usize,
    /// Mean detections to confirmation of the confirmed births.
    pub mean_detections_to_confirm: Option<f64>,
    /// MAP labels confirmed and never within the error bound of an object.
    pub false_tracks: Option<usize>,
    /// Mean GOSPA (km) over its scans.
    pub mean_gospa: f64,
    /// MAP tracks after the last scan.
    pub final_map_cardinality: usize,
    /// Wall-clock ms per scan, mean and max.
    pub mean_ms_per_scan: f64,
    /// The slowest scan (ms).
    pub max_ms_per_scan: f64,
    /// Scans the tracker rejected.
    pub rejected_scans: usize,
}
