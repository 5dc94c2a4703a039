//! Property tests of the 3-D tracker (issue 17): invariants of every scan of a small radar tracker
//! (`Tracker<T, TwoBodyJ2<T>, SensorNetwork<T, RadarRangeAzEl<T>, 3, 2>, 6, 3, 8, 8, 8, 32, 1>`: a ground
//! radar and a spacecraft radar) in f64 and f32, over random scans.
//!
//! A case: one to three LEO objects near a circular orbit 800 km above the ground radar, a child
//! generation (exhaustive or sampled), a seed, and six scans. A scan names a random sensor (the two, the
//! next index or `usize::MAX`), a random time step (1 to 600 s; sometimes 0 or beyond the integrator's
//! 40,000 s bound), a random observer (none, on a LEO orbit, inside the Earth, NaN) and up to four
//! measurements: an object's true measurement plus noise, or a random look (range, azimuth, elevation)
//! inside or outside the sensor's field of view. After every successful scan:
//!
//! - weights are finite, non-negative and sum to 1 within 1e-9 (f64) or 1e-4 (f32);
//! - every track covariance is finite, exactly symmetric and positive definite (a Cholesky factor, no
//!   jitter);
//! - at most H hypotheses and K tracks.
//!
//! Every failed scan leaves `digest()` and `fingerprint()` unchanged, and fails for the reason its draw
//! predicts (time, sensor, observer, or a measurement outside the field of view). Two runs of the same
//! case give the same digests. The seed is fixed, so the cases are the same on every run.

use conformance::fingerprint;
use nalgebra::{SMatrix, SVector};
use proptest::prelude::*;
use proptest::test_runner::{Config as ProptestConfig, RngSeed};
use tracker_core::config::ChildGeneration;
use tracker_core::model::{
    EARTH_J2, EARTH_MIN_RADIUS, EARTH_MU, EARTH_RADIUS, Measure, MotionModel, ProcessNoise, SensorNetwork,
};
use tracker_core::sampler::SamplerConfig;
use tracker_core::sensor::{EarthRotation, GroundSite, Placement, PlacementError, Platform, ScanGeometry, SiteSensor};
use tracker_core::{
    BirthModel, Config, Gaussian, LookShape, PriorHypothesis, PriorObject, RadarRangeAzEl, Real, Region, Sensor,
    StepError, TrackLabel, Tracker, TwoBodyJ2,
};

const DEGREE: f64 = core::f64::consts::PI / 180.0;
const H: usize = 8;
const K: usize = 32;
const SCANS: usize = 6;
const BOUND: f64 = 40_000.0;

type Radars<T> = SensorNetwork<T, RadarRangeAzEl<T>, 3, 2>;
type Small3d<T> = Tracker<T, TwoBodyJ2<T>, Radars<T>, 6, 3, H, 8, 8, K, 1>;

const SITE: GroundSite<f64> = GroundSite { latitude: 40.0 * DEGREE, longitude: -105.0 * DEGREE, height: 0.2 };
const ROTATION: f64 = 0.3;
const GROUND_MAX_RANGE: f64 = 4000.0;

fn c<T: Real>(x: f64) -> T {
    T::of_f64(x)
}

fn network<T: Real>() -> Radars<T> {
    let radar = |platform, half_angle: f64, min_elevation: f64, max_range: f64| SiteSensor {
        platform,
        sigma: [c(0.02), c(0.02 * DEGREE), c(0.02 * DEGREE)],
        detection: Sensor {
            detection_probability: c(0.9),
            clutter_rate: c(1.0),
            field_of_view: Region::Look {
                shape: LookShape::Cone { azimuth: c(0.0), elevation: c(90.0 * DEGREE), half_angle: c(half_angle) },
                min_elevation: c(min_elevation),
                range: Some([c(0.0), c(max_range)]),
                range_rate: None,
            },
        },
    };
    let ground = Platform::Ground(GroundSite {
        latitude: c(SITE.latitude),
        longitude: c(SITE.longitude),
        height: c(SITE.height),
    });
    let sensors = [
        radar(ground, 80.0 * DEGREE, 5.0 * DEGREE, GROUND_MAX_RANGE),
        radar(Platform::Spacecraft, 180.0 * DEGREE, -90.0 * DEGREE, 20_000.0),
    ];
    SensorNetwork::new(EarthRotation::new(c(ROTATION)), &sensors).unwrap()
}

fn motion<T: Real>() -> TwoBodyJ2<T> {
    TwoBodyJ2 {
        mu: c(EARTH_MU),
        j2: c(EARTH_J2),
        radius: c(EARTH_RADIUS),
        min_radius: c(EARTH_MIN_RADIUS),
        noise: ProcessNoise::Isotropic(c(1e-10)),
        max_step: c(20.0),
        max_substeps: 2000,
    }
}

/// A circular LEO object 800 km above the site at t = 0 moving East, shifted by `offset` (km, km/s).
fn object(offset: &([f64; 3], [f64; 3])) -> SVector<f64, 6> {
    let rotation = EarthRotation::new(ROTATION);
    let observer = SITE.observer(&rotation, 0.0);
    let [east, _, up] = SITE.enu(&rotation, 0.0);
    let p: [f64; 3] = core::array::from_fn(|k| observer[k] + 800.0 * up[k] + offset.0[k]);
    let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
    let speed = (EARTH_MU / r).sqrt();
    let v: [f64; 3] = core::array::from_fn(|k| speed * east[k] + offset.1[k]);
    SVector::from([p[0], p[1], p[2], v[0], v[1], v[2]])
}

#[derive(Debug, Clone)]
enum TimeDraw {
    Step(f64),
    Zero,
    BeyondBound,
}

#[derive(Debug, Clone)]
enum ObserverDraw {
    /// What the sensor needs: none for the ground radar, a LEO orbit at this phase for the spacecraft.
    Matching(f64),
    None,
    Orbit(f64),
    Inside([f64; 3]),
    NonFinite(usize),
}

#[derive(Debug, Clone)]
enum MeasurementDraw {
    /// Object `k`'s measurement plus noise (in σ units).
    Object(usize, [f64; 3]),
    /// A look (range, azimuth, elevation), inside the field of view or not.
    Look([f64; 3]),
}

#[derive(Debug, Clone)]
struct ScanDraw {
    sensor: usize,
    time: TimeDraw,
    observer: ObserverDraw,
    measurements: Vec<MeasurementDraw>,
}

#[derive(Debug, Clone)]
struct Case {
    objects: Vec<([f64; 3], [f64; 3])>,
    sampled: bool,
    seed: u64,
    scans: Vec<ScanDraw>,
}

fn scan_draw() -> impl Strategy<Value = ScanDraw> {
    let sensor = prop_oneof![14 => 0..2usize, 1 => Just(2usize), 1 => Just(usize::MAX)];
    let time = prop_oneof![
        14 => (1.0..60.0f64).prop_map(TimeDraw::Step),
        2 => (60.0..3000.0f64).prop_map(TimeDraw::Step),
        1 => Just(TimeDraw::Zero),
        1 => Just(TimeDraw::BeyondBound),
    ];
    let observer = prop_oneof![
        12 => (0.0..6.3f64).prop_map(ObserverDraw::Matching),
        1 => Just(ObserverDraw::None),
        1 => (0.0..6.3f64).prop_map(ObserverDraw::Orbit),
        1 => prop::array::uniform3(-6000.0..6000.0f64).prop_map(ObserverDraw::Inside),
        1 => (0..6usize).prop_map(ObserverDraw::NonFinite),
    ];
    let measurement = prop_oneof![
        6 => (0..3usize, prop::array::uniform3(-3.0..3.0f64)).prop_map(|(k, n)| MeasurementDraw::Object(k, n)),
        1 => (0.0..4500.0f64, -3.2..3.2f64, -0.1..1.6f64).prop_map(|(r, a, e)| MeasurementDraw::Look([r, a, e])),
    ];
    (sensor, time, observer, prop::collection::vec(measurement, 0..=4))
        .prop_map(|(sensor, time, observer, measurements)| ScanDraw { sensor, time, observer, measurements })
}

fn case() -> impl Strategy<Value = Case> {
    let offset = (prop::array::uniform3(-20.0..20.0f64), prop::array::uniform3(-0.02..0.02f64));
    (prop::collection::vec(offset, 1..=3), any::<bool>(), any::<u64>(), prop::collection::vec(scan_draw(), SCANS))
        .prop_map(|(objects, sampled, seed, scans)| Case { objects, sampled, seed, scans })
}

fn tracker<T: Real>(case: &Case) -> Box<Small3d<T>> {
    let measurement = network::<T>();
    let config = Config {
        motion: motion(),
        measurement,
        sensor: measurement.sensors()[0].detection,
        birth: BirthModel::none(),
        death_probability: c(0.01),
        gate: Some(c(25.0)),
        children: if case.sampled {
            ChildGeneration::Sampled(SamplerConfig::default())
        } else {
            ChildGeneration::Exhaustive { max_children_per_scan: 100_000 }
        },
        selection: Default::default(),
        store_overflow: Default::default(),
        numerical_failure: Default::default(),
        track_loss: Default::default(),
        seed: case.seed,
    };
    let mut covariance = SMatrix::<T, 6, 6>::zeros();
    for k in 0..3 {
        covariance[(k, k)] = c(0.25);
        covariance[(k + 3, k + 3)] = c(1e-4);
    }
    let objects: Vec<PriorObject<T, 6>> = case
        .objects
        .iter()
        .enumerate()
        .map(|(k, o)| PriorObject {
            label: TrackLabel(k as u32),
            state: Gaussian { mean: object(o).map(c::<T>), covariance },
        })
        .collect();
    Box::new(Small3d::<T>::new(config, &[PriorHypothesis { weight: T::one(), objects: &objects }], 0.0).unwrap())
}

fn observer<T: Real>(sensor: usize, draw: &ObserverDraw) -> Option<[T; 6]> {
    match *draw {
        ObserverDraw::Matching(_) if sensor == 0 => None,
        ObserverDraw::None => None,
        ObserverDraw::Orbit(phase) | ObserverDraw::Matching(phase) => {
            let (s, co) = phase.sin_cos();
            let (r, speed) = (7200.0, (EARTH_MU / 7200.0).sqrt());
            Some([r * co, r * s, 0.0, -speed * s, speed * co, 0.0].map(c::<T>))
        }
        ObserverDraw::Inside(p) => {
            // Within 6350 km of the centre: inside the ellipsoid (polar radius 6356.75 km).
            let norm = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt().max(6000.0);
            let scale = 6350.0 / norm;
            Some([p[0] * scale, p[1] * scale, p[2] * scale, 0.0, 0.0, 0.0].map(c::<T>))
        }
        ObserverDraw::NonFinite(k) => {
            let mut state = [7000.0, 0.0, 0.0, 0.0, 7.5, 0.0];
            state[k] = f64::NAN;
            Some(state.map(c::<T>))
        }
    }
}

/// The error the draw's time and geometry must give, in `place_scan`'s order; `None` when they are valid.
fn expected_error(scan: &ScanDraw) -> Option<StepError> {
    match scan.time {
        TimeDraw::Zero => return Some(StepError::TimeNotAfterLastScan),
        TimeDraw::BeyondBound => return Some(StepError::TimeStepTooLong { limit_seconds: BOUND as u64 }),
        TimeDraw::Step(_) => {}
    }
    let placement = match (scan.sensor, &scan.observer) {
        (sensor @ 2.., _) => PlacementError::UnknownSensor { sensor, sensors: 2 },
        (0, ObserverDraw::None | ObserverDraw::Matching(_)) => return None,
        (0, _) => PlacementError::UnexpectedObserver,
        (_, ObserverDraw::None) => PlacementError::MissingObserver,
        (_, ObserverDraw::NonFinite(_)) => PlacementError::NonFiniteObserver,
        (_, ObserverDraw::Inside(_)) => PlacementError::ObserverInsideEarth,
        (_, ObserverDraw::Orbit(_) | ObserverDraw::Matching(_)) => return None,
    };
    Some(StepError::Placement(placement))
}

fn check_invariants<T: Real>(t: &Small3d<T>) -> Result<(), TestCaseError> {
    let tolerance = if core::mem::size_of::<T>() == 8 { 1e-9 } else { 1e-4 };
    let count = t.hypotheses().len();
    prop_assert!((1..=H).contains(&count), "{} hypotheses", count);
    prop_assert!(t.tracks().len() <= K);
    let mut total = 0.0;
    for h in t.hypotheses() {
        let w = h.weight().as_f64();
        prop_assert!(w.is_finite() && w >= 0.0, "weight {}", w);
        total += w;
    }
    prop_assert!((total - 1.0).abs() <= tolerance, "weights sum to {}", total);
    for track in t.tracks() {
        let p = &track.state.covariance;
        prop_assert!(track.state.mean.iter().chain(p.iter()).all(|v| v.is_finite_value()), "{:?}", track.state);
        prop_assert_eq!(*p, p.transpose(), "covariance not symmetric");
        prop_assert!(p.map(|v| v.as_f64()).cholesky().is_some(), "covariance not positive definite: {:?}", p);
    }
    Ok(())
}

/// Runs the case; returns the digest after every scan.
fn run<T: Real>(case: &Case) -> Result<Vec<u64>, TestCaseError> {
    let mut t = tracker::<T>(case);
    let true_motion = motion::<f64>();
    let mut truth: Vec<SVector<f64, 6>> = case.objects.iter().map(object).collect();
    let mut digests = vec![t.digest()];
    let mut time = 0.0;
    for scan in &case.scans {
        let dt = match scan.time {
            TimeDraw::Step(dt) => dt,
            TimeDraw::Zero => 0.0,
            TimeDraw::BeyondBound => BOUND + 1.0,
        };
        let geometry =
            ScanGeometry { sensor: scan.sensor, time: time + dt, observer: observer::<T>(scan.sensor, &scan.observer) };
        let moved: Vec<SVector<f64, 6>> = match scan.time {
            TimeDraw::Step(dt) => truth.iter().map(|x| true_motion.propagate(x, dt).unwrap().state).collect(),
            _ => truth.clone(),
        };
        let placed = t.config().measurement.place(&geometry).ok();
        let sigma = [0.02, 0.02 * DEGREE, 0.02 * DEGREE];
        let measurements: Vec<SVector<T, 3>> = scan
            .measurements
            .iter()
            .map(|m| match (m, &placed) {
                (MeasurementDraw::Object(k, noise), Some(placed)) => {
                    let exact = placed.measure(&moved[k % moved.len()].map(c::<T>));
                    SVector::from(core::array::from_fn(|i| exact[i] + c::<T>(noise[i] * sigma[i])))
                }
                (MeasurementDraw::Look(look), _) => SVector::from(look.map(c::<T>)),
                (MeasurementDraw::Object(..), None) => SVector::from([c(1000.0), c(0.0), c(0.5)]),
            })
            .collect();
        let before = (t.digest(), fingerprint(&*t));
        match t.step_scan(&geometry, &measurements) {
            Ok(_) => {
                prop_assert_eq!(expected_error(scan), None, "accepted a bad scan {:?}", scan);
                check_invariants(&*t)?;
                time += dt;
                truth = moved;
            }
            Err(error) => {
                prop_assert_eq!((t.digest(), fingerprint(&*t)), before, "state changed after {:?}", error);
                match expected_error(scan) {
                    Some(expected) => prop_assert_eq!(error, expected),
                    // A valid geometry fails only for a measurement outside the field of view.
                    None => prop_assert!(
                        matches!(error, StepError::MeasurementOutsideFieldOfView { .. }),
                        "{:?} on {:?}",
                        error,
                        scan
                    ),
                }
            }
        }
        digests.push(t.digest());
    }
    Ok(digests)
}

fn config() -> ProptestConfig {
    ProptestConfig { cases: 24, rng_seed: RngSeed::Fixed(13), failure_persistence: None, ..ProptestConfig::default() }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn every_3d_scan_keeps_the_invariants_f64(case in case()) {
        let first = run::<f64>(&case)?;
        prop_assert_eq!(run::<f64>(&case)?, first, "not deterministic");
    }

    #[test]
    fn every_3d_scan_keeps_the_invariants_f32(case in case()) {
        let first = run::<f32>(&case)?;
        prop_assert_eq!(run::<f32>(&case)?, first, "not deterministic");
    }
}
