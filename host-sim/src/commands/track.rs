//! `host-sim track`: CCSDS TDMs tracked with a version 2 scenario's settings.

use super::{CliError, Common};
use crate::error::Error;
use crate::pipeline::TrackerKind;
use crate::scenario::{AnyScenario, load_any};
use std::path::PathBuf;

/// The arguments of `track`.
#[derive(clap::Args)]
pub struct Args {
    /// TDM files (merged by time; PARTICIPANT_1 names the sensor).
    #[arg(long, num_args = 1.., required = true)]
    tdm: Vec<PathBuf>,
    /// Scenario file (version 2) giving everything but the scans.
    #[arg(long)]
    config: PathBuf,
    /// Tracker to run.
    #[arg(long, value_enum, default_value_t = TrackerKind::Rfisst)]
    tracker: TrackerKind,
    /// Output directory.
    #[arg(long)]
    out: PathBuf,
    #[command(flatten)]
    common: Common,
}

/// Runs `track`.
pub(super) fn execute(args: Args, json: bool) -> Result<(), CliError> {
    let AnyScenario::V2(config) = load_any(&args.config)? else {
        return Err(Error::input(format!("{}: --config needs a version 2 scenario", args.config.display())).into());
    };
    let scenario = AnyScenario::V2(Box::new(crate::io::tdm::scenario_from_tdms(&args.tdm, &config)?));
    let options = args.common.run_options(args.tracker)?;
    let (summary, clean) = crate::pipeline::run(&scenario, &options, &args.out)?;
    super::run::finish(&summary, clean, &args.out, json)
}
