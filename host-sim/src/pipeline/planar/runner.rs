//! The planar world's trackers behind one interface, so that `run` and `compare` treat the bounded core
//! trackers (capacities of the [`Profile`]'s [`PLANAR`] table) and the unbounded reference alike.

use super::setup;
use crate::peers::reference::{ReferenceError, ReferenceTracker};
use crate::pipeline::profile::PLANAR;
use crate::pipeline::profile::Profile;
use crate::pipeline::snapshot::Snapshot;
use crate::pipeline::tracker::{ReferenceBudget, StepInfo, StepRejected, TrackerKind, is_refused_input};
use crate::scenario::{MotionSpec, Scenario, ScenarioError};
use crate::with_capacities;
use nalgebra::SVector;
use tracker_core::{ChildGeneration, Config, MotionModel, PositionMeasurement, PriorHypothesis, Tracker};

/// A tracker that processes scans.
pub trait Runner: Send {
    /// Processes one scan.
    ///
    /// # Errors
    /// [`StepRejected`] with the tracker's message; the tracker is unchanged.
    fn step(&mut self, time: f64, measurements: &[SVector<f64, 2>]) -> Result<StepInfo, StepRejected>;
    /// The posterior now.
    fn snapshot(&self) -> Snapshot;
    /// Per measurement of a scan about to be stepped, its association with a MAP track
    /// ([`crate::pipeline::orbital::associate::associate`]); `None` for a tracker that is not judged (the
    /// reference).
    fn associate(
        &self,
        _time: f64,
        _measurements: &[Vec<f64>],
    ) -> Option<Vec<Option<crate::pipeline::orbital::associate::Association>>> {
        None
    }
}

struct CoreRunner<M, const H: usize, const N: usize, const Z: usize, const K: usize, const B: usize> {
    tracker: Box<Tracker<f64, M, PositionMeasurement<f64>, 4, 2, H, N, Z, K, B>>,
}

impl<M, const H: usize, const N: usize, const Z: usize, const K: usize, const B: usize> Runner
    for CoreRunner<M, H, N, Z, K, B>
where
    M: MotionModel<f64, 4> + Send,
{
    fn step(&mut self, time: f64, measurements: &[SVector<f64, 2>]) -> Result<StepInfo, StepRejected> {
        let report =
            self.tracker.step(time, measurements).map_err(|e| StepRejected(e.to_string(), is_refused_input(&e)))?;
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

    fn snapshot(&self) -> Snapshot {
        Snapshot::of(&*self.tracker)
    }

    fn associate(
        &self,
        time: f64,
        measurements: &[Vec<f64>],
    ) -> Option<Vec<Option<crate::pipeline::orbital::associate::Association>>> {
        Some(crate::pipeline::orbital::associate::associate(&self.tracker, 0, time, measurements).1)
    }
}

fn core_runner<M, const H: usize, const N: usize, const Z: usize, const K: usize, const B: usize>(
    scenario: &Scenario,
    motion: M,
    children: ChildGeneration,
) -> Result<Box<dyn Runner>, ScenarioError>
where
    M: MotionModel<f64, 4> + Send + 'static,
{
    let config: Config<f64, M, PositionMeasurement<f64>, 4, B> = setup::config(scenario, motion, children)?;
    let prior = setup::prior(scenario);
    let hypotheses: Vec<PriorHypothesis<'_, f64, 4>> =
        prior.iter().map(|(weight, objects)| PriorHypothesis { weight: *weight, objects }).collect();
    let tracker =
        Tracker::<f64, M, PositionMeasurement<f64>, 4, 2, H, N, Z, K, B>::new(config, &hypotheses, scenario.prior.time)
            .map_err(|e| ScenarioError(format!("tracker configuration: {e}")))?;
    Ok(Box::new(CoreRunner { tracker: Box::new(tracker) }))
}

struct ReferenceRunner<M> {
    tracker: ReferenceTracker<M>,
}

impl<M: MotionModel<f64, 4> + Send> Runner for ReferenceRunner<M> {
    fn step(&mut self, time: f64, measurements: &[SVector<f64, 2>]) -> Result<StepInfo, StepRejected> {
        let report = self.tracker.step(time, measurements).map_err(|e| {
            let refused = matches!(&e, ReferenceError::Step(step) if is_refused_input(step));
            StepRejected(e.to_string(), refused)
        })?;
        Ok(StepInfo {
            children: report.children,
            hypotheses: report.hypotheses,
            captured_mass: report.captured_mass,
            budget_reached: report.budget_reached,
            numerical_drops: tracker_core::report::NumericalDrops::default(),
            lost_tracks: 0,
            tracklets_formed: 0,
        })
    }

    fn snapshot(&self) -> Snapshot {
        self.tracker.snapshot()
    }
}

/// The reference for `scenario`. It has no object capacity N: its event model is checked with the objects
/// of the prior's largest hypothesis when it is built, and with each parent's objects at every scan.
fn reference_runner<M>(
    scenario: &Scenario,
    motion: M,
    budget: ReferenceBudget,
) -> Result<Box<dyn Runner>, ScenarioError>
where
    M: MotionModel<f64, 4> + Clone + Send + 'static,
{
    // The reference has no capacities: allow as many birth cells as the scenario has.
    let config: Config<f64, M, PositionMeasurement<f64>, 4, 1024> =
        setup::config(scenario, motion, setup::exhaustive(scenario))?;
    let mut tracker = ReferenceTracker::new(&config, &setup::prior(scenario), scenario.prior.time, budget.bytes)
        .map_err(ScenarioError)?;
    tracker.set_max_children(budget.children);
    tracker.set_max_work(budget.work);
    Ok(Box::new(ReferenceRunner { tracker }))
}

/// Builds the tracker `kind` for `scenario`.
///
/// # Errors
/// A message when the scenario does not fit the tracker (for example more birth cells than the profile
/// holds) or its configuration is rejected.
pub fn build(
    kind: TrackerKind,
    profile: Profile,
    scenario: &Scenario,
    reference: ReferenceBudget,
) -> Result<Box<dyn Runner>, ScenarioError> {
    let children = if kind == TrackerKind::Rfisst { setup::sampled(scenario) } else { setup::exhaustive(scenario) };
    match (kind, scenario.motion) {
        (TrackerKind::Reference, MotionSpec::TwoBody { .. }) => {
            reference_runner(scenario, setup::two_body(&scenario.motion).expect("two-body"), reference)
        }
        (TrackerKind::Reference, MotionSpec::ConstantVelocity { .. }) => reference_runner(
            scenario,
            setup::constant_velocity(&scenario.motion).expect("constant velocity"),
            reference,
        ),
        (TrackerKind::Homht | TrackerKind::Rfisst, MotionSpec::TwoBody { .. }) => {
            with_capacities!(
                profile,
                PLANAR,
                core_runner,
                [_],
                (scenario, setup::two_body(&scenario.motion).expect("two-body"), children)
            )
        }
        (TrackerKind::Homht | TrackerKind::Rfisst, MotionSpec::ConstantVelocity { .. }) => {
            with_capacities!(
                profile,
                PLANAR,
                core_runner,
                [_],
                (scenario, setup::constant_velocity(&scenario.motion).expect("constant velocity"), children)
            )
        }
    }
}
