//! The reports of `experiment`: `runs.json` of `--runs`, `fifteen.json`, `scaling.json`, `debris.json` and the ablation's.

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// `runs.json` of `host-sim experiment --runs K`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RunsReport {
    /// Experiment name.
    pub experiment: String,
    /// The seeds, one per run.
    pub seeds: Vec<u64>,
    /// Each run's figures (the experiment's own record).
    pub runs: Vec<serde_json::Value>,
    /// Per numeric top-level figure, its spread over the runs.
    pub aggregate: BTreeMap<String, Spread>,
}

/// Mean, standard deviation (population), min and max of a figure over runs.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Spread {
    /// Mean.
    pub mean: f64,
    /// Standard deviation.
    pub std: f64,
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
}

/// Mean and largest time per scan.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Timing {
    /// Mean time per scan (ms).
    pub mean_ms_per_scan: f64,
    /// Largest time per scan (ms).
    pub max_ms_per_scan: f64,
}

/// `fifteen.json` of `experiment fifteen`: the figures, and one record per scan.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FifteenReport {
    /// The figures over the run.
    #[serde(flatten)]
    pub figures: FifteenFigures,
    /// One record per scan.
    pub per_scan: Vec<FifteenScan>,
}

/// The figures of `experiment fifteen`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FifteenFigures {
    /// `fifteen`.
    pub experiment: String,
    /// Seed.
    pub seed: u64,
    /// Scans.
    pub scans: usize,
    /// Fraction of scans whose R-FISST MAP hypothesis is HOMHT's.
    pub map_agreement: f64,
    /// Largest distance between the MAP estimates of R-FISST and HOMHT.
    pub max_map_estimate_difference: f64,
    /// Scans the reference ran.
    pub reference_scans: usize,
    /// Whether the reference's budget stopped it.
    pub reference_budget_reached: bool,
    /// Fraction of the reference's scans whose MAP hypothesis is R-FISST's; `null` when it ran none.
    pub map_agreement_reference: Option<f64>,
    /// R-FISST.
    pub rfisst: FifteenTracker,
    /// HOMHT.
    pub homht: FifteenHomht,
    /// The reference.
    pub reference: Timing,
}

/// R-FISST's figures in `experiment fifteen`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FifteenTracker {
    /// Mean GOSPA.
    pub mean_gospa: f64,
    /// Mean time per scan (ms).
    pub mean_ms_per_scan: f64,
    /// Largest time per scan (ms).
    pub max_ms_per_scan: f64,
}

/// HOMHT's figures in `experiment fifteen`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FifteenHomht {
    /// Mean GOSPA.
    pub mean_gospa: f64,
    /// Mean time per scan (ms).
    pub mean_ms_per_scan: f64,
    /// Largest time per scan (ms).
    pub max_ms_per_scan: f64,
    /// Scans it rejected.
    pub rejected_scans: usize,
    /// Its child budget per scan.
    pub max_children_per_scan: u64,
}

/// One scan of `fifteen.json`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FifteenScan {
    /// Scan index.
    pub scan: usize,
    /// Whether R-FISST's MAP hypothesis is HOMHT's.
    pub map_agreement_homht: bool,
    /// Whether it is the reference's; `null` when the reference did not run the scan.
    pub map_agreement_reference: Option<bool>,
    /// R-FISST's hypotheses.
    pub rfisst_hypotheses: usize,
    /// HOMHT's hypotheses.
    pub homht_hypotheses: usize,
}

/// `scaling.json` of `experiment scaling`: the figures, and one record per problem size.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ScalingReport {
    /// The figures over the sizes.
    #[serde(flatten)]
    pub figures: ScalingFigures,
    /// One record per size, smallest first.
    pub sizes: Vec<ScalingSize>,
}

/// The figures of `experiment scaling`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ScalingFigures {
    /// `scaling`.
    pub experiment: String,
    /// Seed.
    pub seed: u64,
    /// The smallest size from which R-FISST is faster at every larger size measured.
    pub crossover_children: Option<f64>,
    /// The same for pure sampling.
    pub pure_sampling_crossover_children: Option<f64>,
    /// Exhaustive time over R-FISST's at 10⁸ children, log-interpolated.
    pub speedup_at_1e8: Option<f64>,
    /// The largest size.
    pub largest_children: f64,
    /// Exhaustive enumeration's time budget per parent (s).
    pub exhaustive_budget_seconds: f64,
    /// The largest size exhaustive enumeration ran.
    pub exhaustive_broken_beyond: f64,
    /// Whether R-FISST found or beat the truth at every size.
    pub rfisst_found_truth_at_every_size: bool,
    /// The sizes where it did not.
    pub rfisst_sizes_truth_missed: Vec<f64>,
    /// The same with paper 003's 100,000 steps.
    pub rfisst_100k_found_truth_at_every_size: bool,
    /// The largest time of the 100,000-step runs (s).
    pub rfisst_100k_max_seconds: f64,
    /// The largest time of R-FISST (s).
    pub rfisst_max_seconds: f64,
    /// The default sampler.
    pub sampler: ScalingSampler,
}

/// The default sampler's settings in `scaling.json`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScalingSampler {
    /// Unrecorded steps per chain.
    pub burn_in: u32,
    /// Recorded steps per chain.
    pub steps: u32,
    /// Exhaustive limit.
    pub exhaustive_limit: u64,
    /// Exact chain start.
    pub exact_start: bool,
}

/// One problem size of `scaling.json`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScalingSize {
    /// Possible children A_N(m).
    pub children: f64,
    /// Objects N.
    pub objects: usize,
    /// Measurements m.
    pub measurements: usize,
    /// Exhaustive enumeration's time (s); `null` beyond its budget.
    pub exhaustive_seconds: Option<f64>,
    /// R-FISST's median time (s).
    pub rfisst_seconds: f64,
    /// Whether R-FISST found or beat the truth.
    pub rfisst_found_truth: bool,
    /// The 100,000-step run's time (s).
    pub rfisst_100k_seconds: f64,
    /// Whether it found or beat the truth.
    pub rfisst_100k_found_truth: bool,
    /// Pure sampling's median time (s).
    pub pure_sampling_seconds: f64,
}

/// `debris.json` of `experiment debris`: the figures, and one record per scan.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DebrisReport {
    /// The figures over the run.
    #[serde(flatten)]
    pub figures: DebrisFigures,
    /// One record per scan.
    pub per_scan: Vec<DebrisScan>,
}

/// The figures of `experiment debris`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DebrisFigures {
    /// `debris`.
    pub experiment: String,
    /// Seed.
    pub seed: u64,
    /// Scans.
    pub scans: usize,
    /// Fewest possible children of a MAP parent.
    pub min_possible_children_per_map_parent: f64,
    /// Most possible children of a MAP parent.
    pub max_possible_children_per_map_parent: f64,
    /// Fraction of scans whose truth association R-FISST found or beat.
    pub truth_association_found_fraction: f64,
    /// The same with 100,000 steps.
    pub truth_association_found_fraction_100k_steps: f64,
    /// R-FISST.
    pub rfisst: DebrisRfisst,
    /// HOMHT with the same time budget.
    pub homht: DebrisHomht,
    /// True number of objects at the last scan.
    pub true_final_cardinality: f64,
}

/// R-FISST's figures in `experiment debris`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DebrisRfisst {
    /// Mean GOSPA.
    pub mean_gospa: f64,
    /// Expected number of objects at the end.
    pub final_expected_cardinality: f64,
    /// Mean time per scan (ms).
    pub mean_ms_per_scan: f64,
    /// Largest time per scan (ms).
    pub max_ms_per_scan: f64,
}

/// HOMHT's figures in `experiment debris`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DebrisHomht {
    /// Mean GOSPA.
    pub mean_gospa: f64,
    /// Expected number of objects at the end.
    pub final_expected_cardinality: f64,
    /// Mean time per scan (ms).
    pub mean_ms_per_scan: f64,
    /// Its child budget per scan.
    pub children_budget_per_scan: u64,
    /// Scans it rejected.
    pub rejected_scans: usize,
}

/// One scan of `debris.json`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DebrisScan {
    /// Scan index.
    pub scan: usize,
    /// R-FISST's GOSPA.
    pub rfisst_gospa: Option<f64>,
    /// R-FISST's expected number of objects.
    pub rfisst_expected_cardinality: f64,
    /// HOMHT's GOSPA.
    pub homht_gospa: Option<f64>,
    /// HOMHT's expected number of objects.
    pub homht_expected_cardinality: f64,
    /// True number of objects.
    pub true_cardinality: f64,
    /// The truth-association check of the MAP parent before the scan.
    pub check: AssociationCheck,
}

/// The truth-association check of a MAP parent: only `possible_children` (0) when there is no parent.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct AssociationCheck {
    /// Possible children A_N(m) of the parent.
    pub possible_children: f64,
    /// The outcome, when there is a parent.
    #[serde(flatten)]
    pub outcome: Option<CheckOutcome>,
}

/// What the generator found for a MAP parent.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CheckOutcome {
    /// Objects in view (columns).
    pub objects_in_view: usize,
    /// Measurements.
    pub measurements: usize,
    /// Whether the default generator offered the truth association.
    pub truth_offered: bool,
    /// Whether it offered it or a child at least as likely.
    pub truth_found_or_beaten: bool,
    /// ln(best child's weight / truth's).
    pub best_over_truth_log: f64,
    /// Whether 100,000 steps offered it or a child at least as likely.
    pub truth_found_or_beaten_100k_steps: bool,
    /// The same ratio with 100,000 steps.
    pub best_over_truth_log_100k_steps: f64,
}

/// One variant of `ablation.json` (the file maps each variant's name to one).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AblationVariant {
    /// Clusters on.
    pub clusters: bool,
    /// Exact start on.
    pub exact_start: bool,
    /// The fifty-object run.
    pub fifty: AblationFifty,
    /// The debris crossing.
    pub debris: AblationDebris,
    /// Sizes of the scaling family checked.
    pub scaling_sizes: usize,
    /// The sizes whose truth association was missed.
    pub scaling_truth_missed_at: Vec<f64>,
}

/// The fifty-object figures of an ablation variant (keys of its `summary.json`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AblationFifty {
    /// Mean GOSPA.
    pub mean_gospa: Option<f64>,
    /// Expected number of objects at the end.
    pub final_expected_cardinality: f64,
    /// Births confirmed.
    pub births_confirmed: usize,
    /// Red stars in view.
    pub in_view_red_stars: usize,
    /// Misses in view after confirmation.
    pub in_view_misses_after_confirmation: usize,
    /// Mean captured mass.
    pub mean_captured_mass: f64,
    /// Smallest captured mass.
    pub min_captured_mass: f64,
    /// Mean time per scan (ms).
    pub mean_ms_per_scan: f64,
    /// Largest time per scan (ms).
    pub max_ms_per_scan: f64,
}

/// The debris figures of an ablation variant.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AblationDebris {
    /// Fraction of scans whose truth association was found or beaten.
    pub truth_association_found_fraction: f64,
    /// Mean GOSPA.
    pub mean_gospa: f64,
    /// Expected number of objects at the end.
    pub final_expected_cardinality: f64,
    /// Mean time per scan (ms).
    pub mean_ms_per_scan: f64,
    /// Largest time per scan (ms).
    pub max_ms_per_scan: f64,
}
