//! `experiment fifty` (paper 003 §IV): 50 objects, 45 known to the prior, 5 births, with `run`'s outputs.

use super::common::options;
use crate::error::Error;
use crate::io::report::RunSummary;
use crate::pipeline::TrackerKind;
use crate::pipeline::planar as evaluate;
use crate::sim::planar;
use std::path::Path;

/// Paper 003 §IV with R-FISST on the embedded configuration.
pub(crate) fn fifty(dir: &Path, seed: u64, quiet: bool) -> Result<RunSummary, Error> {
    let scenario = planar::fifty_birth_death(seed).run();
    scenario.save(&dir.join("scenario.json"))?;
    let (summary, _) = evaluate::run(&scenario, TrackerKind::Rfisst, &options(quiet), dir)?;
    Ok(summary)
}
