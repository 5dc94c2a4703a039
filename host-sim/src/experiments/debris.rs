//! `experiment debris`: a break-up cloud crossing the field of view, R-FISST against HOMHT with the same time per scan, and the truth-association check.

use super::common::{err, mean};
use super::scaling::{Watch, scaling_matrix};
use crate::error::Error;
use crate::io::report::{
    AssociationCheck, CheckOutcome, DebrisFigures, DebrisHomht, DebrisReport, DebrisRfisst, DebrisScan,
};
use crate::pipeline::output::write_json;
use crate::pipeline::planar::runner::build;
use crate::pipeline::planar::setup;
use crate::pipeline::planar::{score, truth_positions};
use crate::pipeline::snapshot::Snapshot;
use crate::pipeline::{Profile, ReferenceBudget, TrackerKind};
use crate::plots::{self, Scale, Series};
use crate::sim::planar;
use nalgebra::SVector;
use std::collections::HashMap;
use std::path::Path;
use std::time::Instant;
use tracker_core::Gaussian;
use tracker_core::TwoBody;
use tracker_core::association::{AssociationMatrix, CLUTTER, association_count};
use tracker_core::children::{ChildGenerator, ChildSink, ExhaustiveChildren};
use tracker_core::cluster::ClusteredChildren;
use tracker_core::ekf;
use tracker_core::sampler::SamplerConfig;
use tracker_core::selection::TopChildren;
use tracker_core::weight::{Event, WeightModel};

/// R-FISST through the debris crossing with the scenario's sampler settings, checking before each scan
/// whether the same generator finds the truth association of the MAP parent (`association_check`). Per scan: the check, ms, and (GOSPA,
/// expected cardinality) after the step.
pub(super) struct DebrisRun {
    pub(super) checks: Vec<AssociationCheck>,
    pub(super) ms: Vec<f64>,
    pub(super) series: Vec<(Option<f64>, f64)>,
}

pub(crate) fn debris_rfisst(
    scenario: &crate::scenario::Scenario,
    seed: u64,
    bar: &indicatif::ProgressBar,
) -> Result<DebrisRun, Error> {
    let config = setup::sampler_config(scenario);
    let truth = scenario.truth.as_ref().ok_or_else(|| err("debris scenario without truth"))?;
    let mut rfisst = build(TrackerKind::Rfisst, Profile::Host, scenario, ReferenceBudget::default()).map_err(err)?;
    let motion = setup::two_body(&scenario.motion).ok_or_else(|| err("debris scenario is two-body"))?;
    let measurement = setup::measurement(&scenario.measurement);
    let tracker_config = setup::config::<TwoBody<f64>, 16>(scenario, motion, setup::sampled(scenario)).map_err(err)?;
    let weights = WeightModel::from_config(&tracker_config);
    let fov = setup::region(&scenario.sensor.field_of_view);
    let mut run = DebrisRun { checks: vec![], ms: vec![], series: vec![] };
    let mut previous_time = scenario.prior.time;
    for (k, scan) in scenario.scans.iter().enumerate() {
        let zs = setup::measurements(scan);
        run.checks.push(association_check(
            &rfisst.snapshot(),
            &zs,
            &truth.scans[k].origins,
            scan.time - previous_time,
            &motion,
            &measurement,
            &weights,
            &fov,
            seed ^ k as u64,
            config,
        )?);
        let start = Instant::now();
        let outcome = rfisst.step(scan.time, &zs);
        run.ms.push(start.elapsed().as_secs_f64() * 1e3);
        if let Err(e) = outcome {
            return Err(err(format!("rfisst rejected debris scan {k}: {e}")));
        }
        let s = rfisst.snapshot();
        run.series.push((score(scenario, k, &s).map(|g| g.gospa), s.expected_cardinality()));
        previous_time = scan.time;
        bar.inc(1);
    }
    Ok(run)
}

/// The fraction of `checks` with an outcome for which `found` is true.
pub(crate) fn fraction_true(checks: &[AssociationCheck], found: fn(&CheckOutcome) -> bool) -> f64 {
    checks.iter().filter(|c| c.outcome.as_ref().is_some_and(found)).count() as f64 / checks.len().max(1) as f64
}

/// Debris crossing: R-FISST vs HOMHT with the same time budget per scan, and the truth-association check.
pub(crate) fn debris(dir: &Path, seed: u64, quiet: bool) -> Result<DebrisFigures, Error> {
    let scenario = planar::debris_crossing(seed).run();
    scenario.save(&dir.join("scenario.json"))?;
    let profile = Profile::Host;

    // R-FISST first, with the truth-association check on its MAP parent before each scan.
    let bar = crate::pipeline::output::progress(scenario.scans.len() * 2, quiet, "debris");
    let DebrisRun { checks, ms: rfisst_ms, series: rfisst_series } = debris_rfisst(&scenario, seed, &bar)?;
    // HOMHT with the same time budget: as many children per scan as exhaustive enumeration produces in
    // R-FISST's mean time per scan (its measured rate on the scaling family, here measured on the first scan).
    let mean_rfisst_ms = mean(&rfisst_ms);
    let rate = exhaustive_children_per_second(seed);
    let budget = ((mean_rfisst_ms / 1e3) * rate).max(1.0) as u64;
    let HomhtRun { series: homht_series, rejected: homht_rejected, ms: homht_ms } =
        debris_homht(&scenario, profile, budget, &bar)?;
    bar.finish_and_clear();
    let true_count: Vec<f64> =
        (0..scenario.scans.len()).map(|k| truth_positions(&scenario, k).map_or(0.0, |t| t.len() as f64)).collect();
    let gospa = |series: &[(Option<f64>, f64)]| mean(&series.iter().filter_map(|s| s.0).collect::<Vec<_>>());
    let children: Vec<f64> = checks.iter().map(|c| c.possible_children).filter(|c| c.is_finite()).collect();
    let figures = DebrisFigures {
        experiment: "debris".into(),
        seed,
        scans: scenario.scans.len(),
        min_possible_children_per_map_parent: children.iter().copied().fold(f64::INFINITY, f64::min),
        max_possible_children_per_map_parent: children.iter().copied().fold(0.0, f64::max),
        truth_association_found_fraction: fraction_true(&checks, |o| o.truth_found_or_beaten),
        truth_association_found_fraction_100k_steps: fraction_true(&checks, |o| o.truth_found_or_beaten_100k_steps),
        rfisst: DebrisRfisst {
            mean_gospa: gospa(&rfisst_series),
            final_expected_cardinality: rfisst_series.last().map_or(0.0, |s| s.1),
            mean_ms_per_scan: mean_rfisst_ms,
            max_ms_per_scan: rfisst_ms.iter().copied().fold(0.0, f64::max),
        },
        homht: DebrisHomht {
            mean_gospa: gospa(&homht_series),
            final_expected_cardinality: homht_series.last().map_or(0.0, |s| s.1),
            mean_ms_per_scan: mean(&homht_ms),
            children_budget_per_scan: budget,
            rejected_scans: homht_rejected,
        },
        true_final_cardinality: true_count.last().copied().unwrap_or(0.0),
    };
    let per_scan = (0..scenario.scans.len())
        .map(|k| DebrisScan {
            scan: k,
            rfisst_gospa: rfisst_series[k].0,
            rfisst_expected_cardinality: rfisst_series[k].1,
            homht_gospa: homht_series[k].0,
            homht_expected_cardinality: homht_series[k].1,
            true_cardinality: true_count[k],
            check: checks[k],
        })
        .collect();
    write_json(&dir.join("debris.json"), &DebrisReport { figures: figures.clone(), per_scan })?;
    plot_debris(dir, scenario.scans.len(), &rfisst_series, &homht_series, &true_count)?;
    Ok(figures)
}

/// HOMHT through the debris crossing, per scan: (GOSPA, expected cardinality) after the step, and ms.
struct HomhtRun {
    series: Vec<(Option<f64>, f64)>,
    /// Scans the tracker rejected; it coasts on its prior through them.
    rejected: usize,
    ms: Vec<f64>,
}

/// Runs HOMHT through the debris crossing with `budget` children per scan.
fn debris_homht(
    scenario: &crate::scenario::Scenario,
    profile: Profile,
    budget: u64,
    bar: &indicatif::ProgressBar,
) -> Result<HomhtRun, Error> {
    let mut homht_scenario = scenario.clone();
    homht_scenario.tracker.max_children_per_scan = budget;
    let mut homht = build(TrackerKind::Homht, profile, &homht_scenario, ReferenceBudget::default()).map_err(err)?;
    let mut run = HomhtRun { series: vec![], rejected: 0, ms: vec![] };
    for (k, scan) in scenario.scans.iter().enumerate() {
        let zs = setup::measurements(scan);
        let start = Instant::now();
        if homht.step(scan.time, &zs).is_err() {
            run.rejected += 1; // unchanged: it coasts on its prior
        }
        run.ms.push(start.elapsed().as_secs_f64() * 1e3);
        let s = homht.snapshot();
        run.series.push((score(scenario, k, &s).map(|g| g.gospa), s.expected_cardinality()));
        bar.inc(1);
    }
    Ok(run)
}

/// Plots GOSPA and expected cardinality per scan for both trackers (and the true cardinality).
fn plot_debris(
    dir: &Path,
    scans: usize,
    rfisst_series: &[(Option<f64>, f64)],
    homht_series: &[(Option<f64>, f64)],
    true_count: &[f64],
) -> Result<(), Error> {
    let over_time =
        |f: &dyn Fn(usize) -> Option<f64>| (0..scans).filter_map(|k| f(k).map(|v| (k as f64, v))).collect::<Vec<_>>();
    plots::plot_series(
        &dir.join("debris_gospa"),
        "Debris crossing: GOSPA of the MAP estimates",
        "scan",
        "GOSPA (km)",
        Scale::Linear,
        Scale::Linear,
        &[
            Series { name: "R-FISST".into(), points: over_time(&|k| rfisst_series[k].0), markers: true },
            Series { name: "HOMHT, same time budget".into(), points: over_time(&|k| homht_series[k].0), markers: true },
        ],
    )?;
    plots::plot_series(
        &dir.join("debris_cardinality"),
        "Debris crossing: expected number of objects",
        "scan",
        "objects",
        Scale::Linear,
        Scale::Linear,
        &[
            Series { name: "R-FISST".into(), points: over_time(&|k| Some(rfisst_series[k].1)), markers: true },
            Series {
                name: "HOMHT, same time budget".into(),
                points: over_time(&|k| Some(homht_series[k].1)),
                markers: true,
            },
            Series { name: "truth".into(), points: over_time(&|k| Some(true_count[k])), markers: false },
        ],
    )?;
    Ok(())
}

/// Children per second of exhaustive enumeration into the tracker's top-H sink, measured on a scaling
/// problem with about 10⁶ children.
fn exhaustive_children_per_second(seed: u64) -> f64 {
    let (matrix, truth) = scaling_matrix(8, 7, seed);
    let mut watch = Watch { top: TopChildren::new(), truth: &truth, truth_found: false, best: f64::NEG_INFINITY };
    let start = Instant::now();
    let _ = ExhaustiveChildren::new(u64::MAX).generate(&matrix, &mut watch);
    association_count(8, 7) as f64 / start.elapsed().as_secs_f64().max(1e-9)
}

/// For the MAP parent before a scan: builds its no-event association matrix with the core's EKF and weight
/// code, runs the default R-FISST generator on it, and checks whether the truth-consistent association
/// (each measurement to the object that made it) is offered or beaten by a child at least as likely.
#[allow(clippy::too_many_arguments)]
fn association_check(
    parent: &Snapshot,
    zs: &[SVector<f64, 2>],
    origins: &[Option<u64>],
    dt: f64,
    motion: &TwoBody<f64>,
    measurement: &tracker_core::PositionMeasurement<f64>,
    weights: &WeightModel<f64>,
    fov: &tracker_core::Region<f64>,
    seed: u64,
    base: SamplerConfig,
) -> Result<AssociationCheck, Error> {
    let Some(map) = parent.hypotheses.first() else {
        return Ok(AssociationCheck { possible_children: 0.0, outcome: None });
    };
    let mut matrix = AssociationMatrix::<f64, 128, 64>::new(zs.len(), 0, 0.0);
    let mut column_label: HashMap<u32, u16> = HashMap::new();
    for &t in &map.tracks {
        let track = &parent.tracks[t];
        let prior = Gaussian { mean: SVector::from(track.mean), covariance: nalgebra::SMatrix::from(track.covariance) };
        let predicted = ekf::predict(motion, &prior, dt).map_err(err)?;
        let innovation = ekf::innovation(measurement, &predicted).map_err(err)?;
        if !fov.contains(&innovation.predicted) {
            continue;
        }
        let entries: Vec<f64> = zs.iter().map(|z| weights.entry(&innovation, z)).collect();
        if let Some(column) = matrix.push_column(&entries, weights.detection_required()) {
            column_label.insert(track.label, column as u16);
        }
    }
    let in_view = matrix.columns();
    matrix.set_baseline(weights.baseline(
        map.log_weight,
        weights.event_log_probability(Event::None, in_view),
        in_view,
        zs.len(),
    ));
    // Prior labels are the truth ids; a measurement whose object is not a column of this parent is clutter.
    let truth: Vec<u16> =
        origins.iter().map(|o| o.and_then(|id| column_label.get(&(id as u32)).copied()).unwrap_or(CLUTTER)).collect();
    let truth_score = matrix.score(&truth);
    struct Best<'a> {
        truth: &'a [u16],
        found: bool,
        best: f64,
    }
    impl ChildSink<f64> for Best<'_> {
        fn offer(&mut self, w: f64, a: &[u16]) {
            self.found |= a == self.truth;
            self.best = self.best.max(w);
        }
    }
    // The default budget, and paper 003's 100,000 steps.
    let mut outcomes = vec![];
    for steps in [base.steps, 100_000] {
        let mut generator = ClusteredChildren::<f64, 128, 64, 256>::new(SamplerConfig { steps, ..base }, seed);
        let mut best = Best { truth: &truth, found: false, best: f64::NEG_INFINITY };
        generator.generate(&matrix, &mut best).map_err(|e| err(format!("{e:?}")))?;
        outcomes.push(best);
    }
    Ok(AssociationCheck {
        possible_children: association_count(in_view as u32, zs.len() as u32) as f64,
        outcome: Some(CheckOutcome {
            objects_in_view: in_view,
            measurements: zs.len(),
            truth_offered: outcomes[0].found,
            truth_found_or_beaten: outcomes[0].found || outcomes[0].best >= truth_score,
            best_over_truth_log: outcomes[0].best - truth_score,
            truth_found_or_beaten_100k_steps: outcomes[1].found || outcomes[1].best >= truth_score,
            best_over_truth_log_100k_steps: outcomes[1].best - truth_score,
        }),
    })
}
