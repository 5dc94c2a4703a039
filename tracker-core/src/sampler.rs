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
//! - **Start**: greedy: each measurement in turn takes its best free column if that beats clutter; then
//!   each unassigned required column takes its best free measurement.
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
use crate::real::{Real, exp, ln, log_add};
use core::cmp::Ordering;
use rand_core::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

/// Penalty (nats) per unassigned required column in the chain's target.
pub const REQUIRED_PENALTY: f64 = 64.0;

const NONE: u16 = u16::MAX;

/// The proposal of the Metropolis chain.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
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
}

impl Default for SamplerConfig {
    fn default() -> Self {
        Self { burn_in: 100, steps: 2_000, proposal: Proposal::Informed, clusters: true, exhaustive_limit: 2_000 }
    }
}

/// SplitMix64: the per-(row, column) hash of the Zobrist-style association hash, and the seed mixer.
#[inline]
pub(crate) fn mix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// Hash contribution of row `row` taking `column`.
#[inline]
fn cell_hash(row: usize, column: u16) -> u64 {
    mix(((row as u64) << 32) | u64::from(column))
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

    /// Number of children kept.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether the set is empty.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The lowest score a new child must beat to enter, `-inf` while there is room.
    #[inline]
    pub fn threshold(&self) -> T {
        if self.len < C { T::NEG_INFINITY } else { self.scores[self.heap[0] as usize] }
    }

    /// The kept children as (score, assignment), in no particular order.
    pub fn iter(&self) -> impl Iterator<Item = (T, &[u16])> + '_ {
        (0..self.len).map(move |i| (self.scores[i], &self.assignments[i][..self.rows]))
    }

    /// Kept child `index` as (score, assignment).
    pub fn get(&self, index: usize) -> Option<(T, &[u16])> {
        (index < self.len).then(|| (self.scores[index], &self.assignments[index][..self.rows]))
    }

    fn table_slot(&self, slot: usize) -> u16 {
        self.table[slot / C][slot % C]
    }

    fn set_table_slot(&mut self, slot: usize, value: u16) {
        self.table[slot / C][slot % C] = value;
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
            let item = item as usize;
            if self.hashes[item] == hash && self.assignments[item][..self.rows] == *assignment {
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
            let home = (self.hashes[item as usize] % size as u64) as usize;
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
        let (a, b) = (a as usize, b as usize);
        match self.scores[a].partial_cmp(&self.scores[b]) {
            Some(Ordering::Less) => true,
            Some(Ordering::Greater) => false,
            _ => self.arrival[a] > self.arrival[b],
        }
    }

    fn sift_down(&mut self, mut at: usize) {
        loop {
            let (left, right) = (2 * at + 1, 2 * at + 2);
            let mut worst = at;
            if left < self.len && self.worse(self.heap[left], self.heap[worst]) {
                worst = left;
            }
            if right < self.len && self.worse(self.heap[right], self.heap[worst]) {
                worst = right;
            }
            if worst == at {
                return;
            }
            self.heap.swap(at, worst);
            at = worst;
        }
    }

    fn sift_up(&mut self, mut at: usize) {
        while at > 0 {
            let parent = (at - 1) / 2;
            if !self.worse(self.heap[at], self.heap[parent]) {
                return;
            }
            self.heap.swap(at, parent);
            at = parent;
        }
    }

    /// Offers a feasible child with exact `score`; keeps it if it is new and beats the worst kept one.
    /// Returns whether it was kept.
    pub fn insert(&mut self, score: T, hash: u64, assignment: &[u16]) -> bool {
        if C == 0 || !(score > self.threshold()) || self.contains(hash, assignment) {
            return false;
        }
        let replaced = self.len == C;
        let item = if replaced {
            // Evict the worst kept child.
            let worst = self.heap[0] as usize;
            let worst_assignment = self.assignments[worst];
            let (slot, _) = self.find(self.hashes[worst], &worst_assignment[..self.rows]);
            self.remove_slot(slot);
            worst
        } else {
            self.heap[self.len] = self.len as u16;
            self.len += 1;
            self.len - 1
        };
        self.scores[item] = score;
        self.hashes[item] = hash;
        self.assignments[item][..assignment.len()].copy_from_slice(assignment);
        self.arrival[item] = self.next_arrival;
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
    rng: Xoshiro256PlusPlus,
    best: BestChildren<T, C, Z>,
    chain: Chain<T, N, Z>,
    /// Informed proposal: per row, the cumulative distribution of its columns in units of 2⁻³² (clutter
    /// takes the rest up to 2³²), and ln of the row's total weight Σ_c e^{δ_jc} + 1.
    cumulative: [[u32; N]; Z],
    log_row_total: [T; Z],
    steps_taken: u64,
    accepted: u64,
}

impl<T: Real, const N: usize, const Z: usize, const C: usize> MetropolisSampler<T, N, Z, C> {
    /// A sampler with `config`, its random stream seeded by `seed`.
    pub fn new(config: SamplerConfig, seed: u64) -> Self {
        Self {
            config,
            rng: Xoshiro256PlusPlus::seed_from_u64(seed),
            best: BestChildren::default(),
            chain: Chain {
                assignment: [CLUTTER; Z],
                owner: [NONE; N],
                score: T::zero(),
                hash: 0,
                unassigned_required: 0,
            },
            cumulative: [[0; N]; Z],
            log_row_total: [T::zero(); Z],
            steps_taken: 0,
            accepted: 0,
        }
    }

    /// Reseeds the random stream (the tracker derives one seed per scan, parent and event).
    pub fn reseed(&mut self, seed: u64) {
        self.rng = Xoshiro256PlusPlus::seed_from_u64(seed);
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

    /// Builds the informed proposal's per-row tables (O(rows × columns), once per matrix).
    fn build_proposals(&mut self, matrix: &AssociationMatrix<T, N, Z>) {
        let (rows, columns) = (matrix.rows(), matrix.columns());
        for row in 0..rows {
            let mut top = T::zero(); // clutter's δ
            for column in 0..columns {
                let entry = matrix.entry(row, column);
                if entry > top {
                    top = entry;
                }
            }
            // Weights relative to the row's largest, so nothing overflows.
            let mut total = exp(-top);
            for column in 0..columns {
                total += exp(matrix.entry(row, column) - top);
            }
            self.log_row_total[row] = top + ln(total);
            let mut cumulative = T::zero();
            let scale = T::of_f64(4_294_967_296.0) / total;
            for column in 0..columns {
                cumulative += exp(matrix.entry(row, column) - top);
                let units = (cumulative * scale).as_f64();
                self.cumulative[row][column] = if units >= 4_294_967_295.0 { u32::MAX } else { units as u32 };
            }
        }
    }

    /// Draws a column for `row` from the informed proposal with the uniform 32-bit `u`.
    #[inline]
    fn sample_column(&self, row: usize, columns: usize, u: u32) -> u16 {
        let table = &self.cumulative[row][..columns];
        // First column whose cumulative bound exceeds u; none: clutter.
        let index = table.partition_point(|&bound| bound <= u);
        if index == columns { CLUTTER } else { index as u16 }
    }

    /// ln q_j(column) of the informed proposal.
    #[inline]
    fn log_proposal(&self, matrix: &AssociationMatrix<T, N, Z>, row: usize, column: u16) -> T {
        Self::entry(matrix, row, column) - self.log_row_total[row]
    }

    /// Greedy start: rows take their best free column if it beats clutter, then unassigned required
    /// columns take their best free row.
    fn start(&mut self, matrix: &AssociationMatrix<T, N, Z>) {
        let (rows, columns) = (matrix.rows(), matrix.columns());
        let chain = &mut self.chain;
        chain.assignment[..rows].fill(CLUTTER);
        chain.owner[..columns].fill(NONE);
        for row in 0..rows {
            let mut best: Option<(usize, T)> = None;
            for column in 0..columns {
                let entry = matrix.entry(row, column);
                if chain.owner[column] == NONE && entry > T::zero() && best.is_none_or(|(_, b)| entry > b) {
                    best = Some((column, entry));
                }
            }
            if let Some((column, _)) = best {
                chain.assignment[row] = column as u16;
                chain.owner[column] = row as u16;
            }
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
                chain.assignment[row] = column as u16;
                chain.owner[column] = row as u16;
            }
        }
        let mut score = T::zero();
        for row in 0..rows {
            score += Self::entry(matrix, row, chain.assignment[row]);
        }
        chain.unassigned_required = (0..columns).filter(|&c| matrix.is_required(c) && chain.owner[c] == NONE).count();
        chain.score = score - Self::penalty() * T::of_f64(chain.unassigned_required as f64);
        chain.hash = association_hash(&chain.assignment[..rows]);
    }

    /// Records the current state if it is feasible and good enough.
    #[inline]
    fn record(&mut self, matrix: &AssociationMatrix<T, N, Z>) {
        let chain = &self.chain;
        if chain.unassigned_required != 0 || !(matrix.baseline() + chain.score > self.best.threshold()) {
            return;
        }
        let rows = matrix.rows();
        if self.best.contains(chain.hash, &chain.assignment[..rows]) {
            return;
        }
        // Exact weight from the formula, not the running sum.
        let exact = matrix.score(&chain.assignment[..rows]);
        let (hash, assignment) = (chain.hash, chain.assignment);
        self.best.insert(exact, hash, &assignment[..rows]);
    }

    /// One Metropolis step; returns whether the state changed.
    #[inline]
    pub fn step(&mut self, matrix: &AssociationMatrix<T, N, Z>) -> bool {
        let (rows, columns) = (matrix.rows(), matrix.columns());
        self.steps_taken += 1;
        let draw = self.rng.next_u64();
        // Row and column from the two halves of one draw (multiply-shift ranges).
        let row = (((draw >> 32) * rows as u64) >> 32) as usize;
        // Informed: every other step (by one bit of the draw) draws from the row's distribution, the
        // others uniformly, so columns of small weight that a better association needs stay reachable.
        // Each kind of step is a Metropolis–Hastings kernel that preserves the target on its own.
        let informed = self.config.proposal == Proposal::Informed && draw & (1 << 31) != 0;
        let new = if informed {
            self.sample_column(row, columns, (draw as u32) << 1)
        } else {
            let pick = ((u64::from((draw as u32) << 1) * (columns as u64 + 1)) >> 32) as usize;
            if pick == columns { CLUTTER } else { pick as u16 }
        };
        let chain = &self.chain;
        let old = chain.assignment[row];
        if new == old {
            return false;
        }
        let new_entry = Self::entry(matrix, row, new);
        if new_entry == T::NEG_INFINITY {
            return false;
        }
        let required = |column: u16| column != CLUTTER && matrix.is_required(column as usize);
        let penalty = Self::penalty();
        let other = if new == CLUTTER { NONE } else { chain.owner[new as usize] };
        let old_entry = Self::entry(matrix, row, old);
        // Δ of the chain's target and the move to make.
        let (delta, other_takes, correction) = if other == NONE {
            let mut delta = new_entry - old_entry;
            if required(old) {
                delta -= penalty;
            }
            if required(new) {
                delta += penalty;
            }
            // Informed: q(old) / q(new) = e^{δ_old − δ_new} cancels the entries' change exactly.
            let correction = if informed { old_entry - new_entry } else { T::zero() };
            (delta, NONE, correction)
        } else {
            let other_row = other as usize;
            let other_old_entry = matrix.entry(other_row, new as usize);
            match self.config.proposal {
                Proposal::MoveOrSwap | Proposal::Informed => {
                    let other_new_entry = Self::entry(matrix, other_row, old);
                    if other_new_entry == T::NEG_INFINITY {
                        return false;
                    }
                    let delta = new_entry + other_new_entry - old_entry - other_old_entry;
                    // The same swap is proposed by (row, new) and by (other, old); so is its reverse.
                    let correction = if informed {
                        let forward =
                            log_add(self.log_proposal(matrix, row, new), self.log_proposal(matrix, other_row, old));
                        let reverse =
                            log_add(self.log_proposal(matrix, row, old), self.log_proposal(matrix, other_row, new));
                        reverse - forward
                    } else {
                        T::zero()
                    };
                    (delta, old, correction)
                }
                Proposal::Paper => {
                    let mut delta = new_entry - old_entry - other_old_entry;
                    if required(old) {
                        delta -= penalty;
                    }
                    (delta, CLUTTER, T::zero())
                }
            }
        };
        // Accept with probability min(1, e^Δ q_reverse / q_forward).
        let log_acceptance = delta + correction;
        if log_acceptance < T::zero() {
            if log_acceptance < T::of_f64(-40.0) {
                return false;
            }
            let uniform = T::of_f64((self.rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64));
            if !(uniform < exp(log_acceptance)) {
                return false;
            }
        }
        self.accepted += 1;
        let chain = &mut self.chain;
        chain.assignment[row] = new;
        chain.hash ^= cell_hash(row, old) ^ cell_hash(row, new);
        if old != CLUTTER {
            chain.owner[old as usize] = NONE;
        }
        if new != CLUTTER {
            chain.owner[new as usize] = row as u16;
        }
        if other != NONE {
            let other_row = other as usize;
            chain.assignment[other_row] = other_takes;
            chain.hash ^= cell_hash(other_row, new) ^ cell_hash(other_row, other_takes);
            if other_takes != CLUTTER {
                chain.owner[other_takes as usize] = other;
            }
        }
        // Required columns: a single move frees `old` and takes `new`; paper 003's conflict move frees
        // `old`; a swap keeps the set of assigned columns.
        if other == NONE {
            chain.unassigned_required =
                chain.unassigned_required + usize::from(required(old)) - usize::from(required(new));
        } else if other_takes == CLUTTER && required(old) {
            chain.unassigned_required += 1;
        }
        chain.score += delta;
        true
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
        if self.config.proposal == Proposal::Informed {
            self.build_proposals(matrix);
        }
        self.start(matrix);
        self.record(matrix);
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
                sampler.build_proposals(&m);
                sampler.start(&m);
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
        sampler.build_proposals(&m);
        sampler.start(&m);
        let mut counts: BTreeMap<Vec<u16>, u64> = BTreeMap::new();
        let n = 400_000;
        for _ in 0..n {
            sampler.step(&m);
            *counts.entry(sampler.chain.assignment[..3].to_vec()).or_default() += 1;
        }
        for (w, a) in &all {
            let p = w.exp() / total;
            let f = counts.get(a).copied().unwrap_or(0) as f64 / n as f64;
            assert!((f - p).abs() < 0.01 + 0.1 * p, "{proposal:?} {a:?}: frequency {f} vs probability {p}");
        }
    }

    #[test]
    fn offered_children_are_distinct_with_exact_weights() {
        for seed in 0..30 {
            let m = random_matrix(seed + 100, 5, 6);
            let mut sampler = MetropolisSampler::<f64, 8, 6, 16>::new(SamplerConfig::default(), seed);
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
