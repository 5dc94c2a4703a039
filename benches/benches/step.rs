//! A full `Tracker::step` of the default SSA configuration: `SsaTracker<f64>` with R-FISST sampled children
//! (`ChildGeneration::Sampled(SamplerConfig::default())`).
//!
//! - `step/fifty/scans_<a>_<b>`: scans a..b of the recorded `fifty-birth-death` scenario (seed 1, host-sim's
//!   preset), from a checkpoint of the tracker taken after scan a; the time is for all b − a scans.
//! - `step/worst_case/ssa_f64`: one scan at the caps (see `benches::worst_case`; the instruction-count bench
//!   measures the same scan).
//!
//! `cargo bench -p benches --bench step`
use benches::worst_case;
use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use host_sim::pipeline::planar::setup;
use nalgebra::SVector;
use std::hint::black_box;
use tracker_core::ssa_caps::{BIRTH_CELLS as B, HYPOTHESES as H, MEASUREMENTS as Z, OBJECTS as N, TRACKS as K};
use tracker_core::{PriorHypothesis, SsaTracker, Tracker};

/// The default embedded R-FISST tracker on a scenario, as host-sim's `core_runner` builds it.
fn fifty_tracker(scenario: &host_sim::scenario::Scenario) -> Box<SsaTracker<f64>> {
    let motion = setup::two_body(&scenario.motion).expect("two-body scenario");
    let config = setup::config(scenario, motion, setup::sampled(scenario)).expect("configuration");
    let prior = setup::prior(scenario);
    let hypotheses: Vec<PriorHypothesis<'_, f64, 4>> =
        prior.iter().map(|(weight, objects)| PriorHypothesis { weight: *weight, objects }).collect();
    Box::new(Tracker::new(config, &hypotheses, scenario.prior.time).expect("tracker"))
}

fn step(c: &mut Criterion) {
    let scenario = host_sim::sim::planar::fifty_birth_death(1).run();
    let scans: Vec<(f64, Vec<SVector<f64, 2>>)> =
        scenario.scans.iter().map(|scan| (scan.time, setup::measurements(scan))).collect();
    let mut group = c.benchmark_group("step");
    group.sample_size(10);
    let mut tracker = fifty_tracker(&scenario);
    let windows = [(0usize, 50usize), (300, 350)];
    let mut done = 0;
    for (start, end) in windows {
        for (time, measurements) in &scans[done..start] {
            tracker.step(*time, measurements).expect("scan");
        }
        done = start;
        let checkpoint = tracker.clone();
        group.bench_function(format!("fifty/scans_{start}_{end}"), |b| {
            b.iter_batched_ref(
                || checkpoint.clone(),
                |tracker| {
                    for (time, measurements) in &scans[start..end] {
                        black_box(tracker.step(*time, measurements).map(|r| r.hypotheses).unwrap_or(0));
                    }
                },
                BatchSize::PerIteration,
            )
        });
    }
    let case = worst_case::<f64, H, N, Z, K, B>(N - 1);
    group.bench_function("worst_case/ssa_f64", |b| {
        b.iter_batched_ref(
            || case.tracker.clone(),
            |tracker| black_box(tracker.step(case.time, &case.measurements).map(|r| r.hypotheses).unwrap_or(0)),
            BatchSize::PerIteration,
        )
    });
    group.finish();
}

criterion_group!(benches, step);
criterion_main!(benches);
