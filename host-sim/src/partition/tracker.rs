//! [`PartitionedTracker`]: any number of clusters, each a core R-FISST tracker over its own objects with
//! the exact recursion inside, and a birth cluster for the measurements in no gate (docs/maths.md §13).
//! Per scan: route (gate), merge the clusters that share a measurement, step every cluster in parallel
//! (rayon; each cluster's result depends on its own inputs only, so any thread count gives the same
//! bits), promote a birth cluster that gave birth, split clusters that factor. Nothing is committed until
//! every cluster has stepped, so a failed scan leaves the tracker unchanged.

use super::error::{ClusterId, PartitionError};
use super::hypotheses::{self, Hypothesis};
use super::route::{self, Gated, SpeedBound};
use super::split;
use nalgebra::SVector;
use rayon::prelude::*;
use tracker_core::StepError;
use tracker_core::model::{MeasurementModel, MotionModel};
use tracker_core::sensor::ScanGeometry;
use tracker_core::tracker::place_scan;
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

/// One cluster: its identity and its core tracker.
#[derive(Clone)]
pub struct Cluster<
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
    pub id: ClusterId,
    pub core: Box<Core<M, G, S, D, H, N, Z, K, B>>,
    /// Per sensor, the time until which the cluster is certainly beyond that sensor's range window and is
    /// left unstepped by its scans (docs/maths.md §13.2); empty without a view skip.
    pub clear_until: Vec<f64>,
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
> Cluster<M, G, S, D, H, N, Z, K, B>
{
    /// The cluster `id` of `core`, due at every sensor's next scan.
    pub fn new(id: ClusterId, core: Box<Core<M, G, S, D, H, N, Z, K, B>>) -> Self {
        Self { id, core, clear_until: vec![] }
    }

    /// Whether a scan of `sensor` at `time` may leave the cluster unstepped.
    fn clear_at(&self, sensor: usize, time: f64) -> bool {
        self.clear_until.get(sensor).is_some_and(|&until| time < until)
    }
}

/// What a scan does with one cluster.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Fate {
    /// Certainly out of the sensor's range window: not touched (§13.2).
    Skipped,
    /// No measurement and no track in view: stepped in place with an empty scan.
    Quiet,
    /// Stepped on a copy (alone or merged) with its measurements.
    Stepped,
}

/// What one partitioned scan did.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PartitionReport {
    /// Clusters of objects after the scan.
    pub clusters: usize,
    /// Objects (labels) of the largest cluster after the scan.
    pub largest_cluster: usize,
    /// Clusters merged away (a merge of k clusters counts k − 1).
    pub merged: usize,
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
    /// Clusters stepped in place with an empty scan: no measurement and no track in view (§13.2).
    pub quiet: usize,
    /// Clusters not stepped at all: certainly beyond the sensor's range window (§13.2, view skip).
    pub skipped: usize,
    /// Clusters stepped with at least one measurement.
    pub clusters_with_measurements: usize,
    /// Σ over clusters of the core's hypotheses after the scan.
    pub hypotheses: usize,
}

/// One cluster's part of a scan: its id, the core to step (a clone, or a merge's new core) and its
/// measurements.
type Work<
    M,
    G,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
> = (ClusterId, Box<Core<M, G, S, D, H, N, Z, K, B>>, Vec<SVector<f64, D>>);

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
    /// The configuration without births: every cluster of objects'.
    quiet: Config<f64, M, G, S, B>,
    clusters: Vec<Cluster<M, G, S, D, H, N, Z, K, B>>,
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
            quiet,
            clusters: Vec::with_capacity(objects.len()),
            birth,
            next_cluster: 0,
            next_label: labels.last().map_or(0, |l| l + 1),
            time,
            epsilon: if epsilon.is_finite() { epsilon.max(0.0) } else { 0.0 },
            skip: None,
            last: None,
        };
        for object in objects {
            let set = [Hypothesis { weight: 1.0, objects: vec![*object] }];
            let id = ClusterId(tracker.next_cluster);
            tracker.next_cluster += 1;
            let core = tracker.build(id, &set)?;
            tracker.clusters.push(Cluster::new(id, core));
        }
        Ok(tracker)
    }

    /// The tracker that leaves a cluster unstepped while all its tracks are certainly beyond the scanning
    /// sensor's range window, `speed` bounding how fast each track's object closes in on a ground sensor
    /// (docs/maths.md §13.2): the cost of a scan then follows the objects near the sensor, not the
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

    /// A core of the configuration without births holding `set`, at the tracker's time.
    fn build(
        &self,
        id: ClusterId,
        set: &[Hypothesis<S>],
    ) -> Result<Box<Core<M, G, S, D, H, N, Z, K, B>>, PartitionError> {
        let mut core = Box::new(Core::empty(self.quiet.clone()));
        core.reset(&hypotheses::as_prior(set), self.time)
            .map_err(|error| PartitionError::Rebuild { cluster: id, error })?;
        Ok(core)
    }

    /// The clusters of objects, in id order.
    pub fn clusters(&self) -> &[Cluster<M, G, S, D, H, N, Z, K, B>] {
        &self.clusters
    }

    /// The time of the last scan (or of the prior).
    pub fn time(&self) -> f64 {
        self.time
    }

    /// A digest of the whole state: the time, each cluster's id and core digest, the birth cluster's.
    pub fn digest(&self) -> u64 {
        let mut words = vec![self.time.to_bits(), self.next_cluster, u64::from(self.next_label), self.birth.digest()];
        words.extend(self.clusters.iter().flat_map(|c| [c.id.0, c.core.digest()]));
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
        let skip = if quiet_allowed && geometry.observer.is_none() { self.skip } else { None };
        let due: Vec<bool> =
            self.clusters.iter().map(|c| skip.is_none() || !c.clear_at(geometry.sensor, geometry.time)).collect();
        let mut caught = self.catch_up(&due, geometry.time)?;
        let motion = &self.config.motion;
        let gated: Vec<Gated> = (self.clusters.par_iter().zip(&due).zip(&caught))
            .map(|((c, &due), caught)| {
                let core = caught.as_deref().unwrap_or(&c.core);
                let dt = geometry.time - core.time();
                if due { route::gate(motion, &placed, core.tracks(), dt, measurements, skip) } else { Gated::default() }
            })
            .collect();
        let routing = route::route(&gated, measurements.len());
        let mut report = PartitionReport { unclaimed: routing.unclaimed.len(), ..Default::default() };
        // Skipped clusters are left alone; quiet ones (no measurement, no track in view) are stepped in place
        // at the end (§13.2); the work of the scan is each other group's core (a copy, or a merge's new core)
        // and its measurements.
        let mut fate = vec![Fate::Stepped; self.clusters.len()];
        let mut work: Vec<Work<M, G, S, D, H, N, Z, K, B>> = vec![];
        for (group, rows) in routing.groups.iter().zip(&routing.measurements) {
            let id = self.clusters[group[0]].id;
            check_capacity(id, rows.len(), Z)?;
            if quiet_allowed && group.len() == 1 && rows.is_empty() && !gated[group[0]].in_view {
                fate[group[0]] = if due[group[0]] { Fate::Quiet } else { Fate::Skipped };
                continue;
            }
            let core = if group.len() == 1 {
                caught[group[0]].take().unwrap_or_else(|| self.clusters[group[0]].core.clone())
            } else {
                let mut cores = vec![];
                for &i in group {
                    cores.push(match caught[i].take() {
                        Some(core) => core,
                        None => self.caught_up(&self.clusters[i])?.unwrap_or_else(|| self.clusters[i].core.clone()),
                    });
                }
                let (core, pruned) = self.merge(id, &cores)?;
                report.merged += group.len() - 1;
                report.merge_pruned_mass += pruned;
                core
            };
            work.push((id, core, rows.iter().map(|&m| measurements[m]).collect()));
        }
        check_capacity(ClusterId::BIRTH, routing.unclaimed.len(), Z)?;
        work.push((ClusterId::BIRTH, self.birth.clone(), routing.unclaimed.iter().map(|&m| measurements[m]).collect()));
        let results: Vec<Result<StepReport<f64>, StepError>> =
            work.par_iter_mut().map(|(_, core, zs)| core.step_scan(geometry, zs)).collect();
        for ((id, _, _), result) in work.iter().zip(&results) {
            let step = result.map_err(|error| PartitionError::Cluster { cluster: *id, error })?;
            report.step_pruned_mass += (1.0 - step.captured_mass).max(0.0);
        }
        report.clusters_with_measurements = work.iter().filter(|w| !w.2.is_empty()).count();
        let birth = work.pop().expect("the birth cluster's work").1;
        let stepped: Vec<_> = work.into_iter().map(|(id, core, _)| Cluster::new(id, core)).collect();
        let (stepped, counters) = self.rebuild(geometry.time, stepped, &birth, &mut report)?;
        let birth = if birth.tracks().is_empty() { birth } else { self.empty_birth(geometry.time)? };
        // Nothing below can fail (quiet_steps_cannot_fail), so the tracker changes only from here on.
        let clear = Clearance { sensor: geometry.sensor, time: geometry.time, cap: self.config.motion.max_time_step() };
        self.step_quiet(geometry, &fate, &mut caught, &gated, clear)?;
        report.quiet = fate.iter().filter(|f| **f == Fate::Quiet).count();
        report.skipped = fate.iter().filter(|f| **f == Fate::Skipped).count();
        let mut clusters: Vec<_> = std::mem::take(&mut self.clusters)
            .into_iter()
            .zip(&fate)
            .filter(|(_, f)| **f != Fate::Stepped)
            .map(|(c, _)| c)
            .collect();
        clusters.extend(stepped);
        clusters.retain(|c| !c.core.tracks().is_empty());
        clusters.sort_by_key(|c| c.id);
        report.clusters = clusters.len();
        report.largest_cluster = clusters.iter().map(|c| labels(&c.core).len()).max().unwrap_or(0);
        report.hypotheses = clusters.iter().map(|c| c.core.hypotheses().len()).sum();
        self.clusters = clusters;
        self.birth = birth;
        self.last = Some(*geometry);
        (self.next_cluster, self.next_label, self.time) = (counters.next_cluster, counters.next_label, counters.time);
        Ok(report)
    }

    /// Copies of the `due` clusters left behind by more than the motion model's longest prediction by a
    /// scan at `time`, caught up ([`Self::caught_up`]); `None` for the others, which are gated and stepped
    /// from their own time.
    #[allow(clippy::type_complexity)]
    fn catch_up(
        &self,
        due: &[bool],
        time: f64,
    ) -> Result<Vec<Option<Box<Core<M, G, S, D, H, N, Z, K, B>>>>, PartitionError> {
        let limit = self.config.motion.max_time_step().unwrap_or(f64::INFINITY);
        self.clusters
            .par_iter()
            .zip(due)
            .map(|(c, &due)| if due && time - c.core.time() > limit { self.caught_up(c) } else { Ok(None) })
            .collect()
    }

    /// A copy of cluster `c`, when the view skip left it out of the last scan, stepped to that scan with an
    /// empty scan as it would have been had it not been skipped (it was certainly out of that sensor's range
    /// window, so the step only predicts it); `None` when it is at the tracker's time.
    #[allow(clippy::type_complexity)]
    fn caught_up(
        &self,
        c: &Cluster<M, G, S, D, H, N, Z, K, B>,
    ) -> Result<Option<Box<Core<M, G, S, D, H, N, Z, K, B>>>, PartitionError> {
        let Some(last) = self.last.filter(|_| c.core.time() < self.time) else { return Ok(None) };
        let mut core = c.core.clone();
        core.step_scan(&last, &[]).map_err(|error| PartitionError::Cluster { cluster: c.id, error })?;
        Ok(Some(core))
    }

    /// Steps the quiet clusters in place (their caught-up copies where there are), and gives each the time
    /// until which this scan's sensor cannot see it.
    #[allow(clippy::type_complexity)]
    fn step_quiet(
        &mut self,
        geometry: &ScanGeometry<f64>,
        fate: &[Fate],
        caught: &mut [Option<Box<Core<M, G, S, D, H, N, Z, K, B>>>],
        gated: &[Gated],
        clear: Clearance,
    ) -> Result<(), PartitionError> {
        let results: Vec<Result<StepReport<f64>, StepError>> = self
            .clusters
            .par_iter_mut()
            .zip(caught)
            .zip(fate.par_iter().zip(gated))
            .filter(|(_, (f, _))| **f == Fate::Quiet)
            .map(|((c, caught), (_, gated))| {
                if let Some(core) = caught.take() {
                    c.core = core;
                }
                clear.record(&mut c.clear_until, gated.clear_for);
                c.core.step_scan(geometry, &[])
            })
            .collect();
        // Not reachable (see quiet_steps_cannot_fail); were it, the error is returned, and the quiet clusters
        // stepped before it would have moved on (docs/maths.md §13.6).
        let quiet_ids = self.clusters.iter().zip(fate).filter(|(_, f)| **f == Fate::Quiet).map(|(c, _)| c.id);
        if let Some((id, Err(error))) = quiet_ids.zip(results).find(|(_, r)| r.is_err()) {
            return Err(PartitionError::Cluster { cluster: id, error });
        }
        Ok(())
    }

    /// Whether an empty scan of a cluster with no track in view cannot fail: a prediction failure drops the
    /// track (`NumericalFailure::DropTrack`), each parent has its one no-event child (no measurement, no
    /// birth, no death out of view) and the child budget holds H of them.
    fn quiet_steps_cannot_fail(&self) -> bool {
        let budget = match self.quiet.children {
            tracker_core::config::ChildGeneration::Exhaustive { max_children_per_scan } => {
                max_children_per_scan >= H as u64
            }
            tracker_core::config::ChildGeneration::Sampled(_) => true,
        };
        budget && self.quiet.numerical_failure == tracker_core::NumericalFailure::DropTrack
    }

    /// A fresh birth cluster at `time` (the configuration with births, one empty hypothesis).
    fn empty_birth(&self, time: f64) -> Result<Box<Core<M, G, S, D, H, N, Z, K, B>>, PartitionError> {
        let mut core = Box::new(Core::empty(self.config.clone()));
        let empty = [PriorHypothesis { weight: 1.0, objects: &[] }];
        core.reset(&empty, time).map_err(|error| PartitionError::Rebuild { cluster: ClusterId::BIRTH, error })?;
        Ok(core)
    }

    /// The merge of the cores of `group` (clusters at the tracker's time): their product, pruned to H after it, as a new core
    /// with the id `id`; and the mass pruned.
    fn merge(
        &self,
        id: ClusterId,
        group: &[Box<Core<M, G, S, D, H, N, Z, K, B>>],
    ) -> Result<(Box<Core<M, G, S, D, H, N, Z, K, B>>, f64), PartitionError> {
        let mut set = vec![Hypothesis { weight: 1.0, objects: vec![] }];
        for core in group {
            set = hypotheses::product(&set, &hypotheses::read(core), H);
        }
        // Keep the heaviest hypotheses whose tracks fit the store K.
        while set.len() > 1 && hypotheses::distinct_tracks(&set) > K {
            set.pop();
        }
        if let Some(large) = set.iter().map(|h| h.objects.len()).find(|&n| n > N) {
            return Err(PartitionError::MergeTooLarge { cluster: id, objects: large, capacity: N });
        }
        let kept: f64 = set.iter().map(|h| h.weight).sum();
        Ok((self.build(id, &set)?, (1.0 - kept).max(0.0)))
    }
}

fn check_capacity(cluster: ClusterId, received: usize, capacity: usize) -> Result<(), PartitionError> {
    if received > capacity {
        return Err(PartitionError::TooManyMeasurements { cluster, received, capacity });
    }
    Ok(())
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
    /// The clusters a scan stepped, rebuilt: a birth cluster holding tracks becomes a cluster of objects
    /// (fresh labels); clusters that factor are split (§13.4); and the counters after the scan. Nothing of
    /// the tracker changes here, so a failed rebuild leaves it as it was.
    #[allow(clippy::type_complexity)]
    fn rebuild(
        &self,
        time: f64,
        stepped: Vec<Cluster<M, G, S, D, H, N, Z, K, B>>,
        birth: &Core<M, G, S, D, H, N, Z, K, B>,
        report: &mut PartitionReport,
    ) -> Result<(Vec<Cluster<M, G, S, D, H, N, Z, K, B>>, Counters), PartitionError> {
        let mut next = self.clone_counters();
        next.time = time;
        let mut clusters = stepped;
        if !birth.tracks().is_empty() {
            let set = next.relabel(hypotheses::read(birth));
            let id = next.fresh_cluster();
            clusters.push(Cluster::new(id, self.build_at(id, &set, time)?));
            report.born_clusters += 1;
        }
        let factors: Vec<Option<split::Factors<S>>> =
            clusters.par_iter().map(|c| split::factor(&c.core, self.epsilon)).collect();
        let mut out = Vec::with_capacity(clusters.len());
        for (cluster, factors) in clusters.into_iter().zip(factors) {
            match factors {
                None => out.push(cluster),
                Some(f) => {
                    report.split += f.groups.len() - 1;
                    report.split_moved_mass += f.moved;
                    for (k, set) in f.groups.iter().enumerate() {
                        let id = if k == 0 { cluster.id } else { next.fresh_cluster() };
                        out.push(Cluster::new(id, self.build_at(id, set, time)?));
                    }
                }
            }
        }
        Ok((out, next))
    }

    fn clone_counters(&self) -> Counters {
        Counters { next_cluster: self.next_cluster, next_label: self.next_label, time: self.time }
    }

    /// As [`Self::build`] at `time`.
    fn build_at(
        &self,
        id: ClusterId,
        set: &[Hypothesis<S>],
        time: f64,
    ) -> Result<Box<Core<M, G, S, D, H, N, Z, K, B>>, PartitionError> {
        let mut core = Box::new(Core::empty(self.quiet.clone()));
        core.reset(&hypotheses::as_prior(set), time).map_err(|error| PartitionError::Rebuild { cluster: id, error })?;
        Ok(core)
    }
}

/// How long a quiet cluster is left out of its sensor's scans (§13.2).
#[derive(Debug, Clone, Copy)]
struct Clearance {
    sensor: usize,
    time: f64,
    /// The motion model's longest prediction: a skipped cluster is caught up over at most this.
    cap: Option<f64>,
}

impl Clearance {
    /// Sets the sensor's entry of `until` to the scan's time plus `clear_for` (at most the cap), or clears it.
    fn record(&self, until: &mut Vec<f64>, clear_for: Option<f64>) {
        let Some(clear_for) = clear_for else {
            if let Some(entry) = until.get_mut(self.sensor) {
                *entry = f64::NEG_INFINITY;
            }
            return;
        };
        if until.len() <= self.sensor {
            until.resize(self.sensor + 1, f64::NEG_INFINITY);
        }
        until[self.sensor] = self.time + clear_for.min(self.cap.unwrap_or(f64::INFINITY));
    }
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

/// The distinct labels of `core`'s tracks, in order.
pub fn labels<
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
    core: &Core<M, G, S, D, H, N, Z, K, B>,
) -> Vec<u32>
where
    M: MotionModel<f64, S>,
    G: MeasurementModel<f64, S, D>,
{
    let mut labels: Vec<u32> = core.tracks().iter().map(|t| t.label.0).collect();
    labels.sort_unstable();
    labels.dedup();
    labels
}
