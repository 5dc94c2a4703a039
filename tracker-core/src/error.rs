//! Errors: one small `Copy` enum per operation family.
//!
//! [`ConfigError`] is returned when a tracker is built; [`StepError`] by [`crate::Tracker::step`], after
//! which the tracker is exactly as it was before the call.

use crate::ekf::NumericalError;
use crate::sensor::PlacementError;
use crate::store::TrackLabel;

/// A configuration or prior that cannot be used.
///
/// # Examples
/// A prior object whose covariance is not positive definite is named by its position:
/// ```
/// # use nalgebra::SMatrix;
/// # use tracker_core::{Gaussian, LinearTracker};
/// # let (config, object) = (tracker_core::examples::config(), tracker_core::examples::object());
/// use tracker_core::ConfigError;
/// let flat = Gaussian { covariance: SMatrix::zeros(), ..object };
/// match LinearTracker::<f64, 8, 4, 4, 16, 1>::with_objects(config, &[object, flat], 0.0) {
///     Err(ConfigError::PriorObject { hypothesis, object }) => assert_eq!((hypothesis, object), (0, 1)),
///     other => panic!("expected a bad prior object, got {other:?}"),
/// }
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ConfigError {
    /// The motion model rejected its parameters.
    Motion(&'static str),
    /// The sensor is invalid (detection probability, clutter rate or field of view).
    Sensor(&'static str),
    /// The measurement noise covariance R is not symmetric positive definite.
    MeasurementNoise,
    /// α is not in [0, 1].
    BirthProbability,
    /// A birth cell's Gaussian is not finite with a symmetric positive definite covariance.
    BirthCell {
        /// The cell.
        cell: usize,
    },
    /// β is not in [0, 1].
    DeathProbability,
    /// M_b α + N β ≥ 1, so "no event" would have no probability (N is the object capacity).
    EventProbabilities,
    /// Independent births ([`BirthEvents::Independent`](crate::BirthEvents)) with births allowed to go
    /// undetected: every cell would need an undetected-birth child of its own.
    IndependentBirthsUndetected,
    /// The settings of measurement-driven births are invalid (the reason).
    MeasuredBirths(&'static str),
    /// The gate is not finite and positive.
    Gate,
    /// The child budget is zero.
    ChildBudget,
    /// A work parameter is above the limit that keeps one scan's work bounded
    /// ([`crate::config::ChildGeneration::MAX_CHILDREN_PER_SCAN`],
    /// [`crate::sampler::SamplerConfig::MAX_CHAIN_STEPS`],
    /// [`crate::sampler::SamplerConfig::MAX_EXHAUSTIVE_LIMIT`]).
    AboveLimit {
        /// The parameter.
        parameter: &'static str,
        /// Its largest accepted value.
        limit: u64,
    },
    /// The prior has no hypothesis.
    PriorEmpty,
    /// The prior has more hypotheses than the capacity `H`.
    PriorTooManyHypotheses,
    /// A prior weight is negative or not finite.
    PriorWeight {
        /// The hypothesis.
        hypothesis: usize,
    },
    /// The prior weights sum to zero, or their sum overflows.
    PriorWeightTotal,
    /// A prior hypothesis has more objects than the capacity `N`.
    PriorTooManyObjects {
        /// The hypothesis.
        hypothesis: usize,
    },
    /// A prior object is not finite or its covariance not symmetric positive definite.
    PriorObject {
        /// The hypothesis.
        hypothesis: usize,
        /// The object's position in it.
        object: usize,
    },
    /// A label appears twice in one prior hypothesis.
    PriorDuplicateLabel {
        /// The hypothesis.
        hypothesis: usize,
    },
    /// The prior's distinct tracks exceed the track store capacity `K`.
    PriorTrackStoreFull,
    /// The prior's time is not finite.
    PriorTime,
    /// Every birth cell's innovation covariance must factor; this one did not.
    BirthInnovation {
        /// The cell.
        cell: usize,
    },
}

impl core::fmt::Display for ConfigError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            ConfigError::Motion(why) | ConfigError::Sensor(why) => f.write_str(why),
            ConfigError::MeasurementNoise => {
                f.write_str("measurement noise covariance R is not symmetric positive definite")
            }
            ConfigError::BirthProbability => f.write_str("birth probability alpha must be in [0, 1]"),
            ConfigError::BirthCell { cell } => write!(
                f,
                "birth cell {cell}: mean and covariance must be finite, covariance symmetric positive definite"
            ),
            ConfigError::DeathProbability => f.write_str("death probability beta must be in [0, 1]"),
            ConfigError::EventProbabilities => f.write_str(
                "M_b alpha + N beta must be < 1 (N = object capacity; independent births: alpha < 1 and N beta < 1)",
            ),
            ConfigError::MeasuredBirths(reason) => f.write_str(reason),
            ConfigError::IndependentBirthsUndetected => {
                f.write_str("independent births must be detected (birth detection AllDetected)")
            }
            ConfigError::Gate => f.write_str("gate must be finite and > 0"),
            ConfigError::ChildBudget => f.write_str("child budget must be > 0"),
            ConfigError::AboveLimit { parameter, limit } => write!(f, "{parameter} must be at most {limit}"),
            ConfigError::PriorEmpty => f.write_str("prior has no hypothesis"),
            ConfigError::PriorTooManyHypotheses => f.write_str("prior has more hypotheses than the capacity H"),
            ConfigError::PriorWeight { hypothesis } => {
                write!(f, "prior hypothesis {hypothesis}: weight must be finite and >= 0")
            }
            ConfigError::PriorWeightTotal => {
                f.write_str("prior weights must not all be zero, and their sum must be finite")
            }
            ConfigError::PriorTooManyObjects { hypothesis } => {
                write!(f, "prior hypothesis {hypothesis}: more objects than the capacity N")
            }
            ConfigError::PriorObject { hypothesis, object } => {
                write!(
                    f,
                    "prior hypothesis {hypothesis}, object {object}: mean and covariance must be finite, covariance symmetric positive definite"
                )
            }
            ConfigError::PriorDuplicateLabel { hypothesis } => {
                write!(f, "prior hypothesis {hypothesis}: a label appears twice")
            }
            ConfigError::PriorTrackStoreFull => {
                f.write_str("prior needs more distinct tracks than the store capacity K")
            }
            ConfigError::PriorTime => f.write_str("prior time must be finite"),
            ConfigError::BirthInnovation { cell } => {
                write!(f, "birth cell {cell}: innovation covariance is not positive definite")
            }
        }
    }
}

impl core::error::Error for ConfigError {}

/// Why a scan was rejected. The tracker is unchanged after any of these.
///
/// # Examples
/// ```
/// # use nalgebra::SVector;
/// # use tracker_core::LinearTracker;
/// # let (config, object) = (tracker_core::examples::config(), tracker_core::examples::object());
/// use tracker_core::StepError;
/// let mut tracker = LinearTracker::<f64, 8, 4, 4, 16, 1>::with_objects(config, &[object], 0.0)?;
/// let scan = [SVector::from([1.0, 0.0]); 5]; // the tracker holds Z = 4 measurements per scan
/// match tracker.step(1.0, &scan) {
///     Err(StepError::TooManyMeasurements { received, capacity }) => assert_eq!((received, capacity), (5, 4)),
///     other => panic!("expected too many measurements, got {other:?}"),
/// }
/// let error = tracker.step(1.0, &[SVector::from([f64::NAN, 0.0])]).unwrap_err();
/// assert_eq!(error, StepError::NonFiniteMeasurement { index: 0 });
/// assert_eq!(error.to_string(), "measurement 0 is not finite");
/// assert_eq!(tracker.scans(), 0); // nothing was processed
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum StepError {
    /// More measurements than the capacity `Z`.
    TooManyMeasurements {
        /// Measurements given.
        received: usize,
        /// The capacity Z.
        capacity: usize,
    },
    /// A measurement has a NaN or infinite component.
    NonFiniteMeasurement {
        /// Its index in the scan.
        index: usize,
    },
    /// A measurement lies outside the sensor's field of view, where neither clutter nor a detectable
    /// object can produce it.
    MeasurementOutsideFieldOfView {
        /// Its index in the scan.
        index: usize,
    },
    /// A measurement is not of the kind of the scan's sensor: in a network of mixed kinds, a component
    /// beyond the kind's dimension is not zero.
    MeasurementOfWrongKind {
        /// Its index in the scan.
        index: usize,
    },
    /// The scan time is NaN or infinite.
    NonFiniteTime,
    /// The scan time is not after the previous scan (or the prior).
    TimeNotAfterLastScan,
    /// An EKF operation failed for a track.
    Numerical {
        /// The object's label.
        label: TrackLabel,
        /// What failed.
        error: NumericalError,
    },
    /// Exhaustive enumeration reached its budget of children per scan.
    ChildBudgetExceeded {
        /// The budget.
        budget: u64,
    },
    /// The kept children need more distinct tracks than the store holds (with
    /// [`crate::StoreOverflow::Error`]).
    TrackStoreFull {
        /// The capacity K.
        capacity: usize,
    },
    /// Every child has zero weight: the scan cannot be explained by the model (for example p_D = 1
    /// and an object in the field of view with no measurement it could have produced).
    NoViableChild,
    /// 2³² labels have been handed out.
    LabelsExhausted,
    /// The tracker was made with [`crate::Tracker::empty`] and has no prior yet: call
    /// [`crate::Tracker::reset`].
    NotInitialised,
    /// The scan is further after the last one than the motion model can predict
    /// ([`crate::MotionModel::max_time_step`]).
    TimeStepTooLong {
        /// The longest step, in whole seconds.
        limit_seconds: u64,
    },
    /// The scan's sensor or observer cannot be placed (an unknown sensor, a missing, unexpected,
    /// non-finite or underground observer).
    Placement(PlacementError),
    /// A birth cell's innovation cannot be formed for the sensor of this scan.
    BirthCell {
        /// The cell's index.
        cell: usize,
    },
}

impl core::fmt::Display for StepError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            StepError::TooManyMeasurements { received, capacity } => {
                write!(f, "{received} measurements exceed the capacity of {capacity}")
            }
            StepError::NonFiniteMeasurement { index } => write!(f, "measurement {index} is not finite"),
            StepError::MeasurementOutsideFieldOfView { index } => {
                write!(f, "measurement {index} is outside the field of view")
            }
            StepError::MeasurementOfWrongKind { index } => {
                write!(
                    f,
                    "measurement {index} is not of the kind of the scan's sensor (a component beyond its dimension is not 0)"
                )
            }
            StepError::NonFiniteTime => f.write_str("scan time is not finite"),
            StepError::TimeNotAfterLastScan => f.write_str("scan time is not after the previous scan"),
            StepError::Numerical { label, error } => write!(f, "track {label}: {error}"),
            StepError::ChildBudgetExceeded { budget } => write!(f, "more than {budget} children in one scan"),
            StepError::TrackStoreFull { capacity } => write!(f, "kept children need more than {capacity} tracks"),
            StepError::NoViableChild => f.write_str("every child has zero weight"),
            StepError::LabelsExhausted => f.write_str("track labels exhausted"),
            StepError::NotInitialised => f.write_str("no prior loaded: call reset first"),
            StepError::TimeStepTooLong { limit_seconds } => {
                write!(f, "scan is more than {limit_seconds} s after the last one, beyond the motion model's bound")
            }
            StepError::Placement(error) => write!(f, "scan geometry: {error}"),
            StepError::BirthCell { cell } => write!(f, "birth cell {cell}: no innovation for this scan's sensor"),
        }
    }
}

impl core::error::Error for StepError {}
