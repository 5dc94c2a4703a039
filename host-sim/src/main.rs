//! The `host-sim` command line.
//!
//! Exit codes: 0 success; 2 a malformed scenario file or invalid arguments (one-line message on stderr);
//! 3 the run finished but the tracker rejected some scans (listed in `summary.json` and on stderr);
//! 1 any other failure: an output file that cannot be written, or an internal error.

use clap::{Parser, Subcommand};
use host_sim::Error;
use host_sim::pipeline::planar::evaluate::{self, Options};
use host_sim::experiment::Experiment;
use host_sim::scenario::from_simulation::Preset3d;
use host_sim::pipeline::planar::runner::{Profile, TrackerKind};
use host_sim::scenario::v2::{AnyScenario, load_any};
use host_sim::sim::Preset;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(Parser)]
#[command(name = "host-sim", version, about = "SSA scenario simulator and runner for the R-FISST tracker")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(clap::Args, Clone, Copy)]
struct Common {
    /// Capacity profile of the core tracker [default: embedded; on version 2 files, embedded when the
    /// scenario fits it, else host].
    #[arg(long, value_enum)]
    profile: Option<Profile>,
    /// Memory budget of the unbounded reference tracker, in MiB (everything that grows with its
    /// hypotheses, children and measurements); beyond it the reference keeps its best children and
    /// reports the scan in reference_budget_reached_scans (docs/scenario-format.md).
    #[arg(long, default_value_t = 4096)]
    reference_budget_mib: usize,
    /// Children the reference may enumerate per scan; beyond it the scan is rejected (the reference
    /// "breaks", as exhaustive enumeration does in paper 003 §V-B).
    #[arg(long, default_value_t = 1_000_000_000)]
    reference_max_children: u64,
    /// Hypotheses written per scan to scans.jsonl.
    #[arg(long, default_value_t = 100)]
    max_hypotheses_out: usize,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
}

impl Common {
    fn options(self) -> Options {
        Options {
            profile: self.profile.unwrap_or_default(),
            reference: host_sim::pipeline::planar::runner::ReferenceBudget {
                bytes: self.reference_budget_mib.saturating_mul(1 << 20),
                children: self.reference_max_children,
            },
            max_hypotheses_out: self.max_hypotheses_out,
            quiet: self.quiet,
        }
    }
}

/// The inputs of `generate catalogue` (docs/scenario-format.md, "Catalogue files" and "Sensors files").
#[derive(clap::Args, Clone)]
struct CatalogueArgs {
    /// generate catalogue: the catalogue (TLE, 3LE, OMM JSON or CSV).
    #[arg(long)]
    catalogue: Option<PathBuf>,
    /// generate catalogue: the sensors file (`rfisst-sensors/1`).
    #[arg(long)]
    sensors: Option<PathBuf>,
    /// generate catalogue: the start, UTC `YYYY-MM-DDTHH:MM:SS[.f][Z]` (the scenario's epoch).
    #[arg(long)]
    start: Option<String>,
    /// generate catalogue: the duration in hours.
    #[arg(long)]
    duration_hours: Option<f64>,
}

impl CatalogueArgs {
    /// The scenario of `generate catalogue` (`command` names the command in messages).
    fn generate(
        self,
        command: &str,
        seed: u64,
    ) -> Result<(host_sim::scenario::v2::Scenario3d, host_sim::scenario::from_simulation::Generated), Error> {
        let missing = |flag: &str| Error::input(format!("{command}: {flag} is required"));
        let catalogue_file = self.catalogue.ok_or_else(|| missing("--catalogue"))?;
        let sensors = self.sensors.ok_or_else(|| missing("--sensors"))?;
        let start = self.start.ok_or_else(|| missing("--start"))?;
        let duration_hours = self.duration_hours.ok_or_else(|| missing("--duration-hours"))?;
        host_sim::scenario::from_catalogue::generate(host_sim::scenario::from_catalogue::Request {
            catalogue: &catalogue_file,
            sensors: &sensors,
            start: &start,
            duration_hours,
            seed,
        })
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

#[derive(Subcommand)]
enum Command {
    /// Simulate a preset scenario and write it as a scenario file.
    Generate {
        /// The preset.
        #[arg(value_enum)]
        preset: AnyPreset,
        /// Seed of every random choice.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Output scenario file (JSON).
        #[arg(long)]
        out: PathBuf,
        #[command(flatten)]
        catalogue: CatalogueArgs,
        /// radar-leo, optical-geo, tiny-3d: fraction of the objects left out of the prior, in [0, 1].
        #[arg(long, default_value_t = 0.0)]
        missing_fraction: f64,
        /// radar-leo: fragments of a break-up during the run (0: none).
        #[arg(long, default_value_t = 0)]
        breakup: usize,
    },
    /// Run a tracker on a scenario file; writes summary.json, scans.jsonl, estimates.csv and plots.
    Run {
        /// Scenario file.
        file: PathBuf,
        /// Tracker to run.
        #[arg(long, value_enum, default_value_t = TrackerKind::Rfisst)]
        tracker: TrackerKind,
        /// Output directory.
        #[arg(long)]
        out: PathBuf,
        #[command(flatten)]
        common: Common,
    },
    /// Track your own catalogue: simulate what the sensors of a sensors file see of a TLE/OMM catalogue
    /// (as `generate catalogue`) and track it (as `run`); writes scenario.json, summary.json, estimates.csv,
    /// tracks.oem and the plots into the output directory.
    RunCatalogue {
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
        #[command(flatten)]
        common: Common,
    },
    /// Write one CCSDS TDM per sensor of a version 2 scenario (docs/scenario-format.md, "TDM and OEM").
    ExportTdm {
        /// Scenario file (version 2).
        file: PathBuf,
        /// Output directory.
        #[arg(long)]
        out: PathBuf,
    },
    /// Track CCSDS TDMs with a version 2 scenario's models, sensors, prior and tracker settings (its scans
    /// and truth are ignored); writes what `run` writes.
    Track {
        /// TDM files (merged by time; PARTICIPANT_1 names the sensor).
        #[arg(long, num_args = 1.., required = true)]
        tdm: Vec<PathBuf>,
        /// Scenario file (version 2) giving everything but the scans.
        #[arg(long)]
        config: PathBuf,
        /// Tracker to run.
        #[arg(long, value_enum, default_value_t = TrackerKind::Rfisst)]
        tracker: TrackerKind,
        /// Output directory.
        #[arg(long)]
        out: PathBuf,
        #[command(flatten)]
        common: Common,
    },
    /// Run the bounded tracker and the unbounded reference on the same scans; writes compare.json.
    Compare {
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
    },
    /// Reproduce a paper experiment (fifty, fifteen, scaling, debris), the ablation, the 24-hour catalogue
    /// (not in `all`), or all of them.
    Experiment {
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
        /// No progress bar.
        #[arg(long)]
        quiet: bool,
    },
    /// Measure speed and memory side by side in one process; writes a JSON file.
    Perf {
        /// Output JSON file.
        #[arg(long)]
        out: PathBuf,
    },
    /// Run a long scenario with objects entering and leaving; writes a JSON file of health figures.
    Soak {
        /// Number of scans, at most 10,000,000.
        #[arg(long, default_value_t = 100_000)]
        scans: u64,
        /// Seed.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// The soak's geometry: the planar SSA scenario with births and deaths, or a 3-D preset observed without end.
        #[arg(long, value_enum, default_value = "planar")]
        scenario: host_sim::pipeline::soak::planar::Scenario,
        /// Output JSON file.
        #[arg(long)]
        out: PathBuf,
        /// No progress bar.
        #[arg(long)]
        quiet: bool,
    },
    /// Replay a scenario with the embedded (f32) tracker and print the digest the QEMU firmware prints
    /// (version 2: radar only, the prior restricted to the objects the scans detect).
    Digest {
        /// Scenario file.
        file: PathBuf,
        /// Scans to replay (from the start); all when omitted.
        #[arg(long)]
        scans: Option<usize>,
    },
    /// Check SGP4 (the `sgp4` crate, AFSPC mode, through host-sim's TLE parser) against the verification
    /// cases of Vallado et al. 2006 (bundled in host-sim/data/sgp4-verification); writes a JSON file.
    Sgp4Check {
        /// Output JSON file.
        #[arg(long)]
        out: PathBuf,
        /// Element sets to check instead of the bundled ones (needs --expected).
        #[arg(long, requires = "expected")]
        tle: Option<PathBuf>,
        /// Expected states for --tle (format: host-sim/data/sgp4-verification/README.md).
        #[arg(long, requires = "tle")]
        expected: Option<PathBuf>,
    },
    /// Read a catalogue (TLE, 3LE, OMM JSON or CSV) and write its objects with their SGP4 TEME states at
    /// their epochs as JSON (docs/scenario-format.md, "Catalogue files").
    Catalogue {
        /// Catalogue file.
        file: PathBuf,
        /// Output JSON file.
        #[arg(long)]
        out: PathBuf,
    },
    /// Check the R-FISST sampler against exhaustive enumeration on random small problems.
    SamplerCheck {
        /// Number of random cases.
        #[arg(long, default_value_t = 1000)]
        cases: usize,
        /// Seed of the cases.
        #[arg(long, default_value_t = 7)]
        seed: u64,
        /// Output JSON file.
        #[arg(long)]
        out: PathBuf,
    },
}

/// A preset of `generate`: a planar one (version 1 file) or a 3-D one (version 2 file).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum AnyPreset {
    Planar(Preset),
    Ssa(Preset3d),
    /// A catalogue seen by a sensor network (`--catalogue`, `--sensors`, `--start`, `--duration-hours`).
    Catalogue,
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
            AnyPreset::Ssa(Preset3d::Tiny3d),
            AnyPreset::Catalogue,
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
        }
    }
}

/// Why a command failed, at the command line's edge: a one-line message and an exit code.
enum CliError {
    /// A failed command (exit code 2 for bad input, 1 otherwise; [`Error::exit_code`]).
    Failed(Error),
    /// The run finished but the tracker rejected some scans (exit code 3).
    Rejected,
}

impl From<Error> for CliError {
    fn from(e: Error) -> Self {
        CliError::Failed(e)
    }
}

impl From<host_sim::scenario::ScenarioError> for CliError {
    fn from(e: host_sim::scenario::ScenarioError) -> Self {
        CliError::Failed(e.into())
    }
}

impl CliError {
    /// The exit code.
    fn exit_code(&self) -> u8 {
        match self {
            CliError::Failed(e) => e.exit_code(),
            CliError::Rejected => 3,
        }
    }
}

impl std::fmt::Display for CliError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            CliError::Failed(e) => write!(f, "{e}"),
            CliError::Rejected => f.write_str("the tracker rejected some scans (see rejected_scans in summary.json)"),
        }
    }
}

fn execute(cli: Cli) -> Result<(), CliError> {
    match cli.command {
        Command::Generate { preset: AnyPreset::Planar(preset), seed, out, catalogue, missing_fraction, breakup } => {
            catalogue.only_for_catalogue()?;
            if missing_fraction != 0.0 || breakup != 0 {
                return Err(Error::input("--missing-fraction and --breakup need radar-leo or optical-geo").into());
            }
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
            Ok(())
        }
        Command::Generate { preset: AnyPreset::Ssa(preset), seed, out, catalogue, missing_fraction, breakup } => {
            catalogue.only_for_catalogue()?;
            let unknowns = host_sim::ssa::Unknowns { missing_fraction, breakup };
            let simulation = preset.simulate_with(seed, &unknowns)?;
            let (scenario, figures) = host_sim::scenario::from_simulation::to_scenario(&simulation)?;
            scenario.save(&out)?;
            eprintln!(
                "wrote {} ({} scans, {} measurements, at most {} per scan, {} objects, {} measurements outside the \
                 field of view dropped)",
                out.display(),
                figures.scans,
                figures.measurements,
                figures.max_measurements,
                figures.objects,
                figures.dropped_outside
            );
            Ok(())
        }
        Command::Generate { preset: AnyPreset::Catalogue, seed, out, catalogue, missing_fraction, breakup } => {
            if missing_fraction != 0.0 || breakup != 0 {
                return Err(Error::input("--missing-fraction and --breakup need radar-leo or optical-geo").into());
            }
            let (scenario, figures) = catalogue.generate("generate catalogue", seed)?;
            host_sim::scenario::from_catalogue::save_whole(&scenario, &out)?;
            eprintln!(
                "wrote {} ({} scans, {} measurements, at most {} per scan, {} objects, {} measurements outside the \
                 field of view dropped)",
                out.display(),
                figures.scans,
                figures.measurements,
                figures.max_measurements,
                figures.objects,
                figures.dropped_outside
            );
            Ok(())
        }
        Command::Run { file, tracker, out, common } => {
            let scenario = match load_any(&file)? {
                AnyScenario::V1(scenario) => *scenario,
                AnyScenario::V2(scenario) => return run3d(&scenario, tracker, common, &out),
            };
            let (summary, clean) = evaluate::run(&scenario, tracker, &common.options(), &out)?;
            println!("{}", serde_json::to_string_pretty(&summary).unwrap_or_default());
            if clean { Ok(()) } else { Err(CliError::Rejected) }
        }
        Command::RunCatalogue { catalogue, seed, tracker, out, common } => {
            let (scenario, _) = catalogue.generate("run-catalogue", seed)?;
            let (summary, clean) = host_sim::tdm::stage(&out, |dir| {
                scenario.save(&dir.join("scenario.json"))?;
                host_sim::pipeline::orbital::run::run(&scenario, tracker, common.profile, common.quiet, dir)
            })?;
            println!("{}", serde_json::to_string_pretty(&summary).unwrap_or_default());
            if clean { Ok(()) } else { Err(CliError::Rejected) }
        }
        Command::ExportTdm { file, out } => {
            let AnyScenario::V2(scenario) = load_any(&file)? else {
                return Err(Error::input(format!("{}: export-tdm needs a version 2 scenario", file.display())).into());
            };
            for path in host_sim::tdm::export(&scenario, &out)? {
                eprintln!("wrote {}", path.display());
            }
            Ok(())
        }
        Command::Track { tdm, config, tracker, out, common } => {
            let AnyScenario::V2(config_scenario) = load_any(&config)? else {
                return Err(Error::input(format!("{}: --config needs a version 2 scenario", config.display())).into());
            };
            let scenario = host_sim::tdm::scenario_from_tdms(&tdm, &config_scenario)?;
            run3d(&scenario, tracker, common, &out)
        }
        Command::Compare { file, tracker, out, common } => {
            if tracker == TrackerKind::Reference {
                return Err(Error::input("--tracker: the bounded tracker must be homht or rfisst").into());
            }
            let scenario = match load_any(&file)? {
                AnyScenario::V1(scenario) => *scenario,
                AnyScenario::V2(scenario) => {
                    let options = common.options();
                    let profile = host_sim::pipeline::orbital::run::choose_profile(&scenario, common.profile);
                    let figures =
                        host_sim::pipeline::orbital::run::compare3d(&scenario, tracker, Some(profile), options.reference.bytes)?;
                    let summary = host_sim::report::Compare3dSummary {
                        tracker: tracker.name().to_string(),
                        profile: profile.name().to_string(),
                        sensors: scenario.sensors.len(),
                        scans: figures.scans.len(),
                        map_agreement: figures.map_agreement,
                        min_captured_mass: figures.min_captured_mass,
                        mean_captured_mass: figures.mean_captured_mass,
                        max_weight_l1: figures.max_weight_l1,
                        max_map_weight_difference: figures.max_map_weight_difference,
                        min_core_captured_mass: figures.min_core_captured_mass,
                        core_rejected_scans: figures.scans.iter().filter(|s| s.core_error.is_some()).count(),
                        reference_rejected_scans: figures.scans.iter().filter(|s| s.reference_error.is_some()).count(),
                    };
                    std::fs::create_dir_all(&out).map_err(|e| Error::output(&out, e))?;
                    return write_report(&out.join("compare.json"), &summary);
                }
            };
            let result = evaluate::compare(&scenario, tracker, &common.options(), &out)?;
            println!("{}", serde_json::to_string_pretty(&result.summary).unwrap_or_default());
            Ok(())
        }
        Command::Experiment { experiment, out, seed, runs, quiet } => {
            Ok(host_sim::experiment::run(experiment, &out, seed, runs, quiet)?)
        }
        Command::Perf { out } => {
            let report = host_sim::perf::run()?;
            write_report(&out, &report)
        }
        Command::Soak { scans, seed, scenario, out, quiet } => {
            let report = host_sim::pipeline::soak::planar::run_scenario(scenario, scans, seed, quiet)?;
            write_report(&out, &report)
        }
        Command::Digest { file, scans } => {
            let digest = match load_any(&file)? {
                AnyScenario::V1(scenario) => host_sim::pipeline::digest::planar::run(&scenario, scans)?,
                AnyScenario::V2(scenario) => host_sim::pipeline::digest::orbital::run(&scenario, scans)?,
            };
            println!("{digest}");
            Ok(())
        }
        Command::Sgp4Check { out, tle, expected } => {
            let report = match (tle, expected) {
                (Some(tle), Some(expected)) => {
                    let tle_text = host_sim::scenario::read_limited(&tle)?;
                    let expected_text = host_sim::scenario::read_limited(&expected)?;
                    let names = (tle.display().to_string(), expected.display().to_string());
                    host_sim::sgp4_check::run_on((&names.0, &names.1), &tle_text, &expected_text)?
                }
                _ => host_sim::sgp4_check::run()?,
            };
            write_report(&out, &report)?;
            if report.mismatched_cases > 0 {
                return Err(Error::internal(format!(
                    "{} SGP4 verification cases do not match",
                    report.mismatched_cases
                ))
                .into());
            }
            Ok(())
        }
        Command::Catalogue { file, out } => {
            let report = host_sim::catalogue::report(&host_sim::catalogue::load(&file)?);
            evaluate::write_json(&out, &report)?;
            Ok(())
        }
        Command::SamplerCheck { cases, seed, out } => {
            let report = host_sim::sampler_check::run(cases, seed)?;
            write_report(&out, &report)
        }
    }
}

/// `run` on a version 2 scenario, its outputs written only when it succeeds ([`host_sim::tdm::stage`]).
fn run3d(
    scenario: &host_sim::scenario::v2::Scenario3d,
    tracker: TrackerKind,
    common: Common,
    out: &Path,
) -> Result<(), CliError> {
    let (summary, clean) =
        host_sim::tdm::stage(out, |dir| host_sim::pipeline::orbital::run::run(scenario, tracker, common.profile, common.quiet, dir))?;
    println!("{}", serde_json::to_string_pretty(&summary).unwrap_or_default());
    if clean { Ok(()) } else { Err(CliError::Rejected) }
}

/// Writes a JSON report to `out` and prints it.
fn write_report(out: &Path, report: &impl serde::Serialize) -> Result<(), CliError> {
    evaluate::write_json(out, report)?;
    println!("{}", serde_json::to_string_pretty(report).unwrap_or_default());
    Ok(())
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    // The host profile's tracker holds several MiB inline: run on a thread with a large stack.
    let worker = std::thread::Builder::new().stack_size(512 << 20).spawn(move || execute(cli));
    let outcome = match worker {
        Ok(handle) => handle.join(),
        Err(e) => {
            eprintln!("error: cannot start the worker thread: {e}");
            return ExitCode::from(1);
        }
    };
    match outcome {
        Ok(Ok(())) => ExitCode::SUCCESS,
        Ok(Err(e)) => {
            eprintln!("error: {e}");
            ExitCode::from(e.exit_code())
        }
        Err(_) => {
            eprintln!("error: internal failure (a panic); please report it with the scenario file");
            ExitCode::from(1)
        }
    }
}
