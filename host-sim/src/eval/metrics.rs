//! Multi-object metrics for evaluating tracker estimates against truth.
//!
//! Conventions:
//! - Objects are points `[f64; D]` (planar `[x, y]`, or 3-D positions in km); the base distance is Euclidean.
//! - `c > 0` is the cut-off and `p >= 1` the order of GOSPA / OSPA; preconditions are `debug_assert!`ed.
//! - Empty sets are valid input everywhere and never panic.
//! - Assignments are optimal (Hungarian algorithm, O(n^3)) and deterministic: the same input always gives the
//!   same output, ties being broken towards the lowest column index.

use crate::peers::assignment::assign;
use std::collections::HashMap;

/// Minimum-cost assignment (Hungarian / Kuhn-Munkres, O(n^3)) for a rectangular cost matrix given as rows,
/// solved by the host's one solver ([`crate::peers::assignment::assign`]).
/// Returns for each row the column it is assigned to (None when rows > columns and the row is left out).
/// Every column is used at most once; the total cost is minimal. Costs are finite f64 (a NaN cost leaves
/// every row unassigned).
///
/// All rows must have the same length. When rows <= columns every row is assigned; otherwise every column is.
pub fn optimal_assignment(cost: &[Vec<f64>]) -> Vec<Option<usize>> {
    let rows = cost.len();
    let cols = cost.first().map_or(0, Vec::len);
    debug_assert!(cost.iter().all(|row| row.len() == cols), "cost matrix rows must have equal length");
    if rows == 0 || cols == 0 {
        return vec![None; rows];
    }
    if rows <= cols {
        return match assign(rows, cols, |r, c| Some(cost[r][c])) {
            Some(columns) => columns.into_iter().map(Some).collect(),
            None => vec![None; rows],
        };
    }
    // More rows than columns: solve the transposed problem (every column gets a row) and invert it.
    let mut row_to_column = vec![None; rows];
    for (column, row) in assign(cols, rows, |c, r| Some(cost[r][c])).unwrap_or_default().into_iter().enumerate() {
        row_to_column[row] = Some(column);
    }
    row_to_column
}

/// The Euclidean distance; `hypot` in the plane (the planar figures stay bit-identical), the root of the
/// sum of squares otherwise.
fn euclidean<const D: usize>(a: [f64; D], b: [f64; D]) -> f64 {
    if D == 2 {
        (a[0] - b[0]).hypot(a[1] - b[1])
    } else {
        a.iter().zip(&b).map(|(x, y)| (x - y) * (x - y)).sum::<f64>().sqrt()
    }
}

/// Cost matrix `min(d(x_i, y_j), c)^p` with rows `xs` and columns `ys`.
fn cut_off_cost_matrix<const D: usize>(xs: &[[f64; D]], ys: &[[f64; D]], c: f64, p: f64) -> Vec<Vec<f64>> {
    xs.iter().map(|&x| ys.iter().map(|&y| euclidean(x, y).min(c).powf(p)).collect()).collect()
}

/// GOSPA with alpha = 2 (Rahmathullah, Garcia-Fernandez, Svensson, 2017) between point sets, with
/// cut-off c > 0 and order p >= 1, Euclidean base distance.
/// d^p = min over assignments gamma of [ sum_{(i,j) in gamma} min(d(x_i,y_j), c)^p + c^p/2 (|X| - |gamma| + |Y| - |gamma|) ]
/// Pairs at distance >= c are counted as one missed and one false object (that is equivalent for alpha = 2).
#[derive(Debug, Clone, PartialEq)]
pub struct Gospa {
    /// The GOSPA distance d (the p-th root).
    pub distance: f64,
    /// sum over properly assigned pairs (distance < c) of d^p, before the p-th root.
    pub localisation: f64,
    /// Truth objects not assigned to an estimate within c.
    pub missed: usize,
    /// Estimates not assigned to a truth object within c.
    pub false_tracks: usize,
    /// For each truth index, the estimate index it is assigned to within c (None if missed).
    pub assignment: Vec<Option<usize>>,
}

/// Computes [`Gospa`] (alpha = 2) between `truth` and `estimates` with cut-off `c > 0` and order `p >= 1`.
///
/// Since an assigned pair at distance >= c costs c^p = c^p/2 + c^p/2, the minimum over partial assignments equals
/// the minimum over full assignments (min(|X|, |Y|) pairs) of the cut-off cost min(d, c)^p plus
/// c^p/2 (|X| + |Y| - 2 min(|X|, |Y|)); the optimal full assignment is then split into proper pairs (d < c)
/// and missed + false objects (d >= c).
pub fn gospa<const D: usize>(truth: &[[f64; D]], estimates: &[[f64; D]], c: f64, p: f64) -> Gospa {
    debug_assert!(c > 0.0, "GOSPA cut-off c must be positive");
    debug_assert!(p >= 1.0, "GOSPA order p must be at least 1");
    let full_assignment = optimal_assignment(&cut_off_cost_matrix(truth, estimates, c, p));

    let mut assignment = vec![None; truth.len()];
    let mut localisation = 0.0;
    let mut proper_pairs = 0;
    for (truth_index, estimate_index) in full_assignment.into_iter().enumerate() {
        let Some(estimate_index) = estimate_index else { continue };
        let distance = euclidean(truth[truth_index], estimates[estimate_index]);
        if distance < c {
            assignment[truth_index] = Some(estimate_index);
            localisation += distance.powf(p);
            proper_pairs += 1;
        }
    }
    let missed = truth.len() - proper_pairs;
    let false_tracks = estimates.len() - proper_pairs;
    // d^p = localisation + c^p/2 (missed + false).
    let cardinality_penalty = c.powf(p) / 2.0 * (missed + false_tracks) as f64;
    let distance = (localisation + cardinality_penalty).powf(1.0 / p);
    Gospa { distance, localisation, missed, false_tracks, assignment }
}

/// OSPA (Schuhmacher, Vo, Vo 2008) with cut-off c and order p: 0 when both sets are empty, c when exactly one
/// is empty; otherwise with m <= n the sizes of the smaller and larger set,
/// ( (1/n) ( min_pi sum_{i<=m} min(d(x_i, y_pi(i)), c)^p + c^p (n - m) ) )^(1/p).
pub fn ospa<const D: usize>(truth: &[[f64; D]], estimates: &[[f64; D]], c: f64, p: f64) -> f64 {
    debug_assert!(c > 0.0, "OSPA cut-off c must be positive");
    debug_assert!(p >= 1.0, "OSPA order p must be at least 1");
    let (smaller, larger) = if truth.len() <= estimates.len() { (truth, estimates) } else { (estimates, truth) };
    let (m, n) = (smaller.len(), larger.len());
    if n == 0 {
        return 0.0;
    }
    if m == 0 {
        return c;
    }
    let cost = cut_off_cost_matrix(smaller, larger, c, p);
    let assignment = optimal_assignment(&cost);
    // Every row of the smaller set is assigned since m <= n.
    let localisation: f64 = assignment.iter().enumerate().filter_map(|(i, j)| j.map(|j| cost[i][j])).sum();
    ((localisation + c.powf(p) * (n - m) as f64) / n as f64).powf(1.0 / p)
}

/// Absolute error of an expected cardinality: |expected - true_count|.
pub fn cardinality_error(true_count: usize, expected: f64) -> f64 {
    (expected - true_count as f64).abs()
}

/// Counts label switches over a run: for each truth object id, the label of the estimate assigned to it at
/// the last scan where it was assigned; a switch is counted when a truth object is assigned an estimate whose
/// label differs from its previous assigned label. Scans where a truth object is unassigned do not reset it.
#[derive(Debug, Clone, Default)]
pub struct LabelSwitches {
    last_label: HashMap<u64, u32>,
    total: usize,
}

impl LabelSwitches {
    /// Creates a counter with no history.
    pub fn new() -> Self {
        Self::default()
    }

    /// Records one scan's assignment: pairs (truth object id, estimate label). Returns the switches in this scan.
    ///
    /// Pairs are processed in order, so a truth id repeated within one scan is compared with its preceding pair.
    pub fn record(&mut self, pairs: &[(u64, u32)]) -> usize {
        let mut switches = 0;
        for &(truth_id, label) in pairs {
            if let Some(previous) = self.last_label.insert(truth_id, label)
                && previous != label
            {
                switches += 1;
            }
        }
        self.total += switches;
        switches
    }

    /// Total switches so far.
    pub fn total(&self) -> usize {
        self.total
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand_core::{Rng, SeedableRng};

    const EPS: f64 = 1e-9;

    fn assert_close(actual: f64, expected: f64) {
        assert!((actual - expected).abs() <= EPS * (1.0 + expected.abs()), "{actual} != {expected}");
    }

    /// Draws for property tests from rand_xoshiro's splitmix64.
    struct Draws(rand_xoshiro::SplitMix64);

    impl Draws {
        fn new(seed: u64) -> Self {
            Draws(rand_xoshiro::SplitMix64::seed_from_u64(seed))
        }

        fn next_u64(&mut self) -> u64 {
            self.0.next_u64()
        }

        /// Uniform in [0, n); n > 0.
        fn below(&mut self, n: usize) -> usize {
            (self.next_u64() % n as u64) as usize
        }

        /// Uniform in [0, 1).
        fn unit(&mut self) -> f64 {
            (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
        }

        fn points(&mut self, count: usize, span: f64) -> Vec<[f64; 2]> {
            (0..count).map(|_| [self.unit() * span, self.unit() * span]).collect()
        }
    }

    fn assignment_cost(cost: &[Vec<f64>], assignment: &[Option<usize>]) -> f64 {
        assignment.iter().enumerate().filter_map(|(i, j)| j.map(|j| cost[i][j])).sum()
    }

    /// Minimum over all injections of the smaller side into the larger side.
    fn brute_force_min_cost(cost: &[Vec<f64>]) -> f64 {
        fn search(cost: &[Vec<f64>], row: usize, used: &mut [bool]) -> f64 {
            if row == cost.len() {
                return 0.0;
            }
            let mut best = f64::INFINITY;
            for column in 0..used.len() {
                if !used[column] {
                    used[column] = true;
                    best = best.min(cost[row][column] + search(cost, row + 1, used));
                    used[column] = false;
                }
            }
            best
        }
        let rows = cost.len();
        let cols = cost.first().map_or(0, Vec::len);
        if rows == 0 || cols == 0 {
            return 0.0;
        }
        if rows <= cols {
            search(cost, 0, &mut vec![false; cols])
        } else {
            let transposed: Vec<Vec<f64>> = (0..cols).map(|c| (0..rows).map(|r| cost[r][c]).collect()).collect();
            search(&transposed, 0, &mut vec![false; rows])
        }
    }

    fn assert_valid_assignment(cost: &[Vec<f64>], assignment: &[Option<usize>]) {
        let rows = cost.len();
        let cols = cost.first().map_or(0, Vec::len);
        assert_eq!(assignment.len(), rows);
        let mut used = vec![false; cols];
        for &column in assignment.iter().flatten() {
            assert!(column < cols);
            assert!(!used[column], "column {column} used twice");
            used[column] = true;
        }
        assert_eq!(assignment.iter().flatten().count(), rows.min(cols));
    }

    /// The GOSPA objective for one given partial assignment (truth index -> estimate index).
    fn gospa_objective_power(
        truth: &[[f64; 2]],
        estimates: &[[f64; 2]],
        gamma: &[Option<usize>],
        c: f64,
        p: f64,
    ) -> f64 {
        let pairs: Vec<(usize, usize)> = gamma.iter().enumerate().filter_map(|(i, j)| j.map(|j| (i, j))).collect();
        let paired: f64 = pairs.iter().map(|&(i, j)| euclidean(truth[i], estimates[j]).min(c).powf(p)).sum();
        paired + c.powf(p) / 2.0 * (truth.len() + estimates.len() - 2 * pairs.len()) as f64
    }

    fn random_partial_assignment(rng: &mut Draws, rows: usize, cols: usize) -> Vec<Option<usize>> {
        let mut columns: Vec<usize> = (0..cols).collect();
        // Fisher-Yates shuffle, then keep each row's column with probability 1/2.
        for i in (1..columns.len()).rev() {
            columns.swap(i, rng.below(i + 1));
        }
        (0..rows).map(|i| if i < cols && rng.below(2) == 0 { Some(columns[i]) } else { None }).collect()
    }

    // ---------- optimal_assignment ----------

    #[test]
    fn gospa_in_three_dimensions_uses_the_3d_distance() {
        // |(3, 4, 12)| = 13: within c = 20 a proper pair, beyond c = 10 one miss and one false track.
        let g = gospa(&[[0.0, 0.0, 0.0]], &[[3.0, 4.0, 12.0]], 20.0, 2.0);
        assert_close(g.distance, 13.0);
        assert_eq!(g.assignment, vec![Some(0)]);
        let g = gospa(&[[0.0, 0.0, 0.0]], &[[3.0, 4.0, 12.0]], 10.0, 2.0);
        assert_close(g.distance, (2.0 * 100.0_f64 / 2.0).sqrt());
        assert_eq!((g.missed, g.false_tracks), (1, 1));
        // The third coordinate decides the assignment: in the plane both estimates would be equally near.
        let g = gospa(&[[0.0, 0.0, 1.0]], &[[0.0, 0.0, 5.0], [0.0, 0.0, 0.0]], 50.0, 1.0);
        assert_eq!(g.assignment, vec![Some(1)]);
    }

    #[test]
    fn assignment_of_empty_matrices() {
        assert!(optimal_assignment(&[]).is_empty());
        assert_eq!(optimal_assignment(&[vec![], vec![]]), vec![None, None]);
    }

    #[test]
    fn assignment_hand_computed() {
        // Rows pick columns 1, 0, 2: 1 + 2 + 2 = 5 is the unique minimum
        // (the diagonal costs 4 + 4 + 2 = 10, every other permutation is > 5).
        let cost = vec![vec![4.0, 1.0, 3.0], vec![2.0, 4.0, 5.0], vec![3.0, 2.0, 2.0]];
        assert_eq!(optimal_assignment(&cost), vec![Some(1), Some(0), Some(2)]);
        // 3 rows, 2 columns: column 0 -> row 2 (cost 0), column 1 -> row 0 (cost 1); row 1 left out. Total 1.
        let tall = vec![vec![5.0, 1.0], vec![4.0, 4.0], vec![0.0, 3.0]];
        assert_eq!(optimal_assignment(&tall), vec![Some(1), None, Some(0)]);
        // 1 row, 3 columns: the cheapest column 2.
        assert_eq!(optimal_assignment(&[vec![3.0, 2.0, -1.0]]), vec![Some(2)]);
    }

    #[test]
    fn assignment_matches_brute_force_on_random_matrices() {
        let mut rng = Draws::new(1);
        for trial in 0..3000 {
            let rows = rng.below(7);
            let cols = rng.below(7);
            // Alternate continuous costs with small integers (many ties and zeros) and negative values.
            let cost: Vec<Vec<f64>> = (0..rows)
                .map(|_| {
                    (0..cols)
                        .map(|_| match trial % 3 {
                            0 => rng.unit() * 100.0,
                            1 => rng.below(3) as f64,
                            _ => rng.below(7) as f64 - 3.0,
                        })
                        .collect()
                })
                .collect();
            let assignment = optimal_assignment(&cost);
            assert_valid_assignment(&cost, &assignment);
            assert_close(assignment_cost(&cost, &assignment), brute_force_min_cost(&cost));
            assert_eq!(assignment, optimal_assignment(&cost), "not deterministic");
        }
    }

    #[test]
    fn assignment_all_zero_and_constant_matrices() {
        for (rows, cols) in [(3, 3), (2, 5), (5, 2)] {
            for value in [0.0, 7.5] {
                let cost = vec![vec![value; cols]; rows];
                let assignment = optimal_assignment(&cost);
                assert_valid_assignment(&cost, &assignment);
                assert_close(assignment_cost(&cost, &assignment), value * rows.min(cols) as f64);
            }
        }
    }

    #[test]
    fn assignment_large_matrix_is_valid_and_beats_identity() {
        // Sanity check of the O(n^3) path on sizes brute force cannot reach.
        let mut rng = Draws::new(2);
        for (rows, cols) in [(150, 150), (120, 180), (180, 120)] {
            let cost: Vec<Vec<f64>> = (0..rows).map(|_| (0..cols).map(|_| rng.unit()).collect()).collect();
            let assignment = optimal_assignment(&cost);
            assert_valid_assignment(&cost, &assignment);
            let identity: f64 = (0..rows.min(cols)).map(|i| cost[i][i]).sum();
            assert!(assignment_cost(&cost, &assignment) <= identity);
        }
    }

    // ---------- GOSPA ----------

    #[test]
    fn gospa_of_empty_sets_is_zero() {
        let g = gospa::<2>(&[], &[], 10.0, 2.0);
        assert_eq!(g, Gospa { distance: 0.0, localisation: 0.0, missed: 0, false_tracks: 0, assignment: vec![] });
    }

    #[test]
    fn gospa_single_missed_object() {
        // d = (c^p / 2 * 1)^(1/p) = sqrt(10^2 / 2) = sqrt(50) = 7.0710678...
        let g = gospa(&[[3.0, 4.0]], &[], 10.0, 2.0);
        assert_close(g.distance, 50.0_f64.sqrt());
        assert_close(g.distance, 7.071_067_811_865_475);
        assert_eq!((g.missed, g.false_tracks), (1, 0));
        assert_eq!(g.assignment, vec![None]);
        assert_eq!(g.localisation, 0.0);
    }

    #[test]
    fn gospa_single_false_track() {
        // d = (c^p / 2)^(1/p) = 4 / 2 = 2 for c = 4, p = 1.
        let g = gospa(&[], &[[1.0, 1.0]], 4.0, 1.0);
        assert_close(g.distance, 2.0);
        assert_eq!((g.missed, g.false_tracks), (0, 1));
    }

    #[test]
    fn gospa_mixed_example() {
        // (0,0)-(1,0): d = 1 -> 1^2 = 1; (10,0)-(10,3): d = 3 -> 3^2 = 9; localisation = 10.
        // (50,50) is a false track: c^2 / 2 = 25 / 2. d = sqrt(10 + 12.5) = sqrt(22.5).
        let g = gospa(&[[0.0, 0.0], [10.0, 0.0]], &[[1.0, 0.0], [10.0, 3.0], [50.0, 50.0]], 5.0, 2.0);
        assert_close(g.localisation, 10.0);
        assert_close(g.distance, 22.5_f64.sqrt());
        assert_eq!((g.missed, g.false_tracks), (0, 1));
        assert_eq!(g.assignment, vec![Some(0), Some(1)]);
    }

    #[test]
    fn gospa_pair_beyond_cut_off_is_missed_and_false() {
        // d((0,0),(7,0)) = 7 >= c = 5: one missed + one false = 5/2 + 5/2 = 5 for p = 1.
        let g = gospa(&[[0.0, 0.0]], &[[7.0, 0.0]], 5.0, 1.0);
        assert_close(g.distance, 5.0);
        assert_eq!((g.missed, g.false_tracks), (1, 1));
        assert_eq!(g.assignment, vec![None]);
        assert_eq!(g.localisation, 0.0);
        // Exactly at the cut-off it is still missed + false (pairs need d < c).
        let at = gospa(&[[0.0, 0.0]], &[[3.0, 4.0]], 5.0, 1.0);
        assert_eq!((at.missed, at.false_tracks), (1, 1));
        assert_close(at.distance, 5.0);
    }

    #[test]
    fn gospa_order_one_example() {
        // p = 1, c = 3: truth (0,0),(5,0); estimate (0,2).
        // Pair (0,0)-(0,2): 2; (5,0) missed: 3/2. d = 3.5.
        let g = gospa(&[[0.0, 0.0], [5.0, 0.0]], &[[0.0, 2.0]], 3.0, 1.0);
        assert_close(g.distance, 3.5);
        assert_close(g.localisation, 2.0);
        assert_eq!((g.missed, g.false_tracks), (1, 0));
        assert_eq!(g.assignment, vec![Some(0), None]);
    }

    /// Minimum of the GOSPA objective over all partial assignments (for small sets).
    fn brute_force_gospa_power(truth: &[[f64; 2]], estimates: &[[f64; 2]], c: f64, p: f64) -> f64 {
        fn search(
            truth: &[[f64; 2]],
            estimates: &[[f64; 2]],
            c: f64,
            p: f64,
            gamma: &mut Vec<Option<usize>>,
            used: &mut [bool],
        ) -> f64 {
            if gamma.len() == truth.len() {
                return gospa_objective_power(truth, estimates, gamma, c, p);
            }
            gamma.push(None);
            let mut best = search(truth, estimates, c, p, gamma, used);
            gamma.pop();
            for j in 0..estimates.len() {
                if !used[j] {
                    used[j] = true;
                    gamma.push(Some(j));
                    best = best.min(search(truth, estimates, c, p, gamma, used));
                    gamma.pop();
                    used[j] = false;
                }
            }
            best
        }
        search(truth, estimates, c, p, &mut Vec::new(), &mut vec![false; estimates.len()])
    }

    fn random_case(rng: &mut Draws) -> (Vec<[f64; 2]>, Vec<[f64; 2]>, f64, f64) {
        let truth_count = rng.below(5);
        let estimate_count = rng.below(5);
        let truth = rng.points(truth_count, 20.0);
        let estimates = rng.points(estimate_count, 20.0);
        let c = 1.0 + rng.unit() * 15.0;
        let p = [1.0, 2.0, 3.0, 1.5][rng.below(4)];
        (truth, estimates, c, p)
    }

    #[test]
    fn gospa_matches_brute_force_and_is_consistent() {
        let mut rng = Draws::new(3);
        for _ in 0..2000 {
            let (truth, estimates, c, p) = random_case(&mut rng);
            let g = gospa(&truth, &estimates, c, p);
            assert_close(g.distance.powf(p), brute_force_gospa_power(&truth, &estimates, c, p));
            // The reported decomposition reproduces d^p and uses only proper pairs.
            let pairs = g.assignment.iter().flatten().count();
            assert_eq!(g.missed, truth.len() - pairs);
            assert_eq!(g.false_tracks, estimates.len() - pairs);
            let mut localisation = 0.0;
            for (i, j) in g.assignment.iter().enumerate() {
                if let Some(j) = *j {
                    let d = euclidean(truth[i], estimates[j]);
                    assert!(d < c);
                    localisation += d.powf(p);
                }
            }
            assert_close(g.localisation, localisation);
            assert_close(g.distance.powf(p), gospa_objective_power(&truth, &estimates, &g.assignment, c, p));
        }
    }

    #[test]
    fn gospa_is_symmetric() {
        let mut rng = Draws::new(4);
        for _ in 0..2000 {
            let (truth, estimates, c, p) = random_case(&mut rng);
            let forward = gospa(&truth, &estimates, c, p);
            let backward = gospa(&estimates, &truth, c, p);
            assert_close(forward.distance, backward.distance);
            assert_eq!(forward.missed, backward.false_tracks);
            assert_eq!(forward.false_tracks, backward.missed);
        }
    }

    #[test]
    fn gospa_is_not_above_any_other_assignment() {
        let mut rng = Draws::new(5);
        for _ in 0..2000 {
            let truth_count = rng.below(8);
            let estimate_count = rng.below(8);
            let truth = rng.points(truth_count, 20.0);
            let estimates = rng.points(estimate_count, 20.0);
            let (c, p) = (1.0 + rng.unit() * 15.0, 1.0 + rng.unit() * 2.0);
            let optimum = gospa(&truth, &estimates, c, p).distance.powf(p);
            for _ in 0..5 {
                let gamma = random_partial_assignment(&mut rng, truth_count, estimate_count);
                assert!(optimum <= gospa_objective_power(&truth, &estimates, &gamma, c, p) + EPS);
            }
        }
    }

    #[test]
    fn gospa_of_a_set_with_itself_is_zero() {
        let mut rng = Draws::new(6);
        for _ in 0..500 {
            let count = rng.below(10);
            let points = rng.points(count, 50.0);
            let g = gospa(&points, &points, 2.0, 2.0);
            assert_eq!(g.distance, 0.0);
            assert_eq!((g.missed, g.false_tracks), (0, 0));
            assert_eq!(g.assignment.iter().flatten().count(), count);
        }
    }

    #[test]
    fn gospa_satisfies_triangle_inequality() {
        let mut rng = Draws::new(7);
        for _ in 0..3000 {
            let sets: Vec<Vec<[f64; 2]>> = (0..3)
                .map(|_| {
                    let count = rng.below(5);
                    rng.points(count, 10.0)
                })
                .collect();
            let (c, p) = (0.5 + rng.unit() * 8.0, [1.0, 2.0, 3.0][rng.below(3)]);
            let d = |a: usize, b: usize| gospa(&sets[a], &sets[b], c, p).distance;
            assert!(d(0, 2) <= d(0, 1) + d(1, 2) + EPS);
            assert!(d(0, 1) <= d(0, 2) + d(2, 1) + EPS);
            assert!(d(1, 2) <= d(1, 0) + d(0, 2) + EPS);
        }
    }

    // ---------- OSPA ----------

    #[test]
    fn ospa_empty_cases() {
        assert_eq!(ospa::<2>(&[], &[], 10.0, 2.0), 0.0);
        assert_eq!(ospa(&[[1.0, 2.0]], &[], 10.0, 2.0), 10.0);
        assert_eq!(ospa(&[], &[[1.0, 2.0], [3.0, 4.0]], 7.0, 1.0), 7.0);
    }

    #[test]
    fn ospa_hand_computed() {
        // m = 1, n = 2: (0,0)-(0,0) costs 0, one cardinality penalty c = 10: (1/2)(0 + 10) = 5.
        assert_close(ospa(&[[0.0, 0.0], [3.0, 4.0]], &[[0.0, 0.0]], 10.0, 1.0), 5.0);
        // p = 2, c = 10: pairs (0,0)-(3,4) d = 5 and (10,0)-(10,1) d = 1: sqrt((25 + 1) / 2) = sqrt(13).
        assert_close(ospa(&[[0.0, 0.0], [10.0, 0.0]], &[[10.0, 1.0], [3.0, 4.0]], 10.0, 2.0), 13.0_f64.sqrt());
        // Distance capped at c: d = 7 > c = 5, so ospa = min(7, 5) = 5.
        assert_close(ospa(&[[0.0, 0.0]], &[[7.0, 0.0]], 5.0, 1.0), 5.0);
    }

    #[test]
    fn ospa_is_symmetric_and_bounded() {
        let mut rng = Draws::new(8);
        for _ in 0..2000 {
            let (truth, estimates, c, p) = random_case(&mut rng);
            let forward = ospa(&truth, &estimates, c, p);
            assert_close(forward, ospa(&estimates, &truth, c, p));
            assert!((0.0..=c + EPS).contains(&forward));
            assert_eq!(ospa(&truth, &truth, c, p), 0.0);
        }
    }

    // ---------- cardinality error ----------

    #[test]
    fn cardinality_error_is_absolute_difference() {
        assert_eq!(cardinality_error(3, 2.5), 0.5);
        assert_eq!(cardinality_error(0, 1.25), 1.25);
        assert_eq!(cardinality_error(4, 4.0), 0.0);
    }

    // ---------- label switches ----------

    #[test]
    fn label_switches_single_object() {
        // Object 7 gets labels 1, 1, (unassigned), 1, 2, 2: only 1 -> 2 is a switch.
        let mut switches = LabelSwitches::new();
        let per_scan: Vec<usize> = [&[(7, 1)][..], &[(7, 1)], &[], &[(7, 1)], &[(7, 2)], &[(7, 2)]]
            .iter()
            .map(|s| switches.record(s))
            .collect();
        assert_eq!(per_scan, vec![0, 0, 0, 0, 1, 0]);
        assert_eq!(switches.total(), 1);
    }

    #[test]
    fn label_switches_two_objects_swapping() {
        // Scan 1: 1 -> label 10, 2 -> label 20; scan 2: swapped, both change: 2 switches.
        let mut switches = LabelSwitches::new();
        assert_eq!(switches.record(&[(1, 10), (2, 20)]), 0);
        assert_eq!(switches.record(&[(1, 20), (2, 10)]), 2);
        assert_eq!(switches.total(), 2);
    }

    #[test]
    fn label_switches_gap_does_not_reset() {
        // Object 3: label 5, unassigned, label 6 -> compared with 5: 1 switch; a new object never switches.
        let mut switches = LabelSwitches::default();
        assert_eq!(switches.record(&[(3, 5)]), 0);
        assert_eq!(switches.record(&[(4, 9)]), 0);
        assert_eq!(switches.record(&[(3, 6), (8, 5)]), 1);
        assert_eq!(switches.total(), 1);
    }
}
