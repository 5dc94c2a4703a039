//! host-sim: the SSA scenario simulator, scenario files, the unbounded reference tracker, metrics, the
//! `host-sim` command line and its plots.
//!
//! - [`sim`] simulates scenarios (presets of paper 003's experiments) into [`scenario`] files.
//! - [`ssa`] simulates 3-D SSA scans (ground radars, a telescope; two-body + J2 truth) with its own
//!   geometry, independent of tracker-core's (not yet wired into the scenario files).
//! - [`setup`] turns a scenario into tracker-core values; [`runner`] runs a core tracker or the
//!   [`reference`] tracker on it, producing tracker-independent [`snapshot`]s.
//! - [`evaluate`] scores runs against the truth with the [`metrics`], and writes the outputs and plots.
//! - [`catalogue`] reads TLE and OMM element sets and propagates them with SGP4; [`sgp4_check`] verifies
//!   that against the published SGP4 verification cases; [`catalogue_scenario`] makes version 2 scenarios
//!   of a catalogue seen by a sensors file (`generate catalogue`); [`catalogue_experiment`] is `experiment
//!   catalogue` (a catalogue, two radars and a telescope, 24 hours).
//! - [`report`] holds the typed records of every JSON file the commands write; [`error`] the one error
//!   type of the commands and its exit codes.

// `!(x > 0)` is deliberate: unlike `x <= 0` it also rejects NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod assignment;
pub mod catalogue;
pub mod catalogue_experiment;
pub mod ccsds;

pub mod commands;
pub mod error;
pub mod eval;
pub mod experiment;
pub mod gibbs;
pub mod metrics;
pub mod murty;
pub mod oem;
pub mod orbit;
pub mod perf;
pub mod pipeline;
pub mod plots;
pub mod reference;
pub mod report;
pub mod rng;
pub mod sampler_check;
pub mod scenario;
pub mod sgp4_check;
pub mod sim;
pub mod ssa;
pub mod tdm;

pub use error::Error;
