//! Which tracker runs, and what one step of any tracker reports.

/// Which tracker to run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum TrackerKind {
    /// The unbounded exhaustive reference (every child of every parent).
    Reference,
    /// tracker-core with exhaustive children, capped at H∞ hypotheses.
    Homht,
    /// tracker-core with R-FISST's sampled children (Metropolis, by clusters), capped at H∞.
    Rfisst,
}

impl TrackerKind {
    /// The name written to outputs.
    pub fn name(self) -> &'static str {
        match self {
            TrackerKind::Reference => "reference",
            TrackerKind::Homht => "homht",
            TrackerKind::Rfisst => "rfisst",
        }
    }
}

/// What one scan did, in tracker-independent terms.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepInfo {
    /// Children with non-zero weight generated.
    pub children: u64,
    /// Hypotheses kept.
    pub hypotheses: usize,
    /// Fraction of the children's weight kept.
    pub captured_mass: f64,
    /// Whether the reference's memory budget forced pruning.
    pub budget_reached: bool,
    /// Tracks the core dropped for a numerical failure (its count and the first one with its reason);
    /// none for the reference, which has no drop policy.
    pub numerical_drops: tracker_core::report::NumericalDrops,
    /// Tracks the core declared lost (`tracker_core::TrackLoss`); none for the reference's own count.
    pub lost_tracks: usize,
    /// Unexplained measurements whose birth cells came from a tracklet (docs/maths.md §5.10).
    pub tracklets_formed: usize,
}

/// Whether the core refused the scan for its own input (a measurement outside the field of view or not
/// finite, more measurements than the capacity): the tracker is unchanged and the run goes on with the
/// next scan, its gap measured from the last accepted scan; any other error is the tracker failing.
pub fn is_refused_input(error: &tracker_core::StepError) -> bool {
    use tracker_core::StepError;
    matches!(
        error,
        StepError::MeasurementOutsideFieldOfView { .. }
            | StepError::NonFiniteMeasurement { .. }
            | StepError::TooManyMeasurements { .. }
    )
}

/// A scan the tracker rejected, with the tracker's one-line message and whether it refused the scan's
/// input ([`is_refused_input`]); the tracker is unchanged.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct StepRejected(pub String, pub bool);

impl std::fmt::Display for StepRejected {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

/// The unbounded reference's budgets: memory (beyond it the lowest-weight children are dropped), children
/// enumerated per scan and association steps per scan (beyond either the scan fails: the reference is
/// broken there).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ReferenceBudget {
    /// Bytes of everything that grows with the hypotheses, children and measurements.
    pub bytes: usize,
    /// Children enumerated per scan.
    pub children: u64,
    /// Association steps per scan ([`crate::peers::reference::ReferenceTracker::set_max_work`]).
    pub work: u64,
}

impl Default for ReferenceBudget {
    fn default() -> Self {
        Self { bytes: 4 << 30, children: 1_000_000_000, work: crate::peers::reference::DEFAULT_MAX_WORK }
    }
}
