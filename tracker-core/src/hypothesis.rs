//! Hypotheses: weighted sets of tracks.
//!
//! A hypothesis is one term of the multi-object posterior Σ_h w_h Π_i p_h,i(x_i) ([000] (14)): a weight
//! and the store slots of its objects' tracks. Its objects are kept sorted by label, so two hypotheses
//! that hold the same tracks have the same slot list and can be merged exactly (their components are
//! identical, so their weights add).

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
        Self { log_weight: T::NEG_INFINITY, len: 0, slots: [0; N] }
    }
}

impl<T: Real, const N: usize> Hypothesis<T, N> {
    /// A hypothesis with `log_weight` holding `slots` (at most `N`; the caller sorts them by label).
    pub(crate) fn new(log_weight: T, slots: &[u16]) -> Self {
        let mut h = Self { log_weight, len: slots.len() as u16, slots: [0; N] };
        h.slots[..slots.len()].copy_from_slice(slots);
        h
    }

    /// The store slots of the hypothesis's tracks, in label order.
    pub fn slots(&self) -> &[u16] {
        &self.slots[..self.len as usize]
    }

    /// Number of objects.
    pub fn len(&self) -> usize {
        self.len as usize
    }

    /// Whether the hypothesis holds no object.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
}

/// Up to `H` hypotheses, best first after every scan.
#[derive(Debug, Clone)]
pub struct HypothesisSet<T, const N: usize, const H: usize> {
    items: [Hypothesis<T, N>; H],
    len: usize,
}

impl<T: Real, const N: usize, const H: usize> Default for HypothesisSet<T, N, H> {
    fn default() -> Self {
        Self { items: [Hypothesis::default(); H], len: 0 }
    }
}

impl<T: Real, const N: usize, const H: usize> HypothesisSet<T, N, H> {
    /// The hypotheses.
    pub fn as_slice(&self) -> &[Hypothesis<T, N>] {
        &self.items[..self.len]
    }

    pub(crate) fn as_mut_slice(&mut self) -> &mut [Hypothesis<T, N>] {
        &mut self.items[..self.len]
    }

    /// Number of hypotheses.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether there is no hypothesis.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    pub(crate) fn clear(&mut self) {
        self.len = 0;
    }

    /// Appends a hypothesis and returns its index, or hands it back when the set is full.
    pub(crate) fn push(&mut self, hypothesis: Hypothesis<T, N>) -> Result<usize, Hypothesis<T, N>> {
        if self.len == H {
            return Err(hypothesis);
        }
        self.items[self.len] = hypothesis;
        self.len += 1;
        Ok(self.len - 1)
    }
}
