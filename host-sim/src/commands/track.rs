//! `host-sim track`: CCSDS TDMs tracked with a version 2 scenario's settings, optionally continuing an
//! earlier run from its OEM (`--prior-oem`, [`crate::pipeline::orbital::prior_oem`]).

use super::{CliError, Common};
use crate::error::Error;
use crate::io::ccsds::Instant;
use crate::pipeline::TrackerKind;
use crate::pipeline::orbital::prior_oem;
use crate::pipeline::profile::ORBITAL;
use crate::scenario::v2::Scenario3d;
use crate::scenario::{AnyScenario, load_any};
use std::path::{Path, PathBuf};

/// The arguments of `track`.
#[derive(clap::Args)]
pub struct Args {
    /// TDM files (merged by time; PARTICIPANT_1 names the sensor).
    #[arg(long, num_args = 1.., required = true)]
    pub(super) tdm: Vec<PathBuf>,
    /// Scenario file (version 2) giving everything but the scans.
    #[arg(long)]
    pub(super) config: PathBuf,
    /// An earlier run's OEM (`tracks.oem`): its segments' last states and covariances are the prior (instead
    /// of the configuration's), at its last epoch; scans at or before that epoch are skipped.
    #[arg(long)]
    pub(super) prior_oem: Option<PathBuf>,
    /// Tracker to run.
    #[arg(long, value_enum, default_value_t = TrackerKind::Rfisst)]
    pub(super) tracker: TrackerKind,
    /// Output directory.
    #[arg(long)]
    pub(super) out: PathBuf,
    #[command(flatten)]
    pub(super) common: Common,
}

/// Runs `track`.
pub(super) fn execute(args: Args, json: bool) -> Result<(), CliError> {
    let (summary, clean) = track(&args)?;
    super::run::finish(&summary, clean, &args.out, json)
}

/// Tracks the TDMs as `args` say; the run's summary and whether the tracker took every scan.
///
/// # Errors
/// Bad input (the configuration, a TDM, the prior OEM) or an output that cannot be written.
pub(super) fn track(args: &Args) -> Result<(crate::io::report::RunSummary, bool), Error> {
    let AnyScenario::V2(config) = load_any(&args.config)? else {
        return Err(Error::input(format!("{}: --config needs a version 2 scenario", args.config.display())));
    };
    let scenario = match &args.prior_oem {
        None => crate::io::tdm::scenario_from_tdms(&args.tdm, &config)?,
        Some(file) => continued(args, *config, file)?,
    };
    let options = args.common.run_options(args.tracker)?;
    crate::pipeline::run(&AnyScenario::V2(Box::new(scenario)), &options, &args.out)
}

/// The scenario of a run continued from the OEM `file`: its prior, and the TDMs' scans after its epoch. The
/// scans skipped are counted on stderr.
fn continued(args: &Args, mut config: Scenario3d, file: &Path) -> Result<Scenario3d, Error> {
    let oem = crate::io::oem::read::read(file)?;
    // N of the profile asked for; without one, of the largest profile (`choose_profile` takes it when the
    // prior does not fit the embedded one).
    let profile = args.common.profile.unwrap_or(crate::pipeline::Profile::Host);
    let capacity = ORBITAL.of(profile).objects;
    let prior = prior_oem::prior_from_oem(&oem, &Instant::epoch_of(&config), capacity, profile.name())
        .map_err(|e| e.in_file(file))?;
    config.prior = prior.prior;
    let (scenario, skipped) = crate::io::tdm::scenario_after_prior(&args.tdm, &config, true)?;
    eprintln!(
        "note: --prior-oem {}: {} objects at {}{}; {skipped} scans at or before it skipped, {} tracked",
        file.display(),
        scenario.max_prior_objects(),
        prior.epoch,
        if prior.renumbered { " (labelled 1, 2, ... in file order)" } else { "" },
        scenario.scans.len(),
    );
    Ok(scenario)
}
