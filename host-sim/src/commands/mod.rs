//! The `host-sim` command line: the arguments ([`Cli`]), one module per subcommand, and what every
//! subcommand shares (the tracker options, the terminal summary, the exit codes).
//!
//! `main` parses a [`Cli`] and calls [`execute`]. Exit codes: 0 success; 2 a malformed scenario file or
//! invalid arguments (one-line message on stderr); 3 the run finished but the tracker rejected some scans
//! (listed in `summary.json` and on stderr); 1 any other failure: an output file that cannot be written, or
//! an internal error.

mod catalogue;
mod compare;
mod digest;
mod experiment;
mod export_tdm;
mod generate;
mod perf;
mod run;
mod run_catalogue;
mod sampler_check;
mod sgp4_check;
mod soak;
mod terminal;
mod track;
mod track_ilrs;

use crate::error::Error;
use crate::pipeline::RunOptions;
use crate::pipeline::{Profile, ReferenceBudget, TrackerKind};
use clap::{Parser, Subcommand};

/// The command line.
#[derive(Parser)]
#[command(name = "host-sim", version, about = "SSA scenario simulator and runner for the R-FISST tracker")]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
    /// Print the full JSON summary or report on stdout instead of the short human summary.
    #[arg(long, global = true)]
    json: bool,
}

/// An option's value that may be `none` (`--weight-floor`, `--lost-after`).
#[derive(Debug, Clone, Copy)]
struct OrNone<T>(Option<T>);

/// `text` as a `T`, or `none`; `what` says what was expected.
fn parse_or_none<T: std::str::FromStr>(text: &str, what: &str) -> Result<OrNone<T>, String> {
    match text {
        "none" => Ok(OrNone(None)),
        _ => text.parse().map(|n| OrNone(Some(n))).map_err(|_| format!("{text:?}: {what}, or none")),
    }
}

/// `--lost-after N|none` (docs/maths.md §5.9).
fn parse_lost_after(text: &str) -> Result<OrNone<core::num::NonZeroU16>, String> {
    parse_or_none(text, "a number of scans 1-65535")
}

/// The options of the commands that run a tracker on a scenario.
#[derive(clap::Args, Clone, Copy)]
pub struct Common {
    /// Capacity profile of the core tracker [default: embedded; on version 2 files, embedded when the
    /// scenario fits it, else host].
    #[arg(long, value_enum)]
    profile: Option<Profile>,
    /// Memory budget of the unbounded reference tracker, in MiB (everything that grows with its
    /// hypotheses, children and measurements); beyond it the reference keeps its best children and
    /// reports the scan in reference_budget_reached_scans (docs/scenario-format.md). From 1 MiB to
    /// 1 TiB (1048576); above the default, at most this machine's memory (MemTotal of /proc/meminfo).
    #[arg(long, default_value_t = DEFAULT_REFERENCE_BUDGET_MIB, value_parser = clap::value_parser!(u64).range(1..=MAX_REFERENCE_BUDGET_MIB))]
    reference_budget_mib: u64,
    /// Children the reference may enumerate per scan; beyond it the scan is rejected (the reference
    /// "breaks", as exhaustive enumeration does in paper 003 §V-B).
    #[arg(long, default_value_t = 1_000_000_000)]
    reference_max_children: u64,
    /// Association steps the reference may take per scan (every node of its enumeration and every
    /// measurement-object pair it examines); beyond it the scan is rejected, naming the scan (exit code
    /// 3). The default, 1e10, is about 45 s of one core.
    #[arg(long, default_value_t = crate::peers::reference::DEFAULT_MAX_WORK,
          value_parser = clap::value_parser!(u64).range(1..))]
    reference_max_work: u64,
    /// Hypotheses written per scan to scans.jsonl.
    #[arg(long, default_value_t = 100)]
    max_hypotheses_out: usize,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
}

/// The default `--reference-budget-mib`: 4 GiB.
pub const DEFAULT_REFERENCE_BUDGET_MIB: u64 = 4096;

/// The largest `--reference-budget-mib`: 1 TiB.
pub const MAX_REFERENCE_BUDGET_MIB: u64 = 1 << 20;

/// MemTotal of /proc/meminfo in MiB, where there is one.
fn machine_memory_mib() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemTotal:"))?;
    line.split_whitespace().nth(1)?.parse::<u64>().ok().map(|kib| kib / 1024)
}

impl Common {
    /// The pipeline's options for the tracker `tracker`.
    ///
    /// # Errors
    /// Bad input: a reference budget above the default and this machine's memory (clap has checked 1 MiB
    /// to 1 TiB).
    fn run_options(self, tracker: TrackerKind) -> Result<RunOptions, Error> {
        let mib = self.reference_budget_mib;
        let above = |memory: u64| mib > memory.max(DEFAULT_REFERENCE_BUDGET_MIB);
        if let Some(memory) = machine_memory_mib().filter(|&memory| above(memory)) {
            return Err(Error::input(format!(
                "--reference-budget-mib {mib}: more than this machine's memory ({memory} MiB, MemTotal of /proc/meminfo)"
            )));
        }
        let bytes = usize::try_from(mib.saturating_mul(1 << 20))
            .map_err(|_| Error::input(format!("--reference-budget-mib {mib}: more than this machine can address")))?;
        Ok(RunOptions {
            tracker,
            profile: self.profile,
            reference: ReferenceBudget { bytes, children: self.reference_max_children, work: self.reference_max_work },
            max_hypotheses_out: self.max_hypotheses_out,
            quiet: self.quiet,
        })
    }
}

#[derive(Subcommand)]
enum Command {
    /// Simulate a preset scenario and write it as a scenario file.
    Generate(generate::Args),
    /// Run a tracker on a scenario file; writes summary.json, scans.jsonl, estimates.csv and plots.
    Run(run::Args),
    /// Track your own catalogue: simulate what the sensors of a sensors file see of a TLE/OMM catalogue
    /// (as `generate catalogue`) and track it (as `run`); writes scenario.json, summary.json, estimates.csv,
    /// tracks.oem and the plots into the output directory.
    RunCatalogue(run_catalogue::Args),
    /// Write one CCSDS TDM per sensor of a version 2 scenario (docs/scenario-format.md, "TDM and OEM").
    ExportTdm(export_tdm::Args),
    /// Track CCSDS TDMs with a version 2 scenario's models, sensors, prior and tracker settings (its scans
    /// and truth are ignored); writes what `run` writes.
    Track(track::Args),
    /// Track real laser ranging data: the normal points of an ILRS CRD file reduced to ranges (a TDM and a
    /// configuration, as `track` takes them), tracked, and judged against the target's CPF predictions;
    /// writes ranges.tdm, config.json, track/ and ilrs.json.
    TrackIlrs(track_ilrs::Args),
    /// Run the bounded tracker and the unbounded reference on the same scans; writes compare.json.
    Compare(compare::Args),
    /// Reproduce a paper experiment (fifty, fifteen, scaling, debris), the ablation, the 24-hour catalogue
    /// (not in `all`), the catalogue at scale (catalogue-scale --objects N --hours H, not in `all`), or all of
    /// them.
    Experiment(experiment::Args),
    /// Measure speed and memory side by side in one process; writes a JSON file.
    Perf(perf::Args),
    /// Run a long scenario with objects entering and leaving; writes a JSON file of health figures.
    Soak(soak::Args),
    /// Replay a scenario with the embedded (f32) tracker and print the digest the QEMU firmware prints
    /// (version 2: radar only, the prior restricted to the objects the scans detect).
    Digest(digest::Args),
    /// Check SGP4 (the `sgp4` crate, AFSPC mode, through host-sim's TLE parser) against the verification
    /// cases of Vallado et al. 2006 (bundled in host-sim/data/sgp4-verification); writes a JSON file.
    Sgp4Check(sgp4_check::Args),
    /// Read a catalogue (TLE, 3LE, OMM JSON or CSV) and write its objects with their SGP4 TEME states at
    /// their epochs as JSON (docs/scenario-format.md, "Catalogue files").
    Catalogue(catalogue::Args),
    /// Check the R-FISST sampler against exhaustive enumeration on random small problems.
    SamplerCheck(sampler_check::Args),
}

/// Why a command failed, at the command line's edge: a one-line message and an exit code.
#[derive(Debug)]
pub enum CliError {
    /// A failed command (exit code 2 for bad input, 1 otherwise; [`Error::exit_code`]).
    Failed(Error),
    /// The run finished but the tracker rejected some scans (exit code 3).
    Rejected,
    /// `compare` finished but the reference rejected some scans, for example past its work bound (exit
    /// code 3; the message says how many).
    ReferenceRejected(usize),
}

impl From<Error> for CliError {
    fn from(e: Error) -> Self {
        CliError::Failed(e)
    }
}

impl From<crate::scenario::ScenarioError> for CliError {
    fn from(e: crate::scenario::ScenarioError) -> Self {
        CliError::Failed(e.into())
    }
}

impl CliError {
    /// The exit code.
    pub fn exit_code(&self) -> u8 {
        match self {
            CliError::Failed(e) => e.exit_code(),
            CliError::Rejected | CliError::ReferenceRejected(_) => 3,
        }
    }
}

impl std::fmt::Display for CliError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            CliError::Failed(e) => write!(f, "{e}"),
            CliError::Rejected => f.write_str("the tracker rejected some scans (see rejected_scans in summary.json)"),
            CliError::ReferenceRejected(scans) => write!(
                f,
                "the reference rejected {scans} scan(s) (see reference_error in compare.json); its figures there \
                 are of the scans it kept"
            ),
        }
    }
}

/// Runs the command of `cli`.
///
/// # Errors
/// [`CliError`]: the message `main` prints and the exit code it returns.
pub fn execute(cli: Cli) -> Result<(), CliError> {
    let json = cli.json;
    match cli.command {
        Command::Generate(args) => generate::execute(args, json),
        Command::Run(args) => run::execute(args, json),
        Command::RunCatalogue(args) => run_catalogue::execute(args, json),
        Command::ExportTdm(args) => export_tdm::execute(args),
        Command::Track(args) => track::execute(args, json),
        Command::TrackIlrs(args) => track_ilrs::execute(args, json),
        Command::Compare(args) => compare::execute(args, json),
        Command::Experiment(args) => experiment::execute(args),
        Command::Perf(args) => perf::execute(args, json),
        Command::Soak(args) => soak::execute(args, json),
        Command::Digest(args) => digest::execute(args),
        Command::Sgp4Check(args) => sgp4_check::execute(args, json),
        Command::Catalogue(args) => catalogue::execute(args),
        Command::SamplerCheck(args) => sampler_check::execute(args, json),
    }
}
