//! `scale.json` of `experiment catalogue-scale`: the partitioned tracker's cost, memory and quality on a
//! synthetic catalogue streamed scan by scan.

use serde::{Deserialize, Serialize};

/// `scale.json`. Wall-clock and CPU figures (`wall_s`, `realtime_factor`, `peak_rss_mib`, `ms_per_scan_*`,
/// `cpu_*`, `total_wall_s`) vary from run to run; every other figure is the same for the same arguments, whatever
/// `threads`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScaleReport {
    /// Objects tracked: the synthetic catalogue less `dropped_objects`.
    pub objects: usize,
    /// Scans (every sensor's, in time order).
    pub scans: usize,
    /// Measurements given to the tracker (detections and clutter).
    pub observations: usize,
    /// Simulated hours.
    pub hours: f64,
    /// Threads of the rayon pool.
    pub threads: usize,
    /// Wall-clock seconds of the tracker's steps (the simulation and the scoring not counted).
    pub wall_s: f64,
    /// Simulated seconds per wall-clock second of the tracker (`hours` × 3600 / `wall_s`).
    pub realtime_factor: f64,
    /// Peak resident memory of the process (MiB, VmHWM of /proc/self/status; `null` where there is none).
    pub peak_rss_mib: Option<f64>,
    /// Wall-clock ms per scan: mean.
    pub ms_per_scan_mean: f64,
    /// Wall-clock ms per scan: 99th percentile (nearest rank).
    pub ms_per_scan_p99: f64,
    /// Wall-clock ms per scan: the slowest.
    pub ms_per_scan_max: f64,
    /// CPU seconds of the tracker's steps, summed over the process's threads (schedstat; idle pool threads
    /// spinning for work included): on a shared machine, what the steps cost apart from waiting for a core.
    pub cpu_s: Option<f64>,
    /// CPU ms per scan (as `cpu_s`): mean.
    pub cpu_ms_per_scan_mean: Option<f64>,
    /// CPU ms per scan (as `cpu_s`): 99th percentile (nearest rank).
    pub cpu_ms_per_scan_p99: Option<f64>,
    /// Most clusters of objects after one scan.
    pub clusters_max: usize,
    /// Most objects (labels) in one cluster after one scan.
    pub largest_cluster: usize,
    /// Objects missing from the prior (births), detected or not.
    pub births_total: usize,
    /// Births the tracker confirmed.
    pub births_confirmed: usize,
    /// Labels confirmed in the MAP hypothesis and never within the error bound of an object.
    pub false_tracks: usize,
    /// GOSPA (km, over every object of the catalogue) averaged over the scored scans.
    pub mean_gospa: f64,
    /// Objects measured at least once by the last scan.
    pub observed_objects: usize,
    /// Median error (km) at the last scan of the objects observed so far.
    pub observed_median_error_km: Option<f64>,
    /// Median prediction error (km) at the last scan of the objects never observed.
    pub unobserved_median_error_km: Option<f64>,
    /// Label switches along GOSPA's assignment over the scored scans.
    pub label_switches: usize,
    /// Element sets SGP4 could not propagate over the run (left out, each with a warning).
    pub dropped_objects: usize,
    /// Objects in the field of view of the scan's sensor, mean over the scans.
    pub objects_in_view_mean: f64,
    /// The most objects in view in one scan.
    pub objects_in_view_max: usize,
    /// The most measurements in one scan.
    pub observations_max: usize,
    /// Scans the tracker refused (each a warning naming the cluster).
    pub rejected_scans: usize,
    /// Measurements gated by two clusters whose merge could hold more objects than a cluster's N: not
    /// merged, each measurement kept by the cluster that gated it first (docs/maths.md §13.3).
    #[serde(default)]
    pub merges_declined: usize,
    /// Tracks dropped as lost (`lost_after_unseen_scans`, docs/maths.md §5.9), over the run.
    #[serde(default)]
    pub lost_tracks: usize,
    /// Scans scored (one a simulated minute, and the last).
    pub scored_scans: usize,
    /// Wall-clock seconds of the whole command (catalogue, simulation, tracking, scoring, files).
    pub total_wall_s: f64,
    /// The tracker's digest after the last scan (hex): the same whatever `threads`.
    pub digest: String,
    /// The cluster capacities, as `H/N/Z/K/B`.
    pub profile: String,
    /// The seed.
    pub seed: u64,
    /// Whether clusters beyond a sensor's range window were left out of its scans (docs/maths.md §13.2;
    /// `false` with `--step-every-cluster`).
    pub view_skip: bool,
    /// The floor under the clusters' hypothesis weights in decades below the heaviest (docs/maths.md §8.1);
    /// `null`: none, every child up to H kept.
    pub weight_floor_decades: Option<u8>,
    /// Scans in view without a measurement in a track's gate after which the track is dropped
    /// (docs/maths.md §5.9); `null`: never.
    pub lost_after_unseen_scans: Option<u16>,
    /// Clusters stepped per scan (in place or on a copy), mean over the scans: with the view skip, those
    /// near the scanning sensor; without it, every cluster.
    pub clusters_stepped_mean: f64,
    /// Of those, clusters coasting per scan (gated from their tracks' means alone, every track cleared from
    /// the scanning sensor, docs/maths.md §13.2), mean over the scans.
    pub clusters_coasted_mean: f64,
    /// Resident memory (MiB, VmRSS) at the first scan of each simulated hour, from hour 0: flat after
    /// warm-up when memory follows the objects. Varies from run to run.
    pub rss_mib_by_hour: Vec<f64>,
}
