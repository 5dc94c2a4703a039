//! Loading a tracker: the configuration check and the prior.

use super::finish_hypotheses;
use super::{PriorHypothesis, PriorObject};
use crate::config::{BirthDetection, BirthEvents, ChildGeneration, Config};
use crate::ekf;
use crate::error::ConfigError;
use crate::hypothesis::{Hypothesis, HypothesisSet};
use crate::index::insertion_sort_by;
use crate::model::{MeasurementModel, MotionModel};
use crate::real::{Real, ln};
use crate::store::{Track, TrackLabel, TrackStore};

/// A prior read one object at a time: what [`Tracker::reset_from`](super::Tracker::reset_from) and
/// [`Tracker::reset_with_from`](super::Tracker::reset_with_from) load, for a caller that holds its prior in
/// another form (the C interface's doubles) and would otherwise convert every object into a buffer on the
/// stack first. A slice of [`PriorHypothesis`] is one; the tracker reads it exactly as it reads the slice
/// given to [`Tracker::reset`](super::Tracker::reset), hypothesis by hypothesis and object by object.
///
/// Indices passed to the methods are in range (`hypothesis < hypotheses()`,
/// `object < objects(hypothesis)`).
pub trait PriorSource<T: Real, const S: usize> {
    /// Hypotheses in the prior.
    fn hypotheses(&self) -> usize;
    /// Relative weight of `hypothesis`.
    fn weight(&self, hypothesis: usize) -> T;
    /// Objects in `hypothesis`.
    fn objects(&self, hypothesis: usize) -> usize;
    /// The label of object `object` of `hypothesis`.
    fn label(&self, hypothesis: usize, object: usize) -> TrackLabel;
    /// Object `object` of `hypothesis`.
    fn object(&self, hypothesis: usize, object: usize) -> PriorObject<T, S>;
}

impl<T: Real, const S: usize> PriorSource<T, S> for [PriorHypothesis<'_, T, S>] {
    fn hypotheses(&self) -> usize {
        self.len()
    }

    fn weight(&self, hypothesis: usize) -> T {
        self.get(hypothesis).map_or(T::zero(), |h| h.weight)
    }

    fn objects(&self, hypothesis: usize) -> usize {
        self.get(hypothesis).map_or(0, |h| h.objects.len())
    }

    fn label(&self, hypothesis: usize, object: usize) -> TrackLabel {
        self.get(hypothesis).and_then(|h| h.objects.get(object)).map_or(TrackLabel(0), |o| o.label)
    }

    fn object(&self, hypothesis: usize, object: usize) -> PriorObject<T, S> {
        let found = self.get(hypothesis).and_then(|h| h.objects.get(object)).copied();
        // In range by the trait's contract; otherwise an object of NaN mean, which the tracker refuses.
        found.unwrap_or_else(|| {
            let mut state = crate::gaussian::Gaussian::<T, S>::ZERO;
            state.mean.fill(T::of_f64(f64::NAN));
            PriorObject { label: TrackLabel(0), state }
        })
    }
}

/// Checks every parameter of `config` for a tracker of at most `N` objects per hypothesis, the birth cells
/// as the measurement model sees them before its first placement included.
///
/// # Errors
/// [`ConfigError`] naming the first invalid parameter.
pub(super) fn check_config<T, M, G, const S: usize, const D: usize, const N: usize, const B: usize>(
    config: &Config<T, M, G, S, B>,
) -> Result<(), ConfigError>
where
    T: Real,
    M: MotionModel<T, S>,
    G: MeasurementModel<T, S, D>,
{
    // A network with no sensors is a placeholder (`unconfigured`), not a configuration.
    if config.measurement.sensor_count() == 0 {
        return Err(ConfigError::Sensor("sensor network: no sensors"));
    }
    config.motion.validate().map_err(ConfigError::Motion)?;
    // A model whose sensors carry their own detection models checked them when it was built.
    if config.measurement.detection().is_none() {
        config.sensor.validate(&config.measurement).map_err(ConfigError::Sensor)?;
    }
    if !ekf::is_valid_covariance(&config.measurement.noise_covariance()) {
        return Err(ConfigError::MeasurementNoise);
    }
    check_event_probabilities::<T, M, G, S, N, B>(config)?;
    if let Some(gate) = config.gate
        && !(gate.is_finite_value() && gate > T::zero())
    {
        return Err(ConfigError::Gate);
    }
    match config.children {
        ChildGeneration::Exhaustive { max_children_per_scan: 0 } => return Err(ConfigError::ChildBudget),
        ChildGeneration::Exhaustive { max_children_per_scan } => {
            let limit = ChildGeneration::MAX_CHILDREN_PER_SCAN;
            if max_children_per_scan > limit {
                return Err(ConfigError::AboveLimit { parameter: "max_children_per_scan", limit });
            }
        }
        ChildGeneration::Sampled(sampler) => sampler.check()?,
    }
    for (cell, birth) in config.birth.cells.iter().enumerate() {
        if !(birth.mean.iter().all(|v| v.is_finite_value()) && ekf::is_valid_covariance(&birth.covariance)) {
            return Err(ConfigError::BirthCell { cell });
        }
        ekf::innovation::<T, G, S, D>(&config.measurement, birth).map_err(|_| ConfigError::BirthInnovation { cell })?;
    }
    Ok(())
}

/// α and β in [0, 1], and P(no event) = 1 − M_b α − M_d β > 0 for every parent: M_d ≤ N
/// (docs/maths.md §5.1); for independent births 1 − α > 0 and 1 − M_d β > 0 (§5.6).
fn check_event_probabilities<T: Real, M, G, const S: usize, const N: usize, const B: usize>(
    config: &Config<T, M, G, S, B>,
) -> Result<(), ConfigError> {
    let alpha = config.birth.probability;
    if !(alpha.is_finite_value() && alpha >= T::zero() && alpha <= T::one()) {
        return Err(ConfigError::BirthProbability);
    }
    let beta = config.death_probability;
    if !(beta.is_finite_value() && beta >= T::zero() && beta <= T::one()) {
        return Err(ConfigError::DeathProbability);
    }
    let deaths = T::of_f64(N as f64) * beta;
    let first_order_births = match config.birth.events {
        BirthEvents::FirstOrder => T::of_f64(config.birth.cells.len() as f64) * alpha,
        // Independent births: 1 − α > 0 per cell, and births always detected (docs/maths.md §5.6).
        BirthEvents::Independent => {
            if config.birth.detection != BirthDetection::AllDetected {
                return Err(ConfigError::IndependentBirthsUndetected);
            }
            if !(alpha < T::one()) {
                return Err(ConfigError::EventProbabilities);
            }
            T::zero()
        }
    };
    if !(T::one() - first_order_births - deaths > T::zero()) {
        return Err(ConfigError::EventProbabilities);
    }
    if let Some(measured) = &config.birth.measured {
        // Cells from measurements are independent-birth cells (docs/maths.md §5.8).
        if config.birth.events != BirthEvents::Independent {
            return Err(ConfigError::MeasuredBirths("measured births need independent birth events"));
        }
        measured.validate().map_err(ConfigError::MeasuredBirths)?;
        if config.birth.cells.len() >= B {
            return Err(ConfigError::MeasuredBirths("measured births need room in the B cells besides the fixed ones"));
        }
        // A tracklet's cells that cannot all be held would give no birth at all (docs/maths.md §5.10).
        if let Some(tracklets) = &measured.tracklets
            && tracklets.cells[0].saturating_mul(tracklets.cells[1]) > B - config.birth.cells.len()
        {
            return Err(ConfigError::MeasuredBirths(
                "tracklet births: cells (ln-range × range-rate) must fit the B cells besides the fixed ones",
            ));
        }
    }
    Ok(())
}

/// Checks `prior` and writes it into `store` and `set`; returns the next free label.
///
/// # Errors
/// [`ConfigError`] naming the first invalid prior entry; `store` and `set` are then partly written (they
/// are the tracker's inactive buffers).
pub(super) fn load_prior<T: Real, P, const S: usize, const N: usize, const H: usize, const K: usize>(
    prior: &P,
    store: &mut TrackStore<T, S, K>,
    set: &mut HypothesisSet<T, N, H>,
) -> Result<u32, ConfigError>
where
    P: PriorSource<T, S> + ?Sized,
{
    let total = prior_weight_total::<T, P, S, H>(prior)?;
    store.clear();
    set.clear();
    let mut next_label: u32 = 0;
    for index in 0..prior.hypotheses() {
        let count = prior.objects(index);
        if count > N {
            return Err(ConfigError::PriorTooManyObjects { hypothesis: index });
        }
        let mut slots = [0u16; N];
        for (position, slot) in slots.iter_mut().enumerate().take(count) {
            let object = prior.object(index, position);
            let state = &object.state;
            if !(state.mean.iter().all(|v| v.is_finite_value()) && ekf::is_valid_covariance(&state.covariance)) {
                return Err(ConfigError::PriorObject { hypothesis: index, object: position });
            }
            if (0..position).any(|other| prior.label(index, other) == object.label) {
                return Err(ConfigError::PriorDuplicateLabel { hypothesis: index });
            }
            next_label = next_label.max(object.label.0.saturating_add(1));
            let existing = store.as_slice().iter().position(|t| t.label == object.label && t.state == *state);
            *slot = match existing {
                Some(slot) => slot as u16,
                None => store
                    .push(Track { label: object.label, state: *state, existence: T::zero(), unseen_scans: 0 })
                    .map_err(|_| ConfigError::PriorTrackStoreFull)?,
            };
        }
        let weight = prior.weight(index);
        if weight == T::zero() {
            continue;
        }
        let slots = &mut slots[..count];
        // Labels are distinct within a hypothesis, so the order is unique.
        let tracks = store.as_slice();
        let label = |slot: u16| tracks.get(usize::from(slot)).map(|track| track.label);
        insertion_sort_by(slots, |&a, &b| label(a) < label(b));
        // The prior has at most H hypotheses, so this push cannot fail.
        let _ = set.push(Hypothesis::new(ln(weight / total), slots));
    }
    finish_hypotheses(set, store);
    Ok(next_label)
}

/// The sum of the prior's weights, after checking that there are 1 to `H` hypotheses with finite
/// non-negative weights and a finite positive sum.
fn prior_weight_total<T: Real, P: PriorSource<T, S> + ?Sized, const S: usize, const H: usize>(
    prior: &P,
) -> Result<T, ConfigError> {
    let count = prior.hypotheses();
    if count == 0 {
        return Err(ConfigError::PriorEmpty);
    }
    if count > H {
        return Err(ConfigError::PriorTooManyHypotheses);
    }
    let mut total = T::zero();
    for index in 0..count {
        let weight = prior.weight(index);
        if !(weight.is_finite_value() && weight >= T::zero()) {
            return Err(ConfigError::PriorWeight { hypothesis: index });
        }
        total += weight;
    }
    if !(total > T::zero() && total.is_finite_value()) {
        return Err(ConfigError::PriorWeightTotal);
    }
    Ok(total)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gaussian::Gaussian;
    use crate::store::TrackLabel;
    use crate::tracker::PriorObject;
    use nalgebra::{SMatrix, SVector};

    fn object(label: u32, x: f64) -> PriorObject<f64, 4> {
        PriorObject {
            label: TrackLabel(label),
            state: Gaussian { mean: SVector::from([x, 0.0, 1.0, 0.0]), covariance: SMatrix::identity() },
        }
    }

    #[test]
    fn identical_prior_tracks_are_stored_once_and_weights_normalised() {
        let (a, b) = (object(4, 0.0), object(9, 5.0));
        let prior = [PriorHypothesis { weight: 3.0, objects: &[a] }, PriorHypothesis { weight: 1.0, objects: &[b, a] }];
        let mut store = TrackStore::<f64, 4, 8>::new();
        let mut set = HypothesisSet::<f64, 4, 4>::new();
        assert_eq!(load_prior(&prior[..], &mut store, &mut set), Ok(10));
        assert_eq!(store.len(), 2, "object 4 is one track in both hypotheses");
        let weights: std::vec::Vec<f64> = set.as_slice().iter().map(|h| h.log_weight.exp()).collect();
        assert!((weights[0] - 0.75).abs() < 1e-15 && (weights[1] - 0.25).abs() < 1e-15);
        // Slots in label order: track of label 4 before label 9.
        let labels: std::vec::Vec<u32> =
            set.as_slice()[1].slots().iter().map(|&s| store.as_slice()[usize::from(s)].label.0).collect();
        assert_eq!(labels, [4, 9]);
        assert!((store.as_slice()[0].existence - 1.0).abs() < 1e-15);
    }

    #[test]
    fn bad_priors_are_typed_errors() {
        let a = object(1, 0.0);
        let mut store = TrackStore::<f64, 4, 8>::new();
        let mut set = HypothesisSet::<f64, 4, 1>::new();
        let twice = [PriorHypothesis { weight: 1.0, objects: &[a, a] }];
        assert_eq!(
            load_prior(&twice[..], &mut store, &mut set),
            Err(ConfigError::PriorDuplicateLabel { hypothesis: 0 })
        );
        let two = [PriorHypothesis { weight: 1.0, objects: &[a] }, PriorHypothesis { weight: 1.0, objects: &[a] }];
        assert_eq!(load_prior(&two[..], &mut store, &mut set), Err(ConfigError::PriorTooManyHypotheses));
        let overflow = [PriorHypothesis { weight: f64::MAX, objects: &[a] }];
        let mut set2 = HypothesisSet::<f64, 4, 2>::new();
        let both = [overflow[0], overflow[0]];
        assert_eq!(load_prior(&both[..], &mut store, &mut set2), Err(ConfigError::PriorWeightTotal));
    }

    /// A prior held as labels and x positions, each object built when the tracker reads it.
    struct Compact<'a>(&'a [(f64, &'a [(u32, f64)])]);

    impl PriorSource<f64, 4> for Compact<'_> {
        fn hypotheses(&self) -> usize {
            self.0.len()
        }
        fn weight(&self, hypothesis: usize) -> f64 {
            self.0[hypothesis].0
        }
        fn objects(&self, hypothesis: usize) -> usize {
            self.0[hypothesis].1.len()
        }
        fn label(&self, hypothesis: usize, object: usize) -> TrackLabel {
            TrackLabel(self.0[hypothesis].1[object].0)
        }
        fn object(&self, hypothesis: usize, object: usize) -> PriorObject<f64, 4> {
            let (label, x) = self.0[hypothesis].1[object];
            super::tests::object(label, x)
        }
    }

    #[test]
    fn a_prior_source_loads_as_the_slice_of_the_same_objects() {
        let (a, b, c) = (object(4, 0.0), object(9, 5.0), object(2, -3.0));
        let slice =
            [PriorHypothesis { weight: 3.0, objects: &[a, c] }, PriorHypothesis { weight: 1.0, objects: &[b, a] }];
        let compact = Compact(&[(3.0, &[(4, 0.0), (2, -3.0)]), (1.0, &[(9, 5.0), (4, 0.0)])]);
        let (mut store, mut set) = (TrackStore::<f64, 4, 8>::new(), HypothesisSet::<f64, 4, 4>::new());
        let (mut store2, mut set2) = (TrackStore::<f64, 4, 8>::new(), HypothesisSet::<f64, 4, 4>::new());
        assert_eq!(load_prior(&slice[..], &mut store, &mut set), Ok(10));
        assert_eq!(load_prior(&compact, &mut store2, &mut set2), Ok(10));
        assert_eq!(store.as_slice(), store2.as_slice());
        assert_eq!(set.len(), 2);
        for (h, h2) in set.as_slice().iter().zip(set2.as_slice()) {
            assert_eq!((h.log_weight.to_bits(), h.slots()), (h2.log_weight.to_bits(), h2.slots()));
        }
        let twice = Compact(&[(1.0, &[(1, 0.0), (1, 2.0)])]);
        assert_eq!(load_prior(&twice, &mut store2, &mut set2), Err(ConfigError::PriorDuplicateLabel { hypothesis: 0 }));
        let nan = Compact(&[(1.0, &[(1, f64::NAN)])]);
        assert_eq!(
            load_prior(&nan, &mut store2, &mut set2),
            Err(ConfigError::PriorObject { hypothesis: 0, object: 0 })
        );
        assert_eq!(load_prior(&Compact(&[]), &mut store2, &mut set2), Err(ConfigError::PriorEmpty));
    }
}
