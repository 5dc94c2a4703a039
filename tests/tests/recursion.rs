//! Properties of the recursion: child counts A_N(m), normalisation, pruning preserves ratios, invariance
//! to the order of objects and measurements, recursive weights = batch weights (docs/maths.md §10.6).

use conformance::*;
use tracker_core::association::association_count;
use tracker_core::{Gaussian, LinearTracker, PriorHypothesis, PriorObject, TrackLabel};

fn ring_of_objects(n: usize) -> Vec<Gaussian<f64, 4>> {
    (0..n).map(|i| gaussian([i as f64 * 0.7, (i % 3) as f64 * 0.4, 0.5, 0.0], 1.0)).collect()
}

#[test]
fn ten_objects_five_measurements_give_63591_children() {
    let objects = ring_of_objects(10);
    let zs: Vec<V2> = (0..5).map(|j| V2::new(j as f64 * 1.3 + 0.4, 0.3)).collect();
    let mut tracker =
        LinearTracker::<f64, 16, 12, 8, 256, 1>::with_objects(linear_config(0.9, 1.0, 400.0), &objects, 0.0).unwrap();
    let report = tracker.step(1.0, &zs).unwrap();
    assert_eq!(u128::from(report.children), association_count(10, 5));
    assert_eq!(report.children, 63_591);
    assert_eq!(report.hypotheses, 16);
    assert!(report.captured_mass < 1.0 && report.captured_mass > 0.0);
}

#[test]
fn child_counts_follow_the_table() {
    for n in 0..=4 {
        for m in 0..=4 {
            let objects = ring_of_objects(n);
            let zs: Vec<V2> = (0..m).map(|j| V2::new(j as f64, 0.1)).collect();
            let mut tracker =
                LinearTracker::<f64, 8, 4, 4, 64, 1>::with_objects(linear_config(0.8, 1.0, 400.0), &objects, 0.0)
                    .unwrap();
            let report = tracker.step(1.0, &zs).unwrap();
            assert_eq!(u128::from(report.children), association_count(n as u32, m as u32), "A_{n}({m})");
        }
    }
}

#[test]
fn weights_are_normalised_and_pruning_preserves_ratios() {
    let objects = ring_of_objects(4);
    let zs = [V2::new(0.6, 0.2), V2::new(1.1, 0.5), V2::new(2.0, 0.1)];
    let mut full =
        LinearTracker::<f64, 256, 4, 4, 64, 1>::with_objects(linear_config(0.85, 1.5, 400.0), &objects, 0.0).unwrap();
    let mut pruned =
        LinearTracker::<f64, 10, 4, 4, 64, 1>::with_objects(linear_config(0.85, 1.5, 400.0), &objects, 0.0).unwrap();
    let report = full.step(1.0, &zs).unwrap();
    pruned.step(1.0, &zs).unwrap();
    assert_eq!(report.hypotheses, 73, "A_4(3) = 73 children, all kept");
    let total: f64 = full.hypotheses().map(|h| h.weight()).sum();
    assert!((total - 1.0).abs() < 1e-12);
    let total: f64 = pruned.hypotheses().map(|h| h.weight()).sum();
    assert!((total - 1.0).abs() < 1e-12);
    // The pruned set is the top 10 of the full set, with the same ratios.
    let full_weights: Vec<f64> = full.hypotheses().map(|h| h.weight()).collect();
    let pruned_weights: Vec<f64> = pruned.hypotheses().map(|h| h.weight()).collect();
    for i in 0..10 {
        for j in 0..10 {
            assert!(
                relative_difference(pruned_weights[i] / pruned_weights[j], full_weights[i] / full_weights[j]) < 1e-12
            );
        }
    }
    // Weights are non-increasing (best first).
    assert!(full_weights.windows(2).all(|w| w[0] >= w[1]));
}

/// (weight, sorted posterior means) of every hypothesis, sorted.
fn summary<const H: usize>(t: &LinearTracker<f64, H, 4, 4, 64, 1>) -> Vec<(f64, Vec<[f64; 4]>)> {
    let mut out: Vec<_> = t
        .hypotheses()
        .map(|h| {
            let mut means: Vec<[f64; 4]> = h.tracks().map(|tr| tr.state.mean.into()).collect();
            means.sort_by(|a, b| a.partial_cmp(b).unwrap());
            (h.weight(), means)
        })
        .collect();
    // Sort by content (distinct children have distinct means); equal weights would make a weight order ambiguous.
    out.sort_by(|a, b| a.1.partial_cmp(&b.1).unwrap());
    out
}

fn assert_same(a: &[(f64, Vec<[f64; 4]>)], b: &[(f64, Vec<[f64; 4]>)]) {
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(b) {
        assert!(relative_difference(x.0, y.0) < 1e-12, "{} vs {}", x.0, y.0);
        for (mx, my) in x.1.iter().zip(&y.1) {
            for k in 0..4 {
                assert!((mx[k] - my[k]).abs() < 1e-12);
            }
        }
    }
}

#[test]
fn invariant_to_the_order_of_objects_and_measurements() {
    let objects = ring_of_objects(4);
    let zs = [V2::new(0.6, 0.2), V2::new(1.1, 0.5), V2::new(2.0, 0.1)];
    let config = linear_config(0.85, 1.5, 400.0);
    let mut base = LinearTracker::<f64, 128, 4, 4, 64, 1>::with_objects(config.clone(), &objects, 0.0).unwrap();
    base.step(1.0, &zs).unwrap();

    let reversed: Vec<_> = objects.iter().rev().copied().collect();
    let mut permuted = LinearTracker::<f64, 128, 4, 4, 64, 1>::with_objects(config.clone(), &reversed, 0.0).unwrap();
    permuted.step(1.0, &[zs[2], zs[0], zs[1]]).unwrap();
    assert_same(&summary(&base), &summary(&permuted));
}

#[test]
fn recursive_weights_equal_batch_weights_over_two_scans() {
    // docs/maths.md §2.3, [001] (19)–(20): C(h₂) = Pr{γ₁} Pr{γ₂} ∫ℓ₁p⁻ ∫ℓ₂p⁻ for every global hypothesis, normalised once.
    let (pd, clutter_rate, volume) = (0.8, 1.0, 200.0);
    let lambda = clutter_rate / volume;
    let config = linear_config::<1>(pd, clutter_rate, volume);
    let objects = [gaussian([0.0, 0.0, 1.0, 0.0], 0.5), gaussian([2.0, 0.0, 1.0, 0.2], 0.5)];
    let scans = [vec![V2::new(1.1, 0.1), V2::new(2.9, 0.3)], vec![V2::new(2.2, 0.0), V2::new(4.1, 0.5)]];
    let mut tracker = LinearTracker::<f64, 64, 4, 4, 64, 1>::with_objects(config.clone(), &objects, 0.0).unwrap();
    tracker.step(1.0, &scans[0]).unwrap();
    tracker.step(2.0, &scans[1]).unwrap();

    let kf = TextbookKf { config: &config };
    let mut batch: Vec<(f64, Vec<[f64; 4]>)> = vec![];
    for s1 in all_associations(2, 2) {
        for s2 in all_associations(2, 2) {
            let mut weight = 1.0;
            let mut states = objects.to_vec();
            for (scan, sigma) in [&s1, &s2].iter().enumerate() {
                let d = sigma.iter().flatten().count() as i32;
                weight *= pd.powi(d) * (1.0 - pd).powi(2 - d) * lambda.powi(2 - d);
                for (o, state) in states.iter_mut().enumerate() {
                    let predicted = kf.predict(state, 1.0);
                    *state = match sigma.iter().position(|&a| a == Some(o)) {
                        Some(j) => {
                            weight *= kf.likelihood(&predicted, &scans[scan][j]);
                            kf.update(&predicted, &scans[scan][j])
                        }
                        None => predicted,
                    };
                }
            }
            let mut means: Vec<[f64; 4]> = states.iter().map(|s| s.mean.into()).collect();
            means.sort_by(|a, b| a.partial_cmp(b).unwrap());
            batch.push((weight, means));
        }
    }
    let total: f64 = batch.iter().map(|b| b.0).sum();
    for b in &mut batch {
        b.0 /= total;
    }
    batch.sort_by(|a, b| a.0.total_cmp(&b.0));
    assert_eq!(batch.len(), 49);
    assert_eq!(tracker.hypotheses().len(), 49);
    let mut recursive: Vec<_> = tracker
        .hypotheses()
        .map(|h| {
            let mut means: Vec<[f64; 4]> = h.tracks().map(|t| t.state.mean.into()).collect();
            means.sort_by(|a, b| a.partial_cmp(b).unwrap());
            (h.weight(), means)
        })
        .collect();
    recursive.sort_by(|a, b| a.0.total_cmp(&b.0));
    for (r, b) in recursive.iter().zip(&batch) {
        assert!(relative_difference(r.0, b.0) < 1e-12, "recursive {} vs batch {}", r.0, b.0);
        for (mr, mb) in r.1.iter().zip(&b.1) {
            for k in 0..4 {
                assert!((mr[k] - mb[k]).abs() < 1e-10);
            }
        }
    }
}

#[test]
fn tracks_are_shared_between_hypotheses() {
    // 4 objects, 3 measurements: 73 hypotheses but only 4 × (1 + 3) = 16 distinct tracks.
    let objects = ring_of_objects(4);
    let zs = [V2::new(0.6, 0.2), V2::new(1.1, 0.5), V2::new(2.0, 0.1)];
    let mut t =
        LinearTracker::<f64, 128, 4, 4, 64, 1>::with_objects(linear_config(0.85, 1.5, 400.0), &objects, 0.0).unwrap();
    let report = t.step(1.0, &zs).unwrap();
    assert_eq!(report.hypotheses, 73);
    assert_eq!(report.tracks, 16);
    // Existence of every label is 1 (no death), and of every track the weight of its holders.
    for label in 0..4 {
        assert!((t.label_existence(TrackLabel(label)) - 1.0).abs() < 1e-12);
    }
}

#[test]
fn child_pdfs_do_not_depend_on_parent_weights() {
    // docs/maths.md §2.1: changing prior weights never changes a child's EKF mean or covariance.
    let a = [PriorObject { label: TrackLabel(0), state: gaussian([0.0, 0.0, 1.0, 0.0], 0.5) }];
    let b = [
        PriorObject { label: TrackLabel(0), state: gaussian([0.0, 0.0, 1.0, 0.0], 0.5) },
        PriorObject { label: TrackLabel(1), state: gaussian([3.0, 0.0, 1.0, 0.0], 0.5) },
    ];
    let zs = [V2::new(1.1, 0.1), V2::new(3.9, 0.0)];
    let run = |wa: f64| {
        let prior = [PriorHypothesis { weight: wa, objects: &a }, PriorHypothesis { weight: 1.0 - wa, objects: &b }];
        let mut t = LinearTracker::<f64, 128, 4, 4, 64, 1>::new(linear_config(0.85, 1.5, 400.0), &prior, 0.0).unwrap();
        t.step(1.0, &zs).unwrap();
        let mut states: Vec<Vec<u64>> = t
            .tracks()
            .iter()
            .map(|tr| tr.state.mean.iter().chain(tr.state.covariance.iter()).map(|v| v.to_bits()).collect())
            .collect();
        states.sort();
        states
    };
    assert_eq!(run(0.2), run(0.7));
}

#[test]
fn identical_inputs_give_identical_bits() {
    let objects = ring_of_objects(4);
    let zs = [V2::new(0.6, 0.2), V2::new(1.1, 0.5), V2::new(2.0, 0.1)];
    let run = || {
        let mut t = LinearTracker::<f64, 16, 4, 4, 64, 1>::with_objects(linear_config(0.85, 1.5, 400.0), &objects, 0.0)
            .unwrap();
        t.step(1.0, &zs).unwrap();
        t.step(2.0, &zs[..2]).unwrap();
        fingerprint(&t)
    };
    assert_eq!(run(), run());
}
