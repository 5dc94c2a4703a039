//! docs/maths.md §2.4, §10.3: with one object of existence 0.5, no birth and death probability 0.02, R-FISST's
//! existence probability equals IPDA's, with the worked numbers there.
//! P_D = 0.9, λ = 2 clutter returns in V = 100 (λ_C = 0.02), survival 0.98.

use conformance::*;
use tracker_core::{Gaussian, LinearTracker, Measure, PriorHypothesis, PriorObject, TrackLabel};

type Tracker = LinearTracker<f64, 16, 2, 4, 16, 1>;

const PD: f64 = 0.9;
const BETA: f64 = 0.02;

fn tracker() -> (Tracker, Gaussian<f64, 4>) {
    let mut config = linear_config::<1>(PD, 2.0, 100.0);
    config.death_probability = BETA;
    config.measurement = tracker_core::PositionMeasurement::isotropic(0.25);
    let object = gaussian([0.0, 0.0, 1.0, 0.0], 0.05);
    let present = [PriorObject { label: TrackLabel(0), state: object }];
    let prior = [PriorHypothesis { weight: 0.5, objects: &[] }, PriorHypothesis { weight: 0.5, objects: &present }];
    let kf = TextbookKf { config: &config };
    let predicted = kf.predict(&object, 1.0);
    (Tracker::new(config, &prior, 0.0).unwrap(), predicted)
}

/// A measurement whose predicted likelihood N(z; ẑ, S) is exactly `target`.
fn measurement_with_likelihood(predicted: &Gaussian<f64, 4>, target: f64) -> V2 {
    let model = tracker_core::PositionMeasurement::isotropic(0.25);
    let h = model.jacobian(&predicted.mean);
    let s = h * predicted.covariance * h.transpose() + model.noise;
    let peak = 1.0 / (2.0 * std::f64::consts::PI * s.determinant().sqrt());
    assert!(target < peak, "target likelihood above the peak");
    let direction = V2::new(1.0, 0.0);
    let q = (direction.transpose() * s.try_inverse().unwrap() * direction)[0];
    let t = (-2.0 * (target / peak).ln() / q).sqrt();
    h * predicted.mean + direction * t
}

/// IPDA: p_k|k = (1 − δ) / (1 − δ p_k|k−1) p_k|k−1 with δ = P_D (1 − Σ Λ_i / λ_C).
fn ipda(prior: f64, likelihoods: &[f64]) -> f64 {
    let predicted = (1.0 - BETA) * prior;
    let delta = PD * (1.0 - likelihoods.iter().sum::<f64>() / 0.02);
    (1.0 - delta) / (1.0 - delta * predicted) * predicted
}

#[test]
fn one_measurement_gives_existence_0_815485() {
    let (mut tracker, predicted) = tracker();
    let z = measurement_with_likelihood(&predicted, 0.1);
    assert!(relative_difference(TextbookKf { config: tracker.config() }.likelihood(&predicted, &z), 0.1) < 1e-12);
    tracker.step(1.0, &[z]).unwrap();
    let existence = tracker.label_existence(TrackLabel(0));
    assert!((existence - ipda(0.5, &[0.1])).abs() < 1e-12, "existence {existence}");
    assert!((existence - 0.815485).abs() < 5e-7, "existence {existence}");
    // Children: empty (merged from "no object" and "object died") 0.184515, missed 0.017728, z 0.797757.
    let empty: f64 = tracker.hypotheses().filter(|h| h.is_empty()).map(|h| h.weight()).sum();
    assert!((empty - 0.184515).abs() < 5e-7, "empty {empty}");
    let mut present: Vec<f64> = tracker.hypotheses().filter(|h| !h.is_empty()).map(|h| h.weight()).collect();
    present.sort_by(f64::total_cmp);
    assert!((present[0] - 0.017728).abs() < 5e-7 && (present[1] - 0.797757).abs() < 5e-7, "{present:?}");
    // The two empty children (different parents, identical content) were merged into one hypothesis.
    assert_eq!(tracker.hypotheses().filter(|h| h.is_empty()).count(), 1);
}

#[test]
fn two_measurements_give_existence_0_818383() {
    let (mut tracker, predicted) = tracker();
    let z1 = measurement_with_likelihood(&predicted, 0.1);
    let mut z2 = measurement_with_likelihood(&predicted, 0.002);
    // Mirror z2 to the other side of ẑ so that the two measurements differ.
    z2.x = 2.0 * predicted.mean.x - z2.x;
    tracker.step(1.0, &[z1, z2]).unwrap();
    let existence = tracker.label_existence(TrackLabel(0));
    assert!((existence - ipda(0.5, &[0.1, 0.002])).abs() < 1e-12);
    assert!((existence - 0.818383).abs() < 5e-7, "existence {existence}");
    let mut weights: Vec<f64> = tracker.hypotheses().map(|h| h.weight()).collect();
    weights.sort_by(f64::total_cmp);
    let expected = [0.015705, 0.017450, 0.181617, 0.785228];
    for (got, want) in weights.iter().zip(expected) {
        assert!((got - want).abs() < 5e-7, "{weights:?}");
    }
}

#[test]
fn five_empty_scans_decay_as_ipda() {
    let (mut tracker, _) = tracker();
    let expected = [0.087657, 0.009310, 0.000920, 0.000090, 0.000009];
    let mut existence = 0.5;
    for (scan, want) in expected.iter().enumerate() {
        tracker.step(scan as f64 + 1.0, &[]).unwrap();
        existence = ipda(existence, &[]);
        let got = tracker.label_existence(TrackLabel(0));
        assert!((got - existence).abs() < 1e-12, "scan {scan}: {got} vs IPDA {existence}");
        assert!((got - want).abs() < 5e-7, "scan {scan}: {got}");
    }
}

#[test]
fn no_birth_from_empty_and_prediction_keeps_existence_times_survival() {
    // docs/maths.md §10.3: an empty hypothesis has exactly one child, and with no measurement and
    // p_D → 0 (here: the object outside the field of view) existence becomes γ₁₁ × prior.
    let mut config = linear_config::<1>(PD, 2.0, 100.0);
    config.death_probability = BETA;
    config.sensor.field_of_view = tracker_core::Region::Rectangle { min: [50.0, 50.0], max: [60.0, 60.0] };
    let object = gaussian([0.0, 0.0, 1.0, 0.0], 0.05);
    let present = [PriorObject { label: TrackLabel(0), state: object }];
    let prior = [PriorHypothesis { weight: 0.5, objects: &[] }, PriorHypothesis { weight: 0.5, objects: &present }];
    let mut tracker = Tracker::new(config, &prior, 0.0).unwrap();
    let report = tracker.step(1.0, &[]).unwrap();
    // Out of view: no death event (deaths are among objects in the field of view), no missed factor.
    assert_eq!(report.children, 2);
    assert!((tracker.label_existence(TrackLabel(0)) - 0.5).abs() < 1e-15);

    let (mut tracker, _) = self::tracker();
    let empty_only = [PriorHypothesis { weight: 1.0, objects: &[] }];
    let mut empty = Tracker::new(tracker.config().clone(), &empty_only, 0.0).unwrap();
    let report = empty.step(1.0, &[]).unwrap();
    assert_eq!(report.children, 1);
    assert_eq!(empty.expected_cardinality(), 0.0);
    // In view with p_D: existence 0.5 → (1−p_D)(1−β)0.5 / ((1−p_D)(1−β)0.5 + 0.5 + β 0.5) = IPDA.
    tracker.step(1.0, &[]).unwrap();
    assert!((tracker.label_existence(TrackLabel(0)) - ipda(0.5, &[])).abs() < 1e-12);
}

#[test]
fn children_factors_sum_to_one_minus_delta() {
    // docs/maths.md §2.4: the surviving object's children (missed + each z) over λ_C^m sum to 1 − δ.
    let (mut tracker, predicted) = tracker();
    let z1 = measurement_with_likelihood(&predicted, 0.1);
    tracker.step(1.0, &[z1]).unwrap();
    let w_missed_and_z: f64 = tracker.hypotheses().filter(|h| !h.is_empty()).map(|h| h.weight()).sum();
    let w_empty: f64 = tracker.hypotheses().filter(|h| h.is_empty()).map(|h| h.weight()).sum();
    // w_present / w_empty = 0.5(1−β)(1−δ) / (0.5 + 0.5β)
    let one_minus_delta = 1.0 - PD * (1.0 - 0.1 / 0.02);
    let expected = 0.5 * (1.0 - BETA) * one_minus_delta / (0.5 + 0.5 * BETA);
    assert!(relative_difference(w_missed_and_z / w_empty, expected) < 1e-12);
}
