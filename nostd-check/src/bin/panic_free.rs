//! Link-time proof that `Tracker::new`, `Tracker::step` and `Tracker::digest` cannot panic.
//!
//! The panic handler calls a function that does not exist. The release build (fat LTO, one codegen unit)
//! only links if the optimiser removed every path to a panic from the code below, so a successful build of
//! this binary is the proof (`cargo build --release --bin panic_free`). With `--features report-panics`
//! the handler is an ordinary loop instead, so the remaining panic sites can be listed from the
//! disassembly (`scripts/panic-sites.sh`).
//!
//! Every input goes through `black_box`, so the optimiser cannot specialise the tracker to it: any
//! configuration (both child generations, both birth variants, gate on or off, both selections, both
//! store policies, any values), any prior and any scan (any number of measurements, any time) stays
//! possible. The proof covers the monomorphisations instantiated here: `SsaTracker<f64>`,
//! `SsaTracker<f32>`, `LinearTracker<f64, 8, 4, 4, 16, 0>` (no birth cells) and a `ClusterPool` of them (the partitioned
//! tracker in fixed memory) and the 3-D
//! `RadarTracker<f64>` and `RadarTracker<f32>` (a network of two ground radars and a spacecraft one, any
//! sensor index and observer per scan), `NetworkTracker<f64>` and `NetworkTracker<f32>` (sensors of every
//! kind, any sensor index per scan; `new`, and `reset_with` that installs a configuration in place), and
//! the birth geometry `BirthGeometry::birth_components` of the radar (with and without range-rate),
//! optical, mixed-kind and planar models in f64 and f32 (any measurement, region, observer and output
//! length).
#![no_std]
#![no_main]

use core::hint::black_box;
use nalgebra::{SMatrix, SVector};
use tracker_core::config::{ChildGeneration, NumericalFailure, Selection, StoreOverflow};
use tracker_core::model::{LightTime, ProcessNoise};
use tracker_core::partition::ClusterPool;
use tracker_core::sampler::SamplerConfig;
use tracker_core::sensor::LookShape;
use tracker_core::sensor::{EarthRotation, GroundSite, LookAxes, Platform, ScanGeometry, SiteSensor};
use tracker_core::{
    BirthDetection, BirthModel, Config, ConstantVelocity, Gaussian, LinearTracker, MixedSensor, Network, NetworkConfig,
    NetworkTracker, PositionMeasurement, PriorHypothesis, PriorObject, RadarConfig, RadarNetwork, RadarTracker, Real,
    Region, Sensor, SensorKind, SsaConfig, SsaTracker, TrackLabel, TwoBody, TwoBodyJ2, ssa_caps,
};

// The C runtime provides `_start`, which calls `main`.
#[link(name = "c")]
unsafe extern "C" {}

#[cfg(not(feature = "report-panics"))]
unsafe extern "C" {
    /// Deliberately undefined: referencing it from the panic handler makes any reachable panic a link error.
    fn tracker_core_step_can_panic() -> !;
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    #[cfg(not(feature = "report-panics"))]
    // SAFETY: never called: the binary only links when no panic is reachable.
    unsafe {
        tracker_core_step_can_panic()
    }
    #[cfg(feature = "report-panics")]
    loop {}
}

/// The precompiled `core` for this host target was built with unwinding and references this symbol;
/// with `panic = "abort"` it is never called.
#[unsafe(no_mangle)]
extern "C" fn rust_eh_personality() {}

/// More measurements than any capacity here, so every scan length (including too many) is possible.
const MEASUREMENTS: usize = 40;

/// The variant choices, from the command line (they are opaque anyway).
fn children(argc: i32) -> ChildGeneration {
    if argc > 1 {
        ChildGeneration::Sampled(SamplerConfig::default())
    } else {
        ChildGeneration::Exhaustive { max_children_per_scan: 1_000_000 }
    }
}

fn selection(argc: i32) -> Selection {
    match argc {
        5 => Selection::SampledByWeight,
        // The floor's code too (the number of decades from the input, so not folded away).
        6.. => Selection::TopWeightWithin { decades: argc as u8 },
        _ => Selection::TopWeight,
    }
}

fn store_overflow(argc: i32) -> StoreOverflow {
    if argc > 5 { StoreOverflow::Error } else { StoreOverflow::PruneChildren }
}

/// A two-hypothesis prior over `objects` (the second holds the first object only).
fn prior<T: Real>(objects: &[PriorObject<T, 4>; 2]) -> [PriorHypothesis<'_, T, 4>; 2] {
    [
        PriorHypothesis { weight: T::of_f64(0.7), objects },
        PriorHypothesis { weight: T::of_f64(0.3), objects: &objects[..1] },
    ]
}

/// `SsaTracker<T>`: `new`, `with_objects`, then `step` and `digest` over opaque scans.
fn ssa<T: Real>(argc: i32) -> u64 {
    let c = T::of_f64;
    let x = c(f64::from(argc));
    let mut cells = heapless::Vec::<Gaussian<T, 4>, { ssa_caps::BIRTH_CELLS }>::new();
    let _ = cells.push(Gaussian {
        mean: SVector::from([c(8000.0) * x, c(100.0), T::zero(), c(7.0)]),
        covariance: SMatrix::identity() * (c(100.0) * x),
    });
    let config: SsaConfig<T> = black_box(Config {
        motion: TwoBody {
            mu: c(398_600.441_8),
            acceleration_noise: c(1e-13) * x,
            max_step: c(20.0),
            max_substeps: 20_000,
            min_radius: TwoBody::DEFAULT_MIN_RADIUS,
        },
        measurement: PositionMeasurement::isotropic(c(0.5) * x),
        sensor: Sensor {
            detection_probability: c(0.9) / x,
            clutter_rate: x,
            field_of_view: Region::Sector {
                origin: [T::zero(), T::zero()],
                look_direction: c(0.26) * x,
                half_angle: c(0.26),
                max_range: c(30_000.0),
            },
        },
        birth: BirthModel {
            events: Default::default(),
            measured: None,
            probability: c(1e-3) * x,
            cells,
            detection: if argc > 2 { BirthDetection::AllowUndetected } else { BirthDetection::AllDetected },
        },
        death_probability: c(1e-4) * x,
        gate: if argc > 3 { None } else { Some(c(25.0) * x) },
        children: children(argc),
        selection: selection(argc),
        store_overflow: store_overflow(argc),
        numerical_failure: if argc > 5 { NumericalFailure::Error } else { NumericalFailure::DropTrack },
        track_loss: Default::default(),
        seed: argc as u64,
    });
    let state = |position: f64| Gaussian {
        mean: SVector::from([c(7000.0) * x, c(position), -T::one(), c(7.5)]),
        covariance: SMatrix::identity() * x,
    };
    let objects = [
        PriorObject { label: TrackLabel(0), state: state(1000.0) },
        PriorObject { label: TrackLabel(3), state: state(1400.0) },
    ];
    let prior = prior(&objects);
    let mut digest = 0u64;
    if let Ok(tracker) =
        SsaTracker::<T>::with_objects(config.clone(), black_box(&[objects[0].state][..]), black_box(0.0))
    {
        digest ^= tracker.digest();
    }
    let Ok(mut tracker) = SsaTracker::<T>::new(config, black_box(&prior[..]), black_box(0.0)) else { return 2 };
    let zs: [SVector<T, 2>; MEASUREMENTS] =
        core::array::from_fn(|i| SVector::from([c(7000.0 + 60.0 * i as f64) * x, c(1060.0 - 25.0 * i as f64)]));
    for k in 1..=argc as usize {
        let scan = black_box(&zs[..(k * argc as usize) % (MEASUREMENTS + 1)]);
        if tracker.step(black_box(60.0 * k as f64), scan).is_err() {
            digest ^= 1;
        }
        digest ^= tracker.digest();
    }
    digest
}

/// A planar configuration without birth cells whose every value is opaque.
fn linear_config(argc: i32) -> Config<f64, ConstantVelocity<f64>, PositionMeasurement<f64>, 4, 0> {
    let x = f64::from(argc);
    black_box(Config {
        motion: ConstantVelocity { acceleration_noise: 0.01 * x },
        measurement: PositionMeasurement::isotropic(0.3 * x),
        sensor: Sensor {
            detection_probability: 0.9 / x,
            clutter_rate: x,
            field_of_view: Region::Rectangle { min: [-50.0, -50.0], max: [50.0, 50.0 * x] },
        },
        birth: BirthModel::none(),
        death_probability: 0.01 * x,
        gate: if argc > 3 { None } else { Some(16.0 * x) },
        children: children(argc),
        selection: selection(argc),
        store_overflow: store_overflow(argc),
        numerical_failure: if argc > 5 { NumericalFailure::Error } else { NumericalFailure::DropTrack },
        track_loss: Default::default(),
        seed: argc as u64,
    })
}

/// `LinearTracker` without birth cells (`B = 0`): `new`, `step` and `digest` over opaque scans.
fn linear(argc: i32) -> u64 {
    type Tracker = LinearTracker<f64, 8, 4, 4, 16, 0>;
    let x = f64::from(argc);
    let config = linear_config(argc);
    let state = |y: f64| Gaussian { mean: SVector::from([0.0, y, 1.0, 0.0]), covariance: SMatrix::identity() * x };
    let objects = [
        PriorObject { label: TrackLabel(1), state: state(0.0) },
        PriorObject { label: TrackLabel(2), state: state(5.0) },
    ];
    let prior = prior(&objects);
    let Ok(mut tracker) = Tracker::new(config, black_box(&prior[..]), black_box(0.0)) else { return 2 };
    let zs: [SVector<f64, 2>; MEASUREMENTS] =
        core::array::from_fn(|i| SVector::from([i as f64 * x, 5.0 - 0.5 * i as f64]));
    let mut digest = 0u64;
    for k in 1..=argc as usize {
        let scan = black_box(&zs[..(k * argc as usize) % (MEASUREMENTS + 1)]);
        if tracker.step(black_box(k as f64), scan).is_err() {
            digest ^= 1;
        }
        digest ^= tracker.digest();
    }
    digest
}

/// The pool of clusters (`ClusterPool`) of `LinearTracker`s without birth cells: `new`, `step` and
/// `digest` over opaque objects and scans (merges, splits and refusals included).
fn pool(argc: i32) -> u64 {
    type Pool = ClusterPool<f64, ConstantVelocity<f64>, PositionMeasurement<f64>, 4, 2, 8, 4, 4, 16, 0, 4, 8>;
    let x = f64::from(argc);
    let config = linear_config(argc);
    let state = |y: f64| Gaussian { mean: SVector::from([0.0, y, 1.0, 0.0]), covariance: SMatrix::identity() * x };
    let objects: [PriorObject<f64, 4>; 5] =
        core::array::from_fn(|i| PriorObject { label: TrackLabel(i as u32), state: state(5.0 * i as f64) });
    let objects = black_box(&objects[..argc as usize % 6]);
    let Ok(mut pool) = Pool::new(config, objects, black_box(0.0), black_box(0.01 * x)) else { return 2 };
    let zs: [SVector<f64, 2>; MEASUREMENTS] =
        core::array::from_fn(|i| SVector::from([i as f64 * x, 5.0 - 0.5 * i as f64]));
    let mut digest = 0u64;
    for k in 1..=argc as usize {
        let scan = black_box(&zs[..(k * argc as usize) % (MEASUREMENTS + 1)]);
        if pool.step(&black_box(ScanGeometry::single(k as f64)), scan).is_err() {
            digest ^= 1;
        }
        digest ^= pool.digest();
    }
    digest
}

/// Two-body + J2 motion with opaque J2 and process noise (the 3-D trackers' motion model).
fn motion<T: Real>(x: T) -> TwoBodyJ2<T> {
    let c = T::of_f64;
    TwoBodyJ2::<T> {
        mu: c(398_600.441_8),
        j2: c(1.082_626_68e-3) * x,
        radius: c(6378.137),
        min_radius: c(6300.0),
        noise: ProcessNoise::Isotropic(c(1e-12) * x),
        max_step: c(20.0),
        max_substeps: 2000,
    }
}

/// `RadarTracker<T>`: a network of two ground radars and a spacecraft radar, `new`, then `step_scan` and
/// `digest` over opaque scans, sensors and observers.
fn radar<T: Real>(argc: i32) -> u64 {
    let c = T::of_f64;
    let x = c(f64::from(argc));
    let detection = Sensor {
        detection_probability: c(0.9) / x,
        clutter_rate: x,
        field_of_view: Region::Look {
            shape: LookShape::Cone { azimuth: c(0.3) * x, elevation: c(0.9), half_angle: c(0.7) * x },
            min_elevation: c(0.1) * x,
            range: Some([T::zero(), c(3000.0) * x]),
            range_rate: None,
        },
    };
    let site = |latitude: f64| SiteSensor {
        platform: Platform::Ground(GroundSite { latitude: c(latitude) * x, longitude: c(-1.8), height: c(0.2) }),
        sigma: [c(0.02) * x, c(3e-4), c(3e-4)],
        detection,
    };
    let sensors = black_box([site(0.7), site(0.6), SiteSensor { platform: Platform::Spacecraft, ..site(0.0) }]);
    let Ok(network) = RadarNetwork::<T>::new(EarthRotation::new(c(0.4) * x), &sensors[..argc as usize % 4]) else {
        return 3;
    };
    let config: RadarConfig<T> = black_box(Config {
        motion: motion(x),
        measurement: network,
        sensor: detection,
        birth: BirthModel::none(),
        death_probability: c(1e-4) * x,
        gate: if argc > 3 { None } else { Some(c(25.0) * x) },
        children: children(argc),
        selection: selection(argc),
        store_overflow: store_overflow(argc),
        numerical_failure: if argc > 5 { NumericalFailure::Error } else { NumericalFailure::DropTrack },
        track_loss: Default::default(),
        seed: argc as u64,
    });
    let state = |z: f64| Gaussian {
        mean: SVector::from([c(-1400.0) * x, c(-5000.0), c(z), c(7.0), T::zero(), c(1.0)]),
        covariance: SMatrix::identity() * x,
    };
    let objects = [
        PriorObject { label: TrackLabel(0), state: state(4200.0) },
        PriorObject { label: TrackLabel(3), state: state(4300.0) },
    ];
    let prior = [
        PriorHypothesis { weight: c(0.7), objects: &objects[..] },
        PriorHypothesis { weight: c(0.3), objects: &objects[..1] },
    ];
    let Ok(mut tracker) = RadarTracker::<T>::new(config, black_box(&prior[..]), black_box(0.0)) else { return 2 };
    let zs: [SVector<T, 3>; MEASUREMENTS] =
        core::array::from_fn(|i| SVector::from([c(800.0 + 20.0 * i as f64) * x, c(0.1 * i as f64), c(0.8)]));
    let mut digest = 0u64;
    for k in 1..=argc as usize {
        let scan = black_box(&zs[..(k * argc as usize) % (MEASUREMENTS + 1)]);
        let observer =
            if argc > 6 { Some([c(7000.0) * x, T::zero(), T::zero(), T::zero(), c(7.5), T::zero()]) } else { None };
        let geometry = black_box(ScanGeometry { sensor: k % 4, time: 10.0 * k as f64, observer });
        if tracker.step_scan(&geometry, scan).is_err() {
            digest ^= 1;
        }
        digest ^= tracker.digest();
    }
    digest
}

/// `NetworkTracker<T>`: sensors of every kind (radar, radar with range-rate, RA/Dec, az/el, range, range
/// and range-rate) in one network, `new`, then `step_scan` and `digest` over opaque scans and sensors.
fn network<T: Real>(argc: i32) -> u64 {
    let c = T::of_f64;
    let x = c(f64::from(argc));
    let region = |axes: LookAxes| Region::Look {
        shape: LookShape::Cone { azimuth: c(0.3) * x, elevation: c(0.9), half_angle: c(0.7) * x },
        min_elevation: c(0.1) * x,
        range: axes.range.then_some([T::zero(), c(3000.0) * x]),
        range_rate: axes.range_rate.then_some([c(-8.0), c(8.0) * x]),
    };
    let sensor = |kind: SensorKind, latitude: f64| {
        let sigma: [T; 4] = core::array::from_fn(|i| if i < kind.dimension() { c(1e-3) * x } else { T::zero() });
        MixedSensor {
            kind,
            sensor: SiteSensor {
                platform: Platform::Ground(GroundSite {
                    latitude: c(latitude) * x,
                    longitude: c(-1.8),
                    height: c(0.2),
                }),
                sigma,
                detection: Sensor {
                    detection_probability: c(0.9) / x,
                    clutter_rate: x,
                    field_of_view: region(kind.axes()),
                },
            },
        }
    };
    let sensors = black_box(SensorKind::ALL.map(|kind| sensor(kind, 0.7)));
    let Ok(network) = Network::<T>::new(EarthRotation::new(c(0.4) * x), &sensors[..argc as usize % 7]) else {
        return 3;
    };
    // Light time on the first sensor for some inputs: its measurement path is linked too.
    let mode = black_box(if argc > 4 { LightTime::TwoWayReceive } else { LightTime::Off });
    let Ok(network) = network.with_light_time(0, mode) else { return 4 };
    let config: NetworkConfig<T> = black_box(Config {
        motion: motion(x),
        measurement: network,
        sensor: sensors[0].sensor.detection,
        birth: BirthModel::none(),
        death_probability: c(1e-4) * x,
        gate: if argc > 3 { None } else { Some(c(25.0) * x) },
        children: children(argc),
        selection: selection(argc),
        store_overflow: store_overflow(argc),
        numerical_failure: if argc > 5 { NumericalFailure::Error } else { NumericalFailure::DropTrack },
        track_loss: Default::default(),
        seed: argc as u64,
    });
    let state = |z: f64| Gaussian {
        mean: SVector::from([c(-1400.0) * x, c(-5000.0), c(z), c(7.0), T::zero(), c(1.0)]),
        covariance: SMatrix::identity() * x,
    };
    let objects = [PriorObject { label: TrackLabel(0), state: state(4200.0) }];
    let prior = [PriorHypothesis { weight: c(1.0), objects: &objects[..] }];
    let again = black_box(config.clone());
    let Ok(mut tracker) = NetworkTracker::<T>::new(config, black_box(&prior[..]), black_box(0.0)) else { return 2 };
    let zs: [SVector<T, 4>; MEASUREMENTS] =
        core::array::from_fn(|i| SVector::from([c(800.0 + 20.0 * i as f64) * x, c(0.1 * i as f64), c(0.8), x]));
    let mut digest = 0u64;
    for k in 1..=argc as usize {
        let scan = black_box(&zs[..(k * argc as usize) % (MEASUREMENTS + 1)]);
        let geometry = black_box(ScanGeometry { sensor: k % 7, time: 10.0 * k as f64, observer: None });
        if tracker.step_scan(&geometry, scan).is_err() {
            digest ^= 1;
        }
        digest ^= tracker.digest();
    }
    // In place (as a compile-time static takes its run-time configuration): `reset_with`, then a scan.
    if tracker.reset_with(again, black_box(&prior[..]), black_box(0.0)).is_err() {
        digest ^= 2;
    }
    let geometry = black_box(ScanGeometry { sensor: argc as usize % 7, time: 10.0, observer: None });
    if tracker.step_scan(&geometry, black_box(&zs[..argc as usize % (MEASUREMENTS + 1)])).is_err() {
        digest ^= 4;
    }
    digest ^ tracker.digest()
}

/// `birth_components` of every model with one, on opaque models, measurements, regions and output slices.
fn births<T: Real>(argc: i32) -> u64 {
    use tracker_core::model::{
        AdmissibleRegion, BirthComponent, MixedLook, OpticalRaDec, RadarRangeAzEl, RadarRangeRate, SensorBirths,
    };
    use tracker_core::{BirthGeometry, model::MAX_BIRTH_COMPONENTS};
    let c = T::of_f64;
    let x = c(f64::from(argc));
    let mut out = [BirthComponent::<T, 6>::ZERO; MAX_BIRTH_COMPONENTS];
    let length = black_box(argc as usize * 97) % (MAX_BIRTH_COMPONENTS + 1);
    let region = black_box(if argc > 2 { AdmissibleRegion::<T>::geo() } else { AdmissibleRegion::leo() });
    let observer = black_box([c(6000.0) * x, c(1000.0), c(2000.0), c(0.1), c(0.4), T::zero()]);
    let enu = black_box([[T::zero(), T::one(), T::zero()], [-T::one(), T::zero(), T::zero()], [T::zero(); 3]]);
    let mut digest = 0u64;
    let mut fold = |result: Result<usize, tracker_core::model::BirthError>| match result {
        Ok(n) => digest ^= n as u64,
        Err(_) => digest ^= 1,
    };
    let radar = RadarRangeAzEl { observer, enu, sigma: black_box([c(0.02), c(1e-3), c(1e-3)]) };
    fold(radar.birth_components(
        &black_box(SVector::from([c(900.0) * x, c(0.3), c(0.9)])),
        &region,
        &mut out[..length],
    ));
    let rate = RadarRangeRate { observer, enu, sigma: black_box([c(0.02), c(1e-3), c(1e-3), c(1e-4)]) };
    let z = black_box(SVector::from([c(900.0) * x, c(0.3), c(0.9), c(-1.0)]));
    fold(rate.birth_components(&z, &region, &mut out[..length]));
    let optical = OpticalRaDec { observer, sigma: black_box([c(5e-6), c(5e-6)]) };
    fold(optical.birth_components(&black_box(SVector::from([c(0.3) * x, c(0.1)])), &region, &mut out[..length]));
    let kind = black_box(SensorKind::ALL[argc as usize % 6]);
    let mixed = MixedLook {
        kind,
        observer,
        frame: enu,
        sigma: black_box([c(5e-6), c(5e-6), c(1e-3), c(1e-4)]),
        births: SensorBirths::FromModel,
        light_time: LightTime::Off,
    };
    let z = black_box(SVector::from([c(0.3) * x, c(0.1), c(0.9), c(-1.0)]));
    fold(mixed.birth_components(&z, &region, &mut out[..length]));
    let mut planar = [BirthComponent::<T, 4>::ZERO; 2];
    let sensor = PositionMeasurement::isotropic(c(0.5) * x);
    fold(sensor.birth_components(&black_box(SVector::from([x, c(2.0)])), &region, &mut planar[..length % 3]));
    digest
}

/// Inputs come from the command line so the optimiser cannot fold them: argc picks values.
#[unsafe(no_mangle)]
pub extern "C" fn main(argc: i32, _argv: *const *const u8) -> i32 {
    let digest = ssa::<f64>(argc)
        ^ ssa::<f32>(argc)
        ^ linear(argc)
        ^ pool(argc)
        ^ radar::<f64>(argc)
        ^ radar::<f32>(argc)
        ^ network::<f64>(argc)
        ^ network::<f32>(argc)
        ^ births::<f64>(argc)
        ^ births::<f32>(argc);
    (digest & 0x7f) as i32
}
