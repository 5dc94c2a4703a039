//! What a caller reads of a tracker between scans: its configuration, time and scan count, the
//! hypotheses ([`HypothesisView`]) and the tracks they hold, the MAP hypothesis, label existence and
//! cardinality probabilities, and a digest of the whole state.

use super::Tracker;
use crate::config::Config;
use crate::digest::Fnv1a;
use crate::hypothesis::Hypothesis;
use crate::model::{MeasurementModel, MotionModel};
use crate::real::{Real, exp};
use crate::store::{Track, TrackLabel};

/// A read-only view of one hypothesis and the tracks it holds.
#[derive(Debug, Clone, Copy)]
pub struct HypothesisView<'a, T: Real, const S: usize, const N: usize> {
    hypothesis: &'a Hypothesis<T, N>,
    tracks: &'a [Track<T, S>],
}

impl<'a, T: Real, const S: usize, const N: usize> HypothesisView<'a, T, S, N> {
    /// Normalised weight w.
    ///
    /// # Examples
    /// ```
    /// # let tracker = tracker_core::examples::two_hypotheses()?;
    /// let weights: Vec<f64> = tracker.hypotheses().map(|h| h.weight()).collect();
    /// assert!((weights[0] - 0.75).abs() < 1e-12 && (weights[1] - 0.25).abs() < 1e-12);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn weight(&self) -> T {
        exp(self.hypothesis.log_weight)
    }

    /// Normalised log-weight ln w.
    ///
    /// # Examples
    /// ```
    /// # let tracker = tracker_core::examples::two_hypotheses()?;
    /// let map = tracker.map_hypothesis();
    /// assert!((map.log_weight() - 0.75f64.ln()).abs() < 1e-12);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn log_weight(&self) -> T {
        self.hypothesis.log_weight
    }

    /// Number of objects.
    ///
    /// # Examples
    /// ```
    /// # let tracker = tracker_core::examples::two_hypotheses()?;
    /// let lengths: Vec<usize> = tracker.hypotheses().map(|h| h.len()).collect();
    /// assert_eq!(lengths, [1, 0]);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn len(&self) -> usize {
        self.hypothesis.len()
    }

    /// Whether the hypothesis holds no object.
    ///
    /// # Examples
    /// ```
    /// # let tracker = tracker_core::examples::two_hypotheses()?;
    /// assert!(!tracker.map_hypothesis().is_empty());
    /// assert!(tracker.hypotheses().last().is_some_and(|h| h.is_empty()));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn is_empty(&self) -> bool {
        self.hypothesis.is_empty()
    }

    /// Store slots of its tracks (in label order).
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::TrackLabel;
    /// # let tracker = tracker_core::examples::two_hypotheses()?;
    /// let slot = tracker.map_hypothesis().slots()[0];
    /// assert_eq!(tracker.tracks()[usize::from(slot)].label, TrackLabel(7));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn slots(&self) -> &'a [u16] {
        self.hypothesis.slots()
    }

    /// Its tracks, in label order.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::TrackLabel;
    /// # let object = tracker_core::examples::object();
    /// # let tracker = tracker_core::examples::two_hypotheses()?;
    /// let track = tracker.map_hypothesis().tracks().next().unwrap();
    /// assert_eq!(track.label, TrackLabel(7));
    /// assert_eq!(track.state, object);
    /// assert!((track.existence - 0.75).abs() < 1e-12);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn tracks(&self) -> impl Iterator<Item = &'a Track<T, S>> + 'a {
        let tracks = self.tracks;
        // Every slot of a hypothesis is a live track of the store.
        self.hypothesis.slots().iter().filter_map(move |&slot| tracks.get(usize::from(slot)))
    }
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
    /// The configuration.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::LinearTracker;
    /// # let (config, object) = (tracker_core::examples::config(), tracker_core::examples::object());
    /// let mut tracker = LinearTracker::<f64, 8, 4, 4, 16, 1>::with_objects(config, &[object], 0.0)?;
    /// assert_eq!(tracker.config().seed, 1);
    /// assert_eq!(tracker.config().sensor.detection_probability, 0.9);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn config(&self) -> &Config<T, M, G, S, B> {
        &self.config
    }

    /// Time of the last scan (or of the prior), in seconds.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::LinearTracker;
    /// # let (config, object) = (tracker_core::examples::config(), tracker_core::examples::object());
    /// # let mut tracker = LinearTracker::<f64, 8, 4, 4, 16, 1>::with_objects(config, &[object], 0.0)?;
    /// assert_eq!(tracker.time(), 0.0);
    /// tracker.step(2.5, &[])?;
    /// assert_eq!(tracker.time(), 2.5);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Number of scans processed.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::LinearTracker;
    /// # let (config, object) = (tracker_core::examples::config(), tracker_core::examples::object());
    /// # let mut tracker = LinearTracker::<f64, 8, 4, 4, 16, 1>::with_objects(config, &[object], 0.0)?;
    /// for k in 1..=3 {
    ///     tracker.step(f64::from(k), &[])?;
    /// }
    /// assert_eq!(tracker.scans(), 3);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn scans(&self) -> u64 {
        self.scans
    }

    /// The hypotheses, best first, with normalised weights.
    ///
    /// # Examples
    /// One object and one measurement: it came from the object, or it is clutter and the object was missed.
    /// ```
    /// # use nalgebra::SVector;
    /// # use tracker_core::LinearTracker;
    /// # let (config, object) = (tracker_core::examples::config(), tracker_core::examples::object());
    /// # let mut tracker = LinearTracker::<f64, 8, 4, 4, 16, 1>::with_objects(config, &[object], 0.0)?;
    /// tracker.step(1.0, &[SVector::from([1.0, 0.0])])?;
    /// let weights: Vec<f64> = tracker.hypotheses().map(|h| h.weight()).collect();
    /// assert_eq!(weights.len(), 2);
    /// assert!(weights[0] >= weights[1]);
    /// assert!((weights.iter().sum::<f64>() - 1.0).abs() < 1e-12);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn hypotheses(&self) -> impl ExactSizeIterator<Item = HypothesisView<'_, T, S, N>> + '_ {
        let tracks = self.stores[self.live()].as_slice();
        self.hypotheses[self.live()].as_slice().iter().map(move |hypothesis| HypothesisView { hypothesis, tracks })
    }

    /// The maximum a posteriori hypothesis (the first of [`Tracker::hypotheses`]; ties keep the
    /// deterministic enumeration order).
    ///
    /// # Examples
    /// ```
    /// # use nalgebra::SVector;
    /// # use tracker_core::LinearTracker;
    /// # let (config, object) = (tracker_core::examples::config(), tracker_core::examples::object());
    /// # let mut tracker = LinearTracker::<f64, 8, 4, 4, 16, 1>::with_objects(config, &[object], 0.0)?;
    /// tracker.step(1.0, &[SVector::from([1.0, 0.0])])?;
    /// let map = tracker.map_hypothesis();
    /// assert_eq!(map.weight(), tracker.hypotheses().next().unwrap().weight());
    /// assert!(map.weight() > 0.9);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn map_hypothesis(&self) -> HypothesisView<'_, T, S, N> {
        let tracks = self.stores[self.live()].as_slice();
        // There is always at least one hypothesis: the prior has one and every scan keeps one.
        HypothesisView { hypothesis: &self.hypotheses[self.live()].as_slice()[0], tracks }
    }

    /// Every track of the shared store, with its existence probability.
    ///
    /// # Examples
    /// The two hypotheses after a scan hold different tracks of the same object, whose existences add up:
    /// ```
    /// # use nalgebra::SVector;
    /// # use tracker_core::LinearTracker;
    /// # let (config, object) = (tracker_core::examples::config(), tracker_core::examples::object());
    /// # use tracker_core::TrackLabel;
    /// # let mut tracker = LinearTracker::<f64, 8, 4, 4, 16, 1>::with_objects(config, &[object], 0.0)?;
    /// tracker.step(1.0, &[SVector::from([1.0, 0.0])])?;
    /// assert_eq!(tracker.tracks().len(), 2); // updated with z, and missed
    /// let total: f64 = tracker.tracks().iter().map(|t| t.existence).sum();
    /// assert!((total - tracker.label_existence(TrackLabel(0))).abs() < 1e-12);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn tracks(&self) -> &[Track<T, S>] {
        self.stores[self.live()].as_slice()
    }

    /// Existence probability of the object `label`: the total weight of the hypotheses that hold a
    /// track with that label.
    ///
    /// # Examples
    /// With deaths (β = 0.1) and an empty scan, the object survived and was missed (weight (1 − β)(1 − p_D))
    /// or died (weight β):
    /// ```
    /// # use tracker_core::{Config, LinearTracker};
    /// # let config = tracker_core::Config { death_probability: 0.1, ..tracker_core::examples::config() };
    /// # let object = tracker_core::examples::object();
    /// # use tracker_core::TrackLabel;
    /// # let mut tracker = LinearTracker::<f64, 8, 4, 4, 16, 1>::with_objects(config, &[object], 0.0)?;
    /// tracker.step(1.0, &[])?;
    /// let survived = 0.9 * 0.1;
    /// let expected = survived / (survived + 0.1);
    /// assert!((tracker.label_existence(TrackLabel(0)) - expected).abs() < 1e-12);
    /// assert_eq!(tracker.label_existence(TrackLabel(9)), 0.0);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn label_existence(&self, label: TrackLabel) -> T {
        self.tracks().iter().filter(|track| track.label == label).fold(T::zero(), |sum, track| sum + track.existence)
    }

    /// P(number of objects = `n`).
    ///
    /// # Examples
    /// As for [`Tracker::label_existence`]: after an empty scan with β = 0.1, the object is gone with probability
    /// β / ((1 − β)(1 − p_D) + β).
    /// ```
    /// # use tracker_core::{Config, LinearTracker};
    /// # let config = tracker_core::Config { death_probability: 0.1, ..tracker_core::examples::config() };
    /// # let object = tracker_core::examples::object();
    /// # let mut tracker = LinearTracker::<f64, 8, 4, 4, 16, 1>::with_objects(config, &[object], 0.0)?;
    /// tracker.step(1.0, &[])?;
    /// assert!((tracker.cardinality_probability(0) - 0.1 / 0.19).abs() < 1e-12);
    /// assert!((tracker.cardinality_probability(0) + tracker.cardinality_probability(1) - 1.0).abs() < 1e-12);
    /// assert_eq!(tracker.cardinality_probability(2), 0.0);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn cardinality_probability(&self, n: usize) -> T {
        self.hypotheses().filter(|h| h.len() == n).fold(T::zero(), |sum, h| sum + h.weight())
    }

    /// Expected number of objects Σ_h w_h N_h.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::{Config, LinearTracker};
    /// # let config = tracker_core::Config { death_probability: 0.1, ..tracker_core::examples::config() };
    /// # let object = tracker_core::examples::object();
    /// # let mut tracker = LinearTracker::<f64, 8, 4, 4, 16, 1>::with_objects(config, &[object], 0.0)?;
    /// assert_eq!(tracker.expected_cardinality(), 1.0);
    /// let report = tracker.step(1.0, &[])?;
    /// assert!((tracker.expected_cardinality() - 0.09 / 0.19).abs() < 1e-12);
    /// assert_eq!(report.expected_cardinality, tracker.expected_cardinality());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn expected_cardinality(&self) -> T {
        self.hypotheses().fold(T::zero(), |sum, h| sum + h.weight() * T::of_f64(h.len() as f64))
    }

    /// A 64-bit digest (FNV-1a) of everything the tracker exposes: time, scan count, and for every
    /// hypothesis in order its log-weight and its tracks' labels, means and covariances, as raw bits.
    /// Two trackers with the same digest agree bit for bit (up to hash collisions); it is how the host and
    /// an embedded target are compared.
    ///
    /// # Examples
    /// The same configuration, prior and scans give the same digest; anything else almost surely not:
    /// ```
    /// # use nalgebra::SVector;
    /// # use tracker_core::LinearTracker;
    /// # let (config, object) = (tracker_core::examples::config(), tracker_core::examples::object());
    /// # let mut tracker = LinearTracker::<f64, 8, 4, 4, 16, 1>::with_objects(config, &[object], 0.0)?;
    /// let mut twin = tracker.clone();
    /// tracker.step(1.0, &[SVector::from([1.0, 0.0])])?;
    /// twin.step(1.0, &[SVector::from([1.0, 0.0])])?;
    /// assert_eq!(tracker.digest(), twin.digest());
    /// tracker.step(2.0, &[SVector::from([2.0, 0.0])])?;
    /// twin.step(2.0, &[SVector::from([2.0, 0.1])])?;
    /// assert_ne!(tracker.digest(), twin.digest());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn digest(&self) -> u64 {
        let mut hash = Fnv1a::new();
        hash.write_u64(self.time.to_bits());
        hash.write_u64(self.scans);
        for hypothesis in self.hypotheses() {
            hash.write_u64(hypothesis.log_weight().as_f64().to_bits());
            for track in hypothesis.tracks() {
                hash.write(&track.label.0.to_le_bytes());
                for value in track.state.mean.iter().chain(track.state.covariance.iter()) {
                    hash.write_u64(value.as_f64().to_bits());
                }
            }
        }
        hash.finish()
    }
}
