//! One Metropolis step with duplicate removal, at Z = 32 measurements and N = 64 objects, beside a floor
//! loop (one random draw, two table lookups, one compare) measured in the same run.
//!
//! `cargo bench -p benches --bench sampler`; the reported throughput is steps per second.

use benches::crossing_matrix;
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use rand_core::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use std::hint::black_box;
use tracker_core::sampler::{MetropolisSampler, Proposal, SamplerConfig};

const STEPS: u32 = 20_000;

fn sampler(c: &mut Criterion) {
    let matrix = crossing_matrix::<64, 32>(32, 64, 8, 1);
    let mut group = c.benchmark_group("sampler");
    group.throughput(Throughput::Elements(u64::from(STEPS)));
    for proposal in [Proposal::Paper, Proposal::MoveOrSwap, Proposal::Informed] {
        let config = SamplerConfig {
            burn_in: 0,
            steps: STEPS,
            proposal,
            clusters: false,
            exhaustive_limit: 0,
            ..SamplerConfig::default()
        };
        let mut chain = MetropolisSampler::<f64, 64, 32, 32>::new(config, 7);
        group.bench_function(format!("mcmc_step/32x64/{proposal:?}"), |b| {
            b.iter(|| {
                chain.run(black_box(&matrix));
                black_box(chain.best().len())
            })
        });
    }
    // The floor: one random draw, two table lookups and one compare per step.
    let table = [[0.5f64; 64]; 32];
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(7);
    group.bench_function("floor/32x64", |b| {
        b.iter(|| {
            let mut count = 0u32;
            for _ in 0..STEPS {
                let draw = rng.next_u64();
                let row = (((draw >> 32) * 32) >> 32) as usize;
                let column = (((draw & 0xffff_ffff) * 64) >> 32) as usize;
                let other = (column + 1) & 63;
                if black_box(table[row][column]) > black_box(table[row][other]) {
                    count += 1;
                }
            }
            black_box(count)
        })
    });
    group.finish();
}

criterion_group!(benches, sampler);
criterion_main!(benches);
