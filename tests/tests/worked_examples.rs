//! docs/maths.md §10.1: the single-scan worked numbers of the weight form, one object, p_D = 0.9, V = 100,
//! Λ_C = 0.5 (λ_C = 0.005), no birth or death. Measurements are placed so that the predicted likelihood ĝ
//! takes the example's values exactly.

use conformance::*;
use tracker_core::{Gaussian, LinearTracker, Measure};

type Tracker = LinearTracker<f64, 8, 2, 2, 8, 1>;

const PD: f64 = 0.9;
const LAMBDA: f64 = 0.5 / 100.0;

fn setup() -> (Tracker, Gaussian<f64, 4>) {
    let config = linear_config::<1>(PD, 0.5, 100.0);
    let object = gaussian([0.0, 0.0, 1.0, 0.0], 0.05);
    let predicted = TextbookKf { config: &config }.predict(&object, 1.0);
    (Tracker::with_objects(config, &[object], 0.0).unwrap(), predicted)
}

/// A measurement on the +x (`side` = 1) or −x (`side` = −1) side of ẑ with N(z; ẑ, S) = `target`.
fn measurement_with_likelihood(t: &Tracker, predicted: &Gaussian<f64, 4>, target: f64, side: f64) -> V2 {
    let model = &t.config().measurement;
    let h = model.jacobian(&predicted.mean);
    let s = h * predicted.covariance * h.transpose() + model.noise;
    let peak = 1.0 / (2.0 * std::f64::consts::PI * s.determinant().sqrt());
    assert!(target < peak, "target likelihood above the peak {peak}");
    let q = s.try_inverse().unwrap()[(0, 0)];
    let distance = (-2.0 * (target / peak).ln() / q).sqrt();
    h * predicted.mean + V2::new(side * distance, 0.0)
}

/// The weight of the hypothesis whose track is the Kalman update with `z`, or the prediction (`None`).
fn weight_of(t: &Tracker, predicted: &Gaussian<f64, 4>, z: Option<&V2>) -> f64 {
    let kf = TextbookKf { config: t.config() };
    let expected = z.map_or(*predicted, |z| kf.update(predicted, z));
    let mut found = t.hypotheses().filter(|h| {
        h.tracks().all(|tr| {
            (tr.state.mean - expected.mean).abs().max() < 1e-12
                && (tr.state.covariance - expected.covariance).abs().max() < 1e-12
        })
    });
    let weight = found.next().expect("a hypothesis with the expected track").weight();
    assert!(found.next().is_none(), "one hypothesis per association");
    weight
}

#[test]
fn one_measurement_is_the_object_with_probability_0_989011() {
    let (mut t, predicted) = setup();
    let z = measurement_with_likelihood(&t, &predicted, 0.05, 1.0);
    let g = TextbookKf { config: t.config() }.likelihood(&predicted, &z);
    assert!(relative_difference(g, 0.05) < 1e-12, "ĝ = {g}");
    let report = t.step(1.0, &[z]).unwrap();
    assert_eq!(report.children, 2);
    let detected = weight_of(&t, &predicted, Some(&z));
    let exact = PD * g / (PD * g + (1.0 - PD) * LAMBDA);
    assert!(relative_difference(detected, exact) < 1e-12, "{detected} vs {exact}");
    assert!((detected - 0.989011).abs() < 5e-7, "P(z from the object) = {detected}");
}

#[test]
fn two_measurements_weigh_0_96983_0_01940_0_01078() {
    let (mut t, predicted) = setup();
    let z1 = measurement_with_likelihood(&t, &predicted, 0.05, 1.0);
    let z2 = measurement_with_likelihood(&t, &predicted, 0.001, -1.0);
    let report = t.step(1.0, &[z1, z2]).unwrap();
    assert_eq!(report.children, 3);
    let (a, b, c) =
        (weight_of(&t, &predicted, Some(&z1)), weight_of(&t, &predicted, Some(&z2)), weight_of(&t, &predicted, None));
    // Unnormalised: A = p_D ĝ₁ λ_C = 2.25e-4, B = p_D ĝ₂ λ_C = 4.5e-6, C = (1 − p_D) λ_C² = 2.5e-6.
    let kf = TextbookKf { config: t.config() };
    let raw = [
        PD * kf.likelihood(&predicted, &z1) * LAMBDA,
        PD * kf.likelihood(&predicted, &z2) * LAMBDA,
        (1.0 - PD) * LAMBDA * LAMBDA,
    ];
    for (got, want) in raw.iter().zip([2.25e-4, 4.5e-6, 2.5e-6]) {
        assert!(relative_difference(*got, want) < 1e-12, "{raw:?}");
    }
    let total: f64 = raw.iter().sum();
    for (got, exact) in [a, b, c].iter().zip(raw.map(|w| w / total)) {
        assert!(relative_difference(*got, exact) < 1e-12, "{got} vs {exact}");
    }
    for (got, want) in [a, b, c].iter().zip([0.96983, 0.01940, 0.01078]) {
        assert!((got - want).abs() < 5e-6, "A, B, C = {a}, {b}, {c}");
    }
}
