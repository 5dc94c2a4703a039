//! `host-sim sgp4-check`: SGP4 against the published verification cases ([`crate::io::catalogue::sgp4_check`]).

use super::{CliError, terminal};
use crate::error::Error;
use std::path::PathBuf;

/// The arguments of `sgp4-check`.
#[derive(clap::Args)]
pub struct Args {
    /// Output JSON file.
    #[arg(long)]
    out: PathBuf,
    /// Element sets to check instead of the bundled ones (needs --expected).
    #[arg(long, requires = "expected")]
    tle: Option<PathBuf>,
    /// Expected states for --tle (format: host-sim/data/sgp4-verification/README.md).
    #[arg(long, requires = "tle")]
    expected: Option<PathBuf>,
}

/// Runs `sgp4-check`.
pub(super) fn execute(args: Args, json: bool) -> Result<(), CliError> {
    let report = match (&args.tle, &args.expected) {
        (Some(tle), Some(expected)) => {
            let tle_text = crate::scenario::read_limited(tle)?;
            let expected_text = crate::scenario::read_limited(expected)?;
            let names = (tle.display().to_string(), expected.display().to_string());
            crate::io::catalogue::sgp4_check::run_on((&names.0, &names.1), &tle_text, &expected_text)?
        }
        _ => crate::io::catalogue::sgp4_check::run()?,
    };
    crate::pipeline::output::write_json(&args.out, &report)?;
    terminal::print(json, &report, || terminal::sgp4_check(&report, &args.out));
    if report.mismatched_cases > 0 {
        return Err(Error::internal(format!("{} SGP4 verification cases do not match", report.mismatched_cases)).into());
    }
    Ok(())
}
