//! Stage 3 of a scan: the kept children become the next hypotheses and tracks.
//!
//! Only the kept children are built, best first. A child's objects are keyed by (source, measurement): the
//! source is a track of the previous store or a birth cell, the measurement the row that the child's
//! association gives it (read back through the column layout of its (parent, event)), or none when it is
//! missed. A key seen before reuses its track, a new key gets one EKF update. Children that hold exactly
//! the same tracks are merged (their weights add), and the weights are normalised over the kept
//! hypotheses (docs/maths.md §8.2–§8.3).

use super::finish_hypotheses;
use super::generate::Generation;
use super::score::{BirthCells, Scores};
use crate::association::{Column, ColumnLayout};
use crate::config::{Config, StoreOverflow};
use crate::digest::Fnv1a;
use crate::ekf::{self, Innovation};
use crate::error::StepError;
use crate::gaussian::Gaussian;
use crate::hypothesis::{Hypothesis, HypothesisSet};
use crate::index::{At, NONE, insertion_sort_by};
use crate::model::MeasurementModel;
use crate::real::{LogSumExp, Real, log_add};
use crate::selection::Candidate;
use crate::store::{Track, TrackLabel, TrackStore};
use crate::weight::Event;
use nalgebra::SVector;

/// Where a child's track comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Source {
    /// A predicted track of the previous store (its slot).
    Track(u16),
    /// A birth cell.
    Birth(u16),
}

/// Scratch space of stage 3.
#[derive(Debug, Clone)]
pub(super) struct Materialisation<const H: usize, const N: usize, const Z: usize, const K: usize, const B: usize> {
    order: [u16; H],
    /// First new slot made from each old slot / birth cell, and the chain of new slots per source.
    source_head: [u16; K],
    birth_head: [u16; B],
    next_same_source: [u16; K],
    /// The measurement each new slot took, or `NONE` when missed.
    new_slot_measurement: [u16; K],
    /// The measurement each object of the current parent takes, or `NONE`.
    row_of_position: [u16; N],
    child_sources: [(Source, u16); N],
    /// Whether each born object of the child takes its candidate's label (§5.8, "One label per candidate").
    child_inherits: [bool; N],
    /// Whether each new slot made from a birth cell took its candidate's label.
    new_slot_inherited: [bool; K],
    child_slots: [u16; N],
    hashes: [u64; H],
    /// The label of the object born from each measurement this scan, whatever its birth cell.
    birth_label_of_row: [Option<TrackLabel>; Z],
    /// The label of the undetected object born in each cell this scan.
    birth_label_of_cell: [Option<TrackLabel>; B],
    /// The label of the object born from each measurement in the best kept child that gave it one
    /// (its candidate's, or fresh): a candidate the pool makes from the measurement takes it.
    first_birth_label_of_row: [Option<TrackLabel>; Z],
    /// The candidates (pool groups) without a label that gave a birth this scan, with the label of the
    /// first one (best child first): the pool adopts them at the commit.
    candidate_labels: heapless::Vec<(u32, TrackLabel), B>,
}

/// What stage 3 reports besides the new buffers.
#[derive(Debug, Clone, Copy)]
pub(super) struct Materialised<T> {
    /// ln Σ w̃ over the kept hypotheses (before normalisation).
    pub(super) kept_total: LogSumExp<T>,
    pub(super) next_label: u32,
    pub(super) dropped_for_store: usize,
    pub(super) merged: usize,
}

/// The read-only inputs of stage 3.
pub(super) struct Inputs<
    'a,
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
> {
    pub(super) config: &'a Config<T, M, G, S, B>,
    /// The measurement model placed at this scan.
    pub(super) model: &'a G,
    pub(super) birth_cells: &'a BirthCells<T, S, D, B>,
    pub(super) scores: &'a Scores<T, S, D, Z, K, B>,
    pub(super) generation: &'a Generation<T, H, N, Z>,
    pub(super) store: &'a TrackStore<T, S, K>,
    pub(super) parents: &'a HypothesisSet<T, N, H>,
    pub(super) measurements: &'a [SVector<T, D>],
}

impl<const H: usize, const N: usize, const Z: usize, const K: usize, const B: usize> Materialisation<H, N, Z, K, B> {
    pub(super) const fn new() -> Self {
        Self {
            order: [0; H],
            source_head: [NONE; K],
            birth_head: [NONE; B],
            next_same_source: [NONE; K],
            new_slot_measurement: [NONE; K],
            row_of_position: [NONE; N],
            child_sources: [(Source::Track(0), NONE); N],
            child_inherits: [false; N],
            new_slot_inherited: [false; K],
            child_slots: [0; N],
            hashes: [0; H],
            birth_label_of_row: [None; Z],
            birth_label_of_cell: [None; B],
            first_birth_label_of_row: [None; Z],
            candidate_labels: heapless::Vec::new(),
        }
    }

    /// The candidates that gave their first birth in the last scan, each with its label (§5.8).
    pub(super) fn candidate_labels(&self) -> &[(u32, TrackLabel)] {
        &self.candidate_labels
    }

    /// Per measurement of the last scan, the label of the object born from it in the best kept child
    /// that gave it one.
    pub(super) fn birth_labels_of_rows(&self) -> &[Option<TrackLabel>; Z] {
        &self.first_birth_label_of_row
    }

    /// Builds the kept children's tracks and hypotheses into `next_store` and `next_set`, best first.
    ///
    /// # Errors
    /// [`StepError::TrackStoreFull`] (with [`StoreOverflow::Error`]), [`StepError::LabelsExhausted`],
    /// [`StepError::Numerical`] from an EKF update.
    pub(super) fn run<T: Real, M, G, const S: usize, const D: usize>(
        &mut self,
        inputs: &Inputs<'_, T, M, G, S, D, H, N, Z, K, B>,
        next_store: &mut TrackStore<T, S, K>,
        next_set: &mut HypothesisSet<T, N, H>,
        next_label: u32,
    ) -> Result<Materialised<T>, StepError>
    where
        G: MeasurementModel<T, S, D>,
    {
        next_store.clear();
        next_set.clear();
        self.source_head[..inputs.store.len()].fill(NONE);
        self.birth_head.fill(NONE);
        self.birth_label_of_row.fill(None);
        self.birth_label_of_cell.fill(None);
        self.candidate_labels.clear();
        self.first_birth_label_of_row.fill(None);
        let mut outcome = Materialised { kept_total: LogSumExp::new(), next_label, dropped_for_store: 0, merged: 0 };
        let top = &inputs.generation.top;
        let kept = top.best_first(&mut self.order);
        // The floor under the children's weights, relative to the heaviest (§8.1); children are best first.
        let floor = inputs.config.selection.log_floor::<T>().and_then(|log_floor| {
            let heaviest = top.kept().get(usize::from(*self.order.first()?))?;
            Some(heaviest.log_weight + log_floor)
        });
        for rank in 0..kept {
            // A candidate naming a parent or a birth cell that does not exist cannot occur; it would be
            // skipped like a child that does not fit.
            let Some(candidate) = top.kept().get(usize::from(*self.order.at(rank))) else { continue };
            if floor.is_some_and(|floor| candidate.log_weight < floor) {
                break;
            }
            let Some(parent) = inputs.parents.as_slice().get(usize::from(candidate.parent)) else { continue };
            let Some(layout) = inputs.generation.layout(candidate.parent, candidate.event, inputs.birth_cells) else {
                continue;
            };
            let dropped = |slot: u16| inputs.scores.predicted(usize::from(slot)).dropped;
            let count = self.child_sources(candidate, parent, &layout, inputs.measurements.len(), dropped);
            self.choose_inherited(inputs, parent, count, next_label);
            if !self.has_room(count, next_store) {
                match inputs.config.store_overflow {
                    StoreOverflow::PruneChildren => {
                        outcome.dropped_for_store += 1;
                        continue;
                    }
                    StoreOverflow::Error => return Err(StepError::TrackStoreFull { capacity: K }),
                }
            }
            for index in 0..count {
                let (source, row) = *self.child_sources.at(index);
                let inherits = *self.child_inherits.at(index);
                let slot = match self.lookup(source, row, inherits) {
                    Some(slot) => slot,
                    None => self.new_track(inputs, source, row, inherits, next_store, &mut outcome.next_label)?,
                };
                *self.child_slots.at_mut(index) = slot;
            }
            self.keep_or_merge(candidate.log_weight, count, next_store, next_set, &mut outcome.merged);
        }
        // Normalise over the kept hypotheses.
        for hypothesis in next_set.as_slice() {
            outcome.kept_total.add(hypothesis.log_weight);
        }
        for hypothesis in next_set.as_mut_slice() {
            hypothesis.log_weight = outcome.kept_total.normalise(hypothesis.log_weight);
        }
        finish_hypotheses(next_set, next_store);
        Ok(outcome)
    }

    /// Writes the child's objects as (source, measurement) keys into `child_sources`, in the parent's
    /// order with a born object last; returns how many.
    fn child_sources<T: Real, const M: usize>(
        &mut self,
        candidate: &Candidate<T, M>,
        parent: &Hypothesis<T, N>,
        layout: &ColumnLayout<'_>,
        rows: usize,
        dropped: impl Fn(u16) -> bool,
    ) -> usize {
        // Which measurement each column's object takes.
        self.row_of_position[..parent.len()].fill(NONE);
        let assigned = candidate.assignment.iter().enumerate().take(rows);
        for (row, &column) in assigned.clone() {
            if let Some(Column::Object { position }) = layout.column(usize::from(column)) {
                *self.row_of_position.at_mut(usize::from(position)) = row as u16;
            }
        }
        let mut count = 0usize;
        for (position, &slot) in parent.slots().iter().enumerate() {
            // A dead object, or a track dropped for a numerical failure, is in no child.
            if candidate.event == (Event::Death { object: position as u16 }) || dropped(slot) {
                continue;
            }
            *self.child_sources.at_mut(count) = (Source::Track(slot), *self.row_of_position.at(position));
            count += 1;
        }
        // Born objects last, in the order of the measurements they take; a first-order birth that takes
        // none is an undetected birth.
        let mut event_birth = match candidate.event {
            Event::Birth { cell } => Some(cell),
            Event::None | Event::Death { .. } => None,
        };
        for (row, &column) in assigned {
            if let Some(Column::Birth { cell }) = layout.column(usize::from(column)) {
                if event_birth == Some(cell) {
                    event_birth = None;
                }
                if let Some(source) = self.child_sources.get_mut(count) {
                    *source = (Source::Birth(cell), row as u16);
                    count += 1;
                }
            }
        }
        if let (Some(cell), Some(source)) = (event_birth, self.child_sources.get_mut(count)) {
            *source = (Source::Birth(cell), NONE);
            count += 1;
        }
        // A child holds at most N objects; the clamp shows it to the optimiser.
        count.min(N)
    }

    /// Marks the child's born objects that take their candidate's label (docs/maths.md §5.8, "One label
    /// per candidate"): a birth from a pool cell whose candidate was born before under label L takes L
    /// unless the parent holds L or an earlier birth of the child took it. L is below `next_label` (the
    /// labels given before this scan), so it is distinct from this scan's fresh labels and the child's
    /// labels stay distinct. O(N²).
    fn choose_inherited<T: Real, M, G, const S: usize, const D: usize>(
        &mut self,
        inputs: &Inputs<'_, T, M, G, S, D, H, N, Z, K, B>,
        parent: &Hypothesis<T, N>,
        count: usize,
        next_label: u32,
    ) {
        let tracks = inputs.store.as_slice();
        let held = |label: TrackLabel| {
            parent.slots().iter().any(|&slot| tracks.get(usize::from(slot)).is_some_and(|t| t.label == label))
        };
        for index in 0..count {
            let inherited = self.inherited_label(inputs, index);
            let taken_before = |label: TrackLabel| {
                (0..index).any(|earlier| {
                    *self.child_inherits.at(earlier) && self.inherited_label(inputs, earlier) == Some(label)
                })
            };
            *self.child_inherits.at_mut(index) =
                inherited.is_some_and(|label| label.0 < next_label && !held(label) && !taken_before(label));
        }
    }

    /// The label of the candidate of the child's object `index`, when it is born from a labelled one.
    fn inherited_label<T: Real, M, G, const S: usize, const D: usize>(
        &self,
        inputs: &Inputs<'_, T, M, G, S, D, H, N, Z, K, B>,
        index: usize,
    ) -> Option<TrackLabel> {
        match self.child_sources.at(index).0 {
            Source::Birth(cell) => inputs.birth_cells.candidate.get(usize::from(cell)).copied().flatten()?.1,
            Source::Track(_) => None,
        }
    }

    /// Whether the child's new tracks fit the store.
    fn has_room<T: Real, const S: usize>(&self, count: usize, next_store: &TrackStore<T, S, K>) -> bool {
        let new_tracks = (0..count)
            .filter(|&index| {
                let (source, row) = *self.child_sources.at(index);
                self.lookup(source, row, *self.child_inherits.at(index)).is_none()
            })
            .count();
        next_store.len() + new_tracks <= K
    }

    /// Finds the new slot made from `source` with measurement `row` (or missed), if any; a birth's also
    /// by whether it took its candidate's label.
    fn lookup(&self, source: Source, row: u16, inherits: bool) -> Option<u16> {
        let mut slot = match source {
            Source::Track(old) => *self.source_head.at(usize::from(old)),
            Source::Birth(cell) => self.birth_head.get(usize::from(cell)).copied().unwrap_or(NONE),
        };
        // Each source has at most Z + 1 distinct new slots (one per measurement, one missed).
        while slot != NONE {
            if *self.new_slot_measurement.at(usize::from(slot)) == row
                && *self.new_slot_inherited.at(usize::from(slot)) == inherits
            {
                return Some(slot);
            }
            slot = *self.next_same_source.at(usize::from(slot));
        }
        None
    }

    /// Makes the new track of `source` with measurement `row` (missed: `NONE`) and returns its slot.
    fn new_track<T: Real, M, G, const S: usize, const D: usize>(
        &mut self,
        inputs: &Inputs<'_, T, M, G, S, D, H, N, Z, K, B>,
        source: Source,
        row: u16,
        inherits: bool,
        next_store: &mut TrackStore<T, S, K>,
        next_label: &mut u32,
    ) -> Result<u16, StepError>
    where
        G: MeasurementModel<T, S, D>,
    {
        let (label, prior, innovation) = self.source_state(inputs, source, row, inherits, next_label)?;
        let unseen_scans = match source {
            Source::Track(old) => inputs.scores.predicted(usize::from(old)).unseen_scans,
            Source::Birth(_) => 0,
        };
        // Missed: the prediction; else the update with the measurement.
        let state = match inputs.measurements.get(usize::from(row)) {
            None => prior,
            Some(z) => ekf::update(inputs.model, &prior, &innovation, z)
                .map_err(|error| StepError::Numerical { label, error })?,
        };
        // Room was checked before; the error path is unreachable but kept panic-free.
        let new_slot = next_store
            .push(Track { label, state, existence: T::zero(), unseen_scans })
            .map_err(|_| StepError::TrackStoreFull { capacity: K })?;
        let head = match source {
            Source::Track(old) => Some(self.source_head.at_mut(usize::from(old))),
            Source::Birth(cell) => self.birth_head.get_mut(usize::from(cell)),
        };
        if let Some(head) = head {
            *self.next_same_source.at_mut(usize::from(new_slot)) = *head;
            *head = new_slot;
        }
        *self.new_slot_measurement.at_mut(usize::from(new_slot)) = row;
        *self.new_slot_inherited.at_mut(usize::from(new_slot)) = inherits;
        Ok(new_slot)
    }

    /// The label, predicted Gaussian and innovation of `source`; a birth takes its candidate's label when
    /// `inherits`, else a fresh label unless the same measurement (or, undetected, the same cell) already
    /// gave one this scan.
    #[allow(clippy::type_complexity)]
    fn source_state<T: Real, M, G, const S: usize, const D: usize>(
        &mut self,
        inputs: &Inputs<'_, T, M, G, S, D, H, N, Z, K, B>,
        source: Source,
        row: u16,
        inherits: bool,
        next_label: &mut u32,
    ) -> Result<(TrackLabel, Gaussian<T, S>, Innovation<T, D>), StepError> {
        match source {
            Source::Track(old) => {
                let old = usize::from(old);
                let label = inputs.store.as_slice().get(old).map_or(TrackLabel(0), |track| track.label);
                let predicted = inputs.scores.predicted(old);
                Ok((label, predicted.state, predicted.innovation))
            }
            Source::Birth(cell) => {
                let cell = usize::from(cell);
                let prior = inputs.birth_cells.states.get(cell).copied().unwrap_or(Gaussian::ZERO);
                let innovation = inputs.birth_cells.innovations.get(cell).copied().unwrap_or(Innovation::EMPTY);
                let candidate = inputs.birth_cells.candidate.get(cell).copied().flatten();
                if let Some((_, Some(label))) = candidate.filter(|_| inherits) {
                    self.note_row_label(row, label);
                    return Ok((label, prior, innovation));
                }
                // One new object per measurement (or per cell when undetected): the same birth explained by
                // different cells' pdfs is one object with one label.
                let known = match self.birth_label_of_row.get_mut(usize::from(row)) {
                    Some(by_row) => Some(by_row),
                    None => self.birth_label_of_cell.get_mut(cell),
                };
                let Some(known) = known else { return Err(StepError::NoViableChild) };
                let label = match *known {
                    Some(label) => label,
                    None => {
                        let label = TrackLabel(*next_label);
                        *next_label = next_label.checked_add(1).ok_or(StepError::LabelsExhausted)?;
                        *known = Some(label);
                        label
                    }
                };
                // A candidate's first birth names it; the best child's, as children come best first.
                if let Some((group, None)) = candidate
                    && !self.candidate_labels.iter().any(|&(other, _)| other == group)
                {
                    // At most one entry per pool cell's group, so at most B: there is room.
                    let _ = self.candidate_labels.push((group, label));
                }
                self.note_row_label(row, label);
                Ok((label, prior, innovation))
            }
        }
    }

    /// Records `label` as the label of the object born from `row`, unless a better child gave one.
    fn note_row_label(&mut self, row: u16, label: TrackLabel) {
        if let Some(known @ None) = self.first_birth_label_of_row.get_mut(usize::from(row)) {
            *known = Some(label);
        }
    }

    /// Sorts the child's slots by label and keeps it, or merges it into an identical child kept earlier.
    fn keep_or_merge<T: Real, const S: usize>(
        &mut self,
        log_weight: T,
        count: usize,
        next_store: &TrackStore<T, S, K>,
        next_set: &mut HypothesisSet<T, N, H>,
        merged: &mut usize,
    ) {
        let tracks = next_store.as_slice();
        // count ≤ N by construction; `get_mut` keeps the step provably panic-free whatever the inlining.
        let Some(slots) = self.child_slots.get_mut(..count) else { return };
        // Labels are distinct within a child, so the order is unique.
        let label = |slot: u16| tracks.get(usize::from(slot)).map(|track| track.label);
        insertion_sort_by(slots, |&a, &b| label(a) < label(b));
        let mut hash = Fnv1a::new();
        for &slot in slots.iter() {
            hash.write(&slot.to_le_bytes());
        }
        let hash = hash.finish();
        let existing = next_set
            .as_mut_slice()
            .iter_mut()
            .zip(self.hashes.iter())
            .find(|(hypothesis, other)| **other == hash && hypothesis.slots() == &*slots);
        match existing {
            Some((hypothesis, _)) => {
                hypothesis.log_weight = log_add(hypothesis.log_weight, log_weight);
                *merged += 1;
            }
            None => {
                if let Ok(index) = next_set.push(Hypothesis::new(log_weight, slots)) {
                    *self.hashes.at_mut(index) = hash;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::association::{CLUTTER, ParentColumns};

    fn candidate(event: Event, assignment: [u16; 2]) -> Candidate<f64, 2> {
        Candidate { log_weight: 0.0, key: 0.0, sequence: 0, parent: 0, event, assignment }
    }

    #[test]
    fn a_child_is_read_back_through_its_layout() {
        // The parent holds tracks 5, 7, 9; the object at position 1 (track 7) is out of view.
        let parent = Hypothesis::<f64, 4>::new(0.0, &[5, 7, 9]);
        let mut columns = ParentColumns::<4>::new();
        for position in [0, 2] {
            columns.push(position).unwrap();
        }
        let mut work = Materialisation::<2, 4, 2, 16, 4>::new();
        let not_dropped = |_: u16| false;

        // A birth in cell 3 the sensor sees: row 0 takes column 1 (position 2), row 1 the birth column.
        let birth = Event::Birth { cell: 3 };
        let count =
            work.child_sources(&candidate(birth, [1, 2]), &parent, &columns.layout(birth, Some(3)), 2, not_dropped);
        assert_eq!(
            &work.child_sources[..count],
            &[(Source::Track(5), NONE), (Source::Track(7), NONE), (Source::Track(9), 0), (Source::Birth(3), 1)]
        );

        // The death of the object at position 0: its column takes nothing and it is in no child.
        let death = Event::Death { object: 0 };
        let count =
            work.child_sources(&candidate(death, [CLUTTER, 1]), &parent, &columns.layout(death, None), 2, not_dropped);
        assert_eq!(&work.child_sources[..count], &[(Source::Track(7), NONE), (Source::Track(9), 1)]);

        // A track dropped for a numerical failure is in no child either.
        let count = work.child_sources(
            &candidate(Event::None, [0, CLUTTER]),
            &parent,
            &columns.layout(Event::None, None),
            2,
            |slot| slot == 9,
        );
        assert_eq!(&work.child_sources[..count], &[(Source::Track(5), 0), (Source::Track(7), NONE)]);
    }
}
