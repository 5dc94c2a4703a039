//! Selection of the H∞ best children of a scan, and the scan's normaliser.
//!
//! [`TopChildren`] is the [`ChildSink`] of a scan. It keeps the `H` children of largest log-weight in a
//! fixed-size binary min-heap (the worst kept child at the root) and accumulates the log-sum-exp of
//! **every** child offered, over all parents and events: the one global normaliser of docs/maths.md §4.6.
//! Children of one (parent, event) reach it through an [`EventSink`], which knows their origin.
//! Equal weights are ordered by arrival (the generator's deterministic enumeration order), so the
//! selection is a total order and the same inputs always keep the same children.

use crate::children::ChildSink;
use crate::index::{At, WorstFirstHeap, copy_prefix, insertion_sort_by};
use crate::real::{LogSumExp, Real, ln};
pub use crate::weight::Event;
use core::cmp::Ordering;
use rand_core::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

/// One kept child: where it comes from and how it associates the scan.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Candidate<T, const Z: usize> {
    /// Unnormalised log-weight ln w̃.
    pub log_weight: T,
    /// Selection key: ln w̃, plus a standard Gumbel variate when selecting by sampling.
    pub key: T,
    /// Arrival index within the scan (the tie-break: earlier wins).
    pub sequence: u64,
    /// Index of the parent hypothesis.
    pub parent: u16,
    /// The birth/death event.
    pub event: Event,
    /// Per measurement, the association-matrix column it takes or [`crate::association::CLUTTER`].
    pub assignment: [u16; Z],
}

impl<T: Real, const Z: usize> Default for Candidate<T, Z> {
    fn default() -> Self {
        Self::EMPTY
    }
}

impl<T: Real, const Z: usize> Candidate<T, Z> {
    const EMPTY: Self = Self {
        log_weight: T::NEG_INFINITY,
        key: T::NEG_INFINITY,
        sequence: 0,
        parent: 0,
        event: Event::None,
        assignment: [0; Z],
    };

    /// Total order "better than": larger weight, then earlier arrival.
    fn better_than(&self, other: &Self) -> bool {
        match self.key.partial_cmp(&other.key) {
            Some(Ordering::Greater) => true,
            Some(Ordering::Less) => false,
            _ => self.sequence < other.sequence,
        }
    }
}

/// The best `H` children of a scan and the log-sum-exp of all children.
///
/// # Examples
/// ```
/// use tracker_core::children::ChildSink;
/// use tracker_core::selection::TopChildren;
/// let mut top = TopChildren::<f64, 2, 1>::new();
/// for (column, log_weight) in [1.0, 4.0, 2.0, 3.0].into_iter().enumerate() {
///     top.offer(log_weight, &[column as u16]);
/// }
/// let mut order = [0; 2];
/// let kept = top.best_first(&mut order);
/// let best: Vec<(f64, u16)> =
///     order[..kept].iter().map(|&i| top.kept()[usize::from(i)]).map(|c| (c.log_weight, c.assignment[0])).collect();
/// assert_eq!(best, [(4.0, 1), (3.0, 3)]);
/// // The normaliser counts every child offered, kept or not.
/// let all: f64 = [1.0f64, 4.0, 2.0, 3.0].iter().map(|w| w.exp()).sum();
/// assert!((top.log_total() - all.ln()).abs() < 1e-12);
/// ```
#[derive(Debug, Clone)]
pub struct TopChildren<T, const H: usize, const Z: usize> {
    items: [Candidate<T, Z>; H],
    /// Indices into `items` by "better than", the worst kept child at the root.
    heap: WorstFirstHeap<H>,
    offered: u64,
    total: LogSumExp<T>,
    /// When selecting by sampling: the stream of Gumbel perturbations.
    gumbel: Option<Xoshiro256PlusPlus>,
}

impl<T: Real, const H: usize, const Z: usize> Default for TopChildren<T, H, Z> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T: Real, const H: usize, const Z: usize> TopChildren<T, H, Z> {
    /// An empty selection.
    ///
    /// # Examples
    /// ```
    /// use tracker_core::selection::TopChildren;
    /// let top = TopChildren::<f32, 4, 8>::new();
    /// assert!(top.is_empty());
    /// assert_eq!(top.log_total(), f32::NEG_INFINITY);
    /// ```
    pub const fn new() -> Self {
        Self {
            items: [Candidate::EMPTY; H],
            heap: WorstFirstHeap::new(),
            offered: 0,
            total: LogSumExp::new(),
            gumbel: None,
        }
    }

    /// Empties the selection for a new scan that keeps the H children of largest weight.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::children::ChildSink;
    /// # use tracker_core::selection::TopChildren;
    /// # // Five children of one measurement; H = 2 are kept.
    /// # let mut top = TopChildren::<f64, 2, 1>::new();
    /// # for (column, log_weight) in [1.0, 4.0, 2.0, f64::NEG_INFINITY, 3.0].into_iter().enumerate() {
    /// #     top.offer(log_weight, &[column as u16]);
    /// # }
    /// top.clear();
    /// assert_eq!((top.len(), top.offered()), (0, 0));
    /// assert_eq!(top.threshold(), f64::NEG_INFINITY);
    /// ```
    pub fn clear(&mut self) {
        self.heap.clear();
        self.offered = 0;
        self.total = LogSumExp::new();
        self.gumbel = None;
    }

    /// Empties the selection for a new scan that draws H children without replacement with probability
    /// proportional to weight: it keeps the H largest ln w̃ + G with G standard Gumbel (Gumbel-top-k).
    ///
    /// # Examples
    /// Each child is kept with a probability that grows with its weight; the same seed keeps the same children:
    /// ```
    /// use tracker_core::children::ChildSink;
    /// use tracker_core::selection::TopChildren;
    /// let pick = |seed| {
    ///     let mut top = TopChildren::<f64, 1, 1>::new();
    ///     top.clear_sampling(seed);
    ///     for (column, log_weight) in [0.0, 1.0, 2.0].into_iter().enumerate() {
    ///         top.offer(log_weight, &[column as u16]);
    ///     }
    ///     assert!(!top.selects_by_weight());
    ///     top.kept()[0].assignment[0]
    /// };
    /// assert_eq!(pick(7), pick(7));
    /// let picks: Vec<u16> = (0..200).map(pick).collect();
    /// let count = |column| picks.iter().filter(|&&c| c == column).count();
    /// assert!(count(2) > count(0)); // e² against e⁰, over 200 draws
    /// ```
    pub fn clear_sampling(&mut self, seed: u64) {
        self.clear();
        self.gumbel = Some(Xoshiro256PlusPlus::seed_from_u64(seed));
    }

    /// The sink of the children of `parent` under `event`.
    ///
    /// # Examples
    /// ```
    /// use tracker_core::children::ChildSink;
    /// use tracker_core::selection::{Event, TopChildren};
    /// let mut top = TopChildren::<f64, 4, 1>::new();
    /// top.for_event(0, Event::None).offer(-1.0, &[0]);
    /// top.for_event(3, Event::Death { object: 1 }).offer(-2.0, &[0]);
    /// let origins: Vec<(u16, Event)> = top.kept().iter().map(|c| (c.parent, c.event)).collect();
    /// assert!(origins.contains(&(3, Event::Death { object: 1 })));
    /// assert_eq!(top.offered(), 2);
    /// ```
    pub fn for_event(&mut self, parent: u16, event: Event) -> EventSink<'_, T, H, Z> {
        EventSink { top: self, parent, event }
    }

    /// Number of children kept (at most `H`).
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::children::ChildSink;
    /// # use tracker_core::selection::TopChildren;
    /// # // Five children of one measurement; H = 2 are kept.
    /// # let mut top = TopChildren::<f64, 2, 1>::new();
    /// # for (column, log_weight) in [1.0, 4.0, 2.0, f64::NEG_INFINITY, 3.0].into_iter().enumerate() {
    /// #     top.offer(log_weight, &[column as u16]);
    /// # }
    /// assert_eq!(top.len(), 2); // H = 2 of the 4 possible children
    /// ```
    pub fn len(&self) -> usize {
        self.heap.len()
    }

    /// Whether no child is kept.
    ///
    /// # Examples
    /// ```
    /// use tracker_core::children::ChildSink;
    /// use tracker_core::selection::TopChildren;
    /// let mut top = TopChildren::<f64, 2, 1>::new();
    /// top.offer(f64::NEG_INFINITY, &[0]); // an impossible child is not offered
    /// assert!(top.is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.heap.len() == 0
    }

    /// Number of children offered (with non-zero weight).
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::children::ChildSink;
    /// # use tracker_core::selection::TopChildren;
    /// # // Five children of one measurement; H = 2 are kept.
    /// # let mut top = TopChildren::<f64, 2, 1>::new();
    /// # for (column, log_weight) in [1.0, 4.0, 2.0, f64::NEG_INFINITY, 3.0].into_iter().enumerate() {
    /// #     top.offer(log_weight, &[column as u16]);
    /// # }
    /// assert_eq!(top.offered(), 4); // the impossible child is not counted
    /// ```
    pub fn offered(&self) -> u64 {
        self.offered
    }

    /// The key a new child must beat to be kept (`-inf` while there is room). With
    /// [`TopChildren::clear_sampling`] keys are perturbed, so this bounds keys, not weights.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::children::ChildSink;
    /// # use tracker_core::selection::TopChildren;
    /// # // Five children of one measurement; H = 2 are kept.
    /// # let mut top = TopChildren::<f64, 2, 1>::new();
    /// # for (column, log_weight) in [1.0, 4.0, 2.0, f64::NEG_INFINITY, 3.0].into_iter().enumerate() {
    /// #     top.offer(log_weight, &[column as u16]);
    /// # }
    /// assert_eq!(top.threshold(), 3.0); // the worse of the two kept
    /// ```
    pub fn threshold(&self) -> T {
        match self.heap.root() {
            Some(worst) if self.heap.is_full() => self.items.at(usize::from(worst)).key,
            _ => T::NEG_INFINITY,
        }
    }

    /// Whether keys are weights (selection by largest weight).
    ///
    /// # Examples
    /// ```
    /// use tracker_core::selection::TopChildren;
    /// let mut top = TopChildren::<f64, 2, 1>::new();
    /// assert!(top.selects_by_weight());
    /// top.clear_sampling(1);
    /// assert!(!top.selects_by_weight());
    /// ```
    pub fn selects_by_weight(&self) -> bool {
        self.gumbel.is_none()
    }

    /// The running sum of w̃ over every child offered (and reported unoffered).
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::children::ChildSink;
    /// # use tracker_core::selection::TopChildren;
    /// # // Five children of one measurement; H = 2 are kept.
    /// # let mut top = TopChildren::<f64, 2, 1>::new();
    /// # for (column, log_weight) in [1.0, 4.0, 2.0, f64::NEG_INFINITY, 3.0].into_iter().enumerate() {
    /// #     top.offer(log_weight, &[column as u16]);
    /// # }
    /// // The kept children's share of the total (the tracker's captured mass).
    /// let mut kept = tracker_core::real::LogSumExp::new();
    /// for child in top.kept() {
    ///     kept.add(child.log_weight);
    /// }
    /// let share = kept.log_ratio(top.total()).exp();
    /// let expected = (4f64.exp() + 3f64.exp()) / (1f64.exp() + 4f64.exp() + 2f64.exp() + 3f64.exp());
    /// assert!((share - expected).abs() < 1e-12);
    /// ```
    pub fn total(&self) -> &LogSumExp<T> {
        &self.total
    }

    /// ln Σ w̃ over every child offered.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::children::ChildSink;
    /// # use tracker_core::selection::TopChildren;
    /// # // Five children of one measurement; H = 2 are kept.
    /// # let mut top = TopChildren::<f64, 2, 1>::new();
    /// # for (column, log_weight) in [1.0, 4.0, 2.0, f64::NEG_INFINITY, 3.0].into_iter().enumerate() {
    /// #     top.offer(log_weight, &[column as u16]);
    /// # }
    /// let all: f64 = [1.0f64, 4.0, 2.0, 3.0].iter().map(|w| w.exp()).sum();
    /// assert!((top.log_total() - all.ln()).abs() < 1e-12);
    /// ```
    pub fn log_total(&self) -> T {
        self.total.value()
    }

    /// The kept children, in no particular order.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::children::ChildSink;
    /// # use tracker_core::selection::TopChildren;
    /// # // Five children of one measurement; H = 2 are kept.
    /// # let mut top = TopChildren::<f64, 2, 1>::new();
    /// # for (column, log_weight) in [1.0, 4.0, 2.0, f64::NEG_INFINITY, 3.0].into_iter().enumerate() {
    /// #     top.offer(log_weight, &[column as u16]);
    /// # }
    /// let mut columns: Vec<u16> = top.kept().iter().map(|c| c.assignment[0]).collect();
    /// columns.sort();
    /// assert_eq!(columns, [1, 4]);
    /// ```
    pub fn kept(&self) -> &[Candidate<T, Z>] {
        &self.items[..self.len()]
    }

    /// Writes the indices of the kept children into `order`, best first, and returns how many.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::children::ChildSink;
    /// # use tracker_core::selection::TopChildren;
    /// # // Five children of one measurement; H = 2 are kept.
    /// # let mut top = TopChildren::<f64, 2, 1>::new();
    /// # for (column, log_weight) in [1.0, 4.0, 2.0, f64::NEG_INFINITY, 3.0].into_iter().enumerate() {
    /// #     top.offer(log_weight, &[column as u16]);
    /// # }
    /// let mut order = [0; 2];
    /// assert_eq!(top.best_first(&mut order), 2);
    /// let weights: Vec<f64> = order.iter().map(|&i| top.kept()[usize::from(i)].log_weight).collect();
    /// assert_eq!(weights, [4.0, 3.0]);
    /// ```
    pub fn best_first(&self, order: &mut [u16; H]) -> usize {
        let len = self.len();
        for (slot, index) in order.iter_mut().zip(0u16..).take(len) {
            *slot = index;
        }
        // "Better than" is a strict total order (arrivals are distinct): the sorted order is unique.
        insertion_sort_by(&mut order[..len], |&a, &b| {
            self.items.at(usize::from(a)).better_than(self.items.at(usize::from(b)))
        });
        len
    }

    /// Reports the mass of children that exist but were not offered.
    ///
    /// # Examples
    /// ```
    /// use tracker_core::selection::TopChildren;
    /// let mut top = TopChildren::<f64, 2, 1>::new();
    /// top.unoffered(2f64.ln());
    /// top.unoffered(3f64.ln());
    /// assert!((top.log_total() - 5f64.ln()).abs() < 1e-15);
    /// assert_eq!((top.len(), top.offered()), (0, 0)); // counted in the total only
    /// ```
    pub fn unoffered(&mut self, log_mass: T) {
        self.total.add(log_mass);
    }

    /// Offers the child of `parent` under `event` with `log_weight` and `assignment`; keeps it if it is
    /// among the best `H` so far.
    ///
    /// # Examples
    /// ```
    /// use tracker_core::association::CLUTTER;
    /// use tracker_core::selection::{Event, TopChildren};
    /// let mut top = TopChildren::<f64, 1, 2>::new();
    /// top.offer_child(0, Event::None, -3.0, &[0, CLUTTER]);
    /// top.offer_child(1, Event::Birth { cell: 0 }, -3.0, &[1, 0]); // a tie: the earlier child stays
    /// top.offer_child(2, Event::None, -1.0, &[CLUTTER, CLUTTER]);
    /// let best = top.kept()[0];
    /// assert_eq!((best.parent, best.log_weight, best.assignment), (2, -1.0, [CLUTTER, CLUTTER]));
    /// ```
    pub fn offer_child(&mut self, parent: u16, event: Event, log_weight: T, assignment: &[u16]) {
        if log_weight == T::NEG_INFINITY {
            return;
        }
        self.total.add(log_weight);
        let key = match &mut self.gumbel {
            None => log_weight,
            Some(rng) => {
                // G = −ln(−ln U), U uniform in (0, 1).
                let uniform = ((rng.next_u64() >> 11) as f64 + 0.5) * (1.0 / (1u64 << 53) as f64);
                log_weight - ln(-ln(T::of_f64(uniform)))
            }
        };
        let mut candidate = Candidate { log_weight, key, sequence: self.offered, parent, event, assignment: [0; Z] };
        self.offered += 1;
        let items = &mut self.items;
        if !self.heap.is_full() {
            let index = self.heap.len();
            copy_prefix(&mut candidate.assignment, assignment);
            *items.at_mut(index) = candidate;
            self.heap.push(index as u16, |a, b| ranks_below(items, a, b));
        } else if let Some(worst) = self.heap.root() {
            let worst = items.at_mut(usize::from(worst));
            if !candidate.better_than(worst) {
                return;
            }
            copy_prefix(&mut candidate.assignment, assignment);
            *worst = candidate;
            self.heap.root_replaced(|a, b| ranks_below(items, a, b));
        }
    }
}

/// Whether kept child `a` ranks below `b`.
#[inline]
fn ranks_below<T: Real, const H: usize, const Z: usize>(items: &[Candidate<T, Z>; H], a: u16, b: u16) -> bool {
    items.at(usize::from(b)).better_than(items.at(usize::from(a)))
}

/// The sink of one (parent, event)'s children: offers them to the scan's [`TopChildren`] with their origin.
///
/// # Examples
/// A generator fills it like any sink; the children carry their (parent, event):
/// ```
/// use tracker_core::association::AssociationMatrix;
/// use tracker_core::children::{ChildGenerator, ExhaustiveChildren};
/// use tracker_core::selection::{Event, TopChildren};
/// let mut matrix = AssociationMatrix::<f64, 1, 1>::new(1, 1, 0.0);
/// matrix.set_column(0, &[1.0], false);
/// let mut top = TopChildren::<f64, 4, 1>::new();
/// let mut sink = top.for_event(5, Event::Birth { cell: 2 });
/// ExhaustiveChildren::new(100).generate(&matrix, &mut sink)?;
/// assert_eq!(sink.top().offered(), 2);
/// assert!(top.kept().iter().all(|c| c.parent == 5 && c.event == Event::Birth { cell: 2 }));
/// # Ok::<(), tracker_core::children::GenerateError>(())
/// ```
#[derive(Debug)]
pub struct EventSink<'a, T, const H: usize, const Z: usize> {
    top: &'a mut TopChildren<T, H, Z>,
    parent: u16,
    event: Event,
}

impl<T: Real, const H: usize, const Z: usize> EventSink<'_, T, H, Z> {
    /// The scan's selection behind this sink.
    ///
    /// # Examples
    /// ```
    /// use tracker_core::children::ChildSink;
    /// use tracker_core::selection::{Event, TopChildren};
    /// let mut top = TopChildren::<f64, 4, 1>::new();
    /// let mut sink = top.for_event(0, Event::None);
    /// sink.offer(0.5, &[0]);
    /// assert_eq!(sink.top().len(), 1);
    /// ```
    pub fn top(&self) -> &TopChildren<T, H, Z> {
        self.top
    }
}

impl<T: Real, const H: usize, const Z: usize> ChildSink<T> for EventSink<'_, T, H, Z> {
    fn offer(&mut self, log_weight: T, assignment: &[u16]) {
        self.top.offer_child(self.parent, self.event, log_weight, assignment);
    }

    fn unoffered(&mut self, log_mass: T) {
        self.top.unoffered(log_mass);
    }
}

/// A [`TopChildren`] used directly as a sink takes the children of a single matrix: parent 0, no event.
impl<T: Real, const H: usize, const Z: usize> ChildSink<T> for TopChildren<T, H, Z> {
    fn offer(&mut self, log_weight: T, assignment: &[u16]) {
        self.offer_child(0, Event::None, log_weight, assignment);
    }

    fn unoffered(&mut self, log_mass: T) {
        TopChildren::unoffered(self, log_mass);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keeps_the_best_h_with_earlier_arrival_winning_ties() {
        let mut top = TopChildren::<f64, 3, 1>::new();
        for (i, w) in [1.0, 5.0, 3.0, 5.0, 0.0, 4.0, 3.0].iter().enumerate() {
            top.offer(*w, &[i as u16]);
        }
        let mut order = [0u16; 3];
        let n = top.best_first(&mut order);
        let kept: std::vec::Vec<_> = order[..n]
            .iter()
            .map(|&i| (top.kept()[i as usize].log_weight, top.kept()[i as usize].assignment[0]))
            .collect();
        assert_eq!(kept, vec![(5.0, 1), (5.0, 3), (4.0, 5)]);
        let direct = [1.0f64, 5.0, 3.0, 5.0, 0.0, 4.0, 3.0].iter().map(|w| w.exp()).sum::<f64>().ln();
        assert!((top.log_total() - direct).abs() < 1e-14);
        assert_eq!(top.offered(), 7);
    }
}
