//! `host-sim digest`: the digest the QEMU firmware prints, on the host ([`crate::pipeline::digest`]).

use super::CliError;
use std::path::PathBuf;

/// The arguments of `digest`.
#[derive(clap::Args)]
pub struct Args {
    /// Scenario file.
    file: PathBuf,
    /// Scans to replay (from the start); all when omitted.
    #[arg(long)]
    scans: Option<usize>,
}

/// Runs `digest`: the digest is the output, printed as it always was.
pub(super) fn execute(args: Args) -> Result<(), CliError> {
    let scenario = crate::scenario::load_any(&args.file)?;
    println!("{}", crate::pipeline::digest(&scenario, args.scans)?);
    Ok(())
}
