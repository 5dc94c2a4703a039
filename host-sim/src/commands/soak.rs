//! `host-sim soak`: a long run with objects entering and leaving ([`crate::pipeline::soak::run_scenario`]).

use super::{CliError, terminal};
use std::path::PathBuf;

/// The arguments of `soak`.
#[derive(clap::Args)]
pub struct Args {
    /// Number of scans, at most 10,000,000.
    #[arg(long, default_value_t = 100_000)]
    scans: u64,
    /// Seed.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// The soak's geometry: the planar SSA scenario with births and deaths, or a 3-D preset observed without end.
    #[arg(long, value_enum, default_value = "planar")]
    scenario: crate::pipeline::soak::Scenario,
    /// The tracker's process noise q (km²/s³, isotropic white acceleration) instead of the preset's
    /// (3-D soaks only): how the filter's consistency (`mean_nees`) depends on it.
    #[arg(long)]
    process_noise: Option<f64>,
    /// White acceleration noise of density q (km²/s³, isotropic) in the truth (3-D soaks only), drawn from
    /// the seed as the tracker's model assumes: with `--process-noise` equal, the NEES test of a matched
    /// filter (docs/maths.md §8.6). Without it the truth has no process noise.
    #[arg(long)]
    truth_process_noise: Option<f64>,
    /// Output JSON file.
    #[arg(long)]
    out: PathBuf,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
}

/// Runs `soak`.
pub(super) fn execute(args: Args, json: bool) -> Result<(), CliError> {
    let noise = crate::pipeline::soak::Noise { tracker: args.process_noise, truth: args.truth_process_noise };
    let report = crate::pipeline::soak::run_scenario(args.scenario, args.scans, args.seed, noise, args.quiet)?;
    crate::pipeline::output::write_json(&args.out, &report)?;
    terminal::print(json, &report, || terminal::soak(&report, &args.out));
    Ok(())
}
