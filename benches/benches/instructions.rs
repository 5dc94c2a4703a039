//! Instruction counts (callgrind through gungraun): deterministic, so they are what CI compares with the
//! committed baseline (`scripts/instructions-check.sh`, `benches/baselines/instructions.json`).
//!
//! - `step`: one `Tracker::step` of the default SSA configuration (two-body, R-FISST sampled children with
//!   the default sampler) at its caps on the worst-case scan of [`benches::worst_case`]: H hypotheses of
//!   N − 1 objects over a full store, Z measurements inside every gate (dense matrices, one chain per
//!   birth cell per parent). `ssa_f64` and `ssa_f32` are `SsaTracker<f64>` / `SsaTracker<f32>` at
//!   [`tracker_core::ssa_caps`] (H = 32, N = 64, Z = 32, K = 256, B = 8); `ssa_f64_n_full` holds N objects
//!   per hypothesis (no room for a birth, so no birth chains); the others vary one cap of the f64 tracker
//!   (`hH`, `nN` with K = 4N, `zZ`); `ssa_f64_budget_M` is `ssa_f64` with a budget of M Metropolis moves
//!   for the scan (`Tracker::step_with_budget`; the unlimited scan makes 604,800). `radar_f64` and
//!   `radar_f32` are the 3-D `RadarTracker<f64>` / `RadarTracker<f32>` (two-body + J2, two ground radars,
//!   K = 192) on [`benches::radar_worst_case`]: the same construction in one radar's field of view.
//!   `network_f64` and `network_f32` are the fused `NetworkTracker<f64>` / `NetworkTracker<f32>` on
//!   [`benches::network_worst_case`]: every sensor kind in the network, Z measurements of its radar with
//!   range-rate (issue 28 item 6).
//! - `chain`: one Metropolis chain of 20,000 steps with the default (informed) proposal on the 32 × 64
//!   crossing matrix of the `sampler` bench (tables, greedy start, climb, steps, duplicate removal).
//! - `ekf`: two-body predict (dt = 60 s) and update, f64.
//!
//! Setup (building the tracker and the scan) is not counted. Run:
//! `cargo bench -p benches --bench instructions` (needs valgrind and gungraun-runner 0.20.0).
use benches::{
    NetworkWorstCase, RadarWorstCase, WorstCase, crossing_matrix, network_worst_case, radar_worst_case, ssa_motion,
    worst_case,
};
use gungraun::prelude::*;
use nalgebra::{SMatrix, SVector};
use std::hint::black_box;
use tracker_core::sampler::{MetropolisSampler, SamplerConfig};
use tracker_core::ssa_caps::{BIRTH_CELLS as B, HYPOTHESES as H, MEASUREMENTS as Z, OBJECTS as N, TRACKS as K};
use tracker_core::{Gaussian, PositionMeasurement, Real, ekf};

/// A worst-case scan of any capacities, behind one interface.
trait Scan {
    /// Runs the scan; returns the number of hypotheses kept (0 on error).
    fn run(&mut self) -> usize;
}

impl<T: Real, const H: usize, const N: usize, const Z: usize, const K: usize, const B: usize> Scan
    for WorstCase<T, H, N, Z, K, B>
{
    fn run(&mut self) -> usize {
        self.step().map(|report| report.hypotheses).unwrap_or(0)
    }
}

impl<T: Real> Scan for RadarWorstCase<T> {
    fn run(&mut self) -> usize {
        self.step().map(|report| report.hypotheses).unwrap_or(0)
    }
}

impl<T: Real> Scan for NetworkWorstCase<T> {
    fn run(&mut self) -> usize {
        self.step().map(|report| report.hypotheses).unwrap_or(0)
    }
}

fn network_f64() -> Box<dyn Scan> {
    Box::new(network_worst_case::<f64>())
}
fn network_f32() -> Box<dyn Scan> {
    Box::new(network_worst_case::<f32>())
}
fn radar_f64() -> Box<dyn Scan> {
    Box::new(radar_worst_case::<f64>())
}
fn radar_f32() -> Box<dyn Scan> {
    Box::new(radar_worst_case::<f32>())
}
fn ssa_f64() -> Box<dyn Scan> {
    Box::new(worst_case::<f64, H, N, Z, K, B>(N - 1))
}
fn ssa_f32() -> Box<dyn Scan> {
    Box::new(worst_case::<f32, H, N, Z, K, B>(N - 1))
}
fn ssa_f64_n_full() -> Box<dyn Scan> {
    Box::new(worst_case::<f64, H, N, Z, K, B>(N))
}
fn h8() -> Box<dyn Scan> {
    Box::new(worst_case::<f64, 8, N, Z, K, B>(N - 1))
}
fn h16() -> Box<dyn Scan> {
    Box::new(worst_case::<f64, 16, N, Z, K, B>(N - 1))
}
fn n16() -> Box<dyn Scan> {
    Box::new(worst_case::<f64, H, 16, Z, 64, B>(15))
}
fn n32() -> Box<dyn Scan> {
    Box::new(worst_case::<f64, H, 32, Z, 128, B>(31))
}
fn z4() -> Box<dyn Scan> {
    Box::new(worst_case::<f64, H, N, 4, K, B>(N - 1))
}
fn z8() -> Box<dyn Scan> {
    Box::new(worst_case::<f64, H, N, 8, K, B>(N - 1))
}
/// `ssa_f64` with a budget of `moves` Metropolis moves for the scan (`Tracker::step_with_budget`).
fn ssa_f64_budget(moves: u64) -> Box<dyn Scan> {
    let mut scan = worst_case::<f64, H, N, Z, K, B>(N - 1);
    scan.move_budget = moves;
    Box::new(scan)
}

#[library_benchmark]
#[bench::ssa_f64(setup = ssa_f64)]
#[bench::ssa_f32(setup = ssa_f32)]
#[bench::ssa_f64_n_full(setup = ssa_f64_n_full)]
#[bench::h8(setup = h8)]
#[bench::h16(setup = h16)]
#[bench::n16(setup = n16)]
#[bench::n32(setup = n32)]
#[bench::z4(setup = z4)]
#[bench::z8(setup = z8)]
#[bench::ssa_f64_budget_0(args = (0), setup = ssa_f64_budget)]
#[bench::ssa_f64_budget_10k(args = (10_000), setup = ssa_f64_budget)]
#[bench::ssa_f64_budget_100k(args = (100_000), setup = ssa_f64_budget)]
#[bench::ssa_f64_budget_300k(args = (300_000), setup = ssa_f64_budget)]
#[bench::radar_f64(setup = radar_f64)]
#[bench::radar_f32(setup = radar_f32)]
#[bench::network_f64(setup = network_f64)]
#[bench::network_f32(setup = network_f32)]
fn step(mut scan: Box<dyn Scan>) -> usize {
    black_box(scan.run())
}

type Chain = MetropolisSampler<f64, 64, 32, 32>;

fn chain_input() -> (Box<Chain>, Box<tracker_core::association::AssociationMatrix<f64, 64, 32>>) {
    let config =
        SamplerConfig { burn_in: 0, steps: 20_000, clusters: false, exhaustive_limit: 0, ..SamplerConfig::default() };
    (Box::new(MetropolisSampler::new(config, 7)), Box::new(crossing_matrix::<64, 32>(32, 64, 8, 1)))
}

#[library_benchmark]
#[bench::informed_32x64_20000_steps(setup = chain_input)]
fn chain(input: (Box<Chain>, Box<tracker_core::association::AssociationMatrix<f64, 64, 32>>)) -> usize {
    let (mut chain, matrix) = input;
    chain.run(black_box(&matrix));
    black_box(chain.best().len())
}

fn ekf_input() -> (Gaussian<f64, 4>, SVector<f64, 2>) {
    let look = 15f64.to_radians();
    let (r, v) = (7_000.0, (benches::EARTH_MU / 7_000.0f64).sqrt());
    let prior = Gaussian {
        mean: SVector::from([r * look.cos(), r * look.sin(), -v * look.sin(), v * look.cos()]),
        covariance: SMatrix::from_diagonal(&SVector::from([1.0, 1.0, 4e-8, 4e-8])),
    };
    (prior, SVector::from([0.4, -0.3]))
}

#[library_benchmark]
#[bench::two_body_f64(setup = ekf_input)]
fn ekf_predict_update(input: (Gaussian<f64, 4>, SVector<f64, 2>)) -> f64 {
    let (prior, offset) = input;
    let measurement = PositionMeasurement::isotropic(0.5);
    let Ok(predicted) = ekf::predict(&ssa_motion::<f64>(), black_box(&prior), black_box(60.0)) else { return 0.0 };
    let Ok(innovation) = ekf::innovation(&measurement, &predicted) else { return 0.0 };
    let z = innovation.predicted + offset;
    black_box(ekf::update(&measurement, &predicted, &innovation, black_box(&z)).map_or(0.0, |g| g.mean[0]))
}

library_benchmark_group!(name = worst_case_step, benchmarks = [step]);
library_benchmark_group!(name = kernels, benchmarks = [chain, ekf_predict_update]);

main!(library_benchmark_groups = worst_case_step, kernels);
