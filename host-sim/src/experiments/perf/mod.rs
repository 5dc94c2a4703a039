//! `host-sim perf`: speed and memory measured side by side in one process.
//!
//! Every figure is a median of wall-clock samples. The measurements are taken in rounds: each round takes
//! samples of every micro-benchmark in turn (the Metropolis chain under each proposal and the floor loop
//! alternately, the EKF, the exhaustive-vs-sampler and Murty-vs-sampler comparisons) and one pass of the
//! fifty-object scenario, so a burst of load from other processes spreads over all of them instead of
//! biasing one. Samples are short (about a millisecond or less), so most run undisturbed by the scheduler
//! even on a loaded machine and the median ignores the others. The report is a
//! [`PerfReport`](crate::io::report::PerfReport); the keys written:
//!
//! - `mcmc_ns_per_step`: one Metropolis chain of 20,000 steps with the default (informed) proposal on the
//!   32 × 64 crossing matrix ([`crossing_matrix`] seed 1, 8 objects in each gate), including the tables,
//!   the greedy start, the hill climb and the duplicate removal, divided by 20,000 (the `sampler` criterion
//!   bench's `mcmc_step/32x64/Informed`). `mcmc_ns_per_step_<proposal>` for each proposal.
//! - `floor_ns_per_step`: the floor loop of the same bench (one random draw, two table lookups, one
//!   compare per step); `mcmc_over_floor` is the ratio.
//! - `ekf_update_ns`: `tracker_core::ekf::update` of a two-body SSA state (Joseph form, f64); also
//!   `ekf_predict_two_body_ns` (dt = 60 s), `ekf_predict_cv_ns` and `ekf_innovation_ns`.
//! - `step_ms_fifty`: median over scans of the time of `step` of the default embedded R-FISST tracker
//!   (`SsaTracker<f64>` with the scenario's sampled children, as `host-sim run --tracker rfisst` builds it) on `fifty-birth-death` seed 1, each scan's
//!   time being the median over the passes.
//! - `step_ms_radar_leo`, `step_ms_optical_geo`: median over scans of the time of `step_scan` of the 3-D
//!   R-FISST tracker (`RadarTracker`-shaped, with the profile `run` chooses: `host` for radar-leo's 120
//!   objects, `embedded` for optical-geo) on `host-sim generate radar-leo --seed 1` (its first
//!   [`RADAR_LEO_SCANS`] scans, 100 min of the 6 h, in one pass) and `optical-geo --seed 1` (all 161 scans,
//!   [`FIFTY_PASSES`] passes). `details.radar_leo` / `details.optical_geo` give the mean, max and profile.
//! - `murty_over_mcmc_time_at_equal_mass`: on crossing matrices (16 × 32 with 4 objects per gate, 16 × 64
//!   and 32 × 64 with 8; seeds 1..=4), the default child generator (`ClusteredChildren`, default sampler,
//!   C = 32 = H∞) captures a fraction of the mass of the exact 32 best children (from Murty); Murty's
//!   algorithm ([`crate::peers::murty`]) needs its k best to capture as much; the ratio of their times, median over
//!   the matrices.
//! - `gibbs_over_mcmc_time_at_equal_mass`: on the same matrices, the Gibbs sampler of GLMB trackers
//!   ([`crate::peers::gibbs`], from the all-clutter association) runs until its distinct samples capture the
//!   sampler's mass (at most 10⁶ sweeps; a matrix not reached counts as +∞); its time over the sampler's,
//!   median over the matrices. Its runs on the 32-row matrices take milliseconds, longer than the other
//!   samples.
//! - `exhaustive_over_mcmc_at_1e6_children`: a dense 7 × 9 matrix, A₉(7) = 1,047,376 children; time of
//!   `ExhaustiveChildren` over time of the default `ClusteredChildren`, both into the tracker's
//!   `TopChildren<_, 32, _>` sink.
//! - `tracker_bytes_default`, `tracker_bytes_f32`: `size_of::<SsaTracker<f64>>()` and `<f32>`.

use crate::error::Error;
use crate::io::report::{
    PerfDetails, PerfExhaustive, PerfFifty, PerfGibbs, PerfGibbsCase, PerfGibbsShape, PerfMachine, PerfMurty,
    PerfMurtyCase, PerfMurtyShape, PerfReport, PerfSsa,
};
use crate::peers::murty::Murty;
use crate::pipeline::planar::setup;
use nalgebra::{SMatrix, SVector};
use rand_core::{Rng, SeedableRng};
use rand_xoshiro::{SplitMix64, Xoshiro256PlusPlus};
use std::hint::black_box;
use std::time::Instant;
use tracker_core::association::{AssociationMatrix, association_count};
use tracker_core::children::{ChildGenerator, ChildSink, ExhaustiveChildren};
use tracker_core::cluster::ClusteredChildren;
use tracker_core::ekf;
use tracker_core::sampler::{MetropolisSampler, Proposal, SamplerConfig};
use tracker_core::selection::TopChildren;
use tracker_core::{ConstantVelocity, Gaussian, PositionMeasurement, PriorHypothesis, SsaTracker, Tracker, TwoBody};

/// Steps per chain of the sampler benchmark (as in the criterion bench).
const CHAIN_STEPS: u32 = 20_000;
/// Measurement rounds.
const ROUNDS: usize = 7;
/// Samples of each micro-benchmark per round.
const SAMPLES_PER_ROUND: usize = 40;
/// Passes over the fifty-object scenario (in the first rounds).
const FIFTY_PASSES: usize = 5;

/// The crossing matrix of the benches (`benches::crossing_matrix`, same generator and output): each of
/// `rows` measurements is inside the gate of `in_gate` objects around its own (entries −2 to +8 nats).
pub fn crossing_matrix<const N: usize, const Z: usize>(
    rows: usize,
    columns: usize,
    in_gate: usize,
    seed: u64,
) -> AssociationMatrix<f64, N, Z> {
    // The bench inputs' generator: SplitMix64 from the seed.
    let mut state = SplitMix64::seed_from_u64(seed);
    let mut m = AssociationMatrix::new(rows, columns, 0.0);
    let mut column_entries = vec![vec![f64::NEG_INFINITY; rows]; columns];
    for row in 0..rows {
        let centre = row * columns / rows.max(1);
        for k in 0..in_gate {
            let column = (centre + k).min(columns - 1);
            let u = (state.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
            if let Some(entry) = column_entries[column].get_mut(row) {
                *entry = -2.0 + 10.0 * u;
            }
        }
    }
    for (column, entries) in column_entries.iter().enumerate() {
        m.set_column(column, entries, false);
    }
    m
}

/// Median of samples (NaN when empty).
fn median(samples: &[f64]) -> f64 {
    if samples.is_empty() {
        return f64::NAN;
    }
    let mut sorted = samples.to_vec();
    sorted.sort_by(f64::total_cmp);
    let n = sorted.len();
    if n % 2 == 1 { sorted[n / 2] } else { 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]) }
}

/// Smallest sample (the least disturbed run).
fn minimum(samples: &[f64]) -> f64 {
    samples.iter().copied().fold(f64::INFINITY, f64::min)
}

/// Seconds taken by `f`.
fn time<R>(f: impl FnOnce() -> R) -> (f64, R) {
    let start = Instant::now();
    let result = f();
    (start.elapsed().as_secs_f64(), result)
}

/// The floor loop of the sampler bench: one random draw, two table lookups and one compare per step.
#[inline(never)]
fn floor_loop(rng: &mut Xoshiro256PlusPlus, table: &[[f64; 64]; 32], steps: u32) -> u32 {
    let mut count = 0u32;
    for _ in 0..steps {
        let draw = rng.next_u64();
        let row = (((draw >> 32) * 32) >> 32) as usize;
        let column = (((draw & 0xffff_ffff) * 64) >> 32) as usize;
        let other = (column + 1) & 63;
        if black_box(table[row][column]) > black_box(table[row][other]) {
            count += 1;
        }
    }
    count
}

/// A sink that keeps everything offered.
struct Collect(Vec<(f64, Vec<u16>)>);

impl ChildSink<f64> for Collect {
    fn offer(&mut self, log_weight: f64, assignment: &[u16]) {
        self.0.push((log_weight, assignment.to_vec()));
    }
}

/// The sampler micro-benchmark: chains per proposal and the floor, sampled in turn.
struct ChainBench {
    matrix: Box<AssociationMatrix<f64, 64, 32>>,
    chains: Vec<(Proposal, Box<MetropolisSampler<f64, 64, 32, 32>>)>,
    table: Box<[[f64; 64]; 32]>,
    rng: Xoshiro256PlusPlus,
    /// Per proposal, then the floor: ns per step of each sample.
    samples: Vec<Vec<f64>>,
}

impl ChainBench {
    /// Chains per sample: one (under a millisecond, shorter than a scheduler time slice, so most samples
    /// run undisturbed and the median ignores the rest).
    const CHAINS_PER_SAMPLE: u32 = 1;

    fn new() -> Self {
        let chains = [Proposal::Informed, Proposal::Paper, Proposal::MoveOrSwap]
            .into_iter()
            .map(|proposal| {
                let config = SamplerConfig {
                    burn_in: 0,
                    steps: CHAIN_STEPS,
                    proposal,
                    clusters: false,
                    exhaustive_limit: 0,
                    ..SamplerConfig::default()
                };
                (proposal, Box::new(MetropolisSampler::new(config, 7)))
            })
            .collect();
        Self {
            matrix: Box::new(crossing_matrix(32, 64, 8, 1)),
            chains,
            table: Box::new([[0.5; 64]; 32]),
            rng: Xoshiro256PlusPlus::seed_from_u64(7),
            samples: vec![Vec::new(); 4],
        }
    }

    fn sample(&mut self) {
        let steps = f64::from(CHAIN_STEPS * Self::CHAINS_PER_SAMPLE);
        for (index, (_, chain)) in self.chains.iter_mut().enumerate() {
            let (seconds, _) = time(|| {
                for _ in 0..Self::CHAINS_PER_SAMPLE {
                    chain.run(black_box(&self.matrix));
                    black_box(chain.best().len());
                }
            });
            self.samples[index].push(seconds * 1e9 / steps);
        }
        let (seconds, _) = time(|| {
            for _ in 0..Self::CHAINS_PER_SAMPLE {
                black_box(floor_loop(&mut self.rng, &self.table, CHAIN_STEPS));
            }
        });
        self.samples[3].push(seconds * 1e9 / steps);
    }
}

/// EKF micro-benchmarks: ns per call of update, predict (two-body, constant velocity) and innovation.
struct EkfBench {
    two_body: TwoBody<f64>,
    cv: ConstantVelocity<f64>,
    measurement: PositionMeasurement<f64>,
    prior: Gaussian<f64, 4>,
    predicted: Gaussian<f64, 4>,
    innovation: ekf::Innovation<f64, 2>,
    z: SVector<f64, 2>,
    samples: [Vec<f64>; 4],
}

impl EkfBench {
    /// Calls per sample (about 0.1 ms).
    const CALLS: u32 = 2_000;

    fn new() -> Result<Self, Error> {
        let look = 15f64.to_radians();
        let (r, v) = (7_000.0, (crate::sim::planar::EARTH_MU / 7_000.0f64).sqrt());
        let prior = Gaussian {
            mean: SVector::from([r * look.cos(), r * look.sin(), -v * look.sin(), v * look.cos()]),
            covariance: SMatrix::from_diagonal(&SVector::from([1.0, 1.0, 4e-8, 4e-8])),
        };
        let two_body = TwoBody {
            mu: crate::sim::planar::EARTH_MU,
            acceleration_noise: 1e-13,
            max_step: 20.0,
            max_substeps: 20_000,
            min_radius: TwoBody::DEFAULT_MIN_RADIUS,
        };
        let measurement = PositionMeasurement::isotropic(0.5);
        let predicted =
            ekf::predict(&two_body, &prior, 60.0).map_err(|e| Error::internal(format!("ekf bench: {e}")))?;
        let innovation =
            ekf::innovation(&measurement, &predicted).map_err(|e| Error::internal(format!("ekf bench: {e}")))?;
        let z = innovation.predicted + SVector::from([0.4, -0.3]);
        Ok(Self {
            two_body,
            cv: ConstantVelocity { acceleration_noise: 0.01 },
            measurement,
            prior,
            predicted,
            innovation,
            z,
            samples: Default::default(),
        })
    }

    fn sample(&mut self) {
        let calls = f64::from(Self::CALLS);
        let (seconds, _) = time(|| {
            for _ in 0..Self::CALLS {
                let _ = black_box(ekf::update(
                    black_box(&self.measurement),
                    black_box(&self.predicted),
                    black_box(&self.innovation),
                    black_box(&self.z),
                ));
            }
        });
        self.samples[0].push(seconds * 1e9 / calls);
        let (seconds, _) = time(|| {
            for _ in 0..Self::CALLS {
                let _ = black_box(ekf::predict(black_box(&self.two_body), black_box(&self.prior), black_box(60.0)));
            }
        });
        self.samples[1].push(seconds * 1e9 / calls);
        let (seconds, _) = time(|| {
            for _ in 0..Self::CALLS {
                let _ = black_box(ekf::predict(black_box(&self.cv), black_box(&self.prior), black_box(1.0)));
            }
        });
        self.samples[2].push(seconds * 1e9 / calls);
        let (seconds, _) = time(|| {
            for _ in 0..Self::CALLS {
                let _ = black_box(ekf::innovation(black_box(&self.measurement), black_box(&self.predicted)));
            }
        });
        self.samples[3].push(seconds * 1e9 / calls);
    }
}

/// Exhaustive enumeration against the default sampler on a dense matrix with about 10⁶ children.
struct ExhaustiveBench {
    matrix: Box<AssociationMatrix<f64, 16, 8>>,
    sampler: Box<ClusteredChildren<f64, 16, 8, 32>>,
    children: u128,
    exhaustive: Vec<f64>,
    sampled: Vec<f64>,
    /// Best log-weight found by each (exhaustive first).
    best: (f64, f64),
}

impl ExhaustiveBench {
    const ROWS: usize = 7;
    const COLUMNS: usize = 9;

    fn new() -> Self {
        let mut state = SplitMix64::seed_from_u64(11);
        let mut matrix = AssociationMatrix::new(Self::ROWS, Self::COLUMNS, 0.0);
        for column in 0..Self::COLUMNS {
            let entries: Vec<f64> = (0..Self::ROWS)
                .map(|_| -2.0 + 10.0 * ((state.next_u64() >> 11) as f64 / (1u64 << 53) as f64))
                .collect();
            matrix.set_column(column, &entries, false);
        }
        Self {
            matrix: Box::new(matrix),
            sampler: Box::new(ClusteredChildren::new(SamplerConfig::default(), 1)),
            children: association_count(Self::COLUMNS as u32, Self::ROWS as u32),
            exhaustive: Vec::new(),
            sampled: Vec::new(),
            best: (f64::NAN, f64::NAN),
        }
    }

    fn sample(&mut self) -> Result<(), Error> {
        let mut top = Box::new(TopChildren::<f64, 32, 8>::new());
        let (seconds, result) = time(|| ExhaustiveChildren::new(u64::MAX).generate(&self.matrix, &mut *top));
        result.map_err(|e| Error::internal(format!("exhaustive: {e:?}")))?;
        self.exhaustive.push(seconds);
        let best_exhaustive = top.kept().iter().map(|c| c.log_weight).fold(f64::NEG_INFINITY, f64::max);
        let mut top = Box::new(TopChildren::<f64, 32, 8>::new());
        // Several runs per sample: one takes tens of microseconds.
        const RUNS: u32 = 5;
        let (seconds, _) = time(|| {
            for _ in 0..RUNS {
                top.clear();
                self.sampler.reseed(1);
                let _ = black_box(self.sampler.generate(&self.matrix, &mut *top));
            }
        });
        self.sampled.push(seconds / f64::from(RUNS));
        let best_sampled = top.kept().iter().map(|c| c.log_weight).fold(f64::NEG_INFINITY, f64::max);
        self.best = (best_exhaustive, best_sampled);
        Ok(())
    }
}

/// One matrix of the Murty-against-sampler comparison.
struct MurtyCase {
    shape: (usize, usize, usize),
    seed: u64,
    /// Log-weight of the sampler's best child minus the MAP's.
    sampler_best_minus_map: f64,
    /// The MAP's log-weight, and the exact best-C mass Σ e^{w − MAP}.
    map: f64,
    exact_mass: f64,
    matrix: Box<AssociationMatrix<f64, 64, 32>>,
    /// Murty's children needed to capture the sampler's mass.
    k: usize,
    /// Fraction of the exact best-C mass the sampler captured.
    sampler_mass: f64,
    sampler_children: usize,
    murty_seconds: Vec<f64>,
    sampler_seconds: Vec<f64>,
}

/// Murty's k-best against the default sampler at equal captured mass.
struct MurtyBench {
    sampler: Box<ClusteredChildren<f64, 64, 32, 32>>,
    cases: Vec<MurtyCase>,
}

impl MurtyBench {
    /// Children kept per matrix: the tracker's H∞.
    const C: usize = 32;
    /// The family: (rows, columns, objects per gate) crossings, each with these seeds.
    const SHAPES: [(usize, usize, usize); 3] = [(16, 32, 4), (16, 64, 8), (32, 64, 8)];
    const SEEDS: std::ops::RangeInclusive<u64> = 1..=4;
    const SAMPLER_SEED: u64 = 3;

    fn new() -> Self {
        let mut sampler = Box::new(ClusteredChildren::new(SamplerConfig::default(), Self::SAMPLER_SEED));
        let cases = Self::SHAPES
            .iter()
            .flat_map(|&shape| Self::SEEDS.map(move |seed| (shape, seed)))
            .map(|(shape, seed)| {
                let (rows, columns, in_gate) = shape;
                let matrix: Box<AssociationMatrix<f64, 64, 32>> =
                    Box::new(crossing_matrix(rows, columns, in_gate, seed));
                // The exact best C (Murty is exact) and the sampler's children.
                let best: Vec<f64> = Murty::new(&matrix).take(Self::C).map(|c| c.log_weight).collect();
                let top = best.first().copied().unwrap_or(0.0);
                let exact_mass: f64 = best.iter().map(|w| (w - top).exp()).sum();
                let mut found = Collect(Vec::new());
                sampler.reseed(Self::SAMPLER_SEED);
                let _ = sampler.generate(&matrix, &mut found);
                let sampler_mass = found.0.iter().map(|c| (c.0 - top).exp()).sum::<f64>() / exact_mass;
                // Smallest k whose Murty mass reaches the sampler's.
                let mut cumulative = 0.0;
                let mut k = best.len();
                for (i, w) in best.iter().enumerate() {
                    cumulative += (w - top).exp() / exact_mass;
                    if cumulative >= sampler_mass * (1.0 - 1e-12) {
                        k = i + 1;
                        break;
                    }
                }
                let sampler_best = found.0.iter().map(|c| c.0).fold(f64::NEG_INFINITY, f64::max);
                MurtyCase {
                    shape,
                    seed,
                    sampler_best_minus_map: sampler_best - top,
                    map: top,
                    exact_mass,
                    matrix,
                    k,
                    sampler_mass,
                    sampler_children: found.0.len(),
                    murty_seconds: Vec::new(),
                    sampler_seconds: Vec::new(),
                }
            })
            .collect();
        Self { sampler, cases }
    }

    fn sample(&mut self) {
        for case in &mut self.cases {
            let (seconds, _) = time(|| black_box(Murty::new(&case.matrix).take(case.k).count()));
            case.murty_seconds.push(seconds);
            const RUNS: u32 = 5;
            let mut sink = TopChildren::<f64, 32, 32>::new();
            let (seconds, _) = time(|| {
                for _ in 0..RUNS {
                    sink.clear();
                    self.sampler.reseed(Self::SAMPLER_SEED);
                    let _ = black_box(self.sampler.generate(&case.matrix, &mut sink));
                }
            });
            case.sampler_seconds.push(seconds / f64::from(RUNS));
        }
    }
}

/// Scans of `radar-leo` seed 1 timed by `perf` (of 2,161): a full run takes 100 s.
pub const RADAR_LEO_SCANS: usize = 600;

/// A 3-D preset: per-scan times of the R-FISST tracker that `run` builds for it.
struct SsaBench {
    scenario: crate::scenario::v2::Scenario3d,
    profile: crate::pipeline::Profile,
    scans: Vec<(usize, f64, Vec<Vec<f64>>)>,
    times: Vec<Vec<f64>>,
    rejected: usize,
}

impl SsaBench {
    fn new(preset: crate::scenario::from_simulation::Preset3d, scans: usize) -> Result<Self, Error> {
        let simulated = preset.simulate(1).map_err(|e| Error::internal(format!("perf: {e}")))?;
        let (scenario, _) = crate::scenario::from_simulation::to_scenario(&simulated)
            .map_err(|e| Error::internal(format!("perf: {e}")))?;
        let scans: Vec<(usize, f64, Vec<Vec<f64>>)> = scenario
            .scans
            .iter()
            .take(scans)
            .map(|scan| {
                (
                    scan.sensor,
                    scan.time,
                    crate::pipeline::orbital::measurements_in_radians(scenario.measurement, &scan.measurements),
                )
            })
            .collect();
        let profile = crate::pipeline::orbital::choose_profile(&scenario, None);
        let times = vec![Vec::new(); scans.len()];
        Ok(Self { scenario, profile, scans, times, rejected: 0 })
    }

    fn pass(&mut self) -> Result<(), Error> {
        let mut runner =
            crate::pipeline::orbital::build3d(crate::pipeline::TrackerKind::Rfisst, self.profile, &self.scenario)?;
        self.rejected = 0;
        for (index, (sensor, scan_time, measurements)) in self.scans.iter().enumerate() {
            let (seconds, result) = time(|| runner.step(*sensor, *scan_time, measurements));
            self.times[index].push(seconds);
            if result.is_err() {
                self.rejected += 1;
            }
        }
        Ok(())
    }

    /// The per-scan figures, and the median per scan (ms).
    fn report(&self) -> (f64, PerfSsa) {
        let per_scan_ms: Vec<f64> = self.times.iter().map(|t| median(t) * 1e3).collect();
        let m = median(&per_scan_ms);
        let ssa = PerfSsa {
            max_ms: per_scan_ms.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            mean_ms: per_scan_ms.iter().sum::<f64>() / per_scan_ms.len().max(1) as f64,
            median_ms: m,
            passes: self.times.first().map_or(0, Vec::len),
            profile: self.profile.name().to_string(),
            rejected_scans_last_pass: self.rejected,
            scans: self.scans.len(),
            scans_in_scenario: self.scenario.scans.len(),
        };
        (m, ssa)
    }
}

/// The fifty-object scenario: per-scan times of the default embedded R-FISST tracker.
struct FiftyBench {
    scenario: crate::scenario::Scenario,
    scans: Vec<(f64, Vec<SVector<f64, 2>>)>,
    /// Per scan, its time (s) in each pass.
    times: Vec<Vec<f64>>,
    rejected: usize,
}

impl FiftyBench {
    fn new() -> Self {
        let scenario = crate::sim::planar::fifty_birth_death(1).run();
        let scans = scenario.scans.iter().map(|scan| (scan.time, setup::measurements(scan))).collect::<Vec<_>>();
        let times = vec![Vec::new(); scans.len()];
        Self { scenario, scans, times, rejected: 0 }
    }

    /// The default embedded R-FISST tracker on the scenario, built as `runner`'s core runner builds it.
    fn tracker(&self) -> Result<Box<SsaTracker<f64>>, Error> {
        let scenario = &self.scenario;
        let motion =
            setup::two_body(&scenario.motion).ok_or_else(|| Error::internal("fifty-birth-death: not two-body"))?;
        let config = setup::config(scenario, motion, setup::sampled(scenario))
            .map_err(|e| Error::internal(format!("fifty-birth-death: {e}")))?;
        let prior = setup::prior(scenario);
        let hypotheses: Vec<PriorHypothesis<'_, f64, 4>> =
            prior.iter().map(|(weight, objects)| PriorHypothesis { weight: *weight, objects }).collect();
        Tracker::new(config, &hypotheses, scenario.prior.time)
            .map(Box::new)
            .map_err(|e| Error::internal(format!("fifty-birth-death: tracker configuration: {e}")))
    }

    fn pass(&mut self) -> Result<(), Error> {
        let mut tracker = self.tracker()?;
        self.rejected = 0;
        for (index, (scan_time, measurements)) in self.scans.iter().enumerate() {
            let (seconds, result) = time(|| tracker.step(*scan_time, measurements));
            self.times[index].push(seconds);
            if result.is_err() {
                self.rejected += 1;
            }
        }
        Ok(())
    }
}

/// A crossing shape (rows, columns, objects per gate) in words, as `perf.json` names it.
fn label(shape: (usize, usize, usize)) -> String {
    format!("{} x {}, {} per gate", shape.0, shape.1, shape.2)
}

/// A line of `lscpu` (`Model name`, ...), if available.
fn lscpu(field: &str) -> Option<String> {
    let output = std::process::Command::new("lscpu").output().ok()?;
    String::from_utf8_lossy(&output.stdout)
        .lines()
        .find(|line| line.starts_with(field))
        .and_then(|line| line.split_once(':'))
        .map(|(_, value)| value.trim().to_string())
}

fn rustc_version() -> Option<String> {
    let output = std::process::Command::new("rustc").arg("--version").output().ok()?;
    Some(String::from_utf8_lossy(&output.stdout).trim().to_string())
}

/// Runs every measurement (about a minute in release) and returns the report.
///
/// # Errors
/// [`Error::Internal`] when a benchmark input cannot be built or the scenario's tracker cannot be
/// configured (the inputs are built in, so either is a bug).
pub fn run() -> Result<PerfReport, Error> {
    let started = Instant::now();
    let mut chains = ChainBench::new();
    let mut ekf_bench = EkfBench::new()?;
    let mut exhaustive = ExhaustiveBench::new();
    let mut murty = MurtyBench::new();
    let mut gibbs = crate::peers::gibbs::Bench::new(
        murty.cases.iter().map(|c| (label(c.shape), c.seed, &*c.matrix, c.map, c.sampler_mass * c.exact_mass)),
    );
    let mut fifty = FiftyBench::new();
    let mut radar_leo = SsaBench::new(crate::scenario::from_simulation::Preset3d::RadarLeo, RADAR_LEO_SCANS)?;
    let mut optical_geo = SsaBench::new(crate::scenario::from_simulation::Preset3d::OpticalGeo, usize::MAX)?;
    // Warm-up (caches, frequency), not recorded.
    chains.sample();
    ekf_bench.sample();
    chains.samples.iter_mut().for_each(Vec::clear);
    ekf_bench.samples.iter_mut().for_each(Vec::clear);
    for round in 0..ROUNDS {
        for _ in 0..SAMPLES_PER_ROUND {
            chains.sample();
            ekf_bench.sample();
        }
        exhaustive.sample()?;
        murty.sample();
        gibbs.sample();
        if round < FIFTY_PASSES {
            fifty.pass()?;
            optical_geo.pass()?;
        }
        if round == 0 {
            radar_leo.pass()?;
        }
    }

    let (step_ms_radar_leo, radar_leo) = radar_leo.report();
    let (step_ms_optical_geo, optical_geo) = optical_geo.report();
    let mcmc = median(&chains.samples[0]);
    let floor = median(&chains.samples[3]);
    let per_scan_ms: Vec<f64> = fifty.times.iter().map(|t| median(t) * 1e3).collect();
    let (ratios, murty_cases, murty_by_shape) = murty_figures(&murty);
    let exhaustive_ratio = median(&exhaustive.exhaustive) / median(&exhaustive.sampled);
    let (gibbs_ratios, gibbs_cases, gibbs_by_shape) = gibbs_figures(&murty, &gibbs);

    Ok(PerfReport {
        mcmc_ns_per_step: mcmc,
        floor_ns_per_step: floor,
        mcmc_over_floor: mcmc / floor,
        ekf_update_ns: median(&ekf_bench.samples[0]),
        step_ms_fifty: median(&per_scan_ms),
        step_ms_optical_geo,
        step_ms_radar_leo,
        murty_over_mcmc_time_at_equal_mass: median(&ratios),
        gibbs_over_mcmc_time_at_equal_mass: median(&gibbs_ratios),
        exhaustive_over_mcmc_at_1e6_children: exhaustive_ratio,
        tracker_bytes_default: std::mem::size_of::<SsaTracker<f64>>(),
        tracker_bytes_f32: std::mem::size_of::<SsaTracker<f32>>(),
        details: PerfDetails {
            mcmc_ns_per_step_informed: mcmc,
            mcmc_ns_per_step_paper: median(&chains.samples[1]),
            mcmc_ns_per_step_move_or_swap: median(&chains.samples[2]),
            mcmc_samples: chains.samples[0].len(),
            mcmc_ns_per_step_min: minimum(&chains.samples[0]),
            floor_ns_per_step_min: minimum(&chains.samples[3]),
            mcmc_over_floor_of_minima: minimum(&chains.samples[0]) / minimum(&chains.samples[3]),
            ekf_update_ns_min: minimum(&ekf_bench.samples[0]),
            ekf_predict_two_body_ns: median(&ekf_bench.samples[1]),
            ekf_predict_cv_ns: median(&ekf_bench.samples[2]),
            ekf_innovation_ns: median(&ekf_bench.samples[3]),
            fifty: fifty_figures(&per_scan_ms, fifty.rejected),
            murty: PerfMurty {
                matrices: "crossings 16 x 32 (4 per gate), 16 x 64 (8), 32 x 64 (8), seeds 1..=4; sampler = ClusteredChildren, default SamplerConfig, C = 32; Murty lazy, cold-started subproblems".to_string(),
                ratio_median_by_shape: murty_by_shape,
                ratio_min: ratios.iter().copied().fold(f64::INFINITY, f64::min),
                ratio_max: ratios.iter().copied().fold(f64::NEG_INFINITY, f64::max),
                cases: murty_cases,
            },
            optical_geo,
            radar_leo,
            gibbs: PerfGibbs {
                matrices: "the Murty matrices; Gibbs (crate::peers::gibbs) from all-clutter, seed 5, run until its distinct samples' mass reaches the sampler's, at most 10^6 sweeps (a matrix not reached has ratio null and counts as +inf in the median)".to_string(),
                not_reached: gibbs_ratios.iter().filter(|r| r.is_infinite()).count(),
                ratio_median_by_shape: gibbs_by_shape,
                cases: gibbs_cases,
            },
            exhaustive: PerfExhaustive {
                matrix: "dense 7 x 9".to_string(),
                children: exhaustive.children.to_string(),
                exhaustive_ms: median(&exhaustive.exhaustive) * 1e3,
                sampler_us: median(&exhaustive.sampled) * 1e6,
                best_log_weight_exhaustive: exhaustive.best.0,
                best_log_weight_sampler: exhaustive.best.1,
            },
            rounds: ROUNDS,
            seconds: started.elapsed().as_secs_f64(),
        },
        machine: machine(),
    })
}

/// The fifty-object figures from the per-scan times (ms, each the median over the passes).
fn fifty_figures(per_scan_ms: &[f64], rejected: usize) -> PerfFifty {
    let mut sorted_scans = per_scan_ms.to_vec();
    sorted_scans.sort_by(f64::total_cmp);
    let percentile = |p: f64| {
        sorted_scans.get(((sorted_scans.len() as f64 - 1.0) * p).round() as usize).copied().unwrap_or(f64::NAN)
    };
    PerfFifty {
        scans: per_scan_ms.len(),
        passes: FIFTY_PASSES,
        rejected_scans_last_pass: rejected,
        mean_ms: per_scan_ms.iter().sum::<f64>() / per_scan_ms.len().max(1) as f64,
        p90_ms: percentile(0.9),
        max_ms: percentile(1.0),
    }
}

/// Per Murty case the time ratio to the sampler at equal mass, the case records, and the median ratio per shape.
fn murty_figures(murty: &MurtyBench) -> (Vec<f64>, Vec<PerfMurtyCase>, Vec<PerfMurtyShape>) {
    let ratios: Vec<f64> =
        murty.cases.iter().map(|case| median(&case.murty_seconds) / median(&case.sampler_seconds)).collect();
    let murty_cases: Vec<PerfMurtyCase> = murty
        .cases
        .iter()
        .zip(&ratios)
        .map(|(case, &ratio)| PerfMurtyCase {
            matrix: label(case.shape),
            seed: case.seed,
            sampler_best_minus_map_nats: case.sampler_best_minus_map,
            sampler_children: case.sampler_children,
            sampler_captured_mass_of_best_32: case.sampler_mass,
            murty_children_for_equal_mass: case.k,
            sampler_us: median(&case.sampler_seconds) * 1e6,
            murty_us: median(&case.murty_seconds) * 1e6,
            ratio,
        })
        .collect();
    let murty_by_shape = MurtyBench::SHAPES
        .iter()
        .map(|&shape| {
            let by_shape: Vec<f64> =
                murty.cases.iter().zip(&ratios).filter(|(c, _)| c.shape == shape).map(|(_, r)| *r).collect();
            PerfMurtyShape { matrix: label(shape), ratio: median(&by_shape) }
        })
        .collect();
    (ratios, murty_cases, murty_by_shape)
}

/// Per Murty case Gibbs's time ratio to the sampler at equal mass, the case records, and the median ratio per shape.
fn gibbs_figures(
    murty: &MurtyBench,
    gibbs: &crate::peers::gibbs::Bench,
) -> (Vec<f64>, Vec<PerfGibbsCase>, Vec<PerfGibbsShape>) {
    let sampler_seconds: Vec<f64> = murty.cases.iter().map(|case| median(&case.sampler_seconds)).collect();
    let (gibbs_ratios, gibbs_cases) = gibbs.ratios(&sampler_seconds, median);
    let gibbs_by_shape = MurtyBench::SHAPES
        .iter()
        .map(|&shape| {
            let matrix = label(shape);
            let by_shape: Vec<f64> =
                gibbs.labels().zip(&gibbs_ratios).filter(|(l, _)| *l == matrix).map(|(_, r)| *r).collect();
            let m = median(&by_shape);
            PerfGibbsShape { matrix, ratio: m.is_finite().then_some(m) }
        })
        .collect();
    (gibbs_ratios, gibbs_cases, gibbs_by_shape)
}

/// The machine the figures were measured on.
fn machine() -> PerfMachine {
    PerfMachine {
        cpu: lscpu("Model name").unwrap_or_default(),
        cpus: std::thread::available_parallelism().map(|n| n.get()).unwrap_or(0),
        os: std::env::consts::OS.to_string(),
        arch: std::env::consts::ARCH.to_string(),
        rustc: rustc_version().unwrap_or_default(),
        debug_assertions: cfg!(debug_assertions),
    }
}

#[cfg(test)]
mod tests;
