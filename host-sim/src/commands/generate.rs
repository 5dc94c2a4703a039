//! `host-sim generate`: simulate a preset (planar, 3-D, or a catalogue seen by a sensors file) and write
//! it as a scenario file.

use super::CliError;
use crate::error::Error;
use crate::io::catalogue::CatalogueDropped;
use crate::scenario::from_catalogue::{Generation, Request};
use crate::scenario::from_simulation::{Generated, Preset3d};
use crate::scenario::v2::Scenario3d;
use crate::sim::planar::Preset;
use sgp4::chrono::Timelike;
use std::path::PathBuf;

/// The arguments of `generate`.
#[derive(clap::Args)]
pub struct Args {
    /// The preset.
    #[arg(value_enum)]
    preset: AnyPreset,
    /// Seed of every random choice.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Output scenario file (JSON): a new path or a regular file, replaced only once complete.
    #[arg(long)]
    out: PathBuf,
    #[command(flatten)]
    catalogue: CatalogueArgs,
    /// radar-leo, optical-geo, optical-leo, tiny-3d: fraction of the objects left out of the prior, in [0, 1].
    #[arg(long, default_value_t = 0.0)]
    missing_fraction: f64,
    /// radar-leo: fragments of a break-up during the run (0: none).
    #[arg(long, default_value_t = 0)]
    breakup: usize,
    #[command(flatten)]
    synthetic: SyntheticArgs,
}

/// The inputs of `generate synthetic-catalogue` ([`crate::sim::population`]).
#[derive(clap::Args, Clone)]
pub struct SyntheticArgs {
    /// generate synthetic-catalogue: the number of element sets, 1 to 400,000. Mixture: LEO shells 30 %,
    /// sun-synchronous 15 %, debris clouds of break-ups 35 %, MEO navigation 4 %, GEO belt 8 %, GTO 6 %,
    /// Molniya 2 % (docs/scenario-format.md, "Synthetic catalogues").
    #[arg(long)]
    objects: Option<usize>,
    /// generate synthetic-catalogue: the epoch of every element set, UTC `YYYY-MM-DDTHH:MM:SS[.f][Z]`.
    #[arg(long, default_value = "2026-03-20T00:00:00Z")]
    epoch: String,
}

impl SyntheticArgs {
    /// Writes the synthetic catalogue of `seed` to `out` as OMM JSON; prints what it wrote (`json`: as JSON
    /// on stdout).
    fn write(&self, seed: u64, out: &std::path::Path, json: bool) -> Result<(), Error> {
        use crate::sim::population::{MIXTURE, family_counts, synthetic_catalogue};
        let objects =
            self.objects.ok_or_else(|| Error::input("generate synthetic-catalogue: --objects is required"))?;
        let epoch_text = self.epoch.as_str();
        let bad =
            || Error::input(format!("--epoch {epoch_text:?}: not a UTC time YYYY-MM-DDTHH:MM:SS[.f][Z] in 1901-2099"));
        let epoch_jd = crate::sim::time::parse_iso8601(epoch_text).map_err(|_| bad())?;
        let epoch = crate::io::catalogue::parse_omm_epoch(epoch_text).ok_or_else(bad)?;
        // OMM's EPOCH holds microseconds: an epoch with more digits would not read back the same.
        let epoch = epoch.with_nanosecond(epoch.nanosecond() / 1000 * 1000).ok_or_else(bad)?;
        let synthetic = synthetic_catalogue(objects, seed, epoch, epoch_jd).map_err(Error::input)?;
        crate::io::atomic::write(out, crate::io::catalogue::to_omm_json(&synthetic.entries))?;
        let counts = family_counts(objects);
        let families: Vec<String> =
            MIXTURE.iter().zip(&counts).map(|((family, _), count)| format!("{count} {family:?}")).collect();
        eprintln!("wrote {} ({objects} element sets, OMM JSON: {})", out.display(), families.join(", "));
        if json {
            let report = serde_json::json!({
                "out": out,
                "objects": objects,
                "epoch": epoch.format("%Y-%m-%dT%H:%M:%S%.6fZ").to_string(),
                "families": MIXTURE.iter().zip(&counts).map(|((f, _), c)| (format!("{f:?}"), *c)).collect::<std::collections::BTreeMap<_, _>>(),
            });
            println!("{}", serde_json::to_string_pretty(&report).map_err(Error::internal)?);
        }
        Ok(())
    }
}

/// The inputs of `generate catalogue` (docs/scenario-format.md, "Catalogue files" and "Sensors files").
#[derive(clap::Args, Clone)]
pub struct CatalogueArgs {
    /// generate catalogue: the catalogue (TLE, 3LE, OMM JSON or CSV).
    #[arg(long)]
    catalogue: Option<PathBuf>,
    /// generate catalogue: the sensors file (`rfisst-sensors/1`).
    #[arg(long)]
    sensors: Option<PathBuf>,
    /// generate catalogue: the start, UTC `YYYY-MM-DDTHH:MM:SS[.f][Z]` (the scenario's epoch).
    #[arg(long)]
    start: Option<String>,
    /// generate catalogue: the duration in hours, at most 744; `generate catalogue`: at most what makes a
    /// scenario `run` reads (256 MiB: about 130 bytes per object and scan, roughly 2e6 objects x scans),
    /// refused up front with the estimated size (exit code 2); `run-catalogue` draws a longer run as it goes.
    #[arg(long)]
    duration_hours: Option<f64>,
}

impl CatalogueArgs {
    /// The scenario of `generate catalogue` (`command` names the command in messages) and the element sets
    /// it left out.
    pub(super) fn generate(self, command: &str, seed: u64) -> Result<(Scenario3d, Generated, CatalogueDropped), Error> {
        self.with_request(command, seed, crate::scenario::from_catalogue::generate_screened)
    }

    /// [`Self::generate`]'s scenario when it fits a scenario file, else its scans drawn as the run goes
    /// ([`crate::scenario::from_catalogue::generate_or_stream`]).
    pub(super) fn generate_or_stream(self, command: &str, seed: u64) -> Result<Generation, Error> {
        self.with_request(command, seed, crate::scenario::from_catalogue::generate_or_stream)
    }

    /// `work` on the request of these options (all four required by `command`) and `seed`.
    fn with_request<T>(
        self,
        command: &str,
        seed: u64,
        work: impl FnOnce(Request<'_>) -> Result<T, Error>,
    ) -> Result<T, Error> {
        let missing = |flag: &str| Error::input(format!("{command}: {flag} is required"));
        let catalogue = self.catalogue.ok_or_else(|| missing("--catalogue"))?;
        let sensors = self.sensors.ok_or_else(|| missing("--sensors"))?;
        let start = self.start.ok_or_else(|| missing("--start"))?;
        let duration_hours = self.duration_hours.ok_or_else(|| missing("--duration-hours"))?;
        work(Request { catalogue: &catalogue, sensors: &sensors, start: &start, duration_hours, seed })
    }

    /// The catalogue options are refused with a preset.
    fn only_for_catalogue(&self) -> Result<(), Error> {
        let given =
            self.catalogue.is_some() || self.sensors.is_some() || self.start.is_some() || self.duration_hours.is_some();
        if given {
            return Err(Error::input(
                "--catalogue, --sensors, --start and --duration-hours are for generate catalogue only",
            ));
        }
        Ok(())
    }
}

/// A preset of `generate`: a planar one (version 1 file) or a 3-D one (version 2 file).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum AnyPreset {
    Planar(Preset),
    Ssa(Preset3d),
    /// A catalogue seen by a sensor network (`--catalogue`, `--sensors`, `--start`, `--duration-hours`).
    Catalogue,
    /// A synthetic catalogue (`--objects`, `--epoch`), written as OMM JSON.
    SyntheticCatalogue,
}

impl clap::ValueEnum for AnyPreset {
    fn value_variants<'a>() -> &'a [Self] {
        &[
            AnyPreset::Planar(Preset::FiftyBirthDeath),
            AnyPreset::Planar(Preset::FifteenCompare),
            AnyPreset::Planar(Preset::DebrisCrossing),
            AnyPreset::Planar(Preset::LinearSmall),
            AnyPreset::Planar(Preset::Crossings),
            AnyPreset::Ssa(Preset3d::RadarLeo),
            AnyPreset::Ssa(Preset3d::OpticalGeo),
            AnyPreset::Ssa(Preset3d::OpticalLeo),
            AnyPreset::Ssa(Preset3d::OpticalHeo),
            AnyPreset::Ssa(Preset3d::Tiny3d),
            AnyPreset::Ssa(Preset3d::SsaNetwork),
            AnyPreset::Ssa(Preset3d::TinyNetwork),
            AnyPreset::Catalogue,
            AnyPreset::SyntheticCatalogue,
        ]
    }

    fn to_possible_value(&self) -> Option<clap::builder::PossibleValue> {
        match self {
            AnyPreset::Planar(p) => p.to_possible_value(),
            AnyPreset::Ssa(p) => p.to_possible_value(),
            AnyPreset::Catalogue => Some(
                clap::builder::PossibleValue::new("catalogue")
                    .help("A TLE/OMM catalogue (--catalogue) seen by the sensors of --sensors; truth by SGP4"),
            ),
            AnyPreset::SyntheticCatalogue => Some(
                clap::builder::PossibleValue::new("synthetic-catalogue")
                    .help("A synthetic catalogue of --objects element sets shaped like the public one, as OMM JSON"),
            ),
        }
    }
}

/// What `generate catalogue --json` prints: the figures of the file written and the element sets left out.
#[derive(serde::Serialize)]
struct CatalogueGenerated<'a> {
    out: &'a std::path::Path,
    objects: usize,
    scans: usize,
    measurements: usize,
    max_measurements: usize,
    dropped_outside: usize,
    catalogue_dropped: &'a CatalogueDropped,
}

/// Runs `generate` (`json`: `generate catalogue` prints its figures as JSON on stdout).
pub(super) fn execute(args: Args, json: bool) -> Result<(), CliError> {
    let Args { preset, seed, out, catalogue, missing_fraction, breakup, synthetic } = args;
    if preset != AnyPreset::SyntheticCatalogue && synthetic.objects.is_some() {
        return Err(Error::input("--objects is for generate synthetic-catalogue only").into());
    }
    let unknowns_refused = || -> Result<(), Error> {
        if missing_fraction != 0.0 || breakup != 0 {
            return Err(Error::input(
                "--missing-fraction and --breakup need a 3-D preset (radar-leo, optical-geo, optical-leo, tiny-3d)",
            ));
        }
        Ok(())
    };
    let mut dropped = None;
    let figures = match preset {
        AnyPreset::Planar(preset) => {
            catalogue.only_for_catalogue()?;
            unknowns_refused()?;
            let simulation = preset.simulation(seed);
            let scenario = simulation.run();
            scenario.save(&out)?;
            eprintln!(
                "wrote {} ({} scans, {} measurements, {} objects)",
                out.display(),
                scenario.scans.len(),
                scenario.scans.iter().map(|s| s.measurements.len()).sum::<usize>(),
                simulation.objects.len()
            );
            return Ok(());
        }
        AnyPreset::Ssa(preset) => {
            catalogue.only_for_catalogue()?;
            let unknowns = crate::sim::truth::Unknowns { missing_fraction, breakup };
            let simulation = preset.simulate_with(seed, &unknowns)?;
            let (scenario, figures) = crate::scenario::from_simulation::to_scenario(&simulation)?;
            scenario.save(&out)?;
            figures
        }
        AnyPreset::SyntheticCatalogue => {
            catalogue.only_for_catalogue()?;
            unknowns_refused()?;
            return Ok(synthetic.write(seed, &out, json)?);
        }
        AnyPreset::Catalogue => {
            unknowns_refused()?;
            let (scenario, figures, catalogue_dropped) = catalogue.generate("generate catalogue", seed)?;
            crate::scenario::from_catalogue::save_whole(&scenario, &out)?;
            dropped = Some(catalogue_dropped);
            figures
        }
    };
    let left_out = dropped.as_ref().map_or_else(String::new, |d| format!(", {} element sets dropped", d.count));
    eprintln!(
        "wrote {} ({} scans, {} measurements, at most {} per scan, {} objects, {} measurements outside the field \
         of view dropped{left_out})",
        out.display(),
        figures.scans,
        figures.measurements,
        figures.max_measurements,
        figures.objects,
        figures.dropped_outside
    );
    if let (true, Some(catalogue_dropped)) = (json, &dropped) {
        let report = CatalogueGenerated {
            out: &out,
            objects: figures.objects,
            scans: figures.scans,
            measurements: figures.measurements,
            max_measurements: figures.max_measurements,
            dropped_outside: figures.dropped_outside,
            catalogue_dropped,
        };
        println!("{}", serde_json::to_string_pretty(&report).map_err(Error::internal)?);
    }
    Ok(())
}
