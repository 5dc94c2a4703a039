//! The Metropolis chain of one association matrix (R-FISST, paper 003 §III, paper 004 §III-B): a bounded
//! number of moves that search the matrix's associations and record the best distinct ones, each with its
//! exact weight (docs/maths.md §7.3–§7.7).

use super::best::{BestChildren, association_hash, cell_hash};
use super::{Proposal, REQUIRED_PENALTY, SamplerConfig};
use crate::association::{AssociationMatrix, CLUTTER};
use crate::children::{ChildGenerator, ChildSink, GenerateError};
use crate::index::{At, NONE, below};
use crate::optimal::{best_association, best_association_sparse};
use crate::real::{Real, exp};
use rand_core::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

/// Buckets of the informed proposal's guide table per row, and the shift from a 32-bit draw to its bucket.
const GUIDE: usize = 32;
const GUIDE_SHIFT: u32 = 27;

/// The kinds of Metropolis step, as const parameters of the step: paper 003's uniform column of the
/// matrix, a uniform column among the row's possible ones, and the informed draw from the row's weights.
const PAPER: u8 = 0;
const UNIFORM: u8 = 1;
const INFORMED: u8 = 2;

/// Whether a step returns as soon as a swap turns out infeasible (the other measurement cannot take the
/// row's old column), rather than computing the ratio, which is then NaN and rejected: the same decision
/// either way. An in-order core (Cortex-M, RISC-V microcontrollers) pays little for the branch and saves the
/// ratio; a speculative out-of-order core mispredicts it about as often as the draw makes a swap infeasible
/// on a gated matrix, which costs more than the ratio (docs/performance.md, "Impossible weights as NaN").
const EARLY_REJECT: bool = !cfg!(any(target_arch = "x86_64", target_arch = "aarch64"));

/// Whether the chain's loop draws each step's proposal before it decides the previous step (software
/// pipelining; the same draws in the same order, so the same chain). A proposal reads only the matrix's
/// tables, so on a speculative out-of-order core its loads no longer wait behind the previous step's
/// mispredicted branches. With it, the informed proposal's proposals of the current state are rejected by
/// the ratio rather than by a branch ([`MetropolisSampler::decide`]). Together: fewer nanoseconds for more
/// instructions (docs/performance.md, "Pipelined steps"); an in-order core would only pay the instructions.
const PIPELINE: bool = cfg!(any(target_arch = "x86_64", target_arch = "aarch64"));

/// The first `count` of a row's possible columns.
#[inline]
fn possible<const N: usize>(columns: &[u16; N], count: u16) -> &[u16] {
    &columns[..usize::from(count).min(N)]
}

/// A step's proposal ([`MetropolisSampler::propose`]): the row, its proposed column (or clutter) and the
/// acceptance test's uniform bits.
#[derive(Debug, Clone, Copy)]
struct Draw {
    row: usize,
    new: u16,
    acceptance_bits: u32,
}

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

    /// Precomputes `cell_hash` for every (row, column) and for clutter: Z (N + 1) hashes, once.
    fn fill_zobrist(&mut self) {
        for (row, (hashes, clutter)) in self.zobrist.iter_mut().zip(self.zobrist_clutter.iter_mut()).enumerate() {
            for (column, hash) in (0u16..).zip(hashes.iter_mut()) {
                *hash = cell_hash(row, column);
            }
            *clutter = cell_hash(row, CLUTTER);
        }
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

    /// Log-score contribution of `row` taking `column` (0 for clutter).
    #[inline]
    fn entry(matrix: &AssociationMatrix<T, N, Z>, row: usize, column: u16) -> T {
        if column == CLUTTER { T::zero() } else { matrix.entry(row, column as usize) }
    }

    fn penalty() -> T {
        T::of_f64(REQUIRED_PENALTY)
    }

    /// Builds the per-row tables of possible columns, linear weights and the informed proposal's
    /// cumulative distribution (O(rows × columns) once per matrix; one exp per possible entry).
    fn build_tables(&mut self, matrix: &AssociationMatrix<T, N, Z>) {
        let (rows, columns) = (matrix.rows(), matrix.columns());
        self.penalty_factor = exp(T::of_f64(REQUIRED_PENALTY));
        for row in 0..rows {
            let possible = &mut self.row_columns[row];
            let mut top = T::zero(); // clutter's δ
            let mut count = 0usize;
            for column in 0..columns {
                let entry = matrix.entry(row, column);
                if entry > T::NEG_INFINITY {
                    *possible.at_mut(count) = column as u16;
                    count += 1;
                    if entry > top {
                        top = entry;
                    }
                }
            }
            self.row_count[row] = count as u16;
            // Weights relative to the row's largest, so nothing overflows.
            let clutter = exp(-top);
            let mut total = clutter;
            let weights = &mut self.weights[row];
            for column in 0..columns {
                let entry = matrix.entry(row, column);
                weights[column] = if entry > T::NEG_INFINITY {
                    let weight = exp(entry - top);
                    total += weight;
                    weight
                } else {
                    // Impossible: NaN, so that any ratio with this weight is NaN and fails the acceptance
                    // test (a step needs no branch of its own for it; see `EARLY_REJECT`).
                    T::NAN
                };
            }
            self.clutter_weight[row] = clutter;
            self.inverse_row_total[row] = T::one() / total;
            let scale = T::of_f64(4_294_967_296.0) / total;
            let mut cumulative = T::zero();
            let (weights, possible) = (&self.weights[row], &self.row_columns[row]);
            // The guide in the same pass (bounds and bucket starts both increase): O(GUIDE + count).
            let guide = &mut self.guide[row];
            let mut bucket = 0u32;
            let cap = |below: usize| below.min(usize::from(u8::MAX)) as u8;
            for (index, (bound, &column)) in self.cumulative[row].iter_mut().zip(possible).take(count).enumerate() {
                cumulative += *weights.at(usize::from(column));
                let units = (cumulative * scale).as_f64();
                *bound = if units >= 4_294_967_295.0 { u32::MAX } else { units as u32 };
                // Buckets starting below this bound have `index` bounds at or below their start.
                while let Some(start) = guide.get_mut(bucket as usize)
                    && bucket << GUIDE_SHIFT < *bound
                {
                    *start = cap(index);
                    bucket += 1;
                }
            }
            for start in guide.iter_mut().skip(bucket as usize) {
                *start = cap(count);
            }
        }
    }

    /// The informed proposal's index for the 32-bit draw `bits` in `row` (of `count` possible columns;
    /// `count` for clutter): the number of the row's cumulative bounds at or below `bits`, counted from
    /// the guide's lower bound (one comparison unless a bound falls in the draw's bucket).
    #[inline(always)]
    fn informed_index(&self, row: usize, count: usize, bits: u32) -> usize {
        let bounds = &self.cumulative[row][..count];
        let mut k = usize::from(self.guide[row][(bits >> GUIDE_SHIFT) as usize]);
        for &bound in bounds.get(k..).unwrap_or_default() {
            if bound > bits {
                break;
            }
            k += 1;
        }
        k
    }

    /// The possible columns of `row` (finite δ), in order.
    #[inline]
    fn possible_columns(&self, row: usize) -> &[u16] {
        possible(self.row_columns.at(row), *self.row_count.at(row))
    }

    /// `cell_hash(row, column)` from the table (`row < Z`; any value that is no column is clutter).
    #[inline(always)]
    fn zobrist(&self, row: usize, column: u16) -> u64 {
        match below::<N>(column) {
            Some(column) => self.zobrist[row][column],
            None => self.zobrist_clutter[row],
        }
    }

    /// Linear weight of `row` taking `column` (clutter included), relative to the row's largest; as
    /// [`MetropolisSampler::zobrist`].
    #[inline(always)]
    fn weight(&self, row: usize, column: u16) -> T {
        match below::<N>(column) {
            Some(column) => self.weights[row][column],
            None => self.clutter_weight[row],
        }
    }

    /// Optimal start: the association that maximises the chain's target ([`best_association`]). Returns
    /// `false` when that search fails (a NaN entry), leaving the state to [`MetropolisSampler::start_greedy`].
    fn start_optimal(&mut self, matrix: &AssociationMatrix<T, N, Z>) -> bool {
        // On a gated matrix (at most half the entries possible), the search over the row tables' possible
        // columns; on a dense one, the plain search. Both give the same association.
        let (rows, columns) = matrix.shape();
        let (row_columns, row_count) = (&self.row_columns, &self.row_count);
        let entries: usize = row_count.iter().take(rows).map(|&count| usize::from(count)).sum();
        let found = if 2 * entries <= rows * columns {
            let possible_of = |row: usize| possible(row_columns.at(row), *row_count.at(row)).iter().copied();
            best_association_sparse(matrix, Self::penalty(), &mut self.chain.assignment, possible_of)
        } else {
            best_association(matrix, Self::penalty(), &mut self.chain.assignment)
        };
        if !found {
            return false;
        }
        let chain = &mut self.chain;
        chain.owner[..matrix.columns()].fill(NONE);
        for (row, &column) in chain.assignment[..matrix.rows()].iter().enumerate() {
            if let Some(column) = below::<N>(column) {
                *chain.owner.at_mut(column) = row as u16;
            }
        }
        self.settle(matrix);
        true
    }

    /// Greedy start: repeatedly the best remaining (measurement, object) pair that beats clutter, then
    /// each unassigned required column takes its best free row.
    fn start_greedy(&mut self, matrix: &AssociationMatrix<T, N, Z>) {
        let (rows, columns) = (matrix.rows(), matrix.columns());
        let chain = &mut self.chain;
        chain.assignment[..rows].fill(CLUTTER);
        chain.owner[..columns].fill(NONE);
        // Each row's best free column (cached; recomputed when taken) and its entry.
        let mut best_column = [NONE; Z];
        let mut best_entry = [T::NEG_INFINITY; Z];
        let mut row_done = [false; Z];
        for _ in 0..rows {
            let mut pick: Option<usize> = None;
            for row in 0..rows {
                if row_done[row] {
                    continue;
                }
                if best_column[row] == NONE || *chain.owner.at(usize::from(best_column[row])) != NONE {
                    best_column[row] = NONE;
                    best_entry[row] = T::zero(); // clutter: only entries above it count
                    for &column in possible(self.row_columns.at(row), *self.row_count.at(row)) {
                        let entry = matrix.entry(row, usize::from(column));
                        if *chain.owner.at(usize::from(column)) == NONE && entry > best_entry[row] {
                            best_column[row] = column;
                            best_entry[row] = entry;
                        }
                    }
                }
                if best_column[row] != NONE && pick.is_none_or(|p| best_entry[row] > *best_entry.at(p)) {
                    pick = Some(row);
                }
            }
            let Some(row) = pick else { break };
            let column = *best_column.at(row);
            *chain.assignment.at_mut(row) = column;
            *chain.owner.at_mut(usize::from(column)) = row as u16;
            *row_done.at_mut(row) = true;
        }
        for column in 0..columns {
            if !matrix.is_required(column) || chain.owner[column] != NONE {
                continue;
            }
            let mut best: Option<(usize, T)> = None;
            for row in 0..rows {
                let entry = matrix.entry(row, column);
                if chain.assignment[row] == CLUTTER && entry > T::NEG_INFINITY && best.is_none_or(|(_, b)| entry > b) {
                    best = Some((row, entry));
                }
            }
            if let Some((row, _)) = best {
                *chain.assignment.at_mut(row) = column as u16;
                *chain.owner.at_mut(column) = row as u16;
            }
        }
        self.settle(matrix);
    }

    /// Sets the chain's score, required count and hash from its assignment and owners.
    fn settle(&mut self, matrix: &AssociationMatrix<T, N, Z>) {
        let (rows, columns) = (matrix.rows(), matrix.columns());
        let chain = &mut self.chain;
        let mut score = T::zero();
        for row in 0..rows {
            score += Self::entry(matrix, row, chain.assignment[row]);
        }
        chain.unassigned_required = (0..columns).filter(|&c| matrix.is_required(c) && chain.owner[c] == NONE).count();
        chain.score = score - Self::penalty() * T::of_f64(chain.unassigned_required as f64);
        chain.hash = association_hash(&chain.assignment[..rows]);
    }

    /// Records the current state if it is feasible and good enough.
    #[inline(always)]
    fn record(&mut self, matrix: &AssociationMatrix<T, N, Z>) {
        let Self { chain, best, .. } = self;
        if chain.unassigned_required != 0 || !(matrix.baseline() + chain.score > best.threshold()) {
            return;
        }
        let rows = matrix.rows();
        let assignment = &chain.assignment[..rows];
        if best.contains(chain.hash, assignment) {
            return;
        }
        // Exact weight from the formula, not the running sum: the baseline plus the entries, in the order
        // of `AssociationMatrix::score` (the state is valid: no column twice, every required column taken).
        let mut exact = matrix.baseline();
        for (row, &column) in assignment.iter().enumerate() {
            if column != CLUTTER {
                exact += matrix.entry(row, usize::from(column));
            }
        }
        best.insert_absent(exact, chain.hash, assignment);
    }

    /// One Metropolis move (propose, then accept or reject); returns whether the state changed. With the
    /// informed proposal the chain's moves alternate, informed first: the chain's `i`-th move since its
    /// start is informed for even `i`, uniform for odd `i`, whether it runs inside
    /// [`MetropolisSampler::run`] or through this method.
    ///
    /// # Examples
    /// Moves on their own (after [`MetropolisSampler::run`] has built the matrix's tables):
    /// ```
    /// # use tracker_core::association::{AssociationMatrix, CLUTTER};
    /// # // 3 measurements × 3 objects; the best child takes the diagonal: −5 + 2 + 3 + 0.2.
    /// # let mut matrix = AssociationMatrix::<f64, 3, 3>::new(3, 3, -5.0);
    /// # matrix.set_column(0, &[2.0, 0.5, -1.0], false);
    /// # matrix.set_column(1, &[1.5, 3.0, f64::NEG_INFINITY], false);
    /// # matrix.set_column(2, &[f64::NEG_INFINITY, 1.0, 0.2], false);
    /// use tracker_core::sampler::{MetropolisSampler, SamplerConfig};
    /// let config = SamplerConfig { burn_in: 0, steps: 0, ..SamplerConfig::DEFAULT };
    /// let mut sampler = MetropolisSampler::<f64, 3, 3, 8>::new(config, 3);
    /// sampler.run(&matrix);
    /// let moved = (0..100).filter(|_| sampler.metropolis_move(&matrix)).count() as u64;
    /// assert_eq!((sampler.steps_taken(), sampler.accepted()), (100, moved));
    /// ```
    pub fn metropolis_move(&mut self, matrix: &AssociationMatrix<T, N, Z>) -> bool {
        let Some(mut rng) = self.rng.take() else {
            self.steps_taken += 1;
            return false;
        };
        self.steps_taken += 1;
        let moved = match self.config.proposal {
            Proposal::Paper => self.step::<PAPER>(matrix, &mut rng),
            Proposal::MoveOrSwap => self.step::<UNIFORM>(matrix, &mut rng),
            Proposal::Informed if self.chain.moves.is_multiple_of(2) => self.step::<INFORMED>(matrix, &mut rng),
            Proposal::Informed => self.step::<UNIFORM>(matrix, &mut rng),
        };
        self.chain.moves += 1;
        self.rng = Some(rng);
        moved
    }

    /// `count` moves of the chain, recording each new state when `record` is set. The informed proposal's
    /// alternation is unrolled into pairs, so that no step decides its kind at run time.
    fn moves(
        &mut self,
        matrix: &AssociationMatrix<T, N, Z>,
        stream: &mut Xoshiro256PlusPlus,
        count: u32,
        record: bool,
    ) {
        // A local copy of the stream, so that its state stays in registers.
        let rng = &mut stream.clone();
        let mut left = count;
        match self.config.proposal {
            Proposal::Paper => self.steps_of::<PAPER>(matrix, rng, left, record),
            Proposal::MoveOrSwap => self.steps_of::<UNIFORM>(matrix, rng, left, record),
            Proposal::Informed => {
                if left > 0 && self.chain.moves % 2 == 1 {
                    self.step_and_record::<UNIFORM>(matrix, rng, record);
                    left -= 1;
                }
                self.alternating_steps(matrix, rng, left, record);
            }
        }
        self.chain.moves += u64::from(count);
        self.steps_taken += u64::from(count);
        *stream = rng.clone();
    }

    /// `count` steps of `KIND`; with [`PIPELINE`], each step's proposal is drawn before the previous step
    /// is decided.
    #[inline(always)]
    fn steps_of<const KIND: u8>(
        &mut self,
        matrix: &AssociationMatrix<T, N, Z>,
        rng: &mut Xoshiro256PlusPlus,
        count: u32,
        record: bool,
    ) {
        if !PIPELINE {
            for _ in 0..count {
                self.step_and_record::<KIND>(matrix, rng, record);
            }
            return;
        }
        if count == 0 {
            return;
        }
        let mut draw = self.propose::<KIND>(matrix, rng);
        for _ in 1..count {
            let next = self.propose::<KIND>(matrix, rng);
            self.decide_and_record::<KIND>(matrix, draw, record);
            draw = next;
        }
        self.decide_and_record::<KIND>(matrix, draw, record);
    }

    /// `count` steps alternating informed, uniform, informed, ... (informed first); pipelined as
    /// [`MetropolisSampler::steps_of`].
    #[inline(always)]
    fn alternating_steps(
        &mut self,
        matrix: &AssociationMatrix<T, N, Z>,
        rng: &mut Xoshiro256PlusPlus,
        count: u32,
        record: bool,
    ) {
        if !PIPELINE {
            for _ in 0..count / 2 {
                self.step_and_record::<INFORMED>(matrix, rng, record);
                self.step_and_record::<UNIFORM>(matrix, rng, record);
            }
            if count % 2 == 1 {
                self.step_and_record::<INFORMED>(matrix, rng, record);
            }
            return;
        }
        if count == 0 {
            return;
        }
        let mut informed = self.propose::<INFORMED>(matrix, rng);
        for _ in 0..(count - 1) / 2 {
            let uniform = self.propose::<UNIFORM>(matrix, rng);
            self.decide_and_record::<INFORMED>(matrix, informed, record);
            informed = self.propose::<INFORMED>(matrix, rng);
            self.decide_and_record::<UNIFORM>(matrix, uniform, record);
        }
        // The last one or two steps, with no proposal drawn beyond them.
        if count.is_multiple_of(2) {
            let uniform = self.propose::<UNIFORM>(matrix, rng);
            self.decide_and_record::<INFORMED>(matrix, informed, record);
            self.decide_and_record::<UNIFORM>(matrix, uniform, record);
        } else {
            self.decide_and_record::<INFORMED>(matrix, informed, record);
        }
    }

    /// The step deciding `draw`, and the new state recorded if it moved and `record` is set.
    #[inline(always)]
    fn decide_and_record<const KIND: u8>(
        &mut self,
        matrix: &AssociationMatrix<T, N, Z>,
        draw: Option<Draw>,
        record: bool,
    ) {
        if let Some(draw) = draw
            && self.decide::<KIND, EARLY_REJECT>(matrix, draw)
            && record
        {
            self.record(matrix);
        }
    }

    /// One step of `KIND`, and the new state recorded if it moved and `record` is set.
    #[inline(always)]
    fn step_and_record<const KIND: u8>(
        &mut self,
        matrix: &AssociationMatrix<T, N, Z>,
        rng: &mut Xoshiro256PlusPlus,
        record: bool,
    ) {
        if self.step::<KIND>(matrix, rng) && record {
            self.record(matrix);
        }
    }

    /// [`MetropolisSampler::metropolis_move`] of a given kind ([`PAPER`], [`UNIFORM`] or [`INFORMED`]),
    /// with the random stream held outside the sampler, so that inlined in a loop its state stays in
    /// registers.
    // The hot loop of the tracker (hundreds of thousands of moves per worst-case scan): proposal, the
    // Metropolis–Hastings ratio of each proposal kind and acceptance are kept in one function so that the
    // ratio's products stay in registers; splitting it measurably costs instructions.
    #[inline(always)]
    fn step<const KIND: u8>(&mut self, matrix: &AssociationMatrix<T, N, Z>, rng: &mut Xoshiro256PlusPlus) -> bool {
        self.step_with::<KIND, EARLY_REJECT>(matrix, rng)
    }

    /// [`MetropolisSampler::step`], returning early on an infeasible swap if `EARLY` ([`EARLY_REJECT`]).
    #[inline(always)]
    fn step_with<const KIND: u8, const EARLY: bool>(
        &mut self,
        matrix: &AssociationMatrix<T, N, Z>,
        rng: &mut Xoshiro256PlusPlus,
    ) -> bool {
        let Some(draw) = self.propose::<KIND>(matrix, rng) else { return false };
        self.decide::<KIND, EARLY>(matrix, draw)
    }

    /// A step's proposal from the next random draw (`None` never: a row has at most N possible columns).
    /// It reads only the matrix's tables, never the chain's state, so a loop can draw the next step's
    /// proposal before it decides the current one.
    #[inline(always)]
    fn propose<const KIND: u8>(
        &self,
        matrix: &AssociationMatrix<T, N, Z>,
        rng: &mut Xoshiro256PlusPlus,
    ) -> Option<Draw> {
        // The row is clamped below and the column checked by `below`: no need for the clamped sizes.
        let (rows, columns) = matrix.shape();
        let draw = rng.next_u64();
        // Row from the high half of the draw (multiply-shift range), the low half picks the column. The
        // product's low half is the acceptance test's uniform: given the row, it is uniform on a lattice of
        // spacing `rows` in [0, 2³²), and independent of the column's bits.
        let spread = (draw >> 32) * rows as u64;
        let row = ((spread >> 32) as usize).min(Z - 1);
        let acceptance_bits = spread as u32;
        let bits = draw as u32;
        let new = if KIND == PAPER {
            // Paper 003: any column of the matrix, or clutter.
            let pick = ((u64::from(bits) * (columns as u64 + 1)) >> 32) as usize;
            if pick >= columns { CLUTTER } else { pick as u16 }
        } else {
            // A row has at most N possible columns; the bound lets the compiler drop the slices' checks.
            // The pipelined loop clamps (no branch, and never `None`); the plain one returns (no select).
            let count = usize::from(self.row_count[row]);
            let count = if PIPELINE {
                count.min(N)
            } else if count > N {
                return None;
            } else {
                count
            };
            // Informed: from the row's own distribution; uniform: among its possible columns and clutter.
            let k = if KIND == INFORMED {
                self.informed_index(row, count, bits)
            } else {
                ((u64::from(bits) * (count as u64 + 1)) >> 32) as usize
            };
            // `at`: with the clamped count the compiler cannot see that k < N.
            if k >= count { CLUTTER } else { *self.row_columns[row].at(k) }
        };
        Some(Draw { row, new, acceptance_bits })
    }

    /// Accepts or rejects the proposal `draw` by the Metropolis–Hastings ratio of `KIND`, and makes the
    /// move if accepted; returns whether the state changed.
    #[inline(always)]
    fn decide<const KIND: u8, const EARLY: bool>(&mut self, matrix: &AssociationMatrix<T, N, Z>, draw: Draw) -> bool {
        let Draw { row, new, acceptance_bits } = draw;
        let informed = KIND == INFORMED;
        let chain = &self.chain;
        let old = chain.assignment[row];
        // A proposal of the current state is rejected. The informed proposal makes one about every other
        // step (the chain stays near the mode, whose columns carry most of their rows' weight), too often
        // and too irregularly for a branch to predict: on an out-of-order core it goes through the ratio
        // instead, as a swap of the row with itself, and a NaN denominator rejects it below.
        if !(PIPELINE && informed) && new == old {
            return false;
        }
        // Its weight, and the measurement that holds it (if any).
        let (new_weight, other) = match below::<N>(new) {
            None => (self.clutter_weight[row], None),
            Some(column) => {
                let weight = self.weights[row][column];
                // NaN if impossible: only paper 003's uniform column can be (the others draw possible
                // columns). Most of its draws are, so an early return is well predicted there.
                if KIND == PAPER && !weight.is_finite_value() {
                    return false;
                }
                (weight, below::<Z>(chain.owner[column]))
            }
        };
        // Clutter is never required.
        let required = |column: u16| matrix.is_required(usize::from(column));
        let old_weight = self.weight(row, old);
        // The acceptance ratio e^Δ q_reverse / q_forward as numerator / denominator of products of linear
        // weights (no exp, no log, no division), and the move.
        let (mut numerator, mut denominator, other_takes) = match other {
            None => (if informed { T::one() } else { new_weight }, if informed { T::one() } else { old_weight }, NONE),
            Some(other_row) => {
                if KIND == PAPER {
                    // The other measurement goes to clutter.
                    (new_weight * self.clutter_weight[other_row], old_weight * self.weight(other_row, new), CLUTTER)
                } else {
                    // NaN if the other measurement cannot take `old`: the swap is then rejected below.
                    let other_new_weight = self.weight(other_row, old);
                    if EARLY && !other_new_weight.is_finite_value() {
                        return false;
                    }
                    let other_old_weight = self.weight(other_row, new);
                    // e^Δ = (w_j,new / w_j,old) (w_k,old / w_k,new)
                    let (mut numerator, mut denominator) =
                        (new_weight * other_new_weight, old_weight * other_old_weight);
                    // q_reverse / q_forward. A column-for-column swap is proposed by (j, new) and by
                    // (k, old), its reverse by (j, old) and by (k, new). When j held clutter, only (j, new)
                    // proposes it ((k, clutter) would move k alone), and only (k, new) its reverse.
                    let (inverse_j, inverse_k) = (self.inverse_row_total[row], self.inverse_row_total[other_row]);
                    if old == CLUTTER {
                        if informed {
                            numerator *= other_old_weight * inverse_k;
                            denominator *= new_weight * inverse_j;
                        } else {
                            // Uniform over a row's possible columns and clutter: q_j = 1 / (n_j + 1).
                            numerator *= T::of_f64(f64::from(self.row_count[row]) + 1.0);
                            denominator *= T::of_f64(f64::from(self.row_count[other_row]) + 1.0);
                        }
                    } else if informed {
                        // (The uniform ratio is 1: the same products, unmultiplied.)
                        numerator *= old_weight * inverse_j + other_old_weight * inverse_k;
                        denominator *= new_weight * inverse_j + other_new_weight * inverse_k;
                    }
                    (numerator, denominator, old)
                }
            }
        };
        // Required columns freed or taken change the target by e^∓penalty (most matrices have none).
        if matrix.required_count() != 0 {
            let frees_old = other.is_none() || other_takes == CLUTTER;
            if frees_old && required(old) {
                denominator *= self.penalty_factor;
            }
            if other.is_none() && required(new) {
                numerator *= self.penalty_factor;
            }
        }
        if PIPELINE && informed {
            denominator = denominator.nan_if(new == old); // fails both tests below, without a branch
        }
        // Accept with probability min(1, numerator / denominator).
        if !(numerator >= denominator) {
            let uniform = T::of_f64(f64::from(acceptance_bits) * (1.0 / 4_294_967_296.0));
            if !(uniform * denominator < numerator) {
                return false;
            }
        }
        self.accepted += 1;
        self.apply_accepted(matrix, row, new, other, other_takes);
        true
    }

    /// [`MetropolisSampler::apply`] out of line, for an accepted Metropolis move.
    #[inline(never)]
    fn apply_accepted(
        &mut self,
        matrix: &AssociationMatrix<T, N, Z>,
        row: usize,
        new: u16,
        other: Option<usize>,
        other_takes: u16,
    ) {
        self.apply(matrix, row, new, other, other_takes);
    }

    /// Makes the move: `row` takes `new`; the measurement `other` that held `new` (if any) takes
    /// `other_takes`. Updates owners, hash, required count and the log-score by sums of entries.
    // Inlined into the start's climb and the mode's neighbours (thousands of calls per chain on a dense
    // matrix); the step calls it out of line through `apply_accepted`, which keeps the hot loop small.
    #[inline(always)]
    fn apply(
        &mut self,
        matrix: &AssociationMatrix<T, N, Z>,
        row: usize,
        new: u16,
        other: Option<usize>,
        other_takes: u16,
    ) {
        let Some(&old) = self.chain.assignment.get(row) else { return };
        let moved = self.moved_score(matrix, row, old, new, other, other_takes);
        self.apply_moved(row, new, other, other_takes, moved);
    }

    /// [`MetropolisSampler::apply`] given the score and count of unassigned required columns that
    /// [`MetropolisSampler::moved_score`] computed for the move.
    #[inline(always)]
    fn apply_moved(
        &mut self,
        row: usize,
        new: u16,
        other: Option<usize>,
        other_takes: u16,
        (score, unassigned_required): (T, usize),
    ) {
        let Some(&old) = self.chain.assignment.get(row) else { return };
        let mut hash = self.chain.hash ^ self.zobrist(row, old) ^ self.zobrist(row, new);
        if let Some(other_row) = other {
            hash ^= self.zobrist(other_row, new) ^ self.zobrist(other_row, other_takes);
        }
        let chain = &mut self.chain;
        chain.hash = hash;
        chain.assignment[row] = new;
        if let Some(old) = below::<N>(old) {
            chain.owner[old] = NONE;
        }
        if let Some(new) = below::<N>(new) {
            chain.owner[new] = row as u16;
        }
        if let Some(other_row) = other {
            chain.assignment[other_row] = other_takes;
            if let Some(column) = below::<N>(other_takes) {
                chain.owner[column] = other_row as u16;
            }
        }
        (chain.score, chain.unassigned_required) = (score, unassigned_required);
    }

    /// The chain's score and count of unassigned required columns after the move of
    /// [`MetropolisSampler::apply`] (`row` from `old` to `new`, `other` to `other_takes`), from the log-score
    /// by sums of entries; the state is not changed.
    #[inline(always)]
    fn moved_score(
        &self,
        matrix: &AssociationMatrix<T, N, Z>,
        row: usize,
        old: u16,
        new: u16,
        other: Option<usize>,
        other_takes: u16,
    ) -> (T, usize) {
        let required = |column: u16| matrix.is_required(usize::from(column));
        let mut delta = Self::entry(matrix, row, new) - Self::entry(matrix, row, old);
        if let Some(other_row) = other {
            delta += Self::entry(matrix, other_row, other_takes) - Self::entry(matrix, other_row, new);
        }
        // Required columns: a single move frees `old` and takes `new`; paper 003's conflict move frees
        // `old`; a swap keeps the set of assigned columns.
        let before = self.chain.unassigned_required;
        let after = if other.is_none() {
            before + usize::from(required(old)) - usize::from(required(new))
        } else if other_takes == CLUTTER && required(old) {
            before + 1
        } else {
            before
        };
        if after == before {
            // delta − penalty × 0 is delta: the same bits without two integer-to-float conversions.
            (self.chain.score + delta, after)
        } else {
            let penalty = Self::penalty();
            (self.chain.score + (delta - penalty * (T::of_f64(after as f64) - T::of_f64(before as f64))), after)
        }
    }

    /// Hill climbing from the greedy start: applies improving move-or-swap moves (each row to each of its
    /// possible columns or clutter) until none improves, at most `rows` passes.
    fn climb(&mut self, matrix: &AssociationMatrix<T, N, Z>) {
        let rows = matrix.rows();
        let penalty = Self::penalty();
        let required = |column: u16| matrix.is_required(usize::from(column));
        for _ in 0..rows {
            let mut improved = false;
            for row in 0..rows {
                // Each possible column, then clutter.
                for k in 0..=self.possible_columns(row).len() {
                    let new = self.possible_columns(row).get(k).copied().unwrap_or(CLUTTER);
                    let old = self.chain.assignment[row];
                    if new == old {
                        continue;
                    }
                    let other = below::<N>(new).and_then(|column| below::<Z>(self.chain.owner[column]));
                    let mut gain = Self::entry(matrix, row, new) - Self::entry(matrix, row, old);
                    match other {
                        None => {
                            if required(old) {
                                gain -= penalty;
                            }
                            if required(new) {
                                gain += penalty;
                            }
                        }
                        Some(other_row) => {
                            let back = Self::entry(matrix, other_row, old);
                            if back == T::NEG_INFINITY {
                                continue;
                            }
                            gain += back - Self::entry(matrix, other_row, new);
                        }
                    }
                    // Strictly better by a margin, so rounding cannot cycle.
                    if gain > T::of_f64(1e-9) {
                        self.apply(matrix, row, new, other, if other.is_none() { NONE } else { old });
                        improved = true;
                    }
                }
            }
            if !improved {
                break;
            }
        }
    }

    /// Records every feasible move-or-swap neighbour of the current state (each row to each of its
    /// possible columns or clutter), then restores the state: at most rows × (N + 1) moves. From the
    /// mode these are the likeliest candidates for the next best children.
    fn record_neighbours(&mut self, matrix: &AssociationMatrix<T, N, Z>) {
        let saved = (self.chain.score, self.chain.hash, self.chain.unassigned_required);
        for row in 0..matrix.rows().min(Z) {
            for k in 0..=self.possible_columns(row).len() {
                let new = self.possible_columns(row).get(k).copied().unwrap_or(CLUTTER);
                let old = *self.chain.assignment.at(row);
                if new == old {
                    continue;
                }
                let other = below::<N>(new).and_then(|column| below::<Z>(*self.chain.owner.at(column)));
                if let Some(other_row) = other
                    && old != CLUTTER
                    && matrix.entry(other_row, usize::from(old)) == T::NEG_INFINITY
                {
                    continue;
                }
                let (takes, gives_back) = if other.is_none() { (NONE, NONE) } else { (old, new) };
                // A neighbour that cannot enter the kept children is skipped without being made (`record`'s
                // own test, on the score `apply` would give).
                let moved = self.moved_score(matrix, row, old, new, other, takes);
                if moved.1 != 0 || !(matrix.baseline() + moved.0 > self.best.threshold()) {
                    continue;
                }
                self.apply_moved(row, new, other, takes, moved);
                self.record(matrix);
                // The reverse move restores the assignment, owners and hash exactly, and the saved values
                // the running score's bits.
                self.apply_moved(row, old, other, gives_back, (saved.0, saved.2));
                (self.chain.score, self.chain.hash, self.chain.unassigned_required) = saved;
            }
        }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::children::ExhaustiveChildren;
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
                let mut sampler = MetropolisSampler::<f64, 8, 6, 16>::new(
                    SamplerConfig { proposal, ..SamplerConfig::default() },
                    seed,
                );
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
}
