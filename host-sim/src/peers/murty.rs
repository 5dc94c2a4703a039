//! Murty's k-best associations of one association matrix (host only): the deterministic alternative to
//! R-FISST's Metropolis sampler, for comparisons (`host-sim perf`).
//!
//! An association assigns each row (measurement) of an [`AssociationMatrix`] one column (object) or
//! clutter, no column twice, every required column assigned; its log-weight is the baseline plus the sum
//! of its entries (clutter adds 0). Finding the best one is a rectangular assignment problem over the
//! augmented columns: the matrix's columns, then one **private clutter column per row** (row j's clutter
//! column is open to row j only, at cost 0), so clutter is reusable by every row and each association is
//! exactly one assignment of the augmented problem.
//!
//! - **Costs** are lexicographic pairs (−[required column], −δ): minimising them first assigns every
//!   required column it can, then maximises the log-weight. So every feasible association (all required
//!   columns assigned) ranks before every infeasible one, with no big-M constant and no rounding; the
//!   enumeration stops at the first infeasible one.
//! - **Solver**: the host's one assignment solver ([`crate::peers::assignment::assign`]: shortest augmenting
//!   paths with dual potentials), O(r² c) for r free rows and c open columns; impossible
//!   (`-inf`) entries, forbidden pairs and columns taken by forced rows are absent edges, and a row with no
//!   augmenting path proves the subproblem infeasible.
//! - **Murty's partition**: the best association of a subproblem (forced pairs F, forbidden pairs X) is
//!   reported; its free rows r₁..r_t (in row order) then spawn t subproblems: the i-th forces
//!   r₁..r_{i−1} to their columns in the solution and forbids r_i its column. The subproblems partition the
//!   remaining associations, so popping them best first from a priority queue yields the associations in
//!   order of weight, each exactly once. Forced rows leave the subproblem, so deep subproblems are small.
//!   The partition is lazy (done when the next association is asked for), so the k best cost one solve
//!   plus at most r solves per further association. Each subproblem is solved from scratch (no warm start
//!   from its parent's duals as in Miller, Stone and Cox 1997, which would cut the cost per subproblem by
//!   about a factor r).
//!
//! The log-weights returned are exact: recomputed from the matrix ([`AssociationMatrix::score`]), as every
//! child generator of tracker-core does.

use crate::peers::assignment::{AssignmentCost, assign};
use std::cmp::Ordering;
use std::collections::BinaryHeap;
use tracker_core::association::{AssociationMatrix, CLUTTER};

/// One association and its exact log-weight.
#[derive(Debug, Clone, PartialEq)]
pub struct Child {
    /// Baseline + Σ entries.
    pub log_weight: f64,
    /// Per row, its column or [`CLUTTER`].
    pub assignment: Vec<u16>,
}

/// A lexicographic cost: `major` (minus the number of required columns assigned) first, then `minor`
/// (minus the sum of entries). An ordered group, so potentials and slacks work as for plain numbers.
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd)]
struct Cost {
    major: f64,
    minor: f64,
}

impl AssignmentCost for Cost {
    const ZERO: Cost = Cost { major: 0.0, minor: 0.0 };
    const INFINITE: Cost = Cost { major: f64::INFINITY, minor: 0.0 };

    fn is_infinite(self) -> bool {
        self.major == f64::INFINITY
    }
}

impl std::ops::Add for Cost {
    type Output = Cost;
    fn add(self, other: Cost) -> Cost {
        Cost { major: self.major + other.major, minor: self.minor + other.minor }
    }
}

impl std::ops::Sub for Cost {
    type Output = Cost;
    fn sub(self, other: Cost) -> Cost {
        Cost { major: self.major - other.major, minor: self.minor - other.minor }
    }
}

/// The augmented column of a row: a matrix column, or the row's private clutter column.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Column {
    Object(u16),
    Clutter,
}

/// A subproblem of Murty's partition and its best association.
#[derive(Debug, Clone)]
struct Node {
    cost: Cost,
    /// Arrival order: the deterministic tie-break.
    sequence: u64,
    /// Per row: forced to a column, or free.
    forced: Vec<Option<Column>>,
    /// Forbidden (row, column) pairs.
    forbidden: Vec<(usize, Column)>,
    /// The best association of the subproblem, per row.
    solution: Vec<Column>,
}

impl PartialEq for Node {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl Eq for Node {}

impl PartialOrd for Node {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Node {
    /// Max-heap order: the smaller cost (then the earlier arrival) is the greater node.
    fn cmp(&self, other: &Self) -> Ordering {
        other.cost.partial_cmp(&self.cost).unwrap_or(Ordering::Equal).then(other.sequence.cmp(&self.sequence))
    }
}

/// Murty's algorithm over one matrix: an iterator over its associations, best first (see the module
/// documentation). Lazy: the first `next` solves one assignment problem; each later `next` first partitions
/// the subproblem returned last (at most one solve per free row), then pops the best.
pub struct Murty<'a, const N: usize, const Z: usize> {
    matrix: &'a AssociationMatrix<f64, N, Z>,
    queue: BinaryHeap<Node>,
    /// The subproblem whose association was returned last, not yet partitioned.
    pending: Option<Node>,
    sequence: u64,
    required: usize,
    solved: u64,
}

impl<'a, const N: usize, const Z: usize> Murty<'a, N, Z> {
    /// Starts the enumeration (solves the unconstrained problem).
    pub fn new(matrix: &'a AssociationMatrix<f64, N, Z>) -> Self {
        let mut murty = Self { matrix, queue: BinaryHeap::new(), pending: None, sequence: 0, required: 0, solved: 0 };
        murty.required = (0..matrix.columns()).filter(|&c| matrix.is_required(c)).count();
        let rows = matrix.rows();
        if let Some(node) = murty.solve(vec![None; rows], Vec::new()) {
            murty.queue.push(node);
        }
        murty
    }

    /// Assignment problems solved so far.
    pub fn solved(&self) -> u64 {
        self.solved
    }

    /// Cost of `row` taking `column`, `None` when impossible.
    fn edge(&self, row: usize, column: Column) -> Option<Cost> {
        match column {
            Column::Clutter => Some(Cost::ZERO),
            Column::Object(c) => {
                let entry = self.matrix.entry(row, c as usize);
                (entry > f64::NEG_INFINITY).then(|| Cost {
                    major: if self.matrix.is_required(c as usize) { -1.0 } else { 0.0 },
                    minor: -entry,
                })
            }
        }
    }

    /// Solves the subproblem with `forced` rows and `forbidden` pairs; `None` when it has no association.
    fn solve(&mut self, forced: Vec<Option<Column>>, forbidden: Vec<(usize, Column)>) -> Option<Node> {
        self.solved += 1;
        let (rows, columns) = (self.matrix.rows(), self.matrix.columns());
        let mut taken = vec![false; columns];
        let mut fixed_cost = Cost::ZERO;
        for (row, column) in forced.iter().enumerate() {
            if let Some(column) = *column {
                if let Column::Object(c) = column {
                    taken[c as usize] = true;
                }
                fixed_cost = fixed_cost + self.edge(row, column)?;
            }
        }
        let free: Vec<usize> = (0..rows).filter(|&row| forced[row].is_none()).collect();
        // Open columns: untaken matrix columns, then one clutter column per free row.
        let open: Vec<u16> = (0..columns as u16).filter(|&c| !taken[c as usize]).collect();
        let width = open.len() + free.len();
        let mut cost = vec![None; free.len() * width];
        for (i, &row) in free.iter().enumerate() {
            let line = &mut cost[i * width..(i + 1) * width];
            for (j, &c) in open.iter().enumerate() {
                line[j] = self.edge(row, Column::Object(c));
            }
            line[open.len() + i] = Some(Cost::ZERO);
        }
        for &(row, column) in &forbidden {
            if let Some(i) = free.iter().position(|&r| r == row) {
                let j = match column {
                    Column::Object(c) => open.iter().position(|&o| o == c),
                    Column::Clutter => Some(open.len() + i),
                };
                if let Some(j) = j {
                    cost[i * width + j] = None;
                }
            }
        }
        let assignment = assign(free.len(), width, |i, j| cost[i * width + j])?;
        // The total summed in column order (the order that ranks the subproblems).
        let mut row_of_column = vec![None; width];
        for (i, &j) in assignment.iter().enumerate() {
            row_of_column[j] = Some(i);
        }
        let free_cost = row_of_column.iter().enumerate().fold(Cost::ZERO, |total, (j, row)| match row {
            Some(i) => total + cost[i * width + j].unwrap_or(Cost::INFINITE),
            None => total,
        });
        let mut solution: Vec<Column> = forced.iter().map(|c| c.unwrap_or(Column::Clutter)).collect();
        for (i, &row) in free.iter().enumerate() {
            let j = assignment[i];
            solution[row] = if j < open.len() { Column::Object(open[j]) } else { Column::Clutter };
        }
        self.sequence += 1;
        Some(Node { cost: fixed_cost + free_cost, sequence: self.sequence, forced, forbidden, solution })
    }
}

impl<const N: usize, const Z: usize> Iterator for Murty<'_, N, Z> {
    type Item = Child;

    fn next(&mut self) -> Option<Child> {
        if let Some(last) = self.pending.take() {
            // Partition the rest of the last subproblem over its free rows.
            let mut forced = last.forced.clone();
            for row in 0..forced.len() {
                if forced[row].is_some() {
                    continue;
                }
                let mut forbidden = last.forbidden.clone();
                forbidden.push((row, last.solution[row]));
                if let Some(child) = self.solve(forced.clone(), forbidden) {
                    self.queue.push(child);
                }
                forced[row] = Some(last.solution[row]);
            }
        }
        let node = self.queue.pop()?;
        // Lexicographic costs: the first association that misses a required column ends the feasible ones.
        if -node.cost.major < self.required as f64 {
            self.queue.clear();
            return None;
        }
        let assignment: Vec<u16> = node
            .solution
            .iter()
            .map(|c| match *c {
                Column::Object(c) => c,
                Column::Clutter => CLUTTER,
            })
            .collect();
        self.pending = Some(node);
        Some(Child { log_weight: self.matrix.score(&assignment), assignment })
    }
}

/// The `k` best associations of `matrix`, best first, with exact log-weights (fewer when it has fewer).
pub fn k_best<const N: usize, const Z: usize>(matrix: &AssociationMatrix<f64, N, Z>, k: usize) -> Vec<Child> {
    Murty::new(matrix).take(k).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand_core::{Rng, SeedableRng};
    use rand_xoshiro::SplitMix64;
    use tracker_core::children::{ChildGenerator, ChildSink, ExhaustiveChildren};

    struct All(Vec<(f64, Vec<u16>)>);

    impl ChildSink<f64> for All {
        fn offer(&mut self, log_weight: f64, assignment: &[u16]) {
            self.0.push((log_weight, assignment.to_vec()));
        }
    }

    fn exhaustive<const N: usize, const Z: usize>(m: &AssociationMatrix<f64, N, Z>) -> Vec<(f64, Vec<u16>)> {
        let mut all = All(vec![]);
        ExhaustiveChildren::new(u64::MAX).generate(m, &mut all).unwrap();
        all.0.sort_by(|a, b| b.0.total_cmp(&a.0));
        all.0
    }

    fn next(rng: &mut SplitMix64) -> f64 {
        (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    #[test]
    fn k_best_equals_the_exhaustive_top_k_in_weight_order() {
        let mut state = SplitMix64::seed_from_u64(17);
        for case in 0..150 {
            let rows = 1 + (next(&mut state) * 5.0) as usize;
            let columns = 1 + (next(&mut state) * 6.0) as usize;
            let mut m = AssociationMatrix::<f64, 6, 5>::new(rows, columns, -1.5);
            for c in 0..columns {
                let entries: Vec<f64> = (0..rows)
                    .map(|_| if next(&mut state) < 0.3 { f64::NEG_INFINITY } else { 8.0 * next(&mut state) - 4.0 })
                    .collect();
                m.set_column(c, &entries, case % 4 == 0 && next(&mut state) < 0.4);
            }
            let all = exhaustive(&m);
            let k = 1 + case % 25;
            let got = k_best(&m, k);
            assert_eq!(got.len(), k.min(all.len()), "case {case}");
            for (rank, (g, e)) in got.iter().zip(&all).enumerate() {
                assert!((g.log_weight - e.0).abs() < 1e-9, "case {case} rank {rank}: {} vs {}", g.log_weight, e.0);
                assert_eq!(g.log_weight, m.score(&g.assignment), "case {case}: exact weight");
            }
            let distinct: std::collections::BTreeSet<_> = got.iter().map(|c| c.assignment.clone()).collect();
            assert_eq!(distinct.len(), got.len(), "case {case}: distinct");
        }
    }

    #[test]
    fn murty_enumerates_every_feasible_association_once() {
        let mut m = AssociationMatrix::<f64, 4, 3>::new(3, 4, 0.0);
        for c in 0..4 {
            m.set_column(c, &[0.1 * c as f64, -0.2, 0.3 * c as f64 - 0.5], c == 2);
        }
        let all = exhaustive(&m);
        let got: Vec<Child> = Murty::new(&m).collect();
        assert_eq!(got.len(), all.len());
        assert!(got.iter().all(|c| c.assignment.contains(&2)));
    }

    #[test]
    fn fig4_map_is_2_7_9_3_8() {
        const TABLE: [[f64; 10]; 5] = [
            [0.1, 0.2, 0.0, 0.03, 0.05, 0.004, 0.002, 0.001, 0.01, 0.005],
            [0.04, 0.03, 0.05, 0.01, 0.04, 0.014, 0.2, 0.004, 0.005, 0.006],
            [0.09, 0.05, 0.04, 0.03, 0.01, 0.004, 0.005, 0.006, 0.1, 0.001],
            [0.09, 0.04, 0.1, 0.01, 0.02, 0.04, 0.3, 0.004, 0.005, 0.006],
            [0.001, 0.003, 0.002, 0.004, 0.005, 0.006, 0.007, 0.5, 0.01, 0.03],
        ];
        let rows: Vec<&[f64]> = TABLE.iter().map(|r| r.as_slice()).collect();
        let m = AssociationMatrix::<f64, 10, 5>::from_likelihoods(&rows, &[0.02; 5]);
        let best = k_best(&m, 5);
        let paper: Vec<u16> = best[0].assignment.iter().map(|&c| if c == CLUTTER { 11 } else { c + 1 }).collect();
        assert_eq!(paper, vec![2, 7, 9, 3, 8]);
        assert!((best[0].log_weight.exp() - 2.0e-4).abs() < 1e-12);
        let all = exhaustive(&m);
        for (g, e) in best.iter().zip(&all) {
            assert!((g.log_weight - e.0).abs() < 1e-12);
        }
    }
}
