//! Running a tracker over a scenario, scoring it against the truth, and writing the outputs of
//! `host-sim run` and `host-sim compare`.
//!
//! Scoring uses the MAP hypothesis's estimates: GOSPA (α = 2, cut-off and order from the scenario's
//! `evaluation`), OSPA, the error of the expected cardinality, and label switches along GOSPA's
//! assignment. An estimate is *within the error bound* when GOSPA with cut-off `error_bound` assigns it to
//! a true object. A born object is *confirmed* once GOSPA with cut-off `error_bound` assigns it a MAP
//! track whose label's existence probability reaches `confirmation_existence` ([`crate::eval::births`]).

use crate::eval::births::{BirthTally, MapTrack};
use crate::error::Error;
use crate::metrics::{LabelSwitches, gospa, ospa};
use crate::plots::{self, FovLines, Scale, Series, SnapshotPanel};
use crate::report::{
    BirthsSummary, CompareReport, CompareScan, CompareSide, CompareSummary, LabelExistence, RejectedScan, RunSummary,
    ScanHypothesis, ScanLine,
};
use crate::pipeline::planar::runner::{Profile, ReferenceBudget, Runner, TrackerKind, build};
use crate::scenario::{FieldOfViewSpec, Scenario};
use crate::pipeline::planar::setup;
use crate::pipeline::snapshot::{HypothesisOut, Snapshot, TrackOut, match_posteriors};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use serde::Serialize;
use std::collections::HashMap;
use std::io::{IsTerminal, Write};
use std::path::Path;
use std::time::Instant;

/// Options shared by `run` and `compare`.
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

/// The mean of `values`, 0 when there is none.
pub(crate) fn mean(values: &[f64]) -> f64 {
    if values.is_empty() { 0.0 } else { values.iter().sum::<f64>() / values.len() as f64 }
}

/// The fractions of the run at which snapshots are plotted (paper 003 Figs. 6, 8-10).
pub const SNAPSHOT_FRACTIONS: [f64; 4] = [0.10, 0.50, 0.75, 1.00];

/// The scan index at a fraction of a run of `scans` scans.
pub fn scan_at(fraction: f64, scans: usize) -> usize {
    ((fraction * scans as f64).ceil() as usize).clamp(1, scans.max(1)) - 1
}

/// True objects at scan `k`: (id, position).
pub fn truth_positions(scenario: &Scenario, k: usize) -> Option<Vec<(u64, [f64; 2])>> {
    scenario.truth.as_ref().map(|t| t.scans[k].objects.iter().map(|o| (o.id, [o.state[0], o.state[1]])).collect())
}

/// Per-scan record of a run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ScanRecord {
    /// Scan index (0-based).
    pub scan: usize,
    /// Scan time (s).
    pub time: f64,
    /// Wall-clock time of the tracker's step (ms).
    pub ms: f64,
    /// Children generated.
    pub children: u64,
    /// Hypotheses kept.
    pub hypotheses: usize,
    /// Fraction of the children's weight kept.
    pub captured_mass: f64,
    /// Whether the reference's memory budget forced dropping parents or children (never for the core).
    pub budget_reached: bool,
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
}

/// The scored estimates of one scan.
pub(crate) struct Scored {
    pub(crate) gospa: f64,
    ospa: f64,
    /// (truth id, label) pairs within the GOSPA cut-off.
    pairs: Vec<(u64, u32)>,
    /// Per MAP track: within the error bound.
    within_bound: Vec<bool>,
    /// Per true object (in truth order): (id, whether a MAP estimate is within the error bound of it).
    truth_covered: Vec<(u64, bool)>,
    /// Per true object, the MAP track GOSPA with cut-off `error_bound` assigns to it.
    bound_assignment: Vec<Option<usize>>,
}

pub(crate) fn score(scenario: &Scenario, k: usize, snapshot: &Snapshot) -> Option<Scored> {
    let truth = truth_positions(scenario, k)?;
    let evaluation = &scenario.evaluation;
    let points: Vec<[f64; 2]> = truth.iter().map(|t| t.1).collect();
    let map = snapshot.map_tracks();
    let estimates: Vec<[f64; 2]> = map.iter().map(|t| [t.mean[0], t.mean[1]]).collect();
    let g = gospa(&points, &estimates, evaluation.gospa_cutoff, evaluation.gospa_order);
    let pairs = g.assignment.iter().enumerate().filter_map(|(i, e)| e.map(|e| (truth[i].0, map[e].label))).collect();
    let bound = gospa(&points, &estimates, evaluation.error_bound, 1.0);
    let mut within_bound = vec![false; estimates.len()];
    for e in bound.assignment.iter().flatten() {
        within_bound[*e] = true;
    }
    let truth_covered = truth.iter().zip(&bound.assignment).map(|(t, a)| (t.0, a.is_some())).collect();
    Some(Scored {
        gospa: g.distance,
        ospa: ospa(&points, &estimates, evaluation.gospa_cutoff, evaluation.gospa_order),
        pairs,
        within_bound,
        truth_covered,
        bound_assignment: bound.assignment,
    })
}

/// Records scan `k` of a run in the births tally ([`crate::eval::births`]).
fn record_births(tally: &mut BirthTally, scenario: &Scenario, k: usize, snapshot: &Snapshot, scored: &Scored) {
    let Some(truth) = &scenario.truth else { return };
    let scan = &truth.scans[k];
    let objects: Vec<(u64, &[f64])> = scan.objects.iter().map(|o| (o.id, &o.state[..2])).collect();
    let existence: HashMap<u32, f64> = snapshot.label_existence().into_iter().collect();
    let map: Vec<MapTrack<'_>> = snapshot
        .map_tracks()
        .into_iter()
        .map(|t| MapTrack {
            label: t.label,
            position: &t.mean[..2],
            existence: existence.get(&t.label).copied().unwrap_or(0.0),
        })
        .collect();
    tally.record(k, &objects, scan.origins.iter().flatten().copied(), &map, &scored.bound_assignment);
}

pub(crate) fn progress(scans: usize, quiet: bool, message: &'static str) -> ProgressBar {
    if quiet || !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::with_draw_target(Some(scans as u64), ProgressDrawTarget::stderr());
    if let Ok(style) = ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} scans, {elapsed} (eta {eta})") {
        bar.set_style(style.progress_chars("=> "));
    }
    bar.set_message(message);
    bar
}

fn io_error(path: &Path, e: impl std::fmt::Display) -> Error {
    Error::output(path, e)
}

/// Writes `value` as pretty JSON and a line break to `path`.
///
/// # Errors
/// [`Error::Output`] when the file cannot be written.
pub fn write_json(path: &Path, value: &impl Serialize) -> Result<(), Error> {
    let text = serde_json::to_string_pretty(value).map_err(|e| io_error(path, e))?;
    std::fs::write(path, text + "\n").map_err(|e| io_error(path, e))
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
        existence,
    }
}

fn fov_lines(scenario: &Scenario) -> Option<FovLines> {
    match scenario.sensor.field_of_view {
        FieldOfViewSpec::Sector { origin, look_direction_deg, field_of_view_deg, max_range } => Some(FovLines {
            origin,
            look_direction: look_direction_deg.to_radians(),
            half_angle: field_of_view_deg.to_radians() / 2.0,
            max_range,
        }),
        _ => None,
    }
}

fn is_ssa(scenario: &Scenario) -> bool {
    matches!(scenario.motion, crate::scenario::MotionSpec::TwoBody { .. })
}

/// `host-sim run`: runs `kind` on `scenario`, writes `summary.json`, `scans.jsonl`, `estimates.csv` and the
/// plots into `out`, and returns the summary and whether every scan was accepted.
///
/// # Errors
/// A one-line message when the tracker cannot be built or a file cannot be written.
pub fn run(scenario: &Scenario, kind: TrackerKind, options: &Options, out: &Path) -> Result<(RunSummary, bool), Error> {
    std::fs::create_dir_all(out).map_err(|e| io_error(out, e))?;
    let mut runner = build(kind, options.profile, scenario, options.reference)?;
    let prior = runner.snapshot();
    let prior_cardinality = (prior.expected_cardinality(), prior.map_tracks().len());
    let scans_path = out.join("scans.jsonl");
    let mut scans_file =
        std::io::BufWriter::new(std::fs::File::create(&scans_path).map_err(|e| io_error(&scans_path, e))?);
    let csv_path = out.join("estimates.csv");
    let mut csv = std::io::BufWriter::new(std::fs::File::create(&csv_path).map_err(|e| io_error(&csv_path, e))?);
    writeln!(csv, "scan,time,label,x,y,vx,vy,existence,within_error_bound").map_err(|e| io_error(&csv_path, e))?;

    let n = scenario.scans.len();
    let snapshot_scans: Vec<usize> = SNAPSHOT_FRACTIONS.iter().map(|&f| scan_at(f, n)).collect();
    let mut snapshots: Vec<(usize, Snapshot, Vec<bool>)> = vec![];
    let mut records = vec![];
    let mut switches = LabelSwitches::new();
    let mut births = BirthTally::new(
        scenario.truth.iter().flat_map(|t| t.objects.iter().filter(|o| !o.in_prior).map(|o| o.id)),
        scenario.evaluation.confirmation_existence,
        scenario.evaluation.error_bound,
    );
    let mut peak_hypotheses = 0;
    let fov = setup::region(&scenario.sensor.field_of_view);
    let (mut in_view_misses, mut in_view_red_stars, mut out_of_view_red_stars) = (0usize, 0usize, 0usize);
    let bar = progress(n, options.quiet, kind.name());
    for (k, scan) in scenario.scans.iter().enumerate() {
        let zs = setup::measurements(scan);
        let start = Instant::now();
        let outcome = runner.step(scan.time, &zs);
        let ms = start.elapsed().as_secs_f64() * 1e3;
        bar.inc(1);
        let snapshot = runner.snapshot();
        let scored = score(scenario, k, &snapshot);
        if let Some(s) = &scored {
            switches.record(&s.pairs);
            record_births(&mut births, scenario, k, &snapshot, s);
        }
        let (info, error) = match outcome {
            Ok(info) => (Some(info), None),
            Err(e) => {
                bar.suspend(|| eprintln!("warning: scan {k} (t = {}) rejected: {e}", scan.time));
                (None, Some(e.0))
            }
        };
        peak_hypotheses = peak_hypotheses.max(snapshot.hypotheses.len());
        let map = snapshot.map_tracks();
        // Paper 003's "no red stars", restricted to what the sensor sees: an object in the field of view
        // whose track is confirmed (prior objects from the start, births from their confirmation) must
        // have a MAP estimate within the error bound, and no MAP estimate in the field of view may be
        // outside the bound of every true object.
        if let (Some(s), Some(truth)) = (&scored, truth_positions(scenario, k)) {
            for ((id, covered), (_, position)) in s.truth_covered.iter().zip(&truth) {
                let confirmed_track = !births.is_birth(*id) || births.confirmed_at(*id).is_some_and(|c| c <= k);
                if confirmed_track && !covered && fov.contains(&nalgebra::SVector::<f64, 2>::from(*position)) {
                    in_view_misses += 1;
                }
            }
            for (t, within) in map.iter().zip(&s.within_bound) {
                if !within {
                    if fov.contains(&nalgebra::SVector::<f64, 2>::new(t.mean[0], t.mean[1])) {
                        in_view_red_stars += 1;
                    } else {
                        // Out of view nothing corrects a track: counted, not a failure of the check.
                        out_of_view_red_stars += 1;
                    }
                }
            }
        }
        let within: Vec<bool> = scored.as_ref().map(|s| s.within_bound.clone()).unwrap_or_default();
        for (i, t) in map.iter().enumerate() {
            let existence = snapshot.label_existence().iter().find(|e| e.0 == t.label).map_or(0.0, |e| e.1);
            let bound = within.get(i).map_or(String::new(), |w| w.to_string());
            writeln!(
                csv,
                "{k},{},{},{},{},{},{},{existence},{bound}",
                scan.time, t.label, t.mean[0], t.mean[1], t.mean[2], t.mean[3]
            )
            .map_err(|e| io_error(&csv_path, e))?;
        }
        serde_json::to_writer(&mut scans_file, &scan_line(k, scan.time, &snapshot, options.max_hypotheses_out))
            .map_err(|e| io_error(&scans_path, e))?;
        writeln!(scans_file).map_err(|e| io_error(&scans_path, e))?;
        records.push(ScanRecord {
            scan: k,
            time: scan.time,
            ms,
            children: info.map_or(0, |i| i.children),
            hypotheses: snapshot.hypotheses.len(),
            captured_mass: info.map_or(1.0, |i| i.captured_mass),
            budget_reached: info.is_some_and(|i| i.budget_reached),
            expected_cardinality: snapshot.expected_cardinality(),
            map_cardinality: map.len(),
            true_cardinality: truth_positions(scenario, k).map(|t| t.len()),
            gospa: scored.as_ref().map(|s| s.gospa),
            ospa: scored.as_ref().map(|s| s.ospa),
            error,
        });
        if snapshot_scans.contains(&k) {
            // The plots need only the MAP tracks and the weights: a full copy of a large posterior
            // (the reference's) would not fit its memory budget.
            snapshots.push((k, map_and_weights(&snapshot), within));
        }
    }
    bar.finish_and_clear();
    scans_file.flush().map_err(|e| io_error(&scans_path, e))?;
    csv.flush().map_err(|e| io_error(&csv_path, e))?;

    let accepted: Vec<&ScanRecord> = records.iter().filter(|r| r.error.is_none()).collect();
    let ms: Vec<f64> = accepted.iter().map(|r| r.ms).collect();
    let gospas: Vec<f64> = records.iter().filter_map(|r| r.gospa).collect();
    let ospas: Vec<f64> = records.iter().filter_map(|r| r.ospa).collect();
    let rejected: Vec<RejectedScan> = records
        .iter()
        .filter_map(|r| r.error.as_ref().map(|e| RejectedScan { scan: r.scan, error: e.clone() }))
        .collect();
    let last = records.last();
    let figures = births.figures();
    let summary = RunSummary {
        scenario: scenario.name.clone(),
        tracker: kind.name().into(),
        profile: if kind == TrackerKind::Reference { "unbounded" } else { options.profile.name() }.into(),
        scans: n,
        // Without truth there is nothing to score: null, not 0.
        mean_gospa: (!gospas.is_empty()).then(|| mean(&gospas)),
        mean_ospa: (!ospas.is_empty()).then(|| mean(&ospas)),
        gospa_cutoff: scenario.evaluation.gospa_cutoff,
        gospa_order: scenario.evaluation.gospa_order,
        error_bound: scenario.evaluation.error_bound,
        // Without scans, the prior's figures.
        final_expected_cardinality: last.map_or(prior_cardinality.0, |r| r.expected_cardinality),
        final_map_cardinality: last.map_or(prior_cardinality.1, |r| r.map_cardinality),
        true_final_cardinality: last.and_then(|r| r.true_cardinality),
        births: BirthsSummary::new(figures, scenario.truth.is_some()),
        label_switches: switches.total(),
        in_view_misses_after_confirmation: in_view_misses,
        in_view_red_stars,
        out_of_view_red_stars,
        mean_ms_per_scan: mean(&ms),
        max_ms_per_scan: ms.iter().copied().fold(0.0, f64::max),
        peak_hypotheses,
        mean_captured_mass: mean(&accepted.iter().map(|r| r.captured_mass).collect::<Vec<_>>()),
        min_captured_mass: accepted.iter().map(|r| r.captured_mass).fold(1.0, f64::min),
        rejected_scans: rejected,
        reference_budget_reached_scans: records
            .iter()
            .filter(|r| r.budget_reached && kind == TrackerKind::Reference)
            .map(|r| r.scan)
            .collect(),
        peak_resident_kib: None,
        sensors: None,
    };
    write_run_plots(scenario, &records, &snapshots, out)?;
    drop(snapshots);
    let mut summary = summary;
    // The process's peak resident memory so far (Linux), to check the reference's budget.
    summary.peak_resident_kib = peak_resident_kib();
    write_json(&out.join("summary.json"), &summary)?;
    let clean = summary.rejected_scans.is_empty();
    Ok((summary, clean))
}

/// VmHWM of /proc/self/status in KiB, where there is one.
pub(crate) fn peak_resident_kib() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// The part of `snapshot` that the run plots use: every hypothesis's weight, the MAP hypothesis's tracks.
fn map_and_weights(snapshot: &Snapshot) -> Snapshot {
    let tracks: Vec<TrackOut> = snapshot.map_tracks().into_iter().cloned().collect();
    let hypotheses = snapshot
        .hypotheses
        .iter()
        .enumerate()
        .map(|(i, h)| HypothesisOut {
            weight: h.weight,
            log_weight: h.log_weight,
            tracks: if i == 0 { (0..tracks.len()).collect() } else { vec![] },
        })
        .collect();
    Snapshot { hypotheses, tracks }
}

fn write_run_plots(
    scenario: &Scenario,
    records: &[ScanRecord],
    snapshots: &[(usize, Snapshot, Vec<bool>)],
    out: &Path,
) -> Result<(), Error> {
    let n = records.len().max(1);
    let unit = if is_ssa(scenario) { "km" } else { "" };
    let panels: Vec<SnapshotPanel> = snapshots
        .iter()
        .map(|(k, snapshot, within)| {
            let map = snapshot.map_tracks();
            let (mut inside, mut outside) = (vec![], vec![]);
            for (i, t) in map.iter().enumerate() {
                // Without truth every estimate is drawn as within the bound.
                if within.get(i).copied().unwrap_or(true) {
                    inside.push([t.mean[0], t.mean[1]])
                } else {
                    outside.push([t.mean[0], t.mean[1]])
                }
            }
            SnapshotPanel {
                title: format!("{:.0}% (scan {}): truth vs MAP", 100.0 * (*k + 1) as f64 / n as f64, k),
                truth: truth_positions(scenario, *k).unwrap_or_default().iter().map(|t| t.1).collect(),
                estimates_within_bound: inside,
                estimates_outside_bound: outside,
                fov: fov_lines(scenario),
                unit: unit.to_string(),
                central_body_radius: is_ssa(scenario).then_some(crate::sim::EARTH_RADIUS),
            }
        })
        .collect();
    plots::plot_snapshots(&out.join("truth_vs_map"), &panels)?;
    let weights: Vec<(String, Vec<f64>)> = snapshots
        .iter()
        .map(|(k, s, _)| {
            (
                format!("{:.0}% (scan {k})", 100.0 * (*k + 1) as f64 / n as f64),
                s.hypotheses.iter().map(|h| h.weight).collect(),
            )
        })
        .collect();
    plots::plot_hypothesis_weights(&out.join("hypothesis_weights"), &weights)?;
    let percent = |r: &ScanRecord| 100.0 * (r.scan + 1) as f64 / n as f64;
    let mut series = vec![Series {
        name: "expected number of objects".into(),
        points: records.iter().map(|r| (percent(r), r.expected_cardinality)).collect(),
        markers: false,
    }];
    if records.iter().any(|r| r.true_cardinality.is_some()) {
        series.push(Series {
            name: "true number of objects".into(),
            points: records.iter().filter_map(|r| r.true_cardinality.map(|c| (percent(r), c as f64))).collect(),
            markers: false,
        });
    }
    plots::plot_series(
        &out.join("expected_cardinality"),
        "Expected number of objects",
        "run completed (%)",
        "objects",
        Scale::Linear,
        Scale::Linear,
        &series,
    )?;
    if records.iter().any(|r| r.gospa.is_some()) {
        let gospa_series = [Series {
            name: "GOSPA of the MAP estimates".into(),
            points: records.iter().filter_map(|r| r.gospa.map(|g| (percent(r), g))).collect(),
            markers: false,
        }];
        plots::plot_series(
            &out.join("gospa"),
            "GOSPA over the run",
            "run completed (%)",
            &format!("GOSPA ({unit})"),
            Scale::Linear,
            Scale::Linear,
            &gospa_series,
        )?;
    }
    Ok(())
}

/// `host-sim compare`: runs the bounded tracker `bounded` and the unbounded reference on the same scans
/// and writes `compare.json`.
///
/// Captured mass = the reference's posterior mass on the hypotheses the bounded tracker kept; weight L1 =
/// Σ |w_bounded − w_reference| over the union of hypotheses; MAP agreement = the bounded tracker's MAP
/// hypothesis has the reference's largest weight. Hypotheses are matched by the exact bits of their
/// tracks' states ([`Snapshot::hypothesis_key`]).
///
/// # Errors
/// A one-line message when a tracker cannot be built or the file cannot be written.
pub fn compare(
    scenario: &Scenario,
    bounded: TrackerKind,
    options: &Options,
    out: &Path,
) -> Result<CompareReport, Error> {
    std::fs::create_dir_all(out).map_err(|e| io_error(out, e))?;
    let mut trackers: [Box<dyn Runner>; 2] = [
        build(bounded, options.profile, scenario, options.reference)?,
        build(TrackerKind::Reference, options.profile, scenario, options.reference)?,
    ];
    let bar = progress(scenario.scans.len(), options.quiet, "compare");
    let mut per_scan = vec![];
    let mut ms_totals = [vec![], vec![]];
    let mut gospas = [vec![], vec![]];
    let mut budget_scans = vec![];
    for (k, scan) in scenario.scans.iter().enumerate() {
        let zs = setup::measurements(scan);
        let mut snapshots = vec![];
        let mut errors = vec![];
        for (i, tracker) in trackers.iter_mut().enumerate() {
            let start = Instant::now();
            let outcome = tracker.step(scan.time, &zs);
            ms_totals[i].push(start.elapsed().as_secs_f64() * 1e3);
            if let Ok(info) = &outcome
                && info.budget_reached
            {
                budget_scans.push(k);
            }
            errors.push(outcome.err().map(|e| e.0));
            let snapshot = tracker.snapshot();
            if let Some(s) = score(scenario, k, &snapshot) {
                gospas[i].push(s.gospa);
            }
            snapshots.push(snapshot);
        }
        bar.inc(1);
        let (b, r) = (&snapshots[0], &snapshots[1]);
        let matched = match_posteriors(r, b);
        let (captured, l1) = (matched.captured_mass, matched.weight_l1);
        let reference_max = r.hypotheses.first().map_or(0.0, |h| h.weight);
        let map_weight_in_reference = matched.exact_weight_of_map;
        let agree = reference_max > 0.0 && (map_weight_in_reference - reference_max).abs() <= 1e-9 * reference_max;
        let [bounded_error, reference_error] = [errors[0].take(), errors[1].take()];
        per_scan.push(CompareScan {
            scan: k,
            time: scan.time,
            captured_mass: captured,
            weight_l1: l1,
            map_agreement: agree,
            bounded_hypotheses: b.hypotheses.len(),
            reference_hypotheses: r.hypotheses.len(),
            bounded_ms: ms_totals[0][k],
            reference_ms: ms_totals[1][k],
            bounded_error,
            reference_error,
        });
    }
    bar.finish_and_clear();
    // Non-finite figures are written as null and left out of the means, as they always were.
    let column = |f: fn(&CompareScan) -> f64| per_scan.iter().map(f).filter(|v| v.is_finite()).collect::<Vec<f64>>();
    let captured = column(|s| s.captured_mass);
    let agreement = per_scan.iter().filter(|s| s.map_agreement).count() as f64 / per_scan.len().max(1) as f64;
    let side = |tracker: &str, slot: usize| CompareSide {
        tracker: tracker.into(),
        mean_gospa: (!gospas[slot].is_empty()).then(|| mean(&gospas[slot])),
        mean_ms_per_scan: mean(&ms_totals[slot]),
        max_ms_per_scan: ms_totals[slot].iter().copied().fold(0.0, f64::max),
        budget_reached_scans: None,
    };
    let summary = CompareSummary {
        scenario: scenario.name.clone(),
        bounded_tracker: bounded.name().into(),
        profile: options.profile.name().into(),
        scans: scenario.scans.len(),
        mean_captured_mass: mean(&captured),
        min_captured_mass: captured.iter().copied().fold(1.0, f64::min),
        mean_weight_l1: mean(&column(|s| s.weight_l1)),
        map_agreement: agreement,
        bounded: side(bounded.name(), 0),
        reference: CompareSide { budget_reached_scans: Some(budget_scans), ..side("reference", 1) },
    };
    let result = CompareReport { summary, per_scan };
    write_json(&out.join("compare.json"), &result)?;
    Ok(result)
}
