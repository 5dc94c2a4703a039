//! host-sim: the simulators, scenario files, peers and metrics around tracker-core, and the `host-sim` command
//! line with its outputs and plots. Where a change goes, by folder:
//!
//! - [`commands`]: the command line, one module per subcommand (`main` only parses and dispatches), and the
//!   short summary each prints on the terminal.
//! - [`scenario`]: scenario files of both versions read and checked into one in-memory type
//!   ([`scenario::AnyScenario`]), and made from simulations ([`scenario::from_simulation`]) and from
//!   catalogues seen by a sensors file ([`scenario::from_catalogue`]).
//! - [`pipeline`]: one replay of a scenario through a tracker of any world (planar, orbital) over a world
//!   adapter; the comparison with the unbounded reference, the soaks, and the firmware's digest replay.
//! - [`eval`]: scoring against the truth: [`eval::metrics`] (GOSPA, OSPA, label switches), births and false
//!   tracks, the exactness of the bounded tracker against the reference.
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
//! - [`plots`]: the figures, a file per figure type.
//! - [`experiments`]: `host-sim experiment` (a file per experiment, [`experiments::catalogue`] among them) and
//!   `host-sim perf` ([`experiments::perf`]).
//! - [`error`]: the one error type of the commands and its exit codes.

// `!(x > 0)` is deliberate: unlike `x <= 0` it also rejects NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod commands;
pub mod error;
pub mod eval;
pub mod experiments;
pub mod io;
pub mod partition;
pub mod peers;
pub mod pipeline;
pub mod plots;
pub mod scenario;
pub mod sim;

pub use error::Error;
