//! The typed records of every JSON file host-sim writes: `summary.json` of `run` (and of `experiment
//! fifty`), the lines of `scans.jsonl`, `compare.json`, the `soak` and `sampler-check` reports,
//! `runs.json` of `experiment --runs` and `perf.json` of `perf`. Each field is one key of the file, with the same name; a value
//! that may be unknown is an `Option` (written as `null`). Reading a file back is `serde_json::from_str`
//! into the same type.

use crate::pipeline::snapshot::TrackOut;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// `summary.json` of `host-sim run` (and `experiment fifty`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RunSummary {
    /// Scenario name.
    pub scenario: String,
    /// Tracker (`rfisst`, `homht` or `reference`).
    pub tracker: String,
    /// Capacity profile, `unbounded` for the reference.
    pub profile: String,
    /// Number of scans.
    pub scans: usize,
    /// Mean GOSPA of the MAP estimates; `null` without truth.
    pub mean_gospa: Option<f64>,
    /// Mean OSPA of the MAP estimates; `null` without truth.
    pub mean_ospa: Option<f64>,
    /// GOSPA cut-off c.
    pub gospa_cutoff: f64,
    /// GOSPA order p.
    pub gospa_order: f64,
    /// Error bound.
    pub error_bound: f64,
    /// Expected number of objects after the last scan (of the prior when there is no scan).
    pub final_expected_cardinality: f64,
    /// Objects of the MAP hypothesis after the last scan (of the prior when there is no scan).
    pub final_map_cardinality: usize,
    /// True number of objects at the last scan.
    pub true_final_cardinality: Option<usize>,
    /// Births: their confirmation, detections to confirmation and false tracks.
    #[serde(flatten)]
    pub births: BirthsSummary,
    /// Label switches along GOSPA's assignment.
    pub label_switches: usize,
    /// Confirmed objects in view without a MAP estimate within the error bound, summed over scans.
    pub in_view_misses_after_confirmation: usize,
    /// MAP estimates in view outside the error bound of every object, summed over scans.
    pub in_view_red_stars: usize,
    /// The same out of view.
    pub out_of_view_red_stars: usize,
    /// Mean time of an accepted scan (ms).
    pub mean_ms_per_scan: f64,
    /// Largest time of an accepted scan (ms).
    pub max_ms_per_scan: f64,
    /// Largest number of hypotheses.
    pub peak_hypotheses: usize,
    /// Mean captured mass of the accepted scans.
    pub mean_captured_mass: f64,
    /// Smallest captured mass of the accepted scans.
    pub min_captured_mass: f64,
    /// The scans the tracker rejected.
    pub rejected_scans: Vec<RejectedScan>,
    /// Scans at which the reference's memory budget forced pruning.
    pub reference_budget_reached_scans: Vec<usize>,
    /// The process's peak resident memory (VmHWM, KiB) when the summary was written, where the OS tells it.
    pub peak_resident_kib: Option<u64>,
    /// Version 2 (3-D) scenarios only: the number of sensors. Absent from version 1 runs.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sensors: Option<usize>,
}

/// The births of a run, flattened into its summary (docs/scenario-format.md, summary keys).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
pub struct BirthsSummary {
    /// Born objects in the truth.
    pub births_total: usize,
    /// Born objects confirmed.
    pub births_confirmed: usize,
    /// Per born object, the scan of its confirmation.
    pub birth_confirmation_scans: Vec<BirthConfirmation>,
    /// Per born object, detections and scans from its first detection to its confirmation.
    #[serde(default)]
    pub birth_confirmations: Vec<BirthRecord>,
    /// Mean detections to confirmation of the confirmed births; `null` when none is.
    #[serde(default)]
    pub mean_detections_to_confirm: Option<f64>,
    /// Largest detections to confirmation; `null` when no birth is confirmed.
    #[serde(default)]
    pub max_detections_to_confirm: Option<usize>,
    /// MAP labels confirmed at some scan and never within the error bound of an object; `null` without
    /// truth.
    #[serde(default)]
    pub false_tracks: Option<usize>,
}

/// A born object and the scan at which it was confirmed (`null`: never).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BirthConfirmation {
    /// Truth id.
    pub object: u64,
    /// Scan index.
    pub scan: Option<usize>,
}

/// A born object's way to confirmation ([`crate::eval::births`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BirthRecord {
    /// Truth id.
    pub object: u64,
    /// Scan of its first measurement (`null`: never detected).
    pub first_detection_scan: Option<usize>,
    /// Scan of its confirmation (`null`: never).
    pub confirmation_scan: Option<usize>,
    /// Its measurements up to and including the confirmation scan (`null`: never confirmed).
    pub detections_to_confirm: Option<usize>,
    /// Scans from the first detection to the confirmation, both counted (`null`: never confirmed).
    pub scans_to_confirm: Option<usize>,
}

/// A scan the tracker rejected.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RejectedScan {
    /// Scan index.
    pub scan: usize,
    /// The tracker's message.
    pub error: String,
}

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

/// `compare.json`: the figures printed by `host-sim compare`, and the per-scan records.
// `flatten` does not combine with `deny_unknown_fields`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CompareReport {
    /// The figures over the run.
    #[serde(flatten)]
    pub summary: CompareSummary,
    /// One record per scan.
    pub per_scan: Vec<CompareScan>,
}

/// The figures of `compare.json` over the run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CompareSummary {
    /// Scenario name.
    pub scenario: String,
    /// The bounded tracker.
    pub bounded_tracker: String,
    /// Its capacity profile.
    pub profile: String,
    /// Number of scans.
    pub scans: usize,
    /// Mean over scans of the reference's mass on the bounded tracker's hypotheses.
    pub mean_captured_mass: f64,
    /// Its smallest value.
    pub min_captured_mass: f64,
    /// Mean L1 distance between the weights.
    pub mean_weight_l1: f64,
    /// Fraction of scans whose MAP hypotheses agree.
    pub map_agreement: f64,
    /// The bounded tracker's figures.
    pub bounded: CompareSide,
    /// The reference's figures.
    pub reference: CompareSide,
}

/// One tracker's figures in `compare.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompareSide {
    /// Tracker name.
    pub tracker: String,
    /// Mean GOSPA; `null` without truth.
    pub mean_gospa: Option<f64>,
    /// Mean time per scan (ms).
    pub mean_ms_per_scan: f64,
    /// Largest time per scan (ms).
    pub max_ms_per_scan: f64,
    /// The reference only: scans at which its memory budget forced pruning.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub budget_reached_scans: Option<Vec<usize>>,
}

/// One scan of `compare.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompareScan {
    /// Scan index.
    pub scan: usize,
    /// Scan time (s).
    pub time: f64,
    /// The reference's mass on the bounded tracker's hypotheses.
    pub captured_mass: f64,
    /// Σ |w_bounded − w_reference|.
    pub weight_l1: f64,
    /// Whether the bounded MAP hypothesis has the reference's largest weight.
    pub map_agreement: bool,
    /// Hypotheses of the bounded tracker.
    pub bounded_hypotheses: usize,
    /// Hypotheses of the reference.
    pub reference_hypotheses: usize,
    /// Time of the bounded tracker (ms).
    pub bounded_ms: f64,
    /// Time of the reference (ms).
    pub reference_ms: f64,
    /// The bounded tracker's error, when it rejected the scan.
    pub bounded_error: Option<String>,
    /// The reference's error, when it rejected the scan.
    pub reference_error: Option<String>,
}

/// The report of `host-sim soak`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SoakReport {
    /// The scenario (`planar`, `radar-leo`, `optical-geo`).
    pub scenario: String,
    /// Scans run.
    pub scans: u64,
    /// Seed.
    pub seed: u64,
    /// Non-finite values seen, summed over scans.
    pub nan_count: u64,
    /// Scans after which some value was not finite.
    pub non_finite_scans: u64,
    /// The first such scan (1-based).
    pub first_non_finite_scan: Option<u64>,
    /// Largest number of hypotheses.
    pub max_hypotheses: usize,
    /// Largest time per scan (ms).
    pub max_ms_per_scan: f64,
    /// Mean time per scan (ms).
    pub mean_ms_per_scan: f64,
    /// Median time per scan (ms).
    pub p50_ms_per_scan: f64,
    /// 99th percentile of the time per scan (ms).
    pub p99_ms_per_scan: f64,
    /// Largest over median time per scan.
    pub max_over_median: f64,
    /// Mean time per scan over the first tenth of the scans (ms).
    pub mean_ms_per_scan_first_tenth: f64,
    /// Mean time per scan over the last tenth of the scans (ms).
    pub mean_ms_per_scan_last_tenth: f64,
    /// Peak resident memory (VmHWM, KiB) after the first scan, when the system reports it.
    pub peak_resident_kib_start: Option<u64>,
    /// Peak resident memory (VmHWM, KiB) after the last scan.
    pub peak_resident_kib_end: Option<u64>,
    /// Tracks dropped for a numerical failure, summed.
    pub numerical_drops: u64,
    /// Whether the objects stay tracked (3-D soaks, whose objects live for the whole run).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tracking: Option<SoakTracking>,
    /// Step errors by variant.
    pub errors_by_kind: BTreeMap<String, u64>,
    /// The first step error.
    pub first_error: Option<SoakError>,
    /// Track store high-water mark.
    pub track_store_high_water: usize,
    /// Track store capacity K.
    pub track_store_capacity: usize,
    /// Hypothesis capacity H.
    pub hypothesis_capacity: usize,
    /// Most measurements in a scan.
    pub max_measurements_per_scan: usize,
    /// Measurement capacity Z.
    pub measurement_capacity: usize,
    /// Measurements over the run.
    pub measurements: u64,
    /// Births beyond the object capacity, summed.
    pub births_beyond_object_capacity: u64,
    /// Children dropped for the track store, summed.
    pub children_dropped_for_store: u64,
    /// What the truth did.
    pub truth: SoakTruth,
    /// Expected number of objects at the end.
    pub final_expected_cardinality: f64,
    /// Mean |expected − true number of objects|.
    pub mean_abs_cardinality_error: f64,
    /// Largest |expected − true number of objects|.
    pub max_abs_cardinality_error: f64,
    /// Wall-clock time of the run (s).
    pub wall_seconds: f64,
    /// The scenario and tracker.
    pub setup: SoakSetup,
}

/// Whether a 3-D soak's objects stay tracked: an object is tracked at a scan when the MAP hypothesis holds
/// its label with a position within `error_bound_km` of the truth.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SoakTracking {
    /// The bound (km): the scenario's `evaluation.error_bound`.
    pub error_bound_km: f64,
    /// True objects (all alive for the whole run).
    pub objects: usize,
    /// Objects tracked after the last scan.
    pub final_tracked: usize,
    /// Fewest objects tracked after any scan.
    pub min_tracked: usize,
    /// The first scan (1-based) with that fewest.
    pub min_tracked_scan: u64,
    /// Mean number tracked over the scans.
    pub mean_tracked: f64,
    /// Mean number tracked over the last tenth of the scans.
    pub mean_tracked_last_tenth: f64,
    /// Object-scans with the object in the scan's field of view.
    pub in_view: u64,
    /// The fraction of them tracked after the scan.
    pub in_view_tracked_fraction: f64,
    /// The same over the last tenth of the scans.
    pub in_view_tracked_fraction_last_tenth: f64,
    /// Median MAP position error (km) over the objects after the last scan.
    pub final_median_position_error_km: f64,
    /// Labels missing from the MAP hypothesis after the last scan.
    pub final_missing_labels: usize,
    /// Detections dropped because their noisy value fell outside the field of view.
    pub dropped_outside_field_of_view: u64,
    /// Simulated time (days).
    pub simulated_days: f64,
}

/// The first step error of a soak.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SoakError {
    /// Scan (1-based).
    pub scan: u64,
    /// The error's message.
    pub message: String,
}

/// The soak's true objects.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SoakTruth {
    /// Objects known to the prior.
    pub initial_objects: usize,
    /// Births.
    pub births: u64,
    /// Deaths.
    pub deaths: u64,
    /// Most objects alive at once.
    pub max_alive: usize,
    /// Objects alive at the end.
    pub final_alive: usize,
}

/// The soak's scenario and tracker, in words and numbers.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SoakSetup {
    /// The tracker.
    pub tracker: String,
    /// The motion model.
    pub motion: String,
    /// The sensor.
    pub sensor: String,
    /// Seconds between scans.
    pub scan_interval_s: f64,
    /// True birth probability per scan.
    pub birth_rate_per_scan: f64,
    /// True death probability per object and scan.
    pub death_rate_per_object_per_scan: f64,
    /// The tracker's α per cell.
    pub tracker_birth_probability_per_cell: f64,
    /// The tracker's birth cells.
    pub tracker_birth_cells: usize,
    /// The tracker's β.
    pub tracker_death_probability: f64,
}

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

/// `perf.json` of `host-sim perf` (every key is documented in `perf.rs`). The fields of each record are
/// declared in alphabetical order, the order in which the file has always been written.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PerfReport {
    /// The figures behind the headline ones.
    pub details: PerfDetails,
    /// Median ns per `ekf::update` of a two-body state.
    pub ekf_update_ns: f64,
    /// Time of exhaustive enumeration over the default sampler's on the dense 7 × 9 matrix.
    pub exhaustive_over_mcmc_at_1e6_children: f64,
    /// Median ns per step of the floor loop.
    pub floor_ns_per_step: f64,
    /// Gibbs's time over the sampler's at equal captured mass, median over the matrices.
    pub gibbs_over_mcmc_time_at_equal_mass: f64,
    /// The machine and toolchain.
    pub machine: PerfMachine,
    /// Median ns per step of the default (informed) Metropolis chain.
    pub mcmc_ns_per_step: f64,
    /// `mcmc_ns_per_step` over `floor_ns_per_step`.
    pub mcmc_over_floor: f64,
    /// Murty's time over the sampler's at equal captured mass, median over the matrices.
    pub murty_over_mcmc_time_at_equal_mass: f64,
    /// Median over scans of the time of `step` on `fifty-birth-death` (ms).
    pub step_ms_fifty: f64,
    /// Median over scans of the time of `step_scan` on an `optical-geo` scenario (ms).
    pub step_ms_optical_geo: f64,
    /// Median over scans of the time of `step_scan` on a `radar-leo` excerpt (ms).
    pub step_ms_radar_leo: f64,
    /// `size_of::<SsaTracker<f64>>()`.
    pub tracker_bytes_default: usize,
    /// `size_of::<SsaTracker<f32>>()`.
    pub tracker_bytes_f32: usize,
}

/// `details` of `perf.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PerfDetails {
    /// Median ns per `ekf::innovation`.
    pub ekf_innovation_ns: f64,
    /// Median ns per constant-velocity `ekf::predict`.
    pub ekf_predict_cv_ns: f64,
    /// Median ns per two-body `ekf::predict` (dt = 60 s).
    pub ekf_predict_two_body_ns: f64,
    /// Smallest sample of `ekf_update_ns`.
    pub ekf_update_ns_min: f64,
    /// Exhaustive enumeration against the sampler.
    pub exhaustive: PerfExhaustive,
    /// The fifty-object scenario.
    pub fifty: PerfFifty,
    /// Smallest sample of `floor_ns_per_step`.
    pub floor_ns_per_step_min: f64,
    /// Gibbs against the sampler.
    pub gibbs: PerfGibbs,
    /// Median ns per step under the informed proposal (= `mcmc_ns_per_step`).
    pub mcmc_ns_per_step_informed: f64,
    /// Smallest sample of `mcmc_ns_per_step`.
    pub mcmc_ns_per_step_min: f64,
    /// Median ns per step under the move-or-swap proposal.
    pub mcmc_ns_per_step_move_or_swap: f64,
    /// Median ns per step under the paper's proposal.
    pub mcmc_ns_per_step_paper: f64,
    /// `mcmc_ns_per_step_min` over `floor_ns_per_step_min`.
    pub mcmc_over_floor_of_minima: f64,
    /// Samples of each chain figure.
    pub mcmc_samples: usize,
    /// Murty against the sampler.
    pub murty: PerfMurty,
    /// The `optical-geo` scenario.
    pub optical_geo: PerfSsa,
    /// The `radar-leo` excerpt.
    pub radar_leo: PerfSsa,
    /// Measurement rounds.
    pub rounds: usize,
    /// Wall-clock time of the whole run (s).
    pub seconds: f64,
}

/// `details.exhaustive` of `perf.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PerfExhaustive {
    /// Best log-weight found by exhaustive enumeration.
    pub best_log_weight_exhaustive: f64,
    /// Best log-weight found by the sampler.
    pub best_log_weight_sampler: f64,
    /// Number of children, as a decimal string (a `u128`).
    pub children: String,
    /// Median time of the enumeration (ms).
    pub exhaustive_ms: f64,
    /// The matrix, in words.
    pub matrix: String,
    /// Median time of the sampler (µs).
    pub sampler_us: f64,
}

/// `details.fifty` of `perf.json`: per-scan times (each the median over the passes).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PerfFifty {
    /// Largest per-scan time (ms).
    pub max_ms: f64,
    /// Mean per-scan time (ms).
    pub mean_ms: f64,
    /// 90th percentile of the per-scan times (ms).
    pub p90_ms: f64,
    /// Passes over the scenario.
    pub passes: usize,
    /// Scans the tracker rejected in the last pass.
    pub rejected_scans_last_pass: usize,
    /// Scans of the scenario.
    pub scans: usize,
}

/// `details.radar_leo` and `details.optical_geo` of `perf.json`: per-scan times of the 3-D R-FISST tracker
/// (each the median over the passes).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PerfSsa {
    /// Largest per-scan time (ms).
    pub max_ms: f64,
    /// Mean per-scan time (ms).
    pub mean_ms: f64,
    /// Median per-scan time (ms).
    pub median_ms: f64,
    /// Passes over the scans.
    pub passes: usize,
    /// The capacity profile `run` chooses for the scenario.
    pub profile: String,
    /// Scans the tracker rejected in the last pass.
    pub rejected_scans_last_pass: usize,
    /// Scans timed (the first of the scenario).
    pub scans: usize,
    /// Scans of the whole scenario.
    pub scans_in_scenario: usize,
}

/// `details.murty` of `perf.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PerfMurty {
    /// Per matrix.
    pub cases: Vec<PerfMurtyCase>,
    /// The matrices and generators, in words.
    pub matrices: String,
    /// Largest ratio.
    pub ratio_max: f64,
    /// Median ratio per matrix shape.
    pub ratio_median_by_shape: Vec<PerfMurtyShape>,
    /// Smallest ratio.
    pub ratio_min: f64,
}

/// One matrix of `details.murty.cases`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PerfMurtyCase {
    /// Its shape, in words.
    pub matrix: String,
    /// Murty's children needed to capture the sampler's mass.
    pub murty_children_for_equal_mass: usize,
    /// Median time of those Murty children (µs).
    pub murty_us: f64,
    /// `murty_us` over `sampler_us`.
    pub ratio: f64,
    /// Log-weight of the sampler's best child minus the MAP's (nats).
    pub sampler_best_minus_map_nats: f64,
    /// Fraction of the exact best-32 mass the sampler captured.
    pub sampler_captured_mass_of_best_32: f64,
    /// Children the sampler produced.
    pub sampler_children: usize,
    /// Median time of the sampler (µs).
    pub sampler_us: f64,
    /// Seed of the crossing matrix.
    pub seed: u64,
}

/// The median Murty ratio of one matrix shape.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PerfMurtyShape {
    /// The shape, in words.
    pub matrix: String,
    /// Median ratio over its seeds.
    pub ratio: f64,
}

/// `details.gibbs` of `perf.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PerfGibbs {
    /// Per matrix.
    pub cases: Vec<PerfGibbsCase>,
    /// The matrices and the chain, in words.
    pub matrices: String,
    /// Matrices whose chain did not reach the sampler's mass.
    pub not_reached: usize,
    /// Median ratio per matrix shape.
    pub ratio_median_by_shape: Vec<PerfGibbsShape>,
}

/// One matrix of `details.gibbs.cases`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PerfGibbsCase {
    /// Mass of the best 32 distinct samples over the target.
    pub gibbs_best_32_mass_over_target: f64,
    /// Distinct samples at the end of the run.
    pub gibbs_distinct_samples: usize,
    /// Sweeps run.
    pub gibbs_sweeps: u64,
    /// Median time of the chain (µs).
    pub gibbs_us: f64,
    /// Its shape, in words.
    pub matrix: String,
    /// `gibbs_us` over `sampler_us`; `null` when the chain did not reach the target.
    pub ratio: Option<f64>,
    /// Whether the chain reached the target.
    pub reached: bool,
    /// Median time of the sampler (µs).
    pub sampler_us: f64,
    /// Seed of the crossing matrix.
    pub seed: u64,
    /// The sampler's captured mass, Σ e^{w − MAP}.
    pub target_mass_over_map: f64,
}

/// The median Gibbs ratio of one matrix shape.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PerfGibbsShape {
    /// The shape, in words.
    pub matrix: String,
    /// Median ratio over its seeds (a chain not reached counting as +∞); `null` when not finite.
    pub ratio: Option<f64>,
}

/// `machine` of `perf.json`.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PerfMachine {
    /// `std::env::consts::ARCH`.
    pub arch: String,
    /// `lscpu`'s model name (empty when unavailable).
    pub cpu: String,
    /// Available parallelism (0 when unknown).
    pub cpus: usize,
    /// Whether debug assertions were on (a debug build).
    pub debug_assertions: bool,
    /// `std::env::consts::OS`.
    pub os: String,
    /// `rustc --version` (empty when unavailable).
    pub rustc: String,
}

/// `compare.json` of `host-sim compare` on a version 2 (3-D) file: the bounded tracker against the unbounded
/// reference, scan by scan (`exactness::compare_scans`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Compare3dSummary {
    /// The bounded tracker (`homht` or `rfisst`).
    pub tracker: String,
    /// Its capacity profile.
    pub profile: String,
    /// Sensors of the scenario.
    pub sensors: usize,
    /// Scans compared.
    pub scans: usize,
    /// Fraction of scans whose MAP hypotheses agree.
    pub map_agreement: f64,
    /// Smallest captured mass (the reference's mass on the bounded tracker's hypotheses).
    pub min_captured_mass: f64,
    /// Mean captured mass.
    pub mean_captured_mass: f64,
    /// Largest weight L1 distance.
    pub max_weight_l1: f64,
    /// Largest |w_core(MAP) − w_reference| relative to the reference's MAP weight.
    pub max_map_weight_difference: f64,
    /// Smallest captured mass the bounded tracker reported itself.
    pub min_core_captured_mass: f64,
    /// Scans the bounded tracker rejected.
    pub core_rejected_scans: usize,
    /// Scans the reference rejected.
    pub reference_rejected_scans: usize,
}

/// `catalogue.json` of `experiment catalogue`: a catalogue seen by two radars and a telescope, each
/// network tracked by its own R-FISST tracker (one tracker takes one measurement type).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CatalogueReport {
    /// `catalogue`.
    pub experiment: String,
    /// Seed.
    pub seed: u64,
    /// Objects in the catalogue (every one in both trackers' truth).
    pub objects: usize,
    /// Objects missing from the prior (the same in both scenarios).
    pub missing_from_prior: usize,
    /// Births: objects missing from the prior that some sensor detected, each counted once.
    pub births_total: usize,
    /// Births that at least one tracker confirmed, each counted once.
    pub births_confirmed: usize,
    /// GOSPA (km) averaged over every scan of both trackers.
    pub mean_gospa: f64,
    /// Wall-clock ms per scan, averaged over every accepted scan of both trackers.
    pub mean_ms_per_scan: f64,
    /// The slowest scan of both trackers (ms).
    pub max_ms_per_scan: f64,
    /// Per tracker.
    pub details: Vec<CatalogueTracker>,
}

/// One tracker of `experiment catalogue`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CatalogueTracker {
    /// `radars` or `telescope`: its run directory.
    pub network: String,
    /// Its sensors.
    pub sensors: Vec<String>,
    /// Seconds between two scans of one sensor.
    pub scan_interval_s: f64,
    /// Scans.
    pub scans: usize,
    /// Catalogue objects with at least one detection.
    pub objects_seen: usize,
    /// Launch-train objects with at least one detection.
    pub train_seen: usize,
    /// Launch-train objects confirmed.
    pub train_confirmed: usize,
    /// Births: objects missing from the prior (detected or not).
    pub births_total: usize,
    /// Births with at least one detection.
    pub births_detected: usize,
    /// Births confirmed.
    pub births_confirmed: usize,
    /// Mean detections to confirmation of the confirmed births.
    pub mean_detections_to_confirm: Option<f64>,
    /// MAP labels confirmed and never within the error bound of an object.
    pub false_tracks: Option<usize>,
    /// Mean GOSPA (km) over its scans.
    pub mean_gospa: f64,
    /// MAP tracks after the last scan.
    pub final_map_cardinality: usize,
    /// Wall-clock ms per scan, mean and max.
    pub mean_ms_per_scan: f64,
    /// The slowest scan (ms).
    pub max_ms_per_scan: f64,
    /// Scans the tracker rejected.
    pub rejected_scans: usize,
}
