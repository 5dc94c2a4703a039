//! One pipeline over every world: replay a scenario through a tracker, score it against the truth and
//! write the outputs ([`replay`], over any [`world::World`]); compare a bounded tracker with the unbounded
//! reference; soak; the firmware's digest.
//!
//! A world adapter ([`planar::PlanarWorld`], [`orbital::OrbitalWorld`]) says how to build the tracker from
//! its scenario, how to turn a scan into the core's measurements and scan geometry, and how to read a
//! position out of a state; [`run`], [`compare`] and [`digest`] pick the world from the scenario file once,
//! so the commands never branch on the file's version.

pub mod digest;
pub mod orbital;
pub mod output;
pub mod planar;
pub mod profile;
pub mod replay;
pub mod residual_plots;
pub mod run_charts;
pub mod settings;
pub mod snapshot;
pub mod soak;
pub mod tracker;
pub mod world;

pub use profile::Profile;
pub use tracker::{ReferenceBudget, StepInfo, StepRejected, TrackerKind};

use crate::error::Error;
use crate::io::report::{Compare3dSummary, CompareReport, RunSummary};
use crate::scenario::AnyScenario;
use std::path::Path;

/// What `run`, `compare` and `track` ask of the pipeline.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunOptions {
    /// The tracker (for `compare`, the bounded one).
    pub tracker: TrackerKind,
    /// The capacity profile asked for; `None`: embedded on version 1 files, on version 2 files embedded
    /// when the scenario fits it, else host.
    pub profile: Option<Profile>,
    /// Budgets of the reference tracker.
    pub reference: ReferenceBudget,
    /// Hypotheses written per scan to `scans.jsonl`.
    pub max_hypotheses_out: usize,
    /// No progress bar.
    pub quiet: bool,
}

impl RunOptions {
    /// The planar world's options.
    fn planar(&self) -> planar::Options {
        planar::Options {
            profile: self.profile.unwrap_or_default(),
            reference: self.reference,
            max_hypotheses_out: self.max_hypotheses_out,
            quiet: self.quiet,
        }
    }
}

/// `host-sim run`: replays `scenario` through the tracker of `options` and writes the outputs into `out`
/// (version 2 runs are written only when they succeed, [`crate::io::tdm::stage`]); returns the summary and
/// whether every scan was accepted.
///
/// # Errors
/// Bad input (the tracker cannot be built, a scan the world refuses) or a file that cannot be written.
pub fn run(scenario: &AnyScenario, options: &RunOptions, out: &Path) -> Result<(RunSummary, bool), Error> {
    match scenario {
        AnyScenario::V1(scenario) => planar::run(scenario, options.tracker, &options.planar(), out),
        AnyScenario::V2(scenario) => crate::io::tdm::stage(out, |dir| {
            orbital::run(scenario, options.tracker, options.profile, options.quiet, dir)
        }),
    }
}

/// [`run`], with the scenario itself saved as `scenario.json` among the outputs (`run-catalogue`).
///
/// # Errors
/// As [`run`].
pub fn run_with_scenario_file(
    scenario: &AnyScenario,
    options: &RunOptions,
    out: &Path,
) -> Result<(RunSummary, bool), Error> {
    match scenario {
        AnyScenario::V1(scenario) => {
            std::fs::create_dir_all(out).map_err(|e| Error::output(out, e))?;
            scenario.save(&out.join("scenario.json"))?;
            planar::run(scenario, options.tracker, &options.planar(), out)
        }
        AnyScenario::V2(scenario) => crate::io::tdm::stage(out, |dir| {
            scenario.save(&dir.join("scenario.json"))?;
            orbital::run(scenario, options.tracker, options.profile, options.quiet, dir)
        }),
    }
}

/// `run-catalogue` on a catalogue too large to hold: its scans drawn as the run goes
/// ([`orbital::run_streamed`]); `summary.json` is scored against the truth drawn with each scan, and
/// `scenario.json` holds the scans drawn, without truth. Written only when the run succeeds; also returns
/// the element sets dropped.
///
/// # Errors
/// As [`run`].
pub fn run_streamed(
    stream: crate::scenario::catalogue_stream::CatalogueStream,
    options: &RunOptions,
    out: &Path,
) -> Result<(RunSummary, bool, crate::io::catalogue::screen::CatalogueDropped), Error> {
    crate::io::tdm::stage(out, |dir| {
        orbital::run_streamed(stream, options.tracker, options.profile, options.quiet, dir)
    })
}

/// What `compare` found, per world.
#[derive(Debug, Clone, PartialEq)]
pub enum Compared {
    /// A planar comparison (`compare.json` holds the report).
    Planar(CompareReport),
    /// An orbital comparison (`compare.json` holds the summary).
    Orbital(Compare3dSummary),
}

/// `host-sim compare`: the bounded tracker of `options` and the unbounded reference on the same scans;
/// writes `compare.json` into `out`.
///
/// # Errors
/// Bad input (the reference as the bounded tracker, a configuration a tracker refuses) or a file that
/// cannot be written.
pub fn compare(scenario: &AnyScenario, options: &RunOptions, out: &Path) -> Result<Compared, Error> {
    if options.tracker == TrackerKind::Reference {
        return Err(Error::input("--tracker: the bounded tracker must be homht or rfisst"));
    }
    match scenario {
        AnyScenario::V1(scenario) => {
            Ok(Compared::Planar(planar::compare::compare(scenario, options.tracker, &options.planar(), out)?))
        }
        AnyScenario::V2(scenario) => {
            let summary = orbital::compare::summary(scenario, options.tracker, options.profile, options.reference)?;
            std::fs::create_dir_all(out).map_err(|e| Error::output(out, e))?;
            output::write_json(&out.join("compare.json"), &summary)?;
            Ok(Compared::Orbital(summary))
        }
    }
}

/// `host-sim digest`: the digest the QEMU firmware prints for the first `scans` scans of `scenario`.
///
/// # Errors
/// Bad input: a scenario the embedded tracker cannot take.
pub fn digest(scenario: &AnyScenario, scans: Option<usize>) -> Result<String, Error> {
    Ok(match scenario {
        AnyScenario::V1(scenario) => digest::planar::run(scenario, scans)?,
        AnyScenario::V2(scenario) if scenario.measurement == crate::scenario::v2::Measurement3dSpec::Network => {
            digest::network::run(scenario, scans)?
        }
        AnyScenario::V2(scenario) => digest::orbital::run(scenario, scans)?,
    })
}
