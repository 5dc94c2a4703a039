//! The tracker: one scan of the hypothesis-level FISST recursion with birth and death (docs/maths.md §2).
//!
//! [`Tracker::step`] is a pipeline of three stages, each with its own scratch space:
//!
//! 1. [`score`]: predict every track of the shared store once (EKF), decide whether it is in the field of
//!    view, and score it against every measurement once: the entry δ of docs/maths.md §4.2 for each
//!    (track, measurement) pair, `-inf` outside the gate or the field of view. Birth cells likewise.
//! 2. [`generate`]: for each parent and each event (no event, a birth in each cell, the death of each
//!    object in the field of view), the event's association matrix and its column layout; a child
//!    generator offers every child to the scan's selection ([`TopChildren`]), which keeps the H best and
//!    the global log-sum-exp.
//! 3. [`materialise`]: only the kept children become hypotheses and tracks, reading each child's
//!    association back through its column layout; identical children merge; weights are normalised over
//!    the kept hypotheses and the mass of the rest is reported as `1 − captured_mass`.
//!
//! Then the scan is **committed**: everything above wrote into the inactive half of the double-buffered
//! store and hypotheses and into scratch space, and only a scan that succeeds swaps them in. A failed
//! `step` leaves the tracker bit-for-bit as it was.
//!
//! Around the pipeline: `prior` checks a configuration and loads a prior, [`check_scan`] and [`place_scan`]
//! check a scan and place the measurement model at it, and `view` is what a caller reads between scans
//! ([`HypothesisView`], label existence, cardinality, the digest), and `resume` reads out and loads back
//! the state a tracker carries between scans ([`TrackerState`]). The examples share one set-up, the hidden
//! `tracker_core::examples` module.
//!
//! # Panics
//! [`Tracker::new`], [`Tracker::step`] and [`Tracker::digest`] do not panic on any input in a release
//! build: capacity, finiteness and time are checked first, numerical failure is returned as
//! [`StepError::Numerical`], and every index into the fixed-size tables is proved in bounds or clamped
//! (the private `index` module), so no panic path is left. This is proved at link time: `nostd-check`'s
//! `panic_free` binary calls them on inputs the optimiser cannot see through, with a panic handler that
//! references an undefined symbol, and it links only when the optimiser removed every path to a panic
//! (`cd nostd-check && cargo build --release --bin panic_free`; see `docs/embedded.md`, "Panic-freedom").
//! The proof covers the monomorphisations that binary instantiates. Debug builds keep `debug_assert!`s on
//! internal invariants.
//!
//! [`TopChildren`]: crate::selection::TopChildren

mod generate;
mod materialise;
mod prior;
mod resume;
mod scan;
mod score;
mod view;

pub use prior::PriorSource;
pub use resume::TrackerState;
pub use scan::{PlacedScan, check_scan, place_scan};
pub use score::{in_field_of_view, unseen_scans};
pub use view::HypothesisView;

use crate::association::Column;
use crate::config::Config;
use crate::error::{ConfigError, StepError};
use crate::gaussian::Gaussian;
use crate::hypothesis::HypothesisSet;
use crate::index::{At, NONE, insertion_sort_by};
use crate::model::{MeasurementModel, MotionModel};
use crate::pool::{BirthPool, Linking, PoolUpdate, ScanUse};
use crate::random::scan_seed;
use crate::real::{LogSumExp, Real, exp};
use crate::report::StepReport;
use crate::sampler::SamplerConfig;
use crate::sensor::ScanGeometry;
use crate::store::{TrackLabel, TrackStore};
use generate::Generation;
use materialise::{Inputs, Materialisation};
use nalgebra::SVector;
use score::{BirthCells, Scores};

/// One object of a prior hypothesis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PriorObject<T: Real, const S: usize> {
    /// The object's label; the same object in several prior hypotheses carries the same label.
    pub label: TrackLabel,
    /// Its Gaussian at the prior time.
    pub state: Gaussian<T, S>,
}

/// One hypothesis of the prior: a weight (normalised over the prior by the tracker) and its objects.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PriorHypothesis<'a, T: Real, const S: usize> {
    /// Relative weight (≥ 0).
    pub weight: T,
    /// The objects.
    pub objects: &'a [PriorObject<T, S>],
}

/// The R-FISST / hypothesis-level FISST tracker with fixed capacities.
///
/// - `T`: scalar (`f32` or `f64`); `M`: [`MotionModel`]; `G`: [`MeasurementModel`].
/// - `S`, `D`: state and measurement dimensions.
/// - `H`: hypotheses kept per scan (H∞); `N`: objects per hypothesis; `Z`: measurements per scan;
///   `K`: tracks in the shared store (≥ N); `B`: birth cells.
///
/// All memory is inside the value; `step` allocates nothing. The capacities are checked at compile time.
///
/// # Examples
/// ```
/// use nalgebra::{SMatrix, SVector};
/// use tracker_core::{Config, ConstantVelocity, PositionMeasurement, Region, Sensor, Tracker, BirthModel, Gaussian};
/// use tracker_core::config::{ChildGeneration, Selection, StoreOverflow};
///
/// let config = Config {
///     motion: ConstantVelocity { acceleration_noise: 0.01 },
///     measurement: PositionMeasurement::isotropic(0.5),
///     sensor: Sensor { detection_probability: 0.9, clutter_rate: 1.0, field_of_view: Region::Rectangle { min: [-50.0, -50.0], max: [50.0, 50.0] } },
///     birth: BirthModel::none(),
///     death_probability: 0.0,
///     gate: None,
///     children: ChildGeneration::default(),
///     selection: Selection::default(),
///     store_overflow: StoreOverflow::default(),
///     numerical_failure: Default::default(),
///     track_loss: Default::default(),
///     seed: 1,
/// };
/// let object = Gaussian { mean: SVector::from([0.0, 0.0, 1.0, 0.0]), covariance: SMatrix::identity() };
/// let mut tracker: Tracker<f64, _, _, 4, 2, 8, 4, 4, 16, 1> = Tracker::with_objects(config, &[object], 0.0).unwrap();
/// let report = tracker.step(1.0, &[SVector::from([1.1, 0.05])]).unwrap();
/// assert_eq!(report.hypotheses, 2); // z from the object, or clutter and the object missed
/// assert!(tracker.map_hypothesis().weight() > 0.9);
/// ```
#[derive(Debug, Clone)]
pub struct Tracker<
    T: Real,
    M,
    G,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
> {
    config: Config<T, M, G, S, B>,
    stores: [TrackStore<T, S, K>; 2],
    hypotheses: [HypothesisSet<T, N, H>; 2],
    /// Which half of `stores` and `hypotheses` is live (`false`: index 0).
    active: bool,
    time: f64,
    scans: u64,
    next_label: u32,
    /// Whether a prior has been loaded ([`Tracker::reset`]).
    initialised: bool,
    scores: Scores<T, S, D, Z, K, B>,
    generation: Generation<T, H, N, Z>,
    materialisation: Materialisation<H, N, Z, K, B>,
    /// Birth cells made from measurements (docs/maths.md §5.8).
    pool: BirthPool<T, S, B>,
    /// The scan's birth cells as its sensor sees them (scratch, kept here rather than on the stack).
    birth_cells: BirthCells<T, S, D, B>,
}

impl<
    T,
    M,
    G,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
> Tracker<T, M, G, S, D, H, N, Z, K, B>
where
    T: Real,
    M: MotionModel<T, S>,
    G: MeasurementModel<T, S, D>,
{
    const CAPACITY_CHECK: () = {
        assert!(S > 0 && D > 0, "state and measurement dimensions must be > 0");
        assert!(H > 0 && N > 0 && Z > 0, "capacities H, N and Z must be > 0");
        assert!(K >= N, "the track store must hold at least N tracks so that the best child always fits");
        assert!(
            H < u16::MAX as usize
                && N < u16::MAX as usize
                && Z < u16::MAX as usize
                && K < u16::MAX as usize
                && B < u16::MAX as usize,
            "capacities must fit in u16"
        );
    };

    /// Builds a tracker from a configuration, a prior (one or more weighted hypotheses) and the prior's
    /// time in seconds.
    ///
    /// The tracker is returned by value, which can take a few times its size of stack; on a small target
    /// put it in a `static` with [`Tracker::empty`] and load it with [`Tracker::reset`] instead (or with
    /// [`Tracker::reset_with`] when the configuration can only be built at run time).
    ///
    /// # Errors
    /// [`ConfigError`] naming the first invalid parameter or prior entry.
    ///
    /// # Examples
    /// A prior of two hypotheses: object 7 exists with probability 3/4.
    /// ```
    /// # use tracker_core::LinearTracker;
    /// # let (config, object) = (tracker_core::examples::config(), tracker_core::examples::object());
    /// use tracker_core::{ConfigError, PriorHypothesis, PriorObject, TrackLabel};
    ///
    /// let objects = [PriorObject { label: TrackLabel(7), state: object }];
    /// let prior = [PriorHypothesis { weight: 3.0, objects: &objects }, PriorHypothesis { weight: 1.0, objects: &[] }];
    /// let tracker = LinearTracker::<f64, 8, 4, 4, 16, 1>::new(config.clone(), &prior, 0.0)?;
    /// assert!((tracker.label_existence(TrackLabel(7)) - 0.75).abs() < 1e-12);
    ///
    /// // Weights must not all be zero.
    /// let zero = [PriorHypothesis { weight: 0.0, objects: &objects }];
    /// let error = LinearTracker::<f64, 8, 4, 4, 16, 1>::new(config, &zero, 0.0).unwrap_err();
    /// assert_eq!(error, ConfigError::PriorWeightTotal);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn new(
        config: Config<T, M, G, S, B>,
        prior: &[PriorHypothesis<'_, T, S>],
        time: f64,
    ) -> Result<Self, ConfigError> {
        let mut tracker = Self::empty(config);
        tracker.reset(prior, time)?;
        Ok(tracker)
    }

    /// A tracker holding `config` but no prior yet, built in a `const` context so that it can be the
    /// initial value of a `static` (no stack is used for its storage).
    ///
    /// The configuration is checked, and the prior loaded, by [`Tracker::reset`]; until then `step` fails
    /// with [`StepError::NotInitialised`].
    ///
    /// # Examples
    /// A tracker in a `static` behind a mutex (on a bare-metal target, a critical-section mutex such as
    /// `Mutex<RefCell<SsaTracker<f32>>>` in place of std's); the configuration is a `const`:
    /// ```
    /// use std::sync::Mutex;
    /// use tracker_core::{BirthDetection, BirthModel, Config, ConstantVelocity, Gaussian, LinearConfig, LinearTracker};
    /// use tracker_core::{ConfigError, PositionMeasurement, PriorHypothesis, PriorObject, Region, Sensor, StepError};
    /// use tracker_core::{BirthEvents, TrackLabel, real::identity};
    /// use tracker_core::config::{ChildGeneration, Selection, StoreOverflow};
    ///
    /// const CONFIG: LinearConfig<f64, 1> = Config {
    ///     motion: ConstantVelocity { acceleration_noise: 0.01 },
    ///     measurement: PositionMeasurement { noise: identity() },
    ///     sensor: Sensor {
    ///         detection_probability: 0.9,
    ///         clutter_rate: 1.0,
    ///         field_of_view: Region::Everywhere { volume: 1e4 },
    ///     },
    ///     birth: BirthModel {
    ///         probability: 0.0,
    ///         cells: heapless::Vec::new(),
    ///         detection: BirthDetection::AllDetected,
    ///         events: BirthEvents::FirstOrder,
    ///         measured: None,
    ///     },
    ///     death_probability: 0.0,
    ///     gate: None,
    ///     children: ChildGeneration::Exhaustive { max_children_per_scan: 10_000 },
    ///     selection: Selection::TopWeight,
    ///     store_overflow: StoreOverflow::PruneChildren,
    ///     numerical_failure: tracker_core::NumericalFailure::DropTrack,
    ///     track_loss: tracker_core::TrackLoss::Never,
    ///     seed: 1,
    /// };
    /// static TRACKER: Mutex<LinearTracker<f64, 8, 4, 4, 16, 1>> = Mutex::new(LinearTracker::empty(CONFIG));
    ///
    /// let mut tracker = TRACKER.lock().unwrap();
    /// assert_eq!(tracker.step(1.0, &[]), Err(StepError::NotInitialised));
    /// assert_eq!(tracker.reset(&[], 0.0), Err(ConfigError::PriorEmpty));
    /// let object = Gaussian { mean: nalgebra::SVector::from([0.0, 0.0, 1.0, 0.0]), covariance: identity() };
    /// let objects = [PriorObject { label: TrackLabel(0), state: object }];
    /// tracker.reset(&[PriorHypothesis { weight: 1.0, objects: &objects }], 0.0)?;
    /// assert_eq!(tracker.step(1.0, &[])?.scan, 1);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub const fn empty(config: Config<T, M, G, S, B>) -> Self {
        #[allow(clippy::let_unit_value)]
        let () = Self::CAPACITY_CHECK;
        let sampler = match config.children {
            crate::config::ChildGeneration::Sampled(sampler) => sampler,
            crate::config::ChildGeneration::Exhaustive { .. } => SamplerConfig::DEFAULT,
        };
        Self {
            config,
            stores: [TrackStore::new(), TrackStore::new()],
            hypotheses: [HypothesisSet::new(), HypothesisSet::new()],
            active: false,
            time: 0.0,
            scans: 0,
            next_label: 0,
            initialised: false,
            scores: Scores::new(),
            generation: Generation::new(sampler),
            materialisation: Materialisation::new(),
            pool: BirthPool::new(),
            birth_cells: BirthCells::EMPTY,
        }
    }

    /// Checks the configuration and loads `prior` at `time` (seconds), in place: the tracker restarts
    /// from this prior with no scan processed.
    ///
    /// # Errors
    /// [`ConfigError`] naming the first invalid parameter or prior entry; the tracker is then unchanged.
    ///
    /// # Examples
    /// ```
    /// # use nalgebra::SVector;
    /// # use tracker_core::LinearTracker;
    /// # let (config, object) = (tracker_core::examples::config(), tracker_core::examples::object());
    /// # use tracker_core::{PriorHypothesis, ConfigError};
    /// let mut tracker = LinearTracker::<f64, 8, 4, 4, 16, 1>::with_objects(config, &[object], 0.0)?;
    /// tracker.step(1.0, &[SVector::from([1.0, 0.0])])?;
    /// // Restart at t = 10 s with no object.
    /// tracker.reset(&[PriorHypothesis { weight: 1.0, objects: &[] }], 10.0)?;
    /// assert_eq!((tracker.scans(), tracker.time()), (0, 10.0));
    /// assert_eq!(tracker.expected_cardinality(), 0.0);
    /// // A bad prior leaves the tracker as it was.
    /// let before = tracker.digest();
    /// assert_eq!(tracker.reset(&[], 20.0), Err(ConfigError::PriorEmpty));
    /// assert_eq!(tracker.digest(), before);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn reset(&mut self, prior: &[PriorHypothesis<'_, T, S>], time: f64) -> Result<(), ConfigError> {
        self.reset_from(prior, time)
    }

    /// As [`Tracker::reset`], with `config` installed in place of the current configuration: a tracker
    /// that is a compile-time `static` ([`Tracker::empty`] of a `const` placeholder, such as a sensor
    /// network's `unconfigured()`) takes a configuration built at run time (clutter volumes, the Earth
    /// rotation angle) without ever passing through the stack. `config` is checked exactly as
    /// [`Tracker::new`] checks it.
    ///
    /// # Errors
    /// [`ConfigError`] naming the first invalid parameter or prior entry; the tracker, its configuration
    /// included, is then unchanged.
    ///
    /// # Examples
    /// ```
    /// # use nalgebra::SVector;
    /// # use tracker_core::LinearTracker;
    /// # let (config, object) = (tracker_core::examples::config(), tracker_core::examples::object());
    /// # use tracker_core::{ConfigError, PriorHypothesis, PriorObject, TrackLabel};
    /// let objects = [PriorObject { label: TrackLabel(0), state: object }];
    /// let prior = [PriorHypothesis { weight: 1.0, objects: &objects }];
    /// let mut tracker = LinearTracker::<f64, 8, 4, 4, 16, 1>::new(config.clone(), &prior, 0.0)?;
    /// // A bad configuration leaves the tracker as it was.
    /// let before = tracker.digest();
    /// let bad = tracker_core::LinearConfig { death_probability: 2.0, ..config.clone() };
    /// assert_eq!(tracker.reset_with(bad, &prior, 5.0), Err(ConfigError::DeathProbability));
    /// assert_eq!((tracker.digest(), tracker.time()), (before, 0.0));
    /// // A good one is the tracker `new` builds.
    /// let other = tracker_core::LinearConfig { seed: 9, ..config.clone() };
    /// tracker.reset_with(other.clone(), &prior, 5.0)?;
    /// let fresh = LinearTracker::<f64, 8, 4, 4, 16, 1>::new(other, &prior, 5.0)?;
    /// assert_eq!(tracker.digest(), fresh.digest());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn reset_with(
        &mut self,
        config: Config<T, M, G, S, B>,
        prior: &[PriorHypothesis<'_, T, S>],
        time: f64,
    ) -> Result<(), ConfigError> {
        self.reset_with_from(config, prior, time)
    }

    /// As [`Tracker::reset`], with the prior read object by object from `prior` ([`PriorSource`]): a
    /// caller holding its prior in another form (the C interface's doubles) loads it without building a
    /// slice of [`PriorObject`]s first, which for 64 objects of a 6-state `f32` tracker is 11 KiB of stack.
    /// The tracker is the one [`Tracker::reset`] gives for the same objects.
    ///
    /// # Errors
    /// As [`Tracker::reset`]; the tracker is then unchanged.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::LinearTracker;
    /// # let (config, object) = (tracker_core::examples::config(), tracker_core::examples::object());
    /// use tracker_core::{PriorHypothesis, PriorObject, TrackLabel};
    /// let objects = [PriorObject { label: TrackLabel(7), state: object }];
    /// let prior = [PriorHypothesis { weight: 1.0, objects: &objects }];
    /// let mut tracker = LinearTracker::<f64, 8, 4, 4, 16, 1>::new(config.clone(), &prior, 0.0)?;
    /// let before = tracker.digest();
    /// tracker.reset_from(&prior[..], 0.0)?;
    /// assert_eq!(tracker.digest(), before);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn reset_from<P: PriorSource<T, S> + ?Sized>(&mut self, prior: &P, time: f64) -> Result<(), ConfigError> {
        prior::check_config::<T, M, G, S, D, N, B>(&self.config)?;
        let next_label = self.load_prior(prior, time)?;
        self.commit_prior(next_label, time);
        Ok(())
    }

    /// As [`Tracker::reset_with`], with the prior read from `prior` as [`Tracker::reset_from`] reads it.
    ///
    /// # Errors
    /// As [`Tracker::reset_with`]; the tracker, its configuration included, is then unchanged.
    pub fn reset_with_from<P: PriorSource<T, S> + ?Sized>(
        &mut self,
        config: Config<T, M, G, S, B>,
        prior: &P,
        time: f64,
    ) -> Result<(), ConfigError> {
        prior::check_config::<T, M, G, S, D, N, B>(&config)?;
        let next_label = self.load_prior(prior, time)?;
        self.config = config;
        self.commit_prior(next_label, time);
        Ok(())
    }

    /// Checks `time` and writes `prior` into the inactive buffers (the live ones are untouched); returns
    /// the next free label.
    fn load_prior<P: PriorSource<T, S> + ?Sized>(&mut self, prior: &P, time: f64) -> Result<u32, ConfigError> {
        if !time.is_finite() {
            return Err(ConfigError::PriorTime);
        }
        let inactive = usize::from(!self.active);
        prior::load_prior(prior, self.stores.at_mut(inactive), self.hypotheses.at_mut(inactive))
    }

    /// Swaps in the prior [`Tracker::load_prior`] wrote and restarts the scan count at `time`.
    fn commit_prior(&mut self, next_label: u32, time: f64) {
        self.active = !self.active;
        self.time = time;
        self.scans = 0;
        self.next_label = next_label;
        self.initialised = true;
        self.pool.clear();
        self.generation.reset(self.config.children);
    }

    /// Builds a tracker whose prior is one hypothesis (weight 1) holding `objects`, labelled 0, 1, ...
    ///
    /// # Errors
    /// As [`Tracker::new`].
    ///
    /// # Examples
    /// ```
    /// # use nalgebra::{SMatrix, SVector};
    /// # use tracker_core::{Gaussian, LinearTracker};
    /// # let (config, object) = (tracker_core::examples::config(), tracker_core::examples::object());
    /// # use tracker_core::{ConfigError, TrackLabel};
    /// let other = Gaussian { mean: SVector::from([10.0, 0.0, 0.0, 1.0]), covariance: SMatrix::identity() };
    /// let tracker = LinearTracker::<f64, 8, 4, 4, 16, 1>::with_objects(config.clone(), &[object, other], 0.0)?;
    /// let labels: Vec<TrackLabel> = tracker.map_hypothesis().tracks().map(|t| t.label).collect();
    /// assert_eq!(labels, [TrackLabel(0), TrackLabel(1)]);
    ///
    /// // Five objects do not fit N = 4.
    /// let too_many = LinearTracker::<f64, 8, 4, 4, 16, 1>::with_objects(config, &[object; 5], 0.0);
    /// assert_eq!(too_many.unwrap_err(), ConfigError::PriorTooManyObjects { hypothesis: 0 });
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn with_objects(
        config: Config<T, M, G, S, B>,
        objects: &[Gaussian<T, S>],
        time: f64,
    ) -> Result<Self, ConfigError> {
        let mut prior: heapless::Vec<PriorObject<T, S>, N> = heapless::Vec::new();
        for (index, state) in objects.iter().enumerate() {
            prior
                .push(PriorObject { label: TrackLabel(index as u32), state: *state })
                .map_err(|_| ConfigError::PriorTooManyObjects { hypothesis: 0 })?;
        }
        Self::new(config, &[PriorHypothesis { weight: T::one(), objects: &prior }], time)
    }

    /// Processes one scan taken at `time` (seconds, after the previous scan) with `measurements`.
    ///
    /// # Errors
    /// [`StepError`]; the tracker is then exactly as it was before the call.
    ///
    /// # Examples
    /// ```
    /// # use nalgebra::SVector;
    /// # use tracker_core::LinearTracker;
    /// # let (config, object) = (tracker_core::examples::config(), tracker_core::examples::object());
    /// # use tracker_core::StepError;
    /// let mut tracker = LinearTracker::<f64, 8, 4, 4, 16, 1>::with_objects(config, &[object], 0.0)?;
    /// let report = tracker.step(1.0, &[SVector::from([1.1, 0.05])])?;
    /// assert_eq!((report.scan, report.measurements), (1, 1));
    /// // The object's track moved to the measurement.
    /// let track = tracker.map_hypothesis().tracks().next().unwrap();
    /// assert!((track.state.mean[0] - 1.1).abs() < 0.1);
    ///
    /// // A rejected scan changes nothing.
    /// let before = tracker.digest();
    /// match tracker.step(2.0, &[SVector::from([80.0, 0.0])]) {
    ///     Err(StepError::MeasurementOutsideFieldOfView { index }) => assert_eq!(index, 0),
    ///     other => panic!("unexpected {other:?}"),
    /// }
    /// assert_eq!(tracker.step(0.5, &[]), Err(StepError::TimeNotAfterLastScan));
    /// assert_eq!(tracker.digest(), before);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn step(&mut self, time: f64, measurements: &[SVector<T, D>]) -> Result<StepReport<T>, StepError>
    where
        G: Clone,
    {
        self.step_with_budget(time, measurements, u64::MAX)
    }

    /// As [`Tracker::step`], making at most `max_moves` Metropolis moves in the scan (sampled children):
    /// each parent gets ⌊`max_moves` · w⌋ moves for its weight w, shared among its events in turn, and each
    /// chain runs at most its share ([`SamplerConfig::moves_within`]). The report's `sampler_steps` says
    /// how many were made, never more than `max_moves`. The rest of a scan's work does not depend on the
    /// budget: per chain, the tables and the exact start (O(Z N²)), and the enumeration of small clusters
    /// (at most `exhaustive_limit` leaves each); see `docs/performance.md` for instructions per scan as a
    /// function of the budget. `u64::MAX` is [`Tracker::step`]; exhaustive generation ignores the budget.
    ///
    /// # Errors
    /// As [`Tracker::step`].
    ///
    /// # Examples
    /// ```
    /// use nalgebra::{SMatrix, SVector};
    /// use tracker_core::config::{ChildGeneration, Selection, StoreOverflow};
    /// use tracker_core::sampler::SamplerConfig;
    /// use tracker_core::{BirthModel, Config, ConstantVelocity, Gaussian, PositionMeasurement, Region, Sensor, Tracker};
    /// let config = Config {
    ///     motion: ConstantVelocity { acceleration_noise: 0.01 },
    ///     measurement: PositionMeasurement::isotropic(0.5),
    ///     sensor: Sensor { detection_probability: 0.9, clutter_rate: 1.0, field_of_view: Region::Everywhere { volume: 1e4 } },
    ///     birth: BirthModel::none(),
    ///     death_probability: 0.01,
    ///     gate: None,
    ///     children: ChildGeneration::Sampled(SamplerConfig { exhaustive_limit: 0, ..SamplerConfig::DEFAULT }),
    ///     selection: Selection::default(),
    ///     store_overflow: StoreOverflow::default(),
    ///     numerical_failure: Default::default(),
    ///     track_loss: Default::default(),
    ///     seed: 1,
    /// };
    /// let objects = [0.0, 3.0].map(|x| Gaussian { mean: SVector::from([x, 0.0, 1.0, 0.0]), covariance: SMatrix::identity() });
    /// let mut tracker: Tracker<f64, _, _, 4, 2, 8, 4, 4, 32, 1> = Tracker::with_objects(config, &objects, 0.0).unwrap();
    /// let report = tracker.step_with_budget(1.0, &[SVector::from([1.0, 0.0]), SVector::from([4.0, 0.0])], 500).unwrap();
    /// assert!(report.sampler_steps <= 500);
    /// assert_eq!(tracker.map_hypothesis().len(), 2);
    /// ```
    pub fn step_with_budget(
        &mut self,
        time: f64,
        measurements: &[SVector<T, D>],
        max_moves: u64,
    ) -> Result<StepReport<T>, StepError>
    where
        G: Clone,
    {
        self.step_scan_with_budget(&ScanGeometry::single(time), measurements, max_moves)
    }

    /// As [`Tracker::step`] for a scan of the sensor `geometry` names, at `geometry.time`, seen from its
    /// observer: the measurement model is placed at the scan ([`Placement::place`](crate::Placement::place)) before anything
    /// else, and every innovation, field-of-view test and weight of the scan uses it.
    ///
    /// # Errors
    /// As [`Tracker::step`], and [`StepError::Placement`] for an unknown sensor or a missing, unexpected,
    /// non-finite or underground observer.
    pub fn step_scan(
        &mut self,
        geometry: &ScanGeometry<T>,
        measurements: &[SVector<T, D>],
    ) -> Result<StepReport<T>, StepError>
    where
        G: Clone,
    {
        self.step_scan_with_budget(geometry, measurements, u64::MAX)
    }

    /// [`Tracker::step_scan`] with at most `max_moves` Metropolis moves ([`Tracker::step_with_budget`]).
    ///
    /// # Errors
    /// As [`Tracker::step_scan`].
    pub fn step_scan_with_budget(
        &mut self,
        geometry: &ScanGeometry<T>,
        measurements: &[SVector<T, D>],
        max_moves: u64,
    ) -> Result<StepReport<T>, StepError>
    where
        G: Clone,
    {
        if !self.initialised {
            return Err(StepError::NotInitialised);
        }
        let time = geometry.time;
        let mut placed = place_scan(&self.config, geometry, self.time, measurements, Z)?;
        score::birth_cells(&self.config, &self.pool, &mut placed, time, &mut self.birth_cells)?;
        let birth_cells = &self.birth_cells;
        let live = self.live();
        let dt = T::of_f64(time - self.time);
        let (store, next_store) = split_pair(&mut self.stores, self.active);
        let (parents, next_set) = split_pair(&mut self.hypotheses, self.active);

        let (numerical_drops, lost_tracks) =
            self.scores.run(&self.config, &placed, birth_cells, store.as_slice(), dt, measurements)?;
        let generated = self.generation.run(
            &self.config,
            &placed.weights,
            birth_cells,
            &self.scores,
            parents.as_slice(),
            measurements.len(),
            scan_seed(self.config.seed, self.scans + 1),
            max_moves,
        )?;
        let inputs = Inputs {
            config: &self.config,
            model: &placed.model,
            birth_cells,
            scores: &self.scores,
            generation: &self.generation,
            store,
            parents,
            measurements,
        };
        let outcome = self.materialisation.run(&inputs, next_store, next_set, self.next_label)?;

        // Commit.
        self.active = !self.active;
        debug_assert_ne!(live, self.live());
        self.time = time;
        self.scans += 1;
        self.next_label = outcome.next_label;
        let birth_pool = match &self.config.birth.measured {
            Some(measured) => {
                self.pool.adopt_labels(self.materialisation.candidate_labels());
                let (unexplained, born) =
                    measurement_use::<T, S, D, H, N, Z, B>(&self.generation, birth_cells, measurements.len());
                let capacity = B.saturating_sub(self.config.birth.cells.len());
                let rows = measurements.len().min(Z);
                let scan = ScanUse {
                    time,
                    sensor: geometry.sensor,
                    measurements,
                    unexplained: &unexplained[..rows],
                    born: &born,
                    detection: &pool_detection(birth_cells, placed.detection.detection_probability),
                    labels: &self.materialisation.birth_labels_of_rows()[..rows],
                };
                let linking = Linking {
                    motion: &self.config.motion,
                    field_of_view: &placed.detection.field_of_view,
                    weights: &placed.weights,
                    detection_probability: placed.detection.detection_probability,
                };
                self.pool.update(measured, capacity, &placed.model, &linking, &scan)
            }
            None => PoolUpdate::default(),
        };
        let top = &self.generation.top;
        Ok(StepReport {
            scan: self.scans,
            measurements: measurements.len(),
            hypotheses: self.hypotheses[self.live()].len(),
            tracks: self.stores[self.live()].len(),
            children: top.offered(),
            // The kept sum is part of the total: a ratio above 1 is rounding.
            captured_mass: exp(outcome.kept_total.log_ratio(top.total())).min(T::one()),
            merged_children: outcome.merged,
            children_dropped_for_store: outcome.dropped_for_store,
            births_beyond_object_capacity: generated.births_skipped,
            birth_pool,
            sampler_steps: generated.sampler_moves,
            numerical_drops,
            lost_tracks,
            expected_cardinality: self.expected_cardinality(),
        })
    }

    /// Index of the live half of the double buffers (0 or 1).
    fn live(&self) -> usize {
        usize::from(self.active)
    }
}

/// The live half of a double buffer and the other half, mutably.
fn split_pair<X>(pair: &mut [X; 2], active: bool) -> (&X, &mut X) {
    let [first, second] = pair;
    if active { (second, first) } else { (first, second) }
}

/// Orders hypotheses best first (stable, so ties keep their order) and sets every track's existence.
fn finish_hypotheses<T: Real, const S: usize, const N: usize, const H: usize, const K: usize>(
    set: &mut HypothesisSet<T, N, H>,
    store: &mut TrackStore<T, S, K>,
) {
    // Insertion sort: merging only raises weights of earlier entries, so few moves are needed.
    insertion_sort_by(set.as_mut_slice(), |a, b| a.log_weight > b.log_weight);
    let tracks = store.as_mut_slice();
    for track in tracks.iter_mut() {
        track.existence = T::zero();
    }
    for hypothesis in set.as_slice() {
        let weight = exp(hypothesis.log_weight);
        for &slot in hypothesis.slots() {
            if let Some(track) = tracks.get_mut(usize::from(slot)) {
                track.existence += weight;
            }
        }
    }
}

/// Per pool cell, `p_d` when the cell was in the scan's field of view (§3.1, at its predicted mean), else 0
/// (docs/maths.md §5.8).
fn pool_detection<T: Real, const S: usize, const D: usize, const B: usize>(
    birth_cells: &BirthCells<T, S, D, B>,
    p_d: T,
) -> [T; B] {
    let mut detection = [T::zero(); B];
    for cell in 0..birth_cells.count.min(B) {
        let pool_cell = birth_cells.pool_cell.get(cell).copied().unwrap_or(NONE);
        if birth_cells.in_field_of_view(cell) == Some(true)
            && let Some(slot) = detection.get_mut(usize::from(pool_cell))
        {
            *slot = p_d;
        }
    }
    detection
}

/// Per measurement, the posterior probability r_U that no object took it; per pool cell, the posterior
/// probability that it gave birth: sums over the kept children of the scan, with weights normalised over
/// them (docs/maths.md §5.8).
fn measurement_use<
    T: Real,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const B: usize,
>(
    generation: &Generation<T, H, N, Z>,
    birth_cells: &BirthCells<T, S, D, B>,
    rows: usize,
) -> ([T; Z], [T; B]) {
    let kept = generation.top.kept();
    let mut total = LogSumExp::new();
    for child in kept {
        total.add(child.log_weight);
    }
    let mut taken = [T::zero(); Z];
    let mut born = [T::zero(); B];
    for child in kept {
        let weight = exp(total.normalise(child.log_weight));
        let Some(layout) = generation.layout(child.parent, child.event, birth_cells) else { continue };
        for (row, &column) in child.assignment.iter().enumerate().take(rows.min(Z)) {
            match layout.column(usize::from(column)) {
                Some(Column::Object { .. }) => *taken.at_mut(row) += weight,
                Some(Column::Birth { cell }) => {
                    *taken.at_mut(row) += weight;
                    let pool_cell = birth_cells.pool_cell.get(usize::from(cell)).copied().unwrap_or(NONE);
                    if let Some(born) = born.get_mut(usize::from(pool_cell)) {
                        *born += weight;
                    }
                }
                None => {}
            }
        }
    }
    (taken.map(|taken| T::one() - taken), born)
}
