//! `host-sim soak`: long runs with objects entering and leaving, in the planar world ([`planar`]) or an
//! orbital preset observed without end ([`orbital`]); what both share is [`common`], and the scan loop and
//! the report written once over both (`run.rs`).

pub mod common;
mod consistency;
pub mod orbital;
pub mod planar;
mod run;

pub use common::{MAX_SCANS, Scenario};
pub use orbital::Noise;

use crate::error::Error;
use crate::io::report::SoakReport;

/// Runs `scans` scans of the soak `scenario` with `seed` and returns the report; `noise` replaces the 3-D
/// preset tracker's q and gives its truth process noise.
///
/// # Errors
/// As [`planar::run`] and [`orbital::run`]; [`Error::Input`] for a process noise given to the planar soak.
pub fn run_scenario(scenario: Scenario, scans: u64, seed: u64, noise: Noise, quiet: bool) -> Result<SoakReport, Error> {
    match scenario {
        Scenario::Planar if noise.tracker.is_some() => {
            Err(Error::input("--process-noise: only for the 3-D soaks (radar-leo, optical-geo, ssa-network)"))
        }
        Scenario::Planar if noise.truth.is_some() => {
            Err(Error::input("--truth-process-noise: only for the 3-D soaks (radar-leo, optical-geo, ssa-network)"))
        }
        Scenario::Planar => planar::run(scans, seed, quiet),
        Scenario::RadarLeo | Scenario::OpticalGeo | Scenario::SsaNetwork => {
            orbital::run(scenario, scans, seed, noise, quiet)
        }
    }
}
