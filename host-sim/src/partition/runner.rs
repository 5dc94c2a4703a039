//! The partitioned tracker behind the orbital world's [`Runner3d`]: a version 2 scenario's configuration
//! (its sensors, gate, birth model) with clusters of the fixed capacities [`CLUSTER`], chosen by `run` and
//! `run-catalogue` when the prior holds more objects than one tracker's N.

use super::{PartitionError, PartitionedTracker, marginal};
use crate::error::Error;
use crate::pipeline::orbital::associate::{Association, associate};
use crate::pipeline::orbital::{Posterior6, Runner3d, ScenarioNetwork, config3d, padded};
use crate::pipeline::profile::Capacities;
use crate::pipeline::snapshot::Track6;
use crate::pipeline::tracker::{StepInfo, TrackerKind};
use crate::pipeline::world::StepFailure;
use crate::scenario::v2::Scenario3d;
use crate::with_measurement;
use nalgebra::SVector;
use std::collections::{BTreeMap, HashMap};
use tracker_core::model::TwoBodyJ2;
use tracker_core::sensor::ScanGeometry;
use tracker_core::{StepError, ekf, report::NumericalDrops};

/// A cluster's capacities: H, N, Z (the measurements routed to one cluster, the birth cluster's included),
/// K and B (the birth cluster's cells, fixed and measured).
pub const CLUSTER: Capacities =
    Capacities { hypotheses: 32, objects: 16, measurements: 64, tracks: 96, birth_cells: 32 };

/// The smallest radius (km) a two-body + J2 prediction passes through: its default `min_radius`, below
/// which a prediction fails.
const MIN_RADIUS_KM: f64 = tracker_core::model::EARTH_MIN_RADIUS;

/// A ground site's largest speed (km/s) in the inertial frame: the Earth's rotation at 7,000 km from its
/// axis (0.465 km/s at the equator at sea level).
const SITE_SPEED_KM_S: f64 = 0.52;

/// A bound (rad/s) on the Earth's rotation rate (7.2921·10⁻⁵).
const EARTH_RATE_RAD_S: f64 = 7.3e-5;

/// A bound (km/s) on how fast the object of the two-body + J2 state `x` (km, km/s) closes in on any point
/// fixed to the rotating Earth within `reach` km of a ground site (docs/maths.md §13.2): its speed anywhere
/// outside [`MIN_RADIUS_KM`] by conservation of energy, v_max² = v² + 2μ (1/r_min − 1/r), times 1.02 for J2
/// (its potential changes by less than 0.2 km²/s² outside r_min, under 2 % of v_max² for any orbit) and
/// integration error, plus the point's own speed: at most 7,000 + `reach` km from the Earth's axis, it
/// moves at most at the site's speed plus ω⊕ · `reach`.
pub fn ground_closing_speed(x: &SVector<f64, 6>, reach: f64) -> f64 {
    let r = x.fixed_rows::<3>(0).norm();
    let v2 = x.fixed_rows::<3>(3).norm_squared();
    let mu = tracker_core::model::EARTH_MU;
    let v2_max = v2 + 2.0 * mu * (1.0 / MIN_RADIUS_KM - 1.0 / r).max(0.0);
    1.02 * v2_max.sqrt() + SITE_SPEED_KM_S + EARTH_RATE_RAD_S * reach.max(0.0)
}

/// The partitioned tracker of a network `G` with clusters of [`CLUSTER`]'s capacities.
pub type Partitioned<G, const D: usize> = PartitionedTracker<
    TwoBodyJ2<f64>,
    G,
    6,
    D,
    { CLUSTER.hypotheses },
    { CLUSTER.objects },
    { CLUSTER.measurements },
    { CLUSTER.tracks },
    { CLUSTER.birth_cells },
>;

struct Runner<G: ScenarioNetwork<D>, const D: usize> {
    tracker: Partitioned<G, D>,
}

/// The partitioned tracker `kind` (the children inside each cluster) of `scenario`, whose prior must be one
/// hypothesis; splits are exact only (ε = 0).
///
/// # Errors
/// Bad input: a prior of several hypotheses, a configuration or object the core refuses.
pub fn build(kind: TrackerKind, scenario: &Scenario3d) -> Result<Box<dyn Runner3d>, Error> {
    with_measurement!(scenario.measurement, build_for, (kind, scenario))
}

fn build_for<G: ScenarioNetwork<D>, const D: usize>(
    kind: TrackerKind,
    scenario: &Scenario3d,
) -> Result<Box<dyn Runner3d>, Error> {
    if scenario.prior.hypotheses.len() != 1 {
        return Err(Error::input("partitioned tracker: the prior must be one hypothesis (certain objects)"));
    }
    let (config, prior) = config3d::<G, D, { CLUSTER.birth_cells }>(scenario, kind)?;
    let objects = prior.first().map(|(_, o)| o.as_slice()).unwrap_or(&[]);
    let tracker = Partitioned::<G, D>::new(config, objects, scenario.prior.time, 0.0)
        .map_err(|e| Error::input(format!("partitioned tracker: {e}")))?;
    Ok(Box::new(Runner { tracker }))
}

/// A partitioned scan in the run's terms.
fn info(report: &super::PartitionReport) -> StepInfo {
    StepInfo {
        children: 0,
        hypotheses: report.hypotheses,
        captured_mass: 1.0 - report.step_pruned_mass - report.merge_pruned_mass,
        budget_reached: false,
        numerical_drops: NumericalDrops::default(),
        lost_tracks: report.lost_tracks,
        tracklets_formed: report.tracklets_formed,
    }
}

impl<G: ScenarioNetwork<D>, const D: usize> Runner3d for Runner<G, D> {
    /// The core's error behind a partitioned failure, without the cluster's name; the run itself reads
    /// [`Runner3d::step_or_failure`], whose messages name the cluster.
    fn step(&mut self, sensor: usize, time: f64, measurements: &[Vec<f64>]) -> Result<StepInfo, StepError> {
        let zs: Vec<SVector<f64, D>> = measurements.iter().map(|z| padded::<D>(z)).collect();
        match self.tracker.step(&ScanGeometry { sensor, time, observer: None }, &zs) {
            Ok(report) => Ok(info(&report)),
            Err(PartitionError::Scan(e) | PartitionError::Cluster { error: e, .. }) => Err(e),
            Err(PartitionError::TooManyMeasurements { received, capacity, .. }) => {
                Err(StepError::TooManyMeasurements { received, capacity })
            }
            // A merge beyond a cluster's N or K: the store is full.
            Err(_) => Err(StepError::TrackStoreFull { capacity: { CLUSTER.tracks } }),
        }
    }

    fn step_or_failure(
        &mut self,
        sensor: usize,
        time: f64,
        measurements: &[Vec<f64>],
    ) -> Result<StepInfo, StepFailure> {
        let zs: Vec<SVector<f64, D>> = measurements.iter().map(|z| padded::<D>(z)).collect();
        let report = self.tracker.step(&ScanGeometry { sensor, time, observer: None }, &zs).map_err(|e| match e {
            PartitionError::Scan(e) => crate::pipeline::orbital::step_failure(e),
            e => StepFailure::Rejected(e.to_string()),
        })?;
        Ok(info(&report))
    }

    fn posterior(&self) -> Posterior6 {
        posterior(&self.tracker)
    }

    fn associate(&self, sensor: usize, time: f64, measurements: &[Vec<f64>]) -> (usize, Vec<Option<Association>>) {
        let mut best: Vec<Option<Association>> = vec![None; measurements.len()];
        let mut dimension = D;
        // A cluster's rest always loads (the tracker made it), so every cluster is read.
        let _ = self.tracker.for_each_core(|_, core| {
            let (d, found) = associate(core, sensor, time, measurements);
            dimension = d;
            for (best, found) in best.iter_mut().zip(found) {
                if let Some(a) = found
                    && best.as_ref().is_none_or(|b| a.2 < b.2)
                {
                    *best = Some(a);
                }
            }
        });
        (dimension, best)
    }
}

/// The posterior of `tracker`: per-label existence from each cluster's marginals, the MAP hypothesis the
/// union of the clusters' MAP hypotheses.
pub fn posterior<G: ScenarioNetwork<D>, const D: usize>(tracker: &Partitioned<G, D>) -> Posterior6 {
    posterior_at(tracker, tracker.time())
}

/// [`posterior`] with the MAP tracks of clusters left behind by a view skip (§13.2) predicted to `time`
/// (a track whose prediction fails is given as it is).
pub fn posterior_at<G: ScenarioNetwork<D>, const D: usize>(tracker: &Partitioned<G, D>, time: f64) -> Posterior6 {
    let mut objects = BTreeMap::new();
    let mut posterior = Posterior6::default();
    for cluster in tracker.clusters() {
        let rest = &cluster.rest;
        marginal::add_weighted(|| rest.weighted(), &mut objects);
        posterior.hypotheses += rest.hypothesis_count();
        posterior.expected_cardinality += rest.expected_cardinality();
        let dt = time - rest.time();
        // The product's MAP hypothesis is the union of the clusters' MAP hypotheses (each one's first).
        for t in rest.weighted().next().into_iter().flat_map(|(_, tracks)| tracks) {
            let state = match dt > 0.0 {
                true => ekf::predict(tracker.motion(), &t.state, dt).unwrap_or(t.state),
                false => t.state,
            };
            posterior.map.push(Track6 {
                label: t.label.0,
                mean: state.mean.into(),
                existence: 0.0,
                covariance: core::array::from_fn(|i| core::array::from_fn(|j| state.covariance[(i, j)])),
            });
        }
    }
    posterior.existence = objects.iter().map(|(l, o)| (*l, o.existence)).collect::<HashMap<_, _>>();
    for t in &mut posterior.map {
        t.existence = posterior.existence.get(&t.label).copied().unwrap_or(0.0);
    }
    posterior
}
