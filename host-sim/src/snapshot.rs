//! A tracker-independent picture of the posterior after a scan: hypotheses (weights and track indices)
//! and the distinct tracks they hold. Both the core tracker and the reference produce one, so outputs and
//! comparisons are written once.

use serde::Serialize;
use tracker_core::{MeasurementModel, MotionModel, Tracker};

/// One track.
#[derive(Debug, Clone, PartialEq, Serialize)]
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
    /// produce the same key (digest §1.1, Theorem 1: tracks are almost surely distinct).
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
