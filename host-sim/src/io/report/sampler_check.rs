//! The report of `sampler-check`: the sampler's scores against the exact posterior, and its settings.

use serde::{Deserialize, Serialize};

/// The report of `host-sim sampler-check`: the default sampler's scores at the top level.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SamplerCheckReport {
    /// The default sampler's scores.
    #[serde(flatten)]
    pub default: SamplerScores,
    /// Random cases.
    pub cases: usize,
    /// Seed of the cases.
    pub seed: u64,
    /// Mean children of the exhaustive reference per case.
    pub mean_children_per_case: f64,
    /// Most children of a case.
    pub max_children_per_case: f64,
    /// The default sampler's settings.
    pub sampler: SamplerSettings,
    /// The scores of pure sampling (no clusters).
    pub pure_sampling: SamplerScores,
}

/// A sampler configuration's scores over the cases of `sampler-check`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SamplerScores {
    /// Mean captured mass.
    pub mean_captured_mass: f64,
    /// Smallest captured mass.
    pub min_captured_mass: f64,
    /// The case index of the minimum, to replay it.
    pub min_captured_case: Option<usize>,
    /// Mean L1 distance between the weights.
    pub mean_weight_l1: f64,
    /// Fraction of cases whose best exact hypothesis was found.
    pub top1_found_fraction: f64,
    /// Mean sampler steps per case.
    pub mean_sampler_steps_per_case: f64,
}

/// The settings of `SamplerConfig` written to reports.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SamplerSettings {
    /// Unrecorded steps per chain.
    pub burn_in: u32,
    /// Recorded steps per chain.
    pub steps: u32,
    /// The proposal (`Informed`, ...).
    pub proposal: String,
    /// Clusters.
    pub clusters: bool,
    /// Exhaustive limit.
    pub exhaustive_limit: u64,
    /// Exact chain start.
    pub exact_start: bool,
}
