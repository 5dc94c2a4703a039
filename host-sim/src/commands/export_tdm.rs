//! `host-sim export-tdm`: one CCSDS TDM per sensor of a version 2 scenario.

use super::CliError;
use crate::error::Error;
use crate::scenario::{AnyScenario, load_any};
use std::path::PathBuf;

/// The arguments of `export-tdm`.
#[derive(clap::Args)]
pub struct Args {
    /// Scenario file (version 2).
    file: PathBuf,
    /// Output directory.
    #[arg(long)]
    out: PathBuf,
}

/// Runs `export-tdm`.
pub(super) fn execute(args: Args) -> Result<(), CliError> {
    let AnyScenario::V2(scenario) = load_any(&args.file)? else {
        return Err(Error::input(format!("{}: export-tdm needs a version 2 scenario", args.file.display())).into());
    };
    for path in crate::io::tdm::export(&scenario, &args.out)? {
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}
