//! `host-sim run`: a tracker over a scenario file of either version ([`crate::pipeline::run`]).

use super::{CliError, Common, terminal};
use crate::pipeline::TrackerKind;
use std::path::PathBuf;

/// The arguments of `run`.
#[derive(clap::Args)]
pub struct Args {
    /// Scenario file.
    file: PathBuf,
    /// Tracker to run.
    #[arg(long, value_enum, default_value_t = TrackerKind::Rfisst)]
    tracker: TrackerKind,
    /// Output directory.
    #[arg(long)]
    out: PathBuf,
    #[command(flatten)]
    common: Common,
}

/// Runs `run`.
pub(super) fn execute(args: Args, json: bool) -> Result<(), CliError> {
    let scenario = crate::scenario::load_any(&args.file)?;
    let options = args.common.run_options(args.tracker)?;
    let (summary, clean) = crate::pipeline::run(&scenario, &options, &args.out)?;
    finish(&summary, clean, &args.out, json)
}

/// Prints the summary of a run into `out`; [`CliError::Rejected`] when a scan was rejected.
pub(super) fn finish(
    summary: &crate::io::report::RunSummary,
    clean: bool,
    out: &std::path::Path,
    json: bool,
) -> Result<(), CliError> {
    terminal::print(json, summary, || terminal::run(summary, out));
    if clean { Ok(()) } else { Err(CliError::Rejected) }
}
