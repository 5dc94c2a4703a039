//! A Gibbs sampler of associations (host only): the peer that GLMB/LMB trackers use to draw association
//! hypotheses (Vo, Vo and Hoang 2017, "An efficient implementation of the generalized labeled
//! multi-Bernoulli filter"), for comparison with R-FISST's Metropolis sampler (`host-sim perf`).
//!
//! The state is one association of an [`AssociationMatrix`]: per row (measurement) a column (object) or
//! clutter. A **sweep** resamples every row in turn from its conditional given the other rows: row j
//! takes clutter with weight 1 or a column c that no other row holds with weight e^{δ_{j,c}}; that is the
//! exact full conditional of the posterior w(σ) ∝ e^{Σ δ}, so "no column twice" holds by construction.
//! As in the GLMB form, the chain starts at the all-clutter association, the state after each sweep is a
//! sample, and the **distinct** samples are kept with their exact weights ([`AssociationMatrix::score`]),
//! never with visit counts.
//!
//! **Required columns.** A single-row update cannot move a required column from one row to another (the
//! state in between is invalid), so a chain over valid states only can be reducible (two rows, two
//! required columns: the two valid states never reach each other). The chain therefore runs on the
//! *relaxed* target that drops the requirement (a required column left unassigned weighs like any missed
//! column, e^0 relative to the baseline), which every state reaches through the all-clutter association,
//! and only its valid states are kept. The relaxed target equals the posterior on valid states, so the
//! visits to valid states follow the exact posterior over valid associations.
//!
//! **Cost.** Per row the linear weights e^{δ − max} of its possible columns are computed once; a row
//! update sums the weights of the free ones and draws from them, O(possible columns of the row), with no
//! `exp` (a row whose free options all underflow falls back to weights relative to their own maximum).

use crate::io::report::PerfGibbsCase;
use crate::peers::murty::Child;
use rand_core::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use std::collections::HashSet;
use std::hash::{BuildHasherDefault, Hasher};
use std::time::Instant;
use tracker_core::association::{AssociationMatrix, CLUTTER};

/// No row holds the column.
const FREE: u16 = u16::MAX;

/// A fast multiplicative hasher for the sample set (the set's keys are the chain's own states, not
/// adversarial input, so SipHash's protection buys nothing and costs about as much as a sweep).
#[derive(Default, Clone, Copy)]
struct FastHasher(u64);

impl Hasher for FastHasher {
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, bytes: &[u8]) {
        for chunk in bytes.chunks(8) {
            let mut word = [0u8; 8];
            word[..chunk.len()].copy_from_slice(chunk);
            self.write_u64(u64::from_le_bytes(word));
        }
    }

    fn write_u64(&mut self, word: u64) {
        self.0 = (self.0.rotate_left(5) ^ word).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }

    fn write_usize(&mut self, word: usize) {
        self.write_u64(word as u64);
    }
}

/// The distinct states seen.
type Seen = HashSet<Vec<u16>, BuildHasherDefault<FastHasher>>;

/// One possible column of a row.
#[derive(Debug, Clone, Copy)]
struct Possible {
    column: u16,
    /// δ of the entry.
    entry: f64,
    /// e^{δ − m} with m the row's largest log-weight (clutter's 0 included).
    linear: f64,
}

/// A Gibbs chain over the associations of one matrix.
#[derive(Debug, Clone)]
pub struct Gibbs<'a, const N: usize, const Z: usize> {
    matrix: &'a AssociationMatrix<f64, N, Z>,
    /// Per row, its possible columns.
    options: Vec<Vec<Possible>>,
    /// Per row, the linear weight of clutter, e^{−m}.
    clutter: Vec<f64>,
    /// Per row, its column or [`CLUTTER`].
    state: Vec<u16>,
    /// Per column, the row holding it or [`FREE`].
    owner: Vec<u16>,
    /// Required columns currently assigned.
    required_assigned: usize,
    rng: Xoshiro256PlusPlus,
}

impl<'a, const N: usize, const Z: usize> Gibbs<'a, N, Z> {
    /// A chain on `matrix` at the all-clutter association, seeded with `seed`.
    pub fn new(matrix: &'a AssociationMatrix<f64, N, Z>, seed: u64) -> Self {
        let (rows, columns) = (matrix.rows(), matrix.columns());
        let mut options = Vec::with_capacity(rows);
        let mut clutter = Vec::with_capacity(rows);
        for row in 0..rows {
            let mut line: Vec<Possible> = (0..columns)
                .filter_map(|column| {
                    let entry = matrix.entry(row, column);
                    (entry > f64::NEG_INFINITY).then_some(Possible { column: column as u16, entry, linear: 0.0 })
                })
                .collect();
            let top = line.iter().map(|o| o.entry).fold(0.0, f64::max);
            for option in &mut line {
                option.linear = (option.entry - top).exp();
            }
            clutter.push((-top).exp());
            options.push(line);
        }
        Self {
            matrix,
            options,
            clutter,
            state: vec![CLUTTER; rows],
            owner: vec![FREE; columns],
            required_assigned: 0,
            rng: Xoshiro256PlusPlus::seed_from_u64(seed),
        }
    }

    /// The current association: per row, its column or [`CLUTTER`].
    pub fn state(&self) -> &[u16] {
        &self.state
    }

    /// Whether the current association assigns every required column (the chain's other states are
    /// those of the relaxed target, see the module doc).
    pub fn is_valid(&self) -> bool {
        self.required_assigned == self.matrix.required_count()
    }

    /// Resamples every row once, in row order, from its conditional given the others.
    pub fn sweep(&mut self) {
        for row in 0..self.state.len() {
            self.update(row);
        }
    }

    /// Resamples row `row` from its conditional given the other rows.
    fn update(&mut self, row: usize) {
        // Release the row's column.
        let current = self.state[row];
        if current != CLUTTER {
            self.owner[usize::from(current)] = FREE;
            if self.matrix.is_required(usize::from(current)) {
                self.required_assigned -= 1;
            }
        }
        let options = &self.options[row];
        let owner = &self.owner;
        let free = |option: &Possible| owner[usize::from(option.column)] == FREE;
        let clutter = self.clutter[row];
        let mut total = clutter;
        for option in options {
            total += if free(option) { option.linear } else { 0.0 };
        }
        let uniform = (self.rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64);
        let chosen = if total > f64::MIN_POSITIVE {
            // Walk the free options until the draw is used up; rounding falls back to the last free one.
            let mut rest = uniform * total - clutter;
            let mut chosen = CLUTTER;
            if rest >= 0.0 {
                for option in options.iter().filter(|o| free(o)) {
                    chosen = option.column;
                    rest -= option.linear;
                    if rest < 0.0 {
                        break;
                    }
                }
            }
            chosen
        } else {
            // Every free option underflowed: weights relative to the largest free one.
            let top = options.iter().filter(|o| free(o)).map(|o| o.entry).fold(0.0, f64::max);
            let total = (-top).exp() + options.iter().filter(|o| free(o)).map(|o| (o.entry - top).exp()).sum::<f64>();
            let mut rest = uniform * total - (-top).exp();
            let mut chosen = CLUTTER;
            if rest >= 0.0 {
                for option in options.iter().filter(|o| free(o)) {
                    chosen = option.column;
                    rest -= (option.entry - top).exp();
                    if rest < 0.0 {
                        break;
                    }
                }
            }
            chosen
        };
        self.state[row] = chosen;
        if chosen != CLUTTER {
            self.owner[usize::from(chosen)] = row as u16;
            if self.matrix.is_required(usize::from(chosen)) {
                self.required_assigned += 1;
            }
        }
    }
}

/// The GLMB form: `sweeps` sweeps of a chain from the all-clutter association; the distinct valid
/// samples with their exact log-weights, in the order first drawn.
pub fn distinct_samples<const N: usize, const Z: usize>(
    matrix: &AssociationMatrix<f64, N, Z>,
    seed: u64,
    sweeps: u64,
) -> Vec<Child> {
    let mut chain = Gibbs::new(matrix, seed);
    let mut seen = Seen::default();
    let mut samples = Vec::new();
    for _ in 0..sweeps {
        chain.sweep();
        if chain.is_valid() && !seen.contains(chain.state()) {
            seen.insert(chain.state().to_vec());
            samples.push(Child { log_weight: matrix.score(chain.state()), assignment: chain.state().to_vec() });
        }
    }
    samples
}

/// How far a chain went towards a captured mass.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reach {
    /// Sweeps run: until the target was reached, or the cap.
    pub sweeps: u64,
    /// Whether the target was reached within the cap.
    pub reached: bool,
    /// Distinct valid samples kept.
    pub distinct: usize,
    /// Their mass, Σ e^{w − reference}.
    pub mass: f64,
}

/// Runs a chain from the all-clutter association until its distinct samples' mass Σ e^{w − reference}
/// reaches `target`, or for `max_sweeps` sweeps.
pub fn sweeps_to_mass<const N: usize, const Z: usize>(
    matrix: &AssociationMatrix<f64, N, Z>,
    seed: u64,
    reference: f64,
    target: f64,
    max_sweeps: u64,
) -> Reach {
    let mut chain = Gibbs::new(matrix, seed);
    let mut seen = Seen::default();
    let mut mass = 0.0;
    let mut sweeps = 0;
    while sweeps < max_sweeps && mass < target {
        chain.sweep();
        sweeps += 1;
        if chain.is_valid() && !seen.contains(chain.state()) {
            seen.insert(chain.state().to_vec());
            mass += (matrix.score(chain.state()) - reference).exp();
        }
    }
    Reach { sweeps, reached: mass >= target, distinct: seen.len(), mass }
}

/// One matrix of the Gibbs-against-sampler comparison of `host-sim perf`.
struct Case {
    label: String,
    seed: u64,
    matrix: Box<AssociationMatrix<f64, 64, 32>>,
    /// The MAP log-weight (the mass reference).
    reference: f64,
    /// The sampler's captured mass, Σ e^{w − reference} over its children.
    target: f64,
    reach: Reach,
    /// The mass of the best [`Bench::KEPT`] of those samples over the target.
    kept_share: f64,
    seconds: Vec<f64>,
}

/// Gibbs against R-FISST's default child generator at equal captured mass, on the matrices of the Murty
/// comparison (`host-sim perf`): per matrix, the time of a chain run until its distinct samples capture
/// the mass the sampler's children capture.
pub struct Bench {
    cases: Vec<Case>,
}

impl Bench {
    /// Sweeps allowed per matrix; a chain that needs more counts as "did not reach".
    pub const MAX_SWEEPS: u64 = 1_000_000;
    /// The chain's seed.
    pub const SEED: u64 = 5;
    /// Children a tracker keeps per parent (H∞ of the sampler compared with).
    pub const KEPT: usize = 32;

    /// The comparison on `cases`: (label, seed, matrix, MAP log-weight, the sampler's mass Σ e^{w − MAP}).
    /// Runs each chain once (untimed) to find how many sweeps it needs.
    pub fn new<'m>(cases: impl Iterator<Item = (String, u64, &'m AssociationMatrix<f64, 64, 32>, f64, f64)>) -> Self {
        let cases = cases
            .map(|(label, seed, matrix, reference, target)| {
                // The sampler's mass up to rounding (its children sum in another order).
                let target = target * (1.0 - 1e-12);
                let reach = sweeps_to_mass(matrix, Self::SEED, reference, target, Self::MAX_SWEEPS);
                // The same samples again (same seed and sweeps): how much of the mass the best KEPT hold.
                let mut weights: Vec<f64> =
                    distinct_samples(matrix, Self::SEED, reach.sweeps).iter().map(|c| c.log_weight).collect();
                weights.sort_by(|a, b| b.total_cmp(a));
                let kept: f64 = weights.iter().take(Self::KEPT).map(|w| (w - reference).exp()).sum();
                let kept_share = kept / target;
                let matrix = Box::new(matrix.clone());
                Case { label, seed, matrix, reference, target, reach, kept_share, seconds: Vec::new() }
            })
            .collect();
        Self { cases }
    }

    /// One timed run per matrix (a matrix whose chain did not reach the target is timed once, to the cap).
    pub fn sample(&mut self) {
        for case in &mut self.cases {
            if !case.reach.reached && !case.seconds.is_empty() {
                continue;
            }
            let start = Instant::now();
            let reach = sweeps_to_mass(&case.matrix, Self::SEED, case.reference, case.target, Self::MAX_SWEEPS);
            case.seconds.push(start.elapsed().as_secs_f64());
            std::hint::black_box(reach);
        }
    }

    /// Per matrix, Gibbs's time over the sampler's (`sampler_seconds`, one per matrix in the same order);
    /// a matrix not reached counts as +∞. Returns the ratios and the per-matrix details.
    pub fn ratios(&self, sampler_seconds: &[f64], median: impl Fn(&[f64]) -> f64) -> (Vec<f64>, Vec<PerfGibbsCase>) {
        self.cases
            .iter()
            .zip(sampler_seconds)
            .map(|(case, &sampler)| {
                let gibbs = median(&case.seconds);
                let ratio = if case.reach.reached { gibbs / sampler } else { f64::INFINITY };
                let detail = PerfGibbsCase {
                    matrix: case.label.clone(),
                    seed: case.seed,
                    target_mass_over_map: case.target,
                    reached: case.reach.reached,
                    gibbs_sweeps: case.reach.sweeps,
                    gibbs_distinct_samples: case.reach.distinct,
                    gibbs_best_32_mass_over_target: case.kept_share,
                    gibbs_us: gibbs * 1e6,
                    sampler_us: sampler * 1e6,
                    // JSON has no infinity: a matrix not reached has no ratio.
                    ratio: ratio.is_finite().then_some(ratio),
                };
                (ratio, detail)
            })
            .unzip()
    }

    /// The matrices' labels, in order.
    pub fn labels(&self) -> impl Iterator<Item = &str> {
        self.cases.iter().map(|c| c.label.as_str())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::{BTreeMap, BTreeSet};
    use tracker_core::children::{ChildGenerator, ChildSink, ExhaustiveChildren};

    struct All(Vec<(f64, Vec<u16>)>);

    impl ChildSink<f64> for All {
        fn offer(&mut self, log_weight: f64, assignment: &[u16]) {
            self.0.push((log_weight, assignment.to_vec()));
        }
    }

    fn exhaustive<const N: usize, const Z: usize>(m: &AssociationMatrix<f64, N, Z>) -> Vec<(f64, Vec<u16>)> {
        let mut all = All(vec![]);
        ExhaustiveChildren::new(u64::MAX).generate(m, &mut all).unwrap();
        all.0
    }

    fn next(state: &mut u64) -> f64 {
        *state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = *state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }

    /// A random matrix: up to 4 × 5, a quarter of the entries impossible, entries in [−2, 2], a column
    /// required with probability `required`.
    fn random_matrix(state: &mut u64, required: f64) -> AssociationMatrix<f64, 5, 4> {
        let rows = 1 + (next(state) * 4.0) as usize;
        let columns = 1 + (next(state) * 5.0) as usize;
        let mut m = AssociationMatrix::new(rows, columns, -0.7);
        for c in 0..columns {
            let entries: Vec<f64> = (0..rows)
                .map(|_| if next(state) < 0.25 { f64::NEG_INFINITY } else { 4.0 * next(state) - 2.0 })
                .collect();
            m.set_column(c, &entries, next(state) < required);
        }
        m
    }

    /// Independent of `score`: one column or clutter per row, no column twice, every required column.
    fn valid<const N: usize, const Z: usize>(m: &AssociationMatrix<f64, N, Z>, assignment: &[u16]) -> bool {
        let mut used = BTreeSet::new();
        for (row, &column) in assignment.iter().enumerate() {
            if column == CLUTTER {
                continue;
            }
            let c = usize::from(column);
            if c >= m.columns() || !used.insert(c) || m.entry(row, c) == f64::NEG_INFINITY {
                return false;
            }
        }
        assignment.len() == m.rows() && (0..m.columns()).all(|c| !m.is_required(c) || used.contains(&c))
    }

    #[test]
    fn gibbs_distinct_samples_are_the_exhaustive_set() {
        let mut state = 23u64;
        let mut with_required = 0;
        for case in 0..120 {
            let m = random_matrix(&mut state, if case % 2 == 0 { 0.0 } else { 0.4 });
            with_required += usize::from(m.required_count() > 0);
            let all: BTreeMap<Vec<u16>, f64> = exhaustive(&m).into_iter().map(|(w, a)| (a, w)).collect();
            // Enough sweeps to visit the least likely valid association about 200 times, were the
            // sweeps independent and every state valid.
            let top = all.values().copied().fold(f64::NEG_INFINITY, f64::max);
            let total: f64 = all.values().map(|w| (w - top).exp()).sum();
            let least = all.values().map(|w| (w - top).exp() / total).fold(1.0, f64::min);
            let sweeps = ((200.0 / least) as u64).clamp(1_000, 400_000);
            let samples = distinct_samples(&m, case, sweeps);
            let got: BTreeMap<Vec<u16>, f64> = samples.iter().map(|c| (c.assignment.clone(), c.log_weight)).collect();
            assert_eq!(got.len(), samples.len(), "case {case}: samples kept twice");
            assert_eq!(got.keys().collect::<Vec<_>>(), all.keys().collect::<Vec<_>>(), "case {case}: {sweeps} sweeps");
            for (assignment, w) in &got {
                assert_eq!(*w, all[assignment], "case {case}: exact weight");
            }
        }
        assert!(with_required > 20, "{with_required} matrices with required columns");
    }

    #[test]
    fn gibbs_visits_follow_the_exact_posterior() {
        // A 3 × 4 matrix with an impossible entry and a required column, and the same without it.
        let mut m = AssociationMatrix::<f64, 4, 3>::new(3, 4, 0.0);
        m.set_column(0, &[1.2, -0.5, f64::NEG_INFINITY], false);
        m.set_column(1, &[0.3, 0.9, -1.0], true);
        m.set_column(2, &[-0.4, 1.5, 0.2], false);
        m.set_column(3, &[0.0, -1.3, 0.8], false);
        let mut free = m.clone();
        free.set_required(1, false);
        for (name, matrix) in [("required", &m), ("free", &free)] {
            let all = exhaustive(matrix);
            let top = all.iter().map(|c| c.0).fold(f64::NEG_INFINITY, f64::max);
            let total: f64 = all.iter().map(|c| (c.0 - top).exp()).sum();
            let mut chain = Gibbs::new(matrix, 9);
            for _ in 0..100 {
                chain.sweep();
            }
            let mut visits: BTreeMap<Vec<u16>, u64> = BTreeMap::new();
            let mut valid_sweeps = 0u64;
            for _ in 0..300_000 {
                chain.sweep();
                assert!(valid_ignoring_required(chain.state()), "{name}: a column twice");
                assert_eq!(chain.is_valid(), valid(matrix, chain.state()), "{name}: validity");
                if chain.is_valid() {
                    *visits.entry(chain.state().to_vec()).or_default() += 1;
                    valid_sweeps += 1;
                }
            }
            assert!(valid_sweeps > 50_000, "{name}: {valid_sweeps} valid sweeps");
            // Max |empirical − exact| over the valid associations: the standard error of a frequency is at
            // most 0.5/√n ≈ 0.002 for n = 50,000 effective samples, so 0.01 is about five of them; a wrong
            // conditional (e.g. uniform draws) misses by more than 0.05 here.
            let mut worst = 0.0f64;
            for (w, a) in &all {
                let exact = (w - top).exp() / total;
                let empirical = visits.get(a).copied().unwrap_or(0) as f64 / valid_sweeps as f64;
                worst = worst.max((exact - empirical).abs());
            }
            assert!(worst < 0.01, "{name}: max |empirical − exact| = {worst}");
            assert!(visits.keys().all(|a| all.iter().any(|c| &c.1 == a)), "{name}: visited an invalid association");
        }
    }

    /// The state is a partial matching (the chain never assigns a column twice), whatever the requirement.
    fn valid_ignoring_required(assignment: &[u16]) -> bool {
        let columns: Vec<u16> = assignment.iter().copied().filter(|&c| c != CLUTTER).collect();
        columns.iter().collect::<BTreeSet<_>>().len() == columns.len()
    }

    #[test]
    fn gibbs_every_sample_is_valid_with_its_exact_weight() {
        let mut state = 5u64;
        for case in 0..60 {
            let m = random_matrix(&mut state, 0.5);
            for child in distinct_samples(&m, case, 2_000) {
                assert!(valid(&m, &child.assignment), "case {case}: {:?}", child.assignment);
                assert_eq!(child.log_weight, m.score(&child.assignment), "case {case}");
                assert!(child.log_weight > f64::NEG_INFINITY);
            }
        }
        // The chain's own state never assigns a column twice, on a crossing matrix too.
        let m: AssociationMatrix<f64, 64, 32> = crate::experiments::perf::crossing_matrix(32, 64, 8, 2);
        let mut chain = Gibbs::new(&m, 1);
        for _ in 0..500 {
            chain.sweep();
            assert!(valid(&m, chain.state()));
        }
    }

    #[test]
    fn gibbs_reaches_the_mass_of_the_exhaustive_best() {
        let mut state = 41u64;
        let m = random_matrix(&mut state, 0.0);
        let all = exhaustive(&m);
        let top = all.iter().map(|c| c.0).fold(f64::NEG_INFINITY, f64::max);
        let total: f64 = all.iter().map(|c| (c.0 - top).exp()).sum();
        let reach = sweeps_to_mass(&m, 3, top, 0.9 * total, 100_000);
        assert!(reach.reached && reach.mass >= 0.9 * total && reach.distinct <= all.len());
        let capped = sweeps_to_mass(&m, 3, top, 2.0 * total, 1_000);
        assert!(!capped.reached && capped.sweeps == 1_000 && capped.mass <= total * (1.0 + 1e-9));
    }

    #[test]
    fn gibbs_draws_rows_whose_free_options_all_underflow() {
        // Row 0 takes column 0 (clutter weighs e^−1000 beside it); row 1 is then left with clutter and
        // column 1, both below e^−745 relative to its row maximum: the conditional is e^5 : 1.
        let mut m = AssociationMatrix::<f64, 2, 2>::new(2, 2, 0.0);
        m.set_column(0, &[1000.0, 1000.0], false);
        m.set_column(1, &[f64::NEG_INFINITY, 5.0], false);
        let mut chain = Gibbs::new(&m, 4);
        let (mut column_one, sweeps) = (0u32, 5_000);
        for _ in 0..sweeps {
            chain.sweep();
            assert_eq!(chain.state()[0], 0);
            column_one += u32::from(chain.state()[1] == 1);
        }
        let exact = 5f64.exp() / (1.0 + 5f64.exp());
        let empirical = f64::from(column_one) / f64::from(sweeps);
        assert!((empirical - exact).abs() < 0.004, "{empirical} vs {exact}");
    }

    #[test]
    fn gibbs_is_deterministic_per_seed() {
        let m: AssociationMatrix<f64, 64, 32> = crate::experiments::perf::crossing_matrix(16, 32, 4, 1);
        let a: Vec<Vec<u16>> = distinct_samples(&m, 7, 300).into_iter().map(|c| c.assignment).collect();
        let b: Vec<Vec<u16>> = distinct_samples(&m, 7, 300).into_iter().map(|c| c.assignment).collect();
        assert_eq!(a, b);
        assert!(a.len() > 1);
    }
}
