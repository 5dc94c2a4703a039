//! Adaptive child generation by clusters: beyond the papers (paper 003's future work asks for an adaptive
//! method).
//!
//! Gating makes most entries of an association matrix impossible. Rows and columns connected through
//! possible entries form clusters that do not interact: a child is one association per cluster, and its
//! log-weight is the baseline plus the sum of its clusters' log-scores. So:
//!
//! 1. **Split** the matrix into clusters (union-find over possible entries). A row with no possible entry
//!    is clutter in every child; a column with none is missed in every child (or makes every child
//!    impossible when it is required).
//! 2. **Solve each cluster**: enumerate it exhaustively when it has at most `exhaustive_limit`
//!    associations (A_n(m)), else run the Metropolis sampler on it. Either way keep its best `C`
//!    distinct associations.
//! 3. **Combine**: the best `C` children of the whole matrix are the best `C` sums of one association per
//!    cluster; a k-best merge of sorted lists finds them exactly, cluster after cluster.
//! 4. **Offer** them with their exact log-weight recomputed from the full matrix, and report the mass of
//!    the children not offered: exact when every cluster was enumerated (Π of the clusters' sums), a lower
//!    bound otherwise.

use crate::association::{AssociationMatrix, CLUTTER, association_count};
use crate::children::{ChildGenerator, ChildSink, ExhaustiveChildren, GenerateError};
use crate::index::{At, NONE, insertion_sort_by};
use crate::random::cluster_seed;
use crate::real::{LogSumExp, Real, exp, ln};
use crate::sampler::{BestChildren, MetropolisSampler, SamplerConfig, association_hash};
use core::cmp::Ordering;

/// A sink that keeps a cluster's best `C` associations (exhaustive enumeration offers each once) and the
/// log-sum-exp of all of them.
struct ClusterSink<'a, T, const C: usize, const Z: usize> {
    best: &'a mut BestChildren<T, C, Z>,
    total: LogSumExp<T>,
}

impl<T: Real, const C: usize, const Z: usize> ChildSink<T> for ClusterSink<'_, T, C, Z> {
    fn offer(&mut self, log_weight: T, assignment: &[u16]) {
        self.total.add(log_weight);
        self.best.insert(log_weight, association_hash(assignment), assignment);
    }
}

/// One entry of a combination stage: its summed log-score, the entry of the previous stage it extends, and
/// the association of this stage's cluster it adds.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct Combination<T> {
    score: T,
    previous: u16,
    choice: u16,
}

/// Children of a matrix by clusters (see the module documentation). `C` is the number of children kept per
/// matrix; the tracker uses `C = H`.
///
/// # Examples
/// ```
/// use tracker_core::association::AssociationMatrix;
/// use tracker_core::children::{ChildGenerator, ExhaustiveChildren};
/// use tracker_core::cluster::ClusteredChildren;
/// use tracker_core::sampler::SamplerConfig;
/// use tracker_core::selection::TopChildren;
///
/// // Two pairs of measurements, each gated to its own pair of objects: two clusters of 7 associations.
/// let ninf = f64::NEG_INFINITY;
/// let mut matrix = AssociationMatrix::<f64, 4, 4>::new(4, 4, -6.0);
/// matrix.set_column(0, &[1.0, 0.3, ninf, ninf], false);
/// matrix.set_column(1, &[0.2, 2.0, ninf, ninf], false);
/// matrix.set_column(2, &[ninf, ninf, 1.5, -0.5], false);
/// matrix.set_column(3, &[ninf, ninf, 0.1, 0.7], false);
///
/// let mut clustered = TopChildren::<f64, 8, 4>::new();
/// ClusteredChildren::<f64, 4, 4, 8>::new(SamplerConfig::DEFAULT, 1).generate(&matrix, &mut clustered)?;
/// let mut exact = TopChildren::<f64, 8, 4>::new();
/// ExhaustiveChildren::new(1_000).generate(&matrix, &mut exact)?;
/// assert_eq!((clustered.offered(), exact.offered()), (8, 7 * 7));
///
/// let best_weights = |top: &TopChildren<f64, 8, 4>| {
///     let mut weights: Vec<f64> = top.kept().iter().map(|c| c.log_weight).collect();
///     weights.sort_by(|a, b| b.total_cmp(a));
///     weights
/// };
/// for (a, b) in best_weights(&clustered).iter().zip(&best_weights(&exact)) {
///     assert!((a - b).abs() < 1e-12); // the exact 8 best
/// }
/// // Both clusters were enumerated, so the mass of the children not offered is exact too.
/// assert!((clustered.log_total() - exact.log_total()).abs() < 1e-12);
/// # Ok::<(), tracker_core::children::GenerateError>(())
/// ```
#[derive(Debug, Clone)]
pub struct ClusteredChildren<T: Real, const N: usize, const Z: usize, const C: usize> {
    config: SamplerConfig,
    seed: u64,
    /// Metropolis moves allowed for the next matrix ([`ClusteredChildren::limit_moves`]).
    move_limit: u64,
    sampler: MetropolisSampler<T, N, Z, C>,
    /// Scratch matrix of one cluster.
    cluster: AssociationMatrix<T, N, Z>,
    /// Union-find parents: rows are nodes 0..Z, columns Z..Z+N.
    row_root: [u16; Z],
    column_root: [u16; N],
    /// Per row / column, its cluster (NONE: alone).
    row_cluster: [u16; Z],
    column_cluster: [u16; N],
    /// Per stage (cluster): the scores of its kept associations, best first.
    stage_scores: [[T; C]; Z],
    stage_len: [u16; Z],
    /// Per kept association of any cluster, its columns on that cluster's rows (full-matrix indices).
    choices: [[u16; Z]; C],
    /// Combination stages.
    stages: [[Combination<T>; C]; Z],
    combined_len: [u16; Z],
    /// k-best merge frontier: (score, previous entry, choice).
    frontier: [Combination<T>; C],
}

impl<T: Real, const N: usize, const Z: usize, const C: usize> ClusteredChildren<T, N, Z, C> {
    /// A generator with `config`; without `config.clusters` it runs one chain on the whole matrix.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::AssociationMatrix;
    /// # use tracker_core::children::ChildGenerator;
    /// # use tracker_core::cluster::ClusteredChildren;
    /// # use tracker_core::sampler::SamplerConfig;
    /// # use tracker_core::selection::TopChildren;
    /// # let ninf = f64::NEG_INFINITY;
    /// # // Two pairs of measurements, each gated to its own pair of objects: two clusters.
    /// # let mut matrix = AssociationMatrix::<f64, 4, 4>::new(4, 4, -6.0);
    /// # matrix.set_column(0, &[1.0, 0.3, ninf, ninf], false);
    /// # matrix.set_column(1, &[0.2, 2.0, ninf, ninf], false);
    /// # matrix.set_column(2, &[ninf, ninf, 1.5, -0.5], false);
    /// # matrix.set_column(3, &[ninf, ninf, 0.1, 0.7], false);
    /// # let children = |generator: &mut ClusteredChildren<f64, 4, 4, 8>| {
    /// #     let mut top = TopChildren::<f64, 8, 4>::new();
    /// #     generator.generate(&matrix, &mut top).unwrap();
    /// #     top.kept().iter().map(|c| (c.log_weight, c.assignment)).collect::<Vec<_>>()
    /// # };
    /// # // Every cluster sampled.
    /// # let sampled = SamplerConfig { exhaustive_limit: 0, ..SamplerConfig::DEFAULT };
    /// let (mut a, mut b) = (ClusteredChildren::new(sampled, 11), ClusteredChildren::new(sampled, 11));
    /// assert_eq!(children(&mut a), children(&mut b)); // deterministic
    /// assert_eq!(a.chain().accepted(), b.chain().accepted());
    /// assert_eq!(children(&mut a).len(), 8);
    /// ```
    pub fn new(config: SamplerConfig, seed: u64) -> Self {
        let mut generator = Self::empty(config);
        generator.reseed(seed);
        generator.sampler.reseed(seed);
        generator
    }

    /// A generator in a `const` context (for a tracker in a `static`): the sampler gets its random
    /// stream at the first matrix (every matrix is reseeded).
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::AssociationMatrix;
    /// # use tracker_core::children::ChildGenerator;
    /// # use tracker_core::cluster::ClusteredChildren;
    /// # use tracker_core::sampler::SamplerConfig;
    /// # use tracker_core::selection::TopChildren;
    /// # let ninf = f64::NEG_INFINITY;
    /// # // Two pairs of measurements, each gated to its own pair of objects: two clusters.
    /// # let mut matrix = AssociationMatrix::<f64, 4, 4>::new(4, 4, -6.0);
    /// # matrix.set_column(0, &[1.0, 0.3, ninf, ninf], false);
    /// # matrix.set_column(1, &[0.2, 2.0, ninf, ninf], false);
    /// # matrix.set_column(2, &[ninf, ninf, 1.5, -0.5], false);
    /// # matrix.set_column(3, &[ninf, ninf, 0.1, 0.7], false);
    /// # let children = |generator: &mut ClusteredChildren<f64, 4, 4, 8>| {
    /// #     let mut top = TopChildren::<f64, 8, 4>::new();
    /// #     generator.generate(&matrix, &mut top).unwrap();
    /// #     top.kept().iter().map(|c| (c.log_weight, c.assignment)).collect::<Vec<_>>()
    /// # };
    /// # // Every cluster sampled.
    /// # let sampled = SamplerConfig { exhaustive_limit: 0, ..SamplerConfig::DEFAULT };
    /// const CONFIG: SamplerConfig = SamplerConfig { exhaustive_limit: 0, ..SamplerConfig::DEFAULT };
    /// static GENERATOR: std::sync::Mutex<ClusteredChildren<f64, 4, 4, 8>> =
    ///     std::sync::Mutex::new(ClusteredChildren::empty(CONFIG));
    /// let mut generator = GENERATOR.lock().unwrap();
    /// generator.reseed(11);
    /// assert_eq!(children(&mut generator), children(&mut ClusteredChildren::new(sampled, 11)));
    /// ```
    pub const fn empty(config: SamplerConfig) -> Self {
        const fn blank<T: Real>() -> Combination<T> {
            Combination { score: T::ZERO, previous: 0, choice: 0 }
        }
        Self {
            config,
            seed: 0,
            move_limit: u64::MAX,
            sampler: MetropolisSampler::empty(config),
            cluster: AssociationMatrix::new(0, 0, T::ZERO),
            row_root: [0; Z],
            column_root: [0; N],
            row_cluster: [NONE; Z],
            column_cluster: [NONE; N],
            stage_scores: [[T::NEG_INFINITY; C]; Z],
            stage_len: [0; Z],
            choices: [[CLUTTER; Z]; C],
            stages: [[blank(); C]; Z],
            combined_len: [0; Z],
            frontier: [blank(); C],
        }
    }

    /// Replaces the configuration in place: the generator then runs as [`ClusteredChildren::empty`]`(config)`
    /// would (its tables are scratch that every matrix rewrites), without that value, tens of KiB at the
    /// embedded capacities, passing through the stack.
    pub(crate) fn configure(&mut self, config: SamplerConfig) {
        self.config = config;
        self.seed = 0;
        self.move_limit = u64::MAX;
        self.sampler.configure(config);
    }

    /// Sets the seed of the next matrix's samplers.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::AssociationMatrix;
    /// # use tracker_core::children::ChildGenerator;
    /// # use tracker_core::cluster::ClusteredChildren;
    /// # use tracker_core::sampler::SamplerConfig;
    /// # use tracker_core::selection::TopChildren;
    /// # let ninf = f64::NEG_INFINITY;
    /// # // Two pairs of measurements, each gated to its own pair of objects: two clusters.
    /// # let mut matrix = AssociationMatrix::<f64, 4, 4>::new(4, 4, -6.0);
    /// # matrix.set_column(0, &[1.0, 0.3, ninf, ninf], false);
    /// # matrix.set_column(1, &[0.2, 2.0, ninf, ninf], false);
    /// # matrix.set_column(2, &[ninf, ninf, 1.5, -0.5], false);
    /// # matrix.set_column(3, &[ninf, ninf, 0.1, 0.7], false);
    /// # let children = |generator: &mut ClusteredChildren<f64, 4, 4, 8>| {
    /// #     let mut top = TopChildren::<f64, 8, 4>::new();
    /// #     generator.generate(&matrix, &mut top).unwrap();
    /// #     top.kept().iter().map(|c| (c.log_weight, c.assignment)).collect::<Vec<_>>()
    /// # };
    /// # // Every cluster sampled.
    /// # let sampled = SamplerConfig { exhaustive_limit: 0, ..SamplerConfig::DEFAULT };
    /// // Moves accepted by the chains of one matrix under `seed`.
    /// let mut generator = ClusteredChildren::new(sampled, 1);
    /// let mut accepted = |seed| {
    ///     generator.reseed(seed);
    ///     let before = generator.chain().accepted();
    ///     children(&mut generator);
    ///     generator.chain().accepted() - before
    /// };
    /// let (first, second, again) = (accepted(1), accepted(2), accepted(1));
    /// assert_eq!(first, again);
    /// assert_ne!(first, second);
    /// ```
    pub fn reseed(&mut self, seed: u64) {
        self.seed = seed;
    }

    /// Limits the Metropolis moves of the next matrix's chains to `max_moves` in total (`u64::MAX`: the
    /// configured chain length for each). The sampled clusters share the limit in turn, each taking an
    /// equal part of what the ones before it left.
    pub fn limit_moves(&mut self, max_moves: u64) {
        self.move_limit = max_moves;
    }

    /// The Metropolis chain that samples large clusters (for its statistics: moves taken, accepted).
    ///
    /// # Examples
    /// Small clusters are enumerated, not sampled, by default:
    /// ```
    /// # use tracker_core::association::AssociationMatrix;
    /// # use tracker_core::children::ChildGenerator;
    /// # use tracker_core::cluster::ClusteredChildren;
    /// # use tracker_core::sampler::SamplerConfig;
    /// # use tracker_core::selection::TopChildren;
    /// # let ninf = f64::NEG_INFINITY;
    /// # // Two pairs of measurements, each gated to its own pair of objects: two clusters.
    /// # let mut matrix = AssociationMatrix::<f64, 4, 4>::new(4, 4, -6.0);
    /// # matrix.set_column(0, &[1.0, 0.3, ninf, ninf], false);
    /// # matrix.set_column(1, &[0.2, 2.0, ninf, ninf], false);
    /// # matrix.set_column(2, &[ninf, ninf, 1.5, -0.5], false);
    /// # matrix.set_column(3, &[ninf, ninf, 0.1, 0.7], false);
    /// # let children = |generator: &mut ClusteredChildren<f64, 4, 4, 8>| {
    /// #     let mut top = TopChildren::<f64, 8, 4>::new();
    /// #     generator.generate(&matrix, &mut top).unwrap();
    /// #     top.kept().iter().map(|c| (c.log_weight, c.assignment)).collect::<Vec<_>>()
    /// # };
    /// # // Every cluster sampled.
    /// # let sampled = SamplerConfig { exhaustive_limit: 0, ..SamplerConfig::DEFAULT };
    /// let mut enumerated = ClusteredChildren::new(SamplerConfig::DEFAULT, 1);
    /// children(&mut enumerated);
    /// assert_eq!(enumerated.chain().steps_taken(), 0);
    /// let mut sampling = ClusteredChildren::new(sampled, 1);
    /// children(&mut sampling);
    /// assert!(sampling.chain().steps_taken() > 0);
    /// ```
    pub fn chain(&self) -> &MetropolisSampler<T, N, Z, C> {
        &self.sampler
    }

    /// The union-find parent of `node` (rows are nodes `0..Z`, columns `Z..Z + N`; a node outside the
    /// table is its own root).
    fn node_root(&self, node: usize) -> usize {
        let parent = if node < Z { self.row_root.get(node) } else { self.column_root.get(node - Z) };
        parent.map_or(node, |&parent| usize::from(parent))
    }

    fn set_node_root(&mut self, node: usize, root: usize) {
        let parent = if node < Z { self.row_root.get_mut(node) } else { self.column_root.get_mut(node - Z) };
        if let Some(parent) = parent {
            *parent = root as u16;
        }
    }

    fn find(&mut self, mut node: usize) -> usize {
        // Path halving; depth ≤ Z + N.
        for _ in 0..(Z + N) {
            let parent = self.node_root(node);
            if parent == node {
                return node;
            }
            let grandparent = self.node_root(parent);
            self.set_node_root(node, grandparent);
            node = grandparent;
        }
        node
    }

    /// Splits `matrix` into clusters; returns their number, or `None` when a required column can take no
    /// measurement (no feasible child).
    fn split(&mut self, matrix: &AssociationMatrix<T, N, Z>) -> Option<usize> {
        let (rows, columns) = (matrix.rows(), matrix.columns());
        for row in 0..rows {
            self.row_root[row] = row as u16;
        }
        for column in 0..columns {
            self.column_root[column] = (Z + column) as u16;
        }
        let mut column_possible = [false; N];
        let mut row_possible = [false; Z];
        for row in 0..rows {
            // The root of the row's set, kept as the row joins its columns' sets. The smaller root wins, so
            // cluster order follows row order.
            let mut root = self.find(row);
            for column in 0..columns {
                if matrix.entry(row, column) > T::NEG_INFINITY {
                    row_possible[row] = true;
                    column_possible[column] = true;
                    let other = self.find(Z + column);
                    if other != root {
                        let (low, high) = if root < other { (root, other) } else { (other, root) };
                        self.set_node_root(high, low);
                        root = low;
                    }
                }
            }
        }
        for column in 0..columns {
            if !column_possible[column] && matrix.is_required(column) {
                return None;
            }
        }
        // Number the clusters by their root (the smallest row of the cluster).
        let mut count = 0usize;
        self.row_cluster[..rows].fill(NONE);
        self.column_cluster[..columns].fill(NONE);
        for row in 0..rows {
            if !row_possible[row] {
                continue;
            }
            let root = self.find(row);
            if root == row {
                self.row_cluster[row] = count as u16;
                count += 1;
            }
        }
        // A cluster's root is its smallest row.
        for row in 0..rows {
            if row_possible[row] {
                let root = self.find(row);
                self.row_cluster[row] = *self.row_cluster.at(root);
            }
        }
        for column in 0..columns {
            if column_possible[column] {
                let root = self.find(Z + column);
                self.column_cluster[column] = *self.row_cluster.at(root);
            }
        }
        Some(count)
    }

    /// Solves cluster `index` (a chain of at most `max_moves` moves when it is sampled): fills stage
    /// `index`'s scores and the choices table. Returns the log-sum-exp of its associations (exact when
    /// enumerated, a lower bound when sampled) and whether it was sampled.
    fn solve(
        &mut self,
        matrix: &AssociationMatrix<T, N, Z>,
        index: usize,
        max_moves: u64,
    ) -> Result<(T, bool), GenerateError> {
        let (rows, columns) = (matrix.rows(), matrix.columns());
        let mut cluster_rows = [0u16; Z];
        let mut cluster_columns = [0u16; N];
        let (mut m, mut n) = (0usize, 0usize);
        for row in 0..rows {
            if self.row_cluster[row] as usize == index {
                *cluster_rows.at_mut(m) = row as u16;
                m += 1;
            }
        }
        for column in 0..columns {
            if self.column_cluster[column] as usize == index {
                *cluster_columns.at_mut(n) = column as u16;
                n += 1;
            }
        }
        // No-op clamps (m ≤ rows, n ≤ columns) that let the optimiser drop the slices' bounds checks.
        let (cluster_rows, cluster_columns) = (&cluster_rows[..m.min(Z)], &cluster_columns[..n.min(N)]);
        self.cluster = AssociationMatrix::new(m, 0, T::zero());
        let mut entries = [T::NEG_INFINITY; Z];
        for &column in cluster_columns {
            for (entry, &row) in entries.iter_mut().zip(cluster_rows) {
                *entry = matrix.entry(usize::from(row), usize::from(column));
            }
            let _ = self.cluster.push_column(&entries[..cluster_rows.len()], matrix.is_required(usize::from(column)));
        }
        let exhaustive = association_count(n as u32, m as u32) <= u128::from(self.config.exhaustive_limit);
        let total = if exhaustive {
            let mut generator = ExhaustiveChildren::new(self.config.exhaustive_limit.max(1));
            let best = self.sampler.best_mut();
            best.clear(m);
            let mut sink = ClusterSink { best, total: LogSumExp::new() };
            generator.generate(&self.cluster, &mut sink)?;
            sink.total.value()
        } else {
            self.sampler.reseed(cluster_seed(self.seed, index));
            self.sampler.run_with_moves(&self.cluster, max_moves);
            let mut known = LogSumExp::new();
            for (score, _) in self.sampler.best().iter() {
                known.add(score);
            }
            known.value()
        };
        // Best first into the stage, the columns mapped back to the full matrix.
        let best = self.sampler.best();
        let kept = best.len();
        let mut order = [0u16; C];
        for (slot, i) in order.iter_mut().zip(0u16..).take(kept) {
            *slot = i;
        }
        let score_of = |i: u16| best.get(i as usize).map_or(T::NEG_INFINITY, |(score, _)| score);
        // Best first, ties by index: a total order, so the sorted order is unique.
        insertion_sort_by(&mut order[..kept], |&a, &b| {
            score_of(b).partial_cmp(&score_of(a)).unwrap_or(Ordering::Equal).then(a.cmp(&b)) == Ordering::Less
        });
        let stage_scores = self.stage_scores.at_mut(index);
        for (rank, &item) in order[..kept].iter().enumerate() {
            let Some((score, assignment)) = best.get(item as usize) else { continue };
            *stage_scores.at_mut(rank) = score;
            let choice = self.choices.at_mut(rank);
            for (local, &row) in cluster_rows.iter().enumerate() {
                // The cluster's column mapped back to the matrix (clutter, `u16::MAX`, maps to itself).
                *choice.at_mut(usize::from(row)) = assignment
                    .get(local)
                    .and_then(|&column| cluster_columns.get(usize::from(column)))
                    .copied()
                    .unwrap_or(CLUTTER);
            }
        }
        *self.stage_len.at_mut(index) = kept as u16;
        Ok((total, !exhaustive))
    }

    /// How many of the `clusters` clusters are too large to enumerate (A_n(m) above the exhaustive limit).
    fn sampled_clusters(&self, matrix: &AssociationMatrix<T, N, Z>, clusters: usize) -> usize {
        let mut rows = [0u32; Z];
        let mut columns = [0u32; Z];
        for row in 0..matrix.rows() {
            if let Some(count) = rows.get_mut(usize::from(self.row_cluster[row])) {
                *count += 1;
            }
        }
        for column in 0..matrix.columns() {
            if let Some(count) = columns.get_mut(usize::from(self.column_cluster[column])) {
                *count += 1;
            }
        }
        let limit = u128::from(self.config.exhaustive_limit);
        rows.iter().zip(&columns).take(clusters).filter(|&(&m, &n)| association_count(n, m) > limit).count()
    }

    /// Stage `index` = best `C` sums of stage `index − 1` and cluster `index` (k-best merge of two sorted
    /// lists with a frontier heap of at most `C` entries).
    fn combine(&mut self, index: usize) {
        let cluster_len = usize::from(*self.stage_len.at(index));
        let cluster_scores = self.stage_scores.at(index);
        if index == 0 {
            for rank in 0..cluster_len {
                *self.stages[0].at_mut(rank) =
                    Combination { score: *cluster_scores.at(rank), previous: 0, choice: rank as u16 };
            }
            self.combined_len[0] = cluster_len as u16;
            return;
        }
        let previous_len = usize::from(*self.combined_len.at(index - 1));
        // Frontier: for each previous entry i, the next choice j to pair with it; start with (i, 0).
        let mut frontier_len = 0usize;
        if cluster_len > 0 {
            for i in 0..previous_len {
                *self.frontier.at_mut(frontier_len) = Combination {
                    score: self.stages.at(index - 1).at(i).score + cluster_scores[0],
                    previous: i as u16,
                    choice: 0,
                };
                frontier_len += 1;
            }
        }
        let mut out = 0usize;
        while out < C {
            // Take the best of the frontier (ties: lower previous entry, then lower choice).
            let Some((&first, rest)) = self.frontier[..frontier_len.min(C)].split_first() else { break };
            let (mut best, mut taken) = (0usize, first);
            for (f, &a) in (1..).zip(rest) {
                if a.score > taken.score
                    || (a.score == taken.score && (a.previous, a.choice) < (taken.previous, taken.choice))
                {
                    (best, taken) = (f, a);
                }
            }
            *self.stages.at_mut(index).at_mut(out) = taken;
            out += 1;
            let next_choice = usize::from(taken.choice) + 1;
            if next_choice < cluster_len {
                *self.frontier.at_mut(best) = Combination {
                    score: self.stages.at(index - 1).at(usize::from(taken.previous)).score
                        + *cluster_scores.at(next_choice),
                    previous: taken.previous,
                    choice: next_choice as u16,
                };
            } else {
                frontier_len -= 1;
                *self.frontier.at_mut(best) = *self.frontier.at(frontier_len);
            }
        }
        *self.combined_len.at_mut(index) = out as u16;
    }
}

impl<T: Real, const N: usize, const Z: usize, const C: usize> ChildGenerator<T, N, Z>
    for ClusteredChildren<T, N, Z, C>
{
    fn generate<Sink: ChildSink<T>>(
        &mut self,
        matrix: &AssociationMatrix<T, N, Z>,
        sink: &mut Sink,
    ) -> Result<u64, GenerateError> {
        let rows = matrix.rows();
        if !self.config.clusters {
            // Paper 003: one chain on the whole matrix.
            self.sampler.reseed(self.seed);
            self.sampler.run_with_moves(matrix, self.move_limit);
            for (score, assignment) in self.sampler.best().iter() {
                sink.offer(score, assignment);
            }
            return Ok(self.sampler.best().len() as u64);
        }
        let Some(clusters) = self.split(matrix) else { return Ok(0) };
        let mut sampled_left = self.sampled_clusters(matrix, clusters);
        let mut moves_left = self.move_limit;
        let mut log_total = matrix.baseline();
        // The choices of all clusters share one table: clusters have disjoint rows.
        for index in 0..clusters {
            let moves_before = self.sampler.steps_taken();
            let share = moves_left / sampled_left.max(1) as u64;
            let (total, sampled) = self.solve(matrix, index, share)?;
            if sampled {
                sampled_left = sampled_left.saturating_sub(1);
                moves_left -= (self.sampler.steps_taken() - moves_before).min(moves_left);
            }
            log_total += total;
            if *self.stage_len.at(index) == 0 {
                return Ok(0); // a cluster with no feasible association
            }
            self.combine(index);
        }
        // Reconstruct and offer every combination of the last stage.
        let final_len = if clusters == 0 { 1 } else { usize::from(*self.combined_len.at(clusters - 1)) };
        let mut offered_total = LogSumExp::new();
        let mut assignment = [CLUTTER; Z];
        for entry in 0..final_len {
            assignment[..rows].fill(CLUTTER);
            let mut position = entry;
            for stage in (0..clusters).rev() {
                let combination = *self.stages.at(stage).at(position);
                let choice = self.choices.at(usize::from(combination.choice));
                for row in 0..rows {
                    if self.row_cluster[row] as usize == stage {
                        assignment[row] = choice[row];
                    }
                }
                position = usize::from(combination.previous);
            }
            let exact = matrix.score(&assignment[..rows]);
            if exact > T::NEG_INFINITY {
                offered_total.add(exact);
                sink.offer(exact, &assignment[..rows]);
            }
        }
        // Mass of the children not offered: Π of the clusters' sums minus what was offered.
        let offered = offered_total.value();
        if log_total > offered && offered > T::NEG_INFINITY {
            let rest = log_total + ln(T::one() - exp(offered - log_total));
            sink.unoffered(rest);
        }
        Ok(final_len as u64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::real::LogSumExp;
    use std::vec::Vec;

    struct Collect {
        children: Vec<(f64, Vec<u16>)>,
        unoffered: LogSumExp<f64>,
    }

    impl ChildSink<f64> for Collect {
        fn offer(&mut self, w: f64, a: &[u16]) {
            self.children.push((w, a.to_vec()));
        }
        fn unoffered(&mut self, m: f64) {
            self.unoffered.add(m);
        }
    }

    fn sparse_matrix(seed: u64, rows: usize, columns: usize) -> AssociationMatrix<f64, 10, 8> {
        let mut state = seed;
        let mut next = || {
            state = crate::random::mix(state);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut m = AssociationMatrix::new(rows, columns, -2.0);
        for c in 0..columns {
            let entries: Vec<f64> =
                (0..rows).map(|_| if next() < 0.7 { f64::NEG_INFINITY } else { 10.0 * next() - 4.0 }).collect();
            m.set_column(c, &entries, false);
        }
        m
    }

    fn exhaustive_top(m: &AssociationMatrix<f64, 10, 8>, c: usize) -> (Vec<(f64, Vec<u16>)>, f64) {
        let mut all = Collect { children: vec![], unoffered: LogSumExp::new() };
        ExhaustiveChildren::new(u64::MAX).generate(m, &mut all).unwrap();
        let mut total = LogSumExp::new();
        for child in &all.children {
            total.add(child.0);
        }
        all.children.sort_by(|a, b| b.0.total_cmp(&a.0));
        all.children.truncate(c);
        (all.children, total.value())
    }

    #[test]
    fn clustered_children_equal_the_exhaustive_best_and_account_for_the_rest() {
        for seed in 0..300 {
            let m = sparse_matrix(seed, 1 + (seed % 8) as usize, 1 + (seed % 10) as usize);
            let config = SamplerConfig { exhaustive_limit: u64::MAX, ..SamplerConfig::default() };
            let mut clustered = ClusteredChildren::<f64, 10, 8, 12>::new(config, seed);
            let mut got = Collect { children: vec![], unoffered: LogSumExp::new() };
            clustered.generate(&m, &mut got).unwrap();
            let (expected, total) = exhaustive_top(&m, 12);
            let mut got_weights: Vec<f64> = got.children.iter().map(|c| c.0).collect();
            got_weights.sort_by(|a, b| b.total_cmp(a));
            let expected_weights: Vec<f64> = expected.iter().map(|c| c.0).collect();
            assert_eq!(got_weights.len(), expected_weights.len(), "seed {seed}");
            for (g, e) in got_weights.iter().zip(&expected_weights) {
                assert!((g - e).abs() < 1e-12, "seed {seed}: {got_weights:?} vs {expected_weights:?}");
            }
            for (w, a) in &got.children {
                assert_eq!(*w, m.score(a), "exact weight");
            }
            let distinct: std::collections::BTreeSet<_> = got.children.iter().map(|c| c.1.clone()).collect();
            assert_eq!(distinct.len(), got.children.len());
            // Offered + unoffered = the exact total when every cluster is enumerated.
            let mut all = LogSumExp::new();
            for (w, _) in &got.children {
                all.add(*w);
            }
            all.add(got.unoffered.value());
            assert!((all.value() - total).abs() < 1e-9, "seed {seed}: mass {} vs {total}", all.value());
        }
    }

    #[test]
    fn sampled_clusters_find_the_best_children_of_small_problems() {
        for seed in 0..100 {
            let m = sparse_matrix(seed + 1000, 6, 8);
            let config = SamplerConfig { exhaustive_limit: 0, ..SamplerConfig::default() };
            let mut clustered = ClusteredChildren::<f64, 10, 8, 12>::new(config, seed);
            let mut got = Collect { children: vec![], unoffered: LogSumExp::new() };
            clustered.generate(&m, &mut got).unwrap();
            let (expected, _) = exhaustive_top(&m, 1);
            let best = got.children.iter().map(|c| c.0).fold(f64::NEG_INFINITY, f64::max);
            assert!((best - expected[0].0).abs() < 1e-12, "seed {seed}: MAP not found");
        }
    }

    #[test]
    fn a_required_column_that_cannot_be_assigned_gives_no_child() {
        let mut m = sparse_matrix(5, 3, 3);
        m.set_column(1, &[f64::NEG_INFINITY; 3], true);
        let mut clustered = ClusteredChildren::<f64, 10, 8, 12>::new(SamplerConfig::default(), 1);
        let mut got = Collect { children: vec![], unoffered: LogSumExp::new() };
        assert_eq!(clustered.generate(&m, &mut got), Ok(0));
        assert!(got.children.is_empty());
    }
}
