//! Scoring runs against the truth: the [`metrics`] (OSPA, GOSPA, label switches, ...).

pub mod metrics;
