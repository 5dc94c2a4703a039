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
///
/// # Examples
/// One object, one measurement and exhaustive children: two children (the object took it, or it is
/// clutter), both kept.
/// ```
/// # use nalgebra::SVector;
/// # use tracker_core::LinearTracker;
/// # let (config, object) = (tracker_core::examples::config(), tracker_core::examples::object());
/// # let mut tracker = LinearTracker::<f64, 8, 4, 4, 16, 1>::with_objects(config, &[object], 0.0)?;
/// let report = tracker.step(1.0, &[SVector::from([1.0, 0.0])])?;
/// assert_eq!((report.scan, report.measurements, report.children, report.hypotheses), (1, 1, 2, 2));
/// assert_eq!(report.captured_mass, 1.0); // nothing pruned
/// assert_eq!((report.merged_children, report.children_dropped_for_store, report.sampler_steps), (0, 0, 0));
/// assert_eq!(report.expected_cardinality, 1.0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
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
    /// What the scan did to the pool of measurement-driven birth cells (all zero without measured births).
    pub birth_pool: crate::pool::PoolUpdate,
    /// Metropolis moves made in this scan (0 with exhaustive children); never more than the budget given
    /// to [`crate::Tracker::step_with_budget`].
    pub sampler_steps: u64,
    /// Tracks dropped for a numerical failure ([`crate::config::NumericalFailure::DropTrack`]).
    pub numerical_drops: NumericalDrops,
    /// Tracks declared lost and dropped from every hypothesis ([`crate::TrackLoss`]).
    pub lost_tracks: usize,
    /// Expected number of objects after the scan.
    pub expected_cardinality: T,
}
