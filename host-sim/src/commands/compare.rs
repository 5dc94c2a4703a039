//! `host-sim compare`: the bounded tracker against the unbounded reference ([`crate::pipeline::compare`]).

use super::{CliError, Common, terminal};
use crate::pipeline::Compared;
use crate::pipeline::TrackerKind;
use std::path::PathBuf;

/// The arguments of `compare`.
#[derive(clap::Args)]
pub struct Args {
    /// Scenario file.
    file: PathBuf,
    /// The bounded tracker.
    #[arg(long, value_enum, default_value_t = TrackerKind::Rfisst)]
    tracker: TrackerKind,
    /// Output directory.
    #[arg(long)]
    out: PathBuf,
    #[command(flatten)]
    common: Common,
}

/// Runs `compare`.
pub(super) fn execute(args: Args, json: bool) -> Result<(), CliError> {
    let scenario = crate::scenario::load_any(&args.file)?;
    let options = args.common.run_options(args.tracker)?;
    let reference_rejected = match crate::pipeline::compare(&scenario, &options, &args.out)? {
        Compared::Planar(report) => {
            for scan in &report.per_scan {
                if let Some(error) = &scan.reference_error {
                    eprintln!("warning: scan {} (t = {}): the reference rejected it: {error}", scan.scan, scan.time);
                }
            }
            terminal::print(json, &report.summary, || terminal::compare(&report, &args.out));
            report.per_scan.iter().filter(|s| s.reference_error.is_some()).count()
        }
        Compared::Orbital(summary) => {
            terminal::print(json, &summary, || terminal::compare3d(&summary, &args.out));
            summary.reference_rejected_scans
        }
    };
    if reference_rejected > 0 {
        return Err(CliError::ReferenceRejected(reference_rejected));
    }
    Ok(())
}
