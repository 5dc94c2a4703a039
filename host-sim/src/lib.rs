//! host-sim: the simulators, scenario files, peers and metrics around tracker-core, and the `host-sim` command
//! line with its outputs and plots. Where a change goes, by folder:
//!
//! - [`sim`]: what the world does and what sensors report. The planar simulator of paper 003 ([`sim::planar`])
//!   and the 3-D SSA simulator, split by concept: [`sim::time`] (UTC, Julian dates, GMST), [`sim::vector`],
//!   [`sim::frames`], [`sim::site`], [`sim::field_of_view`], [`sim::sensor`], [`sim::truth`], [`sim::breakup`],
//!   [`sim::ssa`] (the scenario and its scans), [`sim::presets`]; the truth propagator [`sim::orbit`] and the
//!   seeded streams [`sim::rng`].
//! - [`io`]: files other than scenarios: TLE and OMM catalogues with SGP4 ([`io::catalogue`], checked by
//!   [`io::catalogue::sgp4_check`]), CCSDS tracking data and ephemerides ([`io::tdm`], [`io::oem`]) with exact UTC
//!   times ([`io::ccsds`]), and the typed JSON record of every report ([`io::report`], a file per output).
//! - [`peers`]: what R-FISST is checked and compared against: the unbounded [`peers::reference`] tracker,
//!   [`peers::murty`], [`peers::gibbs`] over [`peers::assignment`], and [`peers::sampler_check`].
//! - [`eval`]: scoring against the truth ([`eval::metrics`]).
//! - [`plots`]: the figures, a file per figure type.
//! - [`experiments`]: `host-sim experiment` (a file per experiment, [`experiments::catalogue`] among them) and
//!   `host-sim perf` ([`experiments::perf`]).
//! - Scenario files and the run pipeline: [`scenario`] (version 1, planar) and [`scenario3d`] (version 2, 3-D),
//!   [`setup`] (a scenario into tracker-core values), [`runner`] (the core trackers and the reference behind one
//!   interface), [`snapshot`] (a tracker-independent posterior), [`evaluate`] and [`run3d`] (`run` and `compare`,
//!   planar and 3-D), [`births`] and [`exactness`] (births, false tracks; the bounded tracker against the
//!   reference), [`digest`] and [`digest3d`] (the QEMU firmware's replay), [`soak`] and [`soak3d`] (long runs),
//!   [`generate3d`] (the 3-D presets as scenario files), [`catalogue_scenario`] (`generate catalogue`).
//! - [`error`]: the one error type of the commands and its exit codes. `main.rs` is the command line.

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
