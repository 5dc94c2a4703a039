//! What a pool step can refuse: the scan itself, a scan wider than the pool's `L`, a cluster's Z, a merge
//! beyond N, a pool of more than `P` clusters, or a cluster's own core error; each names the cluster, and a
//! failed step leaves the pool exactly as it was.

use crate::error::{ConfigError, StepError};

/// The id the errors give the birth cluster (the clusters of objects are numbered from 0).
pub const BIRTH_CLUSTER: u64 = u64::MAX;

/// Why a [`ClusterPool`](super::ClusterPool) could not be built or could not process a scan.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum PoolError {
    /// The configuration or a prior object, refused by the core (a duplicate label: `PriorDuplicateLabel`).
    Config(ConfigError),
    /// The scan, refused before any cluster was touched (time, geometry, non-finite measurement).
    Scan(StepError),
    /// A scan of more measurements than the pool's `L`.
    ScanTooLarge {
        /// Measurements in the scan.
        received: usize,
        /// The pool's `L`.
        capacity: usize,
    },
    /// More measurements gated to one cluster (or left to the birth cluster) than its `Z`.
    TooManyMeasurements {
        /// The cluster ([`BIRTH_CLUSTER`] for the birth cluster).
        cluster: u64,
        /// Measurements routed to it.
        received: usize,
        /// The cluster's `Z`.
        capacity: usize,
    },
    /// A merge that would give a hypothesis of more than `N` objects.
    MergeTooLarge {
        /// The merged cluster.
        cluster: u64,
        /// Objects of the hypothesis.
        objects: usize,
        /// The cluster's `N`.
        capacity: usize,
    },
    /// More clusters after the scan than the pool's `P`.
    PoolFull {
        /// The pool's `P`.
        capacity: usize,
    },
    /// A cluster's core refused the state it was rebuilt from.
    Rebuild {
        /// The cluster.
        cluster: u64,
        /// The core's error.
        error: ConfigError,
    },
    /// A cluster's core refused its step.
    Cluster {
        /// The cluster ([`BIRTH_CLUSTER`] for the birth cluster).
        cluster: u64,
        /// The core's error.
        error: StepError,
    },
    /// A cluster's core held a birth pool, which a cluster at rest does not keep (never for a cluster of
    /// objects, whose configuration has no births).
    Unresumable {
        /// The cluster.
        cluster: u64,
    },
}

struct Cluster(u64);

impl core::fmt::Display for Cluster {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        if self.0 == BIRTH_CLUSTER { f.write_str("the birth cluster") } else { write!(f, "cluster {}", self.0) }
    }
}

impl core::fmt::Display for PoolError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match *self {
            PoolError::Config(e) => write!(f, "pool configuration: {e}"),
            PoolError::Scan(e) => write!(f, "scan: {e}"),
            PoolError::ScanTooLarge { received, capacity } => {
                write!(f, "a scan of {received} measurements, more than the pool's L = {capacity}")
            }
            PoolError::TooManyMeasurements { cluster, received, capacity } => write!(
                f,
                "{}: {received} measurements in its gates, more than its capacity Z = {capacity}",
                Cluster(cluster)
            ),
            PoolError::MergeTooLarge { cluster, objects, capacity } => write!(
                f,
                "{}: a merge gives a hypothesis of {objects} objects, more than a cluster's capacity N = {capacity}",
                Cluster(cluster)
            ),
            PoolError::PoolFull { capacity } => {
                write!(f, "the scan would leave more clusters than the pool's P = {capacity}")
            }
            PoolError::Rebuild { cluster, error } => write!(f, "{}: rebuilding it: {error}", Cluster(cluster)),
            PoolError::Cluster { cluster, error } => write!(f, "{}: {error}", Cluster(cluster)),
            PoolError::Unresumable { cluster } => {
                write!(f, "{}: its core holds a birth pool, which a cluster at rest does not keep", Cluster(cluster))
            }
        }
    }
}

impl core::error::Error for PoolError {}
