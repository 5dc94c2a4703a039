//! The orbital world's core trackers: the sensor network, configuration and prior of a version 2
//! scenario, and the tracker (f64, two-body + J2) behind one interface whatever its measurement model and
//! capacities ([`Runner3d`]). A network of one kind is the core's [`SensorNetwork`]; sensors of mixed kinds
//! (and the kinds without a model of their own: az/el, range, range and range-rate) are one
//! [`MixedNetwork`] ([`ScenarioNetwork`]).

use crate::error::Error;
use crate::pipeline::profile::ORBITAL;
use crate::pipeline::profile::Profile;
use crate::pipeline::settings;
use crate::pipeline::snapshot::Track6;
use crate::pipeline::tracker::{StepInfo, TrackerKind};
use crate::scenario::v2::{Measurement3dSpec, Scenario3d};
use crate::{with_capacities, with_measurement};
use nalgebra::SVector;
use std::collections::HashMap;
use tracker_core::model::{LightTime, MeasurementModel, MixedNetwork, MixedSensor, Placeable, SensorNetwork};
use tracker_core::sensor::{EarthRotation, GroundSite, Platform, ScanGeometry, SiteSensor};
use tracker_core::{BirthModel, Config, PriorHypothesis, PriorObject, Sensor, StepError, Tracker, TwoBodyJ2};

/// Sensors a network holds on the host: a network of dozens of stations (tracker-core's embedded caps
/// are `ssa_caps::SENSORS` for one kind, `ssa_caps::NETWORK_SENSORS` for mixed kinds).
pub const C: usize = 32;

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
    /// [`Runner3d::step`] with the run's reading of a failure ([`super::step_failure`]); a tracker whose
    /// errors say more than a [`StepError`] (the partitioned tracker's name the cluster) overrides it.
    fn step_or_failure(
        &mut self,
        sensor: usize,
        time: f64,
        measurements: &[Vec<f64>],
    ) -> Result<StepInfo, crate::pipeline::world::StepFailure> {
        self.step(sensor, time, measurements).map_err(super::step_failure)
    }
    /// The posterior now.
    fn posterior(&self) -> Posterior6;
    /// Per measurement of a scan about to be stepped, its association with a MAP track, and the
    /// measurement dimension ([`super::associate::associate`]).
    fn associate(
        &self,
        sensor: usize,
        time: f64,
        measurements: &[Vec<f64>],
    ) -> (usize, Vec<Option<super::associate::Association>>);
}

/// The core measurement model of a scenario's sensors: a network of one kind ([`SensorNetwork`] of the
/// placeable model `X`) or of mixed kinds ([`MixedNetwork`], measurements padded to its `D` components).
pub trait ScenarioNetwork<const D: usize>: MeasurementModel<f64, 6, D> + Clone + Send + Sync + 'static {
    /// The network of `scenario`'s sensors.
    ///
    /// # Errors
    /// The core's message when it rejects the network.
    fn from_scenario(scenario: &Scenario3d) -> Result<Self, Error>;
}

impl<X, const D: usize> ScenarioNetwork<D> for SensorNetwork<f64, X, D, C>
where
    X: Placeable<f64, D> + Send + Sync + 'static,
{
    fn from_scenario(scenario: &Scenario3d) -> Result<Self, Error> {
        let network =
            SensorNetwork::new(EarthRotation::new(scenario.earth_rotation_at_epoch()), &site_sensors::<D>(scenario))
                .map_err(|e| Error::input(format!("sensors: {e}")))?;
        // Light time where a sensor sets it (docs/maths.md §6.12); off, the network measures as before.
        scenario.sensors.iter().enumerate().try_fold(network, |network, (i, sensor)| match sensor.light_time_mode() {
            LightTime::Off => Ok(network),
            mode => network.with_light_time(i, mode).map_err(|e| Error::input(format!("sensors[{i}].light_time: {e}"))),
        })
    }
}

impl ScenarioNetwork<MIXED> for MixedNetwork<f64, C> {
    fn from_scenario(scenario: &Scenario3d) -> Result<Self, Error> {
        let sites = site_sensors::<MIXED>(scenario);
        let mut sensors = Vec::with_capacity(sites.len());
        for (i, sensor) in sites.into_iter().enumerate() {
            let kind = scenario.kind(i).core().ok_or_else(|| Error::input(format!("sensors[{i}]: no kind")))?;
            sensors.push(MixedSensor { kind, sensor });
        }
        let mut network = MixedNetwork::new(EarthRotation::new(scenario.earth_rotation_at_epoch()), &sensors)
            .map_err(|e| Error::input(format!("sensors: {e}")))?;
        for (i, sensor) in scenario.sensors.iter().enumerate() {
            if let Some(births) = sensor.birth_region {
                network =
                    network.with_births(i, births.core()).map_err(|e| Error::input(format!("sensors[{i}]: {e}")))?;
            }
            // Light time where a sensor sets it (docs/maths.md §6.12), as for a network of one kind.
            if sensor.light_time_mode() != LightTime::Off {
                network = network
                    .with_light_time(i, sensor.light_time_mode())
                    .map_err(|e| Error::input(format!("sensors[{i}].light_time: {e}")))?;
            }
        }
        Ok(network)
    }
}

/// The components of a [`MixedNetwork`]'s measurements.
const MIXED: usize = tracker_core::model::MIXED_DIMENSION;

/// `z` (a sensor's own components) as the tracker's vector of `D`: zeros after its components (a mixed
/// network's padding; the identity for a network of one kind, whose measurements have `D`).
pub fn padded<const D: usize>(z: &[f64]) -> SVector<f64, D> {
    SVector::from_iterator(z.iter().copied().chain(core::iter::repeat(0.0)).take(D))
}

type Tracker3d<G, const D: usize, const H: usize, const N: usize, const Z: usize, const K: usize, const B: usize> =
    Tracker<f64, TwoBodyJ2<f64>, G, 6, D, H, N, Z, K, B>;

struct Core3d<G, const D: usize, const H: usize, const N: usize, const Z: usize, const K: usize, const B: usize>
where
    G: ScenarioNetwork<D>,
{
    tracker: Box<Tracker3d<G, D, H, N, Z, K, B>>,
}

impl<G, const D: usize, const H: usize, const N: usize, const Z: usize, const K: usize, const B: usize> Runner3d
    for Core3d<G, D, H, N, Z, K, B>
where
    G: ScenarioNetwork<D>,
{
    fn step(&mut self, sensor: usize, time: f64, measurements: &[Vec<f64>]) -> Result<StepInfo, StepError> {
        let zs: Vec<SVector<f64, D>> = measurements.iter().map(|z| padded::<D>(z)).collect();
        let report = self.tracker.step_scan(&ScanGeometry { sensor, time, observer: None }, &zs)?;
        Ok(StepInfo {
            children: report.children,
            hypotheses: report.hypotheses,
            captured_mass: report.captured_mass,
            budget_reached: false,
            numerical_drops: report.numerical_drops,
            lost_tracks: report.lost_tracks,
            tracklets_formed: report.birth_pool.tracklets,
        })
    }

    fn associate(
        &self,
        sensor: usize,
        time: f64,
        measurements: &[Vec<f64>],
    ) -> (usize, Vec<Option<super::associate::Association>>) {
        super::associate::associate(&self.tracker, sensor, time, measurements)
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
        .enumerate()
        .map(|(i, s)| {
            let sigma = s.noise.sigma(scenario.kind(i));
            SiteSensor {
                platform: Platform::Ground(GroundSite {
                    latitude: s.site.latitude_deg.to_radians(),
                    longitude: s.site.longitude_deg.to_radians(),
                    height: s.site.height_km,
                }),
                // A mixed network's padding is zero; a network of one kind has D components.
                sigma: core::array::from_fn(|k| sigma.get(k).copied().unwrap_or(0.0)),
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
pub fn network<G: ScenarioNetwork<D>, const D: usize>(scenario: &Scenario3d) -> Result<G, Error> {
    G::from_scenario(scenario)
}

/// The core configuration and the prior of `scenario` for the tracker `kind` with `B` birth cells.
///
/// # Errors
/// Bad input: a network the core refuses, more birth cells than `B`, no sensor.
#[allow(clippy::type_complexity)]
pub fn config3d<G, const D: usize, const B: usize>(
    scenario: &Scenario3d,
    kind: TrackerKind,
) -> Result<(Config<f64, TwoBodyJ2<f64>, G, 6, B>, Vec<(f64, Vec<PriorObject<f64, 6>>)>), Error>
where
    G: ScenarioNetwork<D>,
{
    let network = network::<G, D>(scenario)?;
    let cells =
        settings::birth_cells(scenario.birth.cells.iter().map(|c| (&c.mean, &c.covariance)), "this tracker's capacity")
            .map_err(Error::input)?;
    let spec = &scenario.tracker;
    let (selection, store_overflow, numerical_failure, track_loss) = settings::policies(spec);
    let first = network.detection();
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
            detection: settings::birth_detection(scenario.birth.detection),
        },
        death_probability: scenario.death_probability,
        gate: spec.gate,
        children: settings::children(kind, spec),
        selection,
        store_overflow,
        numerical_failure,
        track_loss,
        seed: spec.seed,
    };
    let prior = settings::prior(
        scenario
            .prior
            .hypotheses
            .iter()
            .map(|h| (h.weight, h.objects.iter().map(|o| (o.label, &o.mean, &o.covariance)))),
    );
    Ok((config, prior))
}

fn core3d<G, const D: usize, const H: usize, const N: usize, const Z: usize, const K: usize, const B: usize>(
    scenario: &Scenario3d,
    kind: TrackerKind,
) -> Result<Box<dyn Runner3d>, Error>
where
    G: ScenarioNetwork<D>,
{
    let prior_objects = scenario.max_prior_objects();
    if prior_objects > N {
        // One tracker holds at most N objects per hypothesis (issue 30: a partitioned tracker for catalogues).
        return Err(Error::input(format!(
            "the prior holds {prior_objects} objects, more than one tracker of this profile holds (its capacity \
             N = {N}; the host profile's is {}): track a smaller catalogue",
            crate::pipeline::profile::HOST_OBJECTS_3D
        )));
    }
    let (config, objects) = config3d::<G, D, B>(scenario, kind)?;
    let prior: Vec<PriorHypothesis<'_, f64, 6>> =
        objects.iter().map(|(weight, objects)| PriorHypothesis { weight: *weight, objects }).collect();
    let tracker = Tracker3d::<G, D, H, N, Z, K, B>::new(config, &prior, scenario.prior.time)
        .map_err(|e| Error::input(format!("tracker configuration: {e}")))?;
    Ok(Box::new(Core3d { tracker: Box::new(tracker) }))
}

/// The profile a run uses: the one asked for, or else `embedded` when the scenario fits it (prior objects
/// below N, measurements within Z, birth cells within B) and `host` otherwise.
pub fn choose_profile(scenario: &Scenario3d, asked: Option<Profile>) -> Profile {
    if let Some(profile) = asked {
        return profile;
    }
    let (_, n, z, _, b) = ORBITAL.embedded.tuple();
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

/// The most birth components one measurement of `scenario` can give (0 without measured births,
/// [`Measurement3dSpec::birth_components`]; its tracklet's cells when every birth comes from a tracklet). A
/// measurement whose components do not fit the pool gives no birth.
pub fn birth_components_per_measurement(scenario: &Scenario3d) -> usize {
    if scenario.births_from_tracklets_only()
        && let Some(tracklets) = scenario.birth.measured.and_then(|m| m.tracklets)
    {
        return tracklets.cells[0].saturating_mul(tracklets.cells[1]);
    }
    (0..scenario.sensors.len())
        .filter_map(|i| Some(scenario.kind(i).birth_components(&scenario.birth_region(i)?)))
        .max()
        .unwrap_or(0)
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
    let n = ORBITAL.of(profile).objects;
    if scenario.max_prior_objects() > n {
        // More objects than one tracker holds: clusters of objects (docs/maths.md §13).
        let cluster = crate::partition::runner::CLUSTER;
        eprintln!(
            "note: {} prior objects, more than the {} profile's N = {n}: the partitioned tracker (clusters of H = {}, N = \
             {}, Z = {})",
            scenario.max_prior_objects(),
            profile.name(),
            cluster.hypotheses,
            cluster.objects,
            cluster.measurements
        );
        return crate::partition::runner::build(kind, scenario);
    }
    with_measurement!(scenario.measurement, build_for, (kind, profile, scenario))
}

/// [`build3d`] for the network `G`.
fn build_for<G, const D: usize>(
    kind: TrackerKind,
    profile: Profile,
    scenario: &Scenario3d,
) -> Result<Box<dyn Runner3d>, Error>
where
    G: ScenarioNetwork<D>,
{
    with_capacities!(profile, ORBITAL, core3d, [G, D], (scenario, kind))
}

/// The measurements of a scan in the tracker's units: angles from degrees to radians, azimuth and right
/// ascension first wrapped to the core's (−180°, 180°] ([`crate::io::angles::wrap`]; the identity there).
pub fn measurements_in_radians(kind: Measurement3dSpec, measurements: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let wrapped = |i: usize, v: f64| if kind.wraps(i) { crate::io::angles::wrap(v) } else { v };
    measurements
        .iter()
        .map(|z| {
            z.iter().enumerate().map(|(i, &v)| if kind.is_angle(i) { wrapped(i, v).to_radians() } else { v }).collect()
        })
        .collect()
}
