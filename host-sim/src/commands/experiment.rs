//! `host-sim experiment`: a paper experiment, the ablation or the 24-hour catalogue
//! ([`crate::experiments::run`]).

use super::CliError;
use crate::experiments::Experiment;
use std::path::PathBuf;

/// The arguments of `experiment`.
#[derive(clap::Args)]
pub struct Args {
    /// The experiment.
    #[arg(value_enum)]
    experiment: Experiment,
    /// Output directory.
    #[arg(long)]
    out: PathBuf,
    /// Seed of the scenario (and the tracker).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Number of seeds to run (seed, seed + 1, ...), in parallel; reports mean and spread.
    #[arg(long, default_value_t = 1)]
    runs: u64,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
}

/// Runs `experiment`.
pub(super) fn execute(args: Args) -> Result<(), CliError> {
    crate::experiments::run(args.experiment, &args.out, args.seed, args.runs, args.quiet)?;
    println!("experiment {}: files in {}", args.experiment.name(), args.out.display());
    Ok(())
}
