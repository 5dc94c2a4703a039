//! Routing a scan's measurements to clusters (docs/maths.md §13.2): each cluster's tracks predicted to the
//! scan and gated with the core's own test (an entry δ > −∞: in the field of view and d² within the
//! configuration's gate), clusters sharing a measurement grouped for a merge (union–find, in cluster
//! order), and the measurements in no gate left to the birth cluster.

use nalgebra::SVector;
use tracker_core::model::{MeasurementModel, MotionModel};
use tracker_core::tracker::{PlacedScan, in_field_of_view};
use tracker_core::{Track, ekf};

/// What one cluster's tracks see of a scan.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Gated {
    /// The measurements in the gate of some track of the cluster, in scan order.
    pub measurements: Vec<usize>,
    /// Whether some track is predicted in the field of view.
    pub in_view: bool,
}

/// The measurements of `measurements` in the gates of `tracks` predicted by `dt` with `motion`, as the core
/// decides it ([`tracker_core::weight::WeightModel::entry_of_residual`]). A track whose prediction or
/// innovation fails gates nothing (the core drops it from the scan or fails the scan).
pub fn gate<M, G, const S: usize, const D: usize>(
    motion: &M,
    placed: &PlacedScan<f64, G>,
    tracks: &[Track<f64, S>],
    dt: f64,
    measurements: &[SVector<f64, D>],
) -> Gated
where
    M: MotionModel<f64, S>,
    G: MeasurementModel<f64, S, D>,
{
    let mut hit = vec![false; measurements.len()];
    let mut in_view = false;
    for track in tracks {
        let Ok(state) = ekf::predict(motion, &track.state, dt) else { continue };
        let Ok(innovation) = ekf::innovation(&placed.model, &state) else { continue };
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
    Gated { measurements: hit.iter().enumerate().filter(|(_, h)| **h).map(|(i, _)| i).collect(), in_view }
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
        Gated { measurements: measurements.to_vec(), in_view: true }
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
