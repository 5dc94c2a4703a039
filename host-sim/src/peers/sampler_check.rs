//! `host-sim sampler-check`: the R-FISST sampler against exhaustive enumeration on random small problems.
//!
//! Each case is one scan of a random constant-velocity problem: 1-5 prior objects (sometimes two prior
//! hypotheses), their detections with p_D in [0.6, 0.98], Poisson clutter, 0-2 birth cells with α up to
//! 0.03, death probability up to 0.03, and sometimes a gate. Problems are kept small enough that every
//! child of the scan can be enumerated (at most 2,000 children in all). The exact answer is the unbounded
//! reference tracker's (every child kept); the sampler runs in tracker-core with H∞ = 2,048, so any loss
//! comes from the sampler alone. Per case:
//!
//! - captured mass: the exact posterior mass of the hypotheses the sampler kept;
//! - weight L1: Σ |w_sampler − w_exact| over all hypotheses;
//! - top-1 found: the sampler kept the exact MAP hypothesis (or one tied with it).

use crate::error::Error;
use crate::io::report::{SamplerCheckReport, SamplerScores, SamplerSettings};
use crate::peers::reference::ReferenceTracker;
use crate::pipeline::snapshot::{Snapshot, match_posteriors};
use crate::sim::rng::{Random, Stream};
use nalgebra::{SMatrix, SVector};
use tracker_core::association::association_count;
use tracker_core::sampler::SamplerConfig;
use tracker_core::{
    BirthDetection, BirthModel, ChildGeneration, Config, ConstantVelocity, Gaussian, PositionMeasurement,
    PriorHypothesis, PriorObject, Region, Sensor, StoreOverflow, TrackLabel, Tracker,
};

/// The check's tracker: H∞ = 2048 (more than any case's children), N = 16, Z = 16, K = 4096, B = 4.
type CheckTracker = Tracker<f64, ConstantVelocity<f64>, PositionMeasurement<f64>, 4, 2, 2048, 16, 16, 4096, 4>;

/// Most children a case may have.
const MAX_CHILDREN: u128 = 2_000;

struct Case {
    config: Config<f64, ConstantVelocity<f64>, PositionMeasurement<f64>, 4, 4>,
    prior: Vec<(f64, Vec<PriorObject<f64, 4>>)>,
    measurements: Vec<SVector<f64, 2>>,
}

fn random_case(seed: u64, index: u64) -> Case {
    let mut random = Random::stream(seed, Stream::Scenario, index);
    loop {
        let objects = 1 + random.below(5);
        let detection_probability = random.between(0.6, 0.98);
        let clutter_rate = random.between(0.0, 3.0);
        let area = 60.0 * 60.0;
        let noise = random.between(0.2, 1.0);
        let prior_objects: Vec<PriorObject<f64, 4>> = (0..objects)
            .map(|i| {
                // Objects close together so that associations are ambiguous.
                let mean = SVector::from([
                    random.between(-6.0, 6.0),
                    random.between(-6.0, 6.0),
                    random.between(-1.0, 1.0),
                    random.between(-1.0, 1.0),
                ]);
                let variance = random.between(0.3, 3.0);
                PriorObject {
                    label: TrackLabel(i as u32),
                    state: Gaussian { mean, covariance: SMatrix::identity() * variance },
                }
            })
            .collect();
        let mut prior = vec![(1.0, prior_objects.clone())];
        if objects > 1 && random.uniform() < 0.3 {
            // A second hypothesis without the last object.
            prior.push((random.between(0.1, 0.9), prior_objects[..objects - 1].to_vec()));
        }
        let mut measurements = vec![];
        for object in &prior_objects {
            if random.uniform() < detection_probability {
                let m = object.state.mean;
                measurements.push(SVector::from([
                    m[0] + m[2] + noise * 2.0 * random.normal(),
                    m[1] + m[3] + noise * 2.0 * random.normal(),
                ]));
            }
        }
        for _ in 0..random.poisson(clutter_rate.max(0.3)) {
            measurements.push(SVector::from([random.between(-12.0, 12.0), random.between(-12.0, 12.0)]));
        }
        random.shuffle(&mut measurements);
        let cells = random.below(3);
        let birth_probability = if cells > 0 { random.between(0.0, 0.03) } else { 0.0 };
        let death_probability = random.between(0.0, 0.03);
        let events = 1 + cells + objects;
        let m = measurements.len() as u32;
        let bound = events as u128 * association_count(objects as u32 + 1, m) * prior.len() as u128;
        if m as usize > 16 || bound > MAX_CHILDREN {
            continue;
        }
        let birth_cells = (0..cells)
            .map(|_| Gaussian {
                mean: SVector::from([random.between(-10.0, 10.0), random.between(-10.0, 10.0), 0.0, 0.0]),
                covariance: SMatrix::<f64, 4, 4>::from_diagonal(&SVector::from([25.0, 25.0, 1.0, 1.0])),
            })
            .collect();
        let config = Config {
            motion: ConstantVelocity { acceleration_noise: random.between(0.01, 0.2) },
            measurement: PositionMeasurement::isotropic(noise),
            sensor: Sensor {
                detection_probability,
                clutter_rate: clutter_rate.max(0.05),
                field_of_view: Region::Rectangle { min: [-30.0, -30.0], max: [30.0, 30.0] },
            },
            birth: BirthModel {
                events: Default::default(),
                measured: None,
                probability: birth_probability,
                cells: birth_cells,
                detection: BirthDetection::AllDetected,
            },
            death_probability,
            gate: (random.uniform() < 0.3).then_some(16.0),
            children: ChildGeneration::Exhaustive { max_children_per_scan: 1_000_000 },
            selection: tracker_core::config::Selection::TopWeight,
            store_overflow: StoreOverflow::PruneChildren,
            numerical_failure: Default::default(),
            track_loss: Default::default(),
            seed: seed ^ index,
        };
        let _ = area;
        return Case { config, prior, measurements };
    }
}

/// Scores of one sampler configuration over the cases.
#[derive(Debug, Clone, PartialEq, Default)]
struct Scores {
    captured: Vec<f64>,
    l1: Vec<f64>,
    top1: Vec<bool>,
    steps: Vec<u64>,
}

impl Scores {
    fn record(&self) -> SamplerScores {
        let n = self.captured.len().max(1) as f64;
        SamplerScores {
            mean_captured_mass: self.captured.iter().sum::<f64>() / n,
            min_captured_mass: self.captured.iter().copied().fold(1.0, f64::min),
            min_captured_case: (0..self.captured.len()).min_by(|&a, &b| self.captured[a].total_cmp(&self.captured[b])),
            mean_weight_l1: self.l1.iter().sum::<f64>() / n,
            top1_found_fraction: self.top1.iter().filter(|&&t| t).count() as f64 / n,
            mean_sampler_steps_per_case: self.steps.iter().sum::<u64>() as f64 / n,
        }
    }
}

fn run_sampler(index: u64, case: &Case, sampler: SamplerConfig) -> Result<(Snapshot, u64), Error> {
    let failed = |e: &dyn std::fmt::Display| Error::internal(format!("case {index}: {e}"));
    let mut config = case.config.clone();
    config.children = ChildGeneration::Sampled(sampler);
    let prior: Vec<PriorHypothesis<'_, f64, 4>> =
        case.prior.iter().map(|(w, o)| PriorHypothesis { weight: *w, objects: o }).collect();
    let mut tracker = Box::new(CheckTracker::new(config, &prior, 0.0).map_err(|e| failed(&e))?);
    let report = tracker.step(1.0, &case.measurements).map_err(|e| failed(&e))?;
    Ok((Snapshot::of(&*tracker), report.sampler_steps))
}

fn score(exact: &Snapshot, sampled: &Snapshot, scores: &mut Scores) {
    let matched = match_posteriors(exact, sampled);
    let map = exact.hypotheses.first().map_or(0.0, |h| h.weight);
    scores.captured.push(matched.captured_mass.min(1.0));
    scores.l1.push(matched.weight_l1);
    scores.top1.push(matched.best_exact_weight_found > 0.0 && matched.best_exact_weight_found >= map * (1.0 - 1e-12));
}

/// Runs `cases` random cases from `seed` with the default sampler and with pure sampling (no clusters),
/// and returns the JSON report (default configuration's figures at the top level).
///
/// # Errors
/// A message if a case cannot be built or run (a bug: cases are valid by construction).
pub fn run(cases: usize, seed: u64) -> Result<SamplerCheckReport, Error> {
    let default = SamplerConfig::default();
    let pure = SamplerConfig { clusters: false, ..default };
    let mut default_scores = Scores::default();
    let mut pure_scores = Scores::default();
    let mut children = vec![];
    for index in 0..cases as u64 {
        let case = random_case(seed, index);
        let mut reference = ReferenceTracker::new(&case.config, &case.prior, 0.0, usize::MAX / 2)
            .map_err(|e| Error::internal(format!("case {index}: {e}")))?;
        let report =
            reference.step(1.0, &case.measurements).map_err(|e| Error::internal(format!("case {index}: {e}")))?;
        children.push(report.children as f64);
        let exact = reference.snapshot();
        for (config, scores) in [(default, &mut default_scores), (pure, &mut pure_scores)] {
            let (sampled, steps) = run_sampler(index, &case, config)?;
            score(&exact, &sampled, scores);
            scores.steps.push(steps);
        }
    }
    let report = SamplerCheckReport {
        default: default_scores.record(),
        cases,
        seed,
        mean_children_per_case: children.iter().sum::<f64>() / cases.max(1) as f64,
        max_children_per_case: children.iter().copied().fold(0.0, f64::max),
        sampler: SamplerSettings {
            burn_in: default.burn_in,
            steps: default.steps,
            proposal: format!("{:?}", default.proposal),
            clusters: default.clusters,
            exhaustive_limit: default.exhaustive_limit,
            exact_start: default.exact_start,
        },
        pure_sampling: pure_scores.record(),
    };
    Ok(report)
}
