//! Routing a scan's measurements to clusters (docs/maths.md §13.2): each cluster's tracks predicted to the
//! scan and gated with the core's own test (an entry δ > −∞: in the field of view and d² within the
//! configuration's gate), clusters sharing a measurement grouped for a merge (union–find, in cluster
//! order), and the measurements in no gate left to the birth cluster. With a view skip, also how long the
//! cluster stays out of each ground sensor's field of view ([`super::view`]) and, when no track is in view,
//! its tracks predicted to the scan: all an empty scan would do to it (§13.2).

use super::view::{self, Sight, SpeedBound};
use super::window::Indexed;
use nalgebra::SVector;
use tracker_core::model::{MeasurementModel, MotionModel};
use tracker_core::tracker::{PlacedScan, in_field_of_view};
use tracker_core::{Gaussian, Track, ekf};

/// What one cluster's tracks see of a scan.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Gated<const S: usize> {
    /// The measurements in the gate of some track of the cluster, in scan order.
    pub measurements: Vec<usize>,
    /// Whether some track is predicted in the field of view.
    pub in_view: bool,
    /// With a view skip, per sensor of the network (by index), seconds from the scan during which no track
    /// can enter that sensor's field of view (docs/maths.md §13.2); 0 where none is known (a sensor that is
    /// not a ground sensor, a track whose prediction failed). Empty without a view skip.
    pub clear_for: Vec<f64>,
    /// With a view skip, when no track is in view and every track's prediction succeeded: each track of the
    /// store (in order) predicted to the scan, the state an empty scan leaves it in (§13.2).
    pub predicted: Option<Vec<Gaussian<f64, S>>>,
    /// From [`coast`]: each track's mean (in store order) predicted to the scan, every one cleared from the
    /// scanning sensor; the cluster keeps its state and coasts (§13.2).
    pub coasted: Option<Vec<SVector<f64, S>>>,
}

/// What a view skip needs at one scan: the ground sensors placed at its time, the speed bound and the
/// scanning sensor's index.
pub struct Skip<'a, G, const S: usize> {
    pub sights: &'a [Sight<G>],
    pub speed: SpeedBound<S>,
    pub scanning: usize,
}

impl<G, const S: usize> Clone for Skip<'_, G, S> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<G, const S: usize> Copy for Skip<'_, G, S> {}

/// The measurements of `scan` in the gates of `tracks` predicted by `dt` with `motion`, as the core
/// decides it ([`tracker_core::weight::WeightModel::entry_of_residual`] with the configuration's `gate`). A
/// track whose prediction fails, or in view whose innovation fails, gates nothing (the core drops it from
/// the scan or fails the scan). With `skip`, also [`Gated::clear_for`] and [`Gated::predicted`]. `scan` is
/// indexed with [`distance`] of `placed`'s model.
pub fn gate<M, G, const S: usize, const D: usize>(
    motion: &M,
    placed: &PlacedScan<f64, G>,
    tracks: &[Track<f64, S>],
    dt: f64,
    scan: &Indexed<'_, D>,
    gate: Option<f64>,
    skip: Option<Skip<'_, G, S>>,
) -> Gated<S>
where
    M: MotionModel<f64, S>,
    G: MeasurementModel<f64, S, D>,
{
    let measurements = scan.measurements;
    let mut hit = vec![false; measurements.len()];
    let mut in_view = false;
    // Per sensor: min over tracks of its clearance; 0 for sensors without a sight.
    let mut clear_for = skip.map(|skip| unbounded(&skip)).unwrap_or_default();
    let mut predicted = skip.map(|_| Vec::with_capacity(tracks.len()));
    // Per sight, the gaps of a nearby track already measured (§13.2).
    let mut near = vec![None; skip.map_or(0, |s| s.sights.len())];
    for track in tracks {
        let Ok(state) = ekf::predict(motion, &track.state, dt) else {
            clear_for.fill(0.0);
            predicted = None;
            continue;
        };
        // A track with a clearance from the scanning sensor is more than MARGIN_KM outside the region its
        // field of view lies in, so out of view (§13.2).
        let cleared = skip.is_some_and(|skip| clear(&skip, &state.mean, &mut clear_for, &mut near, false));
        // In view or not from ẑ = h(x̂⁻) alone, as the core decides it; the innovation only for a track in
        // view (out of view, a track whose innovation would fail is dropped at its cluster's next step in a
        // core instead of now, docs/maths.md §13.2).
        if cleared
            || !in_field_of_view(
                &placed.detection.field_of_view,
                &placed.model,
                &state,
                &placed.model.measure(&state.mean),
            )
        {
            if let Some(predicted) = &mut predicted {
                predicted.push(state);
            }
            continue;
        }
        predicted = None;
        let Ok(innovation) = ekf::innovation(&placed.model, &state) else {
            clear_for.fill(0.0);
            continue;
        };
        in_view = true;
        let first = innovation.cholesky[(0, 0)];
        // Only the measurements whose |ν₀| can be within √gate · L₀₀ (§13.2: the window refuses only what
        // the test on w₀ below refuses).
        let radius = gate.map(|gate| gate.sqrt() * first.abs());
        for &m in scan.candidates(&innovation.predicted, radius, distance::<G, S, D>(&placed.model)) {
            if !hit[m] {
                let residual = placed.model.residual(&measurements[m], &innovation.predicted);
                // d² = Σ wᵢ² ≥ w₀² with w₀ = ν₀ / L₀₀ (the first whitened component, the same bits as the
                // core's): a cheaper test that refuses only what the full one refuses.
                let w = residual[0] / first;
                if gate.is_some_and(|gate| w * w > gate) {
                    continue;
                }
                hit[m] = placed.weights.entry_of_residual(&innovation, &residual) > f64::NEG_INFINITY;
            }
        }
    }
    clear_for.iter_mut().filter(|c| !c.is_finite()).for_each(|c| *c = 0.0);
    let measurements = hit.iter().enumerate().filter(|(_, h)| **h).map(|(i, _)| i).collect();
    Gated { measurements, in_view, clear_for, predicted, coasted: None }
}

/// The oldest a cluster's state may be for it to coast (s; docs/maths.md §13.2). Past it the cluster goes
/// through the full gate and is given its predictions, so no prediction from its state spans more than this
/// plus the gap to its next gating. One prediction over hours takes the process noise as a single
/// white-acceleration step in the axes of its first state, not as the orbit carries it (§6.7): unbounded
/// coasts raised the observed objects' median error over a day at 1,000 objects from 0.42 to 1.05 km.
pub const MAX_COAST_AGE_S: f64 = 60.0;

/// The gates of a cluster whose tracks' means alone, predicted to the scan, are all cleared from the
/// scanning sensor (docs/maths.md §13.2, coasting): no track in view, no measurement, the clearances from
/// those means, and the means as [`Gated::coasted`]; `None` when a mean's prediction fails or a track has no
/// clearance from the scanning sensor ([`gate`] then decides). The means are predicted without Φ or P
/// ([`MotionModel::propagate_mean`]): from `from` (a coast's means and the seconds since them) when given,
/// else from the tracks' own means by `dt`. A chain of coasts differs from the one prediction from the
/// tracks' rest by the integrator's error, which [`view::MARGIN_KM`] covers: a track cleared here is out of
/// view as [`gate`] would decide it from its rest.
pub fn coast<M, G, const S: usize, const D: usize>(
    motion: &M,
    tracks: &[Track<f64, S>],
    dt: f64,
    from: Option<(&[SVector<f64, S>], f64)>,
    skip: &Skip<'_, G, S>,
) -> Option<Gated<S>>
where
    M: MotionModel<f64, S>,
    G: MeasurementModel<f64, S, D>,
{
    let from = from.filter(|(means, _)| means.len() == tracks.len());
    let mut clear_for = unbounded(skip);
    let mut near = vec![None; skip.sights.len()];
    let mut means = Vec::with_capacity(tracks.len());
    for (k, track) in tracks.iter().enumerate() {
        let (start, step) = from.map_or((&track.state.mean, dt), |(means, since)| (&means[k], since));
        let mean = motion.propagate_mean(start, step).ok()?;
        if !clear(skip, &mean, &mut clear_for, &mut near, true) {
            return None;
        }
        means.push(mean);
    }
    clear_for.iter_mut().filter(|c| !c.is_finite()).for_each(|c| *c = 0.0);
    Some(Gated { measurements: vec![], in_view: false, clear_for, predicted: None, coasted: Some(means) })
}

/// Per sensor of the network, the clearance before any track: unbounded for a ground sensor (a sight),
/// 0 for the others.
fn unbounded<G, const S: usize>(skip: &Skip<'_, G, S>) -> Vec<f64> {
    let mut clear_for = vec![0.0; skip.sights.iter().map(|s| s.sensor + 1).max().unwrap_or(0)];
    skip.sights.iter().for_each(|s| clear_for[s.sensor] = f64::INFINITY);
    clear_for
}

/// Lowers each sensor's entry of `clear_for` to the clearance of a track whose predicted mean is `mean`
/// (nearby tracks' gaps in `near`, one per sight); a sensor already at 0 is left alone, except the scanning
/// one, which is taken first. Whether the track is cleared from the scanning sensor (§13.2); when it is not
/// and `only_cleared`, the other sensors are left alone. Each entry is a minimum over tracks and each sight's
/// `near` its own, so the order of the sights changes nothing.
fn clear<G, const S: usize, const D: usize>(
    skip: &Skip<'_, G, S>,
    mean: &SVector<f64, S>,
    clear_for: &mut [f64],
    near: &mut [Option<(view::Gaps, SVector<f64, S>)>],
    only_cleared: bool,
) -> bool
where
    G: MeasurementModel<f64, S, D>,
{
    let lower = |k: usize, near: &mut Option<(view::Gaps, SVector<f64, S>)>, clear_for: &mut [f64]| {
        let sight = &skip.sights[k];
        let own = view::clear_near(sight, mean, skip.speed, near);
        clear_for[sight.sensor] = clear_for[sight.sensor].min(own);
        own > 0.0
    };
    let scanning = skip.sights.iter().position(|s| s.sensor == skip.scanning);
    let cleared = scanning.is_some_and(|k| lower(k, &mut near[k], clear_for));
    if !cleared && only_cleared {
        return false;
    }
    for (k, near) in near.iter_mut().enumerate() {
        if Some(k) != scanning && clear_for[skip.sights[k].sensor] > 0.0 {
            lower(k, near, clear_for);
        }
    }
    cleared
}

/// The distance a scan is indexed by for `model` ([`Indexed`]): the absolute first component of the
/// residual, |ν₀(a, b)| (a plain or a wrapped difference, docs/maths.md §13.2).
pub fn distance<G, const S: usize, const D: usize>(model: &G) -> impl Fn(&SVector<f64, D>, &SVector<f64, D>) -> f64 + '_
where
    G: MeasurementModel<f64, S, D>,
{
    move |a, b| model.residual(a, b)[0].abs()
}

/// The scan's routing: the groups of clusters to merge and each group's measurements.
#[derive(Debug, Clone, PartialEq)]
pub struct Routing {
    /// The cluster indices of every group, group after group (each group in increasing order; groups in
    /// the order of their first index): every cluster in exactly one group; a group of two or more is a
    /// merge. Flat, so that a scan of many clusters allocates no vector per cluster.
    members: Vec<usize>,
    /// Where each group ends in `members`.
    ends: Vec<usize>,
    /// Per group, its measurements in scan order.
    pub measurements: Vec<Vec<usize>>,
    /// The measurements in no cluster's gate, in scan order: the birth cluster's.
    pub unclaimed: Vec<usize>,
    /// Shares of a measurement between two groups not merged because the merge could hold more than the
    /// capacity's objects: the measurement stays with the group that gated it first (§13.3).
    pub declined: usize,
}

impl Routing {
    /// The groups, in order.
    pub fn groups(&self) -> impl Iterator<Item = &[usize]> {
        self.ends.iter().scan(0, |start, &end| {
            let group = &self.members[*start..end];
            *start = end;
            Some(group)
        })
    }
}

/// Groups the clusters of `gated` (one entry per cluster, in cluster order) that share a measurement of a
/// scan of `count` measurements, where `objects[c]` is the most objects a hypothesis of cluster `c` holds
/// and no group may hold more than `capacity` (a cluster's N): a share that would join two groups beyond it
/// is declined, and the measurement stays with the group that gated it first (docs/maths.md §13.3).
pub fn route<const S: usize>(gated: &[Gated<S>], count: usize, objects: &[usize], capacity: usize) -> Routing {
    let mut parent: Vec<usize> = (0..gated.len()).collect();
    // The most objects a product over each root's group holds: the sum of its members'.
    let mut group_objects = objects.to_vec();
    let mut first_owner: Vec<Option<usize>> = vec![None; count];
    let mut declined = 0;
    for (cluster, g) in gated.iter().enumerate() {
        for &m in &g.measurements {
            match first_owner[m] {
                None => first_owner[m] = Some(cluster),
                Some(other) => {
                    let (a, b) = (find(&mut parent, other), find(&mut parent, cluster));
                    if a == b {
                        continue;
                    }
                    if group_objects[a] + group_objects[b] > capacity {
                        declined += 1;
                        continue;
                    }
                    let joined = group_objects[a] + group_objects[b];
                    group_objects[union(&mut parent, a, b)] = joined;
                }
            }
        }
    }
    // Each cluster's group (numbered in the order of their first cluster) and the groups' sizes.
    let mut group_of_root: Vec<Option<usize>> = vec![None; gated.len()];
    let (mut group_of, mut sizes) = (Vec::with_capacity(gated.len()), vec![]);
    for cluster in 0..gated.len() {
        let root = find(&mut parent, cluster);
        let group = *group_of_root[root].get_or_insert_with(|| {
            sizes.push(0);
            sizes.len() - 1
        });
        sizes[group] += 1;
        group_of.push(group);
    }
    let ends: Vec<usize> = sizes
        .iter()
        .scan(0, |end, size| {
            *end += size;
            Some(*end)
        })
        .collect();
    let mut next: Vec<usize> = ends.iter().zip(&sizes).map(|(end, size)| end - size).collect();
    let mut members = vec![0; gated.len()];
    for (cluster, &group) in group_of.iter().enumerate() {
        members[next[group]] = cluster;
        next[group] += 1;
    }
    let mut measurements = vec![vec![]; ends.len()];
    let mut unclaimed = vec![];
    for (m, owner) in first_owner.iter().enumerate() {
        match owner {
            Some(cluster) => measurements[group_of[*cluster]].push(m),
            None => unclaimed.push(m),
        }
    }
    Routing { members, ends, measurements, unclaimed, declined }
}

fn find(parent: &mut [usize], mut i: usize) -> usize {
    while parent[i] != i {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    i
}

/// Joins the sets of `a` and `b` under the smaller root, so that roots (and so groups) follow cluster order;
/// returns the root.
fn union(parent: &mut [usize], a: usize, b: usize) -> usize {
    let (ra, rb) = (find(parent, a), find(parent, b));
    let (low, high) = (ra.min(rb), ra.max(rb));
    parent[high] = low;
    low
}

#[cfg(test)]
mod tests {
    use super::*;

    fn gated(measurements: &[usize]) -> Gated<4> {
        Gated { measurements: measurements.to_vec(), in_view: true, clear_for: vec![], predicted: None, coasted: None }
    }

    #[test]
    fn clusters_sharing_a_measurement_are_one_group_and_the_rest_go_to_births() {
        // Clusters 0 and 2 share measurement 1; 2 and 3 share 4 (a chain); cluster 1 is alone.
        let routing = route(&[gated(&[0, 1]), gated(&[2]), gated(&[1, 4]), gated(&[4, 5])], 7, &[1; 4], 16);
        assert_eq!(routing.groups().collect::<Vec<_>>(), vec![&[0, 2, 3][..], &[1]]);
        assert_eq!(routing.measurements, vec![vec![0, 1, 4, 5], vec![2]]);
        assert_eq!(routing.unclaimed, vec![3, 6]);
        assert_eq!(routing.declined, 0);
    }

    #[test]
    fn a_merge_that_could_exceed_the_capacity_is_declined_and_the_measurement_kept_by_its_first_group() {
        // The same clusters holding 3, 1, 2 and 2 objects, capacity 5: 0 and 2 join (5 objects); joining 3
        // would make 7, so measurement 4 stays with cluster 0's group and cluster 3 keeps measurement 5.
        let routing = route(&[gated(&[0, 1]), gated(&[2]), gated(&[1, 4]), gated(&[4, 5])], 7, &[3, 1, 2, 2], 5);
        assert_eq!(routing.groups().collect::<Vec<_>>(), vec![&[0, 2][..], &[1], &[3]]);
        assert_eq!(routing.measurements, vec![vec![0, 1, 4], vec![2], vec![5]]);
        assert_eq!(routing.unclaimed, vec![3, 6]);
        assert_eq!(routing.declined, 1);
        // Every measurement is routed once: none lost.
        let routed: usize = routing.measurements.iter().map(Vec::len).sum::<usize>() + routing.unclaimed.len();
        assert_eq!(routed, 7);
        // With room for all, the chain is one group again.
        let roomy = route(&[gated(&[0, 1]), gated(&[2]), gated(&[1, 4]), gated(&[4, 5])], 7, &[3, 1, 2, 2], 7);
        assert_eq!((roomy.groups().count(), roomy.declined), (2, 0));
    }
}
