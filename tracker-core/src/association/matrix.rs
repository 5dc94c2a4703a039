//! The data association matrix of one parent hypothesis and one birth/death event (docs/maths.md §4.2).
//!
//! Rows are the scan's measurements z₁..z_m; columns are the objects that can be detected in the child
//! (the parent's objects in the field of view, minus a dead one, plus a born one); clutter is implicit and
//! may take any number of rows. An association σ assigns each row a column or clutter, no column twice.
//!
//! Entries are log ratios to the all-clutter, all-missed child, so a child's log-weight is a sum:
//!
//! ```text
//! ln w̃(σ) = baseline + Σ_{(z,o) ∈ σ} δ_{z,o}
//! baseline = ln w_i + ln P(e) + N'_F ln(1 − p_D) + m ln λ_C
//! δ_{z,o}  = ln( p_D ĝ_{z,o} / ((1 − p_D) λ_C) )
//! ```
//!
//! which is the weight of docs/maths.md §4.1, `w̃ = w_i P(e) (1−p_D)^{N'_F} λ_C^m Π p_D ĝ / ((1−p_D) λ_C)`.
//! An impossible entry (outside a gate, or a column that cannot be assigned) is `-inf`. When p_D = 1 the
//! ratio is undefined: the missed factor is dropped from the baseline and the entry, and every such column
//! is *required* instead (a child that leaves it unassigned has weight 0). A birth that must be detected
//! (paper 000's "all births detected") is a required column too.

use crate::index::At;
use crate::real::Real;

/// The assignment value of a measurement taken by clutter.
pub const CLUTTER: u16 = u16::MAX;

/// The data association matrix of one (parent, event) pair: at most `Z` rows and `N` columns.
///
/// # Examples
/// ```
/// use tracker_core::association::{AssociationMatrix, CLUTTER};
/// // Two measurements, two objects; object 1 must be detected (p_D = 1).
/// let mut matrix = AssociationMatrix::<f64, 4, 4>::new(2, 2, -3.0);
/// matrix.set_column(0, &[1.0, f64::NEG_INFINITY], false); // z₂ is outside object 0's gate
/// matrix.set_column(1, &[0.5, 2.0], true);
/// assert_eq!(matrix.score(&[0, 1]), -3.0 + 1.0 + 2.0);
/// assert_eq!(matrix.score(&[CLUTTER, 1]), -3.0 + 2.0);
/// assert_eq!(matrix.score(&[1, 0]), f64::NEG_INFINITY); // impossible entry
/// assert_eq!(matrix.score(&[0, CLUTTER]), f64::NEG_INFINITY); // required column 1 left out
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct AssociationMatrix<T, const N: usize, const Z: usize> {
    rows: usize,
    columns: usize,
    entries: [[T; N]; Z],
    required: [bool; N],
    required_count: usize,
    baseline: T,
}

impl<T: Real, const N: usize, const Z: usize> Default for AssociationMatrix<T, N, Z> {
    fn default() -> Self {
        Self::new(0, 0, T::ZERO)
    }
}

impl<T: Real, const N: usize, const Z: usize> AssociationMatrix<T, N, Z> {
    /// An empty `rows × columns` matrix: every entry impossible, no column required. `rows` and `columns`
    /// are clamped to the capacity (`Z` rows, `N` columns).
    ///
    /// # Examples
    /// ```
    /// use tracker_core::association::{AssociationMatrix, CLUTTER};
    /// let matrix = AssociationMatrix::<f64, 2, 3>::new(5, 2, -1.0);
    /// assert_eq!((matrix.rows(), matrix.columns()), (3, 2)); // rows clamped to Z = 3
    /// assert_eq!(matrix.entry(0, 0), f64::NEG_INFINITY);
    /// assert_eq!(matrix.score(&[CLUTTER; 3]), -1.0); // only the all-clutter child is possible
    /// ```
    pub const fn new(rows: usize, columns: usize, baseline: T) -> Self {
        Self {
            rows: if rows < Z { rows } else { Z },
            columns: if columns < N { columns } else { N },
            entries: [[T::NEG_INFINITY; N]; Z],
            required: [false; N],
            required_count: 0,
            baseline,
        }
    }

    /// Builds a matrix from plain likelihood products, as printed in paper 004's Fig. 4: the weight of an
    /// association is the product of its selected entries, with `clutter[j]` the entry of row `j`'s clutter
    /// column (reusable by every row). A zero entry is impossible.
    ///
    /// # Panics
    /// If the table is larger than the capacity or ragged, or `clutter` is shorter than the table.
    ///
    /// # Examples
    /// ```
    /// use tracker_core::association::{AssociationMatrix, CLUTTER};
    /// let table: [&[f64]; 2] = [&[0.6, 0.1], &[0.2, 0.5]];
    /// let matrix = AssociationMatrix::<f64, 2, 2>::from_likelihoods(&table, &[0.3, 0.3]);
    /// assert!((matrix.score(&[0, 1]).exp() - 0.6 * 0.5).abs() < 1e-15);
    /// assert!((matrix.score(&[CLUTTER, 0]).exp() - 0.3 * 0.2).abs() < 1e-15);
    /// assert!((matrix.baseline().exp() - 0.3 * 0.3).abs() < 1e-15);
    /// ```
    pub fn from_likelihoods(table: &[&[T]], clutter: &[T]) -> Self {
        let columns = table.first().map_or(0, |row| row.len());
        assert!(table.len() <= Z && columns <= N, "likelihood table larger than the matrix capacity");
        let mut matrix = Self::new(table.len(), columns, T::zero());
        for (j, row) in table.iter().enumerate() {
            assert_eq!(row.len(), columns, "ragged likelihood table");
            let ln_clutter = crate::real::ln(clutter[j]);
            matrix.baseline += ln_clutter;
            for (o, &value) in row.iter().enumerate() {
                matrix.entries[j][o] = crate::real::ln(value) - ln_clutter;
            }
        }
        matrix
    }

    /// Number of rows (measurements), at most `Z`.
    ///
    /// # Examples
    /// ```
    /// let matrix = tracker_core::association::AssociationMatrix::<f64, 4, 8>::new(3, 2, 0.0);
    /// assert_eq!(matrix.rows(), 3);
    /// ```
    #[inline]
    pub fn rows(&self) -> usize {
        // `rows ≤ Z` always holds; the `min` lets the optimiser see it (and drop callers' bounds checks).
        self.rows.min(Z)
    }

    /// Number of columns (detectable objects), at most `N`.
    ///
    /// # Examples
    /// ```
    /// let matrix = tracker_core::association::AssociationMatrix::<f64, 4, 8>::new(3, 6, 0.0);
    /// assert_eq!(matrix.columns(), 4); // clamped to N = 4
    /// ```
    #[inline]
    pub fn columns(&self) -> usize {
        self.columns.min(N)
    }

    /// `(rows, columns)` without the `min` of [`AssociationMatrix::rows`] and
    /// [`AssociationMatrix::columns`], for a hot path that bounds its indices itself.
    #[inline(always)]
    pub(crate) fn shape(&self) -> (usize, usize) {
        (self.rows, self.columns)
    }

    /// The log-weight of the child in which every row is clutter and every column missed.
    ///
    /// # Examples
    /// ```
    /// use tracker_core::association::{AssociationMatrix, CLUTTER};
    /// let matrix = AssociationMatrix::<f64, 2, 2>::new(2, 2, -7.5);
    /// assert_eq!(matrix.baseline(), matrix.score(&[CLUTTER, CLUTTER]));
    /// ```
    pub fn baseline(&self) -> T {
        self.baseline
    }

    /// Sets the baseline.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::{AssociationMatrix, CLUTTER};
    /// # // 3 measurements × 3 objects; the best child takes the diagonal: −5 + 2 + 3 + 0.2.
    /// # let mut matrix = AssociationMatrix::<f64, 3, 3>::new(3, 3, -5.0);
    /// # matrix.set_column(0, &[2.0, 0.5, -1.0], false);
    /// # matrix.set_column(1, &[1.5, 3.0, f64::NEG_INFINITY], false);
    /// # matrix.set_column(2, &[f64::NEG_INFINITY, 1.0, 0.2], false);
    /// let before = matrix.score(&[0, 1, 2]);
    /// matrix.set_baseline(-4.0); // one nat more for every child
    /// assert_eq!(matrix.score(&[0, 1, 2]), before + 1.0);
    /// ```
    pub fn set_baseline(&mut self, baseline: T) {
        self.baseline = baseline;
    }

    /// The entry δ of row `row`, column `column` (`-inf` when impossible, and outside the capacity).
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::{AssociationMatrix, CLUTTER};
    /// # // 3 measurements × 3 objects; the best child takes the diagonal: −5 + 2 + 3 + 0.2.
    /// # let mut matrix = AssociationMatrix::<f64, 3, 3>::new(3, 3, -5.0);
    /// # matrix.set_column(0, &[2.0, 0.5, -1.0], false);
    /// # matrix.set_column(1, &[1.5, 3.0, f64::NEG_INFINITY], false);
    /// # matrix.set_column(2, &[f64::NEG_INFINITY, 1.0, 0.2], false);
    /// assert_eq!(matrix.entry(1, 1), 3.0);
    /// assert_eq!(matrix.entry(2, 1), f64::NEG_INFINITY);
    /// assert_eq!(matrix.entry(7, 0), f64::NEG_INFINITY); // outside the capacity
    /// ```
    #[inline(always)]
    pub fn entry(&self, row: usize, column: usize) -> T {
        match self.entries.get(row).and_then(|line| line.get(column)) {
            Some(&entry) => entry,
            None => T::NEG_INFINITY,
        }
    }

    /// The entries of row `row`, one per column (empty outside the capacity).
    #[inline(always)]
    pub(crate) fn row(&self, row: usize) -> &[T] {
        let columns = self.columns();
        self.entries.get(row).map_or(&[], |line| &line[..columns])
    }

    /// Whether `column` must be assigned in every child with non-zero weight (`false` outside the
    /// capacity, so for [`CLUTTER`]).
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::{AssociationMatrix, CLUTTER};
    /// # // 3 measurements × 3 objects; the best child takes the diagonal: −5 + 2 + 3 + 0.2.
    /// # let mut matrix = AssociationMatrix::<f64, 3, 3>::new(3, 3, -5.0);
    /// # matrix.set_column(0, &[2.0, 0.5, -1.0], false);
    /// # matrix.set_column(1, &[1.5, 3.0, f64::NEG_INFINITY], false);
    /// # matrix.set_column(2, &[f64::NEG_INFINITY, 1.0, 0.2], false);
    /// matrix.set_required(2, true);
    /// assert!(matrix.is_required(2) && !matrix.is_required(0));
    /// assert!(!matrix.is_required(usize::from(CLUTTER)));
    /// ```
    #[inline(always)]
    pub fn is_required(&self, column: usize) -> bool {
        self.required.get(column).copied().unwrap_or(false)
    }

    /// Number of required columns.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::{AssociationMatrix, CLUTTER};
    /// # // 3 measurements × 3 objects; the best child takes the diagonal: −5 + 2 + 3 + 0.2.
    /// # let mut matrix = AssociationMatrix::<f64, 3, 3>::new(3, 3, -5.0);
    /// # matrix.set_column(0, &[2.0, 0.5, -1.0], false);
    /// # matrix.set_column(1, &[1.5, 3.0, f64::NEG_INFINITY], false);
    /// # matrix.set_column(2, &[f64::NEG_INFINITY, 1.0, 0.2], false);
    /// matrix.set_required(0, true);
    /// matrix.set_required(0, true); // already required: counted once
    /// matrix.set_required(2, true);
    /// assert_eq!(matrix.required_count(), 2);
    /// ```
    pub fn required_count(&self) -> usize {
        self.required_count
    }

    /// Writes column `column` (`< N`) from `entries` (one per row) and its required flag.
    ///
    /// # Examples
    /// ```
    /// use tracker_core::association::{AssociationMatrix, CLUTTER};
    /// let mut matrix = AssociationMatrix::<f64, 2, 2>::new(2, 1, 0.0);
    /// matrix.set_column(0, &[1.0, 2.0], true);
    /// assert_eq!((matrix.entry(0, 0), matrix.entry(1, 0)), (1.0, 2.0));
    /// assert_eq!(matrix.score(&[CLUTTER, 0]), 2.0);
    /// assert_eq!(matrix.score(&[CLUTTER, CLUTTER]), f64::NEG_INFINITY); // column 0 is required
    /// ```
    pub fn set_column(&mut self, column: usize, entries: &[T], required: bool) {
        let rows = self.rows();
        for (line, &value) in self.entries.iter_mut().zip(entries).take(rows) {
            *line.at_mut(column) = value;
        }
        self.set_required(column, required);
    }

    /// Marks `column` (`< N`) required or not.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::{AssociationMatrix, CLUTTER};
    /// # // 3 measurements × 3 objects; the best child takes the diagonal: −5 + 2 + 3 + 0.2.
    /// # let mut matrix = AssociationMatrix::<f64, 3, 3>::new(3, 3, -5.0);
    /// # matrix.set_column(0, &[2.0, 0.5, -1.0], false);
    /// # matrix.set_column(1, &[1.5, 3.0, f64::NEG_INFINITY], false);
    /// # matrix.set_column(2, &[f64::NEG_INFINITY, 1.0, 0.2], false);
    /// assert!(matrix.score(&[CLUTTER, 1, CLUTTER]).is_finite());
    /// matrix.set_required(2, true);
    /// assert_eq!(matrix.score(&[CLUTTER, 1, CLUTTER]), f64::NEG_INFINITY);
    /// assert!(matrix.score(&[CLUTTER, 1, 2]).is_finite());
    /// ```
    pub fn set_required(&mut self, column: usize, required: bool) {
        let flag = self.required.at_mut(column);
        if *flag != required {
            *flag = required;
            if required {
                self.required_count += 1;
            } else {
                self.required_count -= 1;
            }
        }
    }

    /// Appends a column (for a born object) and returns its index, or `None` when the matrix is full.
    ///
    /// # Examples
    /// ```
    /// use tracker_core::association::AssociationMatrix;
    /// let mut matrix = AssociationMatrix::<f64, 2, 1>::new(1, 1, 0.0);
    /// assert_eq!(matrix.push_column(&[4.0], true), Some(1)); // a born object that must be detected
    /// assert_eq!(matrix.score(&[1]), 4.0);
    /// assert_eq!(matrix.push_column(&[1.0], false), None); // N = 2 columns already
    /// ```
    pub fn push_column(&mut self, entries: &[T], required: bool) -> Option<usize> {
        if self.columns >= N {
            return None;
        }
        let column = self.columns;
        self.columns += 1;
        self.set_column(column, entries, required);
        Some(column)
    }

    /// Makes this matrix a copy of `base` in which column `dead` (if any) can take no measurement and is
    /// not required: the matrix of an event built from its parent's no-event matrix, with the same column
    /// numbering.
    ///
    /// # Examples
    /// The matrix of the death of object 1, from the no-event matrix:
    /// ```
    /// # use tracker_core::association::{AssociationMatrix, CLUTTER};
    /// # // 3 measurements × 3 objects; the best child takes the diagonal: −5 + 2 + 3 + 0.2.
    /// # let mut matrix = AssociationMatrix::<f64, 3, 3>::new(3, 3, -5.0);
    /// # matrix.set_column(0, &[2.0, 0.5, -1.0], false);
    /// # matrix.set_column(1, &[1.5, 3.0, f64::NEG_INFINITY], false);
    /// # matrix.set_column(2, &[f64::NEG_INFINITY, 1.0, 0.2], false);
    /// matrix.set_required(1, true);
    /// let mut death = AssociationMatrix::new(0, 0, 0.0);
    /// death.copy_from(&matrix, Some(1));
    /// assert_eq!(death.entry(1, 1), f64::NEG_INFINITY); // the dead object takes no measurement
    /// assert!(!death.is_required(1));
    /// assert_eq!(death.entry(0, 0), matrix.entry(0, 0));
    /// // A child without object 1 is impossible in the parent's matrix, not in the death's.
    /// assert_eq!(matrix.score(&[0, 2, CLUTTER]), f64::NEG_INFINITY);
    /// assert_eq!(death.score(&[0, 2, CLUTTER]), -5.0 + 2.0 + 1.0);
    /// ```
    pub fn copy_from(&mut self, base: &Self, dead: Option<usize>) {
        let (rows, columns) = (base.rows(), base.columns());
        self.rows = rows;
        self.columns = columns;
        self.baseline = base.baseline;
        for (line, source) in self.entries.iter_mut().zip(&base.entries).take(rows) {
            line[..columns].copy_from_slice(&source[..columns]);
            if let Some(entry) = dead.and_then(|dead| line.get_mut(dead)) {
                *entry = T::NEG_INFINITY;
            }
        }
        self.required = base.required;
        self.required_count = base.required_count;
        if let Some(dead) = dead.filter(|&dead| dead < columns) {
            self.set_required(dead, false);
        }
    }

    /// Copies column `column` (`< N`) into `out` (one entry per row).
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::{AssociationMatrix, CLUTTER};
    /// # // 3 measurements × 3 objects; the best child takes the diagonal: −5 + 2 + 3 + 0.2.
    /// # let mut matrix = AssociationMatrix::<f64, 3, 3>::new(3, 3, -5.0);
    /// # matrix.set_column(0, &[2.0, 0.5, -1.0], false);
    /// # matrix.set_column(1, &[1.5, 3.0, f64::NEG_INFINITY], false);
    /// # matrix.set_column(2, &[f64::NEG_INFINITY, 1.0, 0.2], false);
    /// let mut out = [0.0; 3];
    /// matrix.column(1, &mut out);
    /// assert_eq!(out, [1.5, 3.0, f64::NEG_INFINITY]);
    /// ```
    pub fn column(&self, column: usize, out: &mut [T; Z]) {
        for (slot, line) in out.iter_mut().zip(&self.entries).take(self.rows()) {
            *slot = *line.at(column);
        }
    }

    /// The log-weight of `assignment` (one column or [`CLUTTER`] per row), `-inf` when it is impossible,
    /// assigns a column twice, or leaves a required column unassigned.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::{AssociationMatrix, CLUTTER};
    /// # // 3 measurements × 3 objects; the best child takes the diagonal: −5 + 2 + 3 + 0.2.
    /// # let mut matrix = AssociationMatrix::<f64, 3, 3>::new(3, 3, -5.0);
    /// # matrix.set_column(0, &[2.0, 0.5, -1.0], false);
    /// # matrix.set_column(1, &[1.5, 3.0, f64::NEG_INFINITY], false);
    /// # matrix.set_column(2, &[f64::NEG_INFINITY, 1.0, 0.2], false);
    /// assert!((matrix.score(&[0, 1, 2]) - 0.2).abs() < 1e-12);
    /// assert_eq!(matrix.score(&[CLUTTER, CLUTTER, CLUTTER]), -5.0);
    /// assert_eq!(matrix.score(&[1, 1, CLUTTER]), f64::NEG_INFINITY); // column 1 twice
    /// assert_eq!(matrix.score(&[0, 1]), f64::NEG_INFINITY); // a row without an assignment
    /// ```
    pub fn score(&self, assignment: &[u16]) -> T {
        let (rows, columns) = (self.rows(), self.columns());
        let mut used = [false; N];
        let mut total = self.baseline;
        let mut required_assigned = 0;
        for (line, &column) in self.entries.iter().zip(assignment).take(rows) {
            if column == CLUTTER {
                continue;
            }
            let column = column as usize;
            if column >= columns || *used.at(column) {
                return T::NEG_INFINITY;
            }
            *used.at_mut(column) = true;
            if self.is_required(column) {
                required_assigned += 1;
            }
            total += *line.at(column);
        }
        if required_assigned < self.required_count || assignment.len() < rows { T::NEG_INFINITY } else { total }
    }
}

/// A_N(m) = Σ_{n=0}^{min(m,N)} C(N,n) C(m,n) n!: the number of associations of `measurements` measurements
/// with `objects` objects ([003] (4), docs/maths.md §7.1), saturating at `u128::MAX`.
///
/// # Examples
/// ```
/// assert_eq!(tracker_core::association::association_count(10, 5), 63_591);
/// ```
pub fn association_count(objects: u32, measurements: u32) -> u128 {
    let mut total: u128 = 0;
    // term(n) = C(N,n) C(m,n) n! ; term(n+1) = term(n) (N−n)(m−n)/(n+1)
    let mut term: u128 = 1;
    for n in 0..=objects.min(measurements) {
        total = total.saturating_add(term);
        let numerator = term.saturating_mul(u128::from(objects - n)).saturating_mul(u128::from(measurements - n));
        term = if numerator == u128::MAX { u128::MAX } else { numerator / (u128::from(n) + 1) };
    }
    total
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn association_count_table() {
        // Digest §2.3 (3): A_N(m) for m = 0..4 (rows) and N = 0..5 (columns).
        let table = [
            [1, 1, 1, 1, 1, 1],
            [1, 2, 3, 4, 5, 6],
            [1, 3, 7, 13, 21, 31],
            [1, 4, 13, 34, 73, 136],
            [1, 5, 21, 73, 209, 501],
        ];
        for (m, row) in table.iter().enumerate() {
            for (n, &expected) in row.iter().enumerate() {
                assert_eq!(association_count(n as u32, m as u32), expected, "A_{n}({m})");
            }
        }
        assert_eq!(association_count(11, 5), 106_096);
        assert_eq!(association_count(9, 5), 36_046);
    }

    #[test]
    fn score_rejects_double_assignment_and_missing_required() {
        let mut m = AssociationMatrix::<f64, 3, 2>::new(2, 2, 1.0);
        m.set_column(0, &[0.5, 0.25], false);
        m.set_column(1, &[2.0, 3.0], true);
        assert_eq!(m.score(&[0, 1]), 1.0 + 0.5 + 3.0);
        assert_eq!(m.score(&[1, 1]), f64::NEG_INFINITY);
        assert_eq!(m.score(&[0, CLUTTER]), f64::NEG_INFINITY);
        assert_eq!(m.score(&[CLUTTER, 1]), 4.0);
    }
}
