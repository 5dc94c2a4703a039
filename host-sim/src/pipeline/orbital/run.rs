//! `host-sim run` on version 2 (3-D) scenarios: builds the sensor network and the core tracker (f64,
//! two-body + J2), steps every scan with its sensor and time ([`tracker_core::Tracker::step_scan`]), scores
//! the MAP estimates against the truth in 3-D (km) and writes `summary.json`, `estimates.csv`, the MAP tracks
//! as a CCSDS OEM (`tracks.oem`, [`crate::oem`]) and the plots (a sky plot per sensor, the expected cardinality and GOSPA over time).
//!
//! Scoring is that of version 1 ([`crate::pipeline::planar::evaluate`]) with 3-D positions: GOSPA (α = 2) of the MAP
//! positions against every true object, label switches along GOSPA's assignment, and an estimate *in view*
//! when its position lies in the field of view of the scan's sensor (look angles, range and range-rate of
//! [`SiteGeometry::look`]).

use crate::eval::births::{BirthTally, MapTrack};
use crate::error::Error;
use crate::pipeline::planar::evaluate::{mean, peak_resident_kib, progress, write_json};
use crate::metrics::{LabelSwitches, gospa};
use crate::plots::{self, Scale, Series, SkySeries};
use crate::report::{BirthsSummary, RejectedScan, RunSummary};
use crate::pipeline::planar::runner::{Profile, StepInfo, TrackerKind};
use crate::scenario::{BirthDetectionSpec, NumericalFailureSpec, SelectionSpec, StoreOverflowSpec, TrackerSpec};
use crate::scenario::v2::{Measurement3dSpec, Scenario3d, ShapeSpec};
use nalgebra::{SMatrix, SVector};
use std::collections::{BTreeMap, HashMap};
use std::io::Write;
use std::path::Path;
use std::time::Instant;
use tracker_core::model::{
    EarthRotation, GroundSite, OpticalRaDec, Placeable, Platform, RadarRangeAzEl, RadarRangeRate, ScanGeometry,
    SensorNetwork, SiteSensor,
};
use tracker_core::{
    BirthModel, ChildGeneration, Config, Gaussian, Look, PriorHypothesis, PriorObject, Region, Sensor, StepError,
    TrackLabel, Tracker, TwoBodyJ2, ssa_caps,
};

/// Sensors a network holds (tracker-core's `ssa_caps::SENSORS`).
pub const C: usize = ssa_caps::SENSORS;

/// One MAP track of a 3-D posterior.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Track6 {
    /// Label.
    pub label: u32,
    /// Mean (km, km/s).
    pub mean: [f64; 6],
    /// Existence probability of the label.
    pub existence: f64,
    /// Covariance (row-major; km², km²/s, km²/s²).
    pub covariance: [[f64; 6]; 6],
}

/// What the run needs of a posterior.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Posterior6 {
    /// The MAP hypothesis's tracks.
    pub map: Vec<Track6>,
    /// Σ w_h N_h.
    pub expected_cardinality: f64,
    /// Hypotheses held.
    pub hypotheses: usize,
    /// Existence per label.
    pub existence: HashMap<u32, f64>,
}

/// A 3-D core tracker behind one interface, whatever its measurement type and capacities.
pub trait Runner3d: Send {
    /// Processes one scan of `sensor` at `time` (measurements in the tracker's units: km, rad, km/s).
    ///
    /// # Errors
    /// The core's [`StepError`]; the tracker is unchanged.
    fn step(&mut self, sensor: usize, time: f64, measurements: &[Vec<f64>]) -> Result<StepInfo, StepError>;
    /// The posterior now.
    fn posterior(&self) -> Posterior6;
}

type Tracker3d<X, const D: usize, const H: usize, const N: usize, const Z: usize, const K: usize, const B: usize> =
    Tracker<f64, TwoBodyJ2<f64>, SensorNetwork<f64, X, D, C>, 6, D, H, N, Z, K, B>;

struct Core3d<X, const D: usize, const H: usize, const N: usize, const Z: usize, const K: usize, const B: usize> {
    tracker: Box<Tracker3d<X, D, H, N, Z, K, B>>,
}

impl<X, const D: usize, const H: usize, const N: usize, const Z: usize, const K: usize, const B: usize> Runner3d
    for Core3d<X, D, H, N, Z, K, B>
where
    X: Placeable<f64, D> + Send,
{
    fn step(&mut self, sensor: usize, time: f64, measurements: &[Vec<f64>]) -> Result<StepInfo, StepError> {
        let zs: Vec<SVector<f64, D>> = measurements.iter().map(|z| SVector::from_column_slice(z)).collect();
        let report = self.tracker.step_scan(&ScanGeometry { sensor, time, observer: None }, &zs)?;
        Ok(StepInfo {
            children: report.children,
            hypotheses: report.hypotheses,
            captured_mass: report.captured_mass,
            budget_reached: false,
        })
    }

    fn posterior(&self) -> Posterior6 {
        let tracks = self.tracker.tracks();
        let mut existence: HashMap<u32, f64> = HashMap::new();
        for t in tracks {
            *existence.entry(t.label.0).or_insert(0.0) += t.existence;
        }
        let mut expected_cardinality = 0.0;
        let mut hypotheses = 0;
        let mut map = vec![];
        for (i, h) in self.tracker.hypotheses().enumerate() {
            expected_cardinality += h.weight() * h.slots().len() as f64;
            hypotheses += 1;
            if i == 0 {
                map = h
                    .tracks()
                    .map(|t| Track6 {
                        label: t.label.0,
                        mean: t.state.mean.into(),
                        existence: existence.get(&t.label.0).copied().unwrap_or(0.0),
                        covariance: core::array::from_fn(|i| core::array::from_fn(|j| t.state.covariance[(i, j)])),
                    })
                    .collect();
            }
        }
        Posterior6 { map, expected_cardinality, hypotheses, existence }
    }
}

/// The core's sensors of a scenario (radians).
fn site_sensors<const D: usize>(scenario: &Scenario3d) -> Vec<SiteSensor<f64, D>> {
    scenario
        .sensors
        .iter()
        .map(|s| {
            let sigma = s.noise.sigma(scenario.measurement);
            SiteSensor {
                platform: Platform::Ground(GroundSite {
                    latitude: s.site.latitude_deg.to_radians(),
                    longitude: s.site.longitude_deg.to_radians(),
                    height: s.site.height_km,
                }),
                sigma: core::array::from_fn(|i| sigma.get(i).copied().unwrap_or(f64::NAN)),
                detection: Sensor {
                    detection_probability: s.detection_probability,
                    clutter_rate: s.clutter_rate,
                    field_of_view: s.field_of_view.region(),
                },
            }
        })
        .collect()
}

/// The core's sensor network of a scenario.
///
/// # Errors
/// The core's message when it rejects the network.
pub fn network<X: Placeable<f64, D>, const D: usize>(
    scenario: &Scenario3d,
) -> Result<SensorNetwork<f64, X, D, C>, Error> {
    SensorNetwork::new(EarthRotation::new(scenario.earth_rotation_at_epoch()), &site_sensors::<D>(scenario))
        .map_err(|e| Error::input(format!("sensors: {e}")))
}

fn gaussian6(mean: &[f64; 6], covariance: &[[f64; 6]; 6]) -> Gaussian<f64, 6> {
    Gaussian { mean: SVector::from(*mean), covariance: SMatrix::<f64, 6, 6>::from_fn(|i, j| covariance[i][j]) }
}

/// The child generation of tracker settings.
fn children(kind: TrackerKind, tracker: &TrackerSpec) -> ChildGeneration {
    match kind {
        TrackerKind::Rfisst => ChildGeneration::Sampled(crate::pipeline::planar::setup::sampler_config_of(tracker)),
        _ => ChildGeneration::Exhaustive { max_children_per_scan: tracker.max_children_per_scan },
    }
}

/// The core configuration and the prior of `scenario` for the tracker `kind` with `B` birth cells.
///
/// # Errors
/// Bad input: a network the core refuses, more birth cells than `B`, no sensor.
#[allow(clippy::type_complexity)]
pub fn config3d<X, const D: usize, const B: usize>(
    scenario: &Scenario3d,
    kind: TrackerKind,
) -> Result<(Config<f64, TwoBodyJ2<f64>, SensorNetwork<f64, X, D, C>, 6, B>, Vec<(f64, Vec<PriorObject<f64, 6>>)>), Error>
where
    X: Placeable<f64, D>,
{
    let network = network::<X, D>(scenario)?;
    let mut cells = heapless::Vec::<Gaussian<f64, 6>, B>::new();
    for cell in &scenario.birth.cells {
        cells.push(gaussian6(&cell.mean, &cell.covariance)).map_err(|_| {
            Error::input(format!(
                "birth.cells: {} cells exceed this tracker's capacity of {B}",
                scenario.birth.cells.len()
            ))
        })?;
    }
    let spec = &scenario.tracker;
    let first = network.sensors().first().map(|s| s.detection);
    let config = Config {
        motion: scenario.motion_model(),
        measurement: network,
        // Ignored: every sensor of the network has its own detection model.
        sensor: first.ok_or_else(|| Error::input("sensors: needs at least one sensor"))?,
        birth: BirthModel {
            events: scenario.birth.events.core(),
            measured: scenario.birth.measured.as_ref().map(|m| m.core()),
            probability: scenario.birth.probability,
            cells,
            detection: match scenario.birth.detection {
                BirthDetectionSpec::AllDetected => tracker_core::BirthDetection::AllDetected,
                BirthDetectionSpec::AllowUndetected => tracker_core::BirthDetection::AllowUndetected,
            },
        },
        death_probability: scenario.death_probability,
        gate: spec.gate,
        children: children(kind, spec),
        selection: match spec.selection {
            SelectionSpec::TopWeight => tracker_core::config::Selection::TopWeight,
            SelectionSpec::SampledByWeight => tracker_core::config::Selection::SampledByWeight,
        },
        store_overflow: match spec.store_overflow {
            StoreOverflowSpec::PruneChildren => tracker_core::StoreOverflow::PruneChildren,
            StoreOverflowSpec::Error => tracker_core::StoreOverflow::Error,
        },
        numerical_failure: match spec.numerical_failure {
            NumericalFailureSpec::DropTrack => tracker_core::NumericalFailure::DropTrack,
            NumericalFailureSpec::Error => tracker_core::NumericalFailure::Error,
        },
        seed: spec.seed,
    };
    let prior = scenario
        .prior
        .hypotheses
        .iter()
        .map(|h| {
            let objects = h
                .objects
                .iter()
                .map(|o| PriorObject { label: TrackLabel(o.label), state: gaussian6(&o.mean, &o.covariance) })
                .collect();
            (h.weight, objects)
        })
        .collect();
    Ok((config, prior))
}

fn core3d<X, const D: usize, const H: usize, const N: usize, const Z: usize, const K: usize, const B: usize>(
    scenario: &Scenario3d,
    kind: TrackerKind,
) -> Result<Box<dyn Runner3d>, Error>
where
    X: Placeable<f64, D> + Send + 'static,
{
    let (config, objects) = config3d::<X, D, B>(scenario, kind)?;
    let prior: Vec<PriorHypothesis<'_, f64, 6>> =
        objects.iter().map(|(weight, objects)| PriorHypothesis { weight: *weight, objects }).collect();
    let tracker = Tracker3d::<X, D, H, N, Z, K, B>::new(config, &prior, scenario.prior.time)
        .map_err(|e| Error::input(format!("tracker configuration: {e}")))?;
    Ok(Box::new(Core3d { tracker: Box::new(tracker) }))
}

/// The scans of `scenario` as the trackers take them (angles in radians).
fn scans3d<const D: usize>(scenario: &Scenario3d) -> Vec<crate::eval::exactness::Scan<D>> {
    scenario
        .scans
        .iter()
        .map(|scan| {
            let zs = measurements_in_radians(scenario.measurement, &scan.measurements)
                .iter()
                .map(|z| SVector::<f64, D>::from_column_slice(z))
                .collect();
            (ScanGeometry { sensor: scan.sensor, time: scan.time, observer: None }, zs)
        })
        .collect()
}

fn compare_with<X, const D: usize, const H: usize, const N: usize, const Z: usize, const K: usize, const B: usize>(
    scenario: &Scenario3d,
    kind: TrackerKind,
    budget_bytes: usize,
) -> Result<crate::eval::exactness::CompareFigures, Error>
where
    X: Placeable<f64, D>,
{
    let (config, prior) = config3d::<X, D, B>(scenario, kind)?;
    crate::eval::exactness::compare_scans::<_, _, 6, D, H, N, Z, K, B>(
        &config,
        &prior,
        scenario.prior.time,
        budget_bytes,
        &scans3d::<D>(scenario),
    )
    .map_err(Error::input)
}

macro_rules! compare_for_profile {
    ($x:ty, $d:literal, $profile:expr, $scenario:expr, $kind:expr, $budget:expr) => {
        match $profile {
            Profile::Embedded => compare_with::<
                $x,
                $d,
                { ssa_caps::HYPOTHESES },
                { ssa_caps::OBJECTS },
                { ssa_caps::MEASUREMENTS },
                { ssa_caps::TRACKS_3D },
                { ssa_caps::BIRTH_CELLS },
            >($scenario, $kind, $budget),
            Profile::Host => compare_with::<$x, $d, 256, HOST_OBJECTS_3D, 64, 4096, 64>($scenario, $kind, $budget),
        }
    };
}

/// `host-sim compare` on a version 2 file: the bounded tracker `kind` (homht or rfisst) and the unbounded
/// reference (memory budget `budget_bytes`) on the same scans, placed per sensor by the core's
/// `place_scan` in both ([`crate::eval::exactness::compare_scans`]).
///
/// # Errors
/// Bad input: the configuration, or the reference tracker as bounded tracker.
pub fn compare3d(
    scenario: &Scenario3d,
    kind: TrackerKind,
    profile: Option<Profile>,
    budget_bytes: usize,
) -> Result<crate::eval::exactness::CompareFigures, Error> {
    if kind == TrackerKind::Reference {
        return Err(Error::input("--tracker: the bounded tracker must be homht or rfisst"));
    }
    let profile = choose_profile(scenario, profile);
    match scenario.measurement {
        Measurement3dSpec::Radar => compare_for_profile!(RadarRangeAzEl<f64>, 3, profile, scenario, kind, budget_bytes),
        Measurement3dSpec::RadarRangeRate => {
            compare_for_profile!(RadarRangeRate<f64>, 4, profile, scenario, kind, budget_bytes)
        }
        Measurement3dSpec::Optical => compare_for_profile!(OpticalRaDec<f64>, 2, profile, scenario, kind, budget_bytes),
    }
}

/// N of the `host` profile on version 2 files: 256, twice the planar host profile's, so that a catalogue of
/// more than 128 objects and its births fit (the radar-leo preset with a break-up has 130 objects).
pub const HOST_OBJECTS_3D: usize = 256;

/// The capacities (H, N, Z, K, B) of a profile for 3-D trackers: `embedded` is tracker-core's
/// `RadarTracker` / `OpticalTracker` (K = `ssa_caps::TRACKS_3D`), `host` is [`Profile::caps`] with
/// N = [`HOST_OBJECTS_3D`].
pub fn caps3d(profile: Profile) -> (usize, usize, usize, usize, usize) {
    match profile {
        Profile::Embedded => (
            ssa_caps::HYPOTHESES,
            ssa_caps::OBJECTS,
            ssa_caps::MEASUREMENTS,
            ssa_caps::TRACKS_3D,
            ssa_caps::BIRTH_CELLS,
        ),
        Profile::Host => (256, HOST_OBJECTS_3D, 64, 4096, 64),
    }
}

/// The profile a run uses: the one asked for, or else `embedded` when the scenario fits it (prior objects
/// below N, measurements within Z, birth cells within B) and `host` otherwise.
pub fn choose_profile(scenario: &Scenario3d, asked: Option<Profile>) -> Profile {
    if let Some(profile) = asked {
        return profile;
    }
    let (_, n, z, _, b) = caps3d(Profile::Embedded);
    if scenario.max_prior_objects() < n
        && scenario.max_measurements() <= z
        && scenario.birth.cells.len() <= b
        && birth_components_per_measurement(scenario) <= b
    {
        Profile::Embedded
    } else {
        Profile::Host
    }
}

/// The most birth components one measurement of `scenario` can give (0 without measured births): radar
/// headings × speeds × climbs; for the other models the region's bound
/// ([`AdmissibleRegion::max_components`](tracker_core::model::AdmissibleRegion::max_components)). A
/// measurement whose components do not fit the pool gives no birth.
pub fn birth_components_per_measurement(scenario: &Scenario3d) -> usize {
    let Some(measured) = &scenario.birth.measured else { return 0 };
    let region = measured.core().region;
    match scenario.measurement {
        Measurement3dSpec::Radar => region.headings.saturating_mul(region.speeds).saturating_mul(region.climbs),
        Measurement3dSpec::RadarRangeRate | Measurement3dSpec::Optical => region.max_components(),
    }
}

macro_rules! for_profile {
    ($x:ty, $d:literal, $profile:expr, $scenario:expr, $kind:expr) => {
        match $profile {
            Profile::Embedded => core3d::<
                $x,
                $d,
                { ssa_caps::HYPOTHESES },
                { ssa_caps::OBJECTS },
                { ssa_caps::MEASUREMENTS },
                { ssa_caps::TRACKS_3D },
                { ssa_caps::BIRTH_CELLS },
            >($scenario, $kind),
            Profile::Host => core3d::<$x, $d, 256, HOST_OBJECTS_3D, 64, 4096, 64>($scenario, $kind),
        }
    };
}

/// Builds the 3-D tracker `kind` for `scenario`.
///
/// # Errors
/// Bad input: the reference tracker (not yet available on version 2 files), a scenario that does not fit
/// the profile, or a configuration the core rejects.
pub fn build3d(kind: TrackerKind, profile: Profile, scenario: &Scenario3d) -> Result<Box<dyn Runner3d>, Error> {
    if kind == TrackerKind::Reference {
        return Err(Error::input("--tracker reference: not yet supported on version 2 (3-D) scenario files"));
    }
    match scenario.measurement {
        Measurement3dSpec::Radar => for_profile!(RadarRangeAzEl<f64>, 3, profile, scenario, kind),
        Measurement3dSpec::RadarRangeRate => for_profile!(RadarRangeRate<f64>, 4, profile, scenario, kind),
        Measurement3dSpec::Optical => for_profile!(OpticalRaDec<f64>, 2, profile, scenario, kind),
    }
}

/// The measurements of a scan in the tracker's units: angles from degrees to radians.
pub fn measurements_in_radians(kind: Measurement3dSpec, measurements: &[Vec<f64>]) -> Vec<Vec<f64>> {
    measurements
        .iter()
        .map(|z| z.iter().enumerate().map(|(i, &v)| if kind.is_angle(i) { v.to_radians() } else { v }).collect())
        .collect()
}

/// The look geometry of the scenario's ground sensors, host side: look angles, range and range-rate of an
/// inertial state, topocentric right ascension and declination, and field-of-view membership.
pub struct SiteGeometry {
    rotation: EarthRotation<f64>,
    sites: Vec<GroundSite<f64>>,
    regions: Vec<Region<f64>>,
    kind: Measurement3dSpec,
}

impl SiteGeometry {
    /// The geometry of `scenario`'s sensors.
    pub fn new(scenario: &Scenario3d) -> Self {
        Self {
            rotation: EarthRotation::new(scenario.earth_rotation_at_epoch()),
            sites: scenario
                .sensors
                .iter()
                .map(|s| GroundSite {
                    latitude: s.site.latitude_deg.to_radians(),
                    longitude: s.site.longitude_deg.to_radians(),
                    height: s.site.height_km,
                })
                .collect(),
            regions: scenario.sensors.iter().map(|s| s.field_of_view.region()).collect(),
            kind: scenario.measurement,
        }
    }

    /// Line of sight from sensor `sensor` at `time` (inertial, km), the relative velocity, and the site's
    /// East, North, Up rows.
    fn line_of_sight(&self, sensor: usize, time: f64, state: &[f64; 6]) -> ([f64; 3], [f64; 3], [[f64; 3]; 3]) {
        let site = self.sites[sensor];
        let observer = site.observer(&self.rotation, time);
        let enu = site.enu(&self.rotation, time);
        let d = [state[0] - observer[0], state[1] - observer[1], state[2] - observer[2]];
        let w = [state[3] - observer[3], state[4] - observer[4], state[5] - observer[5]];
        (d, w, enu)
    }

    /// Look angles (rad), range (km) and range-rate (km/s) of `state` from sensor `sensor` at `time`; the
    /// range and range-rate only where the measurement type has them.
    pub fn look(&self, sensor: usize, time: f64, state: &[f64; 6]) -> Look<f64> {
        let (d, w, enu) = self.line_of_sight(sensor, time, state);
        let dot = |a: &[f64; 3], b: &[f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let (e, n, u) = (dot(&enu[0], &d), dot(&enu[1], &d), dot(&enu[2], &d));
        let range = dot(&d, &d).sqrt();
        Look {
            azimuth: e.atan2(n),
            elevation: u.atan2(e.hypot(n)),
            range: (self.kind != Measurement3dSpec::Optical).then_some(range),
            range_rate: (self.kind == Measurement3dSpec::RadarRangeRate).then(|| dot(&d, &w) / range),
        }
    }

    /// Topocentric right ascension and declination (rad) of `state` from sensor `sensor` at `time`.
    pub fn ra_dec(&self, sensor: usize, time: f64, state: &[f64; 6]) -> (f64, f64) {
        let (d, _, _) = self.line_of_sight(sensor, time, state);
        (d[1].atan2(d[0]), d[2].atan2(d[0].hypot(d[1])))
    }

    /// Whether `state` lies in sensor `sensor`'s field of view at `time`.
    pub fn in_view(&self, sensor: usize, time: f64, state: &[f64; 6]) -> bool {
        self.regions[sensor].contains_look(&self.look(sensor, time, state))
    }

    /// The sky-plot point of `state`: (azimuth, elevation) for radar, (right ascension, declination) for
    /// a telescope.
    pub fn sky_point(&self, sensor: usize, time: f64, state: &[f64; 6]) -> (f64, f64) {
        if self.kind == Measurement3dSpec::Optical {
            self.ra_dec(sensor, time, state)
        } else {
            let look = self.look(sensor, time, state);
            (look.azimuth, look.elevation)
        }
    }
}

/// The core's own field-of-view test of measurements ([`Region::sees`] through the placed network), the
/// test `step_scan` applies: a measurement it fails is [`StepError::MeasurementOutsideFieldOfView`].
pub enum FieldOfViewCheck {
    /// Radar networks.
    Radar(SensorNetwork<f64, RadarRangeAzEl<f64>, 3, C>),
    /// Radar networks with range-rate.
    RadarRangeRate(SensorNetwork<f64, RadarRangeRate<f64>, 4, C>),
    /// Telescope networks.
    Optical(SensorNetwork<f64, OpticalRaDec<f64>, 2, C>),
}

fn sees_in<X: Placeable<f64, D>, const D: usize>(
    network: &SensorNetwork<f64, X, D, C>,
    sensor: usize,
    time: f64,
    z: &[f64],
) -> bool {
    use tracker_core::MeasurementModel;
    if z.len() != D {
        return false;
    }
    match network.place(&ScanGeometry { sensor, time, observer: None }) {
        Ok(placed) => placed.detection().is_some_and(|d| d.field_of_view.sees(&placed, &SVector::from_column_slice(z))),
        Err(_) => false,
    }
}

impl FieldOfViewCheck {
    /// The check of `scenario`'s sensors.
    ///
    /// # Errors
    /// The core's message when it rejects the network.
    pub fn new(scenario: &Scenario3d) -> Result<Self, Error> {
        Ok(match scenario.measurement {
            Measurement3dSpec::Radar => Self::Radar(network(scenario)?),
            Measurement3dSpec::RadarRangeRate => Self::RadarRangeRate(network(scenario)?),
            Measurement3dSpec::Optical => Self::Optical(network(scenario)?),
        })
    }

    /// Whether measurement `z` (tracker units: km, rad, km/s) of sensor `sensor` at `time` is in its field of
    /// view.
    pub fn sees(&self, sensor: usize, time: f64, z: &[f64]) -> bool {
        match self {
            Self::Radar(n) => sees_in(n, sensor, time, z),
            Self::RadarRangeRate(n) => sees_in(n, sensor, time, z),
            Self::Optical(n) => sees_in(n, sensor, time, z),
        }
    }
}

/// The outline of a field of view in (azimuth, elevation), radians, for the az/el sky plot.
fn fov_outline(shape: &ShapeSpec, mask_deg: f64) -> Vec<(f64, f64)> {
    const POINTS: usize = 72;
    let mask = mask_deg.to_radians();
    match *shape {
        ShapeSpec::Cone { azimuth_deg, elevation_deg, half_angle_deg } => {
            let (a0, e0, h) = (azimuth_deg.to_radians(), elevation_deg.to_radians(), half_angle_deg.to_radians());
            // Boresight b and two unit vectors across it, in (East, North, Up).
            let b = [e0.cos() * a0.sin(), e0.cos() * a0.cos(), e0.sin()];
            let u = [a0.cos(), -a0.sin(), 0.0];
            let v = [-e0.sin() * a0.sin(), -e0.sin() * a0.cos(), e0.cos()];
            (0..POINTS)
                .map(|i| {
                    let phi = i as f64 * std::f64::consts::TAU / POINTS as f64;
                    let d: Vec<f64> =
                        (0..3).map(|k| h.cos() * b[k] + h.sin() * (phi.cos() * u[k] + phi.sin() * v[k])).collect();
                    (d[0].atan2(d[1]), d[2].clamp(-1.0, 1.0).asin().max(mask))
                })
                .collect()
        }
        ShapeSpec::Box { azimuth_deg, half_width_deg, elevation_deg: [low, high] } => {
            let (a0, w) = (azimuth_deg.to_radians(), half_width_deg.to_radians());
            let (low, high) = (low.to_radians().max(mask), high.to_radians());
            let steps = POINTS / 2;
            let along = |el: f64, forward: bool| {
                (0..=steps).map(move |i| {
                    let f = i as f64 / steps as f64;
                    let f = if forward { f } else { 1.0 - f };
                    (tracker_core::model::wrap_angle(a0 - w + 2.0 * w * f), el)
                })
            };
            if w >= std::f64::consts::PI {
                // Every azimuth: the ring of the lowest elevation seen.
                return along(low, true).collect();
            }
            along(low, true).chain(along(high, false)).collect()
        }
    }
}

/// One sensor's sky-plot truth: per object id, a point per scan of that sensor (`None` out of view).
type SkyTruth = BTreeMap<u64, Vec<Option<(f64, f64)>>>;

/// Per-scan figures of a 3-D run.
struct Record {
    time: f64,
    ms: Option<f64>,
    captured_mass: Option<f64>,
    expected_cardinality: f64,
    map_cardinality: usize,
    true_cardinality: Option<usize>,
    gospa: Option<f64>,
    ospa: Option<f64>,
}

/// `host-sim run` on a version 2 scenario: runs `kind` with `profile` (chosen by [`choose_profile`] when
/// `None`), writes `summary.json`, `estimates.csv` and the plots into `out`, and returns the summary and
/// whether every scan was accepted.
///
/// # Errors
/// Bad input (exit code 2): a tracker that cannot be built, a scan gap beyond the motion model's bound or a
/// scan naming an unknown sensor; [`Error::Output`] when a file cannot be written.
pub fn run(
    scenario: &Scenario3d,
    kind: TrackerKind,
    profile: Option<Profile>,
    quiet: bool,
    out: &Path,
) -> Result<(RunSummary, bool), Error> {
    std::fs::create_dir_all(out).map_err(|e| Error::output(out, e))?;
    let profile = choose_profile(scenario, profile);
    let components = birth_components_per_measurement(scenario);
    let pool = caps3d(profile).4.saturating_sub(scenario.birth.cells.len());
    if components > pool {
        eprintln!(
            "warning: birth.measured gives up to {components} birth components per measurement, more than the \
             {pool} free birth cells of the {} profile: measurements that need more give no birth (--profile host)",
            profile.name()
        );
    }
    let mut runner = build3d(kind, profile, scenario)?;
    let geometry = SiteGeometry::new(scenario);
    let prior = runner.posterior();
    let csv_path = out.join("estimates.csv");
    let mut csv = std::io::BufWriter::new(std::fs::File::create(&csv_path).map_err(|e| Error::output(&csv_path, e))?);
    writeln!(csv, "scan,time,sensor,label,x,y,z,vx,vy,vz,existence,within_error_bound")
        .map_err(|e| Error::output(&csv_path, e))?;

    let evaluation = scenario.evaluation;
    let n = scenario.scans.len();
    let sensors = scenario.sensors.len();
    let mut births = BirthTally::new(
        scenario.truth.iter().flat_map(|t| t.objects.iter().filter(|o| !o.in_prior).map(|o| o.id)),
        evaluation.confirmation_existence,
        evaluation.error_bound,
    );
    // Sky plots: per sensor, per truth object, a point per scan of that sensor (None out of view).
    let mut sky_truth: Vec<SkyTruth> = vec![BTreeMap::new(); sensors];
    let mut sky_estimates: Vec<Vec<Option<(f64, f64)>>> = vec![vec![]; sensors];
    let mut records = vec![];
    let mut rejected = vec![];
    let mut switches = LabelSwitches::new();
    let (mut in_view_misses, mut in_view_red_stars, mut out_of_view_red_stars) = (0usize, 0usize, 0usize);
    let mut peak_hypotheses = prior.hypotheses;
    let mut oem = crate::oem::OemTracks::new(scenario);
    let bar = progress(n, quiet, kind.name());
    for (k, scan) in scenario.scans.iter().enumerate() {
        let zs = measurements_in_radians(scenario.measurement, &scan.measurements);
        let start = Instant::now();
        let outcome = runner.step(scan.sensor, scan.time, &zs);
        let ms = start.elapsed().as_secs_f64() * 1e3;
        bar.inc(1);
        let info = match outcome {
            Ok(info) => Some(info),
            // Bad input, not a tracker failure: one line and exit code 2.
            Err(e @ (StepError::TimeStepTooLong { .. } | StepError::Placement(_))) => {
                bar.finish_and_clear();
                return Err(Error::input(format!("scans[{k}]: {e}")));
            }
            Err(e) => {
                bar.suspend(|| eprintln!("warning: scan {k} (t = {}) rejected: {e}", scan.time));
                rejected.push(RejectedScan { scan: k, error: e.to_string() });
                None
            }
        };
        let posterior = runner.posterior();
        peak_hypotheses = peak_hypotheses.max(posterior.hypotheses);
        if info.is_some() {
            oem.record(scan.time, &posterior.map);
        }
        let estimates: Vec<[f64; 3]> = posterior.map.iter().map(|t| [t.mean[0], t.mean[1], t.mean[2]]).collect();
        let truth = scenario.truth.as_ref().map(|t| &t.scans[k].objects);
        let mut within = vec![None; estimates.len()];
        let (mut g, mut o) = (None, None);
        if let Some(truth) = truth {
            let points: Vec<[f64; 3]> = truth.iter().map(|t| [t.state[0], t.state[1], t.state[2]]).collect();
            let scored = gospa(&points, &estimates, evaluation.gospa_cutoff, evaluation.gospa_order);
            let pairs: Vec<(u64, u32)> = scored
                .assignment
                .iter()
                .enumerate()
                .filter_map(|(i, e)| e.map(|e| (truth[i].id, posterior.map[e].label)))
                .collect();
            switches.record(&pairs);
            g = Some(scored.distance);
            o = Some(crate::metrics::ospa(&points, &estimates, evaluation.gospa_cutoff, evaluation.gospa_order));
            let bound = gospa(&points, &estimates, evaluation.error_bound, 1.0);
            within.iter_mut().for_each(|w| *w = Some(false));
            for e in bound.assignment.iter().flatten() {
                within[*e] = Some(true);
            }
            // Births: confirmed once GOSPA (cut-off: the error bound) assigns them a MAP track of a
            // label with existence ≥ the threshold.
            let objects: Vec<(u64, &[f64])> = truth.iter().map(|t| (t.id, &t.state[..3])).collect();
            let map: Vec<MapTrack<'_>> = posterior
                .map
                .iter()
                .map(|t| MapTrack { label: t.label, position: &t.mean[..3], existence: t.existence })
                .collect();
            let detected = scenario.truth.as_ref().and_then(|t| t.scans[k].origins.as_ref());
            births.record(k, &objects, detected.into_iter().flatten().flatten().copied(), &map, &bound.assignment);
            for (t, assigned) in truth.iter().zip(&bound.assignment) {
                let confirmed_track = !births.is_birth(t.id) || births.confirmed_at(t.id).is_some();
                if confirmed_track && assigned.is_none() && geometry.in_view(scan.sensor, scan.time, &t.state) {
                    in_view_misses += 1;
                }
            }
            for (t, w) in posterior.map.iter().zip(&within) {
                if *w == Some(false) {
                    if geometry.in_view(scan.sensor, scan.time, &t.mean) {
                        in_view_red_stars += 1;
                    } else {
                        out_of_view_red_stars += 1;
                    }
                }
            }
            // Sky plot truth: every object, in view or a break.
            let series = &mut sky_truth[scan.sensor];
            for t in truth {
                let point = geometry
                    .in_view(scan.sensor, scan.time, &t.state)
                    .then(|| geometry.sky_point(scan.sensor, scan.time, &t.state));
                series.entry(t.id).or_default().push(point);
            }
        }
        for t in &posterior.map {
            if geometry.in_view(scan.sensor, scan.time, &t.mean) {
                sky_estimates[scan.sensor].push(Some(geometry.sky_point(scan.sensor, scan.time, &t.mean)));
            }
        }
        for (t, w) in posterior.map.iter().zip(&within) {
            let m = t.mean;
            let bound = w.map_or(String::new(), |w| w.to_string());
            writeln!(
                csv,
                "{k},{},{},{},{},{},{},{},{},{},{},{bound}",
                scan.time, scan.sensor, t.label, m[0], m[1], m[2], m[3], m[4], m[5], t.existence
            )
            .map_err(|e| Error::output(&csv_path, e))?;
        }
        records.push(Record {
            time: scan.time,
            ms: info.map(|_| ms),
            captured_mass: info.map(|i| i.captured_mass),
            expected_cardinality: posterior.expected_cardinality,
            map_cardinality: posterior.map.len(),
            true_cardinality: truth.map(Vec::len),
            gospa: g,
            ospa: o,
        });
    }
    bar.finish_and_clear();
    csv.flush().map_err(|e| Error::output(&csv_path, e))?;

    let ms: Vec<f64> = records.iter().filter_map(|r| r.ms).collect();
    let captured: Vec<f64> = records.iter().filter_map(|r| r.captured_mass).collect();
    let gospas: Vec<f64> = records.iter().filter_map(|r| r.gospa).collect();
    let ospas: Vec<f64> = records.iter().filter_map(|r| r.ospa).collect();
    let last = records.last();
    let figures = births.figures();
    let mut summary = RunSummary {
        scenario: scenario.name.clone(),
        tracker: kind.name().into(),
        profile: profile.name().into(),
        scans: n,
        mean_gospa: (!gospas.is_empty()).then(|| mean(&gospas)),
        mean_ospa: (!ospas.is_empty()).then(|| mean(&ospas)),
        gospa_cutoff: evaluation.gospa_cutoff,
        gospa_order: evaluation.gospa_order,
        error_bound: evaluation.error_bound,
        final_expected_cardinality: last.map_or(prior.expected_cardinality, |r| r.expected_cardinality),
        final_map_cardinality: last.map_or(prior.map.len(), |r| r.map_cardinality),
        true_final_cardinality: last.and_then(|r| r.true_cardinality),
        births: BirthsSummary::new(figures, scenario.truth.is_some()),
        label_switches: switches.total(),
        in_view_misses_after_confirmation: in_view_misses,
        in_view_red_stars,
        out_of_view_red_stars,
        mean_ms_per_scan: mean(&ms),
        max_ms_per_scan: ms.iter().copied().fold(0.0, f64::max),
        peak_hypotheses,
        mean_captured_mass: mean(&captured),
        min_captured_mass: captured.iter().copied().fold(1.0, f64::min),
        rejected_scans: rejected,
        reference_budget_reached_scans: vec![],
        peak_resident_kib: None,
        sensors: Some(sensors),
    };
    write_plots(scenario, &records, &sky_truth, &sky_estimates, out)?;
    oem.write(&out.join("tracks.oem"))?;
    summary.peak_resident_kib = peak_resident_kib();
    write_json(&out.join("summary.json"), &summary)?;
    let clean = summary.rejected_scans.is_empty();
    Ok((summary, clean))
}

/// A file-name stem from a sensor's name: letters, digits and `-`, others as `_`.
fn stem_of(name: &str) -> String {
    name.chars().map(|c| if c.is_ascii_alphanumeric() || c == '-' { c } else { '_' }).collect()
}

fn write_plots(
    scenario: &Scenario3d,
    records: &[Record],
    sky_truth: &[SkyTruth],
    sky_estimates: &[Vec<Option<(f64, f64)>>],
    out: &Path,
) -> Result<(), Error> {
    for (s, sensor) in scenario.sensors.iter().enumerate() {
        let truth: Vec<SkySeries> = sky_truth[s]
            .iter()
            .enumerate()
            .map(|(i, (id, points))| SkySeries { name: format!("object {id}"), points: points.clone(), color: Some(i) })
            .collect();
        let estimates = [SkySeries { name: "MAP estimates".into(), points: sky_estimates[s].clone(), color: None }];
        let stem = out.join(format!("sky_{s}_{}", stem_of(&sensor.name)));
        if scenario.measurement == Measurement3dSpec::Optical {
            let title = format!("{}: right ascension / declination, truth in view and MAP estimates", sensor.name);
            plots::sky_plot_ra_dec(&stem, &title, &truth, &estimates, None)?;
        } else {
            let title = format!("{}: azimuth / elevation, truth in view and MAP estimates", sensor.name);
            let outline = fov_outline(&sensor.field_of_view.shape, sensor.field_of_view.min_elevation_deg);
            plots::sky_plot_az_el(&stem, &title, &truth, &estimates, Some(&outline))?;
        }
    }
    let hours = |r: &Record| r.time / 3600.0;
    let mut series = vec![Series {
        name: "expected number of objects".into(),
        points: records.iter().map(|r| (hours(r), r.expected_cardinality)).collect(),
        markers: false,
    }];
    if records.iter().any(|r| r.true_cardinality.is_some()) {
        series.push(Series {
            name: "true number of objects".into(),
            points: records.iter().filter_map(|r| r.true_cardinality.map(|c| (hours(r), c as f64))).collect(),
            markers: false,
        });
    }
    plots::plot_series(
        &out.join("expected_cardinality"),
        "Expected number of objects",
        "time since the epoch (h)",
        "objects",
        Scale::Linear,
        Scale::Linear,
        &series,
    )?;
    if records.iter().any(|r| r.gospa.is_some()) {
        let gospa_series = [Series {
            name: "GOSPA of the MAP estimates (3-D positions)".into(),
            points: records.iter().filter_map(|r| r.gospa.map(|g| (hours(r), g))).collect(),
            markers: false,
        }];
        plots::plot_series(
            &out.join("gospa"),
            "GOSPA over the run",
            "time since the epoch (h)",
            "GOSPA (km)",
            Scale::Linear,
            Scale::Linear,
            &gospa_series,
        )?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tiny() -> Scenario3d {
        let simulation = crate::ssa::tiny_3d(1).expect("tiny-3d");
        crate::scenario::from_simulation::to_scenario(&simulation).expect("scenario").0
    }

    fn temp(tag: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("host-sim-run3d-{}-{tag}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        dir
    }

    /// The core's own errors for bad input (an unvalidated scenario) are bad input at the command line:
    /// `Error::Input` (exit code 2) with one line naming the scan.
    /// Runs `f` on a thread with the stack `main` gives the trackers.
    fn on_large_stack(f: impl FnOnce() + Send + 'static) {
        std::thread::Builder::new().stack_size(512 << 20).spawn(f).expect("thread").join().expect("no panic");
    }

    #[test]
    fn core_gap_and_placement_errors_are_bad_input() {
        on_large_stack(core_gap_and_placement_errors);
    }

    fn core_gap_and_placement_errors() {
        let mut gap = tiny();
        gap.motion = Motion3dSpecFor::short();
        let out = temp("gap");
        match run(&gap, TrackerKind::Rfisst, None, true, &out) {
            Err(Error::Input(e)) => {
                assert!(e.0.starts_with("scans[1]: scan is more than 5 s after the last one"), "{e}");
                assert!(!e.0.contains('\n'));
            }
            other => panic!("{:?}", other.map(|s| s.0.scans)),
        }
        let mut unknown = tiny();
        unknown.scans[2].sensor = 3;
        match run(&unknown, TrackerKind::Rfisst, None, true, &out) {
            Err(Error::Input(e)) => assert!(e.0.starts_with("scans[2]: scan geometry: scan names sensor 3"), "{e}"),
            other => panic!("{:?}", other.map(|s| s.0.scans)),
        }
        let _ = std::fs::remove_dir_all(&out);
    }

    struct Motion3dSpecFor;

    impl Motion3dSpecFor {
        /// Gaps of at most 5 s: the 10 s between tiny-3d's scans are too long.
        fn short() -> crate::scenario::v2::Motion3dSpec {
            crate::scenario::v2::Motion3dSpec::TwoBodyJ2 {
                process_noise: crate::scenario::v2::ProcessNoiseSpec::Isotropic { q: 1e-12 },
                max_step: 5.0,
                max_substeps: 1,
            }
        }
    }

    #[test]
    fn look_angles_match_the_core_radar_model() {
        use tracker_core::MeasurementModel;
        let scenario = tiny();
        let geometry = SiteGeometry::new(&scenario);
        let network = network::<RadarRangeAzEl<f64>, 3>(&scenario).expect("network");
        let truth = &scenario.truth.as_ref().expect("truth").scans[4].objects[0];
        let time = scenario.scans[4].time;
        let placed = network.place(&ScanGeometry { sensor: 0, time, observer: None }).expect("placed");
        let z = placed.measure(&SVector::from(truth.state));
        let look = geometry.look(0, time, &truth.state);
        assert!((look.range.expect("range") - z[0]).abs() < 1e-9, "{look:?} {z}");
        assert!((look.azimuth - z[1]).abs() < 1e-12 && (look.elevation - z[2]).abs() < 1e-12, "{look:?} {z}");
    }
}
