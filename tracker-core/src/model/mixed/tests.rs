use super::*;
use crate::ekf::{self, Innovation};
use crate::model::{EARTH_MU, MotionModel, ProcessNoise, SensorNetwork, TwoBodyJ2};
use crate::sensor::{GroundSite, LookShape};
use crate::store::TrackLabel;
use crate::tracker::in_field_of_view;
use crate::{BirthModel, Config, Gaussian, PriorHypothesis, PriorObject, StepError, Tracker};

const DEGREE: f64 = core::f64::consts::PI / 180.0;

fn ground(latitude: f64, longitude: f64) -> Platform<f64> {
    Platform::Ground(GroundSite { latitude: latitude * DEGREE, longitude: longitude * DEGREE, height: 0.2 })
}

/// A wide cone about the zenith with the windows of what a kind measures.
fn field_of_view(axes: LookAxes) -> Region<f64> {
    Region::Look {
        shape: LookShape::Cone { azimuth: 0.0, elevation: 90.0 * DEGREE, half_angle: 80.0 * DEGREE },
        min_elevation: 5.0 * DEGREE,
        range: axes.range.then_some([0.0, 4000.0]),
        range_rate: axes.range_rate.then_some([-8.0, 8.0]),
    }
}

fn site_sensor<const D: usize>(platform: Platform<f64>, sigma: [f64; D], axes: LookAxes) -> SiteSensor<f64, D> {
    let detection = Sensor { detection_probability: 0.9, clutter_rate: 1.0, field_of_view: field_of_view(axes) };
    SiteSensor { platform, sigma, detection }
}

/// The noise of each kind's components, padded.
fn sigma(kind: SensorKind) -> [f64; 4] {
    match kind {
        SensorKind::Radar => [0.02, 0.02 * DEGREE, 0.02 * DEGREE, 0.0],
        SensorKind::RadarRangeRate => [0.02, 0.02 * DEGREE, 0.02 * DEGREE, 1e-3],
        SensorKind::OpticalRaDec => [2e-5, 2e-5, 0.0, 0.0],
        SensorKind::AzEl => [0.01 * DEGREE, 0.01 * DEGREE, 0.0, 0.0],
        SensorKind::Range => [0.005, 0.0, 0.0, 0.0],
        SensorKind::RangeRangeRate => [0.005, 2e-4, 0.0, 0.0],
    }
}

fn mixed_sensor(kind: SensorKind, platform: Platform<f64>) -> MixedSensor<f64> {
    MixedSensor { kind, sensor: site_sensor(platform, sigma(kind), kind.axes()) }
}

const SITES: [(f64, f64); 4] = [(40.0, -105.0), (38.0, -100.0), (41.0, -103.0), (39.0, -104.0)];

/// A circular LEO object 900 km from site 0 at azimuth 160°, elevation 60° at time 0, moving westwards.
fn truth(rotation: &EarthRotation<f64>) -> SVector<f64, 6> {
    let GroundSite { .. } = GroundSite { latitude: 0.0, longitude: 0.0, height: 0.0 };
    let Platform::Ground(site) = ground(SITES[0].0, SITES[0].1) else { unreachable!() };
    let (observer, frame) = (site.observer(rotation, 0.0), site.enu(rotation, 0.0));
    let (azimuth, elevation, range) = (160.0 * DEGREE, 60.0 * DEGREE, 900.0);
    let (e, n, u) = (azimuth.sin() * elevation.cos(), azimuth.cos() * elevation.cos(), elevation.sin());
    let p: [f64; 3] =
        core::array::from_fn(|k| observer[k] + range * (e * frame[0][k] + n * frame[1][k] + u * frame[2][k]));
    let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
    let west = frame[0].map(|v| -v);
    let along = (west[0] * p[0] + west[1] * p[1] + west[2] * p[2]) / r;
    let w: [f64; 3] = core::array::from_fn(|k| west[k] - along * p[k] / r);
    let scale = (EARTH_MU / r).sqrt() / (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
    SVector::from([p[0], p[1], p[2], w[0] * scale, w[1] * scale, w[2] * scale])
}

fn motion() -> TwoBodyJ2<f64> {
    TwoBodyJ2::<f64>::earth(ProcessNoise::Isotropic(1e-10), 20.0, 2000)
}

fn prior_covariance() -> SMatrix<f64, 6, 6> {
    let mut covariance = SMatrix::<f64, 6, 6>::zeros();
    for k in 0..3 {
        covariance[(k, k)] = 0.25;
        covariance[(k + 3, k + 3)] = 1e-4;
    }
    covariance
}

fn config<G>(measurement: G, detection: Sensor<f64>) -> Config<f64, TwoBodyJ2<f64>, G, 6, 1> {
    Config {
        motion: motion(),
        measurement,
        sensor: detection,
        birth: BirthModel::<f64, 6, 1>::none(),
        death_probability: 0.0,
        gate: None,
        children: Default::default(),
        selection: Default::default(),
        store_overflow: Default::default(),
        numerical_failure: Default::default(),
        track_loss: Default::default(),
        seed: 3,
    }
}

/// A small deterministic perturbation of component `k` at scan `scan`, in units of σ.
fn wobble(scan: u32, k: usize) -> f64 {
    (f64::from(scan) * 1.7 + k as f64 * 0.9).sin() * 0.8
}

type Tracker4<G> = Tracker<f64, TwoBodyJ2<f64>, G, 6, 4, 8, 4, 8, 16, 1>;

/// Steps a network of one kind (`SensorNetwork` of `X`, `D` components) and a `MixedNetwork` of the
/// same sensors side by side, the second sensor of each with light time `mode`; returns their digests
/// after every scan.
fn side_by_side<X: Placeable<f64, D>, const D: usize>(kind: SensorKind, mode: LightTime) -> (Vec<u64>, Vec<u64>) {
    let rotation = EarthRotation::new(0.3);
    let platforms = [ground(SITES[0].0, SITES[0].1), ground(SITES[1].0, SITES[1].1)];
    let own: [SiteSensor<f64, D>; 2] =
        platforms.map(|p| site_sensor(p, core::array::from_fn(|k| sigma(kind)[k]), kind.axes()));
    let mixed = platforms.map(|p| mixed_sensor(kind, p));
    let single: SensorNetwork<f64, X, D, 2> =
        SensorNetwork::new(rotation, &own).unwrap().with_light_time(1, mode).unwrap();
    let network: MixedNetwork<f64, 2> = MixedNetwork::new(rotation, &mixed).unwrap().with_light_time(1, mode).unwrap();
    let truth0 = truth(&rotation);
    let mut start = truth0;
    start[0] += 0.3;
    start[4] -= 0.005;
    let objects =
        [PriorObject { label: TrackLabel(0), state: Gaussian { mean: start, covariance: prior_covariance() } }];
    let prior = [PriorHypothesis { weight: 1.0, objects: &objects }];
    let detection = own[0].detection;
    let mut a: Tracker<f64, TwoBodyJ2<f64>, _, 6, D, 8, 4, 8, 16, 1> =
        Tracker::new(config(single, detection), &prior, 0.0).unwrap();
    let mut b: Tracker4<MixedNetwork<f64, 2>> = Tracker::new(config(network, detection), &prior, 0.0).unwrap();
    let (mut digests_a, mut digests_b) = (Vec::new(), Vec::new());
    let mut state = truth0;
    for scan in 1..=10u32 {
        state = motion().propagate(&state, 10.0).unwrap().state;
        let geometry = ScanGeometry { sensor: scan as usize % 2, time: 10.0 * f64::from(scan), observer: None };
        let placed = single.place(&geometry).unwrap();
        let exact = placed.measure(&state);
        let sigmas = sigma(kind);
        let z = SVector::<f64, D>::from_fn(|k, _| exact[k] + sigmas[k] * wobble(scan, k));
        // A second measurement: the first one moved by 30 σ in its first component (clutter).
        let mut clutter = z;
        clutter[0] += 30.0 * sigmas[0];
        let scan_a = [z, clutter];
        let scan_b = scan_a.map(|z| pad(&z));
        a.step_scan(&geometry, &scan_a).unwrap();
        b.step_scan(&geometry, &scan_b).unwrap();
        digests_a.push(a.digest());
        digests_b.push(b.digest());
    }
    assert!(b.map_hypothesis().tracks().count() == 1, "the object is kept");
    (digests_a, digests_b)
}

#[test]
fn a_network_of_one_kind_gives_the_bits_of_that_kind_alone() {
    let (radar, mixed) = side_by_side::<RadarRangeAzEl<f64>, 3>(SensorKind::Radar, LightTime::Off);
    assert_eq!(radar, mixed);
    let (radar_rate, mixed) = side_by_side::<RadarRangeRate<f64>, 4>(SensorKind::RadarRangeRate, LightTime::Off);
    assert_eq!(radar_rate, mixed);
    let (optical, mixed) = side_by_side::<OpticalRaDec<f64>, 2>(SensorKind::OpticalRaDec, LightTime::Off);
    assert_eq!(optical, mixed);
}

#[test]
fn with_light_time_a_network_of_one_kind_still_gives_the_bits_of_that_kind_alone() {
    for mode in [LightTime::TwoWayReceive, LightTime::TwoWayTransmit, LightTime::OneWayReceive] {
        let (radar, mixed) = side_by_side::<RadarRangeAzEl<f64>, 3>(SensorKind::Radar, mode);
        assert_eq!(radar, mixed, "{mode:?}");
        let (unset, _) = side_by_side::<RadarRangeAzEl<f64>, 3>(SensorKind::Radar, LightTime::Off);
        assert_ne!(radar[1..], unset[1..], "{mode:?}: the second sensor's scans move the posterior");
        let (radar_rate, mixed) = side_by_side::<RadarRangeRate<f64>, 4>(SensorKind::RadarRangeRate, mode);
        assert_eq!(radar_rate, mixed, "{mode:?}");
    }
    let (optical, mixed) = side_by_side::<OpticalRaDec<f64>, 2>(SensorKind::OpticalRaDec, LightTime::OneWayReceive);
    assert_eq!(optical, mixed);
}

/// τ of `state` seen from `observer` with direction `k`, the light-time equation solved to convergence.
fn converged_light_time(state: &SVector<f64, 6>, observer: &[f64; 6], k: f64) -> (f64, [f64; 3]) {
    let mut tau = 0.0;
    let mut d = [0.0; 3];
    for _ in 0..20 {
        d = core::array::from_fn(|i| state[i] + k * tau * state[i + 3] - observer[i]);
        tau = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt() / crate::model::light_time::SPEED_OF_LIGHT;
    }
    (tau, d)
}

#[test]
fn a_range_only_sensor_with_two_way_light_time_measures_the_light_time_equation() {
    let rotation = EarthRotation::new(0.3);
    let sensors = [mixed_sensor(SensorKind::Range, ground(SITES[0].0, SITES[0].1))];
    let plain: MixedNetwork<f64, 1> = MixedNetwork::new(rotation, &sensors).unwrap();
    let state = truth(&rotation);
    let at = ScanGeometry { sensor: 0, time: 40.0, observer: None };
    for (mode, k) in [(LightTime::TwoWayReceive, -1.0), (LightTime::TwoWayTransmit, 1.0)] {
        let network = plain.with_light_time(0, mode).unwrap();
        assert_eq!(network.light_time(0), mode);
        let placed = network.place(&at).unwrap();
        let observer = placed.placed().observer;
        let (tau, d) = converged_light_time(&state, &observer, k);
        let rho = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        // The mean of both legs: the site moved 2τ v_s between them.
        let along = (0..3).map(|i| d[i] / rho * observer[i + 3]).sum::<f64>();
        let expected = rho - k * tau * along;
        let z = placed.measure(&state);
        assert!((z[0] - expected).abs() < 1e-9, "{mode:?}: {} vs {expected}", z[0]);
        assert_eq!(&z.as_slice()[1..], &[0.0; 3], "the padding stays zero");
        // Light time moves the range by (d̂ · v) τ: metres, well above the 1e-9 km agreement.
        let unset = plain.place(&at).unwrap().measure(&state)[0];
        assert!((z[0] - unset).abs() > 1e-3, "{mode:?}: {} vs {unset}", z[0]);
        // The range of the radar kind with the same light time: the same number.
        let radar = [mixed_sensor(SensorKind::Radar, ground(SITES[0].0, SITES[0].1))];
        let radar: MixedNetwork<f64, 1> =
            MixedNetwork::new(rotation, &radar).unwrap().with_light_time(0, mode).unwrap();
        assert_eq!(radar.place(&at).unwrap().measure(&state)[0], z[0]);
        // The Jacobian against central differences (its range row; the padding zero).
        let h = placed.jacobian(&state);
        for j in 0..6 {
            // ∂ρ/∂v is kτ d̂ (≈ 3e-3 s): a step of 1 m/s keeps rounding (≈ 1e-12 km) below 1e-6 of it.
            let step = 1e-3;
            let (mut up, mut down) = (state, state);
            up[j] += step;
            down[j] -= step;
            let numeric = (placed.measure(&up)[0] - placed.measure(&down)[0]) / (2.0 * step);
            assert!(
                (h[(0, j)] - numeric).abs() < 1e-4 * h[(0, j)].abs().max(1e-3),
                "{mode:?} column {j}: {} vs {numeric}",
                h[(0, j)]
            );
            assert_eq!([h[(1, j)], h[(2, j)], h[(3, j)]], [0.0; 3]);
        }
    }
}

#[test]
fn light_time_is_refused_where_it_does_not_apply_and_off_changes_nothing() {
    let rotation = EarthRotation::new(0.3);
    let network = every_kind(rotation);
    for (sensor, kind) in SensorKind::ALL.into_iter().enumerate() {
        assert_eq!(network.with_light_time(sensor, LightTime::TwoWayReceive).is_ok(), kind.axes().range, "{kind}");
        assert!(network.with_light_time(sensor, LightTime::OneWayReceive).is_ok(), "{kind}");
        assert_eq!(network.with_light_time(sensor, LightTime::Off), Ok(network));
    }
    assert!(network.with_light_time(6, LightTime::OneWayReceive).is_err());
    // Off after on: the network as it was.
    let on = network.with_light_time(0, LightTime::TwoWayReceive).unwrap();
    assert_ne!(on, network);
    assert_eq!(on.with_light_time(0, LightTime::Off), Ok(network));
}

/// A `K`-component model that picks rows `rows` of the radar with range-rate: the kinds without a model
/// of their own, written in their own dimension.
#[derive(Clone, Copy)]
struct Rows<const K: usize> {
    radar: RadarRangeRate<f64>,
    rows: [usize; K],
    sigma: [f64; K],
    wrap: Option<usize>,
}

impl<const K: usize> Measure<f64, 6, K> for Rows<K> {
    fn measure(&self, state: &SVector<f64, 6>) -> SVector<f64, K> {
        let z = self.radar.measure(state);
        SVector::from_fn(|i, _| z[self.rows[i]])
    }
    fn jacobian(&self, state: &SVector<f64, 6>) -> SMatrix<f64, K, 6> {
        let h = self.radar.jacobian(state);
        SMatrix::from_fn(|i, j| h[(self.rows[i], j)])
    }
    fn noise_covariance(&self) -> SMatrix<f64, K, K> {
        SMatrix::from_fn(|i, j| if i == j { self.sigma[i] * self.sigma[i] } else { 0.0 })
    }
    fn residual(&self, z: &SVector<f64, K>, predicted: &SVector<f64, K>) -> SVector<f64, K> {
        let mut nu = z - predicted;
        if let Some(k) = self.wrap {
            nu[k] = wrap_angle(nu[k]);
        }
        nu
    }
}

/// Innovation, score and update of `look` against the same in `K` dimensions: equal bits.
fn same_bits<const K: usize>(look: &MixedLook<f64>, own: &Rows<K>, state: &Gaussian<f64, 6>) {
    let padded = ekf::innovation(look, state).unwrap();
    let direct: Innovation<f64, K> = ekf::innovation(own, state).unwrap();
    let z_own = SVector::<f64, K>::from_fn(|i, _| direct.predicted[i] + 3.0 * own.sigma[i]);
    let z = pad(&z_own);
    for i in 0..K {
        for j in 0..K {
            assert_eq!(
                padded.cholesky[(i, j)].to_bits(),
                direct.cholesky[(i, j)].to_bits(),
                "L {i} {j} {:?}",
                look.kind
            );
        }
    }
    assert_eq!(padded.log_normaliser.to_bits(), direct.log_normaliser.to_bits(), "normaliser {:?}", look.kind);
    let (d_padded, l_padded) = padded.score_residual(&look.residual(&z, &padded.predicted));
    let (d_own, l_own) = direct.score_residual(&own.residual(&z_own, &direct.predicted));
    assert_eq!((d_padded.to_bits(), l_padded.to_bits()), (d_own.to_bits(), l_own.to_bits()), "{:?}", look.kind);
    let updated = ekf::update(look, state, &padded, &z).unwrap();
    let expected = ekf::update(own, state, &direct, &z_own).unwrap();
    assert_eq!(updated, expected, "{:?}", look.kind);
    // Whatever the padding holds, the residual ignores it; `fits` refuses it.
    if K < 4 {
        let mut dirty = z;
        dirty[3] = 7.0;
        assert_eq!(look.residual(&dirty, &padded.predicted)[3], 0.0);
        assert!(look.fits(&z) && !look.fits(&dirty));
    }
}

#[test]
fn the_kinds_without_a_model_of_their_own_are_scored_and_updated_in_their_own_dimension() {
    let rotation = EarthRotation::new(0.3);
    let Platform::Ground(site) = ground(SITES[0].0, SITES[0].1) else { unreachable!() };
    let (observer, frame) = (site.observer(&rotation, 0.0), site.enu(&rotation, 0.0));
    let look = |kind| MixedLook {
        kind,
        observer,
        frame,
        sigma: sigma(kind),
        births: SensorBirths::FromModel,
        light_time: LightTime::Off,
    };
    let radar = RadarRangeRate { observer, enu: frame, sigma: [1.0; 4] };
    let state = Gaussian { mean: truth(&rotation), covariance: prior_covariance() };
    let s = |kind| sigma(kind);
    same_bits(
        &look(SensorKind::AzEl),
        &Rows { radar, rows: [1, 2], sigma: [s(SensorKind::AzEl)[0], s(SensorKind::AzEl)[1]], wrap: Some(0) },
        &state,
    );
    same_bits(
        &look(SensorKind::Range),
        &Rows { radar, rows: [0], sigma: [s(SensorKind::Range)[0]], wrap: None },
        &state,
    );
    let rr = s(SensorKind::RangeRangeRate);
    same_bits(
        &look(SensorKind::RangeRangeRate),
        &Rows { radar, rows: [0, 3], sigma: [rr[0], rr[1]], wrap: None },
        &state,
    );
    let r = s(SensorKind::Radar);
    same_bits(
        &look(SensorKind::Radar),
        &Rows { radar, rows: [0, 1, 2], sigma: [r[0], r[1], r[2]], wrap: Some(1) },
        &state,
    );
    let full = s(SensorKind::RadarRangeRate);
    same_bits(
        &look(SensorKind::RadarRangeRate),
        &Rows { radar, rows: [0, 1, 2, 3], sigma: full, wrap: Some(1) },
        &state,
    );
}

/// A network of every kind, each at its own site (the telescope at site 1 too).
fn every_kind(rotation: EarthRotation<f64>) -> MixedNetwork<f64, 6> {
    let sensors = SensorKind::ALL.map(|kind| {
        let (latitude, longitude) = SITES[SensorKind::ALL.iter().position(|k| *k == kind).unwrap_or(0) % 4];
        mixed_sensor(kind, ground(latitude, longitude))
    });
    MixedNetwork::new(rotation, &sensors).unwrap()
}

#[test]
fn every_kind_in_turn_keeps_one_object_and_wrong_kinds_are_refused_unchanged() {
    let rotation = EarthRotation::new(0.3);
    let network = every_kind(rotation);
    assert_eq!(network.kinds().count(), 6);
    let truth0 = truth(&rotation);
    let mut start = truth0;
    start[0] += 0.3;
    start[4] -= 0.005;
    let objects =
        [PriorObject { label: TrackLabel(0), state: Gaussian { mean: start, covariance: prior_covariance() } }];
    let prior = [PriorHypothesis { weight: 1.0, objects: &objects }];
    let detection = network.sensors()[0].sensor.detection;
    let mut tracker: Tracker4<MixedNetwork<f64, 6>> = Tracker::new(config(network, detection), &prior, 0.0).unwrap();
    let mut state = truth0;
    let mut error = f64::INFINITY;
    for scan in 1..=18u32 {
        state = motion().propagate(&state, 10.0).unwrap().state;
        let sensor = scan as usize % 6;
        let geometry = ScanGeometry { sensor, time: 10.0 * f64::from(scan), observer: None };
        let placed = network.place(&geometry).unwrap();
        let kind = placed.placed().kind;
        let exact = placed.measure(&state);
        let z = SVector::<f64, 4>::from_fn(|k, _| {
            if k < kind.dimension() { exact[k] + sigma(kind)[k] * wobble(scan, k) } else { 0.0 }
        });
        let before = tracker.digest();
        if kind != SensorKind::RadarRangeRate {
            let mut wrong = z;
            wrong[3] = 1.0;
            assert_eq!(tracker.step_scan(&geometry, &[wrong]), Err(StepError::MeasurementOfWrongKind { index: 0 }));
            assert_eq!(tracker.digest(), before);
        }
        tracker.step_scan(&geometry, &[z]).unwrap();
        let map = tracker.map_hypothesis();
        let track = map.tracks().next().expect("the object is kept");
        error = (track.state.mean.fixed_rows::<3>(0) - state.fixed_rows::<3>(0)).norm();
        eprintln!("scan {scan}: {kind} error {error:.3} km, weight {}", map.weight());
        assert!(map.weight() > 0.99 && error < 1.0, "scan {scan} ({kind}): weight {} error {error} km", map.weight());
    }
    assert!(error < 0.3, "{error} km after eighteen scans");
}

#[test]
fn range_only_sensors_read_their_field_of_view_from_the_state_and_their_windows() {
    let rotation = EarthRotation::new(0.3);
    let network = every_kind(rotation);
    let range_sensor = SensorKind::ALL.iter().position(|k| *k == SensorKind::Range).unwrap();
    let placed = network.place(&ScanGeometry { sensor: range_sensor, time: 0.0, observer: None }).unwrap();
    let region = network.sensors()[range_sensor].sensor.detection.field_of_view;
    let object = Gaussian { mean: truth(&rotation), covariance: prior_covariance() };
    let innovation = ekf::innovation(&placed, &object).unwrap();
    assert!(in_field_of_view(&region, &placed, &object, &innovation.predicted));
    // The same object on the far side of the Earth: its range would be in the window, its direction is not.
    let mut behind = object;
    for k in 0..6 {
        behind.mean[k] = -object.mean[k];
    }
    let innovation = ekf::innovation(&placed, &behind).unwrap();
    assert!(!in_field_of_view(&region, &placed, &behind, &innovation.predicted));
    // Measurements: in view exactly when the range is in the window.
    assert!(placed.measurement_in_view(&region, &SVector::from([1000.0, 0.0, 0.0, 0.0])));
    assert!(!placed.measurement_in_view(&region, &SVector::from([4000.5, 0.0, 0.0, 0.0])));
    // Its clutter volume is the window's length, in km.
    assert_eq!(network.volume(range_sensor), Some(4000.0));
    let rr = SensorKind::ALL.iter().position(|k| *k == SensorKind::RangeRangeRate).unwrap();
    assert_eq!(network.volume(rr), Some(4000.0 * 16.0));
    // Az/el has the radar's angular area, without the range window.
    let az_el = SensorKind::ALL.iter().position(|k| *k == SensorKind::AzEl).unwrap();
    let radar = network.volume(0).unwrap();
    assert!((network.volume(az_el).unwrap() * 4000.0 - radar).abs() < 1e-9 * radar);
}

#[test]
fn births_come_from_every_kind_with_angles_and_not_from_range_alone() {
    let rotation = EarthRotation::new(0.3);
    let network = every_kind(rotation);
    let state = truth(&rotation);
    let region = AdmissibleRegion::leo();
    for (index, kind) in SensorKind::ALL.into_iter().enumerate() {
        let placed = network.place(&ScanGeometry { sensor: index, time: 0.0, observer: None }).unwrap();
        let z = placed.measure(&state);
        let mut out = [BirthComponent::<f64, 6>::ZERO; crate::model::MAX_BIRTH_COMPONENTS];
        let result = placed.birth_components(&z, &region, &mut out);
        if !kind.measures_angles() {
            assert_eq!(result, Err(BirthError::Unsupported), "{kind}");
            continue;
        }
        let count = result.unwrap_or_else(|e| panic!("{kind}: {e:?}"));
        assert!(count > 0, "{kind}");
        // Every component lies on the measured line of sight.
        let observer = placed.placed().observer;
        let truth_direction = (state.fixed_rows::<3>(0) - SVector::<f64, 3>::from_fn(|k, _| observer[k])).normalize();
        for component in &out[..count] {
            let direction =
                (component.state.mean.fixed_rows::<3>(0) - SVector::<f64, 3>::from_fn(|k, _| observer[k])).normalize();
            let angle = truth_direction.dot(&direction).clamp(-1.0, 1.0).acos();
            assert!(angle < 1e-6, "{kind}: component {angle} rad off the line of sight");
        }
    }
}

/// A telescope with its own birth region (the GEO belt) puts its births on the GEO shell, while the
/// network's other optical-region births stay in the birth model's region (LEO here).
#[test]
fn a_sensor_with_its_own_birth_region_uses_it() {
    let rotation = EarthRotation::new(0.3);
    let telescope = SensorKind::ALL.iter().position(|k| *k == SensorKind::OpticalRaDec).unwrap_or(0);
    let az_el = SensorKind::ALL.iter().position(|k| *k == SensorKind::AzEl).unwrap_or(0);
    let network = every_kind(rotation).with_births(telescope, SensorBirths::Region(AdmissibleRegion::geo())).unwrap();
    assert_eq!(network.births(telescope), SensorBirths::Region(AdmissibleRegion::geo()));
    assert_eq!(network.births(az_el), SensorBirths::FromModel);
    assert!(every_kind(rotation).with_births(6, SensorBirths::Off).is_err());
    let broken = AdmissibleRegion { mu: -1.0, ..AdmissibleRegion::geo() };
    assert!(every_kind(rotation).with_births(0, SensorBirths::Region(broken)).is_err());
    let state = truth(&rotation);
    let radii = |sensor: usize| {
        let placed = network.place(&ScanGeometry { sensor, time: 0.0, observer: None }).unwrap();
        let z = placed.measure(&state);
        let mut out = [BirthComponent::<f64, 6>::ZERO; crate::model::MAX_BIRTH_COMPONENTS];
        let count = placed.birth_components(&z, &AdmissibleRegion::leo(), &mut out).unwrap();
        out[..count].iter().map(|c| c.state.mean.fixed_rows::<3>(0).norm()).collect::<Vec<f64>>()
    };
    let geo = radii(telescope);
    assert!(!geo.is_empty() && geo.iter().all(|r| (r - 42_164.0).abs() < 300.0), "{geo:?}");
    let leo = radii(az_el);
    assert!(!leo.is_empty() && leo.iter().all(|r| *r < 6378.137 + 2100.0), "{leo:?}");
    // Births off: the sensor's measurements give none.
    let silent = network.with_births(az_el, SensorBirths::Off).unwrap();
    let placed = silent.place(&ScanGeometry { sensor: az_el, time: 0.0, observer: None }).unwrap();
    let mut out = [BirthComponent::<f64, 6>::ZERO; crate::model::MAX_BIRTH_COMPONENTS];
    let z = placed.measure(&state);
    assert_eq!(placed.birth_components(&z, &AdmissibleRegion::leo(), &mut out), Err(BirthError::Unsupported));
}

#[test]
fn invalid_sensors_and_packs_are_refused() {
    let rotation = EarthRotation::new(0.0);
    let mut padded_noise = mixed_sensor(SensorKind::AzEl, ground(40.0, -105.0));
    padded_noise.sensor.sigma[2] = 0.1;
    assert!(MixedNetwork::<f64, 2>::new(rotation, &[padded_noise]).is_err());
    let mut zero_window = mixed_sensor(SensorKind::Range, ground(40.0, -105.0));
    if let Region::Look { range, .. } = &mut zero_window.sensor.detection.field_of_view {
        *range = Some([500.0, 500.0]);
    }
    assert!(MixedNetwork::<f64, 2>::new(rotation, &[zero_window]).is_err());
    let mut range_window_on_angles = mixed_sensor(SensorKind::AzEl, ground(40.0, -105.0));
    range_window_on_angles.sensor.detection.field_of_view = field_of_view(SensorKind::Radar.axes());
    assert!(MixedNetwork::<f64, 2>::new(rotation, &[range_window_on_angles]).is_err());
    let two = [mixed_sensor(SensorKind::Radar, ground(40.0, -105.0)); 3];
    assert!(MixedNetwork::<f64, 2>::new(rotation, &two).is_err());
    let network = MixedNetwork::<f64, 2>::new(rotation, &two[..2]).unwrap();
    assert_eq!(
        network.pack(0, &KindMeasurement::Range(1.0)),
        Err(KindError::WrongKind { sensor: 0, expected: SensorKind::Radar, received: SensorKind::Range })
    );
    assert_eq!(network.pack(2, &KindMeasurement::Range(1.0)), Err(KindError::UnknownSensor { sensor: 2, sensors: 2 }));
    assert_eq!(network.pack(1, &KindMeasurement::Radar([1.0, 2.0, 3.0])).map(|z| z[3]), Ok(0.0));
}

/// MAP weights after each telescope scan of a radar-tracked object, with the telescope's cone `cone`
/// (one clutter measurement per telescope scan, inside its cone; the object never detected by it).
fn weights_under_telescope_scans(cone: LookShape<f64>) -> Vec<f64> {
    let rotation = EarthRotation::new(0.3);
    let radar = mixed_sensor(SensorKind::Radar, ground(SITES[0].0, SITES[0].1));
    let mut telescope = mixed_sensor(SensorKind::OpticalRaDec, ground(SITES[1].0, SITES[1].1));
    if let Region::Look { shape, .. } = &mut telescope.sensor.detection.field_of_view {
        *shape = cone;
    }
    let network: MixedNetwork<f64, 2> = MixedNetwork::new(rotation, &[radar, telescope]).unwrap();
    let truth0 = truth(&rotation);
    let objects =
        [PriorObject { label: TrackLabel(0), state: Gaussian { mean: truth0, covariance: prior_covariance() } }];
    let prior = [PriorHypothesis { weight: 1.0, objects: &objects }];
    let config = Config { death_probability: 0.01, ..config(network, radar.sensor.detection) };
    let mut tracker: Tracker4<MixedNetwork<f64, 2>> = Tracker::new(config, &prior, 0.0).unwrap();
    let mut state = truth0;
    let mut weights = Vec::new();
    for scan in 1..=12u32 {
        state = motion().propagate(&state, 10.0).unwrap().state;
        let sensor = scan as usize % 2;
        let geometry = ScanGeometry { sensor, time: 10.0 * f64::from(scan), observer: None };
        let placed = network.place(&geometry).unwrap();
        let z = if sensor == 0 {
            placed.measure(&state)
        } else {
            // Clutter at the telescope's boresight, as (α, δ).
            let Region::Look { shape: LookShape::Cone { azimuth, elevation, .. }, .. } =
                network.sensors()[1].sensor.detection.field_of_view
            else {
                unreachable!()
            };
            let (direction, _) = placed.placed().az_el_as_ra_dec(azimuth, elevation);
            pad(&direction)
        };
        tracker.step_scan(&geometry, &[z]).unwrap();
        if sensor == 1 {
            let map = tracker.map_hypothesis();
            let kept = map.tracks().count();
            weights.push(if kept == 1 { map.weight() } else { 0.0 });
        }
    }
    weights
}

#[test]
fn a_radar_object_is_not_weakened_by_telescope_scans_it_is_outside_of() {
    let away = LookShape::Cone { azimuth: 0.0, elevation: 30.0 * DEGREE, half_angle: 3.0 * DEGREE };
    let wide = LookShape::Cone { azimuth: 0.0, elevation: 90.0 * DEGREE, half_angle: 80.0 * DEGREE };
    let outside = weights_under_telescope_scans(away);
    let inside = weights_under_telescope_scans(wide);
    eprintln!(
        "MAP weight after each telescope scan: object outside its cone {outside:?}, inside but missed {inside:?}"
    );
    // Outside: no missed detection, no death (deaths are of objects in view): the object keeps its weight
    // (the 3e-11 that is missing is the radar scans' clutter and death hypotheses).
    assert!(outside.iter().all(|&w| w > 1.0 - 1e-9), "{outside:?}");
    // Inside and never detected: each miss moves weight to the object's death.
    assert!(inside.iter().all(|&w| w < 0.95), "{inside:?}");
}

/// Every kind in turn, one object: the per-scan digests of `tracker` from its prior.
fn every_kind_digests(tracker: &mut Tracker4<MixedNetwork<f64, 6>>, network: &MixedNetwork<f64, 6>) -> Vec<u64> {
    let mut state = truth(&EarthRotation::new(0.3));
    (1..=12u32)
        .map(|scan| {
            state = motion().propagate(&state, 10.0).unwrap().state;
            let geometry = ScanGeometry { sensor: scan as usize % 6, time: 10.0 * f64::from(scan), observer: None };
            let placed = network.place(&geometry).unwrap();
            let (kind, exact) = (placed.placed().kind, placed.measure(&state));
            let z = SVector::<f64, 4>::from_fn(|k, _| {
                if k < kind.dimension() { exact[k] + sigma(kind)[k] * wobble(scan, k) } else { 0.0 }
            });
            tracker.step_scan(&geometry, &[z]).unwrap();
            tracker.digest()
        })
        .collect()
}

#[test]
fn a_placeholder_tracker_takes_its_configuration_in_place_and_then_runs_as_a_new_one() {
    // The compile-time placeholder: no sensors, nothing detected, exhaustive children.
    const PLACEHOLDER: Config<f64, TwoBodyJ2<f64>, MixedNetwork<f64, 6>, 6, 1> = Config {
        motion: TwoBodyJ2 {
            mu: 1.0,
            j2: 0.0,
            radius: 1.0,
            min_radius: 1.0,
            noise: ProcessNoise::Isotropic(0.0),
            max_step: 1.0,
            max_substeps: 1,
        },
        measurement: MixedNetwork::unconfigured(),
        sensor: Sensor::UNCONFIGURED,
        birth: BirthModel {
            probability: 0.0,
            cells: heapless::Vec::new(),
            detection: crate::BirthDetection::AllDetected,
            events: crate::BirthEvents::FirstOrder,
            measured: None,
        },
        death_probability: 0.0,
        gate: None,
        children: crate::ChildGeneration::Exhaustive { max_children_per_scan: 1000 },
        selection: crate::config::Selection::TopWeight,
        store_overflow: crate::StoreOverflow::PruneChildren,
        numerical_failure: crate::NumericalFailure::DropTrack,
        track_loss: crate::TrackLoss::Never,
        seed: 0,
    };
    static TRACKER: std::sync::Mutex<Tracker4<MixedNetwork<f64, 6>>> =
        std::sync::Mutex::new(Tracker::empty(PLACEHOLDER));
    let mut tracker = TRACKER.lock().unwrap();

    let network = every_kind(EarthRotation::new(0.3));
    let mut start = truth(&EarthRotation::new(0.3));
    start[0] += 0.3;
    let objects =
        [PriorObject { label: TrackLabel(0), state: Gaussian { mean: start, covariance: prior_covariance() } }];
    let prior = [PriorHypothesis { weight: 1.0, objects: &objects }];
    // The placeholder is no configuration: refused, and nothing runs.
    assert_eq!(tracker.reset(&prior, 0.0), Err(crate::ConfigError::Sensor("sensor network: no sensors")));
    let geometry = ScanGeometry { sensor: 0, time: 10.0, observer: None };
    assert_eq!(tracker.step_scan(&geometry, &[]), Err(StepError::NotInitialised));
    assert_eq!(network.place(&geometry).map(|_| ()), Ok(()));
    assert!(MixedNetwork::<f64, 6>::unconfigured().place(&geometry).is_err());

    // Sampled children (the placeholder's are exhaustive), so the generator is reconfigured in place.
    let sampled = crate::sampler::SamplerConfig { steps: 200, exhaustive_limit: 0, ..Default::default() };
    let real = Config {
        children: crate::ChildGeneration::Sampled(sampled),
        ..config(network, network.sensors()[0].sensor.detection)
    };
    // A bad configuration or prior changes nothing.
    let bad = Config { death_probability: -1.0, ..real.clone() };
    assert_eq!(tracker.reset_with(bad, &prior, 0.0), Err(crate::ConfigError::DeathProbability));
    assert_eq!(tracker.reset_with(real.clone(), &[], 0.0), Err(crate::ConfigError::PriorEmpty));
    assert_eq!(tracker.reset(&prior, 0.0), Err(crate::ConfigError::Sensor("sensor network: no sensors")));

    tracker.reset_with(real.clone(), &prior, 0.0).unwrap();
    let mut fresh: Tracker4<MixedNetwork<f64, 6>> = Tracker::new(real.clone(), &prior, 0.0).unwrap();
    let expected = every_kind_digests(&mut fresh, &network);
    assert_eq!(every_kind_digests(&mut tracker, &network), expected);
    // Again after those scans: the scratch they left behind changes nothing.
    tracker.reset_with(real, &prior, 0.0).unwrap();
    assert_eq!(every_kind_digests(&mut tracker, &network), expected);
}
