//! The typed records of every JSON file host-sim writes: `summary.json` of `run` (and of `experiment
//! fifty`), the lines of `scans.jsonl`, `compare.json`, the `soak` and `sampler-check` reports,
//! `runs.json` of `experiment --runs` and `perf.json` of `perf`. Each field is one key of the file, with the same name; a value
//! that may be unknown is an `Option` (written as `null`). Reading a file back is `serde_json::from_str`
//! into the same type.
//!
//! A file per output: `summary` (`summary.json`), `scans` (`scans.jsonl`), `compare`, `soak`, `sampler_check`,
//! `experiments` (`runs.json`, `fifteen.json`, `scaling.json`, `debris.json`, the ablation), `perf`,
//! `catalogue` (`catalogue.json`), `scale` (`scale.json`) and `ilrs` (`ilrs.json` of `track-ilrs`). The records are re-exported here.

mod catalogue;
mod compare;
mod dropped;
mod experiments;
mod ilrs;
mod perf;
mod residuals;
mod sampler_check;
mod scale;
mod scans;
mod soak;
mod summary;

pub use catalogue::{CatalogueReport, CatalogueTracker, UnconfirmedBirth};
pub use compare::{Compare3dSummary, CompareReport, CompareScan, CompareSide, CompareSummary};
pub use dropped::{NumericalDrop, NumericalDropsSummary, RefusedScan, RefusedScans};
pub use experiments::{
    AblationDebris, AblationFifty, AblationVariant, AssociationCheck, CheckOutcome, DebrisFigures, DebrisHomht,
    DebrisReport, DebrisRfisst, DebrisScan, FifteenFigures, FifteenHomht, FifteenReport, FifteenScan, FifteenTracker,
    RunsReport, ScalingFigures, ScalingReport, ScalingSampler, ScalingSize, Spread, Timing,
};
pub use ilrs::{IlrsPass, IlrsPoint, IlrsPrior, IlrsReport, Stats};
pub use perf::{
    PerfDetails, PerfExhaustive, PerfFifty, PerfGibbs, PerfGibbsCase, PerfGibbsShape, PerfMachine, PerfMurty,
    PerfMurtyCase, PerfMurtyShape, PerfReport, PerfSsa,
};
pub use residuals::SensorResiduals;
pub use sampler_check::{SamplerCheckReport, SamplerScores, SamplerSettings};
pub use scale::ScaleReport;
pub use scans::{LabelExistence, ScanHypothesis, ScanLine};
pub use soak::{SoakError, SoakReport, SoakSetup, SoakTracking, SoakTruth};
pub use summary::{BirthConfirmation, BirthFigures, BirthRecord, BirthsSummary, RejectedScan, RunSummary};
