//! The one replay of a scenario through a tracker, whatever the world: step every scan, score the MAP
//! estimates against the truth, tally births and label switches, check what the sensor sees, write
//! `estimates.csv` and `summary.json` (the world adapter writes its own files, [`World::record`]).
//!
//! Scoring: GOSPA (α = 2, cut-off and order from the scenario's `evaluation`), OSPA, the error of the
//! expected cardinality, and label switches along GOSPA's assignment ([`crate::eval::score`]). A born
//! object is *confirmed* once GOSPA with cut-off `error_bound` assigns it a MAP track whose label's
//! existence probability reaches `confirmation_existence` ([`crate::eval::births`]).

use crate::error::Error;
use crate::eval::births::{BirthTally, MapTrack};
use crate::eval::metrics::LabelSwitches;
use crate::eval::score::{Scored, score};
use crate::io::report::{RejectedScan, RunSummary};
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
    tally.births.record(k, &objects, world.detected(k), &map, &scored.bound_assignment);
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
    let mut tally = Tally {
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
    };
    let n = world.scans();
    let mut records = Vec::with_capacity(n);
    let bar = progress(n, quiet, heading.tracker);
    for k in 0..n {
        let time = world.time(k);
        let start = Instant::now();
        let outcome = world.step(k);
        let ms = start.elapsed().as_secs_f64() * 1e3;
        bar.inc(1);
        let (info, error) = match outcome {
            Ok(info) => (Some(info), None),
            Err(StepFailure::BadInput(e)) => {
                bar.finish_and_clear();
                return Err(Error::input(format!("scans[{k}]: {e}")));
            }
            Err(StepFailure::Rejected(e)) => {
                bar.suspend(|| eprintln!("warning: scan {k} (t = {time}) rejected: {e}"));
                (None, Some(e))
            }
        };
        let posterior = world.posterior();
        tally.peak_hypotheses = tally.peak_hypotheses.max(posterior.hypotheses);
        let truth = world.truth(k);
        let true_cardinality = truth.as_ref().map(Vec::len);
        let scored = truth.map(|truth| score_scan(&*world, k, &truth, &posterior, &mut tally, &evaluation));
        let within: Vec<Option<bool>> = match &scored {
            Some(s) => s.within_bound.iter().map(|&w| Some(w)).collect(),
            None => vec![None; posterior.map.len()],
        };
        let scan_columns = world.csv_scan_columns(k);
        for (t, w) in posterior.map.iter().zip(&within) {
            csv_line(&mut csv, &scan_columns, t, *w).map_err(csv_error)?;
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
        });
    }
    bar.finish_and_clear();
    csv.commit()?;
    world.finish(&records)?;
    let mut summary = summarise(&heading, &records, &prior, &tally);
    // The process's peak resident memory so far (Linux), to check the reference's budget.
    summary.peak_resident_kib = peak_resident_kib();
    write_json(&out.join("summary.json"), &summary)?;
    let clean = summary.rejected_scans.is_empty();
    Ok((summary, clean))
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
    }
}
