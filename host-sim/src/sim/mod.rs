//! The simulators: what the world does and what the sensors report, written independently of tracker-core.
//!
//! - [`planar`]: the planar simulator of paper 003's experiments (one sensor, position measurements) and
//!   its presets.
//! - The 3-D SSA simulator: [`time`] (UTC, Julian dates, GMST), [`vector`] (3-vector maths, angles),
//!   [`frames`] (Earth-fixed to inertial, right ascension / declination), [`site`] (WGS-84 sites and their
//!   observers), [`field_of_view`], [`sensor`] (what a radar or telescope measures, its clutter and noise),
//!   [`truth`] (the objects, their orbits and what the prior knows), [`breakup`], [`error`] (why a simulation fails), [`ssa`] (the scenario
//!   and its scans) and [`presets`] (`radar-leo`, `optical-geo`, `tiny-3d`).
//! - [`population`]: a synthetic catalogue shaped like the public one (`generate synthetic-catalogue`).
//! - [`orbit`]: the truth propagator (adaptive RKF7(8), two-body + J2); [`rng`]: the seeded random streams.

pub mod breakup;
pub mod error;
pub mod field_of_view;
pub mod fk5;
pub mod frames;
#[cfg(test)]
mod long_gap_tests;
pub mod network;
pub mod optical_heo;
pub mod optical_leo;
pub mod orbit;
pub mod physics;
pub mod planar;
pub mod population;
pub mod presets;
pub mod refraction;
pub mod rng;
pub mod sensor;
pub mod site;
pub mod ssa;
#[cfg(test)]
mod ssa_tests;
pub mod time;
pub mod truth;
pub mod vector;
