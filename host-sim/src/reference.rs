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

use crate::pipeline::snapshot::{HypothesisOut, Snapshot, TrackOut};
use nalgebra::SVector;
use std::collections::HashMap;
use std::hash::{DefaultHasher, Hash, Hasher};
use std::mem::size_of;
use tracker_core::ekf::{self, Gaussian, Innovation};
use tracker_core::model::ScanGeometry;
use tracker_core::pool::{BirthPool, ScanUse};
use tracker_core::real::{LogSumExp, log_add};
use tracker_core::tracker::{PlacedScan, place_scan};
use tracker_core::weight::{Event, WeightModel};
use tracker_core::{Config, MeasurementModel, MotionModel, PositionMeasurement, PriorObject, StepError, TrackLabel};

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

/// Where a track comes from: (is a birth, old track index or birth cell, measurement row or [`CLUTTER`]).
type TrackKey = (bool, u32, u32);

#[derive(Debug, Clone)]
struct Track<const S: usize> {
    label: u32,
    state: Gaussian<f64, S>,
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
    in_view: bool,
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
        }
    }
}

impl std::error::Error for ReferenceError {}

/// A track of [`ReferenceTracker::posterior`]: its label and Gaussian.
pub type LabelledState<const S: usize> = (TrackLabel, Gaussian<f64, S>);

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
                        tracks.push(Track { label: object.label.0, state: object.state });
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
        let mut children =
            ChildBuffer::new(children_bytes / (CHILD_BYTES + 4 * tables.widest), tables.widest, self.max_children);
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
            let scan = ScanUse { time, measurements, unexplained: &posterior.unexplained, born: &posterior.born };
            self.pool.update(measured, capacity, model, &scan);
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

    /// The birth cells as the placed sensor sees them (as the core's `birth_cells`).
    fn birth_cells(&self, mut placed: PlacedScan<f64, G>, time: f64) -> Result<Scan<G, S, D>, StepError> {
        let (mut births, mut cells) = (vec![], vec![]);
        let alpha = self.config.birth.probability;
        let fixed = self.config.birth.cells.iter().enumerate().map(|(cell, g)| (Some(cell), *g, alpha, None));
        let from_pool = self.pool.predicted(&self.config.motion, time).map(|(index, g, a)| (None, g, a, Some(index)));
        let mut no_birth = 0.0;
        for (fixed_cell, gaussian, alpha, pool_cell) in fixed.chain(from_pool).take(B) {
            let innovation = match (ekf::innovation(&placed.model, &gaussian), fixed_cell) {
                (Ok(innovation), _) => innovation,
                (Err(_), Some(cell)) => return Err(StepError::BirthCell { cell }),
                (Err(_), None) => continue, // a pool cell is left out of this scan, as in the core
            };
            let in_view = placed.detection.field_of_view.sees(&placed.model, &innovation.predicted);
            births.push((innovation, in_view));
            cells.push((gaussian, alpha, pool_cell));
            no_birth += (1.0 - alpha).ln();
        }
        if self.config.birth.measured.is_some() {
            placed.weights.set_birth_cells(cells.len(), no_birth);
        }
        Ok(Scan { placed, births, cells })
    }

    /// Predicts and scores the tracks of the best parents whose tables fit half the working share (at
    /// least the best parent).
    fn tables(
        &self,
        scan: Scan<G, S, D>,
        dt: f64,
        measurements: &[SVector<f64, D>],
    ) -> Result<Tables<G, S, D>, ReferenceError> {
        let rows = measurements.len();
        let per_track = size_of::<Predicted<S, D>>() + size_of::<f64>() * (2 * rows + 1) + size_of::<u32>() * rows;
        let cells = scan.births.len();
        let fixed = size_of::<u32>() * self.tracks.len()
            + per_track * cells
            + size_of::<f64>() * (2 * rows + 1)
            + map_entry(size_of::<((bool, u32), u32)>()) * (rows + cells);
        let mut order: Vec<u32> = (0..self.hypotheses.len() as u32).collect();
        order.sort_by(|&a, &b| {
            self.hypotheses[b as usize].log_weight.total_cmp(&self.hypotheses[a as usize].log_weight)
        });
        let mut slot = vec![NO_SLOT; self.tracks.len()];
        let (mut used, mut kept) = (0usize, 0usize);
        for &parent in &order {
            let members = self.members(&self.hypotheses[parent as usize]);
            let new = members.iter().filter(|&&t| slot[t as usize] == NO_SLOT).count();
            if kept > 0 && fixed + per_track * (used + new) > self.shares.working / 2 {
                break;
            }
            for &t in members {
                if slot[t as usize] == NO_SLOT {
                    slot[t as usize] = used as u32;
                    used += 1;
                }
            }
            kept += 1;
        }
        let mut parents = order[..kept].to_vec();
        parents.sort_unstable();
        // Slots in track order, so the tables do not depend on the parents' weights.
        for (next, s) in slot.iter_mut().filter(|s| **s != NO_SLOT).enumerate() {
            *s = next as u32;
        }
        self.score(scan, dt, measurements, parents, slot, fixed + per_track * used)
    }

    /// Fills the tables for the tracks that have a slot and the birth cells.
    fn score(
        &self,
        scan: Scan<G, S, D>,
        dt: f64,
        measurements: &[SVector<f64, D>],
        parents: Vec<u32>,
        slot: Vec<u32>,
        bytes: usize,
    ) -> Result<Tables<G, S, D>, ReferenceError> {
        let rows = measurements.len();
        let mut predicted = vec![];
        let (mut entries, mut bounds, mut order) = (vec![], vec![], vec![]);
        let PlacedScan { model, detection, weights } = &scan.placed;
        let mut column = |innovation: &Innovation<f64, D>, in_view: bool, birth: Option<f64>| {
            let (start, first) = (bounds.len(), entries.len());
            for z in measurements {
                let entry = if in_view {
                    weights.entry_of_residual(innovation, &model.residual(z, &innovation.predicted))
                } else {
                    f64::NEG_INFINITY
                };
                let entry = birth.map_or(entry, |alpha| weights.birth_entry_with(entry, alpha));
                entries.push(entry);
                bounds.push(entry.max(0.0));
            }
            bounds.push(0.0);
            for r in (start..start + rows).rev() {
                bounds[r] = bounds[r].max(bounds[r + 1]);
            }
            let column: &[f64] = &entries[first..];
            let mut rows_by_entry: Vec<u32> = (0..rows as u32).collect();
            rows_by_entry.sort_by(|&a, &b| column[b as usize].total_cmp(&column[a as usize]));
            order.extend_from_slice(&rows_by_entry);
        };
        for (track, _) in self.tracks.iter().zip(&slot).filter(|(_, s)| **s != NO_SLOT) {
            let numerical = |error| StepError::Numerical { label: TrackLabel(track.label), error };
            let state = ekf::predict(&self.config.motion, &track.state, dt).map_err(numerical)?;
            let innovation = ekf::innovation(model, &state).map_err(numerical)?;
            let in_view = detection.field_of_view.sees(model, &innovation.predicted);
            column(&innovation, in_view, None);
            predicted.push(Predicted { state, innovation, in_view });
        }
        for ((innovation, in_view), &(_, alpha, _)) in scan.births.iter().zip(&scan.cells) {
            column(innovation, *in_view, Some(alpha));
        }
        let cell_entries = |cell: usize| &entries[(predicted.len() + cell) * rows..(predicted.len() + cell + 1) * rows];
        let birth_columns: Vec<usize> = if weights.independent_births() {
            (0..scan.births.len()).filter(|&cell| cell_entries(cell).iter().any(|&e| e > f64::NEG_INFINITY)).collect()
        } else {
            vec![]
        };
        let births = if weights.independent_births() {
            birth_columns.len()
        } else {
            usize::from(weights.births_possible() && scan.births.iter().any(|b| b.1))
        };
        let widest = parents
            .iter()
            .map(|&p| {
                let members = self.members(&self.hypotheses[p as usize]);
                members.iter().filter(|&&t| predicted[slot[t as usize] as usize].in_view).count()
            })
            .max()
            .unwrap_or(0)
            + births;
        let dead = (vec![f64::NEG_INFINITY; rows], vec![0.0; rows + 1]);
        Ok(Tables { scan, rows, parents, slot, predicted, entries, bounds, order, dead, widest, birth_columns, bytes })
    }

    /// Offers every child of `parent` (each event, each association) to `children`.
    fn enumerate_parent(
        &self,
        tables: &Tables<G, S, D>,
        parent: u32,
        children: &mut ChildBuffer,
    ) -> Result<(), ReferenceError> {
        let hypothesis = &self.hypotheses[parent as usize];
        let (weights, births) = (&tables.scan.placed.weights, &tables.scan.births);
        // (position in the parent, slot) of the objects in view.
        let columns: Vec<(usize, usize)> = self
            .members(hypothesis)
            .iter()
            .enumerate()
            .map(|(position, &t)| (position, tables.slot[t as usize] as usize))
            .filter(|&(_, s)| tables.predicted[s].in_view)
            .collect();
        let in_view = columns.len();
        if !(weights.event_log_probability(Event::None, in_view) > f64::NEG_INFINITY) {
            return Err(ReferenceError::EventProbabilities { in_view });
        }
        let detection_required = weights.detection_required();
        for (event, child_in_view) in events(weights, births, in_view, &columns) {
            let mut matrix: Vec<Column<'_>> = columns
                .iter()
                .map(|&(position, s)| {
                    if event == (Event::Death { object: position as u16 }) {
                        Column { entries: &tables.dead.0, bounds: &tables.dead.1, order: &[], required: false }
                    } else {
                        let (entries, bounds, order) = tables.column(s);
                        Column { entries, bounds, order, required: detection_required }
                    }
                })
                .collect();
            for &cell in &tables.birth_columns {
                let (entries, bounds, order) = tables.birth_column(cell);
                matrix.push(Column { entries, bounds, order, required: false });
            }
            if let Event::Birth { cell } = event
                && births[cell as usize].1
            {
                let (entries, bounds, order) = tables.birth_column(cell as usize);
                matrix.push(Column { entries, bounds, order, required: weights.birth_required() });
            }
            let baseline = weights.baseline(
                hypothesis.log_weight,
                weights.event_log_probability(event, in_view),
                child_in_view,
                tables.rows,
            );
            let mut search = Search {
                columns: &matrix,
                row_of: vec![CLUTTER; matrix.len()],
                rows: tables.rows,
                parent,
                event,
                children: &mut *children,
                candidates: vec![],
            };
            if !search.visit(0, baseline, 0) {
                return Err(StepError::ChildBudgetExceeded { budget: self.max_children }.into());
            }
        }
        Ok(())
    }

    /// Turns the kept children, best first, into hypotheses over shared tracks, merging identical ones,
    /// until the posterior's share is used.
    fn materialise(
        &self,
        tables: &Tables<G, S, D>,
        children: &ChildBuffer,
        measurements: &[SVector<f64, D>],
    ) -> Result<Posterior<S>, ReferenceError> {
        let mut order: Vec<u32> = (0..children.heads.len() as u32).collect();
        // Best first; ties keep the enumeration order.
        order.sort_unstable_by(|&a, &b| {
            let (x, y) = (&children.heads[a as usize], &children.heads[b as usize]);
            y.log_weight.total_cmp(&x.log_weight).then(a.cmp(&b))
        });
        let mut posterior = Posterior::new(self.next_label, self.shares.posterior);
        let mut sources: Vec<TrackKey> = vec![];
        // Σ w over the kept children, and per row and per pool cell the part of it that takes the row or
        // gives birth in the cell, relative to the best child (docs/maths.md §5.8).
        let (mut mass, mut taken, mut born) = (0.0, vec![0.0; tables.rows], vec![0.0; self.pool.cells().len()]);
        let best = order.first().map_or(0.0, |&i| children.heads[i as usize].log_weight);
        for index in order {
            self.sources(tables, children, index as usize, &mut sources);
            let head = &children.heads[index as usize];
            if !posterior.add(self, tables, measurements, head.log_weight, &sources)? {
                posterior.truncated = true;
                break;
            }
            let weight = (head.log_weight - best).exp();
            mass += weight;
            for &(is_birth, source, row) in &sources {
                if row == CLUTTER {
                    continue;
                }
                taken[row as usize] += weight;
                if is_birth && let Some(pool_cell) = tables.scan.cells[source as usize].2 {
                    born[pool_cell] += weight;
                }
            }
        }
        posterior.unexplained = taken.iter().map(|t| 1.0 - t / mass).collect();
        posterior.born = born.iter().map(|b| b / mass).collect();
        posterior.normalise();
        Ok(posterior)
    }

    /// The track keys of child `index`: its parent's surviving objects and its birth, with their rows.
    fn sources(&self, tables: &Tables<G, S, D>, children: &ChildBuffer, index: usize, sources: &mut Vec<TrackKey>) {
        let head = &children.heads[index];
        let row_of = children.rows_of(index);
        sources.clear();
        let mut column = 0;
        for (position, &track) in self.members(&self.hypotheses[head.parent as usize]).iter().enumerate() {
            let row = if tables.predicted[tables.slot[track as usize] as usize].in_view {
                column += 1;
                row_of[column - 1]
            } else {
                CLUTTER
            };
            if head.event != (Event::Death { object: position as u16 }) {
                sources.push((false, track, row));
            }
        }
        // Independent births, in the order of the rows they take (as the core makes their labels).
        let first_birth = sources.len();
        for (&cell, &row) in tables.birth_columns.iter().zip(&row_of[column..]) {
            if row != CLUTTER {
                sources.push((true, cell as u32, row));
            }
        }
        sources[first_birth..].sort_unstable_by_key(|&(_, _, row)| row);
        if let Event::Birth { cell } = head.event {
            let row = if tables.scan.births[cell as usize].1 { row_of[column] } else { CLUTTER };
            sources.push((true, u32::from(cell), row));
        }
    }

    /// The hypotheses, best first: each one's normalised log-weight and its tracks (label and Gaussian)
    /// in label order.
    pub fn posterior(&self) -> Vec<(f64, Vec<LabelledState<S>>)> {
        let track = |&t: &u32| {
            let track = &self.tracks[t as usize];
            (TrackLabel(track.label), track.state)
        };
        self.hypotheses.iter().map(|h| (h.log_weight, self.members(h).iter().map(track).collect())).collect()
    }
}

/// The events of a parent with `in_view` objects in view, each with its child's objects in view.
fn events<const D: usize>(
    weights: &WeightModel<f64>,
    births: &[(Innovation<f64, D>, bool)],
    in_view: usize,
    columns: &[(usize, usize)],
) -> Vec<(Event, usize)> {
    let mut events = vec![(Event::None, in_view)];
    // Independent births are columns of every event's matrix, not events.
    if weights.births_possible() && !weights.independent_births() {
        for (cell, (_, detectable)) in births.iter().enumerate() {
            if *detectable || !weights.birth_required() {
                events.push((Event::Birth { cell: cell as u16 }, in_view + usize::from(*detectable)));
            }
        }
    }
    if weights.deaths_possible() {
        for &(position, _) in columns {
            events.push((Event::Death { object: position as u16 }, in_view - 1));
        }
    }
    events
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

/// One column of an event's association matrix.
struct Column<'a> {
    entries: &'a [f64],
    /// `bounds[r]` ≥ every entry of rows `r..`, and ≥ 0 (clutter).
    bounds: &'a [f64],
    /// The rows by decreasing entry (ties: lower row first).
    order: &'a [u32],
    required: bool,
}

/// A child in the buffer; its rows per column are `rows[start..next start]`.
#[derive(Debug, Clone, Copy)]
struct Head {
    log_weight: f64,
    start: usize,
    parent: u32,
    event: Event,
}

/// The children kept so far, within a byte capacity: when full, the best half is kept and every later
/// child or branch that cannot beat the worst kept one is skipped.
struct ChildBuffer {
    heads: Vec<Head>,
    rows: Vec<u32>,
    /// At most this many heads (and `capacity × widest` rows).
    capacity: usize,
    widest: usize,
    /// The worst kept weight once pruned, else −∞.
    threshold: f64,
    pruned: bool,
    count: u64,
    limit: u64,
    total: LogSumExp<f64>,
}

impl ChildBuffer {
    fn new(capacity: usize, widest: usize, limit: u64) -> Self {
        Self {
            heads: vec![],
            rows: vec![],
            capacity: capacity.max(2),
            widest,
            threshold: f64::NEG_INFINITY,
            pruned: false,
            count: 0,
            limit,
            total: LogSumExp::new(),
        }
    }

    fn rows_of(&self, index: usize) -> &[u32] {
        let end = self.heads.get(index + 1).map_or(self.rows.len(), |h| h.start);
        &self.rows[self.heads[index].start..end]
    }

    /// Whether no child of weight ≤ `bound` can be kept. `tolerance` covers the rounding of a bound
    /// summed in another order than the child's weight.
    fn cannot_beat(&self, bound: f64, tolerance: f64) -> bool {
        self.pruned && bound + tolerance <= self.threshold
    }

    /// Counts and keeps a child; `false` when the children limit is reached.
    fn offer(&mut self, log_weight: f64, parent: u32, event: Event, row_of: &[u32]) -> bool {
        if self.count >= self.limit {
            return false;
        }
        self.count += 1;
        self.total.add(log_weight);
        if self.heads.len() == self.capacity {
            self.prune();
        }
        if self.pruned && log_weight.total_cmp(&self.threshold).is_le() {
            return true;
        }
        let start = self.rows.len();
        grow_within(&mut self.rows, row_of.len(), self.capacity * self.widest);
        self.rows.extend_from_slice(row_of);
        grow_within(&mut self.heads, 1, self.capacity);
        self.heads.push(Head { log_weight, start, parent, event });
        true
    }

    /// Keeps the best `capacity / 2` children (ties: earlier first), in enumeration order.
    fn prune(&mut self) {
        let keep = self.capacity / 2;
        let mut weights: Vec<f64> = self.heads.iter().map(|h| h.log_weight).collect();
        let cut = *weights.select_nth_unstable_by(keep - 1, |a, b| b.total_cmp(a)).1;
        drop(weights);
        let mut ties = keep - self.heads.iter().filter(|h| h.log_weight.total_cmp(&cut).is_gt()).count();
        let (mut kept, mut end) = (0, 0);
        for index in 0..self.heads.len() {
            let head = self.heads[index];
            let keep_it = match head.log_weight.total_cmp(&cut) {
                std::cmp::Ordering::Greater => true,
                std::cmp::Ordering::Equal if ties > 0 => {
                    ties -= 1;
                    true
                }
                _ => false,
            };
            if keep_it {
                let next = self.heads.get(index + 1).map_or(self.rows.len(), |h| h.start);
                self.rows.copy_within(head.start..next, end);
                self.heads[kept] = Head { start: end, ..head };
                kept += 1;
                end += next - head.start;
            }
        }
        self.heads.truncate(kept);
        self.rows.truncate(end);
        self.threshold = cut;
        self.pruned = true;
    }
}

/// Makes room for `more` elements, never past `max` (doubling below it).
fn grow_within<T>(v: &mut Vec<T>, more: usize, max: usize) {
    if v.len() + more > v.capacity() {
        let target = (2 * v.capacity()).max(v.len() + more).max(64).min(max.max(v.len() + more));
        v.reserve_exact(target - v.len());
    }
}

/// The recursive enumeration of one parent-event's associations. A node is a partial association whose
/// rows before `row` are decided; it offers its own child (every later row clutter) first, then assigns
/// an unused column to a later row, last row first. That is the lexicographic order of the rows'
/// choices (clutter first, then columns in order), and each node is one child, so skipping the rows
/// left to clutter costs nothing.
struct Search<'a, 'b> {
    columns: &'a [Column<'a>],
    /// Per column its row, or [`CLUTTER`].
    row_of: Vec<u32>,
    rows: usize,
    parent: u32,
    event: Event,
    children: &'b mut ChildBuffer,
    /// Per depth, the (row, column) candidates of a pruned node.
    candidates: Vec<Vec<(u32, u32)>>,
}

impl Search<'_, '_> {
    /// Offers the node's child and every child below it, skipping children that leave a required column
    /// unassigned and, once the buffer was pruned, branches that cannot beat it. `false` as soon as the
    /// children limit is reached.
    fn visit(&mut self, row: usize, value: f64, depth: usize) -> bool {
        if self.children.pruned && self.cannot_beat(row, value, None) {
            return true;
        }
        let complete = self.columns.iter().zip(&self.row_of).all(|(c, &r)| !c.required || r != CLUTTER);
        if complete && !self.children.offer(value, self.parent, self.event, &self.row_of) {
            return false;
        }
        for r in (row..self.rows).rev() {
            if self.children.pruned {
                return self.visit_candidates(row, r + 1, value, depth);
            }
            for column in 0..self.columns.len() {
                if self.row_of[column] == CLUTTER
                    && self.columns[column].entries[r] > f64::NEG_INFINITY
                    && !self.assign(column, r, value, depth)
                {
                    return false;
                }
            }
        }
        true
    }

    /// Visits the node with `column` assigned to `row`.
    fn assign(&mut self, column: usize, row: usize, value: f64, depth: usize) -> bool {
        self.row_of[column] = row as u32;
        let go_on = self.visit(row + 1, value + self.columns[column].entries[row], depth + 1);
        self.row_of[column] = CLUTTER;
        go_on
    }

    /// Whether no child below the node (with `column` also assigned, if given) can be kept: its value
    /// plus every unused column's best entry from `row` on does not beat the worst kept child.
    fn cannot_beat(&self, row: usize, value: f64, except: Option<usize>) -> bool {
        let (mut bound, mut magnitude) = (value, value.abs() + 1.0);
        for (column, (c, &r)) in self.columns.iter().zip(&self.row_of).enumerate() {
            if r == CLUTTER && Some(column) != except {
                bound += c.bounds[row];
                magnitude += c.bounds[row];
            }
        }
        // The tolerance covers the rounding of a bound summed in another order than a child's weight.
        self.children.cannot_beat(bound, 1e-9 * magnitude)
    }

    /// Once pruned: the assignments of rows `row..end` that may beat the kept children, found from each
    /// column's rows by decreasing entry, visited in the enumeration order.
    fn visit_candidates(&mut self, row: usize, end: usize, value: f64, depth: usize) -> bool {
        if self.candidates.len() <= depth {
            self.candidates.resize_with(depth + 1, Vec::new);
        }
        let mut list = std::mem::take(&mut self.candidates[depth]);
        list.clear();
        for column in 0..self.columns.len() {
            if self.row_of[column] != CLUTTER {
                continue;
            }
            let c = &self.columns[column];
            for &r in c.order {
                let entry = c.entries[r as usize];
                if !(entry > f64::NEG_INFINITY) || self.cannot_beat(row, value + entry, Some(column)) {
                    break;
                }
                if (row..end).contains(&(r as usize)) {
                    list.push((r, column as u32));
                }
            }
        }
        list.sort_unstable_by(|a, b| b.0.cmp(&a.0).then(a.1.cmp(&b.1)));
        let mut go_on = true;
        for &(r, column) in &list {
            if !self.assign(column as usize, r as usize, value, depth) {
                go_on = false;
                break;
            }
        }
        self.candidates[depth] = list;
        go_on
    }
}

/// The posterior being built from the kept children.
struct Posterior<const S: usize> {
    tracks: Vec<Track<S>>,
    hypotheses: Vec<Hypothesis>,
    objects: Vec<u32>,
    next_label: u32,
    /// Shared tracks by origin.
    keys: HashMap<TrackKey, u32>,
    /// One label per new object: per measurement for detected births, per cell for undetected ones.
    birth_labels: HashMap<(bool, u32), u32>,
    /// First hypothesis by hash of its tracks, and the next one with the same hash.
    by_hash: HashMap<u64, u32>,
    same_hash: Vec<u32>,
    bytes: usize,
    share: usize,
    truncated: bool,
    log_mass: f64,
    /// Per measurement, r_U: the kept children's weight that leaves it to clutter (measured births).
    unexplained: Vec<f64>,
    /// Per pool cell, the kept children's weight in which it gives birth.
    born: Vec<f64>,
}

impl<const S: usize> Posterior<S> {
    fn new(next_label: u32, share: usize) -> Self {
        Self {
            tracks: vec![],
            hypotheses: vec![],
            objects: vec![],
            next_label,
            keys: HashMap::new(),
            birth_labels: HashMap::new(),
            by_hash: HashMap::new(),
            same_hash: vec![],
            bytes: 0,
            share,
            truncated: false,
            log_mass: f64::NEG_INFINITY,
            unexplained: vec![],
            born: vec![],
        }
    }

    /// Adds a child of weight `log_weight` with tracks from `sources`; `false` (nothing added) when its
    /// new tracks and hypothesis would not fit the share.
    fn add<M, G: MeasurementModel<f64, S, D>, const D: usize, const B: usize>(
        &mut self,
        tracker: &ReferenceTracker<M, G, S, D, B>,
        tables: &Tables<G, S, D>,
        measurements: &[SVector<f64, D>],
        log_weight: f64,
        sources: &[TrackKey],
    ) -> Result<bool, ReferenceError> {
        let new = sources.iter().filter(|k| !self.keys.contains_key(k)).count();
        let cost = new * track_bytes::<S>() + HYPOTHESIS_BYTES + sources.len() * OBJECT_BYTES;
        if self.bytes + cost > self.share && !self.hypotheses.is_empty() {
            return Ok(false);
        }
        let start = self.objects.len();
        for &key in sources {
            let index = match self.keys.get(&key) {
                Some(&index) => index,
                None => self.new_track(tracker, tables, measurements, key)?,
            };
            self.objects.push(index);
        }
        self.objects[start..].sort_by_key(|&i| self.tracks[i as usize].label);
        let mut hasher = DefaultHasher::new();
        self.objects[start..].hash(&mut hasher);
        let hash = hasher.finish();
        let mut candidate = self.by_hash.get(&hash).copied();
        while let Some(existing) = candidate {
            let h = self.hypotheses[existing as usize];
            if self.objects[h.start..h.start + h.len as usize] == self.objects[start..] {
                self.objects.truncate(start);
                let h = &mut self.hypotheses[existing as usize];
                h.log_weight = log_add(h.log_weight, log_weight);
                self.bytes += new * track_bytes::<S>();
                return Ok(true);
            }
            candidate = Some(self.same_hash[existing as usize]).filter(|&n| n != u32::MAX);
        }
        let index = self.hypotheses.len() as u32;
        self.same_hash.push(self.by_hash.insert(hash, index).unwrap_or(u32::MAX));
        self.hypotheses.push(Hypothesis { log_weight, start, len: sources.len() as u32 });
        self.bytes += cost;
        Ok(true)
    }

    /// Makes the track of `key`: the old track predicted, or the birth cell's, updated with its row.
    fn new_track<M, G: MeasurementModel<f64, S, D>, const D: usize, const B: usize>(
        &mut self,
        tracker: &ReferenceTracker<M, G, S, D, B>,
        tables: &Tables<G, S, D>,
        measurements: &[SVector<f64, D>],
        key: TrackKey,
    ) -> Result<u32, ReferenceError> {
        let (is_birth, source, row) = key;
        let (label, prior, innovation) = if is_birth {
            let birth_key = if row == CLUTTER { (false, source) } else { (true, row) };
            let next_label = &mut self.next_label;
            let label = *self.birth_labels.entry(birth_key).or_insert_with(|| {
                *next_label += 1;
                *next_label - 1
            });
            (label, tables.scan.cells[source as usize].0, tables.scan.births[source as usize].0)
        } else {
            let p = &tables.predicted[tables.slot[source as usize] as usize];
            (tracker.tracks[source as usize].label, p.state, p.innovation)
        };
        let state = if row == CLUTTER {
            prior
        } else {
            ekf::update(&tables.scan.placed.model, &prior, &innovation, &measurements[row as usize])
                .map_err(|error| StepError::Numerical { label: TrackLabel(label), error })?
        };
        self.tracks.push(Track { label, state });
        let index = (self.tracks.len() - 1) as u32;
        self.keys.insert(key, index);
        Ok(index)
    }

    /// Normalises the weights and sorts the hypotheses best first (ties: first made first).
    fn normalise(&mut self) {
        self.keys = HashMap::new();
        self.by_hash = HashMap::new();
        self.same_hash = vec![];
        let mut kept = LogSumExp::new();
        for h in &self.hypotheses {
            kept.add(h.log_weight);
        }
        self.log_mass = kept.value();
        for h in &mut self.hypotheses {
            h.log_weight -= self.log_mass;
        }
        self.hypotheses.sort_by(|a, b| b.log_weight.total_cmp(&a.log_weight));
    }
}
