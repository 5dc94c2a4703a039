//! Per-object posteriors of a hypothesis set: for each label its existence (the weight of the hypotheses
//! that hold it) and the moments of its Gaussian mixture over those hypotheses. Equal for a partitioned
//! tracker and a single tracker exactly when the partition is exact (docs/maths.md §13.1).

use nalgebra::{SMatrix, SVector};
use std::collections::BTreeMap;
use tracker_core::model::{MeasurementModel, MotionModel};
use tracker_core::{Track, Tracker};

/// One object's posterior.
#[derive(Debug, Clone, PartialEq)]
pub struct ObjectPosterior<const S: usize> {
    pub existence: f64,
    pub mean: SVector<f64, S>,
    pub covariance: SMatrix<f64, S, S>,
}

/// Adds `core`'s per-label posteriors to `out`.
pub fn add<
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
    out: &mut BTreeMap<u32, ObjectPosterior<S>>,
) where
    M: MotionModel<f64, S>,
    G: MeasurementModel<f64, S, D>,
{
    let tracks = core.tracks();
    let weighted =
        || core.hypotheses().map(|h| (h.weight(), h.slots().iter().filter_map(|&slot| tracks.get(usize::from(slot)))));
    add_weighted(weighted, out);
}

/// Adds the per-label posteriors of the hypotheses `hypotheses()` yields (each one's weight and tracks;
/// called twice) to `out`.
pub fn add_weighted<'a, const S: usize, I, T>(hypotheses: impl Fn() -> I, out: &mut BTreeMap<u32, ObjectPosterior<S>>)
where
    I: Iterator<Item = (f64, T)>,
    T: Iterator<Item = &'a Track<f64, S>>,
{
    // Two passes (the mean, then the spread about it), so that large means do not cancel the covariance.
    let mut sums: BTreeMap<u32, (f64, SVector<f64, S>)> = BTreeMap::new();
    for (weight, tracks) in hypotheses() {
        for t in tracks {
            let (w, m) = sums.entry(t.label.0).or_insert((0.0, SVector::zeros()));
            *w += weight;
            *m += t.state.mean * weight;
        }
    }
    let means: BTreeMap<u32, SVector<f64, S>> = sums.iter().map(|(l, (w, m))| (*l, m / *w)).collect();
    let mut spread: BTreeMap<u32, SMatrix<f64, S, S>> = BTreeMap::new();
    for (weight, tracks) in hypotheses() {
        for t in tracks {
            let d = t.state.mean - means[&t.label.0];
            *spread.entry(t.label.0).or_insert(SMatrix::zeros()) += (t.state.covariance + d * d.transpose()) * weight;
        }
    }
    for (label, (w, _)) in sums {
        out.insert(label, ObjectPosterior { existence: w, mean: means[&label], covariance: spread[&label] / w });
    }
}
