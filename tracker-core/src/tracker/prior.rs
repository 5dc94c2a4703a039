//! Loading a tracker: the configuration check and the prior.

use super::PriorHypothesis;
use super::finish_hypotheses;
use crate::config::{BirthDetection, BirthEvents, ChildGeneration, Config};
use crate::ekf;
use crate::error::ConfigError;
use crate::hypothesis::{Hypothesis, HypothesisSet};
use crate::index::insertion_sort_by;
use crate::model::{MeasurementModel, MotionModel};
use crate::real::{Real, ln};
use crate::store::{Track, TrackStore};

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
    }
    Ok(())
}

/// Checks `prior` and writes it into `store` and `set`; returns the next free label.
///
/// # Errors
/// [`ConfigError`] naming the first invalid prior entry; `store` and `set` are then partly written (they
/// are the tracker's inactive buffers).
pub(super) fn load_prior<T: Real, const S: usize, const N: usize, const H: usize, const K: usize>(
    prior: &[PriorHypothesis<'_, T, S>],
    store: &mut TrackStore<T, S, K>,
    set: &mut HypothesisSet<T, N, H>,
) -> Result<u32, ConfigError> {
    let total = prior_weight_total::<T, S, H>(prior)?;
    store.clear();
    set.clear();
    let mut next_label: u32 = 0;
    for (index, hypothesis) in prior.iter().enumerate() {
        if hypothesis.objects.len() > N {
            return Err(ConfigError::PriorTooManyObjects { hypothesis: index });
        }
        let mut slots = [0u16; N];
        for (position, (object, slot)) in hypothesis.objects.iter().zip(slots.iter_mut()).enumerate() {
            let state = &object.state;
            if !(state.mean.iter().all(|v| v.is_finite_value()) && ekf::is_valid_covariance(&state.covariance)) {
                return Err(ConfigError::PriorObject { hypothesis: index, object: position });
            }
            if hypothesis.objects.iter().take(position).any(|other| other.label == object.label) {
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
        if hypothesis.weight == T::zero() {
            continue;
        }
        let slots = &mut slots[..hypothesis.objects.len()];
        // Labels are distinct within a hypothesis, so the order is unique.
        let tracks = store.as_slice();
        let label = |slot: u16| tracks.get(usize::from(slot)).map(|track| track.label);
        insertion_sort_by(slots, |&a, &b| label(a) < label(b));
        // The prior has at most H hypotheses, so this push cannot fail.
        let _ = set.push(Hypothesis::new(ln(hypothesis.weight / total), slots));
    }
    finish_hypotheses(set, store);
    Ok(next_label)
}

/// The sum of the prior's weights, after checking that there are 1 to `H` hypotheses with finite
/// non-negative weights and a finite positive sum.
fn prior_weight_total<T: Real, const S: usize, const H: usize>(
    prior: &[PriorHypothesis<'_, T, S>],
) -> Result<T, ConfigError> {
    if prior.is_empty() {
        return Err(ConfigError::PriorEmpty);
    }
    if prior.len() > H {
        return Err(ConfigError::PriorTooManyHypotheses);
    }
    let mut total = T::zero();
    for (index, hypothesis) in prior.iter().enumerate() {
        if !(hypothesis.weight.is_finite_value() && hypothesis.weight >= T::zero()) {
            return Err(ConfigError::PriorWeight { hypothesis: index });
        }
        total += hypothesis.weight;
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
        assert_eq!(load_prior(&prior, &mut store, &mut set), Ok(10));
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
        assert_eq!(load_prior(&twice, &mut store, &mut set), Err(ConfigError::PriorDuplicateLabel { hypothesis: 0 }));
        let two = [PriorHypothesis { weight: 1.0, objects: &[a] }, PriorHypothesis { weight: 1.0, objects: &[a] }];
        assert_eq!(load_prior(&two, &mut store, &mut set), Err(ConfigError::PriorTooManyHypotheses));
        let overflow = [PriorHypothesis { weight: f64::MAX, objects: &[a] }];
        let mut set2 = HypothesisSet::<f64, 4, 2>::new();
        let both = [overflow[0], overflow[0]];
        assert_eq!(load_prior(&both, &mut store, &mut set2), Err(ConfigError::PriorWeightTotal));
    }
}
