//! What a partitioned step can refuse: the scan itself, a cluster's Z, a merge beyond N or K, or a cluster's
//! own core error; each names the cluster, and a failed step leaves the partitioned tracker unchanged.

use std::fmt;
use tracker_core::{ConfigError, StepError};

/// A cluster's identity: clusters of objects are numbered from 0 in the order they are made; the birth
/// cluster (the measurements in no gate) is [`ClusterId::BIRTH`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct ClusterId(pub u64);

impl ClusterId {
    /// The birth cluster.
    pub const BIRTH: ClusterId = ClusterId(u64::MAX);
}

impl fmt::Display for ClusterId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if *self == ClusterId::BIRTH { f.write_str("the birth cluster") } else { write!(f, "cluster {}", self.0) }
    }
}

/// Why a [`super::PartitionedTracker`] refused to be built or refused a scan.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PartitionError {
    /// The configuration or a cluster's prior, as the core checks it.
    Config(ConfigError),
    /// The scan as a whole (time, a non-finite measurement, one outside the field of view, the sensor).
    Scan(StepError),
    /// More measurements gated to one cluster than its capacity Z.
    TooManyMeasurements { cluster: ClusterId, received: usize, capacity: usize },
    /// A merge whose kept hypotheses hold more objects than a cluster's capacity N.
    MergeTooLarge { cluster: ClusterId, objects: usize, capacity: usize },
    /// A cluster rebuilt by a merge, a split or a birth that the core refused (e.g. its track store K).
    Rebuild { cluster: ClusterId, error: ConfigError },
    /// A cluster's own core step failed.
    Cluster { cluster: ClusterId, error: StepError },
    /// A cluster's core holds state a cluster at rest cannot keep (a birth pool with cells).
    Unresumable { cluster: ClusterId },
}

impl fmt::Display for PartitionError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PartitionError::Config(e) => write!(f, "tracker configuration: {e}"),
            PartitionError::Scan(e) => write!(f, "scan: {e}"),
            PartitionError::TooManyMeasurements { cluster, received, capacity } => {
                write!(f, "{cluster}: {received} measurements in its gates, more than its capacity Z = {capacity}")
            }
            PartitionError::MergeTooLarge { cluster, objects, capacity } => write!(
                f,
                "{cluster}: a merge gives a hypothesis of {objects} objects, more than a cluster's capacity N = {capacity}"
            ),
            PartitionError::Rebuild { cluster, error } => write!(f, "{cluster}: rebuilding it: {error}"),
            PartitionError::Cluster { cluster, error } => write!(f, "{cluster}: {error}"),
            PartitionError::Unresumable { cluster } => {
                write!(f, "{cluster}: its core holds a birth pool, which a cluster at rest does not keep")
            }
        }
    }
}

impl std::error::Error for PartitionError {}
