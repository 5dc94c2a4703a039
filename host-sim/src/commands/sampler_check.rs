//! `host-sim sampler-check`: the R-FISST sampler against exhaustive enumeration ([`crate::peers::sampler_check`]).

use super::{CliError, terminal};
use std::path::PathBuf;

/// The arguments of `sampler-check`.
#[derive(clap::Args)]
pub struct Args {
    /// Number of random cases.
    #[arg(long, default_value_t = 1000)]
    cases: usize,
    /// Seed of the cases.
    #[arg(long, default_value_t = 7)]
    seed: u64,
    /// Output JSON file.
    #[arg(long)]
    out: PathBuf,
}

/// Runs `sampler-check`.
pub(super) fn execute(args: Args, json: bool) -> Result<(), CliError> {
    let report = crate::peers::sampler_check::run(args.cases, args.seed)?;
    crate::pipeline::output::write_json(&args.out, &report)?;
    terminal::print(json, &report, || terminal::sampler_check(&report, &args.out));
    Ok(())
}
