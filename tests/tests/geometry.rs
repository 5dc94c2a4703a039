//! Robustness of the 3-D geometry (issues 13 and 17): every bad input of a sensor network (sites, noise,
//! look-angle fields of view, capacity) and of `step_scan` (sensor ids, observers, measurements outside the
//! look field of view, gaps beyond the integrator's bound) is a typed error, one test per row of
//! `docs/robustness.md`. After every refused scan the tracker is bit-identical (`fingerprint` and `digest`),
//! and its next good scan gives the same report and bits as a clone that never saw the bad one. Each case
//! runs in f64 and f32.
//!
//! The seven core bugs these tests found (a network that did not check its sensors' detection models, a
//! measured elevation beyond ±90° read as a direction) are fixed; their tests now run with the others.

use conformance::fingerprint;
use nalgebra::{SMatrix, SVector};
use tracker_core::model::{
    EARTH_J2, EARTH_MIN_RADIUS, EARTH_MU, EARTH_RADIUS, Measure, MotionModel, ProcessNoise, SensorNetwork,
};
use tracker_core::sensor::{EarthRotation, GroundSite, Placement, PlacementError, Platform, ScanGeometry, SiteSensor};
use tracker_core::{
    BirthModel, Config, ConfigError, Gaussian, LookShape, OpticalRaDec, PositionMeasurement, PriorHypothesis,
    PriorObject, RadarRangeAzEl, Real, Region, Sensor, StepError, StepReport, TrackLabel, Tracker, TwoBodyJ2,
};

const DEGREE: f64 = core::f64::consts::PI / 180.0;

type Radars<T> = SensorNetwork<T, RadarRangeAzEl<T>, 3, 2>;
type Telescopes<T> = SensorNetwork<T, OpticalRaDec<T>, 2, 2>;
/// A small 3-D radar tracker: H = 8, N = 8, Z = 8, K = 32, B = 1.
type Small3d<T> = Tracker<T, TwoBodyJ2<T>, Radars<T>, 6, 3, 8, 8, 8, 32, 1>;

fn c<T: Real>(x: f64) -> T {
    T::of_f64(x)
}

/// The site of the ground radar (sensor 0).
const SITE: GroundSite<f64> = GroundSite { latitude: 40.0 * DEGREE, longitude: -105.0 * DEGREE, height: 0.2 };
const ROTATION: f64 = 0.3;

fn site<T: Real>(latitude_degrees: f64, longitude_degrees: f64, height: f64) -> Platform<T> {
    Platform::Ground(GroundSite {
        latitude: c(latitude_degrees * DEGREE),
        longitude: c(longitude_degrees * DEGREE),
        height: c(height),
    })
}

/// A radar's look field of view: a cone about the zenith (80° half angle) above a 5° mask, out to 4000 km.
fn radar_view<T: Real>() -> Region<T> {
    Region::Look {
        shape: LookShape::Cone { azimuth: c(0.0), elevation: c(90.0 * DEGREE), half_angle: c(80.0 * DEGREE) },
        min_elevation: c(5.0 * DEGREE),
        range: Some([c(0.0), c(4000.0)]),
        range_rate: None,
    }
}

fn detection<T: Real>(field_of_view: Region<T>) -> Sensor<T> {
    Sensor { detection_probability: c(0.95), clutter_rate: c(1.0), field_of_view }
}

/// Sensor 0: the ground radar at [`SITE`].
fn ground_radar<T: Real>() -> SiteSensor<T, 3> {
    SiteSensor {
        platform: site(40.0, -105.0, 0.2),
        sigma: [c(0.02), c(0.02 * DEGREE), c(0.02 * DEGREE)],
        detection: detection(radar_view()),
    }
}

/// Sensor 1: a spacecraft radar seeing every direction out to 20,000 km.
fn space_radar<T: Real>() -> SiteSensor<T, 3> {
    let view = Region::Look {
        shape: LookShape::Cone { azimuth: c(0.0), elevation: c(0.0), half_angle: c(180.0 * DEGREE) },
        min_elevation: c(-90.0 * DEGREE),
        range: Some([c(0.0), c(20_000.0)]),
        range_rate: None,
    };
    SiteSensor {
        platform: Platform::Spacecraft,
        sigma: [c(0.05), c(0.05 * DEGREE), c(0.05 * DEGREE)],
        ..ground_radar()
    }
    .with_view(view)
}

trait WithView<T> {
    fn with_view(self, view: Region<T>) -> Self;
}

impl<T: Real, const D: usize> WithView<T> for SiteSensor<T, D> {
    fn with_view(mut self, view: Region<T>) -> Self {
        self.detection.field_of_view = view;
        self
    }
}

fn network<T: Real>(sensors: &[SiteSensor<T, 3>]) -> Result<Radars<T>, &'static str> {
    SensorNetwork::new(EarthRotation::new(c(ROTATION)), sensors)
}

/// Two-body + J2 with RK4 sub-steps of at most 20 s, at most 2000 of them: a bound of 40,000 s per scan.
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

/// A circular LEO object 800 km above [`SITE`] at t = 0, moving East.
fn leo_object() -> SVector<f64, 6> {
    let rotation = EarthRotation::new(ROTATION);
    let observer = SITE.observer(&rotation, 0.0);
    let [east, _, up] = SITE.enu(&rotation, 0.0);
    let p: [f64; 3] = core::array::from_fn(|k| observer[k] + 800.0 * up[k]);
    let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
    let speed = (EARTH_MU / r).sqrt();
    SVector::from([p[0], p[1], p[2], speed * east[0], speed * east[1], speed * east[2]])
}

fn config<T: Real>(measurement: Radars<T>) -> Config<T, TwoBodyJ2<T>, Radars<T>, 6, 1> {
    Config {
        motion: motion(),
        measurement,
        sensor: ground_radar().detection,
        birth: BirthModel::none(),
        death_probability: c(0.01),
        gate: None,
        children: Default::default(),
        selection: Default::default(),
        store_overflow: Default::default(),
        numerical_failure: Default::default(),
        track_loss: Default::default(),
        seed: 7,
    }
}

/// The small tracker with the LEO object (position σ 0.5 km, velocity σ 0.01 km/s) at t = 0.
fn small<T: Real>() -> Box<Small3d<T>> {
    let measurement = network(&[ground_radar(), space_radar()]).unwrap();
    let mut covariance = SMatrix::<T, 6, 6>::zeros();
    for k in 0..3 {
        covariance[(k, k)] = c(0.25);
        covariance[(k + 3, k + 3)] = c(1e-4);
    }
    let objects =
        [PriorObject { label: TrackLabel(0), state: Gaussian { mean: leo_object().map(c::<T>), covariance } }];
    let prior = [PriorHypothesis { weight: T::one(), objects: &objects }];
    Box::new(Small3d::<T>::new(config(measurement), &prior, 0.0).unwrap())
}

/// The exact measurement of the LEO object by the ground radar at `time`.
fn measured<T: Real>(time: f64) -> SVector<T, 3> {
    let truth = motion::<f64>().propagate(&leo_object(), time).unwrap().state;
    let placed = network::<f64>(&[ground_radar(), space_radar()]).unwrap().place(&ScanGeometry::single(time)).unwrap();
    placed.measure(&truth).map(c::<T>)
}

/// A spacecraft observer 500 km beyond the object's orbit, at rest.
fn spacecraft_observer<T: Real>() -> [T; 6] {
    let object = leo_object();
    let r = object.fixed_rows::<3>(0).norm();
    let scale = (r + 500.0) / r;
    [object[0] * scale, object[1] * scale, object[2] * scale, 0.0, 0.0, 0.0].map(c::<T>)
}

/// Runs `bad` on a fresh small tracker and checks that it fails with `expected` and leaves the tracker
/// bit-identical; then the next good scan (the ground radar at 10 s, the object's measurement) gives the
/// same report and bits as a clone that never saw `bad`, and keeps the object.
fn assert_refused<T: Real>(bad: impl FnOnce(&mut Small3d<T>) -> Result<StepReport<T>, StepError>, expected: StepError) {
    let mut tracker = small::<T>();
    let before = fingerprint(&*tracker);
    let digest = tracker.digest();
    let mut untouched = tracker.clone();
    assert_eq!(bad(&mut tracker).err(), Some(expected));
    assert_eq!(fingerprint(&*tracker), before, "state changed after {expected:?}");
    assert_eq!(tracker.digest(), digest);
    let good = ScanGeometry::single(10.0);
    let z = [measured::<T>(10.0)];
    let report = untouched.step_scan(&good, &z).unwrap();
    assert_eq!(tracker.step_scan(&good, &z).unwrap(), report);
    assert_eq!(fingerprint(&*tracker), fingerprint(&*untouched));
    assert!(tracker.map_hypothesis().weight().as_f64() > 0.9 && tracker.map_hypothesis().len() == 1);
}

macro_rules! for_scalars {
    ($check:ident) => {
        $check::<f64>();
        $check::<f32>();
    };
}

// ---- Configuration: the sensor network --------------------------------------------------------------

/// `SensorNetwork::new` refuses `sensors` with a message containing `fragment`.
fn assert_network_refused<T: Real>(sensors: &[SiteSensor<T, 3>], fragment: &str) {
    match network(sensors) {
        Err(why) => assert!(why.contains(fragment), "{why:?} does not mention {fragment:?}"),
        Ok(network) => panic!("accepted {:?}", network.sensors()),
    }
}

#[test]
fn non_finite_earth_rotation_is_refused() {
    fn check<T: Real>() {
        for bad in [f64::NAN, f64::INFINITY] {
            let angle = EarthRotation::new(c::<T>(bad));
            assert!(Radars::<T>::new(angle, &[ground_radar()]).unwrap_err().contains("Earth rotation"));
            let rate = EarthRotation { angle_at_epoch: c::<T>(0.3), rate: c(bad) };
            assert!(Radars::<T>::new(rate, &[ground_radar()]).unwrap_err().contains("Earth rotation"));
        }
    }
    for_scalars!(check);
}

fn with_platform<T: Real>(platform: Platform<T>) -> SiteSensor<T, 3> {
    SiteSensor { platform, ..ground_radar() }
}

#[test]
fn site_latitude_outside_plus_minus_90_degrees_is_refused() {
    fn check<T: Real>() {
        for latitude in [90.001, -90.001, 180.0, 1e30] {
            assert_network_refused(&[with_platform(site::<T>(latitude, 0.0, 0.0))], "latitude");
        }
        for bad in [f64::NAN, f64::INFINITY] {
            let platform = Platform::Ground(GroundSite { latitude: c(bad), longitude: c(0.0), height: c(0.0) });
            assert_network_refused(&[with_platform::<T>(platform)], "latitude");
            let platform = Platform::Ground(GroundSite { latitude: c(0.0), longitude: c(bad), height: c(0.0) });
            assert_network_refused(&[with_platform::<T>(platform)], "longitude");
        }
        // The poles themselves are sites.
        assert!(network(&[with_platform(site::<T>(90.0, 0.0, 0.0))]).is_ok());
        assert!(network(&[with_platform(site::<T>(-90.0, 0.0, 0.0))]).is_ok());
    }
    for_scalars!(check);
}

#[test]
fn site_below_minus_1_km_is_refused() {
    fn check<T: Real>() {
        for height in [-1.001, -50.0, -6378.0, 100.001, f64::NAN, f64::NEG_INFINITY] {
            assert_network_refused(&[with_platform(site::<T>(40.0, -105.0, height))], "height");
        }
        // −1 km (the Dead Sea shore is −0.43 km) and 100 km are accepted.
        assert!(network(&[with_platform(site::<T>(40.0, -105.0, -1.0))]).is_ok());
        assert!(network(&[with_platform(site::<T>(40.0, -105.0, 100.0))]).is_ok());
    }
    for_scalars!(check);
}

#[test]
fn non_finite_or_non_positive_sigma_is_refused() {
    fn check<T: Real>() {
        for bad in [0.0, -0.02, f64::NAN, f64::INFINITY] {
            for component in 0..3 {
                let mut sensor = ground_radar::<T>();
                sensor.sigma[component] = c(bad);
                assert_network_refused(&[sensor], "noise standard deviation");
                let mut spacecraft = space_radar::<T>();
                spacecraft.sigma[component] = c(bad);
                assert_network_refused(&[ground_radar(), spacecraft], "noise standard deviation");
            }
        }
    }
    for_scalars!(check);
}

#[test]
fn empty_network_and_more_sensors_than_c_are_refused() {
    fn check<T: Real>() {
        assert_network_refused::<T>(&[], "no sensors");
        assert_network_refused(&[ground_radar::<T>(), space_radar(), ground_radar()], "capacity");
        assert!(network(&[ground_radar::<T>(), space_radar()]).is_ok());
    }
    for_scalars!(check);
}

fn cone<T: Real>(azimuth: f64, elevation: f64, half_angle: f64) -> Region<T> {
    Region::Look {
        shape: LookShape::Cone { azimuth: c(azimuth), elevation: c(elevation), half_angle: c(half_angle) },
        min_elevation: c(5.0 * DEGREE),
        range: Some([c(0.0), c(4000.0)]),
        range_rate: None,
    }
}

#[test]
fn cone_half_angle_zero_is_refused() {
    fn check<T: Real>() {
        for half_angle in [0.0, -0.1, f64::NAN] {
            let sensor = ground_radar::<T>().with_view(cone(0.0, 90.0 * DEGREE, half_angle));
            assert!(network(&[sensor]).is_err(), "half angle {half_angle}");
        }
        // 180° (every direction) is a valid cone.
        assert!(network(&[ground_radar::<T>().with_view(cone(0.0, 0.0, 180.0 * DEGREE))]).is_ok());
    }
    for_scalars!(check);
}

#[test]
fn field_of_view_of_zero_volume_is_refused() {
    fn check<T: Real>() {
        let look = |shape, min_elevation: f64, range: [f64; 2]| Region::Look {
            shape,
            min_elevation: c(min_elevation),
            range: Some(range.map(c::<T>)),
            range_rate: None,
        };
        let cases = [
            // Everything under the elevation mask: a box, and a cone about the nadir.
            look(LookShape::Box { azimuth: c(0.0), half_width: c(0.5), elevation: [c(0.0), c(0.1)] }, 0.2, [0.0, 4e3]),
            look(LookShape::Cone { azimuth: c(0.0), elevation: c(-1.5), half_angle: c(0.05) }, 0.0, [0.0, 4e3]),
            // An empty range window.
            look(LookShape::Cone { azimuth: c(0.0), elevation: c(1.0), half_angle: c(0.1) }, 0.0, [500.0, 500.0]),
        ];
        for view in cases {
            assert_network_refused(&[ground_radar::<T>().with_view(view)], "volume");
        }
    }
    for_scalars!(check);
}

#[test]
fn cone_half_angle_above_180_degrees_is_refused() {
    fn check<T: Real>() {
        for half_angle in [180.001 * DEGREE, 4.0, 7.0, 1e6] {
            let sensor = ground_radar::<T>().with_view(cone(0.0, 90.0 * DEGREE, half_angle));
            assert_network_refused(&[sensor], "half angle");
        }
    }
    for_scalars!(check);
}

#[test]
fn elevation_outside_plus_minus_90_degrees_is_refused() {
    fn check<T: Real>() {
        // The cone's boresight.
        for elevation in [90.001 * DEGREE, -91.0 * DEGREE, 3.0] {
            let sensor = ground_radar::<T>().with_view(cone(0.0, elevation, 10.0 * DEGREE));
            assert_network_refused(&[sensor], "elevation");
        }
        // The elevation mask and a box's elevations.
        let mask = |min_elevation: f64, elevation: [f64; 2]| Region::Look {
            shape: LookShape::Box { azimuth: c(0.0), half_width: c(0.5), elevation: elevation.map(c::<T>) },
            min_elevation: c(min_elevation),
            range: Some([c(0.0), c(4000.0)]),
            range_rate: None,
        };
        for (min_elevation, elevation) in [
            (-100.0 * DEGREE, [0.0, 0.5]),
            (0.0, [-100.0 * DEGREE, 0.5]),
            (0.0, [0.1, 100.0 * DEGREE]),
            (f64::NAN, [0.0, 0.5]),
        ] {
            let sensor = ground_radar::<T>().with_view(mask(min_elevation, elevation));
            assert_network_refused(&[sensor], "elevation");
        }
    }
    for_scalars!(check);
}

fn with_range<T: Real>(range: Option<[f64; 2]>) -> Region<T> {
    match radar_view::<T>() {
        Region::Look { shape, min_elevation, range_rate, .. } => {
            Region::Look { shape, min_elevation, range: range.map(|r| r.map(c::<T>)), range_rate }
        }
        other => other,
    }
}

#[test]
fn range_window_with_max_not_above_min_is_refused() {
    fn check<T: Real>() {
        for window in [[500.0, 500.0], [4000.0, 0.0], [0.0, f64::NAN], [f64::NEG_INFINITY, 10.0]] {
            let sensor = ground_radar::<T>().with_view(with_range(Some(window)));
            assert!(network(&[sensor]).is_err(), "{window:?}");
        }
    }
    for_scalars!(check);
}

#[test]
fn range_window_with_negative_min_is_refused() {
    fn check<T: Real>() {
        let sensor = ground_radar::<T>().with_view(with_range(Some([-100.0, 4000.0])));
        assert_network_refused(&[sensor], "range window");
    }
    for_scalars!(check);
}

#[test]
fn radar_network_without_a_range_window_is_refused() {
    fn check<T: Real>() {
        assert_network_refused(&[ground_radar::<T>().with_view(with_range(None))], "range window");
    }
    for_scalars!(check);
}

fn telescope<T: Real>(range: Option<[f64; 2]>) -> SiteSensor<T, 2> {
    SiteSensor {
        platform: site(40.0, -105.0, 1.6),
        sigma: [c(2e-6), c(2e-6)],
        detection: detection(Region::Look {
            shape: LookShape::Cone { azimuth: c(3.0), elevation: c(0.7), half_angle: c(0.1) },
            min_elevation: c(0.2),
            range: range.map(|r| r.map(c::<T>)),
            range_rate: None,
        }),
    }
}

#[test]
fn optical_network_with_a_range_window_is_refused() {
    fn check<T: Real>() {
        let rotation = EarthRotation::new(c(ROTATION));
        assert!(Telescopes::<T>::new(rotation, &[telescope(None)]).is_ok());
        match Telescopes::<T>::new(rotation, &[telescope(Some([0.0, 40_000.0]))]) {
            Err(why) => assert!(why.contains("range window"), "{why}"),
            Ok(_) => panic!("an optical network with a range window was accepted"),
        }
    }
    for_scalars!(check);
}

#[test]
fn network_sensor_detection_probability_outside_0_1_is_refused() {
    fn check<T: Real>() {
        for pd in [0.0, -0.5, 1.5, f64::NAN] {
            let mut sensor = ground_radar::<T>();
            sensor.detection.detection_probability = c(pd);
            assert_network_refused(&[sensor], "detection probability");
        }
    }
    for_scalars!(check);
}

#[test]
fn network_sensor_clutter_rate_not_positive_is_refused() {
    fn check<T: Real>() {
        for rate in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let mut sensor = ground_radar::<T>();
            sensor.detection.clutter_rate = c(rate);
            assert!(network(&[sensor]).is_err(), "clutter rate {rate}");
        }
    }
    for_scalars!(check);
}

#[test]
fn planar_field_of_view_in_a_network_is_refused() {
    fn check<T: Real>() {
        let rectangle = Region::Rectangle { min: [c(0.0), c(0.0)], max: [c(1.0), c(1.0)] };
        assert_network_refused(&[ground_radar::<T>().with_view(rectangle)], "look-angle");
    }
    for_scalars!(check);
}

#[test]
fn look_angle_region_with_a_planar_model_is_a_sensor_error() {
    fn check<T: Real>() {
        let config = Config {
            motion: tracker_core::ConstantVelocity { acceleration_noise: c(0.05) },
            measurement: PositionMeasurement::isotropic(c(0.4)),
            sensor: detection(radar_view::<T>()),
            birth: BirthModel::<T, 4, 1>::none(),
            death_probability: c(0.0),
            gate: None,
            children: Default::default(),
            selection: Default::default(),
            store_overflow: Default::default(),
            numerical_failure: Default::default(),
            track_loss: Default::default(),
            seed: 1,
        };
        let object = Gaussian { mean: SVector::<T, 4>::zeros(), covariance: SMatrix::identity() };
        match tracker_core::LinearTracker::<T, 4, 2, 2, 4, 1>::with_objects(config, &[object], 0.0) {
            Err(ConfigError::Sensor(why)) => assert!(why.contains("look-angle"), "{why}"),
            other => panic!("expected ConfigError::Sensor, got {other:?}"),
        }
    }
    for_scalars!(check);
}

// ---- Scans ------------------------------------------------------------------------------------------

#[test]
fn unknown_sensor_index_is_refused_unchanged() {
    fn check<T: Real>() {
        for sensor in [2, 3, usize::MAX] {
            assert_refused::<T>(
                |t| t.step_scan(&ScanGeometry { sensor, time: 5.0, observer: None }, &[measured(5.0)]),
                StepError::Placement(PlacementError::UnknownSensor { sensor, sensors: 2 }),
            );
        }
    }
    for_scalars!(check);
}

#[test]
fn spacecraft_scan_without_observer_is_refused_unchanged() {
    fn check<T: Real>() {
        assert_refused::<T>(
            |t| t.step_scan(&ScanGeometry { sensor: 1, time: 5.0, observer: None }, &[]),
            StepError::Placement(PlacementError::MissingObserver),
        );
    }
    for_scalars!(check);
}

#[test]
fn spacecraft_scan_with_a_non_finite_observer_is_refused_unchanged() {
    fn check<T: Real>() {
        for component in [0, 2, 3, 5] {
            for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
                let mut observer = spacecraft_observer::<T>();
                observer[component] = c(bad);
                assert_refused::<T>(
                    |t| t.step_scan(&ScanGeometry { sensor: 1, time: 5.0, observer: Some(observer) }, &[]),
                    StepError::Placement(PlacementError::NonFiniteObserver),
                );
            }
        }
    }
    for_scalars!(check);
}

#[test]
fn spacecraft_observer_inside_the_earth_is_refused_unchanged() {
    fn check<T: Real>() {
        // The centre, 6000 km on x, just under the pole (polar radius 6356.75 km), just inside the equator.
        let positions = [[0.0, 0.0, 0.0], [6000.0, 0.0, 0.0], [0.0, 0.0, 6356.0], [0.0, -6378.0, 0.0]];
        for [x, y, z] in positions {
            let observer = [x, y, z, 0.0, 7.5, 0.0].map(c::<T>);
            assert_refused::<T>(
                |t| t.step_scan(&ScanGeometry { sensor: 1, time: 5.0, observer: Some(observer) }, &[]),
                StepError::Placement(PlacementError::ObserverInsideEarth),
            );
        }
        // Just above the pole is outside.
        let mut tracker = small::<T>();
        let above = [0.0, 0.0, 6357.0, 7.5, 0.0, 0.0].map(c::<T>);
        assert!(tracker.step_scan(&ScanGeometry { sensor: 1, time: 5.0, observer: Some(above) }, &[]).is_ok());
    }
    for_scalars!(check);
}

#[test]
fn spacecraft_observer_beyond_a_plausible_distance_is_refused_unchanged() {
    fn check<T: Real>() {
        // Issue 33: 1e300 km (f64) and 1e20 km (f32) were accepted and the real track ended dropped.
        let far = if core::mem::size_of::<T>() == 8 { 1e300 } else { 1e20 };
        let beyond = tracker_core::sensor::MAX_OBSERVER_DISTANCE * 1.001;
        for distance in [far, beyond, 1e9] {
            for axis in 0..3 {
                let mut observer = [0.0, 0.0, 0.0, 0.0, 1.0, 0.0];
                observer[axis] = if axis == 1 { -distance } else { distance };
                let observer = observer.map(c::<T>);
                assert_refused::<T>(
                    |t| t.step_scan(&ScanGeometry { sensor: 1, time: 5.0, observer: Some(observer) }, &[]),
                    StepError::Placement(PlacementError::ObserverTooFar),
                );
            }
        }
        // At the Sun–Earth L2 distance (1.5e6 km) and just inside the bound: accepted.
        for distance in [1.5e6, tracker_core::sensor::MAX_OBSERVER_DISTANCE * 0.999] {
            let mut tracker = small::<T>();
            let observer = [distance, 0.0, 0.0, 0.0, 0.3, 0.0].map(c::<T>);
            assert!(tracker.step_scan(&ScanGeometry { sensor: 1, time: 5.0, observer: Some(observer) }, &[]).is_ok());
        }
    }
    for_scalars!(check);
}

#[test]
fn observer_passed_to_a_ground_site_is_refused_unchanged() {
    fn check<T: Real>() {
        let observer = Some(spacecraft_observer::<T>());
        assert_refused::<T>(
            |t| t.step_scan(&ScanGeometry { sensor: 0, time: 5.0, observer }, &[measured(5.0)]),
            StepError::Placement(PlacementError::UnexpectedObserver),
        );
    }
    for_scalars!(check);
}

#[test]
fn gap_beyond_max_step_times_max_substeps_is_refused_unchanged() {
    fn check<T: Real>() {
        // 20 s × 2000 sub-steps = 40,000 s.
        for time in [40_000.001, 40_001.0, 1e9, f64::MAX] {
            assert_refused::<T>(
                |t| t.step_scan(&ScanGeometry { sensor: 0, time, observer: None }, &[]),
                StepError::TimeStepTooLong { limit_seconds: 40_000 },
            );
        }
        // The bound itself is accepted.
        let mut tracker = small::<T>();
        tracker.step_scan(&ScanGeometry::single(40_000.0), &[]).unwrap();
        assert_eq!(tracker.time(), 40_000.0);
    }
    for_scalars!(check);
}

#[test]
fn measurement_outside_the_look_field_of_view_is_refused_unchanged() {
    fn check<T: Real>() {
        let z = measured::<T>(5.0);
        let outside = [
            // Under the 5° mask.
            SVector::from([z[0], z[1], c(2.0 * DEGREE)]),
            // Above the mask but outside the 80° cone about the zenith (elevation 7°).
            SVector::from([z[0], z[1], c(7.0 * DEGREE)]),
            // Beyond the range window, and a negative range.
            SVector::from([c(4000.5), z[1], z[2]]),
            SVector::from([c(-1.0), z[1], z[2]]),
            // Below the horizon.
            SVector::from([z[0], z[1], c(-45.0 * DEGREE)]),
        ];
        for bad in outside {
            assert_refused::<T>(
                |t| t.step_scan(&ScanGeometry::single(5.0), &[z, bad]),
                StepError::MeasurementOutsideFieldOfView { index: 1 },
            );
        }
        // A non-finite angle is a non-finite measurement.
        assert_refused::<T>(
            |t| t.step_scan(&ScanGeometry::single(5.0), &[SVector::from([z[0], c(f64::NAN), z[2]])]),
            StepError::NonFiniteMeasurement { index: 0 },
        );
    }
    for_scalars!(check);
}

#[test]
fn measured_elevation_outside_plus_minus_90_degrees_is_refused_unchanged() {
    fn check<T: Real>() {
        let z = measured::<T>(5.0);
        for elevation in [90.001 * DEGREE, 2.0, 3.1] {
            assert_refused::<T>(
                |t| t.step_scan(&ScanGeometry::single(5.0), &[SVector::from([z[0], z[1], c(elevation)])]),
                StepError::MeasurementOutsideFieldOfView { index: 0 },
            );
        }
    }
    for_scalars!(check);
}

#[test]
fn measured_azimuth_outside_plus_minus_180_degrees_is_refused_unchanged() {
    // An azimuth is reported in (−π, π]; one outside [−π, π] is no measurement the sensor makes (issue 13:
    // angles outside their ranges are a typed error), even though a + 2πk names the direction a.
    fn check<T: Real>() {
        let z = measured::<T>(5.0);
        for turns in [-3.0, 1.0, 2.0] {
            let shifted = SVector::from([z[0], z[1] + c(turns * 2.0 * core::f64::consts::PI), z[2]]);
            assert_refused::<T>(
                |t| t.step_scan(&ScanGeometry::single(5.0), &[shifted]),
                StepError::MeasurementOutsideFieldOfView { index: 0 },
            );
        }
        // The wrapped azimuth itself is accepted.
        small::<T>().step_scan(&ScanGeometry::single(5.0), &[z]).unwrap();
    }
    for_scalars!(check);
}
