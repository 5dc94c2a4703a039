//! Exactness on real 3-D geometry (issue 13): the core tracker against the unbounded reference on a small
//! radar scenario built here. Two ground radars with look-cone fields of view take turns; three LEO
//! objects (two-body + J2 truth from the independent RKF7(8) propagator) pass through the first radar's
//! cone due South, two of them crossing within about two beamwidths, and one through azimuth ±180° so
//! that measured and predicted azimuths straddle the wrap.

use core::f64::consts::PI;
use host_sim::eval::exactness::{CompareFigures, Scan, compare_scans, compare_trackers};
use host_sim::peers::reference::{ReferenceError, ReferenceTracker};
use host_sim::sim::orbit::Propagator;
use host_sim::sim::rng::{Random, Stream};
use nalgebra::{SMatrix, SVector};
use tracker_core::model::{EARTH_MU, ProcessNoise, RadarRangeAzEl, SensorNetwork, TwoBodyJ2};
use tracker_core::sampler::SamplerConfig;
use tracker_core::sensor::{EarthRotation, GroundSite, Placement, PlacementError, Platform, ScanGeometry, SiteSensor};
use tracker_core::{
    BirthDetection, BirthModel, ChildGeneration, Config, Gaussian, LookShape, Measure, PriorObject, Region, Sensor,
    StepError, TrackLabel, Tracker,
};

type Network = SensorNetwork<f64, RadarRangeAzEl<f64>, 3, 2>;
type Radar3d = Config<f64, TwoBodyJ2<f64>, Network, 6, 1>;
/// H, N, Z, K, B of the core tracker: room for every hypothesis the reference keeps.
type Core = Tracker<f64, TwoBodyJ2<f64>, Network, 6, 3, 256, 8, 16, 1024, 1>;

/// The seed of the noise, detections and clutter; with it one measurement of object 0 falls across ±π
/// from its true azimuth (checked below).
const SEED: u64 = 1;
/// Radar noise: range (km), azimuth and elevation (rad).
const SIGMA: [f64; 3] = [0.05, 1e-3, 1e-3];
/// Time at which the objects' truth is set (the second scan of radar 0).
const CROSSING: f64 = 30.0;
const SCANS: usize = 6;

fn cone(azimuth: f64, elevation: f64) -> Region<f64> {
    Region::Look {
        shape: LookShape::Cone { azimuth, elevation, half_angle: 0.6 },
        min_elevation: 0.15,
        range: Some([300.0, 2500.0]),
        range_rate: None,
    }
}

fn network() -> Network {
    let radar = |latitude: f64, longitude: f64, field_of_view| SiteSensor {
        platform: Platform::Ground(GroundSite { latitude, longitude, height: 0.1 }),
        sigma: SIGMA,
        detection: Sensor { detection_probability: 0.9, clutter_rate: 1.5, field_of_view },
    };
    // Radar 0 looks South (azimuth ±180°), radar 1 North of the other site.
    SensorNetwork::new(EarthRotation::new(0.4), &[radar(0.7, 0.1, cone(PI, 0.9)), radar(0.5, -0.3, cone(0.0, 1.0))])
        .unwrap()
}

fn geometry(time: f64, sensor: usize) -> ScanGeometry<f64> {
    ScanGeometry { sensor, time, observer: None }
}

/// A LEO state at `(range, azimuth, elevation)` from radar 0 at [`CROSSING`], on a circular-speed
/// velocity whose horizontal direction is `heading` (from North towards East).
fn object(network: &Network, range: f64, azimuth: f64, elevation: f64, heading: f64) -> [f64; 6] {
    let placed = network.place(&geometry(CROSSING, 0)).unwrap();
    let radar = placed.placed();
    let [east, north, up] = radar.enu.map(SVector::<f64, 3>::from);
    let look =
        east * (azimuth.sin() * elevation.cos()) + north * (azimuth.cos() * elevation.cos()) + up * elevation.sin();
    let position = SVector::<f64, 3>::from([radar.observer[0], radar.observer[1], radar.observer[2]]) + look * range;
    let radial = position.normalize();
    let wanted = east * heading.sin() + north * heading.cos();
    let along = (wanted - radial * radial.dot(&wanted)).normalize();
    let velocity = along * (EARTH_MU / position.norm()).sqrt();
    [position[0], position[1], position[2], velocity[0], velocity[1], velocity[2]]
}

/// The truth states at [`CROSSING`]: objects 0 and 1 cross within ~2 mrad, object 0 exactly due South.
fn truth(network: &Network) -> Vec<[f64; 6]> {
    vec![
        object(network, 800.0, PI, 0.9, 0.5 * PI),
        object(network, 801.0, PI - 0.002, 0.901, 0.15 * PI),
        object(network, 900.0, PI - 0.3, 0.8, 0.4 * PI),
    ]
}

fn state_at(state: &[f64; 6], time: f64) -> SVector<f64, 6> {
    SVector::from(Propagator::EARTH.propagate(*state, time - CROSSING).unwrap())
}

/// Scans 10 s apart, radars alternating (radar 0 first): each object in view is detected with p_D, its
/// measurement noisy; Poisson clutter uniform in (range, azimuth, elevation) over the cone.
fn scans(network: &Network, truth: &[[f64; 6]]) -> Vec<Scan<3>> {
    let mut rng = Random::stream(SEED, Stream::Detection, 0);
    let mut out = vec![];
    for k in 1..=SCANS {
        let (time, sensor) = (10.0 * k as f64, (k - 1) % 2);
        let placed = network.place(&geometry(time, sensor)).unwrap();
        let detection = placed.detection().unwrap();
        let view = detection.field_of_view;
        let mut zs = vec![];
        for state in truth {
            let exact = placed.measure(&state_at(state, time));
            if !(view.sees(&placed, &exact) && rng.uniform() < detection.detection_probability) {
                continue;
            }
            let mut z = exact + SVector::from(SIGMA.map(|s| s * rng.normal()));
            z[1] = tracker_core::sensor::wrap_angle(z[1]);
            if view.sees(&placed, &z) {
                zs.push(z);
            }
        }
        for _ in 0..rng.poisson(detection.clutter_rate) {
            for _ in 0..100_000 {
                let z = SVector::from([rng.between(300.0, 2500.0), rng.between(-PI, PI), rng.between(0.15, 0.5 * PI)]);
                if view.sees(&placed, &z) {
                    zs.push(z);
                    break;
                }
            }
        }
        rng.shuffle(&mut zs);
        out.push((geometry(time, sensor), zs));
    }
    out
}

fn config(network: Network, children: ChildGeneration) -> Radar3d {
    // One birth cell in radar 0's cone: 1000 km away, 150 km and 1 km/s wide.
    let mut cells = heapless::Vec::new();
    let centre = object(&network, 1000.0, PI + 0.3, 1.0, 0.0);
    let spread = SVector::from([150.0f64.powi(2), 150.0f64.powi(2), 150.0f64.powi(2), 1.0, 1.0, 1.0]);
    cells.push(Gaussian { mean: SVector::from(centre), covariance: SMatrix::from_diagonal(&spread) }).unwrap();
    Config {
        motion: TwoBodyJ2::<f64>::earth(ProcessNoise::Isotropic(1e-8), 10.0, 100),
        measurement: network,
        sensor: network.sensors()[0].detection,
        birth: BirthModel {
            probability: 0.005,
            cells,
            detection: BirthDetection::AllDetected,
            events: Default::default(),
            measured: None,
        },
        death_probability: 0.005,
        gate: Some(25.0),
        children,
        selection: Default::default(),
        store_overflow: Default::default(),
        numerical_failure: Default::default(),
        track_loss: Default::default(),
        seed: 7,
    }
}

/// The prior at t = 0: the truth propagated back, perturbed by its own covariance.
fn prior(truth: &[[f64; 6]]) -> Vec<(f64, Vec<PriorObject<f64, 6>>)> {
    let covariance = SMatrix::<f64, 6, 6>::from_diagonal(&SVector::from([0.25, 0.25, 0.25, 1e-6, 1e-6, 1e-6]));
    let mut rng = Random::stream(SEED, Stream::Prior, 0);
    let objects = truth
        .iter()
        .enumerate()
        .map(|(label, state)| PriorObject {
            label: TrackLabel(label as u32),
            state: Gaussian { mean: state_at(state, 0.0) + rng.gaussian(&covariance), covariance },
        })
        .collect();
    vec![(1.0, objects)]
}

/// Runs `f` on a thread with room for the core tracker on its stack (debug builds copy it).
fn big_stack<R: Send + 'static>(f: impl FnOnce() -> R + Send + 'static) -> R {
    std::thread::Builder::new().stack_size(256 << 20).spawn(f).unwrap().join().unwrap()
}

fn compare(children: ChildGeneration) -> CompareFigures {
    big_stack(move || {
        let network = network();
        let truth = truth(&network);
        let scans = scans(&network, &truth);
        let config = config(network, children);
        compare_scans::<_, _, 6, 3, 256, 8, 16, 1024, 1>(&config, &prior(&truth), 0.0, 1 << 30, &scans).unwrap()
    })
}

fn print(name: &str, figures: &CompareFigures) {
    for s in &figures.scans {
        println!(
            "{name} scan {} t {}: MAP weight {:.6}, core {} reference {} hypotheses, captured {:.12}, core captured {:?}, \
             map {} labels {} weight diff {:.3e}",
            s.scan,
            s.time,
            s.reference_map_weight,
            s.core_hypotheses,
            s.reference_hypotheses,
            s.captured_mass,
            s.core_captured_mass,
            s.map_agreement,
            s.map_labels_agree,
            s.map_weight_difference
        );
    }
    println!(
        "{name}: map_agreement {}, min captured mass {:.12}, min core captured mass {:.12}, max MAP weight \
         difference {:.3e}, max weight L1 {:.3e}",
        figures.map_agreement,
        figures.min_captured_mass,
        figures.min_core_captured_mass,
        figures.max_map_weight_difference,
        figures.max_weight_l1
    );
}

#[test]
fn reference_3d_scenario_exercises_the_azimuth_wrap_and_the_crossing() {
    let network = network();
    let truth = truth(&network);
    let scans = scans(&network, &truth);
    // Radar 0 sees every object at the crossing scan, radar 1 none of them (its scans hold clutter only).
    let placed = network.place(&geometry(CROSSING, 0)).unwrap();
    let at_crossing: Vec<SVector<f64, 3>> = truth.iter().map(|s| placed.measure(&state_at(s, CROSSING))).collect();
    assert!(at_crossing.iter().all(|z| network.sensors()[0].detection.field_of_view.sees(&placed, z)));
    let separation = (at_crossing[0] - at_crossing[1]).abs();
    assert!(separation[1] < 3e-3 && separation[2] < 3e-3, "{separation:?}");
    // A measurement across ±π from its object's true azimuth: an unwrapped residual would be ≈ 2π.
    let straddles = scans.iter().filter(|(g, _)| g.sensor == 0).any(|(g, zs)| {
        let placed = network.place(g).unwrap();
        truth.iter().any(|s| {
            let exact = placed.measure(&state_at(s, g.time));
            zs.iter().any(|z| (z[1] - exact[1]).abs() > PI && (placed.residual(z, &exact)).norm() < 0.5)
        })
    });
    assert!(straddles, "no measurement straddles azimuth ±180°");
    assert!(scans.iter().all(|(_, zs)| zs.len() <= 16));
}

fn check(figures: &CompareFigures, weight_tolerance: f64) {
    assert_eq!(figures.scans.len(), SCANS);
    for s in &figures.scans {
        assert_eq!((s.core_error, s.reference_error), (None, None), "scan {}", s.scan);
        assert!(s.map_agreement && s.map_labels_agree, "scan {}: {s:?}", s.scan);
        assert!(s.map_weight_difference <= weight_tolerance, "scan {}: {s:?}", s.scan);
        assert!(s.captured_mass >= 0.999 && s.core_captured_mass.unwrap() >= 0.999, "scan {}: {s:?}", s.scan);
    }
    assert_eq!(figures.map_agreement, 1.0);
    // More than one hypothesis somewhere: the crossing is ambiguous.
    assert!(figures.scans.iter().any(|s| s.reference_hypotheses > 1));
}

#[test]
fn reference_3d_exhaustive_core_is_exact() {
    let figures = compare(ChildGeneration::Exhaustive { max_children_per_scan: 1_000_000 });
    print("exhaustive", &figures);
    check(&figures, 1e-9);
    // The core's H best hypotheses hold the reference's posterior to rounding.
    assert!(figures.max_weight_l1 <= 1e-9, "{}", figures.max_weight_l1);
}

#[test]
fn reference_3d_sampled_core_agrees() {
    let figures = compare(ChildGeneration::Sampled(SamplerConfig::DEFAULT));
    print("sampled", &figures);
    check(&figures, 1e-3);
}

#[test]
fn reference_3d_rejects_the_bad_scans_the_core_rejects() {
    big_stack(|| {
        let network = network();
        let truth = truth(&network);
        let scans = scans(&network, &truth);
        let config = config(network, ChildGeneration::default());
        let prior = prior(&truth);
        let hypotheses: Vec<_> =
            prior.iter().map(|(weight, objects)| tracker_core::PriorHypothesis { weight: *weight, objects }).collect();
        let mut core = Box::new(Core::new(config.clone(), &hypotheses, 0.0).unwrap());
        let mut reference = ReferenceTracker::new(&config, &prior, 0.0, 1 << 30).unwrap();
        // One good scan first, so that there is a posterior to leave unchanged.
        compare_trackers(&mut core, &mut reference, &scans[..1]);
        let zs = &scans[2].1;
        let bad = [
            (
                ScanGeometry { sensor: 2, time: 30.0, observer: None },
                PlacementError::UnknownSensor { sensor: 2, sensors: 2 },
            ),
            (
                ScanGeometry { sensor: 0, time: 30.0, observer: Some([7000.0, 0.0, 0.0, 0.0, 7.5, 0.0]) },
                PlacementError::UnexpectedObserver,
            ),
        ];
        for (geometry, error) in bad {
            let (digest, posterior) = (core.digest(), reference.posterior());
            assert_eq!(core.step_scan(&geometry, zs).unwrap_err(), StepError::Placement(error));
            assert_eq!(
                reference.step_scan(&geometry, zs).unwrap_err(),
                ReferenceError::Step(StepError::Placement(error))
            );
            assert_eq!((core.digest(), reference.posterior()), (digest, posterior));
        }
        // A measurement outside radar 1's cone (radar 0's scan given to radar 1): both reject it alike.
        let wrong = ScanGeometry { sensor: 1, time: 30.0, observer: None };
        let core_error = core.step_scan(&wrong, zs).unwrap_err();
        assert!(matches!(core_error, StepError::MeasurementOutsideFieldOfView { .. }), "{core_error:?}");
        assert_eq!(reference.step_scan(&wrong, zs).unwrap_err(), ReferenceError::Step(core_error));
        // And the good scans still go through both, exactly.
        let figures = compare_trackers(&mut core, &mut reference, &scans[1..]);
        assert_eq!(figures.map_agreement, 1.0);
        assert!(figures.scans.iter().all(|s| s.map_weight_difference <= 1e-9));
        // The MAP hypothesis holds the three objects, each within 1 km of its truth.
        let map = core.map_hypothesis();
        let time = scans[SCANS - 1].0.time;
        let errors: Vec<(u32, f64)> = map
            .tracks()
            .map(|t| {
                let truth = state_at(&truth[t.label.0 as usize], time);
                (t.label.0, (t.state.mean.fixed_rows::<3>(0) - truth.fixed_rows::<3>(0)).norm())
            })
            .collect();
        assert_eq!(errors.iter().map(|e| e.0).collect::<Vec<_>>(), [0, 1, 2], "{errors:?}");
        assert!(errors.iter().all(|e| e.1 < 1.0), "{errors:?}");
    });
}
