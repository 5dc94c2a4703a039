//! Trackers behind one interface, so that `run` and `compare` treat the bounded core trackers and the
//! unbounded reference alike.
//!
//! The core's capacities are compile-time constants, so the host offers two capacity profiles:
//! `embedded` (the default SSA configuration of tracker-core, [`tracker_core::ssa_caps`]) and `host`
//! (larger, for dense scenarios such as the debris crossing).

use crate::reference::ReferenceTracker;
use crate::scenario::{MotionSpec, Scenario, ScenarioError};
use crate::pipeline::planar::setup;
use crate::pipeline::snapshot::Snapshot;
use nalgebra::SVector;
use tracker_core::{ChildGeneration, Config, MotionModel, PositionMeasurement, PriorHypothesis, Tracker, ssa_caps};

/// Which tracker to run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum TrackerKind {
    /// The unbounded exhaustive reference (every child of every parent).
    Reference,
    /// tracker-core with exhaustive children, capped at H∞ hypotheses.
    Homht,
    /// tracker-core with R-FISST's sampled children (Metropolis, by clusters), capped at H∞.
    Rfisst,
}

impl TrackerKind {
    /// The name written to outputs.
    pub fn name(self) -> &'static str {
        match self {
            TrackerKind::Reference => "reference",
            TrackerKind::Homht => "homht",
            TrackerKind::Rfisst => "rfisst",
        }
    }
}

/// Capacity profile of the core tracker.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum, Default)]
pub enum Profile {
    /// H = 32, N = 64, Z = 32, K = 256, B = 8: the embedded default (tracker-core's `ssa_caps`).
    #[default]
    Embedded,
    /// H = 256, N = 128, Z = 64, K = 4096, B = 64 (room for birth cells made from measurements).
    Host,
}

impl Profile {
    /// The name written to outputs.
    pub fn name(self) -> &'static str {
        match self {
            Profile::Embedded => "embedded",
            Profile::Host => "host",
        }
    }

    /// (H, N, Z, K, B).
    pub fn caps(self) -> (usize, usize, usize, usize, usize) {
        match self {
            Profile::Embedded => (
                ssa_caps::HYPOTHESES,
                ssa_caps::OBJECTS,
                ssa_caps::MEASUREMENTS,
                ssa_caps::TRACKS,
                ssa_caps::BIRTH_CELLS,
            ),
            Profile::Host => (256, 128, 64, 4096, 64),
        }
    }
}

/// What one scan did, in tracker-independent terms.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepInfo {
    /// Children with non-zero weight generated.
    pub children: u64,
    /// Hypotheses kept.
    pub hypotheses: usize,
    /// Fraction of the children's weight kept.
    pub captured_mass: f64,
    /// Whether the reference's memory budget forced pruning.
    pub budget_reached: bool,
}

/// A scan the tracker rejected, with the tracker's one-line message; the tracker is unchanged.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct StepRejected(pub String);

impl std::fmt::Display for StepRejected {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

/// A tracker that processes scans.
pub trait Runner: Send {
    /// Processes one scan.
    ///
    /// # Errors
    /// [`StepRejected`] with the tracker's message; the tracker is unchanged.
    fn step(&mut self, time: f64, measurements: &[SVector<f64, 2>]) -> Result<StepInfo, StepRejected>;
    /// The posterior now.
    fn snapshot(&self) -> Snapshot;
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
        let report = self.tracker.step(time, measurements).map_err(|e| StepRejected(e.to_string()))?;
        Ok(StepInfo {
            children: report.children,
            hypotheses: report.hypotheses,
            captured_mass: report.captured_mass,
            budget_reached: false,
        })
    }

    fn snapshot(&self) -> Snapshot {
        Snapshot::of(&*self.tracker)
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
        let report = self.tracker.step(time, measurements).map_err(|e| StepRejected(e.to_string()))?;
        Ok(StepInfo {
            children: report.children,
            hypotheses: report.hypotheses,
            captured_mass: report.captured_mass,
            budget_reached: report.budget_reached,
        })
    }

    fn snapshot(&self) -> Snapshot {
        self.tracker.snapshot()
    }
}

/// The unbounded reference's budgets: memory (beyond it the lowest-weight children are dropped) and
/// children enumerated per scan (beyond it the scan fails: the reference is broken there).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ReferenceBudget {
    /// Bytes of everything that grows with the hypotheses, children and measurements.
    pub bytes: usize,
    /// Children enumerated per scan.
    pub children: u64,
}

impl Default for ReferenceBudget {
    fn default() -> Self {
        Self { bytes: 4 << 30, children: 1_000_000_000 }
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
    Ok(Box::new(ReferenceRunner { tracker }))
}

macro_rules! core_for_profile {
    ($profile:expr, $scenario:expr, $motion:expr, $children:expr) => {
        match $profile {
            Profile::Embedded => core_runner::<
                _,
                { ssa_caps::HYPOTHESES },
                { ssa_caps::OBJECTS },
                { ssa_caps::MEASUREMENTS },
                { ssa_caps::TRACKS },
                { ssa_caps::BIRTH_CELLS },
            >($scenario, $motion, $children),
            Profile::Host => core_runner::<_, 256, 128, 64, 4096, 64>($scenario, $motion, $children),
        }
    };
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
            core_for_profile!(profile, scenario, setup::two_body(&scenario.motion).expect("two-body"), children)
        }
        (TrackerKind::Homht | TrackerKind::Rfisst, MotionSpec::ConstantVelocity { .. }) => {
            core_for_profile!(
                profile,
                scenario,
                setup::constant_velocity(&scenario.motion).expect("constant velocity"),
                children
            )
        }
    }
}
