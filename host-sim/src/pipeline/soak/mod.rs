//! `host-sim soak`: long runs with objects entering and leaving, in the planar world ([`planar`]) or an
//! orbital preset observed without end ([`orbital`]); what both share is [`common`], and the scan loop and
//! the report written once over both (`run.rs`).

pub mod common;
mod consistency;
pub mod orbital;
pub mod planar;
mod run;

pub use common::{MAX_SCANS, Scenario};

use crate::error::Error;
use crate::io::report::SoakReport;

/// Runs `scans` scans of the soak `scenario` with `seed` and returns the report; `process_noise` replaces
/// the 3-D preset tracker's q.
///
/// # Errors
/// As [`planar::run`] and [`orbital::run`]; [`Error::Input`] for a process noise given to the planar soak.
pub fn run_scenario(
    scenario: Scenario,
    scans: u64,
    seed: u64,
    process_noise: Option<f64>,
    quiet: bool,
) -> Result<SoakReport, Error> {
    match scenario {
        Scenario::Planar if process_noise.is_some() => {
            Err(Error::input("--process-noise: only for the 3-D soaks (radar-leo, optical-geo, ssa-network)"))
        }
        Scenario::Planar => planar::run(scans, seed, quiet),
        Scenario::RadarLeo | Scenario::OpticalGeo | Scenario::SsaNetwork => {
            orbital::run(scenario, scans, seed, process_noise, quiet)
        }
    }
}
