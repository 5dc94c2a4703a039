//! Compares the proposals at equal step budgets: fraction of the best-C mass found on random crossing
//! matrices small enough to enumerate.
//!
//! `cargo run --release -p benches --example proposal_quality`
use benches::{crossing_matrix, splitmix};
use std::time::Instant;
use tracker_core::association::AssociationMatrix;
use tracker_core::children::{ChildGenerator, ChildSink, ExhaustiveChildren};
use tracker_core::real::LogSumExp;
use tracker_core::sampler::{MetropolisSampler, Proposal, SamplerConfig};

struct All(Vec<(f64, Vec<u16>)>);
impl ChildSink<f64> for All {
    fn offer(&mut self, w: f64, a: &[u16]) {
        self.0.push((w, a.to_vec()));
    }
}

fn main() {
    const C: usize = 32;
    let mut seed = 1u64;
    for steps in [200u32, 1000, 5000] {
        let mut results = vec![];
        for proposal in [Proposal::Paper, Proposal::MoveOrSwap, Proposal::Informed] {
            let (mut captured_sum, mut top1, mut elapsed) = (0.0, 0, 0.0);
            let cases = 200;
            for case in 0..cases {
                let rows = 6 + (splitmix(&mut seed) % 4) as usize;
                let in_gate: usize = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(3);
                let m: AssociationMatrix<f64, 16, 12> = crossing_matrix(rows, rows + 2, in_gate, 1000 + case);
                let mut all = All(vec![]);
                ExhaustiveChildren::new(u64::MAX).generate(&m, &mut all).unwrap();
                all.0.sort_by(|a, b| b.0.total_cmp(&a.0));
                let mut best = LogSumExp::new();
                for c in all.0.iter().take(C) {
                    best.add(c.0);
                }
                let config = SamplerConfig {
                    burn_in: 0,
                    steps,
                    proposal,
                    clusters: false,
                    exhaustive_limit: 0,
                    ..SamplerConfig::default()
                };
                let mut sampler = MetropolisSampler::<f64, 16, 12, C>::new(config, case);
                let mut got = All(vec![]);
                let start = Instant::now();
                sampler.generate(&m, &mut got).unwrap();
                elapsed += start.elapsed().as_secs_f64();
                let mut found = LogSumExp::new();
                for c in &got.0 {
                    found.add(c.0);
                }
                captured_sum += (found.value() - best.value()).exp();
                if got.0.iter().any(|c| c.0 >= all.0[0].0) {
                    top1 += 1;
                }
            }
            results.push(format!(
                "{proposal:?}: mass of best {C} found {:.5}, MAP found {:.3}, {:.1} µs per chain",
                captured_sum / cases as f64,
                top1 as f64 / cases as f64,
                elapsed / cases as f64 * 1e6
            ));
        }
        println!("steps {steps}:");
        for r in results {
            println!("  {r}");
        }
    }
}
