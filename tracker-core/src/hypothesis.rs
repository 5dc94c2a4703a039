//! Hypotheses: weighted sets of tracks.
//!
//! A hypothesis is one term of the multi-object posterior Σ_h w_h Π_i p_h,i(x_i) ([000] (14)): a weight
//! and the store slots of its objects' tracks. Its objects are kept sorted by label, so two hypotheses
//! that hold the same tracks have the same slot list and can be merged exactly (their components are
//! identical, so their weights add).

use crate::index::copy_prefix;
use crate::real::Real;

/// One hypothesis: a log-weight and up to `N` track slots sorted by label.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hypothesis<T, const N: usize> {
    /// Normalised log-weight ln w.
    pub log_weight: T,
    len: u16,
    slots: [u16; N],
}

impl<T: Real, const N: usize> Default for Hypothesis<T, N> {
    fn default() -> Self {
        Self::EMPTY
    }
}

impl<T: Real, const N: usize> Hypothesis<T, N> {
    const EMPTY: Self = Self { log_weight: T::NEG_INFINITY, len: 0, slots: [0; N] };

    /// A hypothesis with `log_weight` holding `slots` (at most `N`; the caller sorts them by label).
    pub(crate) fn new(log_weight: T, slots: &[u16]) -> Self {
        let len = slots.len().min(N);
        let mut h = Self { log_weight, len: len as u16, slots: [0; N] };
        copy_prefix(&mut h.slots, slots);
        h
    }

    /// The store slots of the hypothesis's tracks, in label order.
    pub fn slots(&self) -> &[u16] {
        &self.slots[..self.len()]
    }

    /// Number of objects (at most `N`).
    pub fn len(&self) -> usize {
        // The `min` only shows the optimiser the invariant `len ≤ N`.
        usize::from(self.len).min(N)
    }

    /// Whether the hypothesis holds no object.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
}

/// Up to `H` hypotheses, best first after every scan.
#[derive(Debug, Clone)]
pub struct HypothesisSet<T, const N: usize, const H: usize> {
    items: heapless::Vec<Hypothesis<T, N>, H>,
}

impl<T: Real, const N: usize, const H: usize> Default for HypothesisSet<T, N, H> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T: Real, const N: usize, const H: usize> HypothesisSet<T, N, H> {
    /// An empty set (usable in a `const` context).
    pub const fn new() -> Self {
        Self { items: heapless::Vec::new() }
    }

    /// The hypotheses.
    pub fn as_slice(&self) -> &[Hypothesis<T, N>] {
        &self.items
    }

    pub(crate) fn as_mut_slice(&mut self) -> &mut [Hypothesis<T, N>] {
        &mut self.items
    }

    /// Number of hypotheses (at most `H`).
    pub fn len(&self) -> usize {
        // The `min` only shows the optimiser the invariant `len ≤ H`.
        self.items.len().min(H)
    }

    /// Whether there is no hypothesis.
    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    pub(crate) fn clear(&mut self) {
        self.items.clear();
    }

    /// Appends a hypothesis and returns its index, or hands it back when the set is full.
    pub(crate) fn push(&mut self, hypothesis: Hypothesis<T, N>) -> Result<usize, Hypothesis<T, N>> {
        let index = self.items.len();
        self.items.push(hypothesis).map(|()| index)
    }
}
