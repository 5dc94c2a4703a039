//! `host-sim digest`: the digest the QEMU firmware prints, on the host ([`crate::pipeline::digest`]).

use super::CliError;
use crate::error::Error;
use crate::scenario::{AnyScenario, ScenarioError};
use std::path::PathBuf;

/// The arguments of `digest`.
#[derive(clap::Args)]
pub struct Args {
    /// Scenario file.
    file: PathBuf,
    /// Scans to replay (from the start); all when omitted.
    #[arg(long)]
    scans: Option<usize>,
    /// Also write the firmware's excerpt of these scans to this file, as Rust source (network scenarios
    /// only; the QEMU firmware's `RFISST_NETWORK_EXCERPT`).
    #[arg(long)]
    excerpt: Option<PathBuf>,
    /// Replay the scans through the embedded pool of cluster trackers instead (radar scenarios only; the
    /// QEMU firmware's pool replay); what the pool did goes to stderr.
    #[arg(long, conflicts_with = "excerpt")]
    pool: bool,
}

/// Runs `digest`: the digest is the output, printed as it always was.
pub(super) fn execute(args: Args) -> Result<(), CliError> {
    let scenario = crate::scenario::load_any(&args.file)?;
    if args.pool {
        let AnyScenario::V2(scenario) = &scenario else {
            return Err(ScenarioError("--pool: only radar (version 2) scenarios have a pool replay".into()).into());
        };
        let (text, totals) = crate::pipeline::digest::pool::run(scenario, args.scans)?;
        println!("{text}");
        eprintln!("pool: {totals}");
        return Ok(());
    }
    if let Some(path) = &args.excerpt {
        let AnyScenario::V2(scenario) = &scenario else {
            return Err(
                ScenarioError("--excerpt: only network (version 2) scenarios have an excerpt file".into()).into()
            );
        };
        let source = crate::pipeline::digest::excerpt::source(scenario, args.scans)?;
        std::fs::write(path, source).map_err(|e| Error::Output(format!("{}: {e}", path.display())))?;
    }
    println!("{}", crate::pipeline::digest(&scenario, args.scans)?);
    Ok(())
}
