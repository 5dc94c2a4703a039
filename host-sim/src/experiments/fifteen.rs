//! `experiment fifteen` (paper 003 §V-A): R-FISST against HOMHT and the unbounded reference on 15 objects.

use super::common::err;
use crate::error::Error;
use crate::io::report::{FifteenFigures, FifteenHomht, FifteenReport, FifteenScan, FifteenTracker, Timing};
use crate::pipeline::output::write_json;
use crate::pipeline::planar::runner::{Runner, build};
use crate::pipeline::planar::score;
use crate::pipeline::planar::setup;
use crate::pipeline::snapshot::Snapshot;
use crate::pipeline::{Profile, ReferenceBudget, TrackerKind};
use crate::plots::{self, Scale, Series};
use crate::sim::planar;
use nalgebra::SVector;
use std::path::Path;
use std::time::Instant;

/// Whether `a`'s MAP hypothesis is also `b`'s (by the exact bits of its tracks' states), allowing for
/// ties in `b`.
fn map_agrees(a: &Snapshot, b: &Snapshot) -> bool {
    let (Some(_), Some(best)) = (a.hypotheses.first(), b.hypotheses.first()) else {
        return a.hypotheses.is_empty() && b.hypotheses.is_empty();
    };
    let key = a.hypothesis_key(0);
    (0..b.hypotheses.len()).any(|i| b.hypotheses[i].weight >= best.weight * (1.0 - 1e-9) && b.hypothesis_key(i) == key)
}

/// Largest distance from a MAP estimate of `a` to the nearest MAP estimate of `b`.
fn map_estimate_difference(a: &Snapshot, b: &Snapshot) -> f64 {
    let bs = b.map_tracks();
    a.map_tracks()
        .iter()
        .map(|t| bs.iter().map(|u| (t.mean[0] - u.mean[0]).hypot(t.mean[1] - u.mean[1])).fold(f64::INFINITY, f64::min))
        .fold(0.0, f64::max)
}

/// Paper 003 §V-A: R-FISST vs HOMHT vs the unbounded reference on the same scans.
pub(crate) fn fifteen(dir: &Path, seed: u64, quiet: bool) -> Result<FifteenFigures, Error> {
    let mut scenario = planar::fifteen_compare(seed).run();
    // HOMHT enumerates the product of every object's options: with 15 objects in view that is millions of
    // children per scan, so give it room (R-FISST does not use this bound).
    scenario.tracker.max_children_per_scan = 200_000_000;
    scenario.save(&dir.join("scenario.json"))?;
    let profile = Profile::Embedded;
    let mut rfisst = build(TrackerKind::Rfisst, profile, &scenario, ReferenceBudget::default()).map_err(err)?;
    let mut homht = build(TrackerKind::Homht, profile, &scenario, ReferenceBudget::default()).map_err(err)?;
    let mut homht_rejected = 0usize;
    // The reference runs while a scan needs at most 2·10⁷ children and its hypotheses fit 1 GiB.
    let mut reference = ReferenceRun {
        runner: Some(
            build(
                TrackerKind::Reference,
                profile,
                &scenario,
                ReferenceBudget { bytes: 1 << 30, children: 20_000_000, ..ReferenceBudget::default() },
            )
            .map_err(err)?,
        ),
        scans: 0,
        budget_reached: false,
        agreements: 0,
    };
    let bar = crate::pipeline::output::progress(scenario.scans.len(), quiet, "fifteen");
    let mut agree_homht = 0usize;
    let mut max_difference: f64 = 0.0;
    let mut per_scan = vec![];
    let mut times = [vec![], vec![], vec![]];
    let mut gospas = [vec![], vec![]];
    for (k, scan) in scenario.scans.iter().enumerate() {
        let zs = setup::measurements(scan);
        let mut step = |runner: &mut Box<dyn Runner>, slot: usize| -> (Snapshot, bool) {
            let start = Instant::now();
            let accepted = runner.step(scan.time, &zs).is_ok();
            times[slot].push(start.elapsed().as_secs_f64() * 1e3);
            (runner.snapshot(), accepted)
        };
        let (a, accepted) = step(&mut rfisst, 0);
        if !accepted {
            return Err(err(format!("rfisst rejected fifteen scan {k}")));
        }
        let (b, accepted) = step(&mut homht, 1);
        homht_rejected += usize::from(!accepted);
        let agrees = map_agrees(&a, &b);
        agree_homht += usize::from(agrees);
        max_difference = max_difference.max(map_estimate_difference(&a, &b));
        let reference_agrees = reference.step(scan.time, &zs, &a, &mut times[2]);
        for (slot, snapshot) in [&a, &b].iter().enumerate() {
            if let Some(s) = score(&scenario, k, snapshot) {
                gospas[slot].push(s.gospa);
            }
        }
        per_scan.push(FifteenScan {
            scan: k,
            map_agreement_homht: agrees,
            map_agreement_reference: reference_agrees,
            rfisst_hypotheses: a.hypotheses.len(),
            homht_hypotheses: b.hypotheses.len(),
        });
        bar.inc(1);
    }
    bar.finish_and_clear();
    let n = scenario.scans.len().max(1) as f64;
    let mean = |v: &[f64]| if v.is_empty() { 0.0 } else { v.iter().sum::<f64>() / v.len() as f64 };
    let max = |v: &[f64]| v.iter().copied().fold(0.0, f64::max);
    let figures = FifteenFigures {
        experiment: "fifteen".into(),
        seed,
        scans: scenario.scans.len(),
        map_agreement: agree_homht as f64 / n,
        max_map_estimate_difference: max_difference,
        reference_scans: reference.scans,
        reference_budget_reached: reference.budget_reached,
        map_agreement_reference: (reference.scans > 0).then(|| reference.agreements as f64 / reference.scans as f64),
        rfisst: FifteenTracker {
            mean_gospa: mean(&gospas[0]),
            mean_ms_per_scan: mean(&times[0]),
            max_ms_per_scan: max(&times[0]),
        },
        homht: FifteenHomht {
            mean_gospa: mean(&gospas[1]),
            mean_ms_per_scan: mean(&times[1]),
            max_ms_per_scan: max(&times[1]),
            rejected_scans: homht_rejected,
            max_children_per_scan: scenario.tracker.max_children_per_scan,
        },
        reference: Timing { mean_ms_per_scan: mean(&times[2]), max_ms_per_scan: max(&times[2]) },
    };
    write_json(&dir.join("fifteen.json"), &FifteenReport { figures: figures.clone(), per_scan })?;
    plot_fifteen(dir, &gospas, &times)?;
    Ok(figures)
}

/// The unbounded reference through the run: it stops after a scan that reaches its budget or takes over
/// 10 s, or that it rejects.
struct ReferenceRun {
    /// `None` once it has stopped.
    runner: Option<Box<dyn Runner>>,
    /// Scans it completed.
    scans: usize,
    budget_reached: bool,
    /// Completed scans whose MAP hypothesis agreed with R-FISST's.
    agreements: usize,
}

impl ReferenceRun {
    /// Steps the reference while it runs, recording its ms in `ms`; whether its MAP agrees with `rfisst`'s.
    fn step(&mut self, time: f64, zs: &[SVector<f64, 2>], rfisst: &Snapshot, ms: &mut Vec<f64>) -> Option<bool> {
        let runner = self.runner.as_mut()?;
        let start = Instant::now();
        let outcome = runner.step(time, zs);
        let seconds = start.elapsed().as_secs_f64();
        ms.push(seconds * 1e3);
        match outcome {
            Ok(info) => {
                let r = runner.snapshot();
                let agrees = map_agrees(rfisst, &r);
                self.agreements += usize::from(agrees);
                self.scans += 1;
                if info.budget_reached || seconds > 10.0 {
                    self.budget_reached |= info.budget_reached;
                    self.runner = None;
                }
                Some(agrees)
            }
            Err(_) => {
                self.runner = None;
                None
            }
        }
    }
}

/// Plots GOSPA per scan (R-FISST, HOMHT) and time per scan (R-FISST, HOMHT, reference).
fn plot_fifteen(dir: &Path, gospas: &[Vec<f64>; 2], times: &[Vec<f64>; 3]) -> Result<(), Error> {
    let points = |v: &[f64]| v.iter().enumerate().map(|(k, &y)| (k as f64, y)).collect::<Vec<_>>();
    plots::plot_series(
        &dir.join("fifteen_gospa"),
        "Fifteen objects: GOSPA of the MAP estimates",
        "scan",
        "GOSPA (km)",
        Scale::Linear,
        Scale::Linear,
        &[
            Series { name: "R-FISST".into(), points: points(&gospas[0]), markers: false },
            Series {
                name: "HOMHT (exhaustive children, same H∞)".into(), points: points(&gospas[1]), markers: false
            },
        ],
    )?;
    plots::plot_series(
        &dir.join("fifteen_time"),
        "Fifteen objects: time per scan",
        "scan",
        "ms per scan",
        Scale::Linear,
        Scale::Log10,
        &[
            Series { name: "R-FISST".into(), points: points(&times[0]), markers: false },
            Series { name: "HOMHT".into(), points: points(&times[1]), markers: false },
            Series { name: "unbounded reference (until its budget)".into(), points: points(&times[2]), markers: true },
        ],
    )?;
    Ok(())
}
