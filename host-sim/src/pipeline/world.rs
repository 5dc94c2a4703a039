//! The seam between the one replay ([`crate::pipeline::replay`]) and a world: what the replay asks of a
//! scenario and its tracker, whatever the geometry (planar, ground radars, telescopes, a fused network).
//!
//! A world adapter owns the scenario's tracker. It turns scan `k` into the core's measurement vectors (and
//! scan geometry) and steps the tracker; it reduces the posterior to the MAP estimates the replay scores;
//! it says where the truth is and what its sensor sees; and it writes its own files (the estimates' CSV
//! columns, scans.jsonl, an OEM, its plots).

use crate::error::Error;
use crate::pipeline::tracker::StepInfo;
use crate::scenario::EvaluationSpec;
use std::io::Write;

/// One MAP estimate.
#[derive(Debug, Clone, PartialEq)]
pub struct Estimate {
    /// Label.
    pub label: u32,
    /// Mean state; the first P entries are the position the replay scores.
    pub mean: Vec<f64>,
    /// Existence probability of the label.
    pub existence: f64,
}

/// What the replay needs of a posterior.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Posterior {
    /// The MAP hypothesis's tracks.
    pub map: Vec<Estimate>,
    /// Σ w_h N_h.
    pub expected_cardinality: f64,
    /// Hypotheses held.
    pub hypotheses: usize,
}

/// One true object at a scan.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TruthObject<'a> {
    /// Truth id.
    pub id: u64,
    /// State; the first P entries are the position.
    pub state: &'a [f64],
}

/// Why a step failed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum StepFailure {
    /// The tracker rejected the scan (it is unchanged); the run goes on and exits with code 3.
    Rejected(String),
    /// The core refused the scan's input ([`crate::pipeline::tracker::is_refused_input`]; the tracker is
    /// unchanged): the run reports it (`refused_scans`) and goes on, and exits 0.
    Refused(String),
    /// The scan is bad input for this world (the run stops with exit code 2).
    BadInput(String),
}

/// What the run's summary says of the world and its tracker.
#[derive(Debug, Clone, PartialEq)]
pub struct Heading {
    /// Scenario name.
    pub scenario: String,
    /// Tracker name.
    pub tracker: &'static str,
    /// Profile name (`unbounded` for the reference).
    pub profile: &'static str,
    /// Sensors (worlds with a sensor network only).
    pub sensors: Option<usize>,
    /// The kinds of the sensors, each once (worlds with a sensor network only).
    pub sensor_kinds: Option<Vec<String>>,
    /// The scenario's evaluation settings.
    pub evaluation: EvaluationSpec,
    /// Whether the scenario has truth.
    pub has_truth: bool,
    /// Truth ids of the objects not in the prior (the births).
    pub births: Vec<u64>,
    /// Whether the peak hypothesis count starts from the prior's (it always has on version 2 files).
    pub peak_counts_prior: bool,
    /// Whether the reference's budget figures are reported.
    pub reference: bool,
    /// Whether every birth cell comes from a tracklet (then `summary.json` counts `tracklet_births`).
    pub births_from_tracklets_only: bool,
}

/// A world: a scenario and its tracker, scored positions of `P` coordinates.
pub trait World<const P: usize> {
    /// What the summary says of the run.
    fn heading(&self) -> Heading;
    /// Scans in the scenario.
    fn scans(&self) -> usize;
    /// Time of scan `k`.
    fn time(&self, k: usize) -> f64;
    /// Makes scan `k` ready, before anything else of it is asked (a world that draws its scans as the run
    /// goes draws it here); the replay asks for the scans in order, each once.
    ///
    /// # Errors
    /// The world cannot make the scan (bad input, or a file it reads).
    fn begin(&mut self, _k: usize) -> Result<(), Error> {
        Ok(())
    }
    /// Steps the tracker with scan `k`.
    ///
    /// # Errors
    /// [`StepFailure`]: a rejected scan, or bad input.
    fn step(&mut self, k: usize) -> Result<StepInfo, StepFailure>;
    /// The posterior now (the adapter may keep what its own outputs need of it).
    fn posterior(&mut self) -> Posterior;
    /// The true objects at scan `k`, when the scenario has truth.
    fn truth(&self, k: usize) -> Option<Vec<TruthObject<'_>>>;
    /// Truth ids of the objects that produced a measurement at scan `k`.
    fn detected(&self, k: usize) -> Vec<u64>;
    /// The name of scan `k`'s sensor, in worlds whose sensors have names.
    fn sensor_name(&self, _k: usize) -> Option<String> {
        None
    }
    /// Whether the world judges its runs without truth ([`World::associate`]; summary.json's `residuals`,
    /// `tracks_started`, `tracks_ended`, `measurements_per_track`, `consistency_warnings`).
    fn judged(&self) -> bool {
        false
    }
    /// Before scan `k` is stepped: its measurements' associations with the MAP tracks
    /// ([`crate::eval::consistency`]), in worlds that judge their runs.
    fn associate(&self, _k: usize) -> Option<crate::eval::consistency::ScanAssociations> {
        None
    }
    /// The names and noise σ (the file's units) of the components of `sensor`'s measurements, for its
    /// residual plot ([`crate::pipeline::residual_plots`]); `None`: unknown (residuals drawn as they are).
    fn residual_axes(&self, _sensor: &str) -> Option<Vec<crate::pipeline::residual_plots::Axis>> {
        None
    }
    /// Whether `state` lies in the field of view of scan `k`'s sensor.
    fn in_view(&self, k: usize, state: &[f64]) -> bool;
    /// Whether `estimates.csv` holds the MAP estimates of scan `k` (every scan's, unless the world says
    /// otherwise).
    fn estimates_due(&self, _k: usize) -> bool {
        true
    }
    /// The header of `estimates.csv`.
    fn csv_header(&self) -> &'static str;
    /// The columns of `estimates.csv` before the label (scan, time and, in a network, the sensor).
    fn csv_scan_columns(&self, k: usize) -> String;
    /// Records scan `k` in the world's own outputs (`accepted`: the tracker took the scan; `within`: per MAP
    /// estimate, within the error bound, when there is truth).
    ///
    /// # Errors
    /// [`Error::Output`] when a file cannot be written.
    fn record(&mut self, k: usize, accepted: bool, posterior: &Posterior, within: &[Option<bool>])
    -> Result<(), Error>;
    /// Writes the world's own files at the end (plots, OEM).
    ///
    /// # Errors
    /// [`Error::Output`] when a file cannot be written.
    fn finish(&mut self, records: &[ScanRecord]) -> Result<(), Error>;
}

/// Per-scan figures of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct ScanRecord {
    /// Scan index (0-based).
    pub scan: usize,
    /// Scan time (s).
    pub time: f64,
    /// Wall-clock time of the tracker's step (ms), for accepted scans.
    pub ms: Option<f64>,
    /// Fraction of the children's weight kept, for accepted scans.
    pub captured_mass: Option<f64>,
    /// Whether the reference's memory budget forced dropping parents or children.
    pub budget_reached: bool,
    /// Hypotheses kept.
    pub hypotheses: usize,
    /// Expected number of objects.
    pub expected_cardinality: f64,
    /// Objects in the MAP hypothesis.
    pub map_cardinality: usize,
    /// True number of objects.
    pub true_cardinality: Option<usize>,
    /// GOSPA of the MAP estimates.
    pub gospa: Option<f64>,
    /// OSPA of the MAP estimates.
    pub ospa: Option<f64>,
    /// The tracker's error when it rejected the scan.
    pub error: Option<String>,
    /// Whether that error refused the scan's input ([`StepFailure::Refused`]).
    pub refused: bool,
    /// Tracks the core dropped for a numerical failure at this scan.
    pub numerical_drops: tracker_core::report::NumericalDrops,
    /// Tracks the core declared lost at this scan (`tracker_core::TrackLoss`).
    pub lost_tracks: usize,
    /// Unexplained measurements whose birth cells came from a tracklet (docs/maths.md §5.10).
    pub tracklets_formed: usize,
}

/// Writes one line of `estimates.csv`: the scan's columns, then label, mean, existence and the bound.
pub(crate) fn csv_line(
    csv: &mut impl Write,
    scan_columns: &str,
    estimate: &Estimate,
    within: Option<bool>,
) -> std::io::Result<()> {
    write!(csv, "{scan_columns},{}", estimate.label)?;
    for m in &estimate.mean {
        write!(csv, ",{m}")?;
    }
    let bound = within.map_or(String::new(), |w| w.to_string());
    writeln!(csv, ",{},{bound}", estimate.existence)
}
