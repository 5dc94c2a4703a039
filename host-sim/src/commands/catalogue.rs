//! `host-sim catalogue`: a catalogue's objects and their SGP4 states at their epochs, as JSON.

use super::CliError;
use std::path::PathBuf;

/// The arguments of `catalogue`.
#[derive(clap::Args)]
pub struct Args {
    /// Catalogue file.
    file: PathBuf,
    /// Output JSON file.
    #[arg(long)]
    out: PathBuf,
}

/// Runs `catalogue` (writes the file; prints nothing, as always).
pub(super) fn execute(args: Args) -> Result<(), CliError> {
    let report = crate::io::catalogue::report(&crate::io::catalogue::load(&args.file)?);
    crate::pipeline::output::write_json(&args.out, &report)?;
    Ok(())
}
