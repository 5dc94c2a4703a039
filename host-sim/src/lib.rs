//! host-sim: the SSA scenario simulator, scenario files, the unbounded reference tracker, metrics, the
//! `host-sim` command line and its plots.
//!
//! - [`sim`] simulates scenarios (presets of paper 003's experiments) into [`scenario`] files.
//! - [`setup`] turns a scenario into tracker-core values; [`runner`] runs a core tracker or the
//!   [`reference`] tracker on it, producing tracker-independent [`snapshot`]s.
//! - [`evaluate`] scores runs against the truth with the [`metrics`], and writes the outputs and plots.

// `!(x > 0)` is deliberate: unlike `x <= 0` it also rejects NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod assignment;
pub mod digest;
pub mod evaluate;
pub mod experiment;
pub mod metrics;
pub mod murty;
pub mod perf;
pub mod plots;
pub mod reference;
pub mod rng;
pub mod runner;
pub mod sampler_check;
pub mod scenario;
pub mod setup;
pub mod sim;
pub mod snapshot;
pub mod soak;
