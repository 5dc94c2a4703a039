//! The Metropolis chain of one association matrix (R-FISST, paper 003 §III, paper 004 §III-B): a bounded
//! number of moves that search the matrix's associations and record the best distinct ones, each with its
//! exact weight (docs/maths.md §7.3–§7.7).
//!
//! One [`MetropolisSampler`] per matrix, its work in four files:
//! - `tables`: the per-row tables built once per matrix (possible columns, linear weights, the informed
//!   proposal's cumulative distribution and its guide table, the Zobrist hashes);
//! - `start`: the chain's start, the exact best association (or a greedy start and hill climbing);
//! - `steps`: the Metropolis moves, each a proposal and a decision, pipelined on out-of-order cores;
//! - `neighbours`: the start's move-or-swap neighbours, recorded as the likeliest next-best children.

mod neighbours;
mod start;
mod steps;
mod tables;
#[cfg(test)]
mod tests;

use super::SamplerConfig;
use super::best::BestChildren;
use crate::association::{AssociationMatrix, CLUTTER};
use crate::children::{ChildGenerator, ChildSink, GenerateError};
use crate::index::NONE;
use crate::real::Real;
use rand_core::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

/// Buckets of the informed proposal's guide table per row, and the shift from a 32-bit draw to its bucket.
const GUIDE: usize = 32;
const GUIDE_SHIFT: u32 = 27;

/// The chain's state.
#[derive(Debug, Clone)]
struct Chain<T, const N: usize, const Z: usize> {
    assignment: [u16; Z],
    owner: [u16; N],
    /// Σ δ of the assignment minus the penalty of unassigned required columns.
    score: T,
    hash: u64,
    unassigned_required: usize,
    /// Moves since the chain's start (the informed proposal alternates its kinds of step by it).
    moves: u64,
}

/// A Metropolis chain per association matrix, keeping the best `C` distinct children.
///
/// # Examples
/// Its best child is the matrix's best child, with its exact weight:
/// ```
/// # use tracker_core::association::{AssociationMatrix, CLUTTER};
/// # // 3 measurements × 3 objects; the best child takes the diagonal: −5 + 2 + 3 + 0.2.
/// # let mut matrix = AssociationMatrix::<f64, 3, 3>::new(3, 3, -5.0);
/// # matrix.set_column(0, &[2.0, 0.5, -1.0], false);
/// # matrix.set_column(1, &[1.5, 3.0, f64::NEG_INFINITY], false);
/// # matrix.set_column(2, &[f64::NEG_INFINITY, 1.0, 0.2], false);
/// use tracker_core::children::{ChildGenerator, ExhaustiveChildren};
/// use tracker_core::sampler::{MetropolisSampler, SamplerConfig};
/// use tracker_core::selection::TopChildren;
/// let mut sampled = TopChildren::<f64, 4, 3>::new();
/// MetropolisSampler::<f64, 3, 3, 4>::new(SamplerConfig::DEFAULT, 42).generate(&matrix, &mut sampled)?;
/// let mut exact = TopChildren::<f64, 4, 3>::new();
/// ExhaustiveChildren::new(1_000).generate(&matrix, &mut exact)?;
/// let best = |top: &TopChildren<f64, 4, 3>| {
///     let mut order = [0; 4];
///     top.best_first(&mut order);
///     top.kept()[usize::from(order[0])]
/// };
/// assert_eq!(best(&sampled).assignment, [0, 1, 2]);
/// assert_eq!(best(&sampled).log_weight, best(&exact).log_weight);
/// assert_eq!(best(&sampled).log_weight, matrix.score(&[0, 1, 2]));
/// # Ok::<(), tracker_core::children::GenerateError>(())
/// ```
#[derive(Debug, Clone)]
pub struct MetropolisSampler<T, const N: usize, const Z: usize, const C: usize> {
    config: SamplerConfig,
    /// The chain's random stream; `None` until the first [`MetropolisSampler::reseed`] of a sampler made
    /// with [`MetropolisSampler::empty`] (steps are then no-ops).
    rng: Option<Xoshiro256PlusPlus>,
    best: BestChildren<T, C, Z>,
    chain: Chain<T, N, Z>,
    /// Per row: its possible columns (finite δ), in order, and how many.
    row_columns: [[u16; N]; Z],
    row_count: [u16; Z],
    /// Per row: the cumulative distribution of the informed proposal over `row_columns`, in units of
    /// 2⁻³² (clutter takes the rest up to 2³²).
    cumulative: [[u32; N]; Z],
    /// Per row, a guide to `cumulative` (Chen and Asau's guide table): entry b counts the bounds at or
    /// below b·2²⁷ (capped at 255), a lower bound of the index of every draw in bucket b (the draws in
    /// [b·2²⁷, (b + 1)·2²⁷)), so the search starts there and finds the index a binary search finds.
    guide: [[u8; GUIDE]; Z],
    /// Linear weights w_jc = e^{δ_jc − m_j} (m_j = max(0, max_c δ_jc)), clutter e^{−m_j}, and 1 / W_j
    /// with W_j the row total: acceptance ratios are products of weights, with no exp or log in a step.
    weights: [[T; N]; Z],
    clutter_weight: [T; Z],
    inverse_row_total: [T; Z],
    /// e^{REQUIRED_PENALTY}.
    penalty_factor: T,
    /// `cell_hash(row, column)` precomputed (Zobrist table), and for clutter.
    zobrist: [[u64; N]; Z],
    zobrist_clutter: [u64; Z],
    steps_taken: u64,
    accepted: u64,
}

impl<T: Real, const N: usize, const Z: usize, const C: usize> MetropolisSampler<T, N, Z, C> {
    /// A sampler with `config`, its random stream seeded by `seed`.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::{AssociationMatrix, CLUTTER};
    /// # // 3 measurements × 3 objects; the best child takes the diagonal: −5 + 2 + 3 + 0.2.
    /// # let mut matrix = AssociationMatrix::<f64, 3, 3>::new(3, 3, -5.0);
    /// # matrix.set_column(0, &[2.0, 0.5, -1.0], false);
    /// # matrix.set_column(1, &[1.5, 3.0, f64::NEG_INFINITY], false);
    /// # matrix.set_column(2, &[f64::NEG_INFINITY, 1.0, 0.2], false);
    /// use tracker_core::sampler::{MetropolisSampler, SamplerConfig};
    /// let run = |seed| {
    ///     let mut sampler = MetropolisSampler::<f64, 3, 3, 8>::new(SamplerConfig::DEFAULT, seed);
    ///     sampler.run(&matrix);
    ///     (sampler.accepted(), sampler.best().iter().map(|(w, a)| (w, a.to_vec())).collect::<Vec<_>>())
    /// };
    /// assert_eq!(run(1), run(1)); // the same seed, the same chain
    /// ```
    pub fn new(config: SamplerConfig, seed: u64) -> Self {
        let mut sampler = Self::empty(config);
        sampler.reseed(seed);
        sampler
    }

    /// A sampler without a random stream yet (usable in a `const` context, so that a tracker can live in
    /// a `static`); [`MetropolisSampler::reseed`] gives it one.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::{AssociationMatrix, CLUTTER};
    /// # // 3 measurements × 3 objects; the best child takes the diagonal: −5 + 2 + 3 + 0.2.
    /// # let mut matrix = AssociationMatrix::<f64, 3, 3>::new(3, 3, -5.0);
    /// # matrix.set_column(0, &[2.0, 0.5, -1.0], false);
    /// # matrix.set_column(1, &[1.5, 3.0, f64::NEG_INFINITY], false);
    /// # matrix.set_column(2, &[f64::NEG_INFINITY, 1.0, 0.2], false);
    /// use tracker_core::sampler::{MetropolisSampler, SamplerConfig};
    /// let mut sampler = MetropolisSampler::<f64, 3, 3, 8>::empty(SamplerConfig::DEFAULT);
    /// sampler.reseed(9);
    /// sampler.run(&matrix);
    /// assert!(sampler.accepted() > 0);
    /// ```
    pub const fn empty(config: SamplerConfig) -> Self {
        Self {
            config,
            rng: None,
            best: BestChildren::new(),
            chain: Chain {
                assignment: [CLUTTER; Z],
                owner: [NONE; N],
                score: T::ZERO,
                hash: 0,
                unassigned_required: 0,
                moves: 0,
            },
            row_columns: [[0; N]; Z],
            row_count: [0; Z],
            cumulative: [[0; N]; Z],
            guide: [[0; GUIDE]; Z],
            weights: [[T::ZERO; N]; Z],
            clutter_weight: [T::ONE; Z],
            inverse_row_total: [T::ONE; Z],
            // Set with the tables (an exp cannot run in a const context).
            penalty_factor: T::ONE,
            // Filled by the first `reseed` (a hash cannot run in a const context here).
            zobrist: [[0; N]; Z],
            zobrist_clutter: [0; Z],
            steps_taken: 0,
            accepted: 0,
        }
    }

    /// Reseeds the random stream (the tracker derives one seed per scan, parent and event).
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::{AssociationMatrix, CLUTTER};
    /// # // 3 measurements × 3 objects; the best child takes the diagonal: −5 + 2 + 3 + 0.2.
    /// # let mut matrix = AssociationMatrix::<f64, 3, 3>::new(3, 3, -5.0);
    /// # matrix.set_column(0, &[2.0, 0.5, -1.0], false);
    /// # matrix.set_column(1, &[1.5, 3.0, f64::NEG_INFINITY], false);
    /// # matrix.set_column(2, &[f64::NEG_INFINITY, 1.0, 0.2], false);
    /// use tracker_core::sampler::{MetropolisSampler, SamplerConfig};
    /// let mut a = MetropolisSampler::<f64, 3, 3, 8>::new(SamplerConfig::DEFAULT, 1);
    /// a.run(&matrix); // a's stream moves on
    /// a.reseed(5);
    /// let before = a.accepted();
    /// a.run(&matrix);
    /// let mut b = MetropolisSampler::<f64, 3, 3, 8>::new(SamplerConfig::DEFAULT, 5);
    /// b.run(&matrix);
    /// assert_eq!(a.accepted() - before, b.accepted()); // the same chain as a fresh sampler's
    /// ```
    pub fn reseed(&mut self, seed: u64) {
        if self.rng.is_none() {
            self.fill_zobrist();
        }
        self.rng = Some(Xoshiro256PlusPlus::seed_from_u64(seed));
    }

    /// Replaces the configuration in place. The tables are scratch that every matrix rewrites, so the
    /// sampler then runs as [`MetropolisSampler::empty`]`(config)` would, without that value passing
    /// through the stack.
    pub(crate) fn configure(&mut self, config: SamplerConfig) {
        self.config = config;
    }

    /// The configuration.
    ///
    /// # Examples
    /// ```
    /// use tracker_core::sampler::{MetropolisSampler, SamplerConfig};
    /// let config = SamplerConfig { steps: 50, ..SamplerConfig::DEFAULT };
    /// assert_eq!(MetropolisSampler::<f64, 2, 2, 4>::new(config, 0).config().steps, 50);
    /// ```
    pub fn config(&self) -> &SamplerConfig {
        &self.config
    }

    /// Steps taken over the sampler's lifetime.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::{AssociationMatrix, CLUTTER};
    /// # // 3 measurements × 3 objects; the best child takes the diagonal: −5 + 2 + 3 + 0.2.
    /// # let mut matrix = AssociationMatrix::<f64, 3, 3>::new(3, 3, -5.0);
    /// # matrix.set_column(0, &[2.0, 0.5, -1.0], false);
    /// # matrix.set_column(1, &[1.5, 3.0, f64::NEG_INFINITY], false);
    /// # matrix.set_column(2, &[f64::NEG_INFINITY, 1.0, 0.2], false);
    /// use tracker_core::sampler::{MetropolisSampler, SamplerConfig};
    /// let config = SamplerConfig { burn_in: 10, steps: 100, ..SamplerConfig::DEFAULT };
    /// let mut sampler = MetropolisSampler::<f64, 3, 3, 8>::new(config, 3);
    /// sampler.run(&matrix);
    /// sampler.run(&matrix);
    /// assert_eq!(sampler.steps_taken(), 2 * (10 + 100));
    /// ```
    pub fn steps_taken(&self) -> u64 {
        self.steps_taken
    }

    /// Accepted proposals over the sampler's lifetime.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::{AssociationMatrix, CLUTTER};
    /// # // 3 measurements × 3 objects; the best child takes the diagonal: −5 + 2 + 3 + 0.2.
    /// # let mut matrix = AssociationMatrix::<f64, 3, 3>::new(3, 3, -5.0);
    /// # matrix.set_column(0, &[2.0, 0.5, -1.0], false);
    /// # matrix.set_column(1, &[1.5, 3.0, f64::NEG_INFINITY], false);
    /// # matrix.set_column(2, &[f64::NEG_INFINITY, 1.0, 0.2], false);
    /// use tracker_core::sampler::{MetropolisSampler, SamplerConfig};
    /// let mut sampler = MetropolisSampler::<f64, 3, 3, 8>::new(SamplerConfig::DEFAULT, 3);
    /// sampler.run(&matrix);
    /// assert!(0 < sampler.accepted() && sampler.accepted() < sampler.steps_taken());
    /// ```
    pub fn accepted(&self) -> u64 {
        self.accepted
    }

    /// The best distinct children of the last chain, as (exact log-weight, assignment).
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::{AssociationMatrix, CLUTTER};
    /// # // 3 measurements × 3 objects; the best child takes the diagonal: −5 + 2 + 3 + 0.2.
    /// # let mut matrix = AssociationMatrix::<f64, 3, 3>::new(3, 3, -5.0);
    /// # matrix.set_column(0, &[2.0, 0.5, -1.0], false);
    /// # matrix.set_column(1, &[1.5, 3.0, f64::NEG_INFINITY], false);
    /// # matrix.set_column(2, &[f64::NEG_INFINITY, 1.0, 0.2], false);
    /// use tracker_core::sampler::{MetropolisSampler, SamplerConfig};
    /// let mut sampler = MetropolisSampler::<f64, 3, 3, 8>::new(SamplerConfig::DEFAULT, 3);
    /// sampler.run(&matrix);
    /// assert_eq!(sampler.best().len(), 8);
    /// for (log_weight, assignment) in sampler.best().iter() {
    ///     assert_eq!(log_weight, matrix.score(assignment)); // exact, never estimated
    /// }
    /// ```
    pub fn best(&self) -> &BestChildren<T, C, Z> {
        &self.best
    }

    /// The best-children set, for a caller that fills it another way (exhaustive clusters).
    pub(crate) fn best_mut(&mut self) -> &mut BestChildren<T, C, Z> {
        &mut self.best
    }

    /// Runs one chain on `matrix` and leaves its best distinct children in [`MetropolisSampler::best`].
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::{AssociationMatrix, CLUTTER};
    /// # // 3 measurements × 3 objects; the best child takes the diagonal: −5 + 2 + 3 + 0.2.
    /// # let mut matrix = AssociationMatrix::<f64, 3, 3>::new(3, 3, -5.0);
    /// # matrix.set_column(0, &[2.0, 0.5, -1.0], false);
    /// # matrix.set_column(1, &[1.5, 3.0, f64::NEG_INFINITY], false);
    /// # matrix.set_column(2, &[f64::NEG_INFINITY, 1.0, 0.2], false);
    /// use tracker_core::sampler::{MetropolisSampler, SamplerConfig};
    /// let mut sampler = MetropolisSampler::<f64, 3, 3, 4>::new(SamplerConfig::DEFAULT, 3);
    /// sampler.run(&matrix);
    /// let best = sampler.best().iter().map(|(w, _)| w).fold(f64::NEG_INFINITY, f64::max);
    /// assert!((best - 0.2).abs() < 1e-12); // the diagonal
    /// ```
    pub fn run(&mut self, matrix: &AssociationMatrix<T, N, Z>) {
        self.run_with_moves(matrix, u64::MAX);
    }

    /// As [`MetropolisSampler::run`], with at most `max_moves` Metropolis moves
    /// ([`SamplerConfig::moves_within`]); the exact start and its neighbours are recorded whatever the
    /// limit, so even a chain allowed no move offers its matrix's best child.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::AssociationMatrix;
    /// # let mut matrix = AssociationMatrix::<f64, 3, 3>::new(3, 3, -5.0);
    /// # matrix.set_column(0, &[2.0, 0.5, -1.0], false);
    /// # matrix.set_column(1, &[1.5, 3.0, f64::NEG_INFINITY], false);
    /// # matrix.set_column(2, &[f64::NEG_INFINITY, 1.0, 0.2], false);
    /// use tracker_core::sampler::{MetropolisSampler, SamplerConfig};
    /// let mut sampler = MetropolisSampler::<f64, 3, 3, 4>::new(SamplerConfig::DEFAULT, 3);
    /// sampler.run_with_moves(&matrix, 50);
    /// assert_eq!(sampler.steps_taken(), 50);
    /// assert!(!sampler.best().is_empty());
    /// ```
    pub fn run_with_moves(&mut self, matrix: &AssociationMatrix<T, N, Z>, max_moves: u64) {
        self.best.clear(matrix.rows());
        if matrix.rows() == 0 {
            // One child: every object missed.
            if matrix.required_count() == 0 {
                self.best.insert(matrix.baseline(), 0, &[]);
            }
            return;
        }
        self.build_tables(matrix);
        if self.config.exact_start && self.start_optimal(matrix) {
            self.record(matrix);
            self.record_neighbours(matrix);
        } else {
            self.start_greedy(matrix);
            self.record(matrix);
            self.climb(matrix);
            self.record(matrix);
        }
        self.chain.moves = 0;
        let (burn_in, steps) = self.config.moves_within(max_moves);
        let Some(mut rng) = self.rng.take() else {
            // No random stream (an `empty` sampler never reseeded): the steps are no-ops.
            self.steps_taken += u64::from(burn_in) + u64::from(steps);
            self.record(matrix);
            return;
        };
        self.moves(matrix, &mut rng, burn_in, false);
        self.record(matrix);
        self.moves(matrix, &mut rng, steps, true);
        self.rng = Some(rng);
    }
}

impl<T: Real, const N: usize, const Z: usize, const C: usize> ChildGenerator<T, N, Z>
    for MetropolisSampler<T, N, Z, C>
{
    fn generate<Sink: ChildSink<T>>(
        &mut self,
        matrix: &AssociationMatrix<T, N, Z>,
        sink: &mut Sink,
    ) -> Result<u64, GenerateError> {
        self.run(matrix);
        for (score, assignment) in self.best.iter() {
            sink.offer(score, assignment);
        }
        Ok(self.best.len() as u64)
    }
}
