//! The partitioned catalogue tracker (issue 30; docs/maths.md §13): objects in clusters that do not
//! interact, each cluster an exact core R-FISST tracker with its own hypotheses, merged when a measurement
//! gates with two of them and split when their hypotheses factor, stepped in parallel.
//!
//! - [`tracker`]: [`PartitionedTracker`], the scan loop (route, merge, step, births, split, commit).
//! - [`cluster`]: one cluster at rest ([`Rest`]: what its core carries between scans) and its clearances.
//! - [`cores`]: the pool of reused cores a scan steps the clusters in.
//! - [`route`]: gating a scan's measurements against each cluster and grouping clusters to merge.
//! - [`view`]: the view skip's geometry: how long a track certainly stays out of each sensor's field of view.
//! - [`window`]: a scan's measurements indexed so that the gate compares a track only with those near it.
//! - [`hypotheses`]: a cluster's hypothesis set as owned data and the product of two of them.
//! - [`split`]: the factorisation of a cluster into independent groups of labels (exact or within ε).
//! - [`marginal`]: per-object posteriors (existence, mean, covariance) of a cluster or a single tracker.
//! - [`error`]: cluster ids and the typed errors.

pub mod cluster;
pub mod cores;
#[cfg(test)]
mod edge_tests;
pub mod error;
pub mod hypotheses;
pub mod marginal;
pub mod route;
pub mod runner;
pub mod split;
#[cfg(test)]
mod tests;
pub mod tracker;
pub mod view;
pub mod window;

pub use cluster::{Cluster, Rest};
pub use error::{ClusterId, PartitionError};
pub use tracker::{PartitionReport, PartitionedTracker};
