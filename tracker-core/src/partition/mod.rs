//! The partitioned tracker in fixed memory (issue 30, docs/maths.md §13): a pool of at most `P` clusters
//! of objects, each an exact R-FISST tracker over its own objects with its own hypotheses, merged when a
//! measurement gates with two of them, split when their hypotheses factor, and a birth cluster for the
//! measurements in no gate. It is the host's partitioned catalogue tracker (`host-sim`'s
//! `partition::PartitionedTracker`, which holds any number of clusters and steps them in parallel) for a
//! processor that holds a fixed pool: with the same configuration, capacities and scans it gives the
//! host's clusters, labels and core states bit for bit (the host stepping every cluster at every scan, no
//! view skip).
//!
//! - [`rest`]: a cluster between scans ([`ClusterRest`]) and the priors a cluster is rebuilt from.
//! - [`route`]: the gates of a scan and the groups of clusters to merge.
//! - [`split`]: a cluster's factorisation into independent groups of labels.
//! - [`error`]: the typed errors, [`PoolError`].
//!
//! Memory: `2 P` clusters at rest (the live ones and the next scan's), three cores (one steps every
//! cluster of objects in turn, two hold the birth cluster before and after a scan) and a scan's routing
//! (`O(P + L)` words on the stack). A failed step writes only the spare halves, so the pool is then
//! exactly as it was.

pub mod error;
pub mod rest;
mod route;
mod split;

pub use error::{BIRTH_CLUSTER, PoolError};
pub use rest::ClusterRest;

use crate::config::{BirthModel, ChildGeneration, Config, NumericalFailure};
use crate::digest::Fnv1a;
use crate::index::insertion_sort_by;
use crate::model::{MeasurementModel, MotionModel};
use crate::real::Real;
use crate::sensor::ScanGeometry;
use crate::tracker::{PriorHypothesis, PriorObject, Tracker, place_scan};
use nalgebra::SVector;
use rest::{Group, Product, Relabelled};
use route::Routing;

/// What one pool step did (the host's partition report, less its view-skip counts).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PoolReport<T> {
    /// Clusters of objects after the scan.
    pub clusters: usize,
    /// Labels of the largest cluster after the scan.
    pub largest_cluster: usize,
    /// Clusters merged away (a merge of k clusters counts k − 1).
    pub merged: usize,
    /// Shared measurements whose groups were not merged because the product could hold more than N objects.
    pub merges_declined: usize,
    /// Mass pruned by merges (1 − the kept part of the product, summed over merges).
    pub merge_pruned_mass: T,
    /// Mass pruned by the cores' own selection of H children.
    pub step_pruned_mass: T,
    /// New clusters made by splits.
    pub split: usize,
    /// Total variation moved by ε-splits (0 when every split was exact).
    pub split_moved_mass: T,
    /// Clusters born from the birth cluster.
    pub born_clusters: usize,
    /// Measurements routed to the birth cluster.
    pub unclaimed: usize,
    /// Tracklets the birth cluster's pool formed.
    pub tracklets_formed: usize,
    /// Tracks the clusters declared lost and dropped (`Config::track_loss`, docs/maths.md §5.9).
    pub lost_tracks: usize,
    /// Clusters with no measurement and no track in view, stepped with an empty scan.
    pub quiet: usize,
    /// Clusters stepped with at least one measurement (the birth cluster included).
    pub clusters_with_measurements: usize,
    /// Σ over clusters of their hypotheses after the scan.
    pub hypotheses: usize,
}

/// A pool of at most `P` clusters, each a core tracker's state of capacities `H`, `N`, `Z`, `K`, `B`;
/// scans of at most `L` measurements.
///
/// # Examples
/// Two objects far apart are two clusters; a measurement in both gates merges them.
/// ```
/// # use nalgebra::{SMatrix, SVector};
/// use tracker_core::partition::ClusterPool;
/// use tracker_core::sensor::ScanGeometry;
/// use tracker_core::{Gaussian, PriorObject, Region, TrackLabel};
/// let mut config = tracker_core::examples::config();
/// config.sensor.field_of_view = Region::Everywhere { volume: 1e4 };
/// config.gate = Some(16.0);
/// let at = |label: u32, x: f64| PriorObject {
///     label: TrackLabel(label),
///     state: Gaussian { mean: SVector::from([x, 0.0, 0.0, 0.0]), covariance: SMatrix::identity() },
/// };
/// let mut pool = Box::new(ClusterPool::<f64, _, _, 4, 2, 16, 4, 4, 16, 1, 8, 8>::new(
///     config,
///     &[at(0, 0.0), at(1, 100.0)],
///     0.0,
///     0.0,
/// )?);
/// let report = pool.step(&ScanGeometry::single(1.0), &[SVector::from([0.2, 0.1]), SVector::from([99.7, 0.0])])?;
/// assert_eq!((report.clusters, report.merged), (2, 0));
/// # Ok::<(), tracker_core::partition::PoolError>(())
/// ```
#[derive(Debug, Clone)]
pub struct ClusterPool<
    T: Real,
    M,
    G,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
    const P: usize,
    const L: usize,
> {
    /// The core every cluster of objects is stepped in: the configuration without births.
    work: Tracker<T, M, G, S, D, H, N, Z, K, B>,
    /// The birth cluster (the configuration with births) and its spare, stepped as a copy.
    births: [Tracker<T, M, G, S, D, H, N, Z, K, B>; 2],
    /// Which of `births` is live (`false`: index 0).
    birth: bool,
    /// The clusters, in id order, and the spare half the next scan writes.
    clusters: [heapless::Vec<ClusterRest<T, S, N, H, K>, P>; 2],
    /// Which of `clusters` is live (`false`: index 0).
    live: bool,
    /// The cluster a scan just stepped, before it is stored or split (scratch, kept here rather than on
    /// the stack).
    stepped: ClusterRest<T, S, N, H, K>,
    next_cluster: u64,
    next_label: u32,
    time: f64,
    epsilon: T,
}

/// The counters a scan advances, committed with it.
#[derive(Clone, Copy)]
struct Counters {
    next_cluster: u64,
    next_label: u32,
}

impl Counters {
    fn fresh_cluster(&mut self) -> u64 {
        self.next_cluster += 1;
        self.next_cluster - 1
    }
}

impl<
    T,
    M,
    G,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
    const P: usize,
    const L: usize,
> ClusterPool<T, M, G, S, D, H, N, Z, K, B, P, L>
where
    T: Real,
    M: MotionModel<T, S> + Clone,
    G: MeasurementModel<T, S, D> + Clone,
{
    const CAPACITY_CHECK: () = {
        assert!(P > 0 && L > 0, "the pool must hold a cluster and a scan of one measurement");
        assert!(P < u16::MAX as usize && L < u16::MAX as usize, "P and L must fit in u16");
    };

    /// A pool of `objects` (each certain, each its own cluster, numbered in the given order) at `time`;
    /// splits approximate within total variation `epsilon` (0: exact splits only). Returned by value, which
    /// takes a few times the pool's size of stack: on a small target put the pool in a `static` with
    /// [`ClusterPool::empty`] and load it with [`ClusterPool::reset_with`].
    ///
    /// # Errors
    /// As [`ClusterPool::reset_with`].
    pub fn new(
        config: Config<T, M, G, S, B>,
        objects: &[PriorObject<T, S>],
        time: f64,
        epsilon: T,
    ) -> Result<Self, PoolError> {
        let mut pool = Self::empty(config.clone(), config.clone(), config.clone());
        pool.reset_with(config, objects, time, epsilon)?;
        Ok(pool)
    }

    /// A pool holding nothing, its three cores (the working one and the birth cluster's two) holding a
    /// placeholder configuration each (the same three times; on a small target a `const` one, such as a
    /// sensor network's `unconfigured()`): a compile-time `static` that [`ClusterPool::reset_with`] loads
    /// in place. It refuses every scan until then.
    pub const fn empty(
        work: Config<T, M, G, S, B>,
        first: Config<T, M, G, S, B>,
        second: Config<T, M, G, S, B>,
    ) -> Self {
        let () = Self::CAPACITY_CHECK;
        Self {
            work: Tracker::empty(work),
            births: [Tracker::empty(first), Tracker::empty(second)],
            birth: false,
            clusters: [heapless::Vec::new(), heapless::Vec::new()],
            live: false,
            stepped: ClusterRest::EMPTY,
            next_cluster: 0,
            next_label: 0,
            time: 0.0,
            epsilon: T::ZERO,
        }
    }

    /// Loads `config` (the birth cluster's; every cluster of objects takes it without births) and
    /// `objects` at `time`, as [`ClusterPool::new`] builds them; splits within total variation `epsilon`.
    ///
    /// # Errors
    /// [`PoolError::Config`] when the core refuses the configuration or two objects share a label,
    /// [`PoolError::PoolFull`] for more than `P` objects, [`PoolError::Rebuild`] naming an object the core
    /// refuses. The pool is then exactly as it was.
    pub fn reset_with(
        &mut self,
        config: Config<T, M, G, S, B>,
        objects: &[PriorObject<T, S>],
        time: f64,
        epsilon: T,
    ) -> Result<(), PoolError> {
        let quiet = Config { birth: BirthModel::none(), ..config.clone() };
        let spare = usize::from(!self.birth);
        let empty = [PriorHypothesis { weight: T::one(), objects: &[] }];
        // The spare birth core checks the configuration, then every object, before anything live changes.
        self.births[spare].reset_with(config.clone(), &empty, time).map_err(PoolError::Config)?;
        self.check_objects(spare, objects, time)?;
        self.births[usize::from(self.birth)].reset_with(config, &empty, time).map_err(PoolError::Config)?;
        self.work.reset_with(quiet, &empty, time).map_err(PoolError::Config)?;
        self.epsilon = if epsilon.is_finite() { epsilon.max(T::zero()) } else { T::zero() };
        self.load_objects(objects, time)
    }

    /// Reloads the pool with `objects` at `time` under its configuration, as [`ClusterPool::reset_with`].
    ///
    /// # Errors
    /// As [`ClusterPool::reset_with`]; the pool is then exactly as it was.
    pub fn reset(&mut self, objects: &[PriorObject<T, S>], time: f64) -> Result<(), PoolError> {
        let spare = usize::from(!self.birth);
        let empty = [PriorHypothesis { weight: T::one(), objects: &[] }];
        self.births[spare].reset(&empty, time).map_err(PoolError::Config)?;
        self.check_objects(spare, objects, time)?;
        self.load_objects(objects, time)
    }

    /// Checks `objects` in the spare birth core (left holding nothing at `time`): at most `P`, distinct
    /// labels, each one the core accepts.
    fn check_objects(&mut self, spare: usize, objects: &[PriorObject<T, S>], time: f64) -> Result<(), PoolError> {
        let spare = spare & 1;
        if objects.len() > P {
            return Err(PoolError::PoolFull { capacity: P });
        }
        let duplicate = (0..objects.len()).any(|i| objects[..i].iter().any(|o| o.label == objects[i].label));
        if duplicate {
            return Err(PoolError::Config(crate::ConfigError::PriorDuplicateLabel { hypothesis: 0 }));
        }
        let core = &mut self.births[spare];
        for (id, object) in objects.iter().enumerate() {
            let prior = [PriorHypothesis { weight: T::one(), objects: core::slice::from_ref(object) }];
            core.reset(&prior, time).map_err(|error| PoolError::Rebuild { cluster: id as u64, error })?;
        }
        let empty = [PriorHypothesis { weight: T::one(), objects: &[] }];
        core.reset(&empty, time).map_err(PoolError::Config)
    }

    /// Builds each of `objects` (checked) as its own cluster and commits them with the spare birth core.
    fn load_objects(&mut self, objects: &[PriorObject<T, S>], time: f64) -> Result<(), PoolError> {
        let next = &mut self.clusters[usize::from(!self.live)];
        next.clear();
        for (id, object) in objects.iter().enumerate() {
            let prior = [PriorHypothesis { weight: T::one(), objects: core::slice::from_ref(object) }];
            let id = id as u64;
            self.work.reset(&prior, time).map_err(|error| PoolError::Rebuild { cluster: id, error })?;
            push_core(next, id, &self.work)?;
        }
        self.birth = !self.birth;
        self.live = !self.live;
        self.next_cluster = objects.len() as u64;
        self.next_label = objects.iter().map(|o| o.label.0 + 1).max().unwrap_or(0);
        self.time = time;
        Ok(())
    }

    /// The clusters of objects, in id order.
    pub fn clusters(&self) -> &[ClusterRest<T, S, N, H, K>] {
        &self.clusters[usize::from(self.live)]
    }

    /// The birth cluster's core.
    pub fn birth(&self) -> &Tracker<T, M, G, S, D, H, N, Z, K, B> {
        &self.births[usize::from(self.birth)]
    }

    /// The time of the last scan (or of the prior).
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Cluster `index` (in id order) loaded into the pool's working core, to read it as a tracker
    /// (hypotheses, tracks, existence); `None` past the last cluster.
    ///
    /// # Errors
    /// [`PoolError::Rebuild`] when its state does not load (not for a state the pool made).
    pub fn load(&mut self, index: usize) -> Result<Option<&Tracker<T, M, G, S, D, H, N, Z, K, B>>, PoolError> {
        let Some(rest) = self.clusters[usize::from(self.live)].get(index) else { return Ok(None) };
        rest.load(&mut self.work)?;
        Ok(Some(&self.work))
    }

    /// A digest of the whole state, the host partition's word for word: FNV-1a over the time, the next
    /// cluster id and label, the birth cluster's core digest, and each cluster's id and core digest (its
    /// state loaded into the working core; 0 for a state that does not load).
    pub fn digest(&mut self) -> u64 {
        let mut hash = Fnv1a::new();
        hash.write_u64(self.time.to_bits());
        hash.write_u64(self.next_cluster);
        hash.write_u64(u64::from(self.next_label));
        hash.write_u64(self.births[usize::from(self.birth)].digest());
        for rest in &self.clusters[usize::from(self.live)] {
            hash.write_u64(rest.id());
            hash.write_u64(rest.load(&mut self.work).map_or(0, |()| self.work.digest()));
        }
        hash.finish()
    }

    /// Processes one scan of the sensor `geometry` names: route, merge, step each cluster in turn, births,
    /// splits, then commit (docs/maths.md §13).
    ///
    /// # Errors
    /// [`PoolError`]; the pool is then exactly as it was. When a scan has two faults the one returned may
    /// differ from the host's: the pool checks every group's Z before any merge.
    pub fn step(
        &mut self,
        geometry: &ScanGeometry<T>,
        measurements: &[SVector<T, D>],
    ) -> Result<PoolReport<T>, PoolError> {
        if measurements.len() > L {
            return Err(PoolError::ScanTooLarge { received: measurements.len(), capacity: L });
        }
        let live = &self.clusters[usize::from(self.live)];
        let config = self.births[usize::from(self.birth)].config();
        let placed = place_scan(config, geometry, self.time, measurements, usize::MAX).map_err(PoolError::Scan)?;
        let mut routing = Routing::<P, L>::new(live.len(), measurements.len());
        let mut in_view = [false; P];
        for (c, rest) in live.iter().enumerate() {
            let mut hit = [false; L];
            let hit = &mut hit[..measurements.len()];
            let seen = route::gate(&config.motion, &placed, rest, geometry.time, measurements, config.gate, hit);
            if let Some(in_view) = in_view.get_mut(c) {
                *in_view = seen;
            }
            routing.claim(c, rest.max_objects(), hit, N);
        }
        routing.finish();
        for g in 0..routing.groups {
            let id = routing.members(g).next().and_then(|c| live.get(c)).map_or(BIRTH_CLUSTER, ClusterRest::id);
            check_capacity(id, routing.measurements(g).count(), Z)?;
        }
        check_capacity(BIRTH_CLUSTER, routing.unclaimed().count(), Z)?;
        let mut report = PoolReport {
            unclaimed: routing.unclaimed().count(),
            merges_declined: routing.declined,
            ..Default::default()
        };
        let mut counters = Counters { next_cluster: self.next_cluster, next_label: self.next_label };
        let born = self.step_birth(geometry, measurements, &routing, &mut counters, &mut report)?;
        self.clusters[usize::from(!self.live)].clear();
        for g in 0..routing.groups {
            self.step_group(geometry, measurements, &routing, g, &in_view, &mut counters, &mut report)?;
        }
        if let Some(id) = born {
            self.settle_birth(id, geometry.time, &mut counters, &mut report)?;
        }
        // Commit: nothing below can fail.
        let next = &mut self.clusters[usize::from(!self.live)];
        insertion_sort_by(next, |a, b| a.id() < b.id());
        report.clusters = next.len();
        report.largest_cluster = next.iter().map(ClusterRest::label_count).max().unwrap_or(0);
        report.hypotheses = next.iter().map(|c| c.hypotheses().len()).sum();
        self.live = !self.live;
        self.birth = !self.birth;
        (self.next_cluster, self.next_label, self.time) = (counters.next_cluster, counters.next_label, geometry.time);
        Ok(report)
    }

    /// Steps a copy of the birth cluster (the spare core) with the measurements in no gate; returns the id
    /// of the cluster it gives birth to, if it holds tracks.
    fn step_birth(
        &mut self,
        geometry: &ScanGeometry<T>,
        measurements: &[SVector<T, D>],
        routing: &Routing<P, L>,
        counters: &mut Counters,
        report: &mut PoolReport<T>,
    ) -> Result<Option<u64>, PoolError> {
        let mut unclaimed = heapless::Vec::<SVector<T, D>, Z>::new();
        for z in routing.unclaimed().filter_map(|m| measurements.get(m)) {
            // Checked against Z by the caller.
            let _ = unclaimed.push(*z);
        }
        let [first, second] = &mut self.births;
        let (live, spare) = if self.birth { (&*second, first) } else { (&*first, second) };
        spare.copy_state_from(live);
        let step = spare
            .step_scan(geometry, &unclaimed)
            .map_err(|error| PoolError::Cluster { cluster: BIRTH_CLUSTER, error })?;
        report.step_pruned_mass += (T::one() - step.captured_mass).max(T::zero());
        report.tracklets_formed = step.birth_pool.tracklets;
        report.lost_tracks += step.lost_tracks;
        report.clusters_with_measurements += usize::from(!unclaimed.is_empty());
        // The birth cluster's id comes before any split's, as on the host.
        Ok((!spare.tracks().is_empty()).then(|| counters.fresh_cluster()))
    }

    /// Steps group `g` of the routing: a quiet cluster (no measurement, no track in view) with an empty scan,
    /// any other after merging its members, then splits it if it factors.
    #[allow(clippy::too_many_arguments)]
    fn step_group(
        &mut self,
        geometry: &ScanGeometry<T>,
        measurements: &[SVector<T, D>],
        routing: &Routing<P, L>,
        g: usize,
        in_view: &[bool; P],
        counters: &mut Counters,
        report: &mut PoolReport<T>,
    ) -> Result<(), PoolError> {
        let quiet_allowed = self.quiet_steps_cannot_fail();
        let live = &self.clusters[usize::from(self.live)];
        let mut members = heapless::Vec::<u16, P>::new();
        for c in routing.members(g) {
            // At most P clusters.
            let _ = members.push(c as u16);
        }
        let mut zs = heapless::Vec::<SVector<T, D>, Z>::new();
        for z in routing.measurements(g).filter_map(|m| measurements.get(m)) {
            // Checked against Z by the caller.
            let _ = zs.push(*z);
        }
        let lead = members.first().map_or(usize::MAX, |&m| usize::from(m));
        // Every group has a member, a cluster of the live half.
        let Some(first) = live.get(lead) else { return Ok(()) };
        let id = first.id();
        let quiet = quiet_allowed && members.len() == 1 && zs.is_empty() && in_view.get(lead) == Some(&false);
        if members.len() == 1 {
            first.load(&mut self.work)?;
        } else {
            report.merge_pruned_mass += merge(&mut self.work, live, &members, id, self.time)?;
            report.merged += members.len() - 1;
        }
        let step = self.work.step_scan(geometry, &zs).map_err(|error| PoolError::Cluster { cluster: id, error })?;
        if quiet {
            report.quiet += 1;
            return push_core(&mut self.clusters[usize::from(!self.live)], id, &self.work);
        }
        report.step_pruned_mass += (T::one() - step.captured_mass).max(T::zero());
        report.lost_tracks += step.lost_tracks;
        report.clusters_with_measurements += usize::from(!zs.is_empty());
        self.stepped.store(id, &self.work)?;
        self.settle(geometry.time, counters, report)
    }

    /// The birth cluster's hypotheses, relabelled from the next free label, as a new cluster `id` (split if
    /// it factors); the spare birth core then starts afresh at `time`.
    fn settle_birth(
        &mut self,
        id: u64,
        time: f64,
        counters: &mut Counters,
        report: &mut PoolReport<T>,
    ) -> Result<(), PoolError> {
        let spare = &mut self.births[usize::from(!self.birth)];
        let mut own = heapless::Vec::<u32, K>::new();
        for h in spare.hypotheses() {
            for t in h.tracks() {
                if !own.contains(&t.label.0) {
                    // Tracks of the store, so at most K labels.
                    let _ = own.push(t.label.0);
                }
            }
        }
        insertion_sort_by(&mut own, |a, b| a < b);
        let source = Relabelled { birth: &*spare, own: &own, first: counters.next_label };
        self.work.reset_from(&source, time).map_err(|error| PoolError::Rebuild { cluster: id, error })?;
        counters.next_label += own.len() as u32;
        let empty = [PriorHypothesis { weight: T::one(), objects: &[] }];
        spare.reset(&empty, time).map_err(|error| PoolError::Rebuild { cluster: BIRTH_CLUSTER, error })?;
        report.born_clusters += 1;
        self.stepped.store(id, &self.work)?;
        self.settle(time, counters, report)
    }

    /// Stores the cluster just stepped (`self.stepped`) in the next scan's half: whole, or as its groups when
    /// it factors (the first group keeps its id, the others take fresh ids in order).
    fn settle(&mut self, time: f64, counters: &mut Counters, report: &mut PoolReport<T>) -> Result<(), PoolError> {
        let next = &mut self.clusters[usize::from(!self.live)];
        let rest = &self.stepped;
        let Some(factors) = split::factor(rest, self.epsilon) else { return push_copy(next, rest) };
        report.split += usize::from(factors.groups) - 1;
        report.split_moved_mass += factors.moved;
        for g in 0..factors.groups {
            let id = if g == 0 { rest.id() } else { counters.fresh_cluster() };
            let entries = split::group_marginal(rest, &factors, g);
            let source = Group { rest, group_of_slot: &factors.group_of_slot, group: g, entries: &entries };
            self.work.reset_from(&source, time).map_err(|error| PoolError::Rebuild { cluster: id, error })?;
            push_core(next, id, &self.work)?;
        }
        Ok(())
    }

    /// Whether an empty scan of a cluster with no track in view cannot fail (the host's rule): a
    /// prediction failure drops the track and the child budget holds H no-event children.
    fn quiet_steps_cannot_fail(&self) -> bool {
        let quiet = self.work.config();
        let budget = match quiet.children {
            ChildGeneration::Exhaustive { max_children_per_scan } => max_children_per_scan >= H as u64,
            ChildGeneration::Sampled(_) => true,
        };
        budget && quiet.numerical_failure == NumericalFailure::DropTrack
    }
}

/// Loads into `core` the merge of the `members`' states (clusters at `time`): their product, each factor
/// pruned to the best H with ties in product order, then the lightest hypotheses dropped while their tracks
/// exceed K (docs/maths.md §13.3). Returns the mass pruned.
fn merge<
    T,
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
    core: &mut Tracker<T, M, G, S, D, H, N, Z, K, B>,
    clusters: &[ClusterRest<T, S, N, H, K>],
    members: &[u16],
    id: u64,
    time: f64,
) -> Result<T, PoolError>
where
    T: Real,
    M: MotionModel<T, S>,
    G: MeasurementModel<T, S, D>,
{
    if members.len() > N {
        return Err(PoolError::MergeTooLarge { cluster: id, objects: members.len(), capacity: N });
    }
    let mut set = heapless::Vec::<(T, [u16; N]), H>::new();
    let _ = set.push((T::one(), [0; N]));
    for (k, &member) in members.iter().enumerate() {
        let Some(rest) = clusters.get(usize::from(member)) else { continue };
        let mut product = heapless::Vec::<(T, [u16; N]), H>::new();
        for (weight, choice) in &set {
            for j in 0..rest.hypotheses().len() {
                let w = *weight * rest.weight(j);
                let at = product.iter().position(|e| e.0 < w).unwrap_or(product.len());
                if at >= H {
                    continue;
                }
                if product.is_full() {
                    product.pop();
                }
                let mut choice = *choice;
                if let Some(c) = choice.get_mut(k) {
                    *c = j as u16;
                }
                let _ = product.insert(at.min(product.len()), (w, choice));
            }
        }
        set = product;
    }
    while set.len() > 1 && distinct_tracks(clusters, members, &set) > K {
        set.pop();
    }
    let product = Product { clusters, members, entries: &set };
    if let Some(objects) = (0..set.len()).map(|h| product.count(h)).find(|&n| n > N) {
        return Err(PoolError::MergeTooLarge { cluster: id, objects, capacity: N });
    }
    let kept = set.iter().fold(T::zero(), |sum, e| sum + e.0);
    core.reset_from(&product, time).map_err(|error| PoolError::Rebuild { cluster: id, error })?;
    Ok((T::one() - kept).max(T::zero()))
}

/// Distinct tracks (label and Gaussian) among the objects of a merge's entries, counted up to K + 1.
fn distinct_tracks<T: Real, const S: usize, const N: usize, const H: usize, const K: usize>(
    clusters: &[ClusterRest<T, S, N, H, K>],
    members: &[u16],
    set: &[(T, [u16; N])],
) -> usize {
    let mut seen = heapless::Vec::<(u16, u16), K>::new();
    let member = |k: usize| members.get(k).and_then(|&m| clusters.get(usize::from(m)));
    let track = |(k, slot): (u16, u16)| member(usize::from(k)).and_then(|rest| rest.track(slot));
    for (_, choice) in set {
        for (k, h) in choice.iter().enumerate().take(members.len()) {
            let Some(rest) = member(k) else { continue };
            for &slot in rest.slots(usize::from(*h)) {
                let this = track((k as u16, slot));
                let same = |&s: &(u16, u16)| {
                    let other = track(s);
                    other.map(|t| (t.label, &t.state)) == this.map(|t| (t.label, &t.state))
                };
                if !seen.iter().any(same) && seen.push((k as u16, slot)).is_err() {
                    return K + 1;
                }
            }
        }
    }
    seen.len()
}

/// Appends a copy of `rest` to the next scan's clusters unless it holds no track (an emptied cluster is
/// dropped), in place.
fn push_copy<T: Real, const S: usize, const N: usize, const H: usize, const K: usize, const P: usize>(
    next: &mut heapless::Vec<ClusterRest<T, S, N, H, K>, P>,
    rest: &ClusterRest<T, S, N, H, K>,
) -> Result<(), PoolError> {
    if rest.tracks().is_empty() {
        return Ok(());
    }
    next.push(ClusterRest::EMPTY).map_err(|_| PoolError::PoolFull { capacity: P })?;
    if let Some(slot) = next.last_mut() {
        slot.copy_from(rest);
    }
    Ok(())
}

/// Appends cluster `id` as `core` holds it to the next scan's clusters unless it holds no track, in place.
fn push_core<
    T,
    M,
    G,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
    const P: usize,
>(
    next: &mut heapless::Vec<ClusterRest<T, S, N, H, K>, P>,
    id: u64,
    core: &Tracker<T, M, G, S, D, H, N, Z, K, B>,
) -> Result<(), PoolError>
where
    T: Real,
    M: MotionModel<T, S>,
    G: MeasurementModel<T, S, D>,
{
    if core.tracks().is_empty() {
        return Ok(());
    }
    next.push(ClusterRest::EMPTY).map_err(|_| PoolError::PoolFull { capacity: P })?;
    match next.last_mut() {
        Some(slot) => slot.store(id, core),
        None => Ok(()),
    }
}

fn check_capacity(cluster: u64, received: usize, capacity: usize) -> Result<(), PoolError> {
    if received > capacity {
        return Err(PoolError::TooManyMeasurements { cluster, received, capacity });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::examples;
    use crate::{ConfigError, ConstantVelocity, Gaussian, PositionMeasurement, Region, StepError, TrackLabel};
    use nalgebra::SMatrix;

    type Pool = ClusterPool<f64, ConstantVelocity<f64>, PositionMeasurement<f64>, 4, 2, 16, 4, 4, 16, 1, 4, 8>;

    fn object(label: u32, x: f64) -> PriorObject<f64, 4> {
        PriorObject {
            label: TrackLabel(label),
            state: Gaussian { mean: SVector::from([x, 0.0, 0.0, 0.0]), covariance: SMatrix::identity() },
        }
    }

    fn config() -> crate::LinearConfig<f64, 1> {
        let mut config = examples::config();
        config.sensor.field_of_view = Region::Everywhere { volume: 1e4 };
        config.gate = Some(16.0);
        config
    }

    #[test]
    fn a_refused_reset_leaves_the_pool_as_it_was() {
        let mut pool = Pool::new(config(), &[object(0, 0.0), object(1, 100.0)], 0.0, 0.0).expect("pool");
        pool.step(&ScanGeometry::single(1.0), &[SVector::from([0.3, 0.0])]).expect("step");
        let before = pool.digest();
        let flat =
            PriorObject { state: Gaussian { covariance: SMatrix::zeros(), ..object(2, 5.0).state }, ..object(2, 5.0) };
        let refused = pool.reset(&[object(0, 0.0), flat], 2.0);
        assert!(matches!(refused, Err(PoolError::Rebuild { cluster: 1, .. })), "{refused:?}");
        let twice = pool.reset(&[object(3, 0.0), object(3, 1.0)], 2.0);
        assert_eq!(twice, Err(PoolError::Config(ConfigError::PriorDuplicateLabel { hypothesis: 0 })));
        let bad = crate::LinearConfig { death_probability: 2.0, ..config() };
        assert_eq!(
            pool.reset_with(bad, &[object(0, 0.0)], 2.0, 0.0),
            Err(PoolError::Config(ConfigError::DeathProbability))
        );
        assert_eq!(pool.digest(), before);
        pool.step(&ScanGeometry::single(2.0), &[]).expect("it goes on");
        // A reset is a fresh pool.
        pool.reset(&[object(0, 0.0)], 5.0).expect("reset");
        let mut fresh = Pool::new(config(), &[object(0, 0.0)], 5.0, 0.0).expect("pool");
        assert_eq!(pool.digest(), fresh.digest());
    }

    #[test]
    fn an_empty_pool_refuses_scans_until_loaded() {
        let mut pool = Pool::empty(config(), config(), config());
        assert!(pool.step(&ScanGeometry::single(1.0), &[]).is_err());
        pool.reset_with(config(), &[object(0, 0.0)], 0.0, 0.0).expect("loaded");
        let report = pool.step(&ScanGeometry::single(1.0), &[SVector::from([0.1, 0.0])]).expect("step");
        assert_eq!((report.clusters, report.clusters_with_measurements), (1, 1));
        assert!(matches!(
            pool.step(&ScanGeometry::single(1.0), &[]),
            Err(PoolError::Scan(StepError::TimeNotAfterLastScan))
        ));
    }
}
