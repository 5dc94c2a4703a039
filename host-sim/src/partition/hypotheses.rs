//! A cluster's hypothesis set as owned data: read out of a core tracker, multiplied with another cluster's
//! (a merge, docs/maths.md §13.3), cut into groups of labels (a split, §13.4) and loaded back
//! ([`tracker_core::Tracker::reset_with`]).

use tracker_core::model::{MeasurementModel, MotionModel};
use tracker_core::{PriorHypothesis, PriorObject, Tracker};

/// One hypothesis: its weight and its objects in label order.
#[derive(Debug, Clone, PartialEq)]
pub struct Hypothesis<const S: usize> {
    pub weight: f64,
    pub objects: Vec<PriorObject<f64, S>>,
}

/// The hypotheses of `core`, heaviest first, with their normalised weights.
pub fn read<
    M,
    G,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
>(
    core: &Tracker<f64, M, G, S, D, H, N, Z, K, B>,
) -> Vec<Hypothesis<S>>
where
    M: MotionModel<f64, S>,
    G: MeasurementModel<f64, S, D>,
{
    core.hypotheses()
        .map(|h| Hypothesis {
            weight: h.weight(),
            objects: h.tracks().map(|t| PriorObject { label: t.label, state: t.state }).collect(),
        })
        .collect()
}

/// The core's prior of `set`.
pub fn as_prior<const S: usize>(set: &[Hypothesis<S>]) -> Vec<PriorHypothesis<'_, f64, S>> {
    set.iter().map(|h| PriorHypothesis { weight: h.weight, objects: &h.objects }).collect()
}

/// The product of two hypothesis sets (weights multiply, objects unite: the clusters hold distinct labels),
/// its best `keep` in weight order (ties in the order of (i, j)). Pruning each pairwise product to the best
/// `keep` keeps the best `keep` of the whole product: a child (a, b, c) among the best `keep` of A × B × C
/// has at most `keep` − 1 pairs (a', b') above (a, b), so (a, b) is among the best `keep` of A × B.
pub fn product<const S: usize>(a: &[Hypothesis<S>], b: &[Hypothesis<S>], keep: usize) -> Vec<Hypothesis<S>> {
    let mut pairs: Vec<(f64, usize, usize)> = a
        .iter()
        .enumerate()
        .flat_map(|(i, x)| b.iter().enumerate().map(move |(j, y)| (x.weight * y.weight, i, j)))
        .collect();
    // Stable: equal weights keep the (i, j) order, so the result does not depend on the sort's internals.
    pairs.sort_by(|p, q| q.0.total_cmp(&p.0));
    pairs.truncate(keep);
    pairs
        .into_iter()
        .map(|(weight, i, j)| {
            let mut objects: Vec<_> = a[i].objects.iter().chain(&b[j].objects).copied().collect();
            objects.sort_by_key(|o| o.label);
            Hypothesis { weight, objects }
        })
        .collect()
}

/// The distinct tracks of `set` as the core stores them (the same label and Gaussian are one track).
pub fn distinct_tracks<const S: usize>(set: &[Hypothesis<S>]) -> usize {
    let mut seen: Vec<&PriorObject<f64, S>> = vec![];
    for o in set.iter().flat_map(|h| &h.objects) {
        if !seen.iter().any(|s| s.label == o.label && s.state == o.state) {
            seen.push(o);
        }
    }
    seen.len()
}

#[cfg(test)]
mod tests {
    use super::*;
    use tracker_core::{Gaussian, TrackLabel};

    fn object(label: u32) -> PriorObject<f64, 1> {
        PriorObject {
            label: TrackLabel(label),
            state: Gaussian { mean: [label as f64].into(), covariance: [[1.0]].into() },
        }
    }

    fn set(weights: &[f64], label: u32) -> Vec<Hypothesis<1>> {
        weights
            .iter()
            .enumerate()
            .map(|(i, &w)| Hypothesis { weight: w, objects: if i == 0 { vec![object(label)] } else { vec![] } })
            .collect()
    }

    #[test]
    fn the_pruned_pairwise_product_is_the_best_of_the_whole_product() {
        let (a, b, c) = (set(&[0.6, 0.4], 1), set(&[0.7, 0.3], 2), set(&[0.9, 0.1], 3));
        let whole = product(&product(&a, &b, usize::MAX), &c, usize::MAX);
        assert_eq!(whole.len(), 8);
        assert!((whole.iter().map(|h| h.weight).sum::<f64>() - 1.0).abs() < 1e-15);
        for keep in 1..=8 {
            let pruned = product(&product(&a, &b, keep), &c, keep);
            let weights: Vec<f64> = pruned.iter().map(|h| h.weight).collect();
            let best: Vec<f64> = whole.iter().take(keep).map(|h| h.weight).collect();
            assert_eq!(weights, best, "keep {keep}");
        }
        // Objects unite in label order.
        let labels: Vec<u32> = whole[0].objects.iter().map(|o| o.label.0).collect();
        assert_eq!(labels, [1, 2, 3]);
    }
}
