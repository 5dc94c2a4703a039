//! `host-sim compare` on a planar scenario: the bounded tracker and the unbounded reference on the same
//! scans.

use super::runner::{Runner, build};
use super::{Options, score, setup};
use crate::error::Error;
use crate::io::report::{CompareReport, CompareScan, CompareSide, CompareSummary};
use crate::pipeline::output::{mean, progress, write_json};
use crate::pipeline::snapshot::match_posteriors;
use crate::pipeline::tracker::TrackerKind;
use crate::scenario::Scenario;
use std::path::Path;
use std::time::Instant;

/// `host-sim compare`: runs the bounded tracker `bounded` and the unbounded reference on the same scans
/// and writes `compare.json`.
///
/// Captured mass = the reference's posterior mass on the hypotheses the bounded tracker kept; weight L1 =
/// Σ |w_bounded − w_reference| over the union of hypotheses; MAP agreement = the bounded tracker's MAP
/// hypothesis has the reference's largest weight. Hypotheses are matched by the exact bits of their
/// tracks' states ([`Snapshot::hypothesis_key`](crate::pipeline::snapshot::Snapshot::hypothesis_key)).
///
/// # Errors
/// A one-line message when a tracker cannot be built or the file cannot be written.
pub fn compare(
    scenario: &Scenario,
    bounded: TrackerKind,
    options: &Options,
    out: &Path,
) -> Result<CompareReport, Error> {
    std::fs::create_dir_all(out).map_err(|e| Error::output(out, e))?;
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
