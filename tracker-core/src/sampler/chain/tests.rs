//! The chain's tests: a consistent state under every proposal, the same chain pipelined or not, early
//! or late rejection, and exact posteriors against enumeration.

use super::steps::{INFORMED, PAPER, UNIFORM};
use super::*;
use crate::children::ExhaustiveChildren;
use crate::sampler::best::association_hash;
use crate::sampler::{Proposal, REQUIRED_PENALTY};
use rand_core::Rng;
use std::collections::{BTreeMap, BTreeSet};
use std::vec::Vec;

fn random_matrix(seed: u64, rows: usize, columns: usize) -> AssociationMatrix<f64, 8, 6> {
    let mut s = crate::random::test_stream(seed);
    let mut m = AssociationMatrix::new(rows, columns, -3.0);
    for c in 0..columns {
        let entries: Vec<f64> = (0..rows)
            .map(|_| {
                let u = (s.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
                if u < 0.25 { f64::NEG_INFINITY } else { 8.0 * u - 3.0 }
            })
            .collect();
        m.set_column(c, &entries, false);
    }
    m
}

fn check_chain(sampler: &MetropolisSampler<f64, 8, 6, 16>, m: &AssociationMatrix<f64, 8, 6>) {
    let chain = &sampler.chain;
    let rows = m.rows();
    let mut owner = [NONE; 8];
    let mut sum = 0.0;
    for row in 0..rows {
        let c = chain.assignment[row];
        if c != CLUTTER {
            assert_eq!(owner[c as usize], NONE, "column {c} assigned twice");
            owner[c as usize] = row as u16;
            sum += m.entry(row, c as usize);
        }
    }
    assert_eq!(&owner[..m.columns()], &chain.owner[..m.columns()]);
    let unassigned = (0..m.columns()).filter(|&c| m.is_required(c) && owner[c] == NONE).count();
    assert_eq!(unassigned, chain.unassigned_required);
    assert!((chain.score - (sum - REQUIRED_PENALTY * unassigned as f64)).abs() < 1e-9);
    assert_eq!(chain.hash, association_hash(&chain.assignment[..rows]));
}

/// `moves` Metropolis moves, the chain's state checked after each.
fn checked_moves(sampler: &mut MetropolisSampler<f64, 8, 6, 16>, m: &AssociationMatrix<f64, 8, 6>, moves: usize) {
    check_chain(sampler, m);
    for _ in 0..moves {
        sampler.metropolis_move(m);
        check_chain(sampler, m);
    }
}

#[test]
fn chain_state_stays_consistent_under_both_proposals() {
    for proposal in [Proposal::Paper, Proposal::MoveOrSwap, Proposal::Informed] {
        for seed in 0..20 {
            let mut m = random_matrix(seed, 5, 7);
            m.set_required((seed % 7) as usize, seed % 2 == 0);
            let mut sampler =
                MetropolisSampler::<f64, 8, 6, 16>::new(SamplerConfig { proposal, ..SamplerConfig::default() }, seed);
            sampler.build_tables(&m);
            // Both starts, the optimal one and its greedy fallback.
            if seed % 2 == 0 {
                assert!(sampler.start_optimal(&m));
            } else {
                sampler.start_greedy(&m);
                check_chain(&sampler, &m);
                sampler.climb(&m);
            }
            checked_moves(&mut sampler, &m, 2_000);
        }
    }
}

/// Entries hundreds of nats apart make linear weights underflow to 0 and ratios to 0 / 0: impossible
/// moves (NaN weights) must still never be accepted, and the state must stay consistent.
#[test]
fn underflowing_weights_never_let_an_impossible_move_through() {
    for proposal in [Proposal::Paper, Proposal::MoveOrSwap, Proposal::Informed] {
        for seed in 0..20 {
            let mut s = crate::random::test_stream(seed + 500);
            let mut m = AssociationMatrix::<f64, 8, 6>::new(5, 6, -3.0);
            for c in 0..6 {
                let entries: Vec<f64> = (0..5)
                    .map(|_| {
                        let u = (s.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
                        if u < 0.3 { f64::NEG_INFINITY } else { 2_000.0 * u - 1_300.0 }
                    })
                    .collect();
                m.set_column(c, &entries, false);
            }
            m.set_required((seed % 6) as usize, seed % 3 == 0);
            let config = SamplerConfig { proposal, ..SamplerConfig::default() };
            let mut sampler = MetropolisSampler::<f64, 8, 6, 16>::new(config, seed);
            sampler.build_tables(&m);
            sampler.start_greedy(&m);
            checked_moves(&mut sampler, &m, 5_000);
        }
    }
}

/// Returning early on an infeasible swap (in-order targets) and rejecting its NaN ratio (speculative
/// ones) make the same decisions: the two chains stay identical, move for move.
#[test]
fn early_and_late_rejection_follow_the_same_chain() {
    for proposal in [Proposal::Paper, Proposal::MoveOrSwap, Proposal::Informed] {
        for seed in 0..20 {
            let mut m = random_matrix(seed + 700, 6, 8);
            m.set_required((seed % 8) as usize, seed % 3 == 0);
            let config = SamplerConfig { proposal, ..SamplerConfig::default() };
            let mut early = MetropolisSampler::<f64, 8, 6, 16>::new(config, seed);
            early.build_tables(&m);
            early.start_greedy(&m);
            let mut late = early.clone();
            let (mut early_rng, mut late_rng) = (early.rng.take().unwrap(), late.rng.take().unwrap());
            let mut moved = 0;
            for i in 0..4_000 {
                let (a, b) = match (proposal, i % 2) {
                    (Proposal::Paper, _) => (
                        early.step_with::<PAPER, true>(&m, &mut early_rng),
                        late.step_with::<PAPER, false>(&m, &mut late_rng),
                    ),
                    (Proposal::Informed, 0) => (
                        early.step_with::<INFORMED, true>(&m, &mut early_rng),
                        late.step_with::<INFORMED, false>(&m, &mut late_rng),
                    ),
                    _ => (
                        early.step_with::<UNIFORM, true>(&m, &mut early_rng),
                        late.step_with::<UNIFORM, false>(&m, &mut late_rng),
                    ),
                };
                assert_eq!(a, b, "{proposal:?}, seed {seed}, move {i}");
                moved += usize::from(a);
            }
            assert!(moved > 0);
            assert_eq!(early.chain.assignment, late.chain.assignment);
            assert_eq!(early.chain.hash, late.chain.hash);
            assert_eq!(early.chain.score.to_bits(), late.chain.score.to_bits());
            check_chain(&late, &m);
        }
    }
}

/// The guide's start and scan give the binary search's index for every draw: at bucket edges, at
/// bounds and beside them, and past the guide's cap of 255 (a row of 300 columns).
fn guided_index_is_the_binary_search<const N: usize, const Z: usize>(m: &AssociationMatrix<f64, N, Z>) {
    let mut sampler = MetropolisSampler::<f64, N, Z, 4>::new(SamplerConfig::default(), 1);
    sampler.build_tables(m);
    let mut s = crate::random::test_stream(9);
    for row in 0..m.rows() {
        let count = usize::from(sampler.row_count[row]);
        let bounds = &sampler.cumulative[row][..count];
        let mut draws: Vec<u32> = (0..2_000).map(|_| s.next_u64() as u32).collect();
        draws.extend((0..=32u64).map(|b| ((b << GUIDE_SHIFT) as u32).wrapping_sub(1)));
        draws.extend((0..32u32).map(|b| b << GUIDE_SHIFT));
        for &bound in bounds {
            draws.extend([bound.wrapping_sub(1), bound, bound.wrapping_add(1)]);
        }
        for bits in draws {
            let expected = bounds.partition_point(|&bound| bound <= bits);
            assert_eq!(sampler.informed_index(row, count, bits), expected, "row {row}, bits {bits}");
        }
    }
}

#[test]
fn the_guide_table_finds_the_binary_search_index() {
    for seed in 0..20 {
        guided_index_is_the_binary_search(&random_matrix(seed, 6, 8));
    }
    // Rows of 300 columns: one with equal entries, one with a dominant entry (most bounds in the top
    // bucket), one with tiny weights (bounds crowded in the first bucket).
    let mut m = AssociationMatrix::<f64, 300, 3>::new(3, 300, -3.0);
    for c in 0..300 {
        let spread = if c == 150 { 40.0 } else { -0.01 * c as f64 };
        m.set_column(c, &[0.5, spread, -30.0 - 0.01 * c as f64], false);
    }
    guided_index_is_the_binary_search(&m);
}

#[test]
fn symmetric_and_informed_proposals_sample_the_exact_posterior() {
    for proposal in [Proposal::MoveOrSwap, Proposal::Informed] {
        exact_posterior(proposal);
    }
}

fn exact_posterior(proposal: Proposal) {
    // Detailed balance: visit frequencies converge to the normalised weights.
    let m = random_matrix(3, 3, 3);
    let mut all = Vec::new();
    struct Sink<'a>(&'a mut Vec<(f64, Vec<u16>)>);
    impl ChildSink<f64> for Sink<'_> {
        fn offer(&mut self, w: f64, a: &[u16]) {
            self.0.push((w, a.to_vec()));
        }
    }
    ExhaustiveChildren::new(u64::MAX).generate(&m, &mut Sink(&mut all)).unwrap();
    let total: f64 = all.iter().map(|c| c.0.exp()).sum();
    let mut sampler =
        MetropolisSampler::<f64, 8, 6, 16>::new(SamplerConfig { proposal, ..SamplerConfig::default() }, 5);
    sampler.build_tables(&m);
    assert!(sampler.start_optimal(&m));
    let mut counts: BTreeMap<Vec<u16>, u64> = BTreeMap::new();
    let n = 2_000_000;
    for _ in 0..n {
        sampler.metropolis_move(&m);
        *counts.entry(sampler.chain.assignment[..3].to_vec()).or_default() += 1;
        check_chain(&sampler, &m);
    }
    for (w, a) in &all {
        let p = w.exp() / total;
        let f = counts.get(a).copied().unwrap_or(0) as f64 / n as f64;
        assert!((f - p).abs() < 0.004 + 0.03 * p, "{proposal:?} {a:?}: frequency {f} vs probability {p}");
    }
}

/// The informed chain alternates its kinds of step by the move's number since the chain's start, so
/// moves made one at a time follow the same chain as the moves of `run`, including an odd count
/// split across burn-in and recorded steps.
#[test]
fn single_moves_follow_the_same_chain_as_run() {
    // `run` pipelines its steps on a host (`PIPELINE`); `metropolis_move` makes one at a time.
    for proposal in [Proposal::Paper, Proposal::MoveOrSwap, Proposal::Informed] {
        for (seed, burn_in, steps) in [(1, 0, 101), (2, 7, 50), (3, 1, 1), (4, 33, 333)] {
            let m = random_matrix(seed + 40, 6, 8);
            let config = |burn_in, steps| SamplerConfig { burn_in, steps, proposal, ..SamplerConfig::default() };
            let mut whole = MetropolisSampler::<f64, 8, 6, 16>::new(config(burn_in, steps), seed);
            whole.run(&m);
            let mut single = MetropolisSampler::<f64, 8, 6, 16>::new(config(0, 1), seed);
            single.run_with_moves(&m, 0); // tables, start and neighbours; no move
            for _ in 0..burn_in + steps {
                single.metropolis_move(&m);
            }
            assert_eq!(whole.steps_taken(), single.steps_taken());
            assert_eq!(whole.accepted(), single.accepted(), "{proposal:?}, seed {seed}");
            assert_eq!(whole.chain.assignment, single.chain.assignment, "{proposal:?}, seed {seed}");
            assert_eq!(whole.chain.hash, single.chain.hash);
            // The pipelined loop draws no proposal beyond its last step.
            assert_eq!(whole.rng, single.rng, "{proposal:?}, seed {seed}");
        }
    }
}

#[test]
fn a_chain_without_steps_offers_the_best_child_and_its_neighbours() {
    struct Sink(Vec<(f64, Vec<u16>)>);
    impl ChildSink<f64> for Sink {
        fn offer(&mut self, w: f64, a: &[u16]) {
            self.0.push((w, a.to_vec()));
        }
    }
    for seed in 0..50 {
        let mut m = random_matrix(seed + 200, 6, 5);
        m.set_required((seed % 5) as usize, seed % 3 == 0);
        let mut all = Sink(Vec::new());
        ExhaustiveChildren::new(u64::MAX).generate(&m, &mut all).unwrap();
        let best = all.0.iter().map(|c| c.0).fold(f64::NEG_INFINITY, f64::max);
        let config = SamplerConfig { burn_in: 0, steps: 0, clusters: false, ..SamplerConfig::default() };
        let mut sampler = MetropolisSampler::<f64, 8, 6, 64>::new(config, seed);
        let mut offered = Sink(Vec::new());
        sampler.generate(&m, &mut offered).unwrap();
        assert_eq!(sampler.steps_taken(), 0);
        let found = offered.0.iter().map(|c| c.0).fold(f64::NEG_INFINITY, f64::max);
        assert_eq!(found, best, "seed {seed}");
        if best > f64::NEG_INFINITY {
            // The mode's feasible neighbours come with it: more than one child whenever one exists.
            assert!(offered.0.len() > 1 || all.0.len() == 1, "seed {seed}: {} children", offered.0.len());
        }
    }
}

#[test]
fn offered_children_are_distinct_with_exact_weights() {
    for seed in 0..30 {
        let m = random_matrix(seed + 100, 5, 6);
        // Both chain starts: the exact mode and the greedy start with its climb.
        let config = SamplerConfig { exact_start: seed % 2 == 0, ..SamplerConfig::default() };
        let mut sampler = MetropolisSampler::<f64, 8, 6, 16>::new(config, seed);
        let mut offered = Vec::new();
        struct Sink<'a>(&'a mut Vec<(f64, Vec<u16>)>);
        impl ChildSink<f64> for Sink<'_> {
            fn offer(&mut self, w: f64, a: &[u16]) {
                self.0.push((w, a.to_vec()));
            }
        }
        sampler.generate(&m, &mut Sink(&mut offered)).unwrap();
        let distinct: BTreeSet<_> = offered.iter().map(|c| c.1.clone()).collect();
        assert_eq!(distinct.len(), offered.len());
        for (w, a) in &offered {
            assert_eq!(*w, m.score(a));
        }
    }
}
