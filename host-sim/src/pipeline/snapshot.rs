//! A tracker-independent picture of the posterior after a scan: hypotheses (weights and track indices)
//! and the distinct tracks they hold. Both the core tracker and the reference produce one, so outputs and
//! comparisons are written once; and the MAP track of an orbital posterior ([`Track6`]).

use serde::{Deserialize, Serialize};
use std::collections::{HashMap, HashSet};
use tracker_core::{MeasurementModel, MotionModel, Tracker};

/// One track.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TrackOut {
    /// Object label.
    pub label: u32,
    /// Mean (x, y, vx, vy).
    pub mean: [f64; 4],
    /// Covariance (row-major 4 × 4; symmetric).
    pub covariance: [[f64; 4]; 4],
    /// Total weight of the hypotheses that hold this track.
    pub existence: f64,
}

/// One MAP track of a 3-D (orbital) posterior: what the OEM and the orbital run read of it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Track6 {
    /// Label.
    pub label: u32,
    /// Mean (km, km/s).
    pub mean: [f64; 6],
    /// Existence probability of the label.
    pub existence: f64,
    /// Covariance (row-major; km², km²/s, km²/s²).
    pub covariance: [[f64; 6]; 6],
}

/// One hypothesis.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HypothesisOut {
    /// Normalised weight.
    pub weight: f64,
    /// ln of the weight.
    #[serde(skip)]
    pub log_weight: f64,
    /// Indices into the snapshot's tracks, in label order.
    pub tracks: Vec<usize>,
}

/// The posterior after a scan.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct Snapshot {
    /// Hypotheses, best first.
    pub hypotheses: Vec<HypothesisOut>,
    /// Distinct tracks.
    pub tracks: Vec<TrackOut>,
}

impl Snapshot {
    /// The snapshot of a core tracker.
    pub fn of<M, G, const H: usize, const N: usize, const Z: usize, const K: usize, const B: usize>(
        tracker: &Tracker<f64, M, G, 4, 2, H, N, Z, K, B>,
    ) -> Self
    where
        M: MotionModel<f64, 4>,
        G: MeasurementModel<f64, 4, 2>,
    {
        let tracks = tracker
            .tracks()
            .iter()
            .map(|t| TrackOut {
                label: t.label.0,
                mean: t.state.mean.into(),
                covariance: t.state.covariance.into(),
                existence: t.existence,
            })
            .collect();
        let hypotheses = tracker
            .hypotheses()
            .map(|h| HypothesisOut {
                weight: h.weight(),
                log_weight: h.log_weight(),
                tracks: h.slots().iter().map(|&s| s as usize).collect(),
            })
            .collect();
        Snapshot { hypotheses, tracks }
    }

    /// The MAP hypothesis's tracks.
    pub fn map_tracks(&self) -> Vec<&TrackOut> {
        self.hypotheses.first().map(|h| h.tracks.iter().map(|&t| &self.tracks[t]).collect()).unwrap_or_default()
    }

    /// Expected number of objects Σ w_h N_h.
    pub fn expected_cardinality(&self) -> f64 {
        self.hypotheses.iter().map(|h| h.weight * h.tracks.len() as f64).sum()
    }

    /// Existence probability per label (summed over the tracks with that label), sorted by label.
    pub fn label_existence(&self) -> Vec<(u32, f64)> {
        let mut out: Vec<(u32, f64)> = vec![];
        for t in &self.tracks {
            match out.iter_mut().find(|(label, _)| *label == t.label) {
                Some(entry) => entry.1 += t.existence,
                None => out.push((t.label, t.existence)),
            }
        }
        out.sort_by_key(|e| e.0);
        out
    }

    /// A key that identifies hypothesis `index` by the exact bits of its tracks' states, independent of
    /// labels and of track order: two trackers that run the same EKF code on the same association history
    /// produce the same key (docs/maths.md §2.1, [000] Theorem 1: tracks are almost surely distinct).
    pub fn hypothesis_key(&self, index: usize) -> Vec<u64> {
        let mut states: Vec<Vec<u64>> = self.hypotheses[index]
            .tracks
            .iter()
            .map(|&t| {
                let track = &self.tracks[t];
                track.mean.iter().chain(track.covariance.iter().flatten()).map(|v| v.to_bits()).collect()
            })
            .collect();
        states.sort();
        states.concat()
    }
}

/// How much of an exact posterior an approximate one holds, both snapshots of the same scan, hypotheses
/// matched by [`Snapshot::hypothesis_key`]. Sums run in hypothesis order, so the figures repeat bit for bit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PosteriorMatch {
    /// Exact mass of the approximation's hypotheses.
    pub captured_mass: f64,
    /// Σ |w_approx − w_exact| over the union of both sets of hypotheses.
    pub weight_l1: f64,
    /// The largest exact weight among the approximation's hypotheses (0 when it holds none of them).
    pub best_exact_weight_found: f64,
    /// The exact weight of the approximation's MAP hypothesis (0 when the exact posterior lacks it).
    pub exact_weight_of_map: f64,
}

/// Compares `approx` with `exact` (see [`PosteriorMatch`]).
pub fn match_posteriors(exact: &Snapshot, approx: &Snapshot) -> PosteriorMatch {
    // Only the approximation's keys are stored: the exact posterior (the reference's) may be large, and
    // its keys are made one at a time.
    let approx: Vec<(f64, Vec<u64>)> =
        approx.hypotheses.iter().enumerate().map(|(i, h)| (h.weight, approx.hypothesis_key(i))).collect();
    let exact = exact.hypotheses.iter().enumerate().map(|(i, h)| (h.weight, exact.hypothesis_key(i)));
    match_keys(exact, &approx)
}

/// [`match_posteriors`] for hypotheses given as (weight, key) pairs, best first, the keys made as
/// [`Snapshot::hypothesis_key`] makes them (or any other function of the tracks' states alone).
pub fn match_keys(exact: impl IntoIterator<Item = (f64, Vec<u64>)>, approx: &[(f64, Vec<u64>)]) -> PosteriorMatch {
    let in_approx: HashSet<&[u64]> = approx.iter().map(|(_, k)| k.as_slice()).collect();
    let mut exact_weight: HashMap<&[u64], f64> = HashMap::new();
    let mut exact_only = -0.0; // the neutral element of `f64::sum`
    for (weight, key) in exact {
        match in_approx.get(key.as_slice()) {
            Some(&k) => {
                exact_weight.insert(k, weight);
            }
            None => exact_only += weight,
        }
    }
    let found = |k: &Vec<u64>| exact_weight.get(k.as_slice()).copied();
    let captured_mass = approx.iter().filter_map(|(_, k)| found(k)).sum();
    let mut weight_l1: f64 = approx.iter().map(|(w, k)| (w - found(k).unwrap_or(0.0)).abs()).sum();
    weight_l1 += exact_only;
    PosteriorMatch {
        captured_mass,
        weight_l1,
        best_exact_weight_found: approx.iter().filter_map(|(_, k)| found(k)).fold(0.0, f64::max),
        exact_weight_of_map: approx.first().and_then(|(_, k)| found(k)).unwrap_or(0.0),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn snapshot(hypotheses: &[(f64, &[f64])]) -> Snapshot {
        // One track per distinct x; a hypothesis holds the tracks at the given x positions.
        let mut tracks: Vec<TrackOut> = vec![];
        let hypotheses = hypotheses
            .iter()
            .map(|&(weight, xs)| {
                let indices = xs
                    .iter()
                    .map(|&x| {
                        tracks.iter().position(|t| t.mean[0] == x).unwrap_or_else(|| {
                            tracks.push(TrackOut {
                                label: tracks.len() as u32,
                                mean: [x, 0.0, 0.0, 0.0],
                                covariance: [
                                    [1.0, 0.0, 0.0, 0.0],
                                    [0.0, 1.0, 0.0, 0.0],
                                    [0.0, 0.0, 1.0, 0.0],
                                    [0.0, 0.0, 0.0, 1.0],
                                ],
                                existence: 0.0,
                            });
                            tracks.len() - 1
                        })
                    })
                    .collect();
                HypothesisOut { weight, log_weight: weight.ln(), tracks: indices }
            })
            .collect();
        Snapshot { hypotheses, tracks }
    }

    #[test]
    fn posteriors_match_by_hypothesis_content() {
        let exact = snapshot(&[(0.5, &[1.0, 2.0]), (0.3, &[1.0]), (0.2, &[])]);
        // Same hypotheses, other order and other track indices: a full match.
        let same = snapshot(&[(0.3, &[1.0]), (0.5, &[2.0, 1.0]), (0.2, &[])]);
        let m = match_posteriors(&exact, &same);
        assert_eq!(
            (m.captured_mass, m.weight_l1, m.best_exact_weight_found, m.exact_weight_of_map),
            (1.0, 0.0, 0.5, 0.3)
        );
        // Two of three hypotheses, renormalised, plus one the exact posterior lacks.
        let approx = snapshot(&[(0.6, &[1.0, 2.0]), (0.3, &[1.0]), (0.1, &[3.0])]);
        let m = match_posteriors(&exact, &approx);
        assert_eq!(m.captured_mass, 0.8);
        assert!((m.weight_l1 - (0.1 + 0.0 + 0.1 + 0.2)).abs() < 1e-15);
        assert_eq!((m.best_exact_weight_found, m.exact_weight_of_map), (0.5, 0.5));
        // Nothing in common.
        let m = match_posteriors(&exact, &snapshot(&[(1.0, &[4.0])]));
        assert_eq!((m.captured_mass, m.best_exact_weight_found, m.exact_weight_of_map), (0.0, 0.0, 0.0));
        assert!((m.weight_l1 - 2.0).abs() < 1e-15);
    }
}
