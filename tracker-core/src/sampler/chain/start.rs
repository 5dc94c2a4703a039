//! The chain's start: the exact best association of the matrix ([`best_association`], on the row tables'
//! possible columns when the matrix is gated), or, when that search fails or the exact start is off, a
//! greedy association improved by hill climbing.

use super::MetropolisSampler;
use super::tables::possible;
use crate::association::{AssociationMatrix, CLUTTER};
use crate::index::{At, NONE, below};
use crate::optimal::{best_association, best_association_sparse};
use crate::real::Real;
use crate::sampler::best::association_hash;

impl<T: Real, const N: usize, const Z: usize, const C: usize> MetropolisSampler<T, N, Z, C> {
    /// Optimal start: the association that maximises the chain's target ([`best_association`]). Returns
    /// `false` when that search fails (a NaN entry), leaving the state to [`MetropolisSampler::start_greedy`].
    pub(super) fn start_optimal(&mut self, matrix: &AssociationMatrix<T, N, Z>) -> bool {
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
    pub(super) fn start_greedy(&mut self, matrix: &AssociationMatrix<T, N, Z>) {
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
    pub(super) fn settle(&mut self, matrix: &AssociationMatrix<T, N, Z>) {
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

    /// Hill climbing from the greedy start: applies improving move-or-swap moves (each row to each of its
    /// possible columns or clutter) until none improves, at most `rows` passes.
    pub(super) fn climb(&mut self, matrix: &AssociationMatrix<T, N, Z>) {
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
}
