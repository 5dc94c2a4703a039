//! What one scan did, in a small `Copy` value returned by [`crate::Tracker::step`].

use crate::NumericalError;
use crate::store::TrackLabel;

/// Tracks dropped in one scan by [`crate::config::NumericalFailure::DropTrack`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct NumericalDrops {
    /// Distinct tracks dropped.
    pub count: usize,
    /// The first dropped track (in track-store order) and why.
    pub first: Option<(TrackLabel, NumericalError)>,
}

/// Summary of one processed scan.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct StepReport<T> {
    /// Number of scans processed so far, this one included.
    pub scan: u64,
    /// Measurements in the scan.
    pub measurements: usize,
    /// Hypotheses kept (≤ H).
    pub hypotheses: usize,
    /// Distinct tracks in the store (≤ K).
    pub tracks: usize,
    /// Children with non-zero weight offered by the child generator, over all parents and events.
    pub children: u64,
    /// Fraction of the scan's total child weight held by the kept hypotheses: 1 when nothing was pruned.
    pub captured_mass: T,
    /// Kept children that held exactly the same tracks as a better one and were merged into it.
    pub merged_children: usize,
    /// Kept children dropped because their tracks did not fit the store
    /// ([`crate::StoreOverflow::PruneChildren`]).
    pub children_dropped_for_store: usize,
    /// Birth events not generated because their parent already held `N` objects.
    pub births_beyond_object_capacity: u64,
    /// Metropolis steps taken in this scan (0 with exhaustive children).
    pub sampler_steps: u64,
    /// Expected number of objects after the scan.
    pub expected_cardinality: T,
}
