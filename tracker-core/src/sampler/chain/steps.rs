//! The Metropolis moves (docs/maths.md §7.3–§7.5): each step draws a proposal (a row and its new column,
//! by paper 003's uniform draw, a uniform possible column or the informed draw from the row's weights)
//! and decides it by the exact ratio of linear weights; an accepted state is recorded among the best
//! children. On a speculative out-of-order core the next proposal is drawn before the current one is
//! decided (pipelining), the same draws in the same order.

use super::MetropolisSampler;
use crate::association::{AssociationMatrix, CLUTTER};
use crate::index::{At, NONE, below};
use crate::real::Real;
use crate::sampler::Proposal;
use rand_core::Rng;
use rand_xoshiro::Xoshiro256PlusPlus;
/// The kinds of Metropolis step, as const parameters of the step: paper 003's uniform column of the
/// matrix, a uniform column among the row's possible ones, and the informed draw from the row's weights.
pub(super) const PAPER: u8 = 0;
pub(super) const UNIFORM: u8 = 1;
pub(super) const INFORMED: u8 = 2;

/// Whether a step returns as soon as a swap turns out infeasible (the other measurement cannot take the
/// row's old column), rather than computing the ratio, which is then NaN and rejected: the same decision
/// either way. An in-order core (Cortex-M, RISC-V microcontrollers) pays little for the branch and saves the
/// ratio; a speculative out-of-order core mispredicts it about as often as the draw makes a swap infeasible
/// on a gated matrix, which costs more than the ratio (docs/performance.md, "Impossible weights as NaN").
pub(super) const EARLY_REJECT: bool = !cfg!(any(target_arch = "x86_64", target_arch = "aarch64"));

/// Whether the chain's loop draws each step's proposal before it decides the previous step (software
/// pipelining; the same draws in the same order, so the same chain). A proposal reads only the matrix's
/// tables, so on a speculative out-of-order core its loads no longer wait behind the previous step's
/// mispredicted branches. With it, the informed proposal's proposals of the current state are rejected by
/// the ratio rather than by a branch ([`MetropolisSampler::decide`]). Together: fewer nanoseconds for more
/// instructions (docs/performance.md, "Pipelined steps"); an in-order core would only pay the instructions.
pub(super) const PIPELINE: bool = cfg!(any(target_arch = "x86_64", target_arch = "aarch64"));

/// A step's proposal ([`MetropolisSampler::propose`]): the row, its proposed column (or clutter) and the
/// acceptance test's uniform bits.
#[derive(Debug, Clone, Copy)]
pub(super) struct Draw {
    row: usize,
    new: u16,
    acceptance_bits: u32,
}

impl<T: Real, const N: usize, const Z: usize, const C: usize> MetropolisSampler<T, N, Z, C> {
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
    pub(super) fn moves(
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
    pub(super) fn steps_of<const KIND: u8>(
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
    pub(super) fn alternating_steps(
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
    pub(super) fn decide_and_record<const KIND: u8>(
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
    pub(super) fn step_and_record<const KIND: u8>(
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
    pub(super) fn step<const KIND: u8>(
        &mut self,
        matrix: &AssociationMatrix<T, N, Z>,
        rng: &mut Xoshiro256PlusPlus,
    ) -> bool {
        self.step_with::<KIND, EARLY_REJECT>(matrix, rng)
    }

    /// [`MetropolisSampler::step`], returning early on an infeasible swap if `EARLY` ([`EARLY_REJECT`]).
    #[inline(always)]
    pub(super) fn step_with<const KIND: u8, const EARLY: bool>(
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
    pub(super) fn propose<const KIND: u8>(
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
    pub(super) fn decide<const KIND: u8, const EARLY: bool>(
        &mut self,
        matrix: &AssociationMatrix<T, N, Z>,
        draw: Draw,
    ) -> bool {
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
    pub(super) fn apply_accepted(
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
    pub(super) fn apply(
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
    pub(super) fn apply_moved(
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
    pub(super) fn moved_score(
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

    /// Records the current state if it is feasible and good enough.
    #[inline(always)]
    pub(super) fn record(&mut self, matrix: &AssociationMatrix<T, N, Z>) {
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
}
