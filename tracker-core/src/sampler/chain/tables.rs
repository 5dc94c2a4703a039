//! The per-row tables of one matrix, built once before its chain runs: each row's possible columns (finite
//! δ), the linear weights that make an acceptance ratio a product with no exp or log, the informed
//! proposal's cumulative distribution with its guide table (Chen and Asau), and the Zobrist hashes of every
//! cell.

use super::{GUIDE_SHIFT, MetropolisSampler};
use crate::association::{AssociationMatrix, CLUTTER};
use crate::index::{At, below};
use crate::real::{Real, exp};
use crate::sampler::REQUIRED_PENALTY;
use crate::sampler::best::cell_hash;
/// The first `count` of a row's possible columns.
#[inline]
pub(super) fn possible<const N: usize>(columns: &[u16; N], count: u16) -> &[u16] {
    &columns[..usize::from(count).min(N)]
}

impl<T: Real, const N: usize, const Z: usize, const C: usize> MetropolisSampler<T, N, Z, C> {
    /// Precomputes `cell_hash` for every (row, column) and for clutter: Z (N + 1) hashes, once.
    pub(super) fn fill_zobrist(&mut self) {
        for (row, (hashes, clutter)) in self.zobrist.iter_mut().zip(self.zobrist_clutter.iter_mut()).enumerate() {
            for (column, hash) in (0u16..).zip(hashes.iter_mut()) {
                *hash = cell_hash(row, column);
            }
            *clutter = cell_hash(row, CLUTTER);
        }
    }

    /// Log-score contribution of `row` taking `column` (0 for clutter).
    #[inline]
    pub(super) fn entry(matrix: &AssociationMatrix<T, N, Z>, row: usize, column: u16) -> T {
        if column == CLUTTER { T::zero() } else { matrix.entry(row, column as usize) }
    }

    #[inline]
    pub(super) fn penalty() -> T {
        T::of_f64(REQUIRED_PENALTY)
    }

    /// Builds the per-row tables of possible columns, linear weights and the informed proposal's
    /// cumulative distribution (O(rows × columns) once per matrix; one exp per possible entry).
    pub(super) fn build_tables(&mut self, matrix: &AssociationMatrix<T, N, Z>) {
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
    pub(super) fn informed_index(&self, row: usize, count: usize, bits: u32) -> usize {
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
    pub(super) fn possible_columns(&self, row: usize) -> &[u16] {
        possible(self.row_columns.at(row), *self.row_count.at(row))
    }

    /// `cell_hash(row, column)` from the table (`row < Z`; any value that is no column is clutter).
    #[inline(always)]
    pub(super) fn zobrist(&self, row: usize, column: u16) -> u64 {
        match below::<N>(column) {
            Some(column) => self.zobrist[row][column],
            None => self.zobrist_clutter[row],
        }
    }

    /// Linear weight of `row` taking `column` (clutter included), relative to the row's largest; as
    /// [`MetropolisSampler::zobrist`].
    #[inline(always)]
    pub(super) fn weight(&self, row: usize, column: u16) -> T {
        match below::<N>(column) {
            Some(column) => self.weights[row][column],
            None => self.clutter_weight[row],
        }
    }
}
