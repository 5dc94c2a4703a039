//! The start's neighbours: every feasible move-or-swap of the exact start (each row to each of its
//! possible columns or clutter) is recorded, then the state restored. From the mode these are the
//! likeliest candidates for the next best children, so even a chain allowed no move offers them.

use super::MetropolisSampler;
use crate::association::{AssociationMatrix, CLUTTER};
use crate::index::{At, NONE, below};
use crate::real::Real;

impl<T: Real, const N: usize, const Z: usize, const C: usize> MetropolisSampler<T, N, Z, C> {
    /// Records every feasible move-or-swap neighbour of the current state (each row to each of its
    /// possible columns or clutter), then restores the state: at most rows × (N + 1) moves. From the
    /// mode these are the likeliest candidates for the next best children.
    pub(super) fn record_neighbours(&mut self, matrix: &AssociationMatrix<T, N, Z>) {
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
}
