//! The soak's scan loop and its report, written once over every world ([`SoakWorld`]): the world draws
//! scan after scan and steps its tracker on it; the loop times the steps, counts the tracker's health and
//! its cardinality error, and assembles the [`SoakReport`] with the world's own parts.

use super::common::{Health, ScanTimes, Scenario, progress};
use crate::error::Error;
use crate::io::report::{SoakError, SoakReport, SoakSetup, SoakTracking, SoakTruth};
use crate::pipeline::output::peak_resident_kib;
use std::time::Instant;
use tracker_core::{StepError, StepReport};

/// A world of the soak: the truth drawn scan by scan and the tracker that follows it.
pub(crate) trait SoakWorld {
    /// One drawn scan, in the tracker's units.
    type Scan;
    /// The tracker's hypothesis capacity H.
    const HYPOTHESES: usize;
    /// The tracker's track store capacity K.
    const TRACKS: usize;
    /// The tracker's measurement capacity Z.
    const MEASUREMENTS: usize;

    /// Draws scan `k` (0-based), or says why the simulation failed (a "Simulation" error of the report).
    fn draw(&mut self, k: u64) -> Result<Self::Scan, String>;
    /// The number of measurements of `scan`.
    fn measurement_count(scan: &Self::Scan) -> usize;
    /// Steps the tracker on scan `k`.
    fn step(&mut self, k: u64, scan: &Self::Scan) -> Result<StepReport<f64>, StepError>;
    /// The non-finite values in the tracker ([`super::common::non_finite_values`]).
    fn non_finite_values(&self) -> u64;
    /// The tracker's expected number of objects.
    fn expected_cardinality(&self) -> f64;
    /// The number of true objects now.
    fn objects(&self) -> usize;
    /// The world's own figures of scan `k`, after the step.
    fn record(&mut self, k: u64, scan: Self::Scan);
    /// The world's parts of the report, after the last scan.
    fn finish(self) -> Result<WorldParts, Error>;
}

/// The parts of a [`SoakReport`] only the world knows.
pub(crate) struct WorldParts {
    /// Objects within 10 km of the truth after the last scan (3-D soaks).
    pub(crate) objects_within_10km: Option<usize>,
    /// Mean NEES of the MAP tracks over the run (3-D soaks).
    pub(crate) mean_nees: Option<f64>,
    pub(crate) tracking: Option<SoakTracking>,
    pub(crate) truth: SoakTruth,
    pub(crate) setup: SoakSetup,
}

/// What the loop counts over the scans.
struct Counts {
    health: Health,
    times: ScanTimes,
    resident_start: Option<u64>,
    measurements: u64,
    cardinality_error: f64,
    max_cardinality_error: f64,
}

/// Runs `scans` scans of `world` (the soak `scenario` with `seed`, started at `started`) and returns the
/// report.
///
/// # Errors
/// As the world's [`SoakWorld::finish`].
pub(crate) fn soak<W: SoakWorld>(
    mut world: W,
    scenario: Scenario,
    scans: u64,
    seed: u64,
    quiet: bool,
    started: Instant,
) -> Result<SoakReport, Error> {
    let bar = progress(scans, quiet);
    let mut counts = Counts {
        health: Health::default(),
        times: ScanTimes::new(scans),
        resident_start: None,
        measurements: 0,
        cardinality_error: 0.0,
        max_cardinality_error: 0.0,
    };
    for k in 0..scans {
        let scan = match world.draw(k) {
            Ok(scan) => scan,
            Err(message) => {
                counts.health.error(k, "Simulation".into(), message);
                bar.inc(1);
                continue;
            }
        };
        let count = W::measurement_count(&scan);
        counts.health.max_measurements = counts.health.max_measurements.max(count);
        counts.measurements += count as u64;
        let step_started = Instant::now();
        let result = world.step(k, &scan);
        counts.times.record(k, step_started.elapsed().as_secs_f64() * 1e3);
        counts.health.record(k, result, world.non_finite_values());
        if k == 0 {
            counts.resident_start = peak_resident_kib();
        }
        let difference = (world.expected_cardinality() - world.objects() as f64).abs();
        counts.cardinality_error += difference;
        counts.max_cardinality_error = counts.max_cardinality_error.max(difference);
        world.record(k, scan);
        bar.inc(1);
    }
    bar.finish_and_clear();
    report(world, counts, scenario, scans, seed, started)
}

/// The report of a finished run.
fn report<W: SoakWorld>(
    world: W,
    counts: Counts,
    scenario: Scenario,
    scans: u64,
    seed: u64,
    started: Instant,
) -> Result<SoakReport, Error> {
    let Counts { health, times, resident_start, measurements, cardinality_error, max_cardinality_error } = counts;
    let (max_ms, mean_ms, p50_ms, p99_ms) = times.timing();
    let final_expected_cardinality = world.expected_cardinality();
    let WorldParts { objects_within_10km, mean_nees, tracking, truth, setup } = world.finish()?;
    Ok(SoakReport {
        scenario: scenario.name().into(),
        scans,
        seed,
        nan_count: health.non_finite,
        non_finite_scans: health.non_finite_scans,
        first_non_finite_scan: health.first_non_finite_scan,
        max_hypotheses: health.max_hypotheses,
        max_ms_per_scan: max_ms,
        mean_ms_per_scan: mean_ms,
        p50_ms_per_scan: p50_ms,
        p99_ms_per_scan: p99_ms,
        max_over_median: max_ms / p50_ms,
        mean_ms_per_scan_first_tenth: times.tenths().0,
        mean_ms_per_scan_last_tenth: times.tenths().1,
        peak_resident_kib_start: resident_start,
        // Linux updates its high-water mark lazily (VmHWM reads max(hiwater, RSS now)), so a later read can be
        // lower than an earlier one; the peak over the run is at least the one read after the first scan.
        peak_resident_kib_end: peak_resident_kib().map(|end| end.max(resident_start.unwrap_or(0))),
        numerical_drops: health.numerical_drops,
        objects_within_10km,
        mean_nees,
        tracking,
        errors_by_kind: health.errors,
        first_error: health.first_error.map(|(scan, message)| SoakError { scan, message }),
        track_store_high_water: health.max_tracks,
        track_store_capacity: W::TRACKS,
        hypothesis_capacity: W::HYPOTHESES,
        max_measurements_per_scan: health.max_measurements,
        measurement_capacity: W::MEASUREMENTS,
        measurements,
        births_beyond_object_capacity: health.births_beyond_capacity,
        children_dropped_for_store: health.children_dropped_for_store,
        truth,
        final_expected_cardinality,
        mean_abs_cardinality_error: cardinality_error / scans as f64,
        max_abs_cardinality_error: max_cardinality_error,
        wall_seconds: started.elapsed().as_secs_f64(),
        setup,
    })
}
