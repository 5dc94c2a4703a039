//! Child generators: the producers of a parent's children for one birth/death event.
//!
//! A [`ChildGenerator`] walks an [`AssociationMatrix`] and offers children to a [`ChildSink`], each
//! **distinct child exactly once**, with its exact log-weight from the matrix (docs/maths.md §7.6: weights
//! are always computed from the formula, never estimated from how often a sampler visits a child). The sink
//! keeps the best ones and the running normaliser. [`ExhaustiveChildren`] offers every child with
//! non-zero weight; the Metropolis sampler implements the same trait.

use crate::association::{AssociationMatrix, CLUTTER};
use crate::index::{At, below};
use crate::real::Real;

/// Receives children.
///
/// # Examples
/// A sink that counts the children and sums their weights:
/// ```
/// use tracker_core::association::AssociationMatrix;
/// use tracker_core::children::{ChildGenerator, ChildSink, ExhaustiveChildren};
///
/// #[derive(Default)]
/// struct Sum {
///     children: usize,
///     weight: f64,
/// }
///
/// impl ChildSink<f64> for Sum {
///     fn offer(&mut self, log_weight: f64, _assignment: &[u16]) {
///         self.children += 1;
///         self.weight += log_weight.exp();
///     }
/// }
///
/// // One measurement, one object: clutter (weight 1) or the object (weight e).
/// let mut matrix = AssociationMatrix::<f64, 1, 1>::new(1, 1, 0.0);
/// matrix.set_column(0, &[1.0], false);
/// let mut sum = Sum::default();
/// ExhaustiveChildren::new(10).generate(&matrix, &mut sum)?;
/// assert_eq!(sum.children, 2);
/// assert!((sum.weight - (1.0 + 1f64.exp())).abs() < 1e-12);
/// # Ok::<(), tracker_core::children::GenerateError>(())
/// ```
pub trait ChildSink<T> {
    /// Offers one distinct child: its log-weight and, per row, the column it takes or [`CLUTTER`].
    fn offer(&mut self, log_weight: T, assignment: &[u16]);

    /// Reports the total log-weight of children that exist but were not offered (so the scan's total
    /// weight, and the captured mass, stay honest). The default ignores it.
    fn unoffered(&mut self, log_mass: T) {
        let _ = log_mass;
    }
}

/// A sink borrowed mutably is a sink (so adapters can wrap one without taking it).
impl<T, Sink: ChildSink<T> + ?Sized> ChildSink<T> for &mut Sink {
    fn offer(&mut self, log_weight: T, assignment: &[u16]) {
        (**self).offer(log_weight, assignment);
    }

    fn unoffered(&mut self, log_mass: T) {
        (**self).unoffered(log_mass);
    }
}

/// Why a generator stopped early.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum GenerateError {
    /// The configured number of children per scan was reached before the enumeration finished.
    BudgetExceeded {
        /// The budget.
        budget: u64,
    },
}

/// Produces the children of one (parent, event) association matrix.
pub trait ChildGenerator<T: Real, const N: usize, const Z: usize> {
    /// Offers children of `matrix` to `sink`; returns how many were offered.
    ///
    /// # Errors
    /// [`GenerateError`] when a budget stops the generator; the sink then holds a partial set.
    fn generate<Sink: ChildSink<T>>(
        &mut self,
        matrix: &AssociationMatrix<T, N, Z>,
        sink: &mut Sink,
    ) -> Result<u64, GenerateError>;
}

/// Every child, by depth-first enumeration, with a budget on the number of leaves visited per scan.
///
/// Order: rows in order; for each row clutter first, then columns in increasing index. This order is the
/// deterministic tie-break of equal weights downstream. Branches that can no longer assign every
/// required column are cut, and impossible (`-inf`) entries are skipped, so with gating the cost follows
/// the number of feasible children, not A_N(m).
///
/// # Examples
/// ```
/// use tracker_core::association::{AssociationMatrix, association_count};
/// use tracker_core::children::{ChildGenerator, ExhaustiveChildren, GenerateError};
/// use tracker_core::selection::TopChildren;
/// let mut matrix = AssociationMatrix::<f64, 2, 2>::new(2, 2, 0.0);
/// matrix.set_column(0, &[1.0, 0.5], false);
/// matrix.set_column(1, &[0.2, 2.0], false);
///
/// let mut top = TopChildren::<f64, 8, 2>::new();
/// let offered = ExhaustiveChildren::new(1_000).generate(&matrix, &mut top)?;
/// assert_eq!(u128::from(offered), association_count(2, 2)); // A_2(2) = 7
/// assert_eq!(top.len(), 7);
/// let best = top.kept().iter().map(|child| child.log_weight).fold(f64::NEG_INFINITY, f64::max);
/// assert_eq!(best, 1.0 + 2.0);
///
/// let mut top = TopChildren::<f64, 8, 2>::new();
/// let error = ExhaustiveChildren::new(5).generate(&matrix, &mut top).unwrap_err();
/// assert_eq!(error, GenerateError::BudgetExceeded { budget: 5 });
/// # Ok::<(), GenerateError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ExhaustiveChildren {
    budget: u64,
    leaves: u64,
}

impl ExhaustiveChildren {
    /// A generator that visits at most `budget` leaves over its lifetime (one scan).
    ///
    /// # Examples
    /// ```
    /// use tracker_core::association::AssociationMatrix;
    /// use tracker_core::children::{ChildGenerator, ExhaustiveChildren};
    /// use tracker_core::selection::TopChildren;
    /// // One budget over a whole scan: three matrices of 2 children each need 6 leaves.
    /// let mut matrix = AssociationMatrix::<f64, 1, 1>::new(1, 1, 0.0);
    /// matrix.set_column(0, &[0.0], false);
    /// let mut generator = ExhaustiveChildren::new(5);
    /// let mut top = TopChildren::<f64, 8, 1>::new();
    /// assert!(generator.generate(&matrix, &mut top).is_ok());
    /// assert!(generator.generate(&matrix, &mut top).is_ok());
    /// assert!(generator.generate(&matrix, &mut top).is_err());
    /// ```
    pub fn new(budget: u64) -> Self {
        Self { budget, leaves: 0 }
    }

    /// Leaves visited so far.
    ///
    /// # Examples
    /// ```
    /// use tracker_core::association::AssociationMatrix;
    /// use tracker_core::children::{ChildGenerator, ExhaustiveChildren};
    /// use tracker_core::selection::TopChildren;
    /// let mut matrix = AssociationMatrix::<f64, 3, 2>::new(2, 3, 0.0);
    /// for column in 0..3 {
    ///     matrix.set_column(column, &[0.0, 0.0], false);
    /// }
    /// let mut generator = ExhaustiveChildren::new(u64::MAX);
    /// generator.generate(&matrix, &mut TopChildren::<f64, 4, 2>::new())?;
    /// assert_eq!(generator.leaves_visited(), 13); // A_3(2)
    /// # Ok::<(), tracker_core::children::GenerateError>(())
    /// ```
    pub fn leaves_visited(&self) -> u64 {
        self.leaves
    }
}

impl<T: Real, const N: usize, const Z: usize> ChildGenerator<T, N, Z> for ExhaustiveChildren {
    // The enumeration is one iterative depth-first loop (no recursion: the stack is bounded by Z rows
    // of fixed-size state), which is why it is longer than the other functions.
    fn generate<Sink: ChildSink<T>>(
        &mut self,
        matrix: &AssociationMatrix<T, N, Z>,
        sink: &mut Sink,
    ) -> Result<u64, GenerateError> {
        let rows = matrix.rows();
        let required_total = matrix.required_count();
        let mut assignment = [CLUTTER; Z];
        if rows == 0 {
            if required_total > 0 {
                return Ok(0);
            }
            self.count_leaf()?;
            sink.offer(matrix.baseline(), &assignment[..0]);
            return Ok(1);
        }

        let mut used = [false; N];
        // partial[j]: log-weight of rows 0..j; next_option[j]: 0 = clutter, 1 + c = column c.
        let mut partial = [T::zero(); Z];
        let mut next_option = [0u16; Z];
        let mut required_assigned = 0usize;
        let mut offered = 0u64;
        let mut row = 0usize;
        *partial.at_mut(0) = matrix.baseline();
        loop {
            // `row < rows ≤ Z` always holds; the check shows it to the optimiser.
            if row >= Z {
                return Ok(offered);
            }
            // Release this row's previous choice.
            if let Some(previous) = below::<N>(assignment[row]) {
                used[previous] = false;
                if matrix.is_required(previous) {
                    required_assigned -= 1;
                }
                assignment[row] = CLUTTER;
            }
            // Find the next feasible option of this row: clutter, then each free column with a possible
            // entry.
            let mut option = usize::from(next_option[row]);
            let mut chosen: Option<(u16, T)> = None;
            if option == 0 {
                chosen = Some((CLUTTER, T::zero()));
                option = 1;
            } else {
                let entries = matrix.row(row);
                for column in option - 1..entries.len() {
                    let entry = entries[column];
                    if !used[column] && entry > T::NEG_INFINITY {
                        chosen = Some((column as u16, entry));
                        option = column + 2;
                        break;
                    }
                }
            }
            let Some((column, entry)) = chosen else {
                // Exhausted: back up one row.
                if row == 0 {
                    return Ok(offered);
                }
                row -= 1;
                continue;
            };
            next_option[row] = option as u16;
            if let Some(index) = below::<N>(column) {
                used[index] = true;
                if matrix.is_required(index) {
                    required_assigned += 1;
                }
                assignment[row] = column;
            }
            let value = partial[row] + entry;
            let rows_left = rows - row - 1;
            if required_total - required_assigned > rows_left {
                continue; // cannot assign every required column any more
            }
            if rows_left == 0 {
                self.count_leaf()?;
                sink.offer(value, &assignment[..rows]);
                offered += 1;
            } else {
                row += 1;
                *partial.at_mut(row) = value;
                *next_option.at_mut(row) = 0;
                *assignment.at_mut(row) = CLUTTER;
            }
        }
    }
}

impl ExhaustiveChildren {
    fn count_leaf(&mut self) -> Result<(), GenerateError> {
        if self.leaves >= self.budget {
            return Err(GenerateError::BudgetExceeded { budget: self.budget });
        }
        self.leaves += 1;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::association::association_count;

    struct Collect {
        children: std::vec::Vec<(f64, std::vec::Vec<u16>)>,
    }

    impl ChildSink<f64> for Collect {
        fn offer(&mut self, log_weight: f64, assignment: &[u16]) {
            self.children.push((log_weight, assignment.to_vec()));
        }
    }

    fn full_matrix(rows: usize, columns: usize) -> AssociationMatrix<f64, 6, 5> {
        let mut m = AssociationMatrix::new(rows, columns, 0.0);
        for c in 0..columns {
            let entries: std::vec::Vec<f64> = (0..rows).map(|r| (r * 7 + c) as f64 * 0.1).collect();
            m.set_column(c, &entries, false);
        }
        m
    }

    #[test]
    fn enumerates_a_n_of_m_distinct_valid_children() {
        for rows in 0..=4 {
            for columns in 0..=5 {
                let m = full_matrix(rows, columns);
                let mut sink = Collect { children: vec![] };
                let n = ExhaustiveChildren::new(u64::MAX).generate(&m, &mut sink).unwrap();
                assert_eq!(u128::from(n), association_count(columns as u32, rows as u32));
                let mut seen = std::collections::BTreeSet::new();
                for (w, a) in &sink.children {
                    assert!(seen.insert(a.clone()), "duplicate child {a:?}");
                    assert_eq!(*w, m.score(a), "weight of {a:?}");
                    let mut cols: std::vec::Vec<_> = a.iter().filter(|&&c| c != CLUTTER).collect();
                    let before = cols.len();
                    cols.dedup();
                    cols.sort();
                    cols.dedup();
                    assert_eq!(before, cols.len(), "double assignment in {a:?}");
                }
            }
        }
    }

    #[test]
    fn required_columns_are_always_assigned_and_impossible_entries_skipped() {
        let mut m = full_matrix(3, 3);
        m.set_required(1, true);
        let mut column = [0.0; 5];
        m.column(2, &mut column);
        column[0] = f64::NEG_INFINITY;
        m.set_column(2, &column[..3], false);
        let mut sink = Collect { children: vec![] };
        ExhaustiveChildren::new(u64::MAX).generate(&m, &mut sink).unwrap();
        assert!(!sink.children.is_empty());
        for (w, a) in &sink.children {
            assert!(a.contains(&1), "{a:?} leaves the required column");
            assert_ne!(a[0], 2);
            assert!(w.is_finite());
        }
        // Brute force count of the feasible children.
        let mut expected = 0;
        for a0 in [CLUTTER, 0, 1, 2] {
            for a1 in [CLUTTER, 0, 1, 2] {
                for a2 in [CLUTTER, 0, 1, 2] {
                    if m.score(&[a0, a1, a2]).is_finite() {
                        expected += 1;
                    }
                }
            }
        }
        assert_eq!(sink.children.len(), expected);
    }

    #[test]
    fn budget_stops_the_enumeration() {
        let m = full_matrix(4, 5);
        let mut sink = Collect { children: vec![] };
        let result = ExhaustiveChildren::new(100).generate(&m, &mut sink);
        assert_eq!(result, Err(GenerateError::BudgetExceeded { budget: 100 }));
        assert_eq!(sink.children.len(), 100);
    }
}
