//! The best `C` distinct children of one chain (or one enumerated cluster), with O(1) duplicate detection
//! through an incremental Zobrist-style hash of the association.

use crate::association::CLUTTER;
use crate::index::{At, NONE, WorstFirstHeap, copy_prefix};
use crate::random::mix;
use crate::real::Real;
use core::cmp::Ordering;

/// Hash contribution of row `row` taking `column`.
#[inline]
pub(crate) fn cell_hash(row: usize, column: u16) -> u64 {
    mix(((row as u64) << 32) | u64::from(column))
}

/// The hash of a whole association: XOR of its cells' hashes (so one move updates it in O(1)).
///
/// # Examples
/// ```
/// use tracker_core::association::CLUTTER;
/// use tracker_core::sampler::association_hash;
/// assert_ne!(association_hash(&[0, 1]), association_hash(&[1, 0])); // the row matters
/// assert_ne!(association_hash(&[0, CLUTTER]), association_hash(&[0]));
/// assert_eq!(association_hash(&[]), 0);
/// ```
pub fn association_hash(assignment: &[u16]) -> u64 {
    assignment.iter().enumerate().fold(0, |h, (row, &column)| h ^ cell_hash(row, column))
}

/// Whether kept child `a` ranks below `b`: a lower score, or an equal score that arrived later.
#[inline]
fn ranks_below<T: Real, const C: usize>(scores: &[T; C], arrival: &[u32; C], a: u16, b: u16) -> bool {
    let (a, b) = (usize::from(a), usize::from(b));
    match scores.at(a).partial_cmp(scores.at(b)) {
        Some(Ordering::Less) => true,
        Some(Ordering::Greater) => false,
        _ => arrival.at(a) > arrival.at(b),
    }
}

/// The best `C` distinct children of one chain, with O(1) duplicate detection.
///
/// A child evicted for a better one can never come back: the worst kept score only rises, and a child is
/// admitted only when it beats it. So every distinct child leaves the set at most once.
///
/// # Examples
/// ```
/// use tracker_core::association::CLUTTER;
/// use tracker_core::sampler::{BestChildren, association_hash};
/// let mut best = BestChildren::<f64, 2, 2>::new();
/// best.clear(2); // two rows
/// let (a, b, c) = ([0, CLUTTER], [CLUTTER, 0], [0, 1]);
/// assert!(best.insert(-1.0, association_hash(&a), &a));
/// assert!(!best.insert(-1.0, association_hash(&a), &a)); // already kept
/// assert!(best.insert(-3.0, association_hash(&b), &b));
/// assert!(best.insert(-2.0, association_hash(&c), &c)); // evicts b
/// assert!(!best.contains(association_hash(&b), &b));
/// assert!(!best.insert(-3.0, association_hash(&b), &b)); // below the worst kept
/// ```
#[derive(Debug, Clone)]
pub struct BestChildren<T, const C: usize, const Z: usize> {
    scores: [T; C],
    hashes: [u64; C],
    assignments: [[u16; Z]; C],
    /// Item indices by (score, arrival), the worst kept child at the root.
    heap: WorstFirstHeap<C>,
    arrival: [u32; C],
    /// Open-addressing table (linear probing) of item indices by hash; 2C slots.
    table: [[u16; C]; 2],
    rows: usize,
    next_arrival: u32,
}

impl<T: Real, const C: usize, const Z: usize> Default for BestChildren<T, C, Z> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T: Real, const C: usize, const Z: usize> BestChildren<T, C, Z> {
    /// An empty set (usable in a `const` context).
    ///
    /// # Examples
    /// ```
    /// let best = tracker_core::sampler::BestChildren::<f32, 4, 3>::new();
    /// assert!(best.is_empty());
    /// assert_eq!(best.threshold(), f32::NEG_INFINITY);
    /// ```
    pub const fn new() -> Self {
        Self {
            scores: [T::NEG_INFINITY; C],
            hashes: [0; C],
            assignments: [[CLUTTER; Z]; C],
            heap: WorstFirstHeap::new(),
            arrival: [0; C],
            table: [[NONE; C]; 2],
            rows: 0,
            next_arrival: 0,
        }
    }
}

impl<T: Real, const C: usize, const Z: usize> BestChildren<T, C, Z> {
    /// Empties the set for a chain over `rows` measurements.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::CLUTTER;
    /// # use tracker_core::sampler::{BestChildren, association_hash};
    /// # let mut best = BestChildren::<f64, 2, 2>::new();
    /// # best.clear(2);
    /// # for (score, child) in [(-1.0, [0, CLUTTER]), (-3.0, [CLUTTER, 0]), (-2.0, [0, 1])] {
    /// #     best.insert(score, association_hash(&child), &child);
    /// # }
    /// best.clear(1); // now one row
    /// assert!(best.is_empty());
    /// assert!(best.insert(0.0, association_hash(&[CLUTTER]), &[CLUTTER]));
    /// assert_eq!(best.get(0), Some((0.0, &[CLUTTER][..])));
    /// ```
    pub fn clear(&mut self, rows: usize) {
        self.heap.clear();
        self.rows = rows;
        self.next_arrival = 0;
        for half in self.table.iter_mut() {
            half.fill(NONE);
        }
    }

    /// Number of children kept (at most `C`).
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::CLUTTER;
    /// # use tracker_core::sampler::{BestChildren, association_hash};
    /// # let mut best = BestChildren::<f64, 2, 2>::new();
    /// # best.clear(2);
    /// # for (score, child) in [(-1.0, [0, CLUTTER]), (-3.0, [CLUTTER, 0]), (-2.0, [0, 1])] {
    /// #     best.insert(score, association_hash(&child), &child);
    /// # }
    /// assert_eq!(best.len(), 2); // C = 2 of the three offered
    /// ```
    pub fn len(&self) -> usize {
        self.heap.len()
    }

    /// Whether the set is empty.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::CLUTTER;
    /// # use tracker_core::sampler::{BestChildren, association_hash};
    /// # let mut best = BestChildren::<f64, 2, 2>::new();
    /// # best.clear(2);
    /// # for (score, child) in [(-1.0, [0, CLUTTER]), (-3.0, [CLUTTER, 0]), (-2.0, [0, 1])] {
    /// #     best.insert(score, association_hash(&child), &child);
    /// # }
    /// assert!(!best.is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.heap.len() == 0
    }

    /// The lowest score a new child must beat to enter, `-inf` while there is room.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::CLUTTER;
    /// # use tracker_core::sampler::{BestChildren, association_hash};
    /// # let mut best = BestChildren::<f64, 2, 2>::new();
    /// # best.clear(2);
    /// # for (score, child) in [(-1.0, [0, CLUTTER]), (-3.0, [CLUTTER, 0]), (-2.0, [0, 1])] {
    /// #     best.insert(score, association_hash(&child), &child);
    /// # }
    /// assert_eq!(best.threshold(), -2.0);
    /// ```
    #[inline]
    pub fn threshold(&self) -> T {
        match self.heap.root() {
            Some(worst) if self.heap.is_full() => *self.scores.at(usize::from(worst)),
            _ => T::NEG_INFINITY,
        }
    }

    /// The first `rows` entries of a kept assignment.
    #[inline]
    fn prefix<'a>(&self, assignment: &'a [u16; Z]) -> &'a [u16] {
        &assignment[..self.rows.min(Z)]
    }

    /// The kept children as (score, assignment), in no particular order.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::CLUTTER;
    /// # use tracker_core::sampler::{BestChildren, association_hash};
    /// # let mut best = BestChildren::<f64, 2, 2>::new();
    /// # best.clear(2);
    /// # for (score, child) in [(-1.0, [0, CLUTTER]), (-3.0, [CLUTTER, 0]), (-2.0, [0, 1])] {
    /// #     best.insert(score, association_hash(&child), &child);
    /// # }
    /// let mut kept: Vec<(f64, Vec<u16>)> = best.iter().map(|(score, a)| (score, a.to_vec())).collect();
    /// kept.sort_by(|x, y| y.0.total_cmp(&x.0));
    /// assert_eq!(kept, [(-1.0, vec![0, CLUTTER]), (-2.0, vec![0, 1])]);
    /// ```
    pub fn iter(&self) -> impl Iterator<Item = (T, &[u16])> + '_ {
        self.scores
            .iter()
            .zip(&self.assignments)
            .take(self.len())
            .map(move |(&score, assignment)| (score, self.prefix(assignment)))
    }

    /// Kept child `index` as (score, assignment).
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::CLUTTER;
    /// # use tracker_core::sampler::{BestChildren, association_hash};
    /// # let mut best = BestChildren::<f64, 2, 2>::new();
    /// # best.clear(2);
    /// # for (score, child) in [(-1.0, [0, CLUTTER]), (-3.0, [CLUTTER, 0]), (-2.0, [0, 1])] {
    /// #     best.insert(score, association_hash(&child), &child);
    /// # }
    /// assert!(best.get(0).is_some() && best.get(1).is_some());
    /// assert_eq!(best.get(2), None);
    /// ```
    pub fn get(&self, index: usize) -> Option<(T, &[u16])> {
        if index >= self.len() {
            return None;
        }
        Some((*self.scores.get(index)?, self.prefix(self.assignments.get(index)?)))
    }

    /// Slot `slot` (`< 2C`) of the hash table.
    fn table_slot(&self, slot: usize) -> u16 {
        *self.table.at(slot / C).at(slot % C)
    }

    fn set_table_slot(&mut self, slot: usize, value: u16) {
        *self.table.at_mut(slot / C).at_mut(slot % C) = value;
    }

    /// Slot of `hash` with `assignment` in the table, or the empty slot where it would go.
    fn find(&self, hash: u64, assignment: &[u16]) -> (usize, bool) {
        let size = 2 * C;
        let mut slot = (hash % size as u64) as usize;
        // The table is at most half full, so an empty slot is always reached.
        for _ in 0..size {
            let item = self.table_slot(slot);
            if item == NONE {
                return (slot, false);
            }
            let item = usize::from(item);
            if *self.hashes.at(item) == hash && self.prefix(self.assignments.at(item)) == assignment {
                return (slot, true);
            }
            slot = (slot + 1) % size;
        }
        (slot, false)
    }

    /// Whether the child is already kept.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::CLUTTER;
    /// # use tracker_core::sampler::{BestChildren, association_hash};
    /// # let mut best = BestChildren::<f64, 2, 2>::new();
    /// # best.clear(2);
    /// # for (score, child) in [(-1.0, [0, CLUTTER]), (-3.0, [CLUTTER, 0]), (-2.0, [0, 1])] {
    /// #     best.insert(score, association_hash(&child), &child);
    /// # }
    /// assert!(best.contains(association_hash(&[0, 1]), &[0, 1]));
    /// assert!(!best.contains(association_hash(&[CLUTTER, 0]), &[CLUTTER, 0])); // evicted
    /// ```
    pub fn contains(&self, hash: u64, assignment: &[u16]) -> bool {
        self.find(hash, assignment).1
    }

    /// Removes the table entry at `slot` (backward-shift deletion keeps probe chains intact).
    fn remove_slot(&mut self, mut slot: usize) {
        let size = 2 * C;
        self.set_table_slot(slot, NONE);
        let mut next = (slot + 1) % size;
        for _ in 0..size {
            let item = self.table_slot(next);
            if item == NONE {
                return;
            }
            let home = (*self.hashes.at(usize::from(item)) % size as u64) as usize;
            // Move the entry back if its home is not cyclically in (slot, next].
            let distance_to_next = (next + size - home) % size;
            let distance_to_slot = (slot + size - home) % size;
            if distance_to_slot < distance_to_next {
                self.set_table_slot(slot, item);
                self.set_table_slot(next, NONE);
                slot = next;
            }
            next = (next + 1) % size;
        }
    }

    /// Offers a feasible child with exact `score`; keeps it if it is new and beats the worst kept one.
    /// Returns whether it was kept.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::CLUTTER;
    /// # use tracker_core::sampler::{BestChildren, association_hash};
    /// # let mut best = BestChildren::<f64, 2, 2>::new();
    /// # best.clear(2);
    /// # for (score, child) in [(-1.0, [0, CLUTTER]), (-3.0, [CLUTTER, 0]), (-2.0, [0, 1])] {
    /// #     best.insert(score, association_hash(&child), &child);
    /// # }
    /// assert!(best.insert(-1.5, association_hash(&[1, 0]), &[1, 0])); // beats −2, which leaves
    /// assert!(!best.contains(association_hash(&[0, 1]), &[0, 1]));
    /// assert_eq!(best.threshold(), -1.5);
    /// ```
    pub fn insert(&mut self, score: T, hash: u64, assignment: &[u16]) -> bool {
        if self.contains(hash, assignment) {
            return false;
        }
        self.insert_absent(score, hash, assignment)
    }

    /// As [`BestChildren::insert`], for a child the caller knows is not kept.
    pub(crate) fn insert_absent(&mut self, score: T, hash: u64, assignment: &[u16]) -> bool {
        if C == 0 || !(score > self.threshold()) {
            return false;
        }
        let replaced = self.heap.is_full();
        let item = match self.heap.root() {
            Some(worst) if replaced => {
                // Evict the worst kept child.
                let worst = usize::from(worst);
                let worst_assignment = *self.assignments.at(worst);
                let (slot, _) = self.find(*self.hashes.at(worst), self.prefix(&worst_assignment));
                self.remove_slot(slot);
                worst
            }
            _ => self.heap.len(),
        };
        *self.scores.at_mut(item) = score;
        *self.hashes.at_mut(item) = hash;
        copy_prefix(self.assignments.at_mut(item), assignment);
        *self.arrival.at_mut(item) = self.next_arrival;
        self.next_arrival = self.next_arrival.wrapping_add(1);
        let (slot, _) = self.find(hash, assignment);
        self.set_table_slot(slot, item as u16);
        let (scores, arrival) = (&self.scores, &self.arrival);
        let worse = |a: u16, b: u16| ranks_below(scores, arrival, a, b);
        if replaced {
            self.heap.root_replaced(worse);
        } else {
            self.heap.push(item as u16, worse);
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand_core::Rng;
    use std::collections::{BTreeMap, BTreeSet};

    #[test]
    fn best_children_keeps_the_top_c_distinct_children() {
        let mut seed = crate::random::test_stream(11);
        for trial in 0..200 {
            let mut best = BestChildren::<f64, 5, 3>::default();
            best.clear(3);
            let mut offered: Vec<(f64, usize, [u16; 3])> = vec![];
            for arrival in 0..60 {
                let a = [(seed.next_u64() % 4) as u16, (seed.next_u64() % 4) as u16, (seed.next_u64() % 4) as u16];
                // Scores are a function of the child, so duplicates carry the same score.
                let score = ((a[0] * 7 + a[1] * 3 + a[2]) % 11) as f64 + (trial % 3) as f64;
                best.insert(score, association_hash(&a), &a);
                offered.push((score, arrival, a));
            }
            // Expected: distinct children by first arrival, top 5 by (score desc, arrival asc).
            let mut first: BTreeMap<[u16; 3], (f64, usize)> = BTreeMap::new();
            for (score, arrival, a) in &offered {
                first.entry(*a).or_insert((*score, *arrival));
            }
            let mut ranked: Vec<_> = first.iter().map(|(a, (s, t))| (*s, *t, *a)).collect();
            ranked.sort_by(|x, y| y.0.total_cmp(&x.0).then(x.1.cmp(&y.1)));
            let expected: BTreeSet<[u16; 3]> = ranked.iter().take(5).map(|r| r.2).collect();
            let got: BTreeSet<[u16; 3]> = best.iter().map(|(_, a)| [a[0], a[1], a[2]]).collect();
            let expected_scores: Vec<f64> = ranked.iter().take(5).map(|r| r.0).collect();
            let mut got_scores: Vec<f64> = best.iter().map(|(s, _)| s).collect();
            got_scores.sort_by(|a, b| b.total_cmp(a));
            assert_eq!(got_scores, expected_scores, "trial {trial}");
            assert_eq!(got.len(), 5);
            // Same scores; the set may differ only among children tied with the worst kept score.
            let worst = expected_scores[4];
            for a in got.symmetric_difference(&expected) {
                assert_eq!(first[a].0, worst, "trial {trial}: {a:?}");
            }
        }
    }
}
