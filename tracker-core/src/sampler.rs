//! The bounded Metropolis sampler of child hypotheses (R-FISST, paper 003 §III, paper 004 §III-B).
//!
//! Heads up: read digest §4.6 before changing anything here. The chain only *searches*; it never
//! estimates weights. Every child it offers carries its exact log-weight, recomputed from the
//! association matrix, and the tracker renormalises over all offered children of all parents.
//!
//! One chain runs on one [`AssociationMatrix`] (a parent and a birth/death event):
//!
//! - **State**: an association vector a (one column or clutter per measurement, no column twice) and its
//!   running log-score Σ δ. Required columns (p_D = 1, or a birth that must be detected) that are left
//!   unassigned cost a penalty of [`REQUIRED_PENALTY`] nats in the chain's target, so the chain can cross
//!   infeasible states; only feasible states are recorded.
//! - **Start**: the mode of the target, found exactly by a shortest augmenting path assignment
//!   ([`crate::optimal`], at most R (M + 1) M reduced costs for R rows and M columns), and recorded:
//!   every chain offers its matrix's best child, whatever its mixing. Then every move-or-swap neighbour
//!   of the mode (at most R (M + 1)) is recorded, the likeliest candidates for the next best children,
//!   and the chain starts from the mode. Should that search fail (only a NaN entry can make it),
//!   greedy (repeatedly the best remaining measurement-object pair that beats clutter, then each
//!   unassigned required column takes its best free measurement) and hill climbing by improving
//!   move-or-swap moves take its place.
//! - **Proposals** (each O(1): one random number picks a row and a column):
//!   - [`Proposal::Paper`]: paper 003's move. The row takes the column; a measurement that held the
//!     column goes to clutter. Not symmetric (undoing a conflict needs two moves), which is harmless
//!     because weights are exact.
//!   - [`Proposal::MoveOrSwap`]: the row takes the column; a measurement that held it takes the row's
//!     old column (or clutter) instead. Symmetric, so Metropolis acceptance is exact detailed balance; it
//!     moves along ridges of good associations instead of falling into clutter.
//!   - [`Proposal::Informed`] (default): as `MoveOrSwap`, but on every other step the column is drawn
//!     from the row's own distribution q_j(c) ∝ e^{δ_jc} (clutter e⁰) through a per-row cumulative table
//!     built once per matrix (a binary search per step). Such a move to a free column is always
//!     accepted, so the chain rarely wastes a step on an impossible or poor column; the uniform steps in
//!     between keep columns of small weight reachable.
//! - **Acceptance**: Metropolis–Hastings, min(1, e^Δ q_reverse / q_forward), with Δ the O(1) change of
//!   the log-score.
//! - **Budget**: `burn_in` steps unrecorded, then `steps` recorded steps; every feasible state visited
//!   after burn-in (and the greedy start) goes to a [`BestChildren`] set that keeps the best `C`
//!   distinct children, with duplicates found in O(1) through an incremental Zobrist-style hash.
//!   At the end the set's children are offered, each once, with exact weights.

use crate::association::{AssociationMatrix, CLUTTER};
use crate::children::{ChildGenerator, ChildSink, GenerateError};
use crate::index::{At, below, copy_prefix};
use crate::optimal::best_association;
use crate::real::{Real, exp};
use core::cmp::Ordering;
use rand_core::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

/// Penalty (nats) per unassigned required column in the chain's target.
pub const REQUIRED_PENALTY: f64 = 64.0;

const NONE: u16 = u16::MAX;

/// The proposal of the Metropolis chain.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Proposal {
    /// Paper 003: a random row takes a random column; a conflicting measurement goes to clutter.
    Paper,
    /// A random row takes a random column; a conflicting measurement takes the row's old column.
    MoveOrSwap,
    /// As `MoveOrSwap`, but every other step draws the column in proportion to the row's entries e^δ
    /// (clutter e⁰), so good associations are proposed often; the Metropolis–Hastings ratio corrects for
    /// it exactly.
    #[default]
    Informed,
}

/// Budget and moves of the sampler.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SamplerConfig {
    /// Steps per chain before recording.
    pub burn_in: u32,
    /// Recorded steps per chain.
    pub steps: u32,
    /// The proposal.
    pub proposal: Proposal,
    /// Split each matrix into independent clusters by gating and combine the clusters' best children.
    pub clusters: bool,
    /// With `clusters`, enumerate a cluster exhaustively when A_n(m) of its n columns and m rows is at most
    /// this; sample larger ones. 0 samples every cluster.
    pub exhaustive_limit: u64,
    /// Start each chain at the exact mode of its target and record the mode's neighbours
    /// ([`crate::optimal`]); `false` starts greedily and climbs, as without it.
    pub exact_start: bool,
}

impl Default for SamplerConfig {
    fn default() -> Self {
        Self::DEFAULT
    }
}

impl SamplerConfig {
    /// The default budget and moves (also usable in a `const` context).
    pub const DEFAULT: Self = Self {
        burn_in: 100,
        steps: 2_000,
        proposal: Proposal::Informed,
        clusters: true,
        exhaustive_limit: 1_000,
        exact_start: true,
    };
}

/// SplitMix64: the per-(row, column) hash of the Zobrist-style association hash, and the seed mixer.
#[inline]
pub(crate) const fn mix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// Hash contribution of row `row` taking `column`.
#[inline]
const fn cell_hash(row: usize, column: u16) -> u64 {
    mix(((row as u64) << 32) | column as u64)
}

/// The hash of a whole association: XOR of its cells' hashes (so one move updates it in O(1)).
pub fn association_hash(assignment: &[u16]) -> u64 {
    assignment.iter().enumerate().fold(0, |h, (row, &column)| h ^ cell_hash(row, column))
}

/// The best `C` distinct children of one chain, with O(1) duplicate detection.
///
/// A child evicted for a better one can never come back: the worst kept score only rises, and a child is
/// admitted only when it beats it. So every distinct child leaves the set at most once.
#[derive(Debug, Clone)]
pub struct BestChildren<T, const C: usize, const Z: usize> {
    scores: [T; C],
    hashes: [u64; C],
    assignments: [[u16; Z]; C],
    /// Min-heap of item indices by (score, arrival): the root is the worst kept child.
    heap: [u16; C],
    arrival: [u32; C],
    len: usize,
    /// Open-addressing table (linear probing) of item indices by hash; 2C slots.
    table: [[u16; C]; 2],
    rows: usize,
    next_arrival: u32,
}

impl<T: Real, const C: usize, const Z: usize> Default for BestChildren<T, C, Z> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T: Real, const C: usize, const Z: usize> BestChildren<T, C, Z> {
    /// An empty set (usable in a `const` context).
    pub const fn new() -> Self {
        Self {
            scores: [T::NEG_INFINITY; C],
            hashes: [0; C],
            assignments: [[CLUTTER; Z]; C],
            heap: [0; C],
            arrival: [0; C],
            len: 0,
            table: [[NONE; C]; 2],
            rows: 0,
            next_arrival: 0,
        }
    }
}

impl<T: Real, const C: usize, const Z: usize> BestChildren<T, C, Z> {
    /// Empties the set for a chain over `rows` measurements.
    pub fn clear(&mut self, rows: usize) {
        self.len = 0;
        self.rows = rows;
        self.next_arrival = 0;
        for half in self.table.iter_mut() {
            half.fill(NONE);
        }
    }

    /// Number of children kept (at most `C`).
    pub fn len(&self) -> usize {
        // The `min` only shows the optimiser the invariant `len ≤ C`.
        self.len.min(C)
    }

    /// Whether the set is empty.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The lowest score a new child must beat to enter, `-inf` while there is room.
    #[inline]
    pub fn threshold(&self) -> T {
        match self.heap.first() {
            Some(&worst) if self.len >= C => *self.scores.at(usize::from(worst)),
            _ => T::NEG_INFINITY,
        }
    }

    /// The first `rows` entries of a kept assignment.
    #[inline]
    fn prefix<'a>(&self, assignment: &'a [u16; Z]) -> &'a [u16] {
        &assignment[..self.rows.min(Z)]
    }

    /// The kept children as (score, assignment), in no particular order.
    pub fn iter(&self) -> impl Iterator<Item = (T, &[u16])> + '_ {
        self.scores
            .iter()
            .zip(&self.assignments)
            .take(self.len)
            .map(move |(&score, assignment)| (score, self.prefix(assignment)))
    }

    /// Kept child `index` as (score, assignment).
    pub fn get(&self, index: usize) -> Option<(T, &[u16])> {
        if index >= self.len {
            return None;
        }
        Some((*self.scores.get(index)?, self.prefix(self.assignments.get(index)?)))
    }

    /// Slot `slot` (`< 2C`) of the hash table.
    fn table_slot(&self, slot: usize) -> u16 {
        *self.table.at(slot / C).at(slot % C)
    }

    fn set_table_slot(&mut self, slot: usize, value: u16) {
        *self.table.at_mut(slot / C).at_mut(slot % C) = value;
    }

    /// Slot of `hash` with `assignment` in the table, or the empty slot where it would go.
    fn find(&self, hash: u64, assignment: &[u16]) -> (usize, bool) {
        let size = 2 * C;
        let mut slot = (hash % size as u64) as usize;
        // The table is at most half full, so an empty slot is always reached.
        for _ in 0..size {
            let item = self.table_slot(slot);
            if item == NONE {
                return (slot, false);
            }
            let item = usize::from(item);
            if *self.hashes.at(item) == hash && self.prefix(self.assignments.at(item)) == assignment {
                return (slot, true);
            }
            slot = (slot + 1) % size;
        }
        (slot, false)
    }

    /// Whether the child is already kept.
    pub fn contains(&self, hash: u64, assignment: &[u16]) -> bool {
        self.find(hash, assignment).1
    }

    /// Removes the table entry at `slot` (backward-shift deletion keeps probe chains intact).
    fn remove_slot(&mut self, mut slot: usize) {
        let size = 2 * C;
        self.set_table_slot(slot, NONE);
        let mut next = (slot + 1) % size;
        for _ in 0..size {
            let item = self.table_slot(next);
            if item == NONE {
                return;
            }
            let home = (*self.hashes.at(usize::from(item)) % size as u64) as usize;
            // Move the entry back if its home is not cyclically in (slot, next].
            let distance_to_next = (next + size - home) % size;
            let distance_to_slot = (slot + size - home) % size;
            if distance_to_slot < distance_to_next {
                self.set_table_slot(slot, item);
                self.set_table_slot(next, NONE);
                slot = next;
            }
            next = (next + 1) % size;
        }
    }

    fn worse(&self, a: u16, b: u16) -> bool {
        let (a, b) = (usize::from(a), usize::from(b));
        match self.scores.at(a).partial_cmp(self.scores.at(b)) {
            Some(Ordering::Less) => true,
            Some(Ordering::Greater) => false,
            _ => self.arrival.at(a) > self.arrival.at(b),
        }
    }

    fn sift_down(&mut self, mut at: usize) {
        loop {
            let (left, right) = (2 * at + 1, 2 * at + 2);
            let mut worst = at;
            if left < self.len && self.worse(*self.heap.at(left), *self.heap.at(worst)) {
                worst = left;
            }
            if right < self.len && self.worse(*self.heap.at(right), *self.heap.at(worst)) {
                worst = right;
            }
            if worst == at {
                return;
            }
            self.heap.swap_at(at, worst);
            at = worst;
        }
    }

    fn sift_up(&mut self, mut at: usize) {
        while at > 0 {
            let parent = (at - 1) / 2;
            if !self.worse(*self.heap.at(at), *self.heap.at(parent)) {
                return;
            }
            self.heap.swap_at(at, parent);
            at = parent;
        }
    }

    /// Offers a feasible child with exact `score`; keeps it if it is new and beats the worst kept one.
    /// Returns whether it was kept.
    pub fn insert(&mut self, score: T, hash: u64, assignment: &[u16]) -> bool {
        if self.contains(hash, assignment) {
            return false;
        }
        self.insert_absent(score, hash, assignment)
    }

    /// As [`BestChildren::insert`], for a child the caller knows is not kept.
    pub(crate) fn insert_absent(&mut self, score: T, hash: u64, assignment: &[u16]) -> bool {
        if C == 0 || !(score > self.threshold()) {
            return false;
        }
        let replaced = self.len >= C;
        let item = if replaced {
            // Evict the worst kept child.
            let worst = usize::from(*self.heap.at(0));
            let worst_assignment = *self.assignments.at(worst);
            let (slot, _) = self.find(*self.hashes.at(worst), self.prefix(&worst_assignment));
            self.remove_slot(slot);
            worst
        } else {
            let item = self.len;
            *self.heap.at_mut(item) = item as u16;
            self.len = item + 1;
            item
        };
        *self.scores.at_mut(item) = score;
        *self.hashes.at_mut(item) = hash;
        copy_prefix(self.assignments.at_mut(item), assignment);
        *self.arrival.at_mut(item) = self.next_arrival;
        self.next_arrival = self.next_arrival.wrapping_add(1);
        let (slot, _) = self.find(hash, assignment);
        self.set_table_slot(slot, item as u16);
        if replaced {
            self.sift_down(0);
        } else {
            self.sift_up(self.len - 1);
        }
        true
    }
}

/// The first `count` of a row's possible columns.
#[inline]
fn possible<const N: usize>(columns: &[u16; N], count: u16) -> &[u16] {
    &columns[..usize::from(count).min(N)]
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
}

/// A Metropolis chain per association matrix, keeping the best `C` distinct children.
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
    pub fn new(config: SamplerConfig, seed: u64) -> Self {
        let mut sampler = Self::empty(config);
        sampler.reseed(seed);
        sampler
    }

    /// A sampler without a random stream yet (usable in a `const` context, so that a tracker can live in
    /// a `static`); [`MetropolisSampler::reseed`] gives it one.
    pub const fn empty(config: SamplerConfig) -> Self {
        let mut zobrist = [[0u64; N]; Z];
        let mut zobrist_clutter = [0u64; Z];
        let mut row = 0;
        while row < Z {
            let mut column = 0;
            while column < N {
                zobrist[row][column] = cell_hash(row, column as u16);
                column += 1;
            }
            zobrist_clutter[row] = cell_hash(row, CLUTTER);
            row += 1;
        }
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
            },
            row_columns: [[0; N]; Z],
            row_count: [0; Z],
            cumulative: [[0; N]; Z],
            weights: [[T::ZERO; N]; Z],
            clutter_weight: [T::ONE; Z],
            inverse_row_total: [T::ONE; Z],
            // Set with the tables (an exp cannot run in a const context).
            penalty_factor: T::ONE,
            zobrist,
            zobrist_clutter,
            steps_taken: 0,
            accepted: 0,
        }
    }

    /// Reseeds the random stream (the tracker derives one seed per scan, parent and event).
    pub fn reseed(&mut self, seed: u64) {
        self.rng = Some(Xoshiro256PlusPlus::seed_from_u64(seed));
    }

    /// The configuration.
    pub fn config(&self) -> &SamplerConfig {
        &self.config
    }

    /// Steps taken over the sampler's lifetime.
    pub fn steps_taken(&self) -> u64 {
        self.steps_taken
    }

    /// Accepted proposals over the sampler's lifetime.
    pub fn accepted(&self) -> u64 {
        self.accepted
    }

    /// The best distinct children of the last chain, as (exact log-weight, assignment).
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
                let weight = if entry > T::NEG_INFINITY { exp(entry - top) } else { T::zero() };
                weights[column] = weight;
                total += weight;
            }
            self.clutter_weight[row] = clutter;
            self.inverse_row_total[row] = T::one() / total;
            let scale = T::of_f64(4_294_967_296.0) / total;
            let mut cumulative = T::zero();
            let (weights, possible) = (&self.weights[row], &self.row_columns[row]);
            for (bound, &column) in self.cumulative[row].iter_mut().zip(possible).take(count) {
                cumulative += *weights.at(usize::from(column));
                let units = (cumulative * scale).as_f64();
                *bound = if units >= 4_294_967_295.0 { u32::MAX } else { units as u32 };
            }
        }
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
        if !best_association(matrix, Self::penalty(), &mut self.chain.assignment) {
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

    /// One Metropolis step; returns whether the state changed.
    #[inline]
    pub fn step(&mut self, matrix: &AssociationMatrix<T, N, Z>) -> bool {
        // The row is clamped below and the column checked by `below`: no need for the clamped sizes.
        let (rows, columns) = matrix.shape();
        self.steps_taken += 1;
        let Some(rng) = self.rng.as_mut() else { return false };
        let draw = rng.next_u64();
        // Row from the high half of the draw (multiply-shift range), the rest picks the column.
        let row = ((((draw >> 32) * rows as u64) >> 32) as usize).min(Z - 1);
        let bits = (draw as u32) << 1;
        let proposal = self.config.proposal;
        // Informed: every other step (one bit of the draw) draws from the row's own distribution, the
        // others uniformly among the row's possible columns and clutter. Each kind of step is a
        // Metropolis–Hastings kernel that preserves the target on its own.
        let informed = proposal == Proposal::Informed && draw & (1 << 31) != 0;
        let new = match proposal {
            Proposal::Paper => {
                // Paper 003: any column of the matrix, or clutter.
                let pick = ((u64::from(bits) * (columns as u64 + 1)) >> 32) as usize;
                if pick >= columns { CLUTTER } else { pick as u16 }
            }
            _ => {
                let count = usize::from(self.row_count[row]);
                if count > N {
                    return false; // never: a row has at most N possible columns
                }
                let k = if informed {
                    self.cumulative[row][..count].partition_point(|&bound| bound <= bits)
                } else {
                    ((u64::from(bits) * (count as u64 + 1)) >> 32) as usize
                };
                if k >= count { CLUTTER } else { self.row_columns[row][k] }
            }
        };
        let chain = &self.chain;
        let old = chain.assignment[row];
        if new == old {
            return false;
        }
        // Its weight, and the measurement that holds it (if any).
        let (new_weight, other) = match below::<N>(new) {
            None => (self.clutter_weight[row], None),
            Some(column) => {
                let weight = self.weights[row][column];
                if weight == T::zero() && matrix.entry(row, column) == T::NEG_INFINITY {
                    return false; // impossible (paper 003's uniform column)
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
            None => {
                if informed {
                    (T::one(), T::one(), NONE)
                } else {
                    (new_weight, old_weight, NONE)
                }
            }
            Some(other_row) => match proposal {
                Proposal::MoveOrSwap | Proposal::Informed => {
                    let other_new_weight = self.weight(other_row, old);
                    if other_new_weight == T::zero()
                        && old != CLUTTER
                        && matrix.entry(other_row, old as usize) == T::NEG_INFINITY
                    {
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
                        numerator *= old_weight * inverse_j + other_old_weight * inverse_k;
                        denominator *= new_weight * inverse_j + other_new_weight * inverse_k;
                    }
                    (numerator, denominator, old)
                }
                Proposal::Paper => {
                    // The other measurement goes to clutter.
                    (new_weight * self.clutter_weight[other_row], old_weight * self.weight(other_row, new), CLUTTER)
                }
            },
        };
        // Required columns freed or taken change the target by e^∓penalty.
        let frees_old = other.is_none() || other_takes == CLUTTER;
        if frees_old && required(old) {
            denominator *= self.penalty_factor;
        }
        if other.is_none() && required(new) {
            numerator *= self.penalty_factor;
        }
        // Accept with probability min(1, numerator / denominator).
        if !(numerator >= denominator) {
            let Some(rng) = self.rng.as_mut() else { return false };
            let uniform = T::of_f64((rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64));
            if !(uniform * denominator < numerator) {
                return false;
            }
        }
        self.accepted += 1;
        self.apply(matrix, row, new, other, other_takes);
        true
    }

    /// Makes the move: `row` takes `new`; the measurement `other` that held `new` (if any) takes
    /// `other_takes`. Updates owners, hash, required count and the log-score by sums of entries.
    #[inline]
    fn apply(
        &mut self,
        matrix: &AssociationMatrix<T, N, Z>,
        row: usize,
        new: u16,
        other: Option<usize>,
        other_takes: u16,
    ) {
        let required = |column: u16| matrix.is_required(usize::from(column));
        let Some(&old) = self.chain.assignment.get(row) else { return };
        let mut delta = Self::entry(matrix, row, new) - Self::entry(matrix, row, old);
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
            delta += Self::entry(matrix, other_row, other_takes) - Self::entry(matrix, other_row, new);
            chain.assignment[other_row] = other_takes;
            if let Some(column) = below::<N>(other_takes) {
                chain.owner[column] = other_row as u16;
            }
        }
        // Required columns: a single move frees `old` and takes `new`; paper 003's conflict move frees
        // `old`; a swap keeps the set of assigned columns.
        let before = chain.unassigned_required;
        if other.is_none() {
            chain.unassigned_required = before + usize::from(required(old)) - usize::from(required(new));
        } else if other_takes == CLUTTER && required(old) {
            chain.unassigned_required += 1;
        }
        if chain.unassigned_required == before {
            // delta − penalty × 0 is delta: the same bits without two integer-to-float conversions.
            chain.score += delta;
        } else {
            let penalty = Self::penalty();
            chain.score += delta - penalty * (T::of_f64(chain.unassigned_required as f64) - T::of_f64(before as f64));
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
                self.apply(matrix, row, new, other, takes);
                self.record(matrix);
                // The reverse move restores the assignment and owners exactly; the saved values restore
                // the running score's bits.
                self.apply(matrix, row, old, other, gives_back);
                (self.chain.score, self.chain.hash, self.chain.unassigned_required) = saved;
            }
        }
    }

    /// Runs one chain on `matrix` and leaves its best distinct children in [`MetropolisSampler::best`].
    pub fn run(&mut self, matrix: &AssociationMatrix<T, N, Z>) {
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
        for _ in 0..self.config.burn_in {
            self.step(matrix);
        }
        self.record(matrix);
        for _ in 0..self.config.steps {
            if self.step(matrix) {
                self.record(matrix);
            }
        }
    }
}

impl<T: Real, const N: usize, const Z: usize, const C: usize> ChildGenerator<T, N, Z>
    for MetropolisSampler<T, N, Z, C>
{
    fn generate<K: ChildSink<T>>(
        &mut self,
        matrix: &AssociationMatrix<T, N, Z>,
        sink: &mut K,
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

    fn splitmix(state: &mut u64) -> u64 {
        *state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        mix(*state)
    }

    fn random_matrix(seed: u64, rows: usize, columns: usize) -> AssociationMatrix<f64, 8, 6> {
        let mut s = seed;
        let mut m = AssociationMatrix::new(rows, columns, -3.0);
        for c in 0..columns {
            let entries: Vec<f64> = (0..rows)
                .map(|_| {
                    let u = (splitmix(&mut s) >> 11) as f64 / (1u64 << 53) as f64;
                    if u < 0.25 { f64::NEG_INFINITY } else { 8.0 * u - 3.0 }
                })
                .collect();
            m.set_column(c, &entries, false);
        }
        m
    }

    #[test]
    fn best_children_keeps_the_top_c_distinct_children() {
        let mut seed = 11u64;
        for trial in 0..200 {
            let mut best = BestChildren::<f64, 5, 3>::default();
            best.clear(3);
            let mut offered: Vec<(f64, usize, [u16; 3])> = vec![];
            for arrival in 0..60 {
                let a = [
                    (splitmix(&mut seed) % 4) as u16,
                    (splitmix(&mut seed) % 4) as u16,
                    (splitmix(&mut seed) % 4) as u16,
                ];
                // Scores are a function of the child, so duplicates carry the same score.
                let score = ((a[0] * 7 + a[1] * 3 + a[2]) % 11) as f64 + (trial % 3) as f64;
                best.insert(score, association_hash(&a), &a);
                offered.push((score, arrival, a));
            }
            // Expected: distinct children by first arrival, top 5 by (score desc, arrival asc).
            let mut first: BTreeMap<[u16; 3], (f64, usize)> = BTreeMap::new();
            for (score, arrival, a) in &offered {
                first.entry(*a).or_insert((*score, *arrival));
            }
            let mut ranked: Vec<_> = first.iter().map(|(a, (s, t))| (*s, *t, *a)).collect();
            ranked.sort_by(|x, y| y.0.total_cmp(&x.0).then(x.1.cmp(&y.1)));
            let expected: BTreeSet<[u16; 3]> = ranked.iter().take(5).map(|r| r.2).collect();
            let got: BTreeSet<[u16; 3]> = best.iter().map(|(_, a)| [a[0], a[1], a[2]]).collect();
            let expected_scores: Vec<f64> = ranked.iter().take(5).map(|r| r.0).collect();
            let mut got_scores: Vec<f64> = best.iter().map(|(s, _)| s).collect();
            got_scores.sort_by(|a, b| b.total_cmp(a));
            assert_eq!(got_scores, expected_scores, "trial {trial}");
            assert_eq!(got.len(), 5);
            // Same scores; the set may differ only among children tied with the worst kept score.
            let worst = expected_scores[4];
            for a in got.symmetric_difference(&expected) {
                assert_eq!(first[a].0, worst, "trial {trial}: {a:?}");
            }
        }
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
                check_chain(&sampler, &m);
                for _ in 0..2_000 {
                    sampler.step(&m);
                    check_chain(&sampler, &m);
                }
            }
        }
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
            sampler.step(&m);
            *counts.entry(sampler.chain.assignment[..3].to_vec()).or_default() += 1;
            check_chain(&sampler, &m);
        }
        for (w, a) in &all {
            let p = w.exp() / total;
            let f = counts.get(a).copied().unwrap_or(0) as f64 / n as f64;
            assert!((f - p).abs() < 0.004 + 0.03 * p, "{proposal:?} {a:?}: frequency {f} vs probability {p}");
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
