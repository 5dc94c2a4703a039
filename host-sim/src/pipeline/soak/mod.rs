//! `host-sim soak`: long runs with objects entering and leaving, in the planar world ([`planar`]) or an
//! orbital preset observed without end ([`orbital`]); what both share is [`common`], and the scan loop and
//! the report written once over both (`run.rs`).

pub mod common;
pub mod orbital;
pub mod planar;
mod run;

pub use common::{MAX_SCANS, Scenario};

use crate::error::Error;
use crate::io::report::SoakReport;

/// Runs `scans` scans of the soak `scenario` with `seed` and returns the report.
///
/// # Errors
/// As [`planar::run`] and [`orbital::run`].
pub fn run_scenario(scenario: Scenario, scans: u64, seed: u64, quiet: bool) -> Result<SoakReport, Error> {
    match scenario {
        Scenario::Planar => planar::run(scans, seed, quiet),
        Scenario::RadarLeo | Scenario::OpticalGeo | Scenario::SsaNetwork => orbital::run(scenario, scans, seed, quiet),
    }
}
