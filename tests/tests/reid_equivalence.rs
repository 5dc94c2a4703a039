//! docs/maths.md §2.2: without birth or death the R-FISST weights equal Reid's HOMHT (30), and the
//! per-hypothesis Kalman states are the textbook ones.

use conformance::*;
use tracker_core::{LinearTracker, TrackLabel};

type Tracker = LinearTracker<f64, 16, 4, 4, 16, 1>;

#[test]
fn thirteen_children_with_reid_weights_and_kalman_states() {
    let (pd, clutter_rate, volume) = (0.9, 0.5, 100.0);
    let lambda = clutter_rate / volume;
    let config = linear_config::<1>(pd, clutter_rate, volume);
    let priors = [gaussian([0.0, 0.0, 1.0, 0.0], 0.5), gaussian([3.0, 0.5, 0.8, 0.1], 0.8)];
    let zs = [V2::new(1.1, 0.1), V2::new(3.7, 0.7), V2::new(2.3, 0.2)];
    let mut tracker = Tracker::with_objects(config.clone(), &priors, 0.0).unwrap();
    let report = tracker.step(1.0, &zs).unwrap();
    assert_eq!(report.children, 13, "A_2(3) children");
    assert_eq!(report.hypotheses, 13);
    assert_eq!(report.captured_mass, 1.0);

    // Reid (30): w ∝ p_D^d (1 − p_D)^(n − d) λ^k Π N(z; H x⁻, S), from the textbook filter.
    let kf = TextbookKf { config: &config };
    let predicted: Vec<_> = priors.iter().map(|p| kf.predict(p, 1.0)).collect();
    let associations = all_associations(3, 2);
    assert_eq!(associations.len(), 13);
    let raw: Vec<f64> = associations
        .iter()
        .map(|sigma| {
            let d = sigma.iter().flatten().count() as i32;
            let k = 3 - d;
            let likelihood: f64 =
                sigma.iter().enumerate().filter_map(|(j, o)| o.map(|o| kf.likelihood(&predicted[o], &zs[j]))).product();
            pd.powi(d) * (1.0 - pd).powi(2 - d) * lambda.powi(k) * likelihood
        })
        .collect();
    let total: f64 = raw.iter().sum();

    let mut matched = [false; 13];
    for (sigma, w) in associations.iter().zip(&raw) {
        // Expected posterior of each object under σ.
        let expected: Vec<_> = (0..2)
            .map(|o| match sigma.iter().position(|&a| a == Some(o)) {
                Some(j) => kf.update(&predicted[o], &zs[j]),
                None => predicted[o],
            })
            .collect();
        let index = tracker
            .hypotheses()
            .position(|h| {
                h.tracks().zip(&expected).all(|(t, e)| {
                    (t.state.mean - e.mean).abs().max() < 1e-12
                        && (t.state.covariance - e.covariance).abs().max() < 1e-12
                })
            })
            .unwrap_or_else(|| panic!("no hypothesis for {sigma:?}"));
        assert!(!matched[index], "two associations matched one hypothesis");
        matched[index] = true;
        let got = tracker.hypotheses().nth(index).unwrap().weight();
        assert!(relative_difference(got, w / total) < 1e-12, "{sigma:?}: {got} vs Reid {}", w / total);
    }
    // Labels survive and every hypothesis holds both objects.
    for h in tracker.hypotheses() {
        let labels: Vec<_> = h.tracks().map(|t| t.label).collect();
        assert_eq!(labels, vec![TrackLabel(0), TrackLabel(1)]);
    }
}

#[test]
fn weight_is_a_product_of_per_object_factors_and_scales_with_clutter() {
    // docs/maths.md §4.1, §10.2: changing λ_C rescales a child by λ_C^k before normalisation, so the ratio of two
    // children with k and k' clutter measurements changes by (λ'/λ)^(k − k').
    let priors = [gaussian([0.0, 0.0, 1.0, 0.0], 0.5)];
    let zs = [V2::new(1.1, 0.1), V2::new(0.9, -0.2)];
    let ratio = |clutter_rate: f64| {
        let mut t = Tracker::with_objects(linear_config::<1>(0.9, clutter_rate, 100.0), &priors, 0.0).unwrap();
        t.step(1.0, &zs).unwrap();
        let all_clutter =
            t.hypotheses().find(|h| h.tracks().next().unwrap().state.covariance[(0, 0)] > 0.5).unwrap().weight();
        let detected: f64 = t.hypotheses().map(|h| h.weight()).sum::<f64>() - all_clutter;
        // detected children have k = 1, the all-clutter child k = 2 (and the object missed)
        all_clutter / detected
    };
    let (r1, r2) = (ratio(0.5), ratio(2.0));
    assert!(relative_difference(r2 / r1, 4.0) < 1e-12, "ratio changed by {}", r2 / r1);
}
