//! [`PartitionedTracker`]: any number of clusters, each a core R-FISST tracker over its own objects with
//! the exact recursion inside, and a birth cluster for the measurements in no gate (docs/maths.md §13).
//! Per scan: route (gate), merge the clusters that share a measurement, step every cluster in parallel
//! (rayon; each cluster's result depends on its own inputs only, so any thread count gives the same
//! bits), promote a birth cluster that gave birth, split clusters that factor. Nothing is committed until
//! every cluster has stepped, so a failed scan leaves the tracker unchanged.
//!
//! Between scans a cluster is held at rest ([`Rest`]: what its core carries from one scan to the next);
//! each step loads it into a core leased from the tracker's pool ([`Cores`]), steps it and stores it back,
//! so memory is the objects' rests plus one core per concurrent task (docs/maths.md §13.2), and the bits
//! are those of a core held per cluster.

use super::cluster::{Clearance, Cluster, Coast, Fate, Rest};
use super::cores::{self, Cores};
use super::error::{ClusterId, PartitionError};
use super::hypotheses::{self, Hypothesis};
use super::route::{self, Gated, Skip};
use super::split;
use super::view::{self, SpeedBound};
use super::window::Indexed;
use nalgebra::SVector;
use rayon::prelude::*;
use tracker_core::model::{MeasurementModel, MotionModel};
use tracker_core::sensor::ScanGeometry;
use tracker_core::tracker::{PlacedScan, place_scan};
use tracker_core::{BirthModel, Config, PriorHypothesis, PriorObject, StepReport, TrackLabel, Tracker};

type Core<
    M,
    G,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
> = Tracker<f64, M, G, S, D, H, N, Z, K, B>;

/// What one partitioned scan did.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PartitionReport {
    /// Clusters of objects after the scan.
    pub clusters: usize,
    /// Objects (labels) of the largest cluster after the scan.
    pub largest_cluster: usize,
    /// Clusters merged away (a merge of k clusters counts k − 1).
    pub merged: usize,
    /// Measurements shared by two groups that were not merged because the product could hold more than N
    /// objects: each stays with the group that gated it first (§13.3).
    pub merges_declined: usize,
    /// Mass pruned by merges (1 − the kept part of the product, summed over merges).
    pub merge_pruned_mass: f64,
    /// Mass pruned by the cores' own selection of H children (Σ over clusters of 1 − captured mass).
    pub step_pruned_mass: f64,
    /// New clusters made by splits.
    pub split: usize,
    /// Total variation moved by ε-splits (0 when every split was exact).
    pub split_moved_mass: f64,
    /// Clusters born from the birth cluster.
    pub born_clusters: usize,
    /// Measurements routed to the birth cluster.
    pub unclaimed: usize,
    /// Tracklets the birth cluster's pool formed from them (docs/maths.md §5.10).
    pub tracklets_formed: usize,
    /// Tracks the clusters' cores declared lost and dropped (`lost_after_unseen_scans`, docs/maths.md §5.9).
    pub lost_tracks: usize,
    /// Clusters with no measurement and no track in view, stepped last with an empty scan, or with a view
    /// skip given their tracks' predictions (§13.2).
    pub quiet: usize,
    /// Quiet clusters given their tracks' predictions instead of a step in a core (view skip, §13.2).
    pub predicted: usize,
    /// Quiet clusters coasting: gated from their tracks' means alone, every track cleared from the scanning
    /// sensor, their state left at its own time (view skip, §13.2).
    pub coasted: usize,
    /// Clusters not stepped at all: certainly out of the sensor's field of view (§13.2, view skip).
    pub skipped: usize,
    /// Clusters stepped with at least one measurement.
    pub clusters_with_measurements: usize,
    /// Σ over clusters of the core's hypotheses after the scan.
    pub hypotheses: usize,
}

/// One cluster's part of a scan: its id, its state to step (its own, caught up, or a merge's) and its
/// measurements.
type Work<const S: usize, const N: usize, const D: usize> = (ClusterId, Rest<S, N>, Vec<SVector<f64, D>>);

/// What stepping one cluster's work gave: the core's report, the state after the step and the cluster's
/// factorisation (§13.4), read while the core held it.
type Stepped<const S: usize, const N: usize> = (StepReport<f64>, Rest<S, N>, Option<split::Factors<S>>);

/// The partitioned tracker of the scans of one sensor network.
#[derive(Clone)]
pub struct PartitionedTracker<
    M,
    G,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
> {
    /// The configuration with births: the birth cluster's.
    config: Config<f64, M, G, S, B>,
    /// The reused cores of the configuration without births: every cluster of objects' (a clone starts an
    /// empty pool).
    cores: Cores<M, G, S, D, H, N, Z, K, B>,
    clusters: Vec<Cluster<S, N>>,
    birth: Box<Core<M, G, S, D, H, N, Z, K, B>>,
    next_cluster: u64,
    next_label: u32,
    time: f64,
    epsilon: f64,
    /// With a view skip, the bound on how fast an object closes in on a sensor (§13.2).
    skip: Option<SpeedBound<S>>,
    /// The last scan's geometry (`None` before the first).
    last: Option<ScanGeometry<f64>>,
}

impl<
    M,
    G,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
> PartitionedTracker<M, G, S, D, H, N, Z, K, B>
where
    M: MotionModel<f64, S> + Clone + Send + Sync,
    G: MeasurementModel<f64, S, D> + Clone + Send + Sync,
{
    /// A tracker of `objects` (each certain, each its own cluster, in the given order) at `time`; splits
    /// approximate within total variation `epsilon` (0: exact splits only).
    ///
    /// # Errors
    /// [`PartitionError::Config`] when the core refuses the configuration or an object; a duplicate label.
    pub fn new(
        config: Config<f64, M, G, S, B>,
        objects: &[PriorObject<f64, S>],
        time: f64,
        epsilon: f64,
    ) -> Result<Self, PartitionError> {
        let quiet = Config { birth: BirthModel::none(), ..config.clone() };
        let empty = [PriorHypothesis { weight: 1.0, objects: &[] }];
        let birth = Box::new(Core::new(config.clone(), &empty, time).map_err(PartitionError::Config)?);
        let mut labels: Vec<u32> = objects.iter().map(|o| o.label.0).collect();
        labels.sort_unstable();
        if labels.windows(2).any(|w| w[0] == w[1]) {
            return Err(PartitionError::Config(tracker_core::ConfigError::PriorDuplicateLabel { hypothesis: 0 }));
        }
        let mut tracker = Self {
            config,
            cores: Cores::new(quiet),
            clusters: Vec::with_capacity(objects.len()),
            birth,
            next_cluster: 0,
            next_label: labels.last().map_or(0, |l| l + 1),
            time,
            epsilon: if epsilon.is_finite() { epsilon.max(0.0) } else { 0.0 },
            skip: None,
            last: None,
        };
        let mut core = tracker.cores.lease();
        for object in objects {
            let set = [Hypothesis { weight: 1.0, objects: vec![*object] }];
            let id = ClusterId(tracker.next_cluster);
            tracker.next_cluster += 1;
            let rest = cores::build(&mut core, id, &set, time)?;
            tracker.clusters.push(Cluster::new(id, rest));
        }
        drop(core);
        Ok(tracker)
    }

    /// The tracker that leaves a cluster unstepped while all its tracks are certainly out of the scanning
    /// sensor's field of view, `speed` bounding how fast each track's object closes in on a ground sensor
    /// (docs/maths.md §13.2), and that gives a cluster with no track in view its tracks' predictions instead
    /// of an empty scan in a core: the cost of a scan then follows the objects near the sensor, not the
    /// catalogue. Not bit-identical to stepping every cluster at every scan: a skipped cluster is predicted
    /// over the longer interval when it is next due. Scans from a spacecraft observer skip nothing.
    pub fn with_view_skip(mut self, speed: SpeedBound<S>) -> Self {
        self.skip = Some(speed);
        self
    }

    /// The motion model of every cluster.
    pub fn motion(&self) -> &M {
        &self.config.motion
    }

    /// The clusters of objects, in id order.
    pub fn clusters(&self) -> &[Cluster<S, N>] {
        &self.clusters
    }

    /// Calls `f` with each cluster (in id order) and a core holding it, loaded from its rest into one
    /// leased core: the readers of a core (marginals, associations, views) read a cluster through it.
    ///
    /// # Errors
    /// [`PartitionError::Rebuild`] when a rest does not load (not for a rest the tracker made).
    pub fn for_each_core(
        &self,
        mut f: impl FnMut(&Cluster<S, N>, &Core<M, G, S, D, H, N, Z, K, B>),
    ) -> Result<(), PartitionError> {
        let mut core = self.cores.lease();
        for cluster in &self.clusters {
            cores::load(&mut core, cluster.id, &cluster.rest)?;
            f(cluster, &core);
        }
        Ok(())
    }

    /// How many cores the pool holds (every one of them free between scans): at most one per task that ran
    /// at once, whatever the number of clusters.
    pub fn pooled_cores(&self) -> usize {
        self.cores.made()
    }

    /// The time of the last scan (or of the prior).
    pub fn time(&self) -> f64 {
        self.time
    }

    /// A digest of the whole state: the time, each cluster's id and core digest (its rest loaded into a
    /// core), the birth cluster's. A rest that does not load (not one the tracker made) digests as 0.
    pub fn digest(&self) -> u64 {
        let mut words = vec![self.time.to_bits(), self.next_cluster, u64::from(self.next_label), self.birth.digest()];
        let mut core = self.cores.lease();
        for c in &self.clusters {
            let digest = cores::load(&mut core, c.id, &c.rest).map_or(0, |()| core.digest());
            words.extend([c.id.0, digest]);
        }
        // FNV-1a over the words' bytes.
        words
            .iter()
            .flat_map(|w| w.to_le_bytes())
            .fold(0xcbf2_9ce4_8422_2325u64, |h, b| (h ^ u64::from(b)).wrapping_mul(0x100_0000_01b3))
    }

    /// Processes one scan of the sensor `geometry` names.
    ///
    /// # Errors
    /// [`PartitionError`]; the tracker is then exactly as it was.
    pub fn step(
        &mut self,
        geometry: &ScanGeometry<f64>,
        measurements: &[SVector<f64, D>],
    ) -> Result<PartitionReport, PartitionError> {
        let placed =
            place_scan(&self.config, geometry, self.time, measurements, usize::MAX).map_err(PartitionError::Scan)?;
        let quiet_allowed = self.quiet_steps_cannot_fail();
        let speed = if quiet_allowed && geometry.observer.is_none() { self.skip } else { None };
        let sights = speed.map(|_| view::sights(&self.config, geometry.time)).unwrap_or_default();
        let skip = speed.map(|speed| Skip { sights: &sights, speed, scanning: geometry.sensor });
        let due: Vec<bool> =
            self.clusters.iter().map(|c| skip.is_none() || !c.clear_at(geometry.sensor, geometry.time)).collect();
        let scan = Indexed::new(measurements, route::distance::<G, S, D>(&placed.model));
        let (mut gated, mut caught) = self.gate_all(&placed, geometry.time, &due, &scan, skip)?;
        let objects: Vec<usize> = self.clusters.iter().map(|c| c.rest.max_objects()).collect();
        let routing = route::route(&gated, measurements.len(), &objects, N);
        let mut report = PartitionReport {
            unclaimed: routing.unclaimed.len(),
            merges_declined: routing.declined,
            ..Default::default()
        };
        // Skipped clusters are left alone; quiet ones (no measurement, no track in view) are stepped at the
        // end (§13.2); the work of the scan is each other group's state (its own, caught up, or a merge's)
        // and its measurements.
        let mut fate = vec![Fate::Stepped; self.clusters.len()];
        let mut work: Vec<Work<S, N, D>> = vec![];
        for (group, rows) in routing.groups().zip(&routing.measurements) {
            let id = self.clusters[group[0]].id;
            check_capacity(id, rows.len(), Z)?;
            if quiet_allowed && group.len() == 1 && rows.is_empty() && !gated[group[0]].in_view {
                fate[group[0]] = if due[group[0]] { Fate::Quiet } else { Fate::Skipped };
                continue;
            }
            let rest = self.group_rest(id, group, &mut caught, &mut report)?;
            work.push((id, rest, rows.iter().map(|&m| measurements[m]).collect()));
        }
        check_capacity(ClusterId::BIRTH, routing.unclaimed.len(), Z)?;
        let unclaimed: Vec<_> = routing.unclaimed.iter().map(|&m| measurements[m]).collect();
        let (stepped, birth) = self.step_work(geometry, &work, &unclaimed, &mut report)?;
        let (stepped, counters) = self.rebuild(geometry.time, stepped, &birth, &mut report)?;
        let birth = if birth.tracks().is_empty() { birth } else { self.empty_birth(geometry.time)? };
        // Nothing below can fail (quiet_steps_cannot_fail), so the tracker changes only from here on.
        let clear = Clearance { time: geometry.time, cap: self.config.motion.max_time_step() };
        (report.predicted, report.coasted) = self.step_quiet(geometry, &fate, &mut caught, &mut gated, clear)?;
        report.quiet = fate.iter().filter(|f| **f == Fate::Quiet).count();
        report.skipped = fate.iter().filter(|f| **f == Fate::Skipped).count();
        let mut clusters: Vec<_> = std::mem::take(&mut self.clusters)
            .into_iter()
            .zip(&fate)
            .filter(|(_, f)| **f != Fate::Stepped)
            .map(|(c, _)| c)
            .collect();
        clusters.extend(stepped);
        clusters.retain(|c| !c.rest.tracks().is_empty());
        clusters.sort_by_key(|c| c.id);
        report.clusters = clusters.len();
        report.largest_cluster = clusters.iter().map(|c| c.rest.label_count()).max().unwrap_or(0);
        report.hypotheses = clusters.iter().map(|c| c.rest.hypothesis_count()).sum();
        self.clusters = clusters;
        self.birth = birth;
        self.last = Some(*geometry);
        (self.next_cluster, self.next_label, self.time) = (counters.next_cluster, counters.next_label, counters.time);
        Ok(report)
    }

    /// Each cluster's gates for a scan at `time` (none for a cluster not `due`), and the states of the due
    /// clusters left behind by more than the motion model's longest prediction, caught up
    /// ([`Self::caught_up`]); `None` for the others, which are gated and stepped from their own time.
    #[allow(clippy::type_complexity)]
    fn gate_all(
        &self,
        placed: &PlacedScan<f64, G>,
        time: f64,
        due: &[bool],
        scan: &Indexed<'_, D>,
        skip: Option<Skip<'_, G, S>>,
    ) -> Result<(Vec<Gated<S>>, Vec<Option<Rest<S, N>>>), PartitionError> {
        let limit = self.config.motion.max_time_step().unwrap_or(f64::INFINITY);
        let motion = &self.config.motion;
        let each: Vec<Result<(Gated<S>, Option<Rest<S, N>>), PartitionError>> = (self.clusters.par_iter().zip(due))
            .map_init(
                || self.cores.lease(),
                |core, (c, &due)| {
                    if !due {
                        return Ok((Gated::default(), None));
                    }
                    let caught = if time - c.rest.time() > limit { self.caught_up(core, c)? } else { None };
                    let rest = caught.as_ref().unwrap_or(&c.rest);
                    let dt = time - rest.time();
                    // A coast continues from its means; a caught-up rest starts afresh (§13.2).
                    let from = c.coast.as_ref().filter(|_| caught.is_none()).map(|k| (&k.means[..], time - k.time));
                    // A coast ends once the state is MAX_COAST_AGE_S old: its next full prediction stays short.
                    let coasting = skip.filter(|_| dt <= route::MAX_COAST_AGE_S);
                    let coasted = coasting.and_then(|skip| route::coast(motion, rest.tracks(), dt, from, &skip));
                    let gated = coasted.unwrap_or_else(|| {
                        route::gate(motion, placed, rest.tracks(), dt, scan, self.config.gate, skip)
                    });
                    Ok((gated, caught))
                },
            )
            .collect();
        // The first error in cluster order, whatever the thread count; one pass over the clusters.
        let (mut gated, mut caught) = (Vec::with_capacity(each.len()), Vec::with_capacity(each.len()));
        for result in each {
            let (g, c) = result?;
            gated.push(g);
            caught.push(c);
        }
        Ok((gated, caught))
    }

    /// The state of cluster `c`, when the view skip left it out of the last scan, stepped (in `core`) to that
    /// scan with an empty scan as it would have been had it not been skipped (it was certainly out of that
    /// sensor's range window, so the step only predicts it); `None` when it is at the tracker's time.
    fn caught_up(
        &self,
        core: &mut Core<M, G, S, D, H, N, Z, K, B>,
        c: &Cluster<S, N>,
    ) -> Result<Option<Rest<S, N>>, PartitionError> {
        let Some(last) = self.last.filter(|_| c.rest.time() < self.time) else { return Ok(None) };
        cores::load(core, c.id, &c.rest)?;
        core.step_scan(&last, &[]).map_err(|error| PartitionError::Cluster { cluster: c.id, error })?;
        Rest::of(c.id, core).map(Some)
    }

    /// The state a group of clusters (indices, in id order) is stepped from: a lone cluster's own (or its
    /// caught-up copy), or the merge of the members' states caught up to the tracker's time.
    fn group_rest(
        &self,
        id: ClusterId,
        group: &[usize],
        caught: &mut [Option<Rest<S, N>>],
        report: &mut PartitionReport,
    ) -> Result<Rest<S, N>, PartitionError> {
        if let [only] = group {
            return Ok(caught[*only].take().unwrap_or_else(|| self.clusters[*only].rest.clone()));
        }
        let mut core = self.cores.lease();
        let mut members = vec![];
        for &i in group {
            let c = &self.clusters[i];
            members.push(match caught[i].take() {
                Some(rest) => rest,
                None => self.caught_up(&mut core, c)?.unwrap_or_else(|| c.rest.clone()),
            });
        }
        let (rest, pruned) = self.merge(&mut core, id, &members)?;
        report.merged += group.len() - 1;
        report.merge_pruned_mass += pruned;
        Ok(rest)
    }

    /// Steps each work item in a leased core and the birth cluster (a copy) with the `unclaimed`
    /// measurements, all in parallel; the step reports' pruned mass goes into `report`.
    #[allow(clippy::type_complexity)]
    fn step_work(
        &self,
        geometry: &ScanGeometry<f64>,
        work: &[Work<S, N, D>],
        unclaimed: &[SVector<f64, D>],
        report: &mut PartitionReport,
    ) -> Result<(Vec<(ClusterId, Stepped<S, N>)>, Box<Core<M, G, S, D, H, N, Z, K, B>>), PartitionError> {
        let epsilon = self.epsilon;
        let (results, (birth, birth_step)) = rayon::join(
            || {
                work.par_iter()
                    .map_init(
                        || self.cores.lease(),
                        |core, (id, rest, zs)| step_one(core, *id, rest, geometry, zs, epsilon),
                    )
                    .collect::<Vec<_>>()
            },
            || {
                let mut birth = self.birth.clone();
                let step = birth.step_scan(geometry, unclaimed);
                (birth, step)
            },
        );
        let mut stepped = Vec::with_capacity(work.len());
        for ((id, _, _), result) in work.iter().zip(results) {
            let result = result?;
            report.step_pruned_mass += (1.0 - result.0.captured_mass).max(0.0);
            report.lost_tracks += result.0.lost_tracks;
            stepped.push((*id, result));
        }
        let step = birth_step.map_err(|error| PartitionError::Cluster { cluster: ClusterId::BIRTH, error })?;
        report.step_pruned_mass += (1.0 - step.captured_mass).max(0.0);
        report.tracklets_formed = step.birth_pool.tracklets;
        report.lost_tracks += step.lost_tracks;
        report.clusters_with_measurements =
            work.iter().filter(|w| !w.2.is_empty()).count() + usize::from(!unclaimed.is_empty());
        Ok((stepped, birth))
    }

    /// Steps the quiet clusters (from their caught-up states where there are): with a view skip, lets a
    /// cluster gated from its means coast (its state kept, its means stored, §13.2), gives each other one
    /// its tracks' predictions where they all succeeded ([`Rest::advance`]), else steps it in a leased core
    /// with an empty scan; and records the times until which each sensor cannot see it. Returns how many were
    /// given their predictions and how many coast.
    fn step_quiet(
        &mut self,
        geometry: &ScanGeometry<f64>,
        fate: &[Fate],
        caught: &mut [Option<Rest<S, N>>],
        gated: &mut [Gated<S>],
        clear: Clearance,
    ) -> Result<(usize, usize), PartitionError> {
        let cores = &self.cores;
        let results: Vec<Result<Quiet, PartitionError>> = self
            .clusters
            .par_iter_mut()
            .zip(caught)
            .zip(fate.par_iter().zip(gated))
            .filter(|(_, (f, _))| **f == Fate::Quiet)
            .map_init(
                || None,
                |core, ((c, caught), (_, gated))| {
                    if let Some(rest) = caught.take() {
                        c.rest = rest;
                    }
                    clear.record(&mut c.clear_until, &gated.clear_for);
                    if let Some(means) = gated.coasted.take() {
                        c.coast = Some(Coast { time: clear.time, means: means.into() });
                        return Ok(Quiet::Coasted);
                    }
                    c.coast = None;
                    if let Some(predicted) = gated.predicted.take() {
                        c.rest.advance(clear.time, predicted);
                        return Ok(Quiet::Predicted);
                    }
                    // A core is leased only by a task that steps one.
                    let core = core.get_or_insert_with(|| cores.lease());
                    cores::load(core, c.id, &c.rest)?;
                    core.step_scan(geometry, &[]).map_err(|error| PartitionError::Cluster { cluster: c.id, error })?;
                    c.rest = Rest::of(c.id, &**core)?;
                    Ok(Quiet::Stepped)
                },
            )
            .collect();
        // Not reachable (see quiet_steps_cannot_fail); were it, the error is returned, and the quiet clusters
        // stepped before it would have moved on (docs/maths.md §13.6).
        results.into_iter().try_fold((0, 0), |(p, k), r| {
            let r = r?;
            Ok((p + usize::from(r == Quiet::Predicted), k + usize::from(r == Quiet::Coasted)))
        })
    }

    /// Whether an empty scan of a cluster with no track in view cannot fail: a prediction failure drops the
    /// track (`NumericalFailure::DropTrack`), each parent has its one no-event child (no measurement, no
    /// birth, no death out of view) and the child budget holds H of them.
    fn quiet_steps_cannot_fail(&self) -> bool {
        let quiet = self.cores.config();
        let budget = match quiet.children {
            tracker_core::config::ChildGeneration::Exhaustive { max_children_per_scan } => {
                max_children_per_scan >= H as u64
            }
            tracker_core::config::ChildGeneration::Sampled(_) => true,
        };
        budget && quiet.numerical_failure == tracker_core::NumericalFailure::DropTrack
    }

    /// A fresh birth cluster at `time` (the configuration with births, one empty hypothesis).
    fn empty_birth(&self, time: f64) -> Result<Box<Core<M, G, S, D, H, N, Z, K, B>>, PartitionError> {
        let mut core = Box::new(Core::empty(self.config.clone()));
        let empty = [PriorHypothesis { weight: 1.0, objects: &[] }];
        core.reset(&empty, time).map_err(|error| PartitionError::Rebuild { cluster: ClusterId::BIRTH, error })?;
        Ok(core)
    }

    /// The merge of the `members`' states (clusters at the tracker's time): their product, pruned to H after
    /// it, as the state of a cluster `id` (loaded through `core`); and the mass pruned.
    fn merge(
        &self,
        core: &mut Core<M, G, S, D, H, N, Z, K, B>,
        id: ClusterId,
        members: &[Rest<S, N>],
    ) -> Result<(Rest<S, N>, f64), PartitionError> {
        let mut set = vec![Hypothesis { weight: 1.0, objects: vec![] }];
        for member in members {
            set = hypotheses::product(&set, &member.read(), H);
        }
        // Keep the heaviest hypotheses whose tracks fit the store K.
        while set.len() > 1 && hypotheses::distinct_tracks(&set) > K {
            set.pop();
        }
        if let Some(large) = set.iter().map(|h| h.objects.len()).find(|&n| n > N) {
            return Err(PartitionError::MergeTooLarge { cluster: id, objects: large, capacity: N });
        }
        let kept: f64 = set.iter().map(|h| h.weight).sum();
        Ok((cores::build(core, id, &set, self.time)?, (1.0 - kept).max(0.0)))
    }

    /// The clusters a scan stepped, rebuilt: a birth cluster holding tracks becomes a cluster of objects
    /// (fresh labels); clusters that factor are split (§13.4); and the counters after the scan. Nothing of
    /// the tracker changes here, so a failed rebuild leaves it as it was.
    #[allow(clippy::type_complexity)]
    fn rebuild(
        &self,
        time: f64,
        stepped: Vec<(ClusterId, Stepped<S, N>)>,
        birth: &Core<M, G, S, D, H, N, Z, K, B>,
        report: &mut PartitionReport,
    ) -> Result<(Vec<Cluster<S, N>>, Counters), PartitionError> {
        let mut next = Counters { next_cluster: self.next_cluster, next_label: self.next_label, time };
        let mut clusters: Vec<_> =
            stepped.into_iter().map(|(id, (_, rest, factors))| (Cluster::new(id, rest), factors)).collect();
        let mut core = self.cores.lease();
        if !birth.tracks().is_empty() {
            let set = next.relabel(hypotheses::read(birth));
            let id = next.fresh_cluster();
            let rest = cores::build(&mut core, id, &set, time)?;
            clusters.push((Cluster::new(id, rest), split::factor(&*core, self.epsilon)));
            report.born_clusters += 1;
        }
        let mut out = Vec::with_capacity(clusters.len());
        for (cluster, factors) in clusters {
            match factors {
                None => out.push(cluster),
                Some(f) => {
                    report.split += f.groups.len() - 1;
                    report.split_moved_mass += f.moved;
                    for (k, set) in f.groups.iter().enumerate() {
                        let id = if k == 0 { cluster.id } else { next.fresh_cluster() };
                        out.push(Cluster::new(id, cores::build(&mut core, id, set, time)?));
                    }
                }
            }
        }
        Ok((out, next))
    }
}

/// Steps cluster `id`'s `rest` with `zs` in `core`: the report, the state after the step and the cluster's
/// factorisation within `epsilon` (§13.4).
#[allow(clippy::type_complexity)]
fn step_one<
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
    core: &mut Core<M, G, S, D, H, N, Z, K, B>,
    id: ClusterId,
    rest: &Rest<S, N>,
    geometry: &ScanGeometry<f64>,
    zs: &[SVector<f64, D>],
    epsilon: f64,
) -> Result<Stepped<S, N>, PartitionError>
where
    M: MotionModel<f64, S>,
    G: MeasurementModel<f64, S, D> + Clone,
{
    cores::load(core, id, rest)?;
    let step = core.step_scan(geometry, zs).map_err(|error| PartitionError::Cluster { cluster: id, error })?;
    Ok((step, Rest::of(id, core)?, split::factor(core, epsilon)))
}

fn check_capacity(cluster: ClusterId, received: usize, capacity: usize) -> Result<(), PartitionError> {
    if received > capacity {
        return Err(PartitionError::TooManyMeasurements { cluster, received, capacity });
    }
    Ok(())
}

/// What [`PartitionedTracker::step_quiet`] did with one quiet cluster.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Quiet {
    Coasted,
    Predicted,
    Stepped,
}

/// The counters a scan advances, committed with it.
struct Counters {
    next_cluster: u64,
    next_label: u32,
    time: f64,
}

impl Counters {
    fn fresh_cluster(&mut self) -> ClusterId {
        self.next_cluster += 1;
        ClusterId(self.next_cluster - 1)
    }

    /// `set` (the birth cluster's, labelled from 0) with fresh labels, in the order of its own labels.
    fn relabel<const S: usize>(&mut self, mut set: Vec<Hypothesis<S>>) -> Vec<Hypothesis<S>> {
        let mut own: Vec<u32> = set.iter().flat_map(|h| h.objects.iter().map(|o| o.label.0)).collect();
        own.sort_unstable();
        own.dedup();
        let first = self.next_label;
        self.next_label += own.len() as u32;
        for o in set.iter_mut().flat_map(|h| h.objects.iter_mut()) {
            o.label = TrackLabel(first + own.binary_search(&o.label.0).expect("collected above") as u32);
        }
        set
    }
}
