//! The planar world (version 1 scenario files, paper 003's geometry): its trackers ([`runner`]), its
//! scenario-to-core conversion ([`setup`]), its adapter to the one replay ([`PlanarWorld`]), `compare`
//! against the unbounded reference ([`compare`]) and its figures ([`plots`]).
//!
//! Besides what every world writes, a planar run writes `scans.jsonl`: per scan, at most
//! `max_hypotheses_out` hypotheses and the tracks they hold. A run of a core tracker is judged without
//! truth as an orbital one is ([`crate::eval::consistency`]; its one sensor named [`SENSOR`]).

pub mod compare;
pub mod plots;
pub mod runner;
pub mod setup;

use crate::error::Error;
use crate::eval::consistency::{Associated, ScanAssociations};
use crate::eval::score::Scored;
use crate::io::report::{LabelExistence, RunSummary, ScanHypothesis, ScanLine};
use crate::pipeline::profile::Profile;
use crate::pipeline::snapshot::Snapshot;
use crate::pipeline::tracker::{ReferenceBudget, StepInfo, StepRejected, TrackerKind};
use crate::pipeline::world::{Estimate, Heading, Posterior, ScanRecord, StepFailure, TruthObject, World};
use crate::scenario::Scenario;
use runner::{Runner, build};
use std::collections::HashMap;
use std::io::Write;
use std::path::{Path, PathBuf};
use tracker_core::Region;

/// The name of a planar scenario's one sensor in summary.json's `residuals` and `consistency_warnings`.
pub const SENSOR: &str = "sensor";

/// Options shared by `run` and `compare` on planar scenarios.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options {
    /// Capacity profile of the core tracker.
    pub profile: Profile,
    /// Budgets of the reference tracker.
    pub reference: ReferenceBudget,
    /// Hypotheses written per scan to `scans.jsonl`.
    pub max_hypotheses_out: usize,
    /// No progress bar.
    pub quiet: bool,
}

/// True objects at scan `k`: (id, position).
pub fn truth_positions(scenario: &Scenario, k: usize) -> Option<Vec<(u64, [f64; 2])>> {
    scenario.truth.as_ref().map(|t| t.scans[k].objects.iter().map(|o| (o.id, [o.state[0], o.state[1]])).collect())
}

/// Scores the MAP estimates of `snapshot` against the truth of scan `k` ([`crate::eval::score`]).
pub fn score(scenario: &Scenario, k: usize, snapshot: &Snapshot) -> Option<Scored> {
    let truth = truth_positions(scenario, k)?;
    let map: Vec<(u32, [f64; 2])> = snapshot.map_tracks().iter().map(|t| (t.label, [t.mean[0], t.mean[1]])).collect();
    Some(crate::eval::score::score(&truth, &map, &scenario.evaluation))
}

/// The planar world's adapter: a scenario, its tracker and its own outputs (`scans.jsonl`, the plots).
pub struct PlanarWorld<'a> {
    scenario: &'a Scenario,
    kind: TrackerKind,
    options: Options,
    runner: Box<dyn Runner>,
    fov: Region<f64>,
    /// The posterior after the last step, whole (for scans.jsonl).
    snapshot: Snapshot,
    scans_path: PathBuf,
    /// scans.jsonl, renamed into place when the run finishes ([`crate::io::atomic`]).
    scans_file: Option<crate::io::atomic::AtomicFile>,
    /// Scans whose posterior is plotted, and (scan, MAP tracks and weights, within the bound) there.
    snapshot_scans: Vec<usize>,
    snapshots: Vec<(usize, Snapshot, Vec<bool>)>,
    /// Tracks the core dropped for a numerical failure at the last step (for scans.jsonl).
    numerical_drops: usize,
    out: PathBuf,
}

impl<'a> PlanarWorld<'a> {
    /// The world of `scenario` with the tracker `kind`, writing into `out`.
    ///
    /// # Errors
    /// Bad input when the tracker cannot be built; [`Error::Output`] when scans.jsonl cannot be created.
    pub fn new(scenario: &'a Scenario, kind: TrackerKind, options: &Options, out: &Path) -> Result<Self, Error> {
        let runner = build(kind, options.profile, scenario, options.reference)?;
        let scans_path = out.join("scans.jsonl");
        let file = crate::io::atomic::AtomicFile::create(&scans_path)?;
        let n = scenario.scans.len();
        Ok(Self {
            scenario,
            kind,
            options: *options,
            runner,
            fov: setup::region(&scenario.sensor.field_of_view),
            snapshot: Snapshot::default(),
            scans_path,
            scans_file: Some(file),
            snapshot_scans: plots::SNAPSHOT_FRACTIONS.iter().map(|&f| plots::scan_at(f, n)).collect(),
            snapshots: vec![],
            numerical_drops: 0,
            out: out.to_path_buf(),
        })
    }
}

impl World<2> for PlanarWorld<'_> {
    fn heading(&self) -> Heading {
        let scenario = self.scenario;
        Heading {
            scenario: scenario.name.clone(),
            tracker: self.kind.name(),
            profile: if self.kind == TrackerKind::Reference { "unbounded" } else { self.options.profile.name() },
            sensors: None,
            sensor_kinds: None,
            evaluation: scenario.evaluation,
            has_truth: scenario.truth.is_some(),
            births: scenario
                .truth
                .iter()
                .flat_map(|t| t.objects.iter().filter(|o| !o.in_prior).map(|o| o.id))
                .collect(),
            peak_counts_prior: false,
            reference: self.kind == TrackerKind::Reference,
            births_from_tracklets_only: false,
        }
    }

    fn scans(&self) -> usize {
        self.scenario.scans.len()
    }

    fn time(&self, k: usize) -> f64 {
        self.scenario.scans[k].time
    }

    fn step(&mut self, k: usize) -> Result<StepInfo, StepFailure> {
        let scan = &self.scenario.scans[k];
        let outcome = self.runner.step(scan.time, &setup::measurements(scan));
        self.numerical_drops = outcome.as_ref().map_or(0, |info| info.numerical_drops.count);
        outcome.map_err(
            |StepRejected(message, refused)| {
                if refused { StepFailure::Refused(message) } else { StepFailure::Rejected(message) }
            },
        )
    }

    fn posterior(&mut self) -> Posterior {
        self.snapshot = self.runner.snapshot();
        let existence: HashMap<u32, f64> = self.snapshot.label_existence().into_iter().collect();
        let map = self
            .snapshot
            .map_tracks()
            .iter()
            .map(|t| Estimate {
                label: t.label,
                mean: t.mean.to_vec(),
                existence: existence.get(&t.label).copied().unwrap_or(0.0),
            })
            .collect();
        Posterior {
            map,
            expected_cardinality: self.snapshot.expected_cardinality(),
            hypotheses: self.snapshot.hypotheses.len(),
        }
    }

    fn truth(&self, k: usize) -> Option<Vec<TruthObject<'_>>> {
        let truth = self.scenario.truth.as_ref()?;
        Some(truth.scans[k].objects.iter().map(|o| TruthObject { id: o.id, state: &o.state }).collect())
    }

    fn detected(&self, k: usize) -> Vec<u64> {
        self.scenario.truth.iter().flat_map(|t| t.scans[k].origins.iter().flatten().copied()).collect()
    }

    fn judged(&self) -> bool {
        self.kind != TrackerKind::Reference
    }

    fn associate(&self, k: usize) -> Option<ScanAssociations> {
        let scan = &self.scenario.scans[k];
        let zs: Vec<Vec<f64>> = scan.measurements.iter().map(|z| z.to_vec()).collect();
        let associations = self.runner.associate(scan.time, &zs)?;
        let associated = associations
            .into_iter()
            .flatten()
            .map(|(label, residual, nis)| Associated { label, residual, nis })
            .collect();
        Some(ScanAssociations { sensor: SENSOR.into(), dimension: 2, measurements: zs.len(), associated })
    }

    fn residual_axes(&self, _sensor: &str) -> Option<Vec<crate::pipeline::residual_plots::Axis>> {
        let crate::scenario::MeasurementSpec::Position { noise_covariance } = &self.scenario.measurement;
        Some(vec![("x", noise_covariance[0][0].sqrt()), ("y", noise_covariance[1][1].sqrt())])
    }

    fn in_view(&self, _k: usize, state: &[f64]) -> bool {
        self.fov.contains(&nalgebra::SVector::<f64, 2>::new(state[0], state[1]))
    }

    fn csv_header(&self) -> &'static str {
        "scan,time,label,x,y,vx,vy,existence,within_error_bound"
    }

    fn csv_scan_columns(&self, k: usize) -> String {
        format!("{k},{}", self.scenario.scans[k].time)
    }

    fn record(
        &mut self,
        k: usize,
        _accepted: bool,
        _posterior: &Posterior,
        within: &[Option<bool>],
    ) -> Result<(), Error> {
        let mut line = scan_line(k, self.scenario.scans[k].time, &self.snapshot, self.options.max_hypotheses_out);
        line.numerical_drops = self.numerical_drops;
        let path = &self.scans_path;
        let file = self.scans_file.as_mut().ok_or_else(|| Error::internal("scans.jsonl already written"))?;
        serde_json::to_writer(&mut *file, &line).map_err(|e| Error::output(path, e))?;
        writeln!(file).map_err(|e| Error::output(path, e))?;
        if self.snapshot_scans.contains(&k) {
            // Without truth, no estimate is marked (an empty list).
            let within: Vec<bool> = within.iter().copied().collect::<Option<_>>().unwrap_or_default();
            // The plots need only the MAP tracks and the weights: a full copy of a large posterior
            // (the reference's) would not fit its memory budget.
            self.snapshots.push((k, plots::map_and_weights(&self.snapshot), within));
        }
        Ok(())
    }

    fn finish(&mut self, records: &[ScanRecord]) -> Result<(), Error> {
        let file = self.scans_file.take().ok_or_else(|| Error::internal("scans.jsonl already written"))?;
        file.commit()?;
        plots::write_run_plots(self.scenario, records, &self.snapshots, &self.out)?;
        self.snapshots.clear();
        Ok(())
    }
}

/// `host-sim run` on a planar scenario: runs `kind` on `scenario`, writes `summary.json`, `scans.jsonl`,
/// `estimates.csv` and the plots into `out`, and returns the summary and whether every scan was accepted.
///
/// # Errors
/// A one-line message when the tracker cannot be built or a file cannot be written.
pub fn run(scenario: &Scenario, kind: TrackerKind, options: &Options, out: &Path) -> Result<(RunSummary, bool), Error> {
    std::fs::create_dir_all(out).map_err(|e| Error::output(out, e))?;
    let mut world = PlanarWorld::new(scenario, kind, options, out)?;
    crate::pipeline::replay::run(&mut world, options.quiet, out)
}

/// One scan's line of `scans.jsonl`: at most `max` hypotheses and the tracks they hold.
fn scan_line(k: usize, time: f64, snapshot: &Snapshot, max: usize) -> ScanLine {
    let written = &snapshot.hypotheses[..snapshot.hypotheses.len().min(max)];
    let mut index: HashMap<usize, usize> = HashMap::new();
    let mut tracks = vec![];
    let hypotheses = written
        .iter()
        .map(|h| {
            let ids: Vec<usize> = h
                .tracks
                .iter()
                .map(|&t| {
                    *index.entry(t).or_insert_with(|| {
                        tracks.push(snapshot.tracks[t].clone());
                        tracks.len() - 1
                    })
                })
                .collect();
            ScanHypothesis { weight: h.weight, tracks: ids }
        })
        .collect();
    let existence =
        snapshot.label_existence().iter().map(|&(label, existence)| LabelExistence { label, existence }).collect();
    ScanLine {
        scan: k,
        time,
        expected_cardinality: snapshot.expected_cardinality(),
        hypotheses_total: snapshot.hypotheses.len(),
        hypotheses,
        tracks,
        numerical_drops: 0,
        existence,
    }
}
