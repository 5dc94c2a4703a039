//! `host-sim experiment`: a paper experiment, the ablation, the 24-hour catalogue
//! ([`crate::experiments::run`]) or the catalogue at scale ([`crate::experiments::catalogue_scale`]).

use super::{CliError, OrNone, parse_lost_after, parse_or_none};
use crate::error::Error;
use crate::experiments::Experiment;
use crate::experiments::catalogue_scale::{self, Settings};
use crate::scenario::SelectionSpec;
use crate::scenario::from_simulation::{CATALOGUE_SELECTION, CATALOGUE_TRACK_LOSS};
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
    /// catalogue-scale: objects of the synthetic catalogue.
    #[arg(long)]
    objects: Option<usize>,
    /// catalogue-scale: simulated hours.
    #[arg(long)]
    hours: Option<f64>,
    /// catalogue-scale: threads of the tracker's pool [default: every core].
    #[arg(long)]
    threads: Option<usize>,
    /// catalogue-scale: step every cluster at every scan, not only those a sensor may see (for comparison).
    #[arg(long)]
    step_every_cluster: bool,
    /// catalogue-scale: the clusters keep the hypotheses within this many decades of the heaviest
    /// (docs/maths.md §8.1), or `none` for every one up to H (slower: each observed object's cluster then
    /// holds up to H versions of it) [default: 9, the catalogue scenarios']
    #[arg(long, value_parser = parse_floor)]
    weight_floor: Option<OrNone<u8>>,
    /// catalogue-scale: a track in view of this many scans in a row with no measurement in its gate is
    /// dropped (docs/maths.md §5.9), or `none` to keep every track [default: 8, the catalogue scenarios']
    #[arg(long, value_parser = parse_lost_after)]
    lost_after: Option<OrNone<core::num::NonZeroU16>>,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
}

/// The catalogue scenarios' floor ([`CATALOGUE_SELECTION`]).
fn catalogue_floor() -> Option<u8> {
    match CATALOGUE_SELECTION {
        SelectionSpec::TopWeightWithin { decades } => Some(decades),
        SelectionSpec::TopWeight | SelectionSpec::SampledByWeight => None,
    }
}

fn parse_floor(text: &str) -> Result<OrNone<u8>, String> {
    parse_or_none(text, "a number of decades 0-255")
}

/// Runs `experiment`.
pub(super) fn execute(args: Args) -> Result<(), CliError> {
    let name = args.experiment.name();
    if args.experiment == Experiment::CatalogueScale {
        let (Some(objects), Some(hours)) = (args.objects, args.hours) else {
            return Err(Error::input("experiment catalogue-scale: needs --objects N and --hours H").into());
        };
        if args.runs > 1 {
            return Err(Error::input("experiment catalogue-scale: no --runs (one run, its own threads)").into());
        }
        let settings = Settings {
            objects,
            hours,
            seed: args.seed,
            threads: args.threads,
            quiet: args.quiet,
            step_every_cluster: args.step_every_cluster,
            weight_floor_decades: args.weight_floor.map_or_else(catalogue_floor, |f| f.0),
            lost_after_unseen_scans: args.lost_after.map_or(CATALOGUE_TRACK_LOSS, |n| n.0).map(|n| n.get()),
        };
        let report = catalogue_scale::run(&args.out, &settings)?;
        eprintln!(
            "catalogue-scale: {} objects, {} scans, {:.1} s of tracking ({:.0}x real time), {} rejected scans",
            report.objects, report.scans, report.wall_s, report.realtime_factor, report.rejected_scans
        );
    } else {
        let own = args.objects.is_some() || args.hours.is_some() || args.threads.is_some();
        if own || args.step_every_cluster || args.weight_floor.is_some() || args.lost_after.is_some() {
            return Err(Error::input(format!(
                "experiment {name}: --objects, --hours, --threads, --step-every-cluster, --weight-floor and \
                 --lost-after are catalogue-scale's"
            ))
            .into());
        }
        crate::experiments::run(args.experiment, &args.out, args.seed, args.runs, args.quiet)?;
    }
    println!("experiment {name}: files in {}", args.out.display());
    Ok(())
}
