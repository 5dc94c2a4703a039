//! Routing a scan's measurements to clusters (docs/maths.md §13.2): each cluster's tracks predicted to the
//! scan and gated with the core's own test (an entry δ > −∞: in the field of view and d² within the
//! configuration's gate), clusters sharing a measurement grouped for a merge (union–find, in cluster
//! order), and the measurements in no gate left to the birth cluster. With a speed bound, also how long the
//! cluster stays beyond the sensor's range window, so that it can be left unstepped (§13.2).

use nalgebra::SVector;
use tracker_core::model::{MeasurementModel, MotionModel};
use tracker_core::sensor::Region;
use tracker_core::tracker::{PlacedScan, in_field_of_view};
use tracker_core::{Track, ekf};

/// What one cluster's tracks see of a scan.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Gated {
    /// The measurements in the gate of some track of the cluster, in scan order.
    pub measurements: Vec<usize>,
    /// Whether some track is predicted in the field of view.
    pub in_view: bool,
    /// Seconds from the scan during which no track can come within the sensor's range window: every
    /// track beyond it and closing in no faster than the speed bound (docs/maths.md §13.2). `None` when
    /// not asked for, when some track is within the window's range or its range is not known.
    pub clear_for: Option<f64>,
}

/// A bound (km/s) on how fast an object of state `x` can close in on any sensor of the network.
pub type SpeedBound<const S: usize> = fn(&SVector<f64, S>) -> f64;

/// The measurements of `measurements` in the gates of `tracks` predicted by `dt` with `motion`, as the core
/// decides it ([`tracker_core::weight::WeightModel::entry_of_residual`]). A track whose prediction or
/// innovation fails gates nothing (the core drops it from the scan or fails the scan). With `speed`, also
/// [`Gated::clear_for`].
pub fn gate<M, G, const S: usize, const D: usize>(
    motion: &M,
    placed: &PlacedScan<f64, G>,
    tracks: &[Track<f64, S>],
    dt: f64,
    measurements: &[SVector<f64, D>],
    speed: Option<SpeedBound<S>>,
) -> Gated
where
    M: MotionModel<f64, S>,
    G: MeasurementModel<f64, S, D>,
{
    let mut hit = vec![false; measurements.len()];
    let mut in_view = false;
    let max_range = match placed.detection.field_of_view {
        Region::Look { range: Some([_, max]), .. } => Some(max),
        _ => None,
    };
    // min over tracks of (range − max range) / speed bound; None once some track cannot be bounded.
    let mut clear_for = speed.and(max_range).map(|_| f64::INFINITY);
    for track in tracks {
        let Ok(state) = ekf::predict(motion, &track.state, dt) else {
            clear_for = None;
            continue;
        };
        let Ok(innovation) = ekf::innovation(&placed.model, &state) else {
            clear_for = None;
            continue;
        };
        if let (Some(bound), Some(speed), Some(max)) = (clear_for, speed, max_range) {
            let look = placed.model.look_of_state(&state.mean).or_else(|| placed.model.look(&innovation.predicted));
            let closing = speed(&state.mean);
            clear_for = match look.and_then(|l| l.range) {
                Some(range) if range > max && closing.is_finite() && closing > 0.0 => {
                    Some(bound.min((range - max) / closing))
                }
                _ => None,
            };
        }
        if !in_field_of_view(&placed.detection.field_of_view, &placed.model, &state, &innovation.predicted) {
            continue;
        }
        in_view = true;
        for (hit, z) in hit.iter_mut().zip(measurements) {
            if !*hit {
                let residual = placed.model.residual(z, &innovation.predicted);
                *hit = placed.weights.entry_of_residual(&innovation, &residual) > f64::NEG_INFINITY;
            }
        }
    }
    let measurements = hit.iter().enumerate().filter(|(_, h)| **h).map(|(i, _)| i).collect();
    Gated { measurements, in_view, clear_for: clear_for.filter(|c| c.is_finite() && *c > 0.0) }
}

/// The scan's routing: the groups of clusters to merge and each group's measurements.
#[derive(Debug, Clone, PartialEq)]
pub struct Routing {
    /// Groups of cluster indices (each in increasing order; groups in the order of their first index),
    /// every cluster in exactly one group; a group of two or more is a merge.
    pub groups: Vec<Vec<usize>>,
    /// Per group, its measurements in scan order.
    pub measurements: Vec<Vec<usize>>,
    /// The measurements in no cluster's gate, in scan order: the birth cluster's.
    pub unclaimed: Vec<usize>,
}

/// Groups the clusters of `gated` (one entry per cluster, in cluster order) that share a measurement of a
/// scan of `count` measurements.
pub fn route(gated: &[Gated], count: usize) -> Routing {
    let mut parent: Vec<usize> = (0..gated.len()).collect();
    let mut first_owner: Vec<Option<usize>> = vec![None; count];
    for (cluster, g) in gated.iter().enumerate() {
        for &m in &g.measurements {
            match first_owner[m] {
                None => first_owner[m] = Some(cluster),
                Some(other) => union(&mut parent, other, cluster),
            }
        }
    }
    let mut group_of_root: Vec<Option<usize>> = vec![None; gated.len()];
    let mut groups: Vec<Vec<usize>> = vec![];
    for cluster in 0..gated.len() {
        let root = find(&mut parent, cluster);
        let group = *group_of_root[root].get_or_insert_with(|| {
            groups.push(vec![]);
            groups.len() - 1
        });
        groups[group].push(cluster);
    }
    let mut measurements = vec![vec![]; groups.len()];
    let mut unclaimed = vec![];
    for (m, owner) in first_owner.iter().enumerate() {
        match owner {
            Some(cluster) => {
                let root = find(&mut parent, *cluster);
                measurements[group_of_root[root].expect("every root has a group")].push(m);
            }
            None => unclaimed.push(m),
        }
    }
    Routing { groups, measurements, unclaimed }
}

fn find(parent: &mut [usize], mut i: usize) -> usize {
    while parent[i] != i {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    i
}

/// Joins the sets of `a` and `b` under the smaller root, so that roots (and so groups) follow cluster order.
fn union(parent: &mut [usize], a: usize, b: usize) {
    let (ra, rb) = (find(parent, a), find(parent, b));
    let (low, high) = (ra.min(rb), ra.max(rb));
    parent[high] = low;
}

#[cfg(test)]
mod tests {
    use super::*;

    fn gated(measurements: &[usize]) -> Gated {
        Gated { measurements: measurements.to_vec(), in_view: true, clear_for: None }
    }

    #[test]
    fn clusters_sharing_a_measurement_are_one_group_and_the_rest_go_to_births() {
        // Clusters 0 and 2 share measurement 1; 2 and 3 share 4 (a chain); cluster 1 is alone.
        let routing = route(&[gated(&[0, 1]), gated(&[2]), gated(&[1, 4]), gated(&[4, 5])], 7);
        assert_eq!(routing.groups, vec![vec![0, 2, 3], vec![1]]);
        assert_eq!(routing.measurements, vec![vec![0, 1, 4, 5], vec![2]]);
        assert_eq!(routing.unclaimed, vec![3, 6]);
    }
}
