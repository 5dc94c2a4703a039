//! Tracker configuration: models, sensor, birth/death model, child generation and overflow policy.
//!
//! Every field is checked when a tracker is built ([`crate::Tracker::new`]); a bad value is a
//! [`crate::ConfigError`], never a later surprise.

use crate::gaussian::Gaussian;
use crate::real::Real;
use crate::sensor::{Placement, Sensor};

/// Whether a born object may go undetected in the scan it is born (docs/maths.md §5.2, [000] (34)–(43)).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum BirthDetection {
    /// Paper 000's "all births detected" heuristic: a birth child must assign a measurement to the born
    /// object. **The default.** Every child with an undetected birth weighs at most (1 − p_D) α / P(no
    /// event) of its companion without that birth ([000] (39)), and its track would carry only the broad
    /// birth pdf; dropping those children keeps H∞ for hypotheses that explain measurements. The mass
    /// discarded per scan, relative to the kept children, is about M_b α (1 − p_D) / P(no event) (docs/maths.md §5.2).
    #[default]
    AllDetected,
    /// The exact first-order model: a born object is detected with p_D like any other, so undetected
    /// births are children too.
    AllowUndetected,
}

/// How many objects a scan may bring, and with what probability (docs/maths.md §5.1, §5.6).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum BirthEvents {
    /// R-FISST's first-order model ([003] §II-C): at most one birth or one death per scan, P(birth in a
    /// cell) = α, P(no event) = 1 − M_b α − M_d β. **The default.**
    #[default]
    FirstOrder,
    /// Each cell gives birth independently with probability α, so a scan may bring as many objects as it
    /// has measurements (a launch, a break-up); at most one death per scan, P(no death) = 1 − M_d β. Every
    /// cell is a column of every parent's matrix that a measurement may take (docs/maths.md §5.6). Births
    /// must be detected ([`BirthDetection::AllDetected`]).
    Independent,
}

/// The birth model: cells with a Gaussian birth pdf each, α per cell and scan, and how births combine
/// ([`BirthEvents`]; by default R-FISST's first-order model, at most one birth per scan, [003] §II-C;
/// docs/maths.md §5.1).
///
/// # Examples
/// One birth cell around (30, 30): a measurement there that no object explains becomes a new object.
/// ```
/// # use nalgebra::{SMatrix, SVector};
/// # use tracker_core::{BirthModel, Config, Gaussian, LinearTracker};
/// # let (config, object) = (tracker_core::examples::config(), tracker_core::examples::object());
/// use tracker_core::{BirthDetection, TrackLabel};
/// let cell = Gaussian { mean: SVector::from([30.0, 30.0, 0.0, 0.0]), covariance: SMatrix::identity() * 25.0 };
/// let mut cells = heapless::Vec::new();
/// cells.push(cell).unwrap();
/// let birth = BirthModel { probability: 0.05, cells, detection: BirthDetection::AllDetected, events: Default::default(), measured: None };
/// let config = Config { birth, ..config };
/// let mut tracker = LinearTracker::<f64, 8, 4, 4, 16, 1>::with_objects(config, &[object], 0.0)?;
/// tracker.step(1.0, &[SVector::from([1.0, 0.0]), SVector::from([31.0, 29.0])])?;
/// let map = tracker.map_hypothesis();
/// assert_eq!(map.len(), 2);
/// assert!(map.tracks().any(|t| t.label == TrackLabel(1) && (t.state.mean[0] - 31.0).abs() < 1.0));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BirthModel<T: Real, const S: usize, const B: usize> {
    /// α: probability of a birth in each cell per scan.
    pub probability: T,
    /// The birth pdf of each cell (at most `B` cells; M_b = `cells.len()`).
    pub cells: heapless::Vec<Gaussian<T, S>, B>,
    /// Whether births must be detected at birth.
    pub detection: BirthDetection,
    /// At most one birth per scan, or independent births in every cell.
    #[cfg_attr(feature = "serde", serde(default))]
    pub events: BirthEvents,
    /// Birth cells made from earlier scans' unexplained measurements, besides `cells`
    /// (docs/maths.md §5.8); they need [`BirthEvents::Independent`].
    #[cfg_attr(feature = "serde", serde(default))]
    pub measured: Option<crate::pool::MeasuredBirths<T>>,
}

impl<T: Real, const S: usize, const B: usize> BirthModel<T, S, B> {
    /// No births.
    ///
    /// # Examples
    /// ```
    /// use tracker_core::BirthModel;
    /// let births = BirthModel::<f64, 4, 2>::none();
    /// assert_eq!(births.probability, 0.0);
    /// assert!(births.cells.is_empty());
    /// ```
    pub fn none() -> Self {
        Self {
            probability: T::zero(),
            cells: heapless::Vec::new(),
            detection: BirthDetection::AllDetected,
            events: BirthEvents::FirstOrder,
            measured: None,
        }
    }
}

/// How the children of each parent are produced.
///
/// # Examples
/// Exhaustive enumeration fails the scan when it needs more children than its budget; the sampler
/// finds the same best hypothesis on a small scan:
/// ```
/// # use nalgebra::SVector;
/// # use tracker_core::{Config, LinearTracker};
/// # let (config, object) = (tracker_core::examples::config(), tracker_core::examples::object());
/// use tracker_core::{ChildGeneration, StepError};
/// use tracker_core::sampler::SamplerConfig;
/// let scan = [SVector::from([1.0, 0.0]), SVector::from([-3.0, 2.0])];
///
/// let tight = Config { children: ChildGeneration::Exhaustive { max_children_per_scan: 2 }, ..config.clone() };
/// let mut tracker = LinearTracker::<f64, 8, 4, 4, 16, 1>::with_objects(tight, &[object], 0.0)?;
/// // Three children: the object takes z₁, takes z₂, or is missed.
/// assert_eq!(tracker.step(1.0, &scan), Err(StepError::ChildBudgetExceeded { budget: 2 }));
///
/// let exhaustive = Config { children: ChildGeneration::Exhaustive { max_children_per_scan: 3 }, ..config.clone() };
/// let sampled = Config { children: ChildGeneration::Sampled(SamplerConfig::DEFAULT), ..config };
/// let mut a = LinearTracker::<f64, 8, 4, 4, 16, 1>::with_objects(exhaustive, &[object], 0.0)?;
/// let mut b = LinearTracker::<f64, 8, 4, 4, 16, 1>::with_objects(sampled, &[object], 0.0)?;
/// assert_eq!(a.step(1.0, &scan)?.hypotheses, 3);
/// b.step(1.0, &scan)?;
/// assert_eq!(a.map_hypothesis().tracks().next(), b.map_hypothesis().tracks().next());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum ChildGeneration {
    /// Every child with non-zero weight (HOMHT-style), at most `max_children_per_scan` leaves of the
    /// enumeration per scan; more is [`crate::StepError::ChildBudgetExceeded`].
    Exhaustive {
        /// Bound on the enumeration's leaves per scan.
        max_children_per_scan: u64,
    },
    /// R-FISST: the Metropolis sampler with a fixed step budget per (parent, event), optionally by
    /// clusters with small clusters enumerated ([`crate::cluster`]). Every chain keeps its best H distinct
    /// children.
    Sampled(crate::sampler::SamplerConfig),
}

impl ChildGeneration {
    /// The largest accepted `max_children_per_scan` of [`ChildGeneration::Exhaustive`]: 10⁹ leaves, tens
    /// of seconds of one host core, so that no configuration makes one scan endless.
    pub const MAX_CHILDREN_PER_SCAN: u64 = 1_000_000_000;
}

impl Default for ChildGeneration {
    fn default() -> Self {
        ChildGeneration::Exhaustive { max_children_per_scan: 1_000_000 }
    }
}

/// What to do when the kept children need more distinct tracks than the track store holds.
///
/// # Examples
/// One object and two measurements give three children with three different tracks; a store of
/// K = 2 tracks cannot hold them all:
/// ```
/// # use nalgebra::SVector;
/// # use tracker_core::{Config, LinearTracker};
/// # let (config, object) = (tracker_core::examples::config(), tracker_core::examples::object());
/// use tracker_core::{StepError, StoreOverflow};
/// let scan = [SVector::from([1.0, 0.0]), SVector::from([-3.0, 2.0])];
/// let strict = Config { store_overflow: StoreOverflow::Error, ..config.clone() };
/// let mut tracker = LinearTracker::<f64, 8, 2, 4, 2, 1>::with_objects(strict, &[object], 0.0)?;
/// assert_eq!(tracker.step(1.0, &scan), Err(StepError::TrackStoreFull { capacity: 2 }));
///
/// let mut tracker = LinearTracker::<f64, 8, 2, 4, 2, 1>::with_objects(config, &[object], 0.0)?;
/// let report = tracker.step(1.0, &scan)?;
/// assert_eq!((report.hypotheses, report.children_dropped_for_store), (2, 1));
/// assert!(report.captured_mass < 1.0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum StoreOverflow {
    /// Drop the lowest-weight children that do not fit (like H∞ pruning) and report how many in
    /// [`crate::StepReport::children_dropped_for_store`]. The best child always fits (the store holds at
    /// least `N` tracks). **The default.**
    #[default]
    PruneChildren,
    /// Fail the scan with [`crate::StepError::TrackStoreFull`]; the tracker is left unchanged.
    Error,
}

/// What a scan does when the EKF fails for one track: a [`crate::NumericalError`] from its
/// prediction, its innovation or its update (a covariance the filter cannot keep positive definite, an
/// object inside the central body or lost by the integrator, a non-finite value).
///
/// With [`NumericalFailure::Error`] one such track rejects every later scan too, since it stays in
/// every hypothesis and fails again: the tracker never recovers. Hence the default.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum NumericalFailure {
    /// Drop the track: it leaves every hypothesis that holds it in this scan, before the children are
    /// generated, as if it had died with probability 1 (hypothesis weights unchanged, the other
    /// objects and their labels untouched; its label is never reused). The scan then goes on, and
    /// [`crate::report::NumericalDrops`] in the step report counts the dropped tracks and names the
    /// first. **The default.**
    #[default]
    DropTrack,
    /// Strict: the scan fails with [`crate::StepError::Numerical`] and the tracker is left unchanged.
    Error,
}

/// Track management beyond the recursion: when a track is declared *lost* and leaves every hypothesis
/// (docs/maths.md §5.9). A track is *unseen* in a scan when its predicted measurement lies in the scan's
/// field of view and no measurement of the scan lies in its gate (every entry δ of its row is −∞); a
/// scan out of view leaves its count as it is, a measurement in its gate resets it. The count belongs to
/// the track (its association history), so every hypothesis that holds the track agrees on it.
///
/// With β = 0 (objects never die) nothing else removes a track whose estimate has left its object — a
/// short-arc birth that coasted for an hour, say: it stays in every hypothesis, the object's next pass
/// starts a new label, and the old track is reported for ever.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum TrackLoss {
    /// Tracks are never declared lost: the exact recursion. **The default.**
    #[default]
    Never,
    /// A track unseen in this many consecutive scans is dropped from every hypothesis before the scan's
    /// children are generated, as a track dropped for a numerical failure is (no column, no missed
    /// factor, hypothesis weights unchanged; identical children merge), and counted in
    /// [`crate::StepReport::lost_tracks`]. Needs a gate ([`Config::gate`]): without one, only a scan
    /// with no measurement at all leaves a track in view unseen.
    AfterUnseenScans(core::num::NonZeroU16),
}

impl TrackLoss {
    /// Whether a track unseen in `unseen` consecutive scans is lost.
    ///
    /// # Examples
    /// ```
    /// use core::num::NonZeroU16;
    /// use tracker_core::TrackLoss;
    /// let rule = TrackLoss::AfterUnseenScans(NonZeroU16::new(3).unwrap());
    /// assert!(!rule.is_lost(2) && rule.is_lost(3));
    /// assert!(!TrackLoss::Never.is_lost(u16::MAX));
    /// ```
    pub fn is_lost(self, unseen: u16) -> bool {
        match self {
            TrackLoss::Never => false,
            TrackLoss::AfterUnseenScans(after) => unseen >= after.get(),
        }
    }
}

/// How the H∞ hypotheses are chosen among the children (paper 003 §III-A).
///
/// # Examples
/// Both keep the best child when H∞ is large enough to keep every child:
/// ```
/// # use nalgebra::SVector;
/// # use tracker_core::{Config, LinearTracker};
/// # let (config, object) = (tracker_core::examples::config(), tracker_core::examples::object());
/// use tracker_core::config::Selection;
/// let scan = [SVector::from([1.0, 0.0])];
/// let sampled = Config { selection: Selection::SampledByWeight, ..config.clone() };
/// let mut a = LinearTracker::<f64, 8, 4, 4, 16, 1>::with_objects(config, &[object], 0.0)?;
/// let mut b = LinearTracker::<f64, 8, 4, 4, 16, 1>::with_objects(sampled, &[object], 0.0)?;
/// a.step(1.0, &scan)?;
/// b.step(1.0, &scan)?;
/// assert_eq!(a.map_hypothesis().weight(), b.map_hypothesis().weight());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Selection {
    /// The H∞ children of largest weight. **The default.**
    #[default]
    TopWeight,
    /// H∞ children drawn without replacement with probability proportional to their weight (the
    /// Gumbel-top-k trick: the H∞ largest ln w + G, G standard Gumbel, seeded by the configuration seed
    /// and the scan index).
    SampledByWeight,
    /// The H∞ children of largest weight, less those lighter than 10^−`decades` times the heaviest
    /// (docs/maths.md §8.1): a floor on the relative weight, as GLMB implementations prune. The mass it
    /// drops is at most (H∞ − 1) · 10^−`decades` of the kept mass per scan and shows in
    /// [`crate::StepReport::captured_mass`]. A long-lived object's hypotheses otherwise fill H∞ with
    /// versions of it that missed one scan (relative weights near (1 − p_D) λ_c c(z) / (p_D g(z)), tiny for
    /// a precise radar), each a track to predict at every scan. `decades: 0` keeps only the heaviest child
    /// and its ties.
    TopWeightWithin {
        /// The floor as a power of ten below the heaviest child's weight.
        decades: u8,
    },
}

impl Selection {
    /// The natural logarithm of the floor relative to the heaviest child, −decades · ln 10; `None`
    /// without a floor.
    ///
    /// # Examples
    /// ```
    /// use tracker_core::config::Selection;
    /// assert_eq!(Selection::TopWeight.log_floor::<f64>(), None);
    /// let floor = Selection::TopWeightWithin { decades: 9 }.log_floor::<f64>().unwrap();
    /// assert!((floor.exp() - 1e-9).abs() < 1e-21);
    /// ```
    pub fn log_floor<T: Real>(self) -> Option<T> {
        match self {
            Selection::TopWeight | Selection::SampledByWeight => None,
            Selection::TopWeightWithin { decades } => Some(T::of_f64(-f64::from(decades) * core::f64::consts::LN_10)),
        }
    }
}

/// The complete configuration of a tracker.
///
/// # Examples
/// Every field is checked when a tracker is built:
/// ```
/// use nalgebra::{SMatrix, SVector};
/// use tracker_core::{BirthModel, Config, ConfigError, ConstantVelocity, Gaussian, LinearTracker, PositionMeasurement};
/// use tracker_core::{Region, Sensor};
///
/// let config = Config {
///     motion: ConstantVelocity { acceleration_noise: 0.01 },
///     measurement: PositionMeasurement::isotropic(0.5),
///     sensor: Sensor {
///         detection_probability: 0.9,
///         clutter_rate: 1.0,
///         field_of_view: Region::Rectangle { min: [-50.0, -50.0], max: [50.0, 50.0] },
///     },
///     birth: BirthModel::none(),
///     death_probability: 0.01,
///     gate: Some(25.0),
///     children: Default::default(),
///     selection: Default::default(),
///     store_overflow: Default::default(),
///     numerical_failure: Default::default(),
///     track_loss: Default::default(),
///     seed: 7,
/// };
/// let object = Gaussian { mean: SVector::from([0.0, 0.0, 1.0, 0.0]), covariance: SMatrix::identity() };
/// assert!(LinearTracker::<f64, 8, 4, 4, 16, 1>::with_objects(config.clone(), &[object], 0.0).is_ok());
///
/// let bad_gate = Config { gate: Some(-1.0), ..config };
/// let error = LinearTracker::<f64, 8, 4, 4, 16, 1>::with_objects(bad_gate, &[object], 0.0).unwrap_err();
/// assert_eq!(error, ConfigError::Gate);
/// ```
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Config<T: Real, M, G, const S: usize, const B: usize> {
    /// How objects move.
    pub motion: M,
    /// How the sensor measures an object.
    pub measurement: G,
    /// Detection, clutter and field of view. Not used (and not checked) when the measurement model's
    /// sensors carry their own ([`Placement::detection`], e.g. a [`SensorNetwork`](crate::SensorNetwork));
    /// [`Config::detection`] chooses.
    pub sensor: Sensor<T>,
    /// Births.
    pub birth: BirthModel<T, S, B>,
    /// β: probability that a given object in the field of view dies before a scan.
    pub death_probability: T,
    /// Gate on the squared Mahalanobis distance νᵀS⁻¹ν: an association beyond it is impossible.
    /// `None` disables gating (the exact recursion).
    pub gate: Option<T>,
    /// Child generation.
    pub children: ChildGeneration,
    /// How the H∞ hypotheses are chosen.
    pub selection: Selection,
    /// Track-store overflow policy.
    pub store_overflow: StoreOverflow,
    /// What a numerical failure of one track does to the scan: drop that track (the default) or fail.
    pub numerical_failure: NumericalFailure,
    /// When a track is declared lost ([`TrackLoss`]; by default never).
    #[cfg_attr(feature = "serde", serde(default))]
    pub track_loss: TrackLoss,
    /// Seed of every random choice (the Metropolis sampler); results depend only on it and the inputs.
    pub seed: u64,
}

impl<T: Real, M, G, const S: usize, const B: usize> Config<T, M, G, S, B> {
    /// The detection model of the sensor that `placed` (this configuration's measurement model placed at a
    /// scan) stands for: its own when its sensors carry one, else [`Config::sensor`].
    pub fn detection<const D: usize>(&self, placed: &G) -> Sensor<T>
    where
        G: Placement<T, D>,
    {
        placed.detection().unwrap_or(self.sensor)
    }
}

#[cfg(all(test, feature = "serde"))]
mod tests {
    use super::*;
    use crate::model::{PositionMeasurement, TwoBody};
    use crate::sensor::Region;

    #[test]
    fn configuration_round_trips_through_serde() {
        let mut cells = heapless::Vec::<Gaussian<f64, 4>, 2>::new();
        let _ = cells.push(Gaussian {
            mean: nalgebra::SVector::from([1.0, 2.0, 3.0, 4.0]),
            covariance: nalgebra::SMatrix::identity(),
        });
        let config: Config<f64, TwoBody<f64>, PositionMeasurement<f64>, 4, 2> = Config {
            motion: TwoBody {
                mu: 398_600.0,
                acceleration_noise: 1e-13,
                max_step: 20.0,
                max_substeps: 100,
                min_radius: 6378.137,
            },
            measurement: PositionMeasurement::isotropic(0.5),
            sensor: Sensor {
                detection_probability: 0.9,
                clutter_rate: 1.0,
                field_of_view: Region::Rectangle { min: [0.0, 0.0], max: [1.0, 1.0] },
            },
            birth: BirthModel {
                probability: 0.01,
                cells,
                detection: BirthDetection::AllowUndetected,
                events: Default::default(),
                measured: None,
            },
            death_probability: 0.001,
            gate: Some(25.0),
            children: ChildGeneration::Sampled(crate::sampler::SamplerConfig::default()),
            selection: Selection::SampledByWeight,
            store_overflow: StoreOverflow::Error,
            numerical_failure: Default::default(),
            track_loss: Default::default(),
            seed: 42,
        };
        let text = serde_json::to_string(&config).unwrap();
        let back: Config<f64, TwoBody<f64>, PositionMeasurement<f64>, 4, 2> = serde_json::from_str(&text).unwrap();
        assert_eq!(back, config);
    }

    #[test]
    fn numerical_failure_defaults_to_dropping_the_track_and_round_trips() {
        assert_eq!(NumericalFailure::default(), NumericalFailure::DropTrack);
        for policy in [NumericalFailure::DropTrack, NumericalFailure::Error] {
            let text = serde_json::to_string(&policy).unwrap();
            assert_eq!(serde_json::from_str::<NumericalFailure>(&text).unwrap(), policy);
        }
        let drops = crate::report::NumericalDrops {
            count: 2,
            first: Some((crate::TrackLabel(7), crate::NumericalError::Model(crate::model::ModelError::InsideBody))),
        };
        let text = serde_json::to_string(&drops).unwrap();
        assert_eq!(serde_json::from_str::<crate::report::NumericalDrops>(&text).unwrap(), drops);
    }
}
