//! `host-sim perf`: speed and memory side by side ([`crate::experiments::perf::run`]).

use super::{CliError, terminal};
use std::path::PathBuf;

/// The arguments of `perf`.
#[derive(clap::Args)]
pub struct Args {
    /// Output JSON file.
    #[arg(long)]
    out: PathBuf,
}

/// Runs `perf`.
pub(super) fn execute(args: Args, json: bool) -> Result<(), CliError> {
    let report = crate::experiments::perf::run()?;
    crate::pipeline::output::write_json(&args.out, &report)?;
    terminal::print(json, &report, || {
        format!(
            "perf: step {:.3} ms (fifty), {:.3} ms (radar-leo), {:.3} ms (optical-geo); tracker {} bytes\n{}",
            report.step_ms_fifty,
            report.step_ms_radar_leo,
            report.step_ms_optical_geo,
            report.tracker_bytes_default,
            terminal::written("  report", &args.out)
        )
    });
    Ok(())
}
