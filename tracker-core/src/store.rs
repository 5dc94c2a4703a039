//! The track store shared by all hypotheses.
//!
//! A track is one object's Gaussian under one association history. Hypotheses hold indices into the store,
//! so a track held by many hypotheses is stored, predicted and scored once. The store is rebuilt every
//! scan from the kept children: a new track is keyed by (source track or birth cell, measurement or
//! missed), so two children that extend the same track with the same measurement share the result.

use crate::gaussian::Gaussian;
use crate::real::Real;

/// The identity of an object: the same across scans and across hypotheses. Prior objects carry the
/// labels the caller gives them; every birth gets a fresh label.
///
/// # Examples
/// ```
/// use tracker_core::TrackLabel;
/// assert_eq!(TrackLabel(3).to_string(), "#3");
/// assert!(TrackLabel(2) < TrackLabel(10));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TrackLabel(pub u32);

impl core::fmt::Display for TrackLabel {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "#{}", self.0)
    }
}

/// One track: a labelled Gaussian and the total weight of the hypotheses that hold it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Track<T: Real, const S: usize> {
    /// The object's label.
    pub label: TrackLabel,
    /// The object's posterior Gaussian under this track's association history.
    pub state: Gaussian<T, S>,
    /// Existence probability of this track: the total weight of the hypotheses that hold it.
    pub existence: T,
    /// Consecutive scans in which the track was in view with no measurement in its gate
    /// ([`crate::TrackLoss`]).
    pub unseen_scans: u16,
}

impl<T: Real, const S: usize> Default for Track<T, S> {
    fn default() -> Self {
        Self::EMPTY
    }
}

impl<T: Real, const S: usize> Track<T, S> {
    const EMPTY: Self = Self { label: TrackLabel(0), state: Gaussian::ZERO, existence: T::ZERO, unseen_scans: 0 };
}

/// The tracks of a scan, at most `K`; a track's slot is its index.
#[derive(Debug, Clone)]
pub struct TrackStore<T: Real, const S: usize, const K: usize> {
    tracks: heapless::Vec<Track<T, S>, K>,
}

impl<T: Real, const S: usize, const K: usize> Default for TrackStore<T, S, K> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T: Real, const S: usize, const K: usize> TrackStore<T, S, K> {
    /// An empty store (usable in a `const` context).
    pub const fn new() -> Self {
        Self { tracks: heapless::Vec::new() }
    }

    /// The live tracks.
    pub fn as_slice(&self) -> &[Track<T, S>] {
        &self.tracks
    }

    pub(crate) fn as_mut_slice(&mut self) -> &mut [Track<T, S>] {
        &mut self.tracks
    }

    /// Number of live tracks (at most `K`).
    pub fn len(&self) -> usize {
        // The `min` only shows the optimiser the invariant `len ≤ K`.
        self.tracks.len().min(K)
    }

    /// Whether no track is live.
    pub fn is_empty(&self) -> bool {
        self.tracks.is_empty()
    }

    pub(crate) fn clear(&mut self) {
        self.tracks.clear();
    }

    /// Appends a track and returns its slot, or hands it back when the store is full.
    pub(crate) fn push(&mut self, track: Track<T, S>) -> Result<u16, Track<T, S>> {
        let slot = self.tracks.len() as u16;
        self.tracks.push(track).map(|()| slot)
    }
}
