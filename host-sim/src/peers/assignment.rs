//! The host's one rectangular assignment solver, used by the metrics (GOSPA / OSPA pairings) and by
//! Murty's k-best associations.
//!
//! Minimum-cost assignment of every row of a `rows × columns` table, `rows <= columns`, each column at
//! most once, some pairs possibly absent: the shortest-augmenting-path Hungarian algorithm with dual
//! potentials (Kuhn–Munkres in the form of Jonker and Volgenant, without their initialisation
//! heuristics). Each of the `rows` phases grows one augmenting path by a Dijkstra search over reduced
//! costs in O(rows × columns), so O(rows² columns) overall. Deterministic: ties go to the lowest column.
//!
//! tracker-core's [`best_association`](tracker_core::optimal::best_association) solves a related problem
//! (clutter as one column of unlimited capacity, on a capacity-bounded `AssociationMatrix`); it has no
//! absent pairs or forced rows (Murty's subproblems), no lexicographic costs and no unbounded sizes
//! (GOSPA's point sets), so the host keeps this one.

use std::ops::{Add, Sub};

/// A cost the solver can minimise: an ordered group with an infinity ("not reached yet").
pub trait AssignmentCost: Copy + PartialOrd + Add<Output = Self> + Sub<Output = Self> {
    /// The neutral cost.
    const ZERO: Self;
    /// Larger than every finite cost.
    const INFINITE: Self;
    /// Whether this cost is not finite (a column not reached by the search).
    fn is_infinite(self) -> bool;
}

impl AssignmentCost for f64 {
    const ZERO: f64 = 0.0;
    const INFINITE: f64 = f64::INFINITY;

    fn is_infinite(self) -> bool {
        self == f64::INFINITY
    }
}

/// The minimum-cost assignment of every row to its own column; `cost(row, column)` is `None` where the
/// pair is not allowed. Returns the column of each row, or `None` when no assignment covers every row
/// (or a cost is NaN, which leaves a row unreachable).
///
/// Internally 1-based, with column 0 a virtual column holding the row being inserted.
pub fn assign<C: AssignmentCost>(
    rows: usize,
    columns: usize,
    cost: impl Fn(usize, usize) -> Option<C>,
) -> Option<Vec<usize>> {
    debug_assert!(rows <= columns);
    let mut row_potential = vec![C::ZERO; rows + 1];
    let mut column_potential = vec![C::ZERO; columns + 1];
    // row_of_column[j]: 1-based row matched to column j (0 = free).
    let mut row_of_column = vec![0usize; columns + 1];
    // previous[j]: predecessor of column j on the current alternating path.
    let mut previous = vec![0usize; columns + 1];
    let mut slack = vec![C::INFINITE; columns + 1];
    let mut visited = vec![false; columns + 1];
    for row in 1..=rows {
        row_of_column[0] = row;
        let mut column = 0usize;
        slack.fill(C::INFINITE);
        visited.fill(false);
        loop {
            visited[column] = true;
            let current = row_of_column[column];
            let mut delta = C::INFINITE;
            let mut next = 0usize;
            for j in 1..=columns {
                if visited[j] {
                    continue;
                }
                if let Some(c) = cost(current - 1, j - 1) {
                    // Reduced cost: cost(i, j) − u_i − v_j.
                    let reduced = c - row_potential[current] - column_potential[j];
                    if reduced < slack[j] {
                        slack[j] = reduced;
                        previous[j] = column;
                    }
                }
                // Strict `<` keeps the lowest column on ties.
                if !slack[j].is_infinite() && (next == 0 || slack[j] < delta) {
                    delta = slack[j];
                    next = j;
                }
            }
            if next == 0 {
                return None; // no augmenting path: this row cannot be covered
            }
            // Dual update: keeps reduced costs non-negative and makes `next`'s edge tight.
            for j in 0..=columns {
                if visited[j] {
                    row_potential[row_of_column[j]] = row_potential[row_of_column[j]] + delta;
                    column_potential[j] = column_potential[j] - delta;
                } else if !slack[j].is_infinite() {
                    slack[j] = slack[j] - delta;
                }
            }
            column = next;
            if row_of_column[column] == 0 {
                break;
            }
        }
        // Augment: flip the alternating path back to the virtual column 0.
        while column != 0 {
            let back = previous[column];
            row_of_column[column] = row_of_column[back];
            column = back;
        }
    }
    let mut assignment = vec![0usize; rows];
    for (column, &row) in row_of_column.iter().enumerate().skip(1) {
        if row != 0 {
            assignment[row - 1] = column - 1;
        }
    }
    Some(assignment)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand_core::{Rng, SeedableRng};
    use rand_xoshiro::SplitMix64;

    /// Minimum total over every injection of the rows into the columns (`None`: no allowed one).
    fn brute_force(rows: usize, columns: usize, cost: &[Option<f64>]) -> Option<f64> {
        fn search(row: usize, rows: usize, columns: usize, cost: &[Option<f64>], used: &mut [bool]) -> Option<f64> {
            if row == rows {
                return Some(0.0);
            }
            let mut best: Option<f64> = None;
            for column in 0..columns {
                if let (false, Some(c)) = (used[column], cost[row * columns + column]) {
                    used[column] = true;
                    if let Some(rest) = search(row + 1, rows, columns, cost, used) {
                        best = Some(best.map_or(c + rest, |b| b.min(c + rest)));
                    }
                    used[column] = false;
                }
            }
            best
        }
        search(0, rows, columns, cost, &mut vec![false; columns])
    }

    #[test]
    fn assign_matches_brute_force_on_random_tables_with_absent_pairs() {
        let mut rng = SplitMix64::seed_from_u64(2026);
        let mut unit = move || (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        for case in 0..400 {
            let rows = (unit() * 6.0) as usize;
            let columns = rows + (unit() * 4.0) as usize;
            let absent = if case % 3 == 0 { 0.0 } else { 0.35 };
            // Integer-valued costs make ties common; the others are continuous.
            let cost: Vec<Option<f64>> = (0..rows * columns)
                .map(|_| {
                    let value = if case % 2 == 0 { (unit() * 5.0).floor() } else { 20.0 * unit() - 10.0 };
                    (unit() >= absent).then_some(value)
                })
                .collect();
            let expected = brute_force(rows, columns, &cost);
            let got = assign(rows, columns, |r, c| cost[r * columns + c]);
            match (got, expected) {
                (None, None) => {}
                (Some(assignment), Some(best)) => {
                    let mut used = vec![false; columns];
                    let mut total = 0.0;
                    for (row, &column) in assignment.iter().enumerate() {
                        assert!(!used[column], "case {case}: column {column} twice");
                        used[column] = true;
                        total += cost[row * columns + column].expect("an allowed pair");
                    }
                    assert!((total - best).abs() <= 1e-9 * (1.0 + best.abs()), "case {case}: {total} vs {best}");
                }
                (got, expected) => panic!("case {case}: solver {got:?}, brute force {expected:?}"),
            }
        }
    }

    #[test]
    fn splitmix_from_rand_xoshiro_is_the_classic_sequence() {
        // The first output of the reference splitmix64 (Vigna) seeded with 0.
        assert_eq!(SplitMix64::seed_from_u64(0).next_u64(), 0xe220_a839_7b1d_cdaf);
    }
}
