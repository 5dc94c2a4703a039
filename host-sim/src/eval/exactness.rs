//! Exactness of the bounded core tracker on any model: the core [`Tracker`] and the unbounded
//! [`ReferenceTracker`] run on the same scans, each scan naming its sensor and geometry, and their
//! posteriors are compared after every scan as `host-sim compare` compares them
//! ([`crate::pipeline::planar::compare`]): hypotheses matched by the exact bits of their tracks' states
//! ([`match_keys`]), captured mass = the reference's mass on the core's hypotheses, MAP agreement = the
//! core's MAP hypothesis has the reference's largest weight (to 1e-9 relative).
//!
//! It needs no scenario file, so it serves the 3-D models (radar, telescope, several sensors) as well as
//! the planar ones.

use crate::peers::reference::{ReferenceError, ReferenceTracker};
use crate::pipeline::snapshot::match_keys;
use nalgebra::SVector;
use tracker_core::sensor::ScanGeometry;
use tracker_core::{
    Config, Gaussian, MeasurementModel, MotionModel, PriorHypothesis, PriorObject, StepError, TrackLabel, Tracker,
};

/// One scan: which sensor, when, from where, and its measurements.
pub type Scan<const D: usize> = (ScanGeometry<f64>, Vec<SVector<f64, D>>);

/// The comparison after one scan.
#[derive(Debug, Clone, PartialEq)]
pub struct ScanFigures {
    /// Scan index (0-based).
    pub scan: usize,
    /// Scan time (s).
    pub time: f64,
    /// The reference's mass on the core's hypotheses.
    pub captured_mass: f64,
    /// Σ |w_core − w_reference| over the union of both sets of hypotheses.
    pub weight_l1: f64,
    /// Whether the core's MAP hypothesis has the reference's largest weight (to 1e-9 relative).
    pub map_agreement: bool,
    /// The reference's largest weight.
    pub reference_map_weight: f64,
    /// Whether the core's MAP hypothesis and the reference hypothesis with the same track states give
    /// every track the same label.
    pub map_labels_agree: bool,
    /// |w_core(MAP) − w_reference(same hypothesis)| / w_reference(MAP of the reference); 1 when the
    /// reference lacks the core's MAP hypothesis.
    pub map_weight_difference: f64,
    /// The captured mass the core reports for its own scan (`None` when it rejected the scan).
    pub core_captured_mass: Option<f64>,
    /// Hypotheses of the core.
    pub core_hypotheses: usize,
    /// Hypotheses of the reference.
    pub reference_hypotheses: usize,
    /// The core's error, when it rejected the scan (it is then unchanged).
    pub core_error: Option<StepError>,
    /// The reference's error, when it rejected the scan (it is then unchanged).
    pub reference_error: Option<ReferenceError>,
}

/// The comparison over a run.
#[derive(Debug, Clone, PartialEq)]
pub struct CompareFigures {
    /// Per scan.
    pub scans: Vec<ScanFigures>,
    /// Fraction of scans whose MAP hypotheses agree.
    pub map_agreement: f64,
    /// Smallest captured mass (the reference's mass on the core's hypotheses; 1 without scans).
    pub min_captured_mass: f64,
    /// Mean captured mass.
    pub mean_captured_mass: f64,
    /// Largest weight L1 distance.
    pub max_weight_l1: f64,
    /// Largest [`ScanFigures::map_weight_difference`].
    pub max_map_weight_difference: f64,
    /// Smallest captured mass the core reported (1 without scans it accepted).
    pub min_core_captured_mass: f64,
}

/// A hypothesis as the comparison sees it: its weight, its key (the sorted bits of its tracks' means and
/// covariances) and its tracks' labels in key order.
struct Keyed {
    weight: f64,
    key: Vec<u64>,
    labels: Vec<u32>,
}

fn keyed<'a, const S: usize>(weight: f64, tracks: impl Iterator<Item = (TrackLabel, &'a Gaussian<f64, S>)>) -> Keyed {
    let mut states: Vec<(Vec<u64>, u32)> = tracks
        .map(|(label, g)| (g.mean.iter().chain(g.covariance.iter()).map(|v| v.to_bits()).collect(), label.0))
        .collect();
    states.sort();
    let labels = states.iter().map(|s| s.1).collect();
    Keyed { weight, key: states.into_iter().flat_map(|s| s.0).collect(), labels }
}

/// Runs `core` and `reference` (built from the same configuration and prior) on `scans` and compares
/// them after every scan. A scan either rejects is recorded with its error; the tracker that rejected it
/// is unchanged and goes on with the next scan.
pub fn compare_trackers<
    M,
    G,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
>(
    core: &mut Tracker<f64, M, G, S, D, H, N, Z, K, B>,
    reference: &mut ReferenceTracker<M, G, S, D, B>,
    scans: &[Scan<D>],
) -> CompareFigures
where
    M: MotionModel<f64, S>,
    G: MeasurementModel<f64, S, D> + Clone,
{
    let mut figures = vec![];
    for (k, (geometry, zs)) in scans.iter().enumerate() {
        let core_outcome = core.step_scan(geometry, zs);
        let reference_outcome = reference.step_scan(geometry, zs);
        let approx: Vec<Keyed> =
            core.hypotheses().map(|h| keyed(h.weight(), h.tracks().map(|t| (t.label, &t.state)))).collect();
        let exact: Vec<Keyed> = reference
            .posterior()
            .iter()
            .map(|(log_weight, tracks)| keyed(log_weight.exp(), tracks.iter().map(|(l, g)| (*l, g))))
            .collect();
        let pairs: Vec<(f64, Vec<u64>)> = approx.iter().map(|h| (h.weight, h.key.clone())).collect();
        let matched = match_keys(exact.iter().map(|h| (h.weight, h.key.clone())), &pairs);
        let reference_max = exact.first().map_or(0.0, |h| h.weight);
        let map_agreement =
            reference_max > 0.0 && (matched.exact_weight_of_map - reference_max).abs() <= 1e-9 * reference_max;
        let twin = approx.first().and_then(|map| exact.iter().find(|h| h.key == map.key).map(|h| (map, h)));
        let map_labels_agree = twin.is_some_and(|(map, h)| map.labels == h.labels);
        let map_weight_difference =
            twin.map_or(1.0, |(map, h)| (map.weight - h.weight).abs() / reference_max.max(f64::MIN_POSITIVE));
        figures.push(ScanFigures {
            scan: k,
            time: geometry.time,
            captured_mass: matched.captured_mass,
            weight_l1: matched.weight_l1,
            map_agreement,
            reference_map_weight: reference_max,
            map_labels_agree,
            map_weight_difference,
            core_captured_mass: core_outcome.as_ref().ok().map(|r| r.captured_mass),
            core_hypotheses: approx.len(),
            reference_hypotheses: exact.len(),
            core_error: core_outcome.err(),
            reference_error: reference_outcome.err(),
        });
    }
    summarise(figures)
}

fn summarise(scans: Vec<ScanFigures>) -> CompareFigures {
    let n = scans.len().max(1) as f64;
    let fold = |f: fn(&ScanFigures) -> f64, start: f64, pick: fn(f64, f64) -> f64| {
        scans.iter().map(f).filter(|v| v.is_finite()).fold(start, pick)
    };
    CompareFigures {
        map_agreement: scans.iter().filter(|s| s.map_agreement).count() as f64 / n,
        min_captured_mass: fold(|s| s.captured_mass, 1.0, f64::min),
        mean_captured_mass: scans.iter().map(|s| s.captured_mass).sum::<f64>() / n,
        max_weight_l1: fold(|s| s.weight_l1, 0.0, f64::max),
        max_map_weight_difference: fold(|s| s.map_weight_difference, 0.0, f64::max),
        min_core_captured_mass: scans.iter().filter_map(|s| s.core_captured_mass).fold(1.0, f64::min),
        scans,
    }
}

/// Builds the core tracker (capacities H, N, Z, K, B; its children as `config.children` says) and the
/// reference (memory budget `budget_bytes`, no children bound, the default work bound) from `config` and
/// `prior` at `time`, and compares them on `scans` ([`compare_trackers`]).
///
/// # Errors
/// A message when either tracker rejects the configuration or the prior.
pub fn compare_scans<
    M,
    G,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
>(
    config: &Config<f64, M, G, S, B>,
    prior: &[(f64, Vec<PriorObject<f64, S>>)],
    time: f64,
    budget_bytes: usize,
    scans: &[Scan<D>],
) -> Result<CompareFigures, String>
where
    M: MotionModel<f64, S> + Clone,
    G: MeasurementModel<f64, S, D> + Clone,
{
    let budget = crate::pipeline::ReferenceBudget { bytes: budget_bytes, children: u64::MAX, ..Default::default() };
    compare_scans_with_budget::<M, G, S, D, H, N, Z, K, B>(config, prior, time, budget, scans)
}

/// [`compare_scans`] with every budget of the reference given: memory `budget.bytes`, children and work
/// per scan `budget.children`, `budget.work`.
///
/// # Errors
/// A message when either tracker rejects the configuration or the prior.
pub fn compare_scans_with_budget<
    M,
    G,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
>(
    config: &Config<f64, M, G, S, B>,
    prior: &[(f64, Vec<PriorObject<f64, S>>)],
    time: f64,
    budget: crate::pipeline::ReferenceBudget,
    scans: &[Scan<D>],
) -> Result<CompareFigures, String>
where
    M: MotionModel<f64, S> + Clone,
    G: MeasurementModel<f64, S, D> + Clone,
{
    let hypotheses: Vec<PriorHypothesis<'_, f64, S>> =
        prior.iter().map(|(weight, objects)| PriorHypothesis { weight: *weight, objects }).collect();
    let mut core = Box::new(
        Tracker::<f64, M, G, S, D, H, N, Z, K, B>::new(config.clone(), &hypotheses, time)
            .map_err(|e| format!("tracker configuration: {e}"))?,
    );
    let mut reference = ReferenceTracker::new(config, prior, time, budget.bytes)?;
    reference.set_max_children(budget.children);
    reference.set_max_work(budget.work);
    Ok(compare_trackers(&mut core, &mut reference, scans))
}
