//! The one replay of a scenario through a tracker, whatever the world: step every scan, score the MAP
//! estimates against the truth, tally births and label switches, check what the sensor sees, write
//! `estimates.csv` and `summary.json` (the world adapter writes its own files, [`World::record`]).
//!
//! Scoring: GOSPA (α = 2, cut-off and order from the scenario's `evaluation`), OSPA, the error of the
//! expected cardinality, and label switches along GOSPA's assignment ([`crate::eval::score`]). A born
//! object is *confirmed* once GOSPA with cut-off `error_bound` assigns it a MAP track whose label's
//! existence probability reaches `confirmation_existence` ([`crate::eval::births`]).
//!
//! Nothing the tracker does not take passes in silence: a scan the core refuses for its input (a
//! measurement outside the field of view, …) is reported and the run goes on (`refused_scans`); tracks the
//! core drops for a numerical failure are counted (`numerical_drops`). Each gets a stderr line, for the
//! first [`NOTICE_LINES`] scans of each kind and then one count at the end.

use crate::error::Error;
use crate::eval::births::{BirthTally, MapTrack};
use crate::eval::consistency::Judge;
use crate::eval::metrics::LabelSwitches;
use crate::eval::observed::{MATCH_CUTOFF_KM, ObjectAt, ObservedErrors, observed_errors};
use crate::eval::score::{Scored, score};
use crate::io::report::{NumericalDrop, NumericalDropsSummary, RefusedScan, RefusedScans, RejectedScan, RunSummary};
use crate::pipeline::output::{mean, peak_resident_kib, progress, write_json};
use crate::pipeline::world::{Posterior, ScanRecord, StepFailure, TruthObject, World, csv_line};
use std::io::Write;
use std::path::Path;
use std::time::Instant;

/// What the replay counts over the run besides the per-scan records.
struct Tally {
    births: BirthTally,
    switches: LabelSwitches,
    in_view_misses: usize,
    in_view_red_stars: usize,
    out_of_view_red_stars: usize,
    peak_hypotheses: usize,
    /// The labels of the prior's MAP tracks (object i's prior track is labelled i).
    prior_labels: std::collections::HashSet<u32>,
    /// Each object's latest observation time.
    last_observed: std::collections::HashMap<u64, f64>,
    /// Per scan with truth: its time and the observed and unobserved objects' errors.
    observed: Vec<(f64, ObservedErrors)>,
}

impl Tally {
    /// The tally before the first scan.
    fn new(heading: &crate::pipeline::world::Heading, prior: &Posterior) -> Self {
        let evaluation = heading.evaluation;
        Tally {
            births: BirthTally::new(
                heading.births.iter().copied(),
                evaluation.confirmation_existence,
                evaluation.error_bound,
            ),
            switches: LabelSwitches::new(),
            in_view_misses: 0,
            in_view_red_stars: 0,
            out_of_view_red_stars: 0,
            peak_hypotheses: if heading.peak_counts_prior { prior.hypotheses } else { 0 },
            prior_labels: prior.map.iter().map(|t| t.label).collect(),
            last_observed: std::collections::HashMap::new(),
            observed: vec![],
        }
    }
}

/// Scans of one kind (refused, with numerical drops) that get their own stderr line; the rest are counted
/// in one line at the end of the run.
pub const NOTICE_LINES: usize = 10;

/// The stderr lines of refused scans and numerical drops: one per scan for the first [`NOTICE_LINES`] of
/// each kind, then a count.
#[derive(Default)]
struct Notices {
    refused: usize,
    drops: usize,
}

impl Notices {
    /// The line for scan `k` at `time` refused by the core (`sensor`: its name when the world names it).
    fn refused(&mut self, k: usize, time: f64, sensor: Option<&str>, why: &str) -> Option<String> {
        self.refused += 1;
        let sensor = sensor.map_or(String::new(), |s| format!(", sensor {s}"));
        (self.refused <= NOTICE_LINES)
            .then(|| format!("warning: scan {k} (t = {time}{sensor}) refused: {why}; the run goes on"))
    }

    /// The line for scan `k` at `time` whose step dropped tracks for a numerical failure.
    fn dropped(&mut self, k: usize, time: f64, drops: &tracker_core::report::NumericalDrops) -> Option<String> {
        let (label, error) = drops.first?;
        self.drops += 1;
        (self.drops <= NOTICE_LINES).then(|| {
            format!(
                "warning: scan {k} (t = {time}): {} track(s) dropped for a numerical failure, the first track {} ({error})",
                drops.count, label.0
            )
        })
    }

    /// The counts of the scans beyond the first [`NOTICE_LINES`] of each kind.
    fn finish(&self) -> Vec<String> {
        let mut lines = vec![];
        if self.refused > NOTICE_LINES {
            lines.push(format!(
                "warning: {} more scans refused (refused_scans in summary.json)",
                self.refused - NOTICE_LINES
            ));
        }
        if self.drops > NOTICE_LINES {
            lines.push(format!(
                "warning: {} more scans dropped tracks for a numerical failure (numerical_drops in summary.json)",
                self.drops - NOTICE_LINES
            ));
        }
        lines
    }
}

/// The first `P` entries of `state`.
fn position<const P: usize>(state: &[f64]) -> [f64; P] {
    core::array::from_fn(|i| state[i])
}

/// Scores scan `k` and records it in the tally: label switches, births, and paper 003's "no red stars"
/// restricted to what the sensor sees (an object in view whose track is confirmed, prior objects from the
/// start and births from their confirmation, must have a MAP estimate within the error bound; a MAP
/// estimate outside the bound of every true object is a red star, counted apart when out of view, where
/// nothing corrects a track).
fn score_scan<W: World<P>, const P: usize>(
    world: &W,
    k: usize,
    truth: &[TruthObject<'_>],
    posterior: &Posterior,
    tally: &mut Tally,
    evaluation: &crate::scenario::EvaluationSpec,
) -> Scored {
    let points: Vec<(u64, [f64; P])> = truth.iter().map(|t| (t.id, position(t.state))).collect();
    let estimates: Vec<(u32, [f64; P])> = posterior.map.iter().map(|t| (t.label, position(&t.mean))).collect();
    let scored = score(&points, &estimates, evaluation);
    tally.switches.record(&scored.pairs);
    let objects: Vec<(u64, &[f64])> = truth.iter().map(|t| (t.id, &t.state[..P])).collect();
    let map: Vec<MapTrack<'_>> = posterior
        .map
        .iter()
        .map(|t| MapTrack { label: t.label, position: &t.mean[..P], existence: t.existence })
        .collect();
    let detected = world.detected(k);
    observe::<P>(world.time(k), &detected, truth, posterior, tally);
    tally.births.record(k, &objects, detected, &map, &scored.bound_assignment);
    for (t, assigned) in truth.iter().zip(&scored.bound_assignment) {
        let confirmed_track = !tally.births.is_birth(t.id) || tally.births.confirmed_at(t.id).is_some();
        if confirmed_track && assigned.is_none() && world.in_view(k, t.state) {
            tally.in_view_misses += 1;
        }
    }
    for (t, within) in posterior.map.iter().zip(&scored.within_bound) {
        if !within {
            if world.in_view(k, &t.mean) {
                tally.in_view_red_stars += 1;
            } else {
                tally.out_of_view_red_stars += 1;
            }
        }
    }
    scored
}

/// Records the objects `detected` at `time` and the observed and unobserved objects' errors then
/// ([`crate::eval::observed`]); 3-D runs only.
fn observe<const P: usize>(
    time: f64,
    detected: &[u64],
    truth: &[TruthObject<'_>],
    posterior: &Posterior,
    tally: &mut Tally,
) {
    if P != 3 {
        return; // catalogue figures, in km: 3-D runs only
    }
    for &id in detected {
        tally.last_observed.insert(id, time);
    }
    let objects: Vec<ObjectAt<P>> = truth
        .iter()
        .map(|t| ObjectAt {
            id: t.id,
            position: position(t.state),
            prior_label: u32::try_from(t.id).ok().filter(|l| tally.prior_labels.contains(l)),
            last_observed: tally.last_observed.get(&t.id).copied(),
        })
        .collect();
    let tracks: Vec<(u32, [f64; P])> = posterior.map.iter().map(|t| (t.label, position(&t.mean))).collect();
    tally.observed.push((time, observed_errors(time, &objects, &tracks, MATCH_CUTOFF_KM)));
}

/// The plot of the observed and unobserved objects' median errors over the run (`observed_errors.png` and
/// `.svg`), for 3-D runs with truth (none for others).
fn plot_observed<const P: usize>(observed: &[(f64, ObservedErrors)], out: &Path) -> Result<(), Error> {
    if P != 3 || observed.is_empty() {
        return Ok(());
    }
    let series = |name: &str, pick: fn(&ObservedErrors) -> Option<f64>| crate::plots::Series {
        name: name.into(),
        points: observed.iter().filter_map(|(t, e)| pick(e).map(|v| (t / 3600.0, v.max(1e-3)))).collect(),
        markers: false,
    };
    let lines = [
        series("observed objects: median error", |e| e.observed_median_error_km),
        series("unobserved objects: median prediction error", |e| e.unobserved_median_error_km),
    ];
    Ok(crate::plots::plot_series(
        &out.join("observed_errors"),
        "Errors of the objects observed so far and of those not yet observed",
        "time since the start (h)",
        "median error (km)",
        crate::plots::Scale::Linear,
        crate::plots::Scale::Log10,
        &lines,
    )?)
}

/// Replays `world` with progress bar `quiet`, writing `estimates.csv` and `summary.json` into `out`;
/// returns the summary and whether every scan was accepted.
///
/// # Errors
/// Bad input (a scan the world refuses) or [`Error::Output`] when a file cannot be written.
pub fn run<W: World<P>, const P: usize>(world: &mut W, quiet: bool, out: &Path) -> Result<(RunSummary, bool), Error> {
    let heading = world.heading();
    let evaluation = heading.evaluation;
    let prior = world.posterior();
    let csv_path = out.join("estimates.csv");
    let csv_error = |e: std::io::Error| Error::output(&csv_path, e);
    let mut csv = crate::io::atomic::AtomicFile::create(&csv_path)?;
    writeln!(csv, "{}", world.csv_header()).map_err(csv_error)?;
    let mut tally = Tally::new(&heading, &prior);
    let n = world.scans();
    let mut records = Vec::with_capacity(n);
    let bar = progress(n, quiet, heading.tracker);
    let mut notices = Notices::default();
    let mut judge = Judge::new(prior.map.iter().map(|t| t.label));
    let mut residual_plots = crate::pipeline::residual_plots::ResidualPlots::default();
    for k in 0..n {
        world.begin(k).inspect_err(|_| bar.finish_and_clear())?;
        let time = world.time(k);
        let associations = world.associate(k);
        let start = Instant::now();
        let outcome = world.step(k);
        let ms = start.elapsed().as_secs_f64() * 1e3;
        bar.inc(1);
        let (info, error, refused) = match outcome {
            Ok(info) => (Some(info), None, false),
            Err(StepFailure::BadInput(e)) => {
                bar.finish_and_clear();
                return Err(Error::input(format!("scans[{k}]: {e}")));
            }
            Err(StepFailure::Rejected(e)) => {
                bar.suspend(|| eprintln!("warning: scan {k} (t = {time}) rejected: {e}"));
                (None, Some(e), false)
            }
            Err(StepFailure::Refused(e)) => {
                if let Some(line) = notices.refused(k, time, world.sensor_name(k).as_deref(), &e) {
                    bar.suspend(|| eprintln!("{line}"));
                }
                (None, Some(e), true)
            }
        };
        if let (Some(scan), Some(_)) = (&associations, info) {
            judge.scan(scan);
            residual_plots.add(time, scan, world.residual_axes(&scan.sensor));
        }
        let numerical_drops = info.map(|i| i.numerical_drops).unwrap_or_default();
        if let Some(line) = notices.dropped(k, time, &numerical_drops) {
            bar.suspend(|| eprintln!("{line}"));
        }
        let posterior = world.posterior();
        tally.peak_hypotheses = tally.peak_hypotheses.max(posterior.hypotheses);
        judge.labels(posterior.map.iter().map(|t| t.label));
        let truth = world.truth(k);
        let true_cardinality = truth.as_ref().map(Vec::len);
        let scored = truth.map(|truth| score_scan(&*world, k, &truth, &posterior, &mut tally, &evaluation));
        let within: Vec<Option<bool>> = match &scored {
            Some(s) => s.within_bound.iter().map(|&w| Some(w)).collect(),
            None => vec![None; posterior.map.len()],
        };
        if world.estimates_due(k) {
            csv_lines(&mut csv, &world.csv_scan_columns(k), &posterior, &within).map_err(csv_error)?;
        }
        world.record(k, info.is_some(), &posterior, &within)?;
        records.push(ScanRecord {
            scan: k,
            time,
            ms: info.map(|_| ms),
            captured_mass: info.map(|i| i.captured_mass),
            budget_reached: info.is_some_and(|i| i.budget_reached),
            hypotheses: posterior.hypotheses,
            expected_cardinality: posterior.expected_cardinality,
            map_cardinality: posterior.map.len(),
            true_cardinality,
            gospa: scored.as_ref().map(|s| s.gospa),
            ospa: scored.as_ref().map(|s| s.ospa),
            error,
            refused,
            numerical_drops,
            lost_tracks: info.map_or(0, |i| i.lost_tracks),
            tracklets_formed: info.map_or(0, |i| i.tracklets_formed),
        });
    }
    bar.finish_and_clear();
    notices.finish().iter().for_each(|line| eprintln!("{line}"));
    csv.commit()?;
    world.finish(&records)?;
    let mut summary = summarise(&heading, &records, &prior, &tally);
    plot_observed::<P>(&tally.observed, out)?;
    summary.numerical_drops = numerical_drops(&records);
    summary.refused_scans = refused_scans(&*world, &records);
    if world.judged() {
        judged(&mut summary, &judge);
        residual_plots.write(out)?;
    }
    // The process's peak resident memory so far (Linux), to check the reference's budget.
    summary.peak_resident_kib = peak_resident_kib();
    write_json(&out.join("summary.json"), &summary)?;
    // Refused scans are reported and the run goes on; a scan the tracker failed on is exit code 3.
    let clean = records.iter().all(|r| r.error.is_none() || r.refused);
    Ok((summary, clean))
}

/// Writes the lines of `estimates.csv` of one scan: its columns, then each MAP estimate with its bound.
fn csv_lines(
    csv: &mut impl Write,
    scan_columns: &str,
    posterior: &Posterior,
    within: &[Option<bool>],
) -> std::io::Result<()> {
    posterior.map.iter().zip(within).try_for_each(|(t, w)| csv_line(csv, scan_columns, t, *w))
}

/// The summary of a run from its records.
fn summarise(
    heading: &crate::pipeline::world::Heading,
    records: &[ScanRecord],
    prior: &Posterior,
    tally: &Tally,
) -> RunSummary {
    let ms: Vec<f64> = records.iter().filter_map(|r| r.ms).collect();
    let captured: Vec<f64> = records.iter().filter_map(|r| r.captured_mass).collect();
    let gospas: Vec<f64> = records.iter().filter_map(|r| r.gospa).collect();
    let ospas: Vec<f64> = records.iter().filter_map(|r| r.ospa).collect();
    let last = records.last();
    let evaluation = heading.evaluation;
    RunSummary {
        scenario: heading.scenario.clone(),
        tracker: heading.tracker.into(),
        profile: heading.profile.into(),
        scans: records.len(),
        // Without truth there is nothing to score: null, not 0.
        mean_gospa: (!gospas.is_empty()).then(|| mean(&gospas)),
        mean_ospa: (!ospas.is_empty()).then(|| mean(&ospas)),
        gospa_cutoff: evaluation.gospa_cutoff,
        gospa_order: evaluation.gospa_order,
        error_bound: evaluation.error_bound,
        // Without scans, the prior's figures.
        final_expected_cardinality: last.map_or(prior.expected_cardinality, |r| r.expected_cardinality),
        final_map_cardinality: last.map_or(prior.map.len(), |r| r.map_cardinality),
        true_final_cardinality: last.and_then(|r| r.true_cardinality),
        births: tally.births.figures().summary(heading.has_truth),
        label_switches: tally.switches.total(),
        in_view_misses_after_confirmation: tally.in_view_misses,
        in_view_red_stars: tally.in_view_red_stars,
        out_of_view_red_stars: tally.out_of_view_red_stars,
        mean_ms_per_scan: mean(&ms),
        max_ms_per_scan: ms.iter().copied().fold(0.0, f64::max),
        peak_hypotheses: tally.peak_hypotheses,
        mean_captured_mass: mean(&captured),
        min_captured_mass: captured.iter().copied().fold(1.0, f64::min),
        rejected_scans: records
            .iter()
            .filter_map(|r| r.error.as_ref().map(|e| RejectedScan { scan: r.scan, error: e.clone() }))
            .collect(),
        reference_budget_reached_scans: records
            .iter()
            .filter(|r| r.budget_reached && heading.reference)
            .map(|r| r.scan)
            .collect(),
        peak_resident_kib: None,
        sensors: heading.sensors,
        sensor_kinds: heading.sensor_kinds.clone(),
        numerical_drops: NumericalDropsSummary::default(),
        lost_tracks: records.iter().map(|r| r.lost_tracks).sum(),
        tracklets_formed: records.iter().map(|r| r.tracklets_formed).sum(),
        tracklet_births: heading
            .births_from_tracklets_only
            .then(|| tally.births.confirmed_labels(|label| !tally.prior_labels.contains(&label))),
        refused_scans: RefusedScans::default(),
        catalogue_dropped: None,
        residuals: None,
        tracks_started: None,
        tracks_ended: None,
        measurements_per_track: None,
        consistency_warnings: None,
        observed_objects: tally.observed.last().map(|(_, e)| e.observed_objects),
        unobserved_objects: tally.observed.last().map(|(_, e)| e.unobserved_objects),
        observed_median_error_km: tally.observed.last().and_then(|(_, e)| e.observed_median_error_km),
        unobserved_median_error_km: tally.observed.last().and_then(|(_, e)| e.unobserved_median_error_km),
    }
}

/// The keys that judge a run without truth ([`crate::eval::consistency`]), and a stderr `warning:` line per
/// sensor whose mean NIS lies outside its band.
fn judged(summary: &mut RunSummary, judge: &Judge) {
    let judgement = judge.finish();
    for name in &judgement.consistency_warnings {
        let r = &judgement.residuals[name];
        let why = match (r.mean_nis, r.nis_band) {
            (Some(mean), Some([low, high])) => {
                format!("mean NIS {mean:.3} outside its 95 % band [{low:.3}, {high:.3}]")
            }
            _ => format!("none of its {} measurements lies within a MAP track's gate", r.measurements),
        };
        eprintln!("warning: sensor {name}: {why} (consistency_warnings in summary.json)");
    }
    summary.residuals = Some(judgement.residuals);
    summary.tracks_started = Some(judgement.tracks_started);
    summary.tracks_ended = Some(judgement.tracks_ended);
    summary.measurements_per_track = Some(judgement.measurements_per_track);
    summary.consistency_warnings = Some(judgement.consistency_warnings);
}

/// `numerical_drops` of the summary: per scan with drops, the first dropped track and the count.
fn numerical_drops(records: &[ScanRecord]) -> NumericalDropsSummary {
    let tracks: Vec<NumericalDrop> = records
        .iter()
        .filter_map(|r| {
            let (label, error) = r.numerical_drops.first?;
            Some(NumericalDrop {
                scan: r.scan,
                time: r.time,
                label: label.0,
                reason: error.to_string(),
                dropped: r.numerical_drops.count,
            })
        })
        .collect();
    NumericalDropsSummary { count: records.iter().map(|r| r.numerical_drops.count).sum(), tracks }
}

/// `refused_scans` of the summary: every scan the core refused for its input, with its reason.
fn refused_scans<W: World<P>, const P: usize>(world: &W, records: &[ScanRecord]) -> RefusedScans {
    let reasons: Vec<RefusedScan> = records
        .iter()
        .filter(|r| r.refused)
        .map(|r| RefusedScan {
            scan: r.scan,
            time: r.time,
            sensor: world.sensor_name(r.scan),
            reason: r.error.clone().unwrap_or_default(),
        })
        .collect();
    RefusedScans { count: reasons.len(), reasons }
}

#[cfg(test)]
mod tests {
    use super::*;
    use tracker_core::report::NumericalDrops;
    use tracker_core::{NumericalError, TrackLabel};

    #[test]
    fn a_line_per_scan_for_the_first_ten_then_one_count() {
        let mut notices = Notices::default();
        let drops = NumericalDrops { count: 2, first: Some((TrackLabel(7), NumericalError::NonFinite)) };
        assert_eq!(notices.dropped(0, 1.0, &NumericalDrops::default()), None, "no drop, no line");
        for k in 0..25 {
            let refused = notices.refused(k, 2.0, Some("radar"), "measurement 0 is outside the field of view");
            let dropped = notices.dropped(k, 2.0, &drops);
            assert_eq!(refused.is_some(), k < NOTICE_LINES, "{k}");
            assert_eq!(dropped.is_some(), k < NOTICE_LINES, "{k}");
            if k == 0 {
                assert_eq!(
                    refused.as_deref(),
                    Some(
                        "warning: scan 0 (t = 2, sensor radar) refused: measurement 0 is outside the field of view; the run goes on"
                    )
                );
                let dropped = dropped.unwrap_or_default();
                assert!(dropped.contains("2 track(s) dropped") && dropped.contains("track 7"), "{dropped}");
            }
        }
        let finish = notices.finish();
        assert_eq!(finish.len(), 2, "{finish:?}");
        assert!(
            finish[0].contains("15 more scans refused") && finish[1].contains("15 more scans dropped"),
            "{finish:?}"
        );
    }
}
