//! `catalogue.json` of `experiment catalogue`: the fused network tracker's figures.

use serde::{Deserialize, Serialize};

/// `catalogue.json` of `experiment catalogue`: a catalogue seen by two radars and a telescope, tracked by one
/// R-FISST tracker over the whole network (sensors of mixed kinds).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CatalogueReport {
    /// `catalogue`.
    pub experiment: String,
    /// Seed.
    pub seed: u64,
    /// Objects in the catalogue (every one in the tracker's truth).
    pub objects: usize,
    /// Objects missing from the prior.
    pub missing_from_prior: usize,
    /// Births: objects missing from the prior that some sensor detected, each counted once.
    pub births_total: usize,
    /// Births the tracker confirmed, each counted once.
    pub births_confirmed: usize,
    /// Confirmed tracks that follow no object (summary.json's `false_tracks`).
    pub false_tracks: usize,
    /// The sensor kinds of the network (`radar`, `optical`, ...), in the core's order.
    pub sensor_kinds: Vec<String>,
    /// GOSPA (km) averaged over every scan.
    pub mean_gospa: f64,
    /// Wall-clock ms per scan, averaged over every accepted scan.
    pub mean_ms_per_scan: f64,
    /// The slowest scan (ms).
    pub max_ms_per_scan: f64,
    /// Objects observed (measured at least once) by the last scan ([`crate::eval::observed`]).
    #[serde(default)]
    pub observed_objects: Option<usize>,
    /// Median error (km) at the last scan of the objects observed so far.
    #[serde(default)]
    pub observed_median_error_km: Option<f64>,
    /// Median prediction error (km) at the last scan of the objects never observed.
    #[serde(default)]
    pub unobserved_median_error_km: Option<f64>,
    /// The tracker's figures (one entry: the fused network).
    pub details: Vec<CatalogueTracker>,
}

/// One tracker of `experiment catalogue`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CatalogueTracker {
    /// `network`: its run directory.
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
    /// The detected births it did not confirm, and how much each was seen.
    #[serde(default)]
    pub unconfirmed_births: Vec<UnconfirmedBirth>,
}

/// A birth some sensor detected and the tracker did not confirm.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct UnconfirmedBirth {
    /// Object id (its index in the catalogue).
    pub object: u64,
    /// Its catalogue number.
    pub norad_id: u64,
    /// Its detections, by any sensor.
    pub detections: usize,
    /// Time (s since the start) of its first and last detection.
    pub detected_from_s: f64,
    /// See `detected_from_s`.
    pub detected_until_s: f64,
}
