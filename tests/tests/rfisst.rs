//! R-FISST's sampled children against the exhaustive answer (issue 4, docs/maths.md §7).

use conformance::*;
use tracker_core::association::{AssociationMatrix, CLUTTER};
use tracker_core::children::{ChildGenerator, ChildSink};
use tracker_core::cluster::ClusteredChildren;
use tracker_core::config::Selection;
use tracker_core::sampler::{MetropolisSampler, Proposal, SamplerConfig};
use tracker_core::{BirthModel, ChildGeneration, LinearConfig, LinearTracker};

const FIG4: [[f64; 10]; 5] = [
    [0.1, 0.2, 0.0, 0.03, 0.05, 0.004, 0.002, 0.001, 0.01, 0.005],
    [0.04, 0.03, 0.05, 0.01, 0.04, 0.014, 0.2, 0.004, 0.005, 0.006],
    [0.09, 0.05, 0.04, 0.03, 0.01, 0.004, 0.005, 0.006, 0.1, 0.001],
    [0.09, 0.04, 0.1, 0.01, 0.02, 0.04, 0.3, 0.004, 0.005, 0.006],
    [0.001, 0.003, 0.002, 0.004, 0.005, 0.006, 0.007, 0.5, 0.01, 0.03],
];

struct Best(f64, Vec<u16>);

impl ChildSink<f64> for Best {
    fn offer(&mut self, w: f64, a: &[u16]) {
        if w > self.0 {
            self.0 = w;
            self.1 = a.to_vec();
        }
    }
}

#[test]
fn the_sampler_finds_the_fig4_map() {
    let rows: Vec<&[f64]> = FIG4.iter().map(|r| r.as_slice()).collect();
    let m = AssociationMatrix::<f64, 10, 5>::from_likelihoods(&rows, &[0.02; 5]);
    let map: Vec<u16> = [2, 7, 9, 3, 8].iter().map(|c| c - 1).collect();
    for proposal in [Proposal::Paper, Proposal::MoveOrSwap, Proposal::Informed] {
        for seed in 0..20 {
            let config = SamplerConfig { proposal, ..SamplerConfig::default() };
            let mut plain = MetropolisSampler::<f64, 10, 5, 32>::new(config, seed);
            let mut best = Best(f64::NEG_INFINITY, vec![]);
            plain.generate(&m, &mut best).unwrap();
            assert_eq!(best.1, map, "{proposal:?}, seed {seed}");
            assert!((best.0.exp() - 2.0e-4).abs() < 1e-15);
            let mut clustered =
                ClusteredChildren::<f64, 10, 5, 32>::new(SamplerConfig { exhaustive_limit: 0, ..config }, seed);
            let mut best = Best(f64::NEG_INFINITY, vec![]);
            clustered.generate(&m, &mut best).unwrap();
            assert_eq!(best.1, map, "clustered {proposal:?}, seed {seed}");
        }
    }
    assert!(!map.contains(&CLUTTER));
}

/// Dense clutter and broad births keep every child within a few e-folds of the best, so that a chain of
/// moderate length visits them all.
fn config(children: ChildGeneration) -> LinearConfig<f64, 2> {
    let mut config = linear_config::<2>(0.85, 20.0, 100.0);
    config.birth = BirthModel {
        events: Default::default(),
        measured: None,
        probability: 0.05,
        cells: [gaussian([1.5, 1.0, 0.0, 0.0], 4.0)].into_iter().collect(),
        detection: Default::default(),
    };
    config.death_probability = 0.05;
    config.children = children;
    config
}

type Big = LinearTracker<f64, 2048, 8, 6, 4096, 2>;

fn scans() -> Vec<Vec<V2>> {
    vec![vec![V2::new(0.9, 0.1), V2::new(1.6, 0.4), V2::new(3.2, 3.1)], vec![V2::new(2.1, 0.0), V2::new(3.1, 2.9)]]
}

fn objects() -> Vec<tracker_core::Gaussian<f64, 4>> {
    vec![gaussian([0.0, 0.0, 1.0, 0.0], 0.5), gaussian([0.8, 0.4, 0.9, 0.1], 0.5)]
}

/// (state bits of every track, weight) per hypothesis, sorted.
fn hypotheses(t: &Big) -> Vec<(Vec<u64>, f64)> {
    let mut out: Vec<_> = t
        .hypotheses()
        .map(|h| {
            let mut bits: Vec<Vec<u64>> = h
                .tracks()
                .map(|tr| tr.state.mean.iter().chain(tr.state.covariance.iter()).map(|v| v.to_bits()).collect())
                .collect();
            bits.sort();
            (bits.concat(), h.weight())
        })
        .collect();
    out.sort_by(|a, b| a.0.cmp(&b.0));
    out
}

#[test]
fn with_a_budget_that_visits_every_child_the_sampler_equals_exhaustive_enumeration() {
    with_large_stack(sampler_equals_exhaustive);
}

fn sampler_equals_exhaustive() {
    let exhaustive = config(ChildGeneration::Exhaustive { max_children_per_scan: 10_000_000 });
    let reference = Box::new(Big::with_objects(exhaustive, &objects(), 0.0).unwrap());
    // Pure chains visit every child of the first scan (all within e^-12 of the best of their chain);
    // clusters enumerated exhaustively reproduce both scans.
    let cases = [
        (SamplerConfig { steps: 100_000, clusters: false, ..SamplerConfig::default() }, 1),
        (SamplerConfig { steps: 100_000, exhaustive_limit: 0, ..SamplerConfig::default() }, 1),
        (SamplerConfig { exhaustive_limit: SamplerConfig::MAX_EXHAUSTIVE_LIMIT, ..SamplerConfig::default() }, 2),
        (SamplerConfig::default(), 2),
    ];
    for (configuration, scans_checked) in cases {
        let mut sampled =
            Box::new(Big::with_objects(config(ChildGeneration::Sampled(configuration)), &objects(), 0.0).unwrap());
        let mut exact = Box::new((*reference).clone());
        for (k, zs) in scans().iter().enumerate().take(scans_checked) {
            let report = sampled.step(k as f64 + 1.0, zs).unwrap();
            exact.step(k as f64 + 1.0, zs).unwrap();
            assert!(report.hypotheses > 30, "a problem with many children: {}", report.hypotheses);
            assert!((report.captured_mass - 1.0).abs() < 1e-12, "H∞ holds every child");
            let (a, b) = (hypotheses(&sampled), hypotheses(&exact));
            assert_eq!(a.len(), b.len(), "{configuration:?}, scan {k}: same hypotheses");
            for (x, y) in a.iter().zip(&b) {
                assert_eq!(x.0, y.0, "identical track states");
                assert!(
                    relative_difference(x.1, y.1) < 1e-12,
                    "{configuration:?}, scan {k}: weight {} vs {}",
                    x.1,
                    y.1
                );
            }
        }
    }
}

#[test]
fn chains_long_enough_to_visit_every_child_offer_exactly_the_exhaustive_children() {
    use tracker_core::children::ExhaustiveChildren;
    struct All(Vec<(f64, Vec<u16>)>);
    impl ChildSink<f64> for All {
        fn offer(&mut self, w: f64, a: &[u16]) {
            self.0.push((w, a.to_vec()));
        }
    }
    let mut state = 17u64;
    let mut next = || {
        state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    for trial in 0..40 {
        let (rows, columns) = (1 + trial % 4, 1 + trial % 5);
        let mut m = AssociationMatrix::<f64, 8, 6>::new(rows, columns, -1.0);
        for c in 0..columns {
            // Entries within ±1 nat: every child is within e^-8 of the best.
            let entries: Vec<f64> = (0..rows).map(|_| 2.0 * next() - 1.0).collect();
            m.set_column(c, &entries, trial % 3 == 0 && c == 0);
        }
        let mut exhaustive = All(vec![]);
        ExhaustiveChildren::new(u64::MAX).generate(&m, &mut exhaustive).unwrap();
        for proposal in [Proposal::Paper, Proposal::MoveOrSwap, Proposal::Informed] {
            let mut sampler = MetropolisSampler::<f64, 8, 6, 512>::new(
                SamplerConfig { proposal, steps: 200_000, ..SamplerConfig::default() },
                trial as u64,
            );
            let mut sampled = All(vec![]);
            sampler.generate(&m, &mut sampled).unwrap();
            let mut e = exhaustive.0.clone();
            let mut s = sampled.0;
            e.sort_by(|a, b| a.1.cmp(&b.1));
            s.sort_by(|a, b| a.1.cmp(&b.1));
            assert_eq!(e, s, "trial {trial}, {proposal:?}: same children, bit-identical weights");
        }
    }
}

#[test]
fn doubling_the_budget_never_changes_the_ratio_of_two_children_found_in_both() {
    type Small = LinearTracker<f64, 24, 8, 6, 512, 2>;
    let run = |steps: u32| {
        let sampler = SamplerConfig { steps, burn_in: 0, clusters: false, ..SamplerConfig::default() };
        let mut t = Small::with_objects(config(ChildGeneration::Sampled(sampler)), &objects(), 0.0).unwrap();
        t.step(1.0, &scans()[0]).unwrap();
        t.hypotheses()
            .map(|h| {
                let mut bits: Vec<u64> =
                    h.tracks().flat_map(|tr| tr.state.mean.iter().map(|v| v.to_bits()).collect::<Vec<_>>()).collect();
                bits.sort();
                (bits, h.weight())
            })
            .collect::<Vec<_>>()
    };
    let mut compared = 0;
    for steps in [10, 40, 160, 640] {
        let (short, long) = (run(steps), run(2 * steps));
        let common: Vec<(f64, f64)> =
            short.iter().filter_map(|(k, w)| long.iter().find(|(k2, _)| k2 == k).map(|(_, w2)| (*w, *w2))).collect();
        for a in &common {
            for b in &common {
                assert!(relative_difference(a.0 / b.0, a.1 / b.1) < 1e-12);
                compared += 1;
            }
        }
    }
    assert!(compared > 100, "enough pairs compared: {compared}");
}

#[test]
fn same_seed_same_bits_and_seeds_matter() {
    let run = |seed: u64| {
        let mut c =
            config(ChildGeneration::Sampled(SamplerConfig { steps: 50, clusters: false, ..SamplerConfig::default() }));
        c.seed = seed;
        let mut t = LinearTracker::<f64, 8, 8, 6, 512, 2>::with_objects(c, &objects(), 0.0).unwrap();
        for (k, zs) in scans().iter().enumerate() {
            t.step(k as f64 + 1.0, zs).unwrap();
        }
        fingerprint(&t)
    };
    assert_eq!(run(3), run(3));
    let distinct: std::collections::BTreeSet<Vec<u64>> = (0..8).map(run).collect();
    assert!(distinct.len() > 1, "a short chain's result depends on its seed");
}

#[test]
fn selection_by_sampling_keeps_children_in_proportion_to_weight() {
    // One object, one measurement: children "detected" and "missed / clutter"; H∞ = 1 keeps one.
    let mut c = linear_config::<1>(0.5, 1.0, 400.0);
    c.selection = Selection::SampledByWeight;
    let z = [V2::new(1.0, 0.0)];
    let mut kept_detected = 0;
    let trials = 4000;
    let mut exact = LinearTracker::<f64, 4, 2, 2, 8, 1>::with_objects(
        linear_config::<1>(0.5, 1.0, 400.0),
        &[gaussian([0.0, 0.0, 1.0, 0.0], 0.5)],
        0.0,
    )
    .unwrap();
    exact.step(1.0, &z).unwrap();
    let p_detected =
        exact.hypotheses().find(|h| h.tracks().next().unwrap().state.covariance[(0, 0)] < 0.5).unwrap().weight();
    for seed in 0..trials {
        c.seed = seed;
        let mut t =
            LinearTracker::<f64, 1, 2, 2, 8, 1>::with_objects(c.clone(), &[gaussian([0.0, 0.0, 1.0, 0.0], 0.5)], 0.0)
                .unwrap();
        t.step(1.0, &z).unwrap();
        assert_eq!(t.hypotheses().len(), 1);
        if t.map_hypothesis().tracks().next().unwrap().state.covariance[(0, 0)] < 0.5 {
            kept_detected += 1;
        }
    }
    let frequency = kept_detected as f64 / trials as f64;
    assert!((frequency - p_detected).abs() < 0.03, "kept {frequency}, weight {p_detected}");
}

/// A floor under the weights (`Selection::TopWeightWithin`) drops exactly the children lighter than
/// 10^−decades of the heaviest, the dropped mass shows in the captured mass, and a floor below every child
/// changes nothing.
#[test]
fn a_floor_under_the_weights_drops_only_the_children_below_it() {
    let object = [gaussian([0.0, 0.0, 1.0, 0.0], 0.5)];
    let z = [V2::new(1.0, 0.0)];
    let step = |selection: Selection| {
        let mut c = linear_config::<1>(0.5, 1.0, 400.0);
        c.selection = selection;
        let mut t = LinearTracker::<f64, 4, 2, 2, 8, 1>::with_objects(c, &object, 0.0).unwrap();
        let report = t.step(1.0, &z).unwrap();
        let weights: Vec<f64> = t.hypotheses().map(|h| h.weight()).collect();
        (weights, report.captured_mass, t.digest())
    };
    let (exact, captured, digest) = step(Selection::TopWeight);
    assert_eq!(exact.len(), 2, "detected and missed");
    assert_eq!(captured, 1.0);
    let ratio = exact[1] / exact[0];
    let decades = (-ratio.log10()).floor();
    assert!((1.0..20.0).contains(&decades), "the missed child is {ratio} of the detected one");
    // Floors above and below the lighter child.
    let (above, captured_above, _) = step(Selection::TopWeightWithin { decades: (decades - 1.0) as u8 });
    assert_eq!(above, vec![1.0], "only the heaviest child is left, renormalised");
    assert!((captured_above - exact[0]).abs() < 1e-12, "captured {captured_above}, heaviest {}", exact[0]);
    let (below, captured_below, digest_below) = step(Selection::TopWeightWithin { decades: (decades + 1.0) as u8 });
    assert_eq!((below, captured_below, digest_below), (exact, 1.0, digest));
}

/// The caller's move budget per scan is never exceeded, whatever its size, with clusters or one chain per
/// matrix; no budget (`u64::MAX`) is exactly `step`; a budget of 0 still gives every parent's best children
/// (the exact starts).
#[test]
fn a_scan_never_makes_more_moves_than_its_budget() {
    with_large_stack(budget_never_exceeded);
}

fn budget_never_exceeded() {
    for clusters in [true, false] {
        let sampler = SamplerConfig { clusters, exhaustive_limit: 0, ..SamplerConfig::default() };
        let start = Box::new(Big::with_objects(config(ChildGeneration::Sampled(sampler)), &objects(), 0.0).unwrap());
        let mut unlimited = Box::new((*start).clone());
        let mut same = Box::new((*start).clone());
        for (k, zs) in scans().iter().enumerate() {
            let time = k as f64 + 1.0;
            let full = unlimited.step(time, zs).unwrap();
            let also_full = same.step_with_budget(time, zs, u64::MAX).unwrap();
            assert_eq!(full, also_full);
            assert_eq!(unlimited.digest(), same.digest());
            assert!(full.sampler_steps >= 4_000, "the unlimited scan makes its chains' moves: {}", full.sampler_steps);
        }
        let mut previous_steps = 0;
        for budget in [0u64, 1, 7, 100, 999, 2_000, 4_000, 1_000_000] {
            let mut limited = Box::new((*start).clone());
            let report = limited.step_with_budget(1.0, &scans()[0], budget).unwrap();
            assert!(
                report.sampler_steps <= budget,
                "clusters {clusters}: {} moves > budget {budget}",
                report.sampler_steps
            );
            assert!(report.sampler_steps >= previous_steps, "a larger budget is used at least as much");
            previous_steps = report.sampler_steps;
            assert!(report.hypotheses > 0);
            let total: f64 = limited.hypotheses().map(|h| h.weight()).sum();
            assert!((total - 1.0).abs() < 1e-12);
        }
        // The budget is a large part of what a scan does: most of it is used when it is small.
        let mut limited = Box::new((*start).clone());
        let report = limited.step_with_budget(1.0, &scans()[0], 2_000).unwrap();
        assert!(report.sampler_steps >= 1_000, "clusters {clusters}: only {} of 2000 moves used", report.sampler_steps);
    }
}
