//! From a scenario's settings to tracker-core values, for every world and scalar: Gaussians, the prior,
//! birth cells, the child generation and the tracker's policies. Each conversion is written once; the
//! worlds add their models and sensors.

use crate::pipeline::tracker::TrackerKind;
use crate::scenario::{
    BirthDetectionSpec, NumericalFailureSpec, ProposalSpec, SelectionSpec, StoreOverflowSpec, TrackerSpec,
};
use nalgebra::{SMatrix, SVector};
use tracker_core::config::Selection;
use tracker_core::sampler::{Proposal, SamplerConfig};
use tracker_core::{
    BirthDetection, ChildGeneration, Gaussian, NumericalFailure, PriorObject, Real, StoreOverflow, TrackLabel,
    TrackLoss,
};

/// A Gaussian from a mean and a covariance given by rows, each value rounded once to `T`.
pub fn gaussian<T: Real, const S: usize>(mean: &[f64; S], covariance: &[[f64; S]; S]) -> Gaussian<T, S> {
    Gaussian {
        mean: SVector::from(*mean).map(T::of_f64),
        covariance: SMatrix::<f64, S, S>::from_fn(|i, j| covariance[i][j]).map(T::of_f64),
    }
}

/// One prior object of a scenario: label, mean and covariance by rows.
pub type PriorObjectParts<'a, const S: usize> = (u32, &'a [f64; S], &'a [[f64; S]; S]);

/// The prior hypotheses as (weight, objects) in scalar `T`.
pub fn prior<'a, T: Real, const S: usize, O>(
    hypotheses: impl IntoIterator<Item = (f64, O)>,
) -> Vec<(T, Vec<PriorObject<T, S>>)>
where
    O: IntoIterator<Item = PriorObjectParts<'a, S>>,
{
    hypotheses
        .into_iter()
        .map(|(weight, objects)| {
            let objects = objects
                .into_iter()
                .map(|(label, mean, covariance)| PriorObject {
                    label: TrackLabel(label),
                    state: gaussian(mean, covariance),
                })
                .collect();
            (T::of_f64(weight), objects)
        })
        .collect()
}

/// The birth cells (mean, covariance by rows) in a store of `B` cells.
///
/// # Errors
/// A one-line message when there are more than `B` cells.
pub fn birth_cells<'a, T: Real, const S: usize, const B: usize>(
    cells: impl ExactSizeIterator<Item = (&'a [f64; S], &'a [[f64; S]; S])>,
    capacity_name: &str,
) -> Result<heapless::Vec<Gaussian<T, S>, B>, String> {
    let count = cells.len();
    let mut store = heapless::Vec::new();
    for (mean, covariance) in cells {
        store
            .push(gaussian(mean, covariance))
            .map_err(|_| format!("birth.cells: {count} cells exceed {capacity_name} of {B}"))?;
    }
    Ok(store)
}

/// The sampler settings of tracker settings `tracker` (`tracker.sampler`), of either scenario version.
pub fn sampler_config(tracker: &TrackerSpec) -> SamplerConfig {
    let spec = tracker.sampler;
    SamplerConfig {
        burn_in: spec.burn_in,
        steps: spec.steps,
        proposal: match spec.proposal {
            ProposalSpec::Paper => Proposal::Paper,
            ProposalSpec::MoveOrSwap => Proposal::MoveOrSwap,
            ProposalSpec::Informed => Proposal::Informed,
        },
        clusters: spec.clusters,
        exhaustive_limit: spec.exhaustive_limit,
        exact_start: spec.exact_start,
    }
}

/// The child generation of the tracker `kind` with settings `tracker`: R-FISST's sampled children, or the
/// exhaustive children of the reference and HOMHT.
pub fn children(kind: TrackerKind, tracker: &TrackerSpec) -> ChildGeneration {
    match kind {
        TrackerKind::Rfisst => ChildGeneration::Sampled(sampler_config(tracker)),
        TrackerKind::Homht | TrackerKind::Reference => {
            ChildGeneration::Exhaustive { max_children_per_scan: tracker.max_children_per_scan }
        }
    }
}

/// The core's birth detection.
pub fn birth_detection(spec: BirthDetectionSpec) -> BirthDetection {
    match spec {
        BirthDetectionSpec::AllDetected => BirthDetection::AllDetected,
        BirthDetectionSpec::AllowUndetected => BirthDetection::AllowUndetected,
    }
}

/// The core's policies of tracker settings: hypothesis selection, track-store overflow, numerical failure,
/// track loss.
pub fn policies(tracker: &TrackerSpec) -> (Selection, StoreOverflow, NumericalFailure, TrackLoss) {
    (
        match tracker.selection {
            SelectionSpec::TopWeight => Selection::TopWeight,
            SelectionSpec::SampledByWeight => Selection::SampledByWeight,
            SelectionSpec::TopWeightWithin { decades } => Selection::TopWeightWithin { decades },
        },
        match tracker.store_overflow {
            StoreOverflowSpec::PruneChildren => StoreOverflow::PruneChildren,
            StoreOverflowSpec::Error => StoreOverflow::Error,
        },
        match tracker.numerical_failure {
            NumericalFailureSpec::DropTrack => NumericalFailure::DropTrack,
            NumericalFailureSpec::Error => NumericalFailure::Error,
        },
        tracker.lost_after_unseen_scans.map_or(TrackLoss::Never, TrackLoss::AfterUnseenScans),
    )
}
