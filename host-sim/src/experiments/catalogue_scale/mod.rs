//! `host-sim experiment catalogue-scale --objects N --hours H --seed S [--threads T] --out DIR` (issue 30
//! item 6): a synthetic catalogue of N objects ([`crate::sim::population`]) seen by a wide-field radar and
//! the two radars of `radar-leo` ([`world`]), some objects missing from the prior, tracked by the
//! partitioned tracker ([`crate::partition`], clusters of [`CLUSTER`]'s capacities) on a rayon pool of T
//! threads.
//!
//! Streamed: each scan is simulated, given to the tracker and scored, then dropped; no scenario is held,
//! so the run's memory is the tracker's and one scan's. A scan of more measurements than one cluster's Z is
//! routed to the clusters whose gates hold them; a cluster (or the birth cluster) given more than Z refuses
//! the scan with an error naming it, counted in `rejected_scans` and printed, and the run goes on.
//!
//! Writes `DIR/scale.json` ([`ScaleReport`]), `DIR/cost_per_scan.png|svg` (ms per scan against the
//! objects in view, a colour per sensor) and `DIR/cluster_sizes.png|svg` (objects per cluster after the
//! last scan).

mod score;
mod world;

#[cfg(test)]
mod tests;

use crate::error::Error;
use crate::io::report::ScaleReport;
use crate::partition::runner::{CLUSTER, Partitioned, ground_closing_speed, posterior_at};
use crate::pipeline::TrackerKind;
use crate::pipeline::orbital::config3d;
use crate::pipeline::output::{cpu_time_ns, peak_resident_kib, resident_kib, write_json};
use crate::plots::{self, Series};
use crate::scenario::SelectionSpec;
use score::Score;
use std::collections::BTreeMap;
use std::path::Path;
use std::time::Instant;
use tracker_core::model::{RadarRangeAzEl, SensorNetwork};
use tracker_core::sensor::ScanGeometry;
pub use world::{MISSING_FRACTION, SCAN_INTERVAL_S, START};

/// The radar network's measurement model.
type Radars = SensorNetwork<f64, RadarRangeAzEl<f64>, 3, { crate::pipeline::orbital::C }>;

/// The longest run (hours), as `generate catalogue`'s.
pub const MAX_HOURS: f64 = crate::scenario::from_catalogue::MAX_DURATION_HOURS;

/// Rejected scans printed one by one; the rest are counted.
const WARNING_LINES: usize = 10;

/// What a run is asked.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    pub objects: usize,
    pub hours: f64,
    pub seed: u64,
    /// Threads of the pool (`None`: every core).
    pub threads: Option<usize>,
    pub quiet: bool,
    /// Step every cluster at every scan (`--step-every-cluster`) instead of leaving the clusters beyond a
    /// sensor's range window out of its scans (docs/maths.md §13.2, the default).
    pub step_every_cluster: bool,
    /// The clusters keep the children within this many decades of the heaviest (`--weight-floor`,
    /// docs/maths.md §8.1; the default [`crate::scenario::from_simulation::CATALOGUE_SELECTION`]'s 9);
    /// `None`: every child up to H.
    pub weight_floor_decades: Option<u8>,
    /// A track in view of this many scans in a row with no measurement in its gate is dropped
    /// (`--lost-after`, docs/maths.md §5.9; the default
    /// [`crate::scenario::from_simulation::CATALOGUE_TRACK_LOSS`]'s 8); `None`: tracks are never dropped.
    pub lost_after_unseen_scans: Option<u16>,
}

/// One scan's figures.
struct ScanFigures {
    sensor: usize,
    in_view: usize,
    measurements: usize,
    ms: f64,
    /// Clusters the scan stepped (in place or on a copy; the skipped ones not counted).
    stepped: usize,
    /// Of those, the clusters coasting.
    coasted: usize,
    /// CPU ms of the step, summed over the process's threads (`None`: not known).
    cpu_ms: Option<f64>,
}

/// Runs the experiment into `dir`.
///
/// # Errors
/// [`Error::Input`] for bad settings; [`Error::Output`] when a file cannot be written.
pub fn run(dir: &Path, settings: &Settings) -> Result<ScaleReport, Error> {
    let max = crate::sim::population::MAX_OBJECTS;
    if settings.objects == 0 || settings.objects > max {
        return Err(Error::input(format!("--objects {}: must be in [1, {max}]", settings.objects)));
    }
    if !(settings.hours.is_finite() && settings.hours > 0.0 && settings.hours <= MAX_HOURS) {
        return Err(Error::input(format!("--hours {}: must be in (0, {MAX_HOURS}]", settings.hours)));
    }
    let threads = match settings.threads {
        Some(0) => return Err(Error::input("--threads 0: must be at least 1")),
        Some(t) => t,
        None => std::thread::available_parallelism().map_or(1, usize::from),
    };
    std::fs::create_dir_all(dir).map_err(|e| Error::output(dir, e))?;
    let started = Instant::now();
    let epoch = crate::io::catalogue::parse_omm_epoch(START).ok_or_else(|| Error::internal("start"))?;
    let epoch_jd = crate::sim::time::parse_iso8601(START).map_err(|e| Error::internal(format!("start: {e}")))?;
    let catalogue = crate::sim::population::synthetic_catalogue(settings.objects, settings.seed, epoch, epoch_jd)
        .map_err(Error::input)?;
    // Cluster trackers hold their hypotheses inline: large stacks.
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .stack_size(256 << 20)
        .build()
        .map_err(|e| Error::internal(format!("thread pool: {e}")))?;
    pool.install(|| run_on(dir, settings, threads, catalogue.entries, started))
}

/// The experiment on `entries` (tests give catalogues of their own), on the current rayon pool.
pub(crate) fn run_on(
    dir: &Path,
    settings: &Settings,
    threads: usize,
    entries: Vec<crate::io::catalogue::CatalogueEntry>,
    started: Instant,
) -> Result<ScaleReport, Error> {
    let mut world = world::World::new(entries, settings.hours, settings.seed)?;
    let mut scenario = world.scenario()?;
    scenario.tracker.selection = match settings.weight_floor_decades {
        Some(decades) => SelectionSpec::TopWeightWithin { decades },
        None => SelectionSpec::TopWeight,
    };
    scenario.tracker.lost_after_unseen_scans = settings.lost_after_unseen_scans.and_then(core::num::NonZeroU16::new);
    let (config, prior) = config3d::<Radars, 3, { CLUSTER.birth_cells }>(&scenario, TrackerKind::Rfisst)?;
    let objects = prior.first().map(|(_, o)| o.as_slice()).unwrap_or(&[]);
    let mut tracker = Partitioned::<Radars, 3>::new(config, objects, scenario.prior.time, 0.0)
        .map_err(|e| Error::input(format!("partitioned tracker: {e}")))?;
    if !settings.step_every_cluster {
        tracker = tracker.with_view_skip(ground_closing_speed);
    }
    let known: Vec<bool> = {
        let mut known = vec![false; world.objects()];
        objects.iter().for_each(|o| known[o.label.0 as usize] = true);
        known
    };
    let births = (0..world.objects()).filter(|&i| !known[i]).map(|i| i as u64).collect();
    let prior_labels = objects.iter().map(|o| o.label.0).collect();
    let mut score = Score::new(scenario.evaluation, births, prior_labels);
    let (mut figures, mut rejected, mut clusters_max, mut largest) = (vec![], 0usize, 0usize, 0usize);
    let (mut merges_declined, mut lost_tracks) = (0, 0);
    let mut rss_by_hour = vec![];
    let last = world.scans() - 1;
    for k in 0..=last {
        let scan = world.scan(k)?;
        score.detected(k, scan.time, &scan.detected);
        let geometry = ScanGeometry { sensor: scan.sensor, time: scan.time, observer: None };
        let (step_started, cpu_started) = (Instant::now(), cpu_time_ns());
        let stepped = tracker.step(&geometry, &scan.measurements);
        let ms = step_started.elapsed().as_secs_f64() * 1e3;
        let cpu_ms = cpu_started.zip(cpu_time_ns()).map(|(a, b)| b.saturating_sub(a) as f64 / 1e6);
        let (mut stepped_clusters, mut coasted) = (0, 0);
        match stepped {
            Ok(report) => {
                clusters_max = clusters_max.max(report.clusters);
                largest = largest.max(report.largest_cluster);
                merges_declined += report.merges_declined;
                lost_tracks += report.lost_tracks;
                stepped_clusters = report.clusters.saturating_sub(report.skipped);
                coasted = report.coasted;
            }
            Err(e) => {
                rejected += 1;
                if rejected <= WARNING_LINES {
                    eprintln!("warning: scan {k} (t = {} s, sensor {}) refused: {e}", scan.time, scan.sensor);
                }
            }
        }
        let m = scan.measurements.len();
        let (sensor, in_view) = (scan.sensor, scan.in_view);
        figures.push(ScanFigures { sensor, in_view, measurements: m, ms, stepped: stepped_clusters, coasted, cpu_ms });
        if score.due(scan.time) || k == last {
            score.score(k, scan.time, &scan.truth, &posterior_at(&tracker, scan.time));
        }
        // The resident memory at each simulated hour (the first scan of the hour).
        if scan.time - scenario.prior.time >= 3600.0 * rss_by_hour.len() as f64 {
            rss_by_hour.push(resident_kib().map_or(f64::NAN, |kib| kib as f64 / 1024.0));
        }
        if !settings.quiet && (k + 1) % (last / 10).max(1) == 0 {
            eprintln!("catalogue-scale: scan {} of {}, {} clusters", k + 1, last + 1, tracker.clusters().len());
        }
    }
    if rejected > WARNING_LINES {
        eprintln!("warning: {} more scans refused (rejected_scans in scale.json)", rejected - WARNING_LINES);
    }
    let sizes: Vec<usize> = tracker.clusters().iter().map(|c| c.rest.labels().len()).collect();
    plot(dir, &world.sensors, &figures, &sizes)?;
    let outcome = Outcome {
        figures,
        rejected,
        merges_declined,
        lost_tracks,
        clusters_max,
        largest,
        digest: tracker.digest(),
        dropped: world.dropped,
        rss_by_hour,
    };
    let report = report(settings, threads, world.tracked(), &outcome, &score, started);
    write_json(&dir.join("scale.json"), &report)?;
    Ok(report)
}

/// What the scan loop leaves for the report.
struct Outcome {
    figures: Vec<ScanFigures>,
    rejected: usize,
    merges_declined: usize,
    lost_tracks: usize,
    clusters_max: usize,
    largest: usize,
    digest: u64,
    dropped: usize,
    /// Resident memory (MiB) at the first scan of each simulated hour.
    rss_by_hour: Vec<f64>,
}

/// The 99th percentile (nearest rank) of `values`.
fn p99(values: &[f64]) -> f64 {
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    let rank = ((0.99 * sorted.len() as f64).ceil() as usize).clamp(1, sorted.len().max(1));
    sorted.get(rank - 1).copied().unwrap_or(0.0)
}

fn report(
    settings: &Settings,
    threads: usize,
    objects: usize,
    outcome: &Outcome,
    score: &Score,
    started: Instant,
) -> ScaleReport {
    let f = &outcome.figures;
    let ms: Vec<f64> = f.iter().map(|s| s.ms).collect();
    let wall_s = ms.iter().sum::<f64>() / 1e3;
    let scored = score.figures();
    let cpu_ms: Option<Vec<f64>> = f.iter().map(|s| s.cpu_ms).collect();
    let c = CLUSTER;
    ScaleReport {
        objects,
        scans: f.len(),
        observations: f.iter().map(|s| s.measurements).sum(),
        hours: settings.hours,
        threads,
        wall_s,
        realtime_factor: settings.hours * 3600.0 / wall_s.max(1e-9),
        peak_rss_mib: peak_resident_kib().map(|kib| kib as f64 / 1024.0),
        ms_per_scan_mean: crate::experiments::common::mean(&ms),
        ms_per_scan_p99: p99(&ms),
        ms_per_scan_max: ms.iter().copied().fold(0.0, f64::max),
        cpu_s: cpu_ms.as_ref().map(|c| c.iter().sum::<f64>() / 1e3),
        cpu_ms_per_scan_mean: cpu_ms.as_ref().map(|c| crate::experiments::common::mean(c)),
        cpu_ms_per_scan_p99: cpu_ms.as_ref().map(|c| p99(c)),
        clusters_max: outcome.clusters_max,
        largest_cluster: outcome.largest,
        births_total: scored.births_total,
        births_confirmed: scored.births_confirmed,
        false_tracks: scored.false_tracks,
        mean_gospa: scored.mean_gospa,
        observed_objects: scored.observed.observed_objects,
        observed_median_error_km: scored.observed.observed_median_error_km,
        unobserved_median_error_km: scored.observed.unobserved_median_error_km,
        label_switches: scored.label_switches,
        dropped_objects: outcome.dropped,
        objects_in_view_mean: crate::experiments::common::mean(&f.iter().map(|s| s.in_view as f64).collect::<Vec<_>>()),
        objects_in_view_max: f.iter().map(|s| s.in_view).max().unwrap_or(0),
        observations_max: f.iter().map(|s| s.measurements).max().unwrap_or(0),
        rejected_scans: outcome.rejected,
        merges_declined: outcome.merges_declined,
        lost_tracks: outcome.lost_tracks,
        scored_scans: scored.scored_scans,
        total_wall_s: started.elapsed().as_secs_f64(),
        digest: format!("{:016x}", outcome.digest),
        profile: format!("{}/{}/{}/{}/{}", c.hypotheses, c.objects, c.measurements, c.tracks, c.birth_cells),
        seed: settings.seed,
        view_skip: !settings.step_every_cluster,
        weight_floor_decades: settings.weight_floor_decades,
        lost_after_unseen_scans: settings.lost_after_unseen_scans,
        clusters_stepped_mean: crate::experiments::common::mean(
            &f.iter().map(|s| s.stepped as f64).collect::<Vec<_>>(),
        ),
        clusters_coasted_mean: crate::experiments::common::mean(
            &f.iter().map(|s| s.coasted as f64).collect::<Vec<_>>(),
        ),
        rss_mib_by_hour: outcome.rss_by_hour.clone(),
    }
}

/// The cost per scan against the objects in view (a colour per sensor) and the cluster sizes.
fn plot(
    dir: &Path,
    sensors: &[crate::sim::sensor::SensorSpec],
    figures: &[ScanFigures],
    sizes: &[usize],
) -> Result<(), Error> {
    let series: Vec<Series> = sensors
        .iter()
        .enumerate()
        .map(|(s, spec)| Series {
            name: spec.name.clone(),
            points: figures.iter().filter(|f| f.sensor == s).map(|f| (f.in_view as f64, f.ms)).collect(),
            markers: true,
        })
        .collect();
    let title = format!("Cost per scan against the objects in view ({} scans)", figures.len());
    plots::scatter(
        &dir.join("cost_per_scan"),
        &title,
        "objects in the sensor's field of view",
        "ms per scan",
        &series,
    )?;
    let mut counts: BTreeMap<u64, u64> = BTreeMap::new();
    for &size in sizes {
        *counts.entry(size as u64).or_default() += 1;
    }
    let counts: Vec<(u64, u64)> = counts.into_iter().collect();
    let title = format!("Cluster sizes after the last scan ({} clusters)", sizes.len());
    Ok(plots::histogram(&dir.join("cluster_sizes"), &title, "objects in the cluster", "clusters", &counts)?)
}
