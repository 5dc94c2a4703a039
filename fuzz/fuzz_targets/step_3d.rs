//! Fuzz target `step_3d`: arbitrary scans through `Tracker::step_scan` on a small 3-D radar tracker
//! (two-body + J2 motion, a network of two ground radars and a spacecraft radar), in f64 and f32. Each
//! scan names any sensor index (valid, just past the last, `usize::MAX`), any time step (any f64 bits, or
//! a useful number of seconds), an observer state or none (near a LEO orbit, inside the Earth, any bits),
//! and up to Z + 2 measurements: near an object's true measurement, or any numbers.
//!
//! Checked on every input:
//! - nothing panics (a panic is a crash);
//! - a failed `step_scan` leaves the tracker unchanged: `digest()` and every track's existence are the
//!   same bits before and after;
//! - a successful one leaves a healthy posterior: 1 to H hypotheses, finite weights summing to 1, finite
//!   means, finite and exactly symmetric covariances, existence in [0, 1];
//! - replaying the same inputs on a fresh tracker gives the same digests (determinism).
#![no_main]

use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;
use nalgebra::{SMatrix, SVector};
use tracker_core::model::{
    EARTH_J2, EARTH_MIN_RADIUS, EARTH_MU, EARTH_RADIUS, Measure, MotionModel, ProcessNoise, SensorNetwork,
};
use tracker_core::sampler::SamplerConfig;
use tracker_core::sensor::{EarthRotation, GroundSite, Placement, Platform, ScanGeometry, SiteSensor};
use tracker_core::{
    BirthDetection, BirthModel, ChildGeneration, Config, Gaussian, LookShape, PriorHypothesis, PriorObject,
    RadarRangeAzEl, Real, Region, Sensor, TrackLabel, Tracker, TwoBodyJ2,
};

const H: usize = 8;
const N: usize = 4;
const Z: usize = 6;
const K: usize = 16;
const B: usize = 1;
const DEGREE: f64 = core::f64::consts::PI / 180.0;

type Radars<T> = SensorNetwork<T, RadarRangeAzEl<T>, 3, 3>;
type Fuzzed<T> = Tracker<T, TwoBodyJ2<T>, Radars<T>, 6, 3, H, N, Z, K, B>;

/// A number: any bits, or a value in a useful range, or a special value.
#[derive(Debug, Clone, Copy, Arbitrary)]
enum Num {
    /// Any f64 bit pattern.
    Bits(u64),
    /// In [-512, 512) in steps of 1/64.
    Small(i16),
    /// In [-1e6, 1e6).
    Wide(i32),
    /// 0, -0, 1, -1, NaN, ±inf, MAX, MIN_POSITIVE, subnormal, 1e-300, 1e300, EPSILON, MIN, 1e-30.
    Special(u8),
}

impl Num {
    fn value(self) -> f64 {
        const SPECIAL: [f64; 15] = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::MAX,
            f64::MIN_POSITIVE,
            5e-324,
            1e-300,
            1e300,
            f64::EPSILON,
            f64::MIN,
            1e-30,
        ];
        match self {
            Num::Bits(bits) => f64::from_bits(bits),
            Num::Small(i) => f64::from(i) / 64.0,
            Num::Wide(i) => f64::from(i) / 2048.0,
            Num::Special(k) => SPECIAL[usize::from(k) % SPECIAL.len()],
        }
    }
}

#[derive(Debug, Clone, Copy, Arbitrary)]
enum SensorIn {
    /// `index % 4`: the three sensors and the first index past them.
    Index(u8),
    /// `usize::MAX`.
    Max,
}

#[derive(Debug, Clone, Copy, Arbitrary)]
enum TimeIn {
    /// The last accepted time plus this many seconds.
    Seconds(u16),
    /// The last accepted time plus this.
    After(Num),
    /// This time.
    At(Num),
}

#[derive(Debug, Clone, Copy, Arbitrary)]
enum ObserverIn {
    None,
    /// On a 7000 km circular orbit at this phase (1/256 of a turn), plus a small offset.
    Orbit(u8, [i16; 3]),
    /// This position (km) from the Earth's centre, at rest: often inside the Earth.
    Position([i16; 3]),
    /// Any numbers.
    Raw([Num; 6]),
}

#[derive(Debug, Clone, Copy, Arbitrary)]
enum MeasurementIn {
    /// Object `object % objects`'s exact measurement from the scan's placed sensor plus a small offset
    /// (km, and 1e-4 rad per unit).
    Near(u8, [i8; 3]),
    /// Any numbers.
    Raw([Num; 3]),
}

#[derive(Debug, Clone, Arbitrary)]
struct Scan {
    sensor: SensorIn,
    time: TimeIn,
    observer: ObserverIn,
    measurements: Vec<MeasurementIn>,
}

#[derive(Debug, Clone, Arbitrary)]
struct Input {
    single_precision: bool,
    replay: bool,
    sampled: bool,
    birth: bool,
    seed: u64,
    /// Up to N objects: a circular LEO orbit above the first site, shifted (km) and sped up (m/s).
    objects: Vec<([i8; 3], [i8; 3])>,
    scans: Vec<Scan>,
}

const SITES: [GroundSite<f64>; 2] = [
    GroundSite { latitude: 40.0 * DEGREE, longitude: -105.0 * DEGREE, height: 0.2 },
    GroundSite { latitude: -30.0 * DEGREE, longitude: 20.0 * DEGREE, height: 1.0 },
];
const ROTATION: f64 = 0.3;

fn c<T: Real>(x: f64) -> T {
    T::of_f64(x)
}

fn network<T: Real>() -> Radars<T> {
    let radar = |platform: Platform<T>, half_angle: f64, max_range: f64| SiteSensor {
        platform,
        sigma: [c(0.02), c(0.02 * DEGREE), c(0.02 * DEGREE)],
        detection: Sensor {
            detection_probability: c(0.9),
            clutter_rate: c(1.0),
            field_of_view: Region::Look {
                shape: LookShape::Cone { azimuth: c(0.0), elevation: c(90.0 * DEGREE), half_angle: c(half_angle) },
                min_elevation: c(-90.0 * DEGREE),
                range: Some([c(0.0), c(max_range)]),
                range_rate: None,
            },
        },
    };
    let ground = |site: GroundSite<f64>| {
        Platform::Ground(GroundSite {
            latitude: c(site.latitude),
            longitude: c(site.longitude),
            height: c(site.height),
        })
    };
    let sensors = [
        radar(ground(SITES[0]), 80.0 * DEGREE, 4000.0),
        radar(ground(SITES[1]), 70.0 * DEGREE, 3000.0),
        radar(Platform::Spacecraft, 180.0 * DEGREE, 20_000.0),
    ];
    SensorNetwork::new(EarthRotation::new(c(ROTATION)), &sensors).expect("a valid network")
}

/// At most 500 RK4 sub-steps of 20 s: a bound of 10,000 s per scan keeps one input fast.
fn motion<T: Real>() -> TwoBodyJ2<T> {
    TwoBodyJ2 {
        mu: c(EARTH_MU),
        j2: c(EARTH_J2),
        radius: c(EARTH_RADIUS),
        min_radius: c(EARTH_MIN_RADIUS),
        noise: ProcessNoise::Isotropic(c(1e-10)),
        max_step: c(20.0),
        max_substeps: 500,
    }
}

/// A circular LEO object 800 km above the first site at t = 0, moving East, shifted by `offset`.
fn object(offset: ([i8; 3], [i8; 3])) -> SVector<f64, 6> {
    let rotation = EarthRotation::new(ROTATION);
    let observer = SITES[0].observer(&rotation, 0.0);
    let [east, _, up] = SITES[0].enu(&rotation, 0.0);
    let p: [f64; 3] = core::array::from_fn(|k| observer[k] + 800.0 * up[k] + f64::from(offset.0[k]));
    let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
    let speed = (EARTH_MU / r).sqrt();
    let v: [f64; 3] = core::array::from_fn(|k| speed * east[k] + 1e-3 * f64::from(offset.1[k]));
    SVector::from([p[0], p[1], p[2], v[0], v[1], v[2]])
}

fn config<T: Real>(input: &Input) -> Config<T, TwoBodyJ2<T>, Radars<T>, 6, B> {
    let measurement = network::<T>();
    let mut birth = BirthModel::none();
    if input.birth {
        birth.probability = c(0.01);
        birth.detection = BirthDetection::AllDetected;
        let mut covariance = SMatrix::<T, 6, 6>::zeros();
        for k in 0..3 {
            covariance[(k, k)] = c(1e4);
            covariance[(k + 3, k + 3)] = c(1.0);
        }
        let _ = birth.cells.push(Gaussian { mean: object(([0; 3], [0; 3])).map(c::<T>), covariance });
    }
    Config {
        motion: motion(),
        measurement,
        sensor: measurement.sensors()[0].detection,
        birth,
        death_probability: c(0.01),
        gate: Some(c(25.0)),
        children: if input.sampled {
            ChildGeneration::Sampled(SamplerConfig::default())
        } else {
            ChildGeneration::Exhaustive { max_children_per_scan: 100_000 }
        },
        selection: Default::default(),
        store_overflow: Default::default(),
        numerical_failure: Default::default(),
        track_loss: Default::default(),
        seed: input.seed,
    }
}

/// Everything a successful step must leave.
fn assert_healthy<T: Real>(tracker: &Fuzzed<T>) {
    let tolerance = if core::mem::size_of::<T>() == 8 { 1e-6 } else { 1e-3 };
    let count = tracker.hypotheses().len();
    assert!((1..=H).contains(&count), "{count} hypotheses");
    let mut total = 0.0;
    for h in tracker.hypotheses() {
        let weight = h.weight().as_f64();
        assert!(weight.is_finite() && weight >= 0.0, "weight {weight}");
        total += weight;
    }
    assert!((total - 1.0).abs() <= tolerance, "weights sum to {total}");
    for track in tracker.tracks() {
        let state = &track.state;
        assert!(state.mean.iter().chain(state.covariance.iter()).all(|v| v.is_finite_value()), "{state:?}");
        assert_eq!(state.covariance, state.covariance.transpose(), "covariance not symmetric");
        let existence = track.existence.as_f64();
        assert!((-tolerance..=1.0 + tolerance).contains(&existence), "existence {existence}");
    }
}

/// The bits of a tracker's state: its digest and every track's existence.
fn state<T: Real>(tracker: &Fuzzed<T>) -> (u64, Vec<u64>) {
    (tracker.digest(), tracker.tracks().iter().map(|t| t.existence.as_f64().to_bits()).collect())
}

fn observer<T: Real>(input: ObserverIn) -> Option<[T; 6]> {
    match input {
        ObserverIn::None => None,
        ObserverIn::Orbit(phase, offset) => {
            let angle = f64::from(phase) / 256.0 * 2.0 * core::f64::consts::PI;
            let (s, co) = angle.sin_cos();
            let r = 7000.0;
            let speed = (EARTH_MU / r).sqrt();
            let o = offset.map(|v| f64::from(v) / 64.0);
            Some([r * co + o[0], r * s + o[1], o[2], -speed * s, speed * co, 0.0].map(c::<T>))
        }
        ObserverIn::Position(p) => Some([f64::from(p[0]), f64::from(p[1]), f64::from(p[2]), 0.0, 0.0, 0.0].map(c::<T>)),
        ObserverIn::Raw(raw) => Some(raw.map(|n| c::<T>(n.value()))),
    }
}

/// Builds the tracker of `input` and runs its scans; returns the digest after every scan.
fn run<T: Real>(input: &Input) -> Vec<u64> {
    let mut covariance = SMatrix::<T, 6, 6>::zeros();
    for k in 0..3 {
        covariance[(k, k)] = c(0.25);
        covariance[(k + 3, k + 3)] = c(1e-4);
    }
    let mut truth: Vec<SVector<f64, 6>> = input.objects.iter().take(N).map(|&o| object(o)).collect();
    let objects: Vec<PriorObject<T, 6>> = truth
        .iter()
        .enumerate()
        .map(|(k, mean)| PriorObject {
            label: TrackLabel(k as u32),
            state: Gaussian { mean: mean.map(c::<T>), covariance },
        })
        .collect();
    let prior = [PriorHypothesis { weight: T::one(), objects: &objects }];
    let mut tracker = Box::new(Fuzzed::<T>::new(config::<T>(input), &prior, 0.0).expect("a valid configuration"));
    let truth_motion = motion::<f64>();
    let mut digests = vec![tracker.digest()];
    let mut previous = 0.0;
    for scan in input.scans.iter().take(10) {
        let time = match scan.time {
            TimeIn::Seconds(s) => previous + f64::from(s),
            TimeIn::After(dt) => previous + dt.value(),
            TimeIn::At(t) => t.value(),
        };
        let sensor = match scan.sensor {
            SensorIn::Index(i) => usize::from(i % 4),
            SensorIn::Max => usize::MAX,
        };
        let geometry = ScanGeometry { sensor, time, observer: observer::<T>(scan.observer) };
        // The objects' true states at the scan time, when the motion model can reach it.
        let dt = time - previous;
        let moved: Option<Vec<SVector<f64, 6>>> = if dt > 0.0 && dt <= 10_000.0 {
            truth.iter().map(|x| truth_motion.propagate(x, dt).ok().map(|p| p.state)).collect()
        } else {
            None
        };
        let placed = tracker.config().measurement.place(&geometry).ok();
        let measurements: Vec<SVector<T, 3>> = scan
            .measurements
            .iter()
            .take(Z + 2)
            .map(|m| match (*m, &placed, &moved) {
                (MeasurementIn::Near(k, offset), Some(placed), Some(moved)) if !moved.is_empty() => {
                    let exact = placed.measure(&moved[usize::from(k) % moved.len()].map(c::<T>));
                    let step = [1.0, 1e-4, 1e-4];
                    SVector::from(core::array::from_fn(|i| exact[i] + c::<T>(f64::from(offset[i]) * step[i])))
                }
                (MeasurementIn::Raw(raw), _, _) => SVector::from(raw.map(|n| c::<T>(n.value()))),
                _ => SVector::zeros(),
            })
            .collect();
        let before = state(&*tracker);
        match tracker.step_scan(&geometry, &measurements) {
            Ok(report) => {
                assert_healthy(&*tracker);
                let captured = report.captured_mass.as_f64();
                assert!((0.0..=1.0 + 1e-3).contains(&captured), "captured mass {captured}");
                assert_eq!(tracker.time(), time);
                previous = time;
                if let Some(moved) = moved {
                    truth = moved;
                }
            }
            Err(error) => {
                assert_eq!(state(&*tracker), before, "the state changed after {error:?}");
                let _ = error.to_string();
            }
        }
        digests.push(tracker.digest());
    }
    digests
}

fn run_twice<T: Real>(input: &Input) {
    let first = run::<T>(input);
    if input.replay {
        assert_eq!(run::<T>(input), first, "not deterministic");
    }
}

fuzz_target!(|input: Input| {
    if input.single_precision {
        run_twice::<f32>(&input);
    } else {
        run_twice::<f64>(&input);
    }
});
