//! The unbounded reference tracker: the same hypothesis-level FISST recursion as tracker-core, with `Vec`
//! instead of capacities and **every** child of every parent kept.
//!
//! It works with any motion and measurement model, as the core does: each scan is checked and its sensor
//! placed by the core's [`place_scan`] (the sensor the scan names, seen from where it was), and every
//! innovation, field-of-view test ([`Region::sees`](tracker_core::Region::sees)), entry and update of the
//! scan uses the placed model and its residual (angles wrapped). It calls the core's model, EKF
//! ([`tracker_core::ekf`]) and weight code ([`WeightModel`]); only the bookkeeping is its own: a recursive enumeration of associations (independent of the core's iterative
//! enumerator, so the two check each other), hash maps for shared tracks, and merging of identical
//! hypotheses.
//!
//! **Memory budget.** Every allocation that grows with the hypotheses, the children or the measurements
//! is charged to the budget given to [`ReferenceTracker::new`] (see [`Shares`]): a fifth for the
//! posterior kept after a scan (with its snapshot and the copies `run` keeps for plots), two fifths for a
//! scan's tables and children; the rest is headroom for the allocator and the caller. Nothing is dropped
//! while everything fits. When it does not, the scan still finishes: the lowest-weight parents are left
//! out when their tables do not fit, the children are pruned to the best half whenever their buffer is
//! full (before it grows past its share), a branch of the enumeration whose best possible child cannot
//! beat the worst kept one is not entered (so the work after pruning shrinks and the kept children are
//! exactly the best ones), and children are materialised best first until the posterior's share is
//! used. The scan's report and [`ReferenceTracker::budget_scans`] then say so.

//!
//! Here the tracker, its records and its budget; a scan's tables and scores in `scan`, the enumeration of children
//! in `children`, the posterior built from them in `posterior`.

mod children;
mod posterior;
mod scan;

use crate::pipeline::snapshot::{HypothesisOut, Snapshot, TrackOut};
use nalgebra::SVector;
use std::collections::HashMap;
use std::hash::{DefaultHasher, Hash, Hasher};
use std::mem::size_of;
use tracker_core::Gaussian;
use tracker_core::ekf::{self, Innovation};
use tracker_core::pool::{BirthPool, Linking, ScanUse};
use tracker_core::real::{LogSumExp, log_add};
use tracker_core::sensor::ScanGeometry;
use tracker_core::tracker::{PlacedScan, place_scan};
use tracker_core::weight::{Event, WeightModel};
use tracker_core::{Config, MeasurementModel, MotionModel, PositionMeasurement, PriorObject, StepError, TrackLabel};

use children::{ChildBuffer, Column, Head, Search};
use posterior::events;

/// Row of a column left unassigned.
const CLUTTER: u32 = u32::MAX;
/// Slot of a track no kept parent holds.
const NO_SLOT: u32 = u32::MAX;
/// Header and rounding of one small heap allocation (glibc: 16-byte chunks, 8-byte header).
const ALLOCATION: usize = 32;
/// A hash map entry of `E` bytes: buckets at ≥ 1/8 free plus a control byte, twice over while it grows.
const fn map_entry(bytes: usize) -> usize {
    4 * (bytes + 1)
}
/// Bytes charged per hypothesis kept: its record and merge link, the hash of its tracks, its snapshot
/// record and allocation, the four thinned copies `run` keeps for its plots, and sorting scratch.
const HYPOTHESIS_BYTES: usize = size_of::<Hypothesis>()
    + 4
    + map_entry(size_of::<(u64, u32)>())
    + size_of::<HypothesisOut>()
    + ALLOCATION
    + 4 * size_of::<HypothesisOut>()
    + size_of::<Hypothesis>();
/// Bytes charged per object of a hypothesis: its index here and in the snapshot.
const OBJECT_BYTES: usize = size_of::<u32>() + size_of::<usize>();
/// Bytes charged per track of S states kept: the track, its snapshot record and its key in the sharing
/// map.
const fn track_bytes<const S: usize>() -> usize {
    size_of::<Track<S>>() + size_of::<TrackOut>() + map_entry(size_of::<(TrackKey, u32)>())
}
/// Bytes charged per child besides its rows: its head, its weight while pruning, its place in the order.
const CHILD_BYTES: usize = size_of::<Head>() + size_of::<f64>() + size_of::<u32>();

/// How a budget of B bytes is shared.
#[derive(Debug, Clone, Copy)]
struct Shares {
    /// B/5: the hypotheses and tracks kept after a scan, charged with their copies.
    posterior: usize,
    /// 2B/5: one scan's tables and children. With the posterior before and after the scan, 4B/5 at most.
    working: usize,
}

impl Shares {
    fn of(budget: usize) -> Self {
        Self { posterior: budget / 5, working: budget / 5 * 2 }
    }
}

/// Where a track comes from: (is a birth, old track index or birth cell, measurement row or [`CLUTTER`],
/// whether a birth takes its candidate's label).
type TrackKey = (bool, u32, u32, bool);

#[derive(Debug, Clone)]
struct Track<const S: usize> {
    label: u32,
    state: Gaussian<f64, S>,
    /// Consecutive scans in view with no measurement in the gate (`tracker_core::TrackLoss`).
    unseen: u16,
}

/// A hypothesis: its tracks are `objects[start..start + len]`, sorted by label.
#[derive(Debug, Clone, Copy)]
struct Hypothesis {
    log_weight: f64,
    start: usize,
    len: u32,
}

#[derive(Debug, Clone, Copy)]
struct Predicted<const S: usize, const D: usize> {
    state: Gaussian<f64, S>,
    innovation: Innovation<f64, D>,
    /// In view and not lost.
    in_view: bool,
    /// Unseen scans, this one counted.
    unseen: u16,
    /// Lost (`tracker_core::TrackLoss`): in no child, as in the core.
    lost: bool,
}

/// One scan's sensor: the measurement model placed at the scan ([`place_scan`]), and each birth cell's
/// innovation under it and whether it lies in the placed field of view.
struct Scan<G, const S: usize, const D: usize> {
    placed: PlacedScan<f64, G>,
    births: Vec<(Innovation<f64, D>, bool)>,
    /// Each birth cell's density at the scan, its α, and the pool cell it was predicted from.
    cells: Vec<(Gaussian<f64, S>, f64, Option<usize>)>,
}

/// What one reference scan did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReferenceReport {
    /// Children enumerated: every child with non-zero weight unless the budget was reached, after which
    /// branches that cannot beat the kept children are skipped uncounted.
    pub children: u64,
    /// Hypotheses after the scan.
    pub hypotheses: usize,
    /// Whether the memory budget forced dropping parents or children this scan.
    pub budget_reached: bool,
    /// Fraction of the enumerated children's weight kept: exactly 1 unless the budget was reached, then
    /// an upper bound of the fraction of all children's weight (skipped branches are not in the total).
    pub captured_mass: f64,
}

/// Why a reference scan failed; the tracker is then unchanged.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ReferenceError {
    /// The core's error for the same bad input (time, measurement, numerical failure, child budget).
    Step(StepError),
    /// 1 − M_b α − M_d β ≤ 0 for a parent with M_d objects in view: "no event" has no probability.
    EventProbabilities {
        /// Objects of the parent in view.
        in_view: usize,
    },
    /// The scan's enumeration took more association steps than its bound
    /// ([`ReferenceTracker::set_max_work`]).
    WorkBudgetExceeded {
        /// The bound.
        budget: u64,
    },
}

impl From<StepError> for ReferenceError {
    fn from(error: StepError) -> Self {
        Self::Step(error)
    }
}

impl core::fmt::Display for ReferenceError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::Step(error) => error.fmt(f),
            Self::EventProbabilities { in_view } => write!(
                f,
                "M_b alpha + M_d beta must be < 1 for every parent (M_d = {in_view} objects in view of a parent)"
            ),
            Self::WorkBudgetExceeded { budget } => write!(
                f,
                "the reference's enumeration passed its work bound of {budget} association steps in one scan \
                 (--reference-max-work)"
            ),
        }
    }
}

impl std::error::Error for ReferenceError {}

/// A track of [`ReferenceTracker::posterior`]: its label and Gaussian.
pub type LabelledState<const S: usize> = (TrackLabel, Gaussian<f64, S>);

/// The association steps one scan may take unless [`ReferenceTracker::set_max_work`] says otherwise:
/// 10¹⁰, about 45 s of one core (2.2·10⁸ steps a second, measured on one scan of 10⁶ measurements;
/// docs/robustness.md). The longest reference scans of docs/results.md take 5 s.
pub const DEFAULT_MAX_WORK: u64 = 10_000_000_000;

/// The birth cells the reference's configuration holds when none is named: as many as `run` gives it.
pub const BIRTH_CELLS: usize = 1024;

/// The unbounded exhaustive tracker for motion model `M` and measurement model `G` (S states, D
/// measurement components); `B` is only the birth-cell capacity of its configuration. The defaults are
/// the planar world of the scenario files.
pub struct ReferenceTracker<
    M,
    G = PositionMeasurement<f64>,
    const S: usize = 4,
    const D: usize = 2,
    const B: usize = BIRTH_CELLS,
> {
    /// The configuration: each scan is checked and its sensor placed from it, as in the core.
    config: Box<Config<f64, M, G, S, B>>,
    tracks: Vec<Track<S>>,
    hypotheses: Vec<Hypothesis>,
    objects: Vec<u32>,
    time: f64,
    next_label: u32,
    shares: Shares,
    max_children: u64,
    max_work: u64,
    budget_scans: Vec<usize>,
    scans: usize,
    /// Birth cells made from measurements, as the core's (docs/maths.md §5.8).
    pool: BirthPool<f64, S, B>,
}

/// One scan's predictions and association entries, for the tracks of the parents it processes.
struct Tables<G, const S: usize, const D: usize> {
    scan: Scan<G, S, D>,
    rows: usize,
    /// Parents processed (the best ones whose tables fit), in their order.
    parents: Vec<u32>,
    /// Old track → its slot below, or [`NO_SLOT`].
    slot: Vec<u32>,
    predicted: Vec<Predicted<S, D>>,
    /// `rows` entries per slot, then per birth cell.
    entries: Vec<f64>,
    /// `rows + 1` bounds per slot, then per birth cell: max(0, best entry from that row on).
    bounds: Vec<f64>,
    /// `rows` rows per slot, then per birth cell, by decreasing entry.
    order: Vec<u32>,
    /// `rows` impossible entries and `rows + 1` zero bounds: the column of a dying object.
    dead: (Vec<f64>, Vec<f64>),
    /// Columns of the widest child (objects in view plus a birth, or plus every independent-birth column).
    widest: usize,
    /// Independent births: the cells some measurement may take, a column each in every matrix
    /// (docs/maths.md §5.6).
    birth_columns: Vec<usize>,
    bytes: usize,
}

impl<G, const S: usize, const D: usize> Tables<G, S, D> {
    fn column(&self, slot: usize) -> (&[f64], &[f64], &[u32]) {
        let (r, b) = (self.rows, self.rows + 1);
        let span = slot * r..(slot + 1) * r;
        (&self.entries[span.clone()], &self.bounds[slot * b..(slot + 1) * b], &self.order[span])
    }

    fn birth_column(&self, cell: usize) -> (&[f64], &[f64], &[u32]) {
        self.column(self.predicted.len() + cell)
    }
}

impl<M, G, const S: usize, const D: usize, const B: usize> ReferenceTracker<M, G, S, D, B>
where
    M: MotionModel<f64, S>,
    G: MeasurementModel<f64, S, D> + Clone,
{
    /// A reference tracker for `config` (its capacities do not apply), the prior hypotheses and a memory
    /// budget in bytes (see the module documentation). The first-order event model needs
    /// M_b α + M_d β < 1 for every parent with M_d objects in view: the reference has no object capacity,
    /// so it checks M_b α < 1 here and each parent's actual M_d at every scan.
    ///
    /// # Errors
    /// A message when M_b α ≥ 1 or a birth cell's innovation cannot be factored by the configuration's
    /// measurement model (each scan forms them again with the model placed at the scan).
    pub fn new(
        config: &Config<f64, M, G, S, B>,
        prior: &[(f64, Vec<PriorObject<f64, S>>)],
        time: f64,
        budget_bytes: usize,
    ) -> Result<Self, String>
    where
        M: Clone,
    {
        let weights = WeightModel::from_config(config);
        if !(weights.event_log_probability(Event::None, 0) > f64::NEG_INFINITY) {
            return Err(format!("tracker configuration: {}", ReferenceError::EventProbabilities { in_view: 0 }));
        }
        for (cell, gaussian) in config.birth.cells.iter().enumerate() {
            ekf::innovation(&config.measurement, gaussian).map_err(|e| format!("birth cell {cell}: {e}"))?;
        }
        let mut tracks: Vec<Track<S>> = vec![];
        let (mut hypotheses, mut objects) = (vec![], vec![]);
        let total: f64 = prior.iter().map(|p| p.0).sum();
        let mut next_label = 0;
        for (weight, members) in prior {
            let start = objects.len();
            for object in members {
                next_label = next_label.max(object.label.0.saturating_add(1));
                let index = tracks
                    .iter()
                    .position(|t| t.label == object.label.0 && t.state == object.state)
                    .unwrap_or_else(|| {
                        tracks.push(Track { label: object.label.0, state: object.state, unseen: 0 });
                        tracks.len() - 1
                    });
                objects.push(index as u32);
            }
            objects[start..].sort_by_key(|&i| tracks[i as usize].label);
            if *weight > 0.0 {
                let len = members.len() as u32;
                hypotheses.push(Hypothesis { log_weight: (weight / total).ln(), start, len });
            } else {
                objects.truncate(start);
            }
        }
        Ok(Self {
            config: Box::new(config.clone()),
            tracks,
            hypotheses,
            objects,
            time,
            next_label,
            shares: Shares::of(budget_bytes),
            max_children: u64::MAX,
            max_work: DEFAULT_MAX_WORK,
            budget_scans: vec![],
            scans: 0,
            pool: BirthPool::new(),
        })
    }

    /// Bounds the children enumerated per scan: beyond it the scan fails with
    /// [`StepError::ChildBudgetExceeded`] and the tracker is unchanged (the reference is then "broken",
    /// as exhaustive enumeration is in paper 003 §V-B).
    pub fn set_max_children(&mut self, max_children: u64) {
        self.max_children = max_children;
    }

    /// Bounds the association steps per scan (default [`DEFAULT_MAX_WORK`]): every node of the
    /// enumeration and every (row, column) pair it examines is a step. Beyond it the scan fails with
    /// [`ReferenceError::WorkBudgetExceeded`] and the tracker is unchanged: a scan whose enumeration would
    /// not finish in a sensible time (one scan of 10⁶ measurements) stops instead.
    pub fn set_max_work(&mut self, max_work: u64) {
        self.max_work = max_work;
    }

    /// Scans (1-based) at which the memory budget forced dropping parents or children.
    pub fn budget_scans(&self) -> &[usize] {
        &self.budget_scans
    }

    /// Number of hypotheses.
    pub fn len(&self) -> usize {
        self.hypotheses.len()
    }

    /// Whether there is no hypothesis.
    pub fn is_empty(&self) -> bool {
        self.hypotheses.is_empty()
    }

    fn members(&self, hypothesis: &Hypothesis) -> &[u32] {
        &self.objects[hypothesis.start..hypothesis.start + hypothesis.len as usize]
    }

    /// Processes one scan of the only sensor, taken at `time` ([`ReferenceTracker::step_scan`] with
    /// [`ScanGeometry::single`]); on error the tracker is unchanged.
    ///
    /// # Errors
    /// The core's [`StepError`] for the same bad inputs (non-finite values, time, numerical failure,
    /// more children than [`ReferenceTracker::set_max_children`]), or
    /// [`ReferenceError::EventProbabilities`].
    pub fn step(&mut self, time: f64, measurements: &[SVector<f64, D>]) -> Result<ReferenceReport, ReferenceError> {
        self.step_scan(&ScanGeometry::single(time), measurements)
    }

    /// Processes one scan of the sensor `geometry` names, at `geometry.time`, seen from its observer; on
    /// error the tracker is unchanged. The scan is checked and its sensor placed by the core's
    /// [`place_scan`] (without a measurement capacity), and every innovation, field-of-view test, entry and
    /// update of the scan uses the placed model, as [`Tracker::step_scan`](tracker_core::Tracker::step_scan)
    /// does.
    ///
    /// # Errors
    /// As [`ReferenceTracker::step`], and [`StepError::Placement`] for a geometry the model cannot place.
    pub fn step_scan(
        &mut self,
        geometry: &ScanGeometry<f64>,
        measurements: &[SVector<f64, D>],
    ) -> Result<ReferenceReport, ReferenceError> {
        let time = geometry.time;
        let placed = place_scan(&self.config, geometry, self.time, measurements, usize::MAX)?;
        let scan = self.birth_cells(placed, time)?;
        let tables = self.tables(scan, time - self.time, measurements)?;
        let mut budget_reached = tables.parents.len() < self.hypotheses.len();
        // The pruned search's candidate lists: at most every (row, column) pair at each depth.
        let candidates = size_of::<(u32, u32)>().saturating_mul(tables.rows * tables.widest * (tables.widest + 1));
        let children_bytes = self.shares.working.saturating_sub(tables.bytes).saturating_sub(candidates);
        let mut children = ChildBuffer::new(
            children_bytes / (CHILD_BYTES + 4 * tables.widest),
            tables.widest,
            self.max_children,
            self.max_work,
        );
        for &parent in &tables.parents {
            self.enumerate_parent(&tables, parent, &mut children)?;
        }
        if children.heads.is_empty() {
            return Err(StepError::NoViableChild.into());
        }
        budget_reached |= children.pruned;
        let posterior = self.materialise(&tables, &children, measurements)?;
        budget_reached |= posterior.truncated;
        let log_kept = posterior.log_mass;
        if let Some(measured) = &self.config.birth.measured {
            let capacity = B.saturating_sub(self.config.birth.cells.len());
            let model = &tables.scan.placed.model;
            let scan = ScanUse {
                time,
                sensor: geometry.sensor,
                measurements,
                unexplained: &posterior.unexplained,
                born: &posterior.born,
                detection: &pool_detection(&tables.scan, self.pool.cells().len()),
                labels: &posterior.row_labels,
            };
            let placed = &tables.scan.placed;
            let linking = Linking {
                motion: &self.config.motion,
                field_of_view: &placed.detection.field_of_view,
                weights: &placed.weights,
                detection_probability: placed.detection.detection_probability,
            };
            self.pool.adopt_labels(&posterior.candidate_labels);
            self.pool.update(measured, capacity, model, &linking, &scan);
        }
        self.tracks = posterior.tracks;
        self.hypotheses = posterior.hypotheses;
        self.objects = posterior.objects;
        self.time = time;
        self.next_label = posterior.next_label;
        self.scans += 1;
        if budget_reached {
            self.budget_scans.push(self.scans);
        }
        Ok(ReferenceReport {
            children: children.count,
            hypotheses: self.hypotheses.len(),
            budget_reached,
            captured_mass: if budget_reached { (log_kept - children.total.value()).exp().min(1.0) } else { 1.0 },
        })
    }
}

impl<M, G, const D: usize, const B: usize> ReferenceTracker<M, G, 4, D, B>
where
    M: MotionModel<f64, 4>,
    G: MeasurementModel<f64, 4, D> + Clone,
{
    /// The hypotheses and tracks, best first, with existence per track.
    pub fn snapshot(&self) -> Snapshot {
        let mut tracks: Vec<TrackOut> = self
            .tracks
            .iter()
            .map(|t| TrackOut {
                label: t.label,
                mean: t.state.mean.into(),
                covariance: t.state.covariance.into(),
                existence: 0.0,
            })
            .collect();
        let hypotheses = self
            .hypotheses
            .iter()
            .map(|h| {
                let weight = h.log_weight.exp();
                for &t in self.members(h) {
                    tracks[t as usize].existence += weight;
                }
                HypothesisOut {
                    weight,
                    log_weight: h.log_weight,
                    tracks: self.members(h).iter().map(|&t| t as usize).collect(),
                }
            })
            .collect();
        Snapshot { hypotheses, tracks }
    }
}

/// Per pool cell, the scan sensor's p_D when the cell was in its field of view, else 0 (as the core's).
fn pool_detection<G, const S: usize, const D: usize>(scan: &Scan<G, S, D>, cells: usize) -> Vec<f64> {
    let mut detection = vec![0.0; cells];
    for ((_, in_view), &(_, _, pool_cell)) in scan.births.iter().zip(&scan.cells) {
        if let (true, Some(slot)) = (*in_view, pool_cell.and_then(|c| detection.get_mut(c))) {
            *slot = scan.placed.detection.detection_probability;
        }
    }
    detection
}
