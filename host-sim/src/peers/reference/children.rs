//! The children of a scan: the columns and heads of the enumeration, the buffer that keeps the best children
//! within the budget, and the search that enumerates associations.

use super::*;

/// One column of an event's association matrix.
pub(super) struct Column<'a> {
    pub(super) entries: &'a [f64],
    /// `bounds[r]` ≥ every entry of rows `r..`, and ≥ 0 (clutter).
    pub(super) bounds: &'a [f64],
    /// The rows by decreasing entry (ties: lower row first).
    pub(super) order: &'a [u32],
    pub(super) required: bool,
}

/// A child in the buffer; its rows per column are `rows[start..next start]`.
#[derive(Debug, Clone, Copy)]
pub(super) struct Head {
    pub(super) log_weight: f64,
    start: usize,
    pub(super) parent: u32,
    pub(super) event: Event,
}

/// The children kept so far, within a byte capacity: when full, the best half is kept and every later
/// child or branch that cannot beat the worst kept one is skipped.
pub(super) struct ChildBuffer {
    pub(super) heads: Vec<Head>,
    rows: Vec<u32>,
    /// At most this many heads (and `capacity × widest` rows).
    capacity: usize,
    widest: usize,
    /// The worst kept weight once pruned, else −∞.
    threshold: f64,
    pub(super) pruned: bool,
    pub(super) count: u64,
    limit: u64,
    /// Association steps taken this scan ([`ChildBuffer::step`]) and their bound.
    pub(super) work: u64,
    max_work: u64,
    pub(super) total: LogSumExp<f64>,
}

impl ChildBuffer {
    pub(super) fn new(capacity: usize, widest: usize, limit: u64, max_work: u64) -> Self {
        Self {
            heads: vec![],
            rows: vec![],
            capacity: capacity.max(2),
            widest,
            threshold: f64::NEG_INFINITY,
            pruned: false,
            count: 0,
            limit,
            work: 0,
            max_work,
            total: LogSumExp::new(),
        }
    }

    pub(super) fn rows_of(&self, index: usize) -> &[u32] {
        let end = self.heads.get(index + 1).map_or(self.rows.len(), |h| h.start);
        &self.rows[self.heads[index].start..end]
    }

    /// Whether no child of weight ≤ `bound` can be kept. `tolerance` covers the rounding of a bound
    /// summed in another order than the child's weight.
    fn cannot_beat(&self, bound: f64, tolerance: f64) -> bool {
        self.pruned && bound + tolerance <= self.threshold
    }

    /// Counts `steps` association steps; `false` when the work bound is passed.
    fn step(&mut self, steps: u64) -> bool {
        self.work = self.work.saturating_add(steps);
        self.work <= self.max_work
    }

    /// Whether the search stopped for the work bound (not the children limit).
    pub(super) fn work_exceeded(&self) -> bool {
        self.work > self.max_work
    }

    /// Counts and keeps a child; `false` when the children limit is reached.
    fn offer(&mut self, log_weight: f64, parent: u32, event: Event, row_of: &[u32]) -> bool {
        if self.count >= self.limit {
            return false;
        }
        self.count += 1;
        self.total.add(log_weight);
        if self.heads.len() == self.capacity {
            self.prune();
        }
        if self.pruned && log_weight.total_cmp(&self.threshold).is_le() {
            return true;
        }
        let start = self.rows.len();
        grow_within(&mut self.rows, row_of.len(), self.capacity * self.widest);
        self.rows.extend_from_slice(row_of);
        grow_within(&mut self.heads, 1, self.capacity);
        self.heads.push(Head { log_weight, start, parent, event });
        true
    }

    /// Keeps the best `capacity / 2` children (ties: earlier first), in enumeration order.
    fn prune(&mut self) {
        let keep = self.capacity / 2;
        let mut weights: Vec<f64> = self.heads.iter().map(|h| h.log_weight).collect();
        let cut = *weights.select_nth_unstable_by(keep - 1, |a, b| b.total_cmp(a)).1;
        drop(weights);
        let mut ties = keep - self.heads.iter().filter(|h| h.log_weight.total_cmp(&cut).is_gt()).count();
        let (mut kept, mut end) = (0, 0);
        for index in 0..self.heads.len() {
            let head = self.heads[index];
            let keep_it = match head.log_weight.total_cmp(&cut) {
                std::cmp::Ordering::Greater => true,
                std::cmp::Ordering::Equal if ties > 0 => {
                    ties -= 1;
                    true
                }
                _ => false,
            };
            if keep_it {
                let next = self.heads.get(index + 1).map_or(self.rows.len(), |h| h.start);
                self.rows.copy_within(head.start..next, end);
                self.heads[kept] = Head { start: end, ..head };
                kept += 1;
                end += next - head.start;
            }
        }
        self.heads.truncate(kept);
        self.rows.truncate(end);
        self.threshold = cut;
        self.pruned = true;
    }
}

/// Makes room for `more` elements, never past `max` (doubling below it).
pub(super) fn grow_within<T>(v: &mut Vec<T>, more: usize, max: usize) {
    if v.len() + more > v.capacity() {
        let target = (2 * v.capacity()).max(v.len() + more).max(64).min(max.max(v.len() + more));
        v.reserve_exact(target - v.len());
    }
}

/// The recursive enumeration of one parent-event's associations. A node is a partial association whose
/// rows before `row` are decided; it offers its own child (every later row clutter) first, then assigns
/// an unused column to a later row, last row first. That is the lexicographic order of the rows'
/// choices (clutter first, then columns in order), and each node is one child, so skipping the rows
/// left to clutter costs nothing.
pub(super) struct Search<'a, 'b> {
    pub(super) columns: &'a [Column<'a>],
    /// Per column its row, or [`CLUTTER`].
    pub(super) row_of: Vec<u32>,
    pub(super) rows: usize,
    pub(super) parent: u32,
    pub(super) event: Event,
    pub(super) children: &'b mut ChildBuffer,
    /// Per depth, the (row, column) candidates of a pruned node.
    pub(super) candidates: Vec<Vec<(u32, u32)>>,
}

impl Search<'_, '_> {
    /// Offers the node's child and every child below it, skipping children that leave a required column
    /// unassigned and, once the buffer was pruned, branches that cannot beat it. `false` as soon as the
    /// children limit or the work bound is reached: the node and each (row, column) pair it examines is
    /// one association step.
    pub(super) fn visit(&mut self, row: usize, value: f64, depth: usize) -> bool {
        if !self.children.step(1) {
            return false;
        }
        if self.children.pruned && self.cannot_beat(row, value, None) {
            return true;
        }
        let complete = self.columns.iter().zip(&self.row_of).all(|(c, &r)| !c.required || r != CLUTTER);
        if complete && !self.children.offer(value, self.parent, self.event, &self.row_of) {
            return false;
        }
        for r in (row..self.rows).rev() {
            if self.children.pruned {
                return self.visit_candidates(row, r + 1, value, depth);
            }
            if !self.children.step(self.columns.len() as u64) {
                return false;
            }
            for column in 0..self.columns.len() {
                if self.row_of[column] == CLUTTER
                    && self.columns[column].entries[r] > f64::NEG_INFINITY
                    && !self.assign(column, r, value, depth)
                {
                    return false;
                }
            }
        }
        true
    }

    /// Visits the node with `column` assigned to `row`.
    fn assign(&mut self, column: usize, row: usize, value: f64, depth: usize) -> bool {
        self.row_of[column] = row as u32;
        let go_on = self.visit(row + 1, value + self.columns[column].entries[row], depth + 1);
        self.row_of[column] = CLUTTER;
        go_on
    }

    /// Whether no child below the node (with `column` also assigned, if given) can be kept: its value
    /// plus every unused column's best entry from `row` on does not beat the worst kept child.
    fn cannot_beat(&self, row: usize, value: f64, except: Option<usize>) -> bool {
        let (mut bound, mut magnitude) = (value, value.abs() + 1.0);
        for (column, (c, &r)) in self.columns.iter().zip(&self.row_of).enumerate() {
            if r == CLUTTER && Some(column) != except {
                bound += c.bounds[row];
                magnitude += c.bounds[row];
            }
        }
        // The tolerance covers the rounding of a bound summed in another order than a child's weight.
        self.children.cannot_beat(bound, 1e-9 * magnitude)
    }

    /// Once pruned: the assignments of rows `row..end` that may beat the kept children, found from each
    /// column's rows by decreasing entry, visited in the enumeration order.
    fn visit_candidates(&mut self, row: usize, end: usize, value: f64, depth: usize) -> bool {
        if self.candidates.len() <= depth {
            self.candidates.resize_with(depth + 1, Vec::new);
        }
        let mut list = std::mem::take(&mut self.candidates[depth]);
        list.clear();
        for column in 0..self.columns.len() {
            if self.row_of[column] != CLUTTER {
                continue;
            }
            let c = &self.columns[column];
            for &r in c.order {
                if !self.children.step(1) {
                    self.candidates[depth] = list;
                    return false;
                }
                let entry = c.entries[r as usize];
                if !(entry > f64::NEG_INFINITY) || self.cannot_beat(row, value + entry, Some(column)) {
                    break;
                }
                if (row..end).contains(&(r as usize)) {
                    list.push((r, column as u32));
                }
            }
        }
        list.sort_unstable_by(|a, b| b.0.cmp(&a.0).then(a.1.cmp(&b.1)));
        let mut go_on = true;
        for &(r, column) in &list {
            if !self.assign(column as usize, r as usize, value, depth) {
                go_on = false;
                break;
            }
        }
        self.candidates[depth] = list;
        go_on
    }
}
