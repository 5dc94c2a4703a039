//! The core trackers behind one object-safe interface ([`Engine`]), built from a scenario of either version
//! exactly as `host-sim run` builds them: the same configuration and prior (host-sim's
//! `pipeline::planar::setup` and `pipeline::orbital::config3d`), the same capacity profiles, the same
//! measurement units; so that the MAP estimates equal the CLI's bit for bit.

use host_sim::pipeline::orbital::{ScenarioNetwork, choose_profile, config3d};
use host_sim::pipeline::planar::setup;
use host_sim::pipeline::profile::{ORBITAL, PLANAR};
use host_sim::pipeline::{Profile, TrackerKind, settings};
use host_sim::scenario::v2::Scenario3d;
use host_sim::scenario::{MotionSpec, Scenario};
use host_sim::{with_capacities, with_measurement};
use nalgebra::SVector;
use tracker_core::report::StepReport;
use tracker_core::sensor::ScanGeometry;
use tracker_core::{
    ChildGeneration, Config, MeasurementModel, MotionModel, PositionMeasurement, PriorHypothesis, StepError, Tracker,
    TwoBodyJ2,
};

/// The stack of the thread that builds and steps a tracker: the core's trackers are built and stepped by
/// value on the stack (megabytes; more with the host profile), as `host-sim` runs them on a 512 MiB stack.
const STACK_BYTES: usize = 512 << 20;

type Job = Box<dyn FnOnce() + Send>;

/// A thread with a [`STACK_BYTES`] stack (reserved, not committed, until used) that runs one job at a time;
/// one per tracker, kept for its life (starting a thread per scan would cost about 0.2 ms).
pub struct LargeStack {
    jobs: std::sync::mpsc::Sender<Job>,
}

impl LargeStack {
    /// Starts the thread.
    ///
    /// # Errors
    /// A message when the thread cannot be started.
    pub fn new() -> Result<Self, String> {
        let (jobs, queue) = std::sync::mpsc::channel::<Job>();
        std::thread::Builder::new()
            .name("rfisst".into())
            .stack_size(STACK_BYTES)
            .spawn(move || {
                // Ends when the tracker (the sender) is dropped. A job that panics drops its reply channel,
                // which its caller reports; the thread goes on.
                for job in queue {
                    let _ = std::panic::catch_unwind(std::panic::AssertUnwindSafe(job));
                }
            })
            .map_err(|e| format!("cannot start the tracker's thread: {e}"))?;
        Ok(Self { jobs })
    }

    /// Runs `f` on the thread and returns its result.
    ///
    /// # Errors
    /// A message when the thread has stopped or `f` panicked.
    pub fn run<R: Send + 'static>(&self, f: impl FnOnce() -> R + Send + 'static) -> Result<R, String> {
        let (reply, result) = std::sync::mpsc::sync_channel(1);
        self.jobs
            .send(Box::new(move || {
                let _ = reply.send(f());
            }))
            .map_err(|_| "the tracker's thread has stopped".to_string())?;
        result.recv().map_err(|_| "the tracker panicked (a bug: please report it)".to_string())
    }
}

/// One track of the posterior.
pub struct TrackData {
    /// Object label.
    pub label: u32,
    /// Mean (state dimension).
    pub mean: Vec<f64>,
    /// Covariance, row-major.
    pub covariance: Vec<f64>,
    /// Existence probability of this track.
    pub existence: f64,
}

/// One hypothesis: its weight and the indices of its tracks in [`Posterior::tracks`], in label order.
pub struct HypothesisData {
    /// Normalised weight.
    pub weight: f64,
    /// ln of the weight.
    pub log_weight: f64,
    /// Indices into the posterior's tracks.
    pub tracks: Vec<usize>,
}

/// The posterior: hypotheses best first (the first is the MAP) and the distinct tracks they hold.
pub struct Posterior {
    /// Hypotheses, best first.
    pub hypotheses: Vec<HypothesisData>,
    /// Distinct tracks, in the track store's order.
    pub tracks: Vec<TrackData>,
}

/// A core tracker of any model and capacities.
pub trait Engine: Send + Sync {
    /// Steps the tracker with one scan of `sensor` at `time`; `measurements` are row-major, `D` per row, in
    /// the tracker's units.
    ///
    /// # Errors
    /// The core's [`StepError`]; the tracker is unchanged.
    fn step(&mut self, sensor: usize, time: f64, measurements: &[f64]) -> Result<StepReport<f64>, StepError>;
    /// The posterior now.
    fn posterior(&self) -> Posterior;
    /// Time of the last scan (or of the prior).
    fn time(&self) -> f64;
}

struct Core<
    M,
    G,
    const X: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
> {
    tracker: Box<Tracker<f64, M, G, X, D, H, N, Z, K, B>>,
    /// Planar trackers are stepped as `host-sim` steps them (`Tracker::step`), 3-D ones with their scan
    /// geometry (`Tracker::step_scan`).
    planar: bool,
}

impl<
    M,
    G,
    const X: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
> Engine for Core<M, G, X, D, H, N, Z, K, B>
where
    M: MotionModel<f64, X> + Send + Sync,
    G: MeasurementModel<f64, X, D> + Clone + Send + Sync,
{
    fn step(&mut self, sensor: usize, time: f64, measurements: &[f64]) -> Result<StepReport<f64>, StepError> {
        let zs: Vec<SVector<f64, D>> = measurements.chunks_exact(D).map(SVector::from_column_slice).collect();
        if self.planar {
            self.tracker.step(time, &zs)
        } else {
            self.tracker.step_scan(&ScanGeometry { sensor, time, observer: None }, &zs)
        }
    }

    fn posterior(&self) -> Posterior {
        let tracks = self
            .tracker
            .tracks()
            .iter()
            .map(|t| TrackData {
                label: t.label.0,
                mean: t.state.mean.iter().copied().collect(),
                covariance: t.state.covariance.transpose().iter().copied().collect(),
                existence: t.existence,
            })
            .collect();
        let hypotheses = self
            .tracker
            .hypotheses()
            .map(|h| HypothesisData {
                weight: h.weight(),
                log_weight: h.log_weight(),
                tracks: h.slots().iter().map(|&s| usize::from(s)).collect(),
            })
            .collect();
        Posterior { hypotheses, tracks }
    }

    fn time(&self) -> f64 {
        self.tracker.time()
    }
}

fn planar<M, const H: usize, const N: usize, const Z: usize, const K: usize, const B: usize>(
    scenario: &Scenario,
    motion: M,
    children: ChildGeneration,
) -> Result<Box<dyn Engine>, String>
where
    M: MotionModel<f64, 4> + Send + Sync + 'static,
{
    let config: Config<f64, M, PositionMeasurement<f64>, 4, B> =
        setup::config(scenario, motion, children).map_err(|e| e.to_string())?;
    let prior = setup::prior(scenario);
    let hypotheses: Vec<PriorHypothesis<'_, f64, 4>> =
        prior.iter().map(|(weight, objects)| PriorHypothesis { weight: *weight, objects }).collect();
    let tracker =
        Tracker::<f64, M, PositionMeasurement<f64>, 4, 2, H, N, Z, K, B>::new(config, &hypotheses, scenario.prior.time)
            .map_err(|e| format!("tracker configuration: {e}"))?;
    Ok(Box::new(Core { tracker: Box::new(tracker), planar: true }))
}

/// The planar tracker `kind` of a version 1 scenario with the capacities of `profile`.
///
/// # Errors
/// A one-line message when the scenario does not fit the tracker or the core refuses its configuration.
pub fn build_planar(scenario: &Scenario, kind: TrackerKind, profile: Profile) -> Result<Box<dyn Engine>, String> {
    let children = settings::children(kind, &scenario.tracker);
    match scenario.motion {
        MotionSpec::TwoBody { .. } => {
            let motion = setup::two_body(&scenario.motion).ok_or("motion: not two-body")?;
            with_capacities!(profile, PLANAR, planar, [_], (scenario, motion, children))
        }
        MotionSpec::ConstantVelocity { .. } => {
            let motion = setup::constant_velocity(&scenario.motion).ok_or("motion: not constant velocity")?;
            with_capacities!(profile, PLANAR, planar, [_], (scenario, motion, children))
        }
    }
}

fn orbital<G, const D: usize, const H: usize, const N: usize, const Z: usize, const K: usize, const B: usize>(
    scenario: &Scenario3d,
    kind: TrackerKind,
) -> Result<Box<dyn Engine>, String>
where
    G: ScenarioNetwork<D>,
{
    let (config, objects) = config3d::<G, D, B>(scenario, kind).map_err(|e| e.to_string())?;
    let prior: Vec<PriorHypothesis<'_, f64, 6>> =
        objects.iter().map(|(weight, objects)| PriorHypothesis { weight: *weight, objects }).collect();
    let tracker = Tracker::<f64, TwoBodyJ2<f64>, G, 6, D, H, N, Z, K, B>::new(config, &prior, scenario.prior.time)
        .map_err(|e| format!("tracker configuration: {e}"))?;
    Ok(Box::new(Core { tracker: Box::new(tracker), planar: false }))
}

fn orbital_for<G, const D: usize>(
    scenario: &Scenario3d,
    kind: TrackerKind,
    profile: Profile,
) -> Result<Box<dyn Engine>, String>
where
    G: ScenarioNetwork<D>,
{
    with_capacities!(profile, ORBITAL, orbital, [G, D], (scenario, kind))
}

/// The 3-D tracker `kind` of a version 2 scenario; `profile` `None` picks it as `host-sim run` does.
///
/// # Errors
/// A one-line message when the scenario does not fit the tracker or the core refuses its configuration.
pub fn build_orbital(
    scenario: &Scenario3d,
    kind: TrackerKind,
    profile: Option<Profile>,
) -> Result<(Box<dyn Engine>, Profile), String> {
    let profile = choose_profile(scenario, profile);
    let engine = with_measurement!(scenario.measurement, orbital_for, (scenario, kind, profile))?;
    Ok((engine, profile))
}
