//! Routing a scan's measurements to the pool's clusters (docs/maths.md §13.2), in fixed memory: each
//! cluster's tracks predicted to the scan and gated with the core's own test (in the field of view and an
//! entry δ > −∞), clusters that share a measurement grouped for a merge (union–find in cluster order; a
//! merge that could exceed N objects declined, the measurement kept by its first group), and the
//! measurements in no gate left to the birth cluster.

use super::rest::ClusterRest;
use crate::ekf;
use crate::model::{MeasurementModel, MotionModel};
use crate::real::Real;
use crate::tracker::{PlacedScan, in_field_of_view};
use nalgebra::SVector;

/// No cluster.
pub(super) const NONE: u16 = u16::MAX;

/// Marks in `hit` the measurements in the gate of some track of `rest` predicted to `time`; returns whether
/// some track is in the field of view.
#[allow(clippy::too_many_arguments)]
pub(super) fn gate<T, M, G, const S: usize, const D: usize, const N: usize, const H: usize, const K: usize>(
    motion: &M,
    placed: &PlacedScan<T, G>,
    rest: &ClusterRest<T, S, N, H, K>,
    time: f64,
    measurements: &[SVector<T, D>],
    gate: Option<T>,
    hit: &mut [bool],
) -> bool
where
    T: Real,
    M: MotionModel<T, S>,
    G: MeasurementModel<T, S, D>,
{
    let dt = T::of_f64(time - rest.time());
    let mut in_view = false;
    for track in rest.tracks() {
        let Ok(state) = ekf::predict(motion, &track.state, dt) else { continue };
        let predicted = placed.model.measure(&state.mean);
        if !in_field_of_view(&placed.detection.field_of_view, &placed.model, &state, &predicted) {
            continue;
        }
        let Ok(innovation) = ekf::innovation(&placed.model, &state) else { continue };
        in_view = true;
        let first = innovation.cholesky[(0, 0)];
        for (z, hit) in measurements.iter().zip(hit.iter_mut()).filter(|(_, h)| !**h) {
            let residual = placed.model.residual(z, &innovation.predicted);
            // The first whitened component alone rejects most measurements (d² ≥ w²).
            let w = residual[0] / first;
            if gate.is_some_and(|gate| w * w > gate) {
                continue;
            }
            *hit = placed.weights.entry_of_residual(&innovation, &residual) > T::NEG_INFINITY;
        }
    }
    in_view
}

/// The routing of one scan: which cluster claimed each measurement first, the groups of clusters to merge
/// and the merges declined.
pub(super) struct Routing<const P: usize, const L: usize> {
    owner: [u16; L],
    parent: [u16; P],
    objects: [usize; P],
    group_of: [u16; P],
    clusters: usize,
    measurements: usize,
    /// Groups, numbered in the order of their first cluster.
    pub groups: usize,
    /// Shared measurements whose groups were not merged: the product could hold more than N objects.
    pub declined: usize,
}

impl<const P: usize, const L: usize> Routing<P, L> {
    /// The routing of `measurements` measurements among `clusters` clusters, before any gate.
    pub fn new(clusters: usize, measurements: usize) -> Self {
        let mut parent = [0; P];
        for (i, p) in parent.iter_mut().enumerate() {
            *p = i as u16;
        }
        Self {
            owner: [NONE; L],
            parent,
            objects: [0; P],
            group_of: [NONE; P],
            clusters: clusters.min(P),
            measurements: measurements.min(L),
            groups: 0,
            declined: 0,
        }
    }

    /// Cluster `cluster` (of at most `objects` objects per hypothesis, taken in cluster order) claims the
    /// measurements of `hit`: an unclaimed one becomes its, a claimed one joins the two groups unless they
    /// could hold more than `capacity` objects together.
    pub fn claim(&mut self, cluster: usize, objects: usize, hit: &[bool], capacity: usize) {
        if let Some(o) = self.objects.get_mut(cluster) {
            *o = objects;
        }
        for (m, _) in hit.iter().enumerate().take(self.measurements).filter(|(_, h)| **h) {
            let Some(owner) = self.owner.get_mut(m) else { break };
            if *owner == NONE {
                *owner = cluster as u16;
                continue;
            }
            let other = usize::from(*owner);
            let (a, b) = (self.find(other), self.find(cluster));
            if a == b {
                continue;
            }
            let (low, high) = (a.min(b), a.max(b));
            let joined = self.objects(a) + self.objects(b);
            if joined > capacity {
                self.declined += 1;
                continue;
            }
            if let (Some(parent), Some(o)) = (self.parent.get_mut(high), self.objects.get_mut(low)) {
                (*parent, *o) = (low as u16, joined);
            }
        }
    }

    /// Numbers the groups in the order of their first cluster; call once, after every claim.
    pub fn finish(&mut self) {
        let mut group_of_root = [NONE; P];
        for cluster in 0..self.clusters {
            let root = self.find(cluster);
            let Some(group) = group_of_root.get_mut(root) else { continue };
            if *group == NONE {
                *group = self.groups as u16;
                self.groups += 1;
            }
            if let Some(g) = self.group_of.get_mut(cluster) {
                *g = *group;
            }
        }
    }

    /// The clusters of group `group`, in cluster order.
    pub fn members(&self, group: usize) -> impl Iterator<Item = usize> + '_ {
        (0..self.clusters).filter(move |&c| self.group_of(c) == Some(group))
    }

    /// The measurements routed to group `group`, in scan order.
    pub fn measurements(&self, group: usize) -> impl Iterator<Item = usize> + '_ {
        (0..self.measurements).filter(move |&m| {
            let owner = self.owner.get(m).copied().unwrap_or(NONE);
            owner != NONE && self.group_of(usize::from(owner)) == Some(group)
        })
    }

    /// The measurements in no gate (the birth cluster's), in scan order.
    pub fn unclaimed(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.measurements).filter(|&m| self.owner.get(m) == Some(&NONE))
    }

    fn group_of(&self, cluster: usize) -> Option<usize> {
        self.group_of.get(cluster).filter(|&&g| g != NONE).map(|&g| usize::from(g))
    }

    fn objects(&self, root: usize) -> usize {
        self.objects.get(root).copied().unwrap_or(usize::MAX / 2)
    }

    /// The root of `i`'s group (path halving); at most P steps.
    fn find(&mut self, mut i: usize) -> usize {
        for _ in 0..P {
            let Some(&parent) = self.parent.get(i) else { return i };
            let parent = usize::from(parent);
            if parent == i {
                return i;
            }
            let grand = self.parent.get(parent).copied().unwrap_or(parent as u16);
            if let Some(p) = self.parent.get_mut(i) {
                *p = grand;
            }
            i = usize::from(grand);
        }
        i
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hits(measurements: &[usize]) -> [bool; 7] {
        let mut hit = [false; 7];
        measurements.iter().for_each(|&m| hit[m] = true);
        hit
    }

    fn routed(gated: &[&[usize]], objects: &[usize], capacity: usize) -> Routing<4, 7> {
        let mut routing = Routing::<4, 7>::new(gated.len(), 7);
        for (c, g) in gated.iter().enumerate() {
            routing.claim(c, objects[c], &hits(g), capacity);
        }
        routing.finish();
        routing
    }

    fn groups(routing: &Routing<4, 7>) -> ([[usize; 4]; 3], [[usize; 7]; 3]) {
        let (mut members, mut measurements) = ([[9; 4]; 3], [[9; 7]; 3]);
        for g in 0..routing.groups {
            routing.members(g).enumerate().for_each(|(i, c)| members[g][i] = c);
            routing.measurements(g).enumerate().for_each(|(i, m)| measurements[g][i] = m);
        }
        (members, measurements)
    }

    #[test]
    fn clusters_sharing_a_measurement_are_one_group_and_the_rest_go_to_births() {
        let routing = routed(&[&[0, 1], &[2], &[1, 4], &[4, 5]], &[1; 4], 16);
        assert_eq!((routing.groups, routing.declined), (2, 0));
        let (members, measurements) = groups(&routing);
        assert_eq!(members[..2], [[0, 2, 3, 9], [1, 9, 9, 9]]);
        assert_eq!(measurements[..2], [[0, 1, 4, 5, 9, 9, 9], [2, 9, 9, 9, 9, 9, 9]]);
        assert!(routing.unclaimed().eq([3, 6]));
    }

    #[test]
    fn a_merge_that_could_exceed_the_capacity_is_declined_and_the_measurement_kept_by_its_first_group() {
        let routing = routed(&[&[0, 1], &[2], &[1, 4], &[4, 5]], &[3, 1, 2, 2], 5);
        assert_eq!((routing.groups, routing.declined), (3, 1));
        let (members, measurements) = groups(&routing);
        assert_eq!(members, [[0, 2, 9, 9], [1, 9, 9, 9], [3, 9, 9, 9]]);
        assert_eq!(measurements, [[0, 1, 4, 9, 9, 9, 9], [2, 9, 9, 9, 9, 9, 9], [5, 9, 9, 9, 9, 9, 9]]);
        assert!(routing.unclaimed().eq([3, 6]));
    }
}
