//! `perf.json` of `perf`: the headline figures, the details per benchmark and the machine.

use serde::{Deserialize, Serialize};

/// `perf.json` of `host-sim perf` (every key is documented in `experiments/perf.rs`). The fields of each record are
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
