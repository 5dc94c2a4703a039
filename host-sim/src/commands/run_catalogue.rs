//! `host-sim run-catalogue`: `generate catalogue` and `run` in one command.

use super::generate::CatalogueArgs;
use super::{CliError, Common, OrNone, parse_lost_after};
use crate::pipeline::TrackerKind;
use crate::scenario::AnyScenario;
use crate::scenario::from_catalogue::Generation;
use std::path::PathBuf;

/// The arguments of `run-catalogue`.
#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    catalogue: CatalogueArgs,
    /// Seed of the simulated detections, noise and clutter.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Tracker to run.
    #[arg(long, value_enum, default_value_t = TrackerKind::Rfisst)]
    tracker: TrackerKind,
    /// Output directory.
    #[arg(long)]
    out: PathBuf,
    /// A track in view of this many scans in a row with no measurement in its gate is dropped
    /// (docs/maths.md §5.9), or `none` to keep every track [default: the sensors' preset's, else 8 (not for a
    /// telescope alone)]
    #[arg(long, value_parser = parse_lost_after)]
    lost_after: Option<OrNone<core::num::NonZeroU16>>,
    #[command(flatten)]
    common: Common,
}

/// Runs `run-catalogue`.
pub(super) fn execute(args: Args, json: bool) -> Result<(), CliError> {
    let options = args.common.run_options(args.tracker)?;
    let (mut summary, clean, dropped) = match args.catalogue.generate_or_stream("run-catalogue", args.seed)? {
        Generation::Held(held) => {
            let (mut scenario, _, dropped) = *held;
            if let Some(OrNone(n)) = args.lost_after {
                scenario.tracker.lost_after_unseen_scans = n;
            }
            let scenario = AnyScenario::V2(Box::new(scenario));
            let (summary, clean) = crate::pipeline::run_with_scenario_file(&scenario, &options, &args.out)?;
            (summary, clean, dropped)
        }
        Generation::Streamed(mut stream) => {
            if let Some(OrNone(n)) = args.lost_after {
                stream.set_lost_after_unseen_scans(n);
            }
            eprintln!(
                "note: {} objects x {} scans: more than a scenario file holds; the scans are drawn as the run goes \
                 (estimates.csv and tracks.oem: the tracks once a simulated hour and at the end; scenario.json \
                 without truth)",
                stream.objects(),
                stream.scans()
            );
            crate::pipeline::run_streamed(*stream, &options, &args.out)?
        }
    };
    // The run's summary.json with the element sets the scenario left out.
    summary.catalogue_dropped = Some(dropped);
    crate::pipeline::output::write_json(&args.out.join("summary.json"), &summary)?;
    super::run::finish(&summary, clean, &args.out, json)
}
