//! The best association of one matrix, exactly: the start of every Metropolis chain.
//!
//! Maximises the chain's own target over association vectors: Σ δ_{z,a(z)} (clutter 0) plus a bonus per
//! required column taken (the sampler's [`REQUIRED_PENALTY`](crate::sampler::REQUIRED_PENALTY)), so
//! that the chain starts at the mode of its target instead of at a greedy local optimum. It is a
//! rectangular linear assignment problem: rows are measurements; columns are the matrix's columns, each
//! taken at most once, and clutter, which any number of rows may take (cost 0).
//!
//! Solved by the shortest augmenting path method with row and column potentials (Kuhn–Munkres in the
//! form of Jonker and Volgenant): rows are added one at a time, each by a Dijkstra search over reduced
//! costs that stops at the first free column or at clutter. Clutter is one column of unlimited capacity
//! with potential 0: it is always free, so reaching it ends a search, and no search passes through it
//! (every held edge has reduced cost 0 and every other one at least 0, which is what makes the result
//! optimal). Row `r` visits at most min(r, M) + 1 columns, each visit scans the M matrix columns once:
//! at most R (M + 1) M reduced costs for R rows, with no allocation and no transcendental function. On a
//! gated matrix the sparse search does the same with each visit limited to the visited row's possible
//! columns and the columns reached so far (docs/maths.md §7.4).

use crate::association::{AssociationMatrix, CLUTTER};
use crate::index::{At, below};
use crate::real::Real;

const NONE: usize = usize::MAX;
/// The search root in predecessor links: the row being added.
const ROOT: usize = usize::MAX - 1;

/// Writes into `assignment[..rows]` an association vector that maximises Σ δ + `required_bonus` ×
/// (required columns taken) over `matrix`, and returns whether it succeeded. It fails only when the
/// search meets no finite reduced cost, which needs a NaN entry; `assignment` is then unspecified.
///
/// # Examples
/// ```
/// # use tracker_core::association::{AssociationMatrix, CLUTTER};
/// # // 3 measurements × 3 objects; the best child takes the diagonal: −5 + 2 + 3 + 0.2.
/// # let mut matrix = AssociationMatrix::<f64, 3, 3>::new(3, 3, -5.0);
/// # matrix.set_column(0, &[2.0, 0.5, -1.0], false);
/// # matrix.set_column(1, &[1.5, 3.0, f64::NEG_INFINITY], false);
/// # matrix.set_column(2, &[f64::NEG_INFINITY, 1.0, 0.2], false);
/// use tracker_core::optimal::best_association;
/// let mut assignment = [CLUTTER; 3];
/// assert!(best_association(&matrix, 0.0, &mut assignment));
/// assert_eq!(assignment, [0, 1, 2]);
///
/// // A required column is taken even at a loss, given a large enough bonus.
/// let mut required = AssociationMatrix::<f64, 1, 1>::new(1, 1, 0.0);
/// required.set_column(0, &[-3.0], true);
/// let mut one = [CLUTTER; 1];
/// assert!(best_association(&required, 0.0, &mut one) && one == [CLUTTER]);
/// assert!(best_association(&required, 64.0, &mut one) && one == [0]);
/// ```
pub fn best_association<T: Real, const N: usize, const Z: usize>(
    matrix: &AssociationMatrix<T, N, Z>,
    required_bonus: T,
    assignment: &mut [u16; Z],
) -> bool {
    let (rows, columns) = (matrix.rows().min(Z), matrix.columns().min(N));
    let mut search = Search::<T, N, Z>::new();
    for row in 0..rows {
        if !search.add_row_dense(matrix, required_bonus, row, columns) {
            return false;
        }
    }
    search.write(assignment, rows, columns);
    true
}

/// [`best_association`] for a gated matrix, given each row's possible columns (finite δ) in increasing
/// order: `possible(row)` must yield exactly the columns `c` with `matrix.entry(row, c) > −∞`. Its searches
/// visit only the columns that the rows they reach can take, so a row costs its reach rather than all the
/// matrix's columns; the result is [`best_association`]'s, bit for bit (the same arithmetic on the same
/// columns, and ties broken the same way). On a dense matrix the plain method is the cheaper of the two.
pub(crate) fn best_association_sparse<T: Real, const N: usize, const Z: usize, I: Iterator<Item = u16>>(
    matrix: &AssociationMatrix<T, N, Z>,
    required_bonus: T,
    assignment: &mut [u16; Z],
    possible: impl Fn(usize) -> I,
) -> bool {
    let (rows, columns) = (matrix.rows().min(Z), matrix.columns().min(N));
    let mut search = Search::<T, N, Z>::new();
    for row in 0..rows {
        if !search.add_row_sparse(matrix, required_bonus, row, columns, &possible) {
            return false;
        }
    }
    search.write(assignment, rows, columns);
    true
}

/// Cost of `row` taking the possible `column` (minimised): −δ − bonus for a required column, −δ otherwise.
#[inline(always)]
fn cost<T: Real, const N: usize, const Z: usize>(
    matrix: &AssociationMatrix<T, N, Z>,
    required_bonus: T,
    row: usize,
    column: usize,
) -> T {
    let entry = matrix.entry(row, column);
    if matrix.is_required(column) { -(entry + required_bonus) } else { -entry }
}

/// The solver's state: potentials, the column holders, and the current search's labels.
struct Search<T, const N: usize, const Z: usize> {
    row_potential: [T; Z],
    column_potential: [T; N],
    /// The row holding each column (NONE: free).
    holder: [usize; N],
    /// Each reached column's predecessor on the shortest path tree (a column, or ROOT).
    predecessor: [usize; N],
    slack: [T; N],
    visited: [bool; N],
    /// The sparse search's reached columns (finite slack), in the order reached, and the least slack of
    /// the unvisited ones with its column.
    reached: [u16; N],
    reached_count: usize,
    least: Option<(T, usize)>,
}

/// Where a search ended: a free column, or clutter (`None`), with clutter's predecessor.
type End = (Option<usize>, usize);

impl<T: Real, const N: usize, const Z: usize> Search<T, N, Z> {
    fn new() -> Self {
        Self {
            row_potential: [T::ZERO; Z],
            column_potential: [T::ZERO; N],
            holder: [NONE; N],
            predecessor: [ROOT; N],
            slack: [T::INFINITY; N],
            visited: [false; N],
            reached: [0; N],
            reached_count: 0,
            least: None,
        }
    }

    /// Adds `row` by a Dijkstra search over reduced costs that ends at the first free column or at clutter,
    /// then augments; returns `false` if the search met no finite reduced cost. The two searches differ only
    /// in which columns they look at: `visit(search, tree_row, base, current)` lowers the slacks of the
    /// columns `tree_row` (of potential `base`) can take, reached through `current`, and returns the least
    /// slack of the unvisited columns with its column (the lowest of equal ones), if any;
    /// `fall(search, delta, next)` moves the potentials of the visited columns and the slacks of the others
    /// by `delta` once the search has chosen `next`.
    #[inline(always)]
    fn add_row(
        &mut self,
        row: usize,
        columns: usize,
        mut visit: impl FnMut(&mut Self, usize, T, usize) -> Option<(T, usize)>,
        mut fall: impl FnMut(&mut Self, T, Option<usize>),
    ) -> bool {
        let (mut clutter_slack, mut clutter_predecessor) = (T::INFINITY, ROOT);
        let mut current = ROOT;
        for _ in 0..=columns {
            let tree_row = if current == ROOT { row } else { *self.holder.at(current) };
            let base = *self.row_potential.at(tree_row);
            if -base < clutter_slack {
                clutter_slack = -base;
                clutter_predecessor = current;
            }
            // Ties go to clutter, which ends the search soonest.
            let (delta, next) = match visit(self, tree_row, base, current) {
                Some((least, column)) if least < clutter_slack => (least, Some(column)),
                _ => (clutter_slack, None),
            };
            if !(delta < T::INFINITY) {
                return false;
            }
            *self.row_potential.at_mut(row) += delta;
            fall(self, delta, next);
            clutter_slack -= delta;
            match next {
                Some(column) if *self.holder.at(column) != NONE => {
                    *self.visited.at_mut(column) = true;
                    current = column;
                }
                end => {
                    self.augment(row, columns, (end, clutter_predecessor));
                    return true;
                }
            }
        }
        false
    }

    /// [`Search::add_row`] scanning every column at every visit (∞ cost where impossible).
    fn add_row_dense(
        &mut self,
        matrix: &AssociationMatrix<T, N, Z>,
        required_bonus: T,
        row: usize,
        columns: usize,
    ) -> bool {
        self.slack[..columns].fill(T::INFINITY);
        self.visited[..columns].fill(false);
        let visit = |search: &mut Self, tree_row: usize, base: T, current: usize| {
            let Self { column_potential, predecessor, slack, visited, .. } = search;
            let (mut least, mut at) = (T::INFINITY, None);
            for column in 0..columns {
                if visited[column] {
                    continue;
                }
                let entry = matrix.entry(tree_row, column);
                let cost =
                    if entry > T::NEG_INFINITY { cost(matrix, required_bonus, tree_row, column) } else { T::INFINITY };
                let reduced = cost - base - column_potential[column];
                if reduced < slack[column] {
                    slack[column] = reduced;
                    predecessor[column] = current;
                }
                if slack[column] < least {
                    least = slack[column];
                    at = Some(column);
                }
            }
            at.map(|column| (least, column))
        };
        let fall = |search: &mut Self, delta: T, _: Option<usize>| {
            let Self { row_potential, column_potential, holder, slack, visited, .. } = search;
            for column in 0..columns {
                if visited[column] {
                    *row_potential.at_mut(holder[column]) += delta;
                    column_potential[column] -= delta;
                } else {
                    slack[column] -= delta;
                }
            }
        };
        self.add_row(row, columns, visit, fall)
    }

    /// [`Search::add_row`] over the reached columns only (those a reached row can take; the others' slack is
    /// ∞ and stays ∞), deciding as [`Search::add_row_dense`] does, bit for bit.
    fn add_row_sparse<I: Iterator<Item = u16>>(
        &mut self,
        matrix: &AssociationMatrix<T, N, Z>,
        required_bonus: T,
        row: usize,
        columns: usize,
        possible: &impl Fn(usize) -> I,
    ) -> bool {
        for &column in &self.reached[..self.reached_count.min(N)] {
            if let Some(column) = below::<N>(column) {
                self.slack[column] = T::INFINITY;
                self.visited[column] = false;
            }
        }
        self.reached_count = 0;
        self.least = None;
        // The least slack of the unvisited reached columns and its column, the lowest of equal ones (the
        // dense search's first in column order), kept up to date as slacks fall.
        let lower = |least: Option<(T, usize)>, value: T, index: usize| match least {
            Some((best, at)) if !(value < best || (value == best && index < at)) => least,
            _ => Some((value, index)),
        };
        let visit = |search: &mut Self, tree_row: usize, base: T, current: usize| {
            let Self { column_potential, predecessor, slack, visited, reached, reached_count, least, .. } = search;
            for column in possible(tree_row) {
                let Some(index) = below::<N>(column) else { continue };
                if visited[index] {
                    continue;
                }
                let reduced = cost(matrix, required_bonus, tree_row, index) - base - column_potential[index];
                if reduced < slack[index] {
                    if slack[index] == T::INFINITY {
                        *reached.at_mut(*reached_count) = column;
                        *reached_count += 1;
                    }
                    slack[index] = reduced;
                    predecessor[index] = current;
                    *least = lower(*least, reduced, index);
                }
            }
            *least
        };
        // Every unvisited slack falls by delta; the least of them, but for `next`, leads the next visit.
        let fall = |search: &mut Self, delta: T, next: Option<usize>| {
            let Self { row_potential, column_potential, holder, slack, visited, reached, reached_count, least, .. } =
                search;
            *least = None;
            for &column in &reached[..(*reached_count).min(N)] {
                let Some(index) = below::<N>(column) else { continue };
                if visited[index] {
                    *row_potential.at_mut(holder[index]) += delta;
                    column_potential[index] -= delta;
                } else {
                    slack[index] -= delta;
                    if Some(index) != next {
                        *least = lower(*least, slack[index], index);
                    }
                }
            }
        };
        self.add_row(row, columns, visit, fall)
    }

    /// Augments along the search's path: each column on it passes to the row that reached it; the row at
    /// the clutter end (if any) is left holding no column, which is clutter.
    fn augment(&mut self, row: usize, columns: usize, (end, clutter_predecessor): End) {
        let (mut column, mut previous) = match end {
            Some(column) => (column, *self.predecessor.at(column)),
            None => (NONE, clutter_predecessor),
        };
        for _ in 0..=columns {
            if column != NONE {
                *self.holder.at_mut(column) = if previous == ROOT { row } else { *self.holder.at(previous) };
            }
            if previous == ROOT {
                break;
            }
            column = previous;
            previous = *self.predecessor.at(column);
        }
    }

    /// Writes the association of the rows added: each row its held column, or clutter.
    fn write(&self, assignment: &mut [u16; Z], rows: usize, columns: usize) {
        assignment[..rows].fill(CLUTTER);
        for (column, &row) in self.holder.iter().enumerate().take(columns) {
            if let Some(row) = assignment.get_mut(row) {
                *row = column as u16;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::children::{ChildGenerator, ChildSink, ExhaustiveChildren};
    use rand_core::Rng;

    /// The best child by exhaustive enumeration.
    struct Best(f64);
    impl ChildSink<f64> for Best {
        fn offer(&mut self, weight: f64, _: &[u16]) {
            self.0 = self.0.max(weight);
        }
    }

    #[test]
    fn finds_the_exhaustive_maximum_on_random_matrices() {
        let mut stream = crate::random::test_stream(11);
        for case in 0..2_000u32 {
            let rows = 1 + (stream.next_u64() % 6) as usize;
            let columns = (stream.next_u64() % 7) as usize;
            let mut matrix = AssociationMatrix::<f64, 6, 6>::new(rows, columns, 0.0);
            for column in 0..columns {
                let entries: [f64; 6] = core::array::from_fn(|_| {
                    let draw = stream.next_u64();
                    if draw.is_multiple_of(3) {
                        f64::NEG_INFINITY
                    } else if case.is_multiple_of(2) {
                        (draw >> 11) as f64 / (1u64 << 53) as f64 * 8.0 - 4.0
                    } else {
                        ((draw >> 11) % 5) as f64 - 2.0 // many ties
                    }
                });
                matrix.set_column(column, &entries[..rows], case % 4 == 0 && column == 0);
            }
            let mut exhaustive = Best(f64::NEG_INFINITY);
            ExhaustiveChildren::new(u64::MAX).generate(&matrix, &mut exhaustive).unwrap();
            let mut assignment = [CLUTTER; 6];
            assert!(best_association(&matrix, 64.0, &mut assignment));
            let found = matrix.score(&assignment[..rows]);
            if exhaustive.0 == f64::NEG_INFINITY {
                // No feasible child: the required column cannot be taken.
                assert_eq!(found, f64::NEG_INFINITY, "case {case}");
            } else {
                assert!((found - exhaustive.0).abs() < 1e-12, "case {case}: {found} vs {}", exhaustive.0);
            }
        }
    }

    #[test]
    fn the_sparse_search_gives_the_dense_association_bit_for_bit() {
        let mut stream = crate::random::test_stream(12);
        for case in 0..3_000u32 {
            let rows = 1 + (stream.next_u64() % 8) as usize;
            let columns = (stream.next_u64() % 9) as usize;
            // From dense to one possible entry in four; real entries, or integers with many ties.
            let impossible = stream.next_u64() % 4;
            let mut matrix = AssociationMatrix::<f64, 8, 8>::new(rows, columns, 0.0);
            for column in 0..columns {
                let entries: [f64; 8] = core::array::from_fn(|_| {
                    let draw = stream.next_u64();
                    if draw % 4 < impossible {
                        f64::NEG_INFINITY
                    } else if case.is_multiple_of(2) {
                        (draw >> 11) as f64 / (1u64 << 53) as f64 * 8.0 - 4.0
                    } else {
                        ((draw >> 11) % 5) as f64 - 2.0
                    }
                });
                matrix.set_column(column, &entries[..rows], case % 3 == 0 && column < 2);
            }
            let mut dense = [CLUTTER; 8];
            let dense_found = best_association(&matrix, 64.0, &mut dense);
            let mut sparse = [CLUTTER; 8];
            let matrix = &matrix;
            let possible =
                |row: usize| (0..columns as u16).filter(move |&c| matrix.entry(row, c.into()) > f64::NEG_INFINITY);
            let sparse_found = best_association_sparse(matrix, 64.0, &mut sparse, possible);
            assert_eq!((sparse_found, &sparse[..rows]), (dense_found, &dense[..rows]), "case {case}");
        }
    }

    #[test]
    fn beats_the_greedy_choice() {
        // Greedy takes (0, 0) = 5 and leaves row 1 in clutter (total 5); the optimum swaps (9.7).
        let mut matrix = AssociationMatrix::<f64, 2, 2>::new(2, 2, 0.0);
        matrix.set_column(0, &[5.0, 4.8], false);
        matrix.set_column(1, &[4.9, f64::NEG_INFINITY], false);
        let mut assignment = [CLUTTER; 2];
        assert!(best_association(&matrix, 64.0, &mut assignment));
        assert_eq!(assignment, [1, 0]);
    }

    #[test]
    fn takes_a_required_column_at_a_loss() {
        // Row 0 prefers clutter to column 0 (−3 < 0), but column 0 is required.
        let mut matrix = AssociationMatrix::<f64, 1, 2>::new(2, 1, 0.0);
        matrix.set_column(0, &[-3.0, -5.0], true);
        let mut assignment = [CLUTTER; 2];
        assert!(best_association(&matrix, 64.0, &mut assignment));
        assert_eq!(assignment, [0, CLUTTER]);
    }

    #[test]
    fn a_nan_entry_is_reported_not_hidden() {
        let mut matrix = AssociationMatrix::<f64, 2, 2>::new(2, 2, 0.0);
        matrix.set_column(0, &[f64::NAN, f64::NAN], false);
        matrix.set_column(1, &[f64::NAN, f64::NAN], false);
        let mut assignment = [CLUTTER; 2];
        // NaN costs are never below a slack, so only the clutter columns are reachable: still a valid
        // (all-clutter) answer, or a failure; never a panic or an out-of-range index.
        if best_association(&matrix, 64.0, &mut assignment) {
            assert!(assignment.iter().all(|&c| c == CLUTTER || (c as usize) < 2));
        }
    }
}
