//! `host-sim soak`: a long run with objects entering and leaving, through the default embedded tracker.
//!
//! The scenario is paper 003's SSA geometry, generated scan by scan (nothing of the truth is kept beyond
//! the objects alive now): planar two-body orbits from LEO to MEO with white acceleration noise, the
//! sensor at the Earth's centre looking 15° above +x with a 30° field of view out to 30,000 km, p_D = 0.95,
//! one clutter return per scan, a scan every 60 s. It starts with [`INITIAL_OBJECTS`] objects known to the
//! prior; every scan a new object is born inside the field of view with probability [`BIRTH_RATE`], and
//! every object dies with probability [`DEATH_RATE`], so about `BIRTH_RATE / DEATH_RATE` objects are alive
//! in the steady state and each lives about 1 / `DEATH_RATE` scans.
//!
//! The tracker is tracker-core's [`SsaTracker<f64>`] (the embedded capacities [`tracker_core::ssa_caps`])
//! with R-FISST's sampled children and the default [`SamplerConfig`], the fifty-object preset's birth
//! cells (α = 10⁻³ each) and β = 10⁻⁴. After every scan the soak counts non-finite values in every weight,
//! mean, covariance and existence probability, and every `StepError` by kind; it reports the largest and
//! mean time per scan, the largest number of hypotheses and the track store's high-water mark, and how far
//! the expected number of objects is from the truth.
//!
//! # Capacities are checked at compile time
//!
//! A tracker with a zero capacity does not compile (`CAPACITY_CHECK` in tracker-core's tracker.rs, a
//! constant evaluation error E0080):
//!
//! ```compile_fail,E0080
//! use tracker_core::{BirthModel, ChildGeneration, Config, ConstantVelocity, LinearTracker};
//! use tracker_core::{PositionMeasurement, Region, Sensor, StoreOverflow};
//! let config = Config {
//!     motion: ConstantVelocity { acceleration_noise: 0.1 },
//!     measurement: PositionMeasurement::isotropic(0.5),
//!     sensor: Sensor { detection_probability: 0.9, clutter_rate: 1.0, field_of_view: Region::Everywhere { volume: 1.0 } },
//!     birth: BirthModel::none(),
//!     death_probability: 0.0,
//!     gate: None,
//!     children: ChildGeneration::default(),
//!     selection: Default::default(),
//!     store_overflow: StoreOverflow::default(),
//!     numerical_failure: Default::default(),
//!     track_loss: Default::default(),
//!     seed: 1,
//! };
//! // H = 0 hypotheses.
//! let _ = LinearTracker::<f64, 0, 1, 1, 1, 0>::with_objects(config, &[], 0.0);
//! ```
//!
//! while the same code with the smallest non-zero capacities compiles and runs:
//!
//! ```
//! use tracker_core::{BirthModel, ChildGeneration, Config, ConstantVelocity, LinearTracker};
//! use tracker_core::{PositionMeasurement, Region, Sensor, StoreOverflow};
//! let config = Config {
//!     motion: ConstantVelocity { acceleration_noise: 0.1 },
//!     measurement: PositionMeasurement::isotropic(0.5),
//!     sensor: Sensor { detection_probability: 0.9, clutter_rate: 1.0, field_of_view: Region::Everywhere { volume: 1.0 } },
//!     birth: BirthModel::none(),
//!     death_probability: 0.0,
//!     gate: None,
//!     children: ChildGeneration::default(),
//!     selection: Default::default(),
//!     store_overflow: StoreOverflow::default(),
//!     numerical_failure: Default::default(),
//!     track_loss: Default::default(),
//!     seed: 1,
//! };
//! assert!(LinearTracker::<f64, 1, 1, 1, 1, 0>::with_objects(config, &[], 0.0).is_ok());
//! ```

use super::common::{MAX_SCANS, Scenario, non_finite_values};
use super::run::{SoakWorld, WorldParts, soak};
use crate::error::Error;
use crate::io::report::{SoakReport, SoakSetup, SoakTruth};
use crate::pipeline::planar::setup;
use crate::pipeline::profile::PLANAR;
use crate::scenario::FieldOfViewSpec;
use crate::sim::planar::{self, EARTH_MU, Orbit};
use crate::sim::rng::{Random, Stream};
use nalgebra::{SMatrix, SVector};
use std::time::Instant;
use tracker_core::sampler::SamplerConfig;
use tracker_core::{
    BirthDetection, BirthModel, ChildGeneration, Config, Gaussian, PositionMeasurement, PriorObject, SsaConfig,
    SsaTracker, StepError, StepReport, StoreOverflow, TrackLabel, ssa_caps,
};

/// Objects known to the prior.
pub const INITIAL_OBJECTS: usize = 20;
/// Probability of a birth per scan.
pub const BIRTH_RATE: f64 = 2e-3;
/// Probability that a given object dies, per scan.
pub const DEATH_RATE: f64 = 1e-4;
/// Seconds between scans.
pub const SCAN_INTERVAL: f64 = 60.0;
/// Measurement noise standard deviation (km).
const SIGMA: f64 = 0.5;

/// One true object, alive now.
struct Object {
    id: u64,
    state: [f64; 4],
    motion: Random,
    detection: Random,
}

impl Object {
    fn new(seed: u64, id: u64, orbit: Orbit) -> Self {
        Object {
            id,
            state: orbit.state(EARTH_MU),
            motion: Random::stream(seed, Stream::Motion, id),
            detection: Random::stream(seed, Stream::Detection, id),
        }
    }
}

/// The position of a planar state.
fn position(state: &[f64; 4]) -> SVector<f64, 2> {
    SVector::from([state[0], state[1]])
}

/// A random LEO-MEO orbit whose position at the epoch is inside the field of view, 2° from its edges.
fn orbit_in_view(random: &mut Random) -> Orbit {
    let mut orbit = planar::random_orbit(random, 6_878.0, 26_560.0, 0.02);
    orbit.true_anomaly = random.between(2.0, 28.0).to_radians() - orbit.periapsis;
    orbit
}

/// The tracker's birth probability per cell.
const TRACKER_BIRTH_PROBABILITY: f64 = 1e-3;
/// The tracker's death probability.
const TRACKER_DEATH_PROBABILITY: f64 = 1e-4;

/// The soak's tracker (the embedded capacities) and the number of its birth cells.
fn tracker(seed: u64, alive: &[Object]) -> Result<(Box<SsaTracker<f64>>, usize), Error> {
    let sensor = planar::ssa_sensor(0.95, 1.0, 30_000.0);
    let two_body =
        setup::two_body(&planar::ssa_motion()).ok_or_else(|| Error::internal("soak: the motion is two-body"))?;
    let cells = planar::ssa_birth_cells(&sensor, 6_600.0, 30_000.0, 8, 0.3);
    let mut birth = BirthModel::none();
    birth.probability = TRACKER_BIRTH_PROBABILITY;
    birth.detection = BirthDetection::AllDetected;
    for cell in &cells {
        birth
            .cells
            .push(setup::gaussian(&cell.mean, &cell.covariance))
            .map_err(|_| Error::internal("soak: too many birth cells"))?;
    }
    let config: SsaConfig<f64> = Config {
        motion: two_body,
        measurement: PositionMeasurement::isotropic(SIGMA),
        sensor: setup::sensor(&sensor),
        birth,
        death_probability: TRACKER_DEATH_PROBABILITY,
        gate: Some(25.0),
        children: ChildGeneration::Sampled(SamplerConfig::default()),
        selection: tracker_core::config::Selection::TopWeight,
        store_overflow: StoreOverflow::PruneChildren,
        numerical_failure: Default::default(),
        track_loss: Default::default(),
        seed,
    };
    // The prior: the true states with a small error, as the presets do.
    let (sp, sv) = (1.0, 2e-4);
    let covariance = SMatrix::<f64, 4, 4>::from_diagonal(&SVector::from([sp * sp, sp * sp, sv * sv, sv * sv]));
    let prior: Vec<PriorObject<f64, 4>> = alive
        .iter()
        .map(|o| {
            let mut random = Random::stream(seed, Stream::Prior, o.id);
            let error = [sp * random.normal(), sp * random.normal(), sv * random.normal(), sv * random.normal()];
            let mean = SVector::from([0, 1, 2, 3].map(|i| o.state[i] + error[i]));
            PriorObject { label: TrackLabel(o.id as u32), state: Gaussian { mean, covariance } }
        })
        .collect();
    let hypothesis = [tracker_core::PriorHypothesis { weight: 1.0, objects: &prior }];
    let tracker =
        SsaTracker::<f64>::new(config, &hypothesis, 0.0).map_err(|e| Error::internal(format!("soak: tracker: {e}")))?;
    Ok((Box::new(tracker), cells.len()))
}

/// The true objects, generated scan by scan.
struct World {
    seed: u64,
    motion: crate::scenario::MotionSpec,
    sensor: crate::scenario::SensorSpec,
    fov: tracker_core::Region<f64>,
    noise: SMatrix<f64, 2, 2>,
    alive: Vec<Object>,
    next_id: u64,
    births: u64,
    deaths: u64,
    max_alive: usize,
}

impl World {
    /// The objects at t = 0, all known to the prior.
    fn new(seed: u64) -> Self {
        let sensor = planar::ssa_sensor(0.95, 1.0, 30_000.0);
        let alive: Vec<Object> = (0..INITIAL_OBJECTS as u64)
            .map(|id| {
                let orbit = planar::random_orbit(&mut Random::stream(seed, Stream::Orbit, id), 6_878.0, 26_560.0, 0.02);
                Object::new(seed, id, orbit)
            })
            .collect();
        World {
            seed,
            motion: planar::ssa_motion(),
            fov: setup::region(&sensor.field_of_view),
            sensor,
            noise: SMatrix::<f64, 2, 2>::identity() * (SIGMA * SIGMA),
            max_alive: alive.len(),
            alive,
            next_id: INITIAL_OBJECTS as u64,
            births: 0,
            deaths: 0,
        }
    }

    /// Scan `k`: deaths, the survivors move one interval, at most one birth placed in the field of view;
    /// returns the scan's measurements (detections and clutter, shuffled).
    fn scan(&mut self, k: u64) -> Vec<SVector<f64, 2>> {
        let seed = self.seed;
        let mut events = Random::stream(seed, Stream::Scenario, k);
        let before = self.alive.len();
        self.alive.retain(|_| events.uniform() >= DEATH_RATE);
        self.deaths += (before - self.alive.len()) as u64;
        for object in &mut self.alive {
            object.state = planar::move_object(&self.motion, object.state, SCAN_INTERVAL, &mut object.motion);
        }
        if events.uniform() < BIRTH_RATE {
            let orbit = orbit_in_view(&mut Random::stream(seed, Stream::Orbit, self.next_id));
            self.alive.push(Object::new(seed, self.next_id, orbit));
            self.next_id += 1;
            self.births += 1;
        }
        self.max_alive = self.max_alive.max(self.alive.len());
        let mut measurements: Vec<SVector<f64, 2>> = vec![];
        for object in &mut self.alive {
            // Draw the detection and the noise every scan, so that each object's stream stays aligned.
            let detected = object.detection.uniform() < self.sensor.detection_probability;
            let z = position(&object.state) + object.detection.gaussian(&self.noise);
            if detected && self.fov.contains(&position(&object.state)) && self.fov.contains(&z) {
                measurements.push(z);
            }
        }
        let mut clutter = Random::stream(seed, Stream::Clutter, k);
        for _ in 0..clutter.poisson(self.sensor.clutter_rate) {
            measurements.push(SVector::from(planar::uniform_in_region(&self.sensor.field_of_view, &mut clutter)));
        }
        events.shuffle(&mut measurements);
        measurements
    }
}

/// Runs `scans` scans of the soak scenario with `seed` and returns the report.
///
/// # Errors
/// [`Error::Input`] when `scans` is 0 or above [`MAX_SCANS`]; [`Error::Internal`] when the tracker cannot
/// be built (which would be a bug).
pub fn run(scans: u64, seed: u64, quiet: bool) -> Result<SoakReport, Error> {
    if !(1..=MAX_SCANS).contains(&scans) {
        return Err(Error::input(format!("--scans {scans}: must be in [1, {MAX_SCANS}]")));
    }
    let started = Instant::now();
    let world = World::new(seed);
    let (tracker, birth_cells) = tracker(seed, &world.alive)?;
    soak(PlanarSoak { world, tracker, birth_cells }, Scenario::Planar, scans, seed, quiet, started)
}

/// The planar world and its tracker, for the soak's loop.
struct PlanarSoak {
    world: World,
    tracker: Box<SsaTracker<f64>>,
    birth_cells: usize,
}

impl SoakWorld for PlanarSoak {
    type Scan = Vec<SVector<f64, 2>>;
    const HYPOTHESES: usize = ssa_caps::HYPOTHESES;
    const TRACKS: usize = ssa_caps::TRACKS;
    const MEASUREMENTS: usize = ssa_caps::MEASUREMENTS;

    fn draw(&mut self, k: u64) -> Result<Self::Scan, String> {
        Ok(self.world.scan(k))
    }

    fn measurement_count(scan: &Self::Scan) -> usize {
        scan.len()
    }

    fn step(&mut self, k: u64, scan: &Self::Scan) -> Result<StepReport<f64>, StepError> {
        self.tracker.step((k + 1) as f64 * SCAN_INTERVAL, scan)
    }

    fn non_finite_values(&self) -> u64 {
        non_finite_values(&*self.tracker)
    }

    fn expected_cardinality(&self) -> f64 {
        self.tracker.expected_cardinality()
    }

    fn objects(&self) -> usize {
        self.world.alive.len()
    }

    fn record(&mut self, _: u64, _: Self::Scan) {}

    fn finish(self) -> Result<WorldParts, Error> {
        let world = &self.world;
        Ok(WorldParts {
            objects_within_10km: None,
            mean_nees: None,
            tracking: None,
            truth: SoakTruth {
                initial_objects: INITIAL_OBJECTS,
                births: world.births,
                deaths: world.deaths,
                max_alive: world.max_alive,
                final_alive: world.alive.len(),
            },
            setup: setup_record(&world.sensor, self.birth_cells)?,
        })
    }
}

/// The scenario and tracker in words and numbers.
fn setup_record(sensor: &crate::scenario::SensorSpec, birth_cells: usize) -> Result<SoakSetup, Error> {
    let FieldOfViewSpec::Sector { field_of_view_deg, max_range, .. } = sensor.field_of_view else {
        return Err(Error::internal("soak: the SSA sensor is a sector"));
    };
    Ok(SoakSetup {
        tracker: format!(
            "tracker-core SsaTracker<f64> (H = {}, N = {}, Z = {}, K = {}, B = {}), R-FISST sampled children, default SamplerConfig",
            PLANAR.embedded.hypotheses,
            PLANAR.embedded.objects,
            PLANAR.embedded.measurements,
            PLANAR.embedded.tracks,
            PLANAR.embedded.birth_cells
        ),
        motion: "planar two-body, q = 1e-13 km^2/s^3, RK4 sub-steps of at most 20 s".into(),
        sensor: format!(
            "sector of {field_of_view_deg} deg to {max_range} km, p_D = {}, clutter {} per scan",
            sensor.detection_probability, sensor.clutter_rate
        ),
        scan_interval_s: SCAN_INTERVAL,
        birth_rate_per_scan: BIRTH_RATE,
        death_rate_per_object_per_scan: DEATH_RATE,
        tracker_birth_probability_per_cell: TRACKER_BIRTH_PROBABILITY,
        tracker_birth_cells: birth_cells,
        tracker_death_probability: TRACKER_DEATH_PROBABILITY,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    /// The figures that do not depend on timing.
    fn untimed(report: &SoakReport) -> serde_json::Value {
        let mut report = serde_json::to_value(report).unwrap();
        if let Some(object) = report.as_object_mut() {
            object.retain(|key, _| {
                !key.contains("ms_per_scan")
                    && !key.starts_with("peak_resident")
                    && !["wall_seconds", "max_over_median"].contains(&key.as_str())
            });
        }
        report
    }

    /// Runs `f` on a thread with the CLI worker's stack: the tracker holds several hundred KiB inline.
    fn with_large_stack(f: impl FnOnce() + Send + 'static) {
        std::thread::Builder::new().stack_size(512 << 20).spawn(f).unwrap().join().unwrap();
    }

    #[test]
    fn a_short_soak_is_healthy_and_deterministic() {
        with_large_stack(|| {
            let record = run(100, 4, true).unwrap();
            let report = serde_json::to_value(&record).unwrap();
            for key in ["scans", "nan_count", "max_hypotheses", "max_ms_per_scan", "errors_by_kind"] {
                assert!(report.get(key).is_some(), "{key} missing");
            }
            assert_eq!(report["scans"], 100);
            assert_eq!(report["nan_count"], 0);
            assert_eq!(report["errors_by_kind"], json!({}));
            let max_hypotheses = report["max_hypotheses"].as_u64().unwrap();
            assert!((1..=ssa_caps::HYPOTHESES as u64).contains(&max_hypotheses));
            assert_eq!(untimed(&run(100, 4, true).unwrap()), untimed(&record));
            assert_ne!(untimed(&run(100, 5, true).unwrap()), untimed(&record));
        });
    }

    #[test]
    fn zero_or_too_many_scans_is_an_error() {
        for scans in [0, MAX_SCANS + 1, u64::MAX] {
            assert!(matches!(run(scans, 1, true), Err(Error::Input(_))), "{scans}");
        }
    }
}
