//! Tracker configuration: models, sensor, birth/death model, child generation and overflow policy.
//!
//! Every field is checked when a tracker is built ([`crate::Tracker::new`]); a bad value is a
//! [`crate::ConfigError`], never a later surprise.

use crate::ekf::Gaussian;
use crate::real::Real;
use crate::sensor::Sensor;

/// Whether a born object may go undetected in the scan it is born (digest §1.1, [000] (34)–(43)).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum BirthDetection {
    /// Paper 000's "all births detected" heuristic: a birth child must assign a measurement to the born
    /// object. **The default.** Every child with an undetected birth weighs at most (1 − p_D) α / P(no
    /// event) of its companion without that birth ([000] (39)), and its track would carry only the broad
    /// birth pdf; dropping those children keeps H∞ for hypotheses that explain measurements. The mass
    /// discarded per scan is about (1 − p_D) M_b α (digest §1.3 (5)).
    #[default]
    AllDetected,
    /// The exact first-order model: a born object is detected with p_D like any other, so undetected
    /// births are children too.
    AllowUndetected,
}

/// R-FISST's first-order birth model: per scan at most one birth, in one of the cells, each with
/// probability α ([003] §II-C; digest §4.4 "Event probabilities").
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BirthModel<T: Real, const S: usize, const B: usize> {
    /// α: probability of a birth in each cell per scan.
    pub probability: T,
    /// The birth pdf of each cell (at most `B` cells; M_b = `cells.len()`).
    pub cells: heapless::Vec<Gaussian<T, S>, B>,
    /// Whether births must be detected at birth.
    pub detection: BirthDetection,
}

impl<T: Real, const S: usize, const B: usize> BirthModel<T, S, B> {
    /// No births.
    pub fn none() -> Self {
        Self { probability: T::zero(), cells: heapless::Vec::new(), detection: BirthDetection::AllDetected }
    }
}

/// How the children of each parent are produced.
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

impl Default for ChildGeneration {
    fn default() -> Self {
        ChildGeneration::Exhaustive { max_children_per_scan: 1_000_000 }
    }
}

/// What to do when the kept children need more distinct tracks than the track store holds.
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

/// How the H∞ hypotheses are chosen among the children (paper 003 §III-A).
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
}

/// The complete configuration of a tracker.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Config<T: Real, M, G, const S: usize, const B: usize> {
    /// How objects move.
    pub motion: M,
    /// How the sensor measures an object.
    pub measurement: G,
    /// Detection, clutter and field of view.
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
    /// Seed of every random choice (the Metropolis sampler); results depend only on it and the inputs.
    pub seed: u64,
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
            birth: BirthModel { probability: 0.01, cells, detection: BirthDetection::AllowUndetected },
            death_probability: 0.001,
            gate: Some(25.0),
            children: ChildGeneration::Sampled(crate::sampler::SamplerConfig::default()),
            selection: Selection::SampledByWeight,
            store_overflow: StoreOverflow::Error,
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
