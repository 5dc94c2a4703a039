//! host-sim: the SSA scenario simulator, scenario files, the unbounded reference tracker, metrics, the
//! `host-sim` command line and its plots.
//!
//! - [`commands`] is the command line, one module per subcommand (`main` only parses and dispatches).
//! - [`scenario`] reads and checks scenario files of both versions into one in-memory type
//!   ([`scenario::AnyScenario`]) and makes them from simulations ([`scenario::from_simulation`]) and
//!   catalogues seen by a sensors file ([`scenario::from_catalogue`]).
//! - [`pipeline`] replays a scenario through a tracker of any world (planar, orbital) with one replay over a
//!   world adapter, compares with the unbounded [`reference`], soaks, and replays the firmware's digest.
//! - [`eval`] scores runs against the truth (GOSPA and OSPA through [`metrics`], births, exactness).
//! - [`sim`] simulates paper 003's planar presets; [`ssa`] simulates 3-D SSA scans (ground radars, a
//!   telescope; two-body + J2 truth) with its own geometry, independent of tracker-core's.
//! - [`catalogue`] reads TLE and OMM element sets and propagates them with SGP4; [`sgp4_check`] verifies
//!   that against the published SGP4 verification cases; [`catalogue_experiment`] is `experiment
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
