//! The lines of `scans.jsonl`: per scan, the MAP tracks, the hypotheses and the labels' existence.

use crate::pipeline::snapshot::TrackOut;
use serde::{Deserialize, Serialize};

/// One line of `scans.jsonl`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScanLine {
    /// Scan index.
    pub scan: usize,
    /// Scan time (s).
    pub time: f64,
    /// Expected number of objects.
    pub expected_cardinality: f64,
    /// Hypotheses held (all of them, not only those written).
    pub hypotheses_total: usize,
    /// The best hypotheses, at most `--max-hypotheses-out`.
    pub hypotheses: Vec<ScanHypothesis>,
    /// The tracks of the written hypotheses.
    pub tracks: Vec<TrackOut>,
    /// Existence probability per label.
    pub existence: Vec<LabelExistence>,
    /// Tracks the core dropped for a numerical failure at this scan (`numerical_drops` in summary.json
    /// names them).
    #[serde(default)]
    pub numerical_drops: usize,
}

/// A hypothesis of `scans.jsonl`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScanHypothesis {
    /// Normalised weight.
    pub weight: f64,
    /// Indices into the line's `tracks`.
    pub tracks: Vec<usize>,
}

/// A label's existence probability.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LabelExistence {
    /// Label.
    pub label: u32,
    /// Existence probability.
    pub existence: f64,
}
