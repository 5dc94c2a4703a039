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

pub mod births;
pub mod catalogue_scenario;
pub mod digest;
pub mod digest3d;
pub mod error;
pub mod eval;
pub mod evaluate;
pub mod exactness;
pub mod experiments;
pub mod generate3d;
pub mod io;
pub mod peers;
pub mod plots;
pub mod run3d;
pub mod runner;
pub mod scenario;
pub mod scenario3d;
pub mod setup;
pub mod sim;
pub mod snapshot;
pub mod soak;
pub mod soak3d;

pub use error::Error;
