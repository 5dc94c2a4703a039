//! Runs a fixed number of Metropolis steps (for `perf stat` or callgrind instruction counts per step).
//!
//! `cargo run --release -p benches --example chain_steps -- <proposal: paper|move-or-swap|informed> <chains> [steps]`
//!
//! `steps` (default 20,000) is the length of each chain; 0 runs only each chain's set-up (tables, exact
//! start, the mode's neighbours), so the difference of two runs gives the cost of the steps alone.
use benches::crossing_matrix;
use std::hint::black_box;
use tracker_core::sampler::{MetropolisSampler, Proposal, SamplerConfig};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let proposal = match args.get(1).map(String::as_str) {
        Some("paper") => Proposal::Paper,
        Some("move-or-swap") => Proposal::MoveOrSwap,
        _ => Proposal::Informed,
    };
    let chains: u32 = args.get(2).and_then(|a| a.parse().ok()).unwrap_or(500);
    let steps: u32 = args.get(3).and_then(|a| a.parse().ok()).unwrap_or(20_000);
    let matrix = crossing_matrix::<64, 32>(32, 64, 8, 1);
    let config =
        SamplerConfig { burn_in: 0, steps, proposal, clusters: false, exhaustive_limit: 0, ..SamplerConfig::default() };
    let mut chain = MetropolisSampler::<f64, 64, 32, 32>::new(config, 7);
    for _ in 0..chains {
        chain.run(black_box(&matrix));
    }
    println!("{:?}: {} steps, {} accepted", proposal, chain.steps_taken(), chain.accepted());
}
