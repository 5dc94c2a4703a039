//! A scan of the reference tracker: the birth cells as placed, the tables of every parent, the scores and the
//! recursive enumeration of every parent's children.

use super::*;
use tracker_core::tracker::{in_field_of_view, unseen_scans};

impl<M, G, const S: usize, const D: usize, const B: usize> ReferenceTracker<M, G, S, D, B>
where
    M: MotionModel<f64, S>,
    G: MeasurementModel<f64, S, D> + Clone,
{
    /// The birth cells as the placed sensor sees them (as the core's `birth_cells`).
    pub(super) fn birth_cells(&self, mut placed: PlacedScan<f64, G>, time: f64) -> Result<Scan<G, S, D>, StepError> {
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
            let in_view =
                in_field_of_view(&placed.detection.field_of_view, &placed.model, &gaussian, &innovation.predicted);
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
    pub(super) fn tables(
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
            let in_view = in_field_of_view(&detection.field_of_view, model, &state, &innovation.predicted);
            // Track loss as the core decides it: unseen when in view with no measurement in the gate.
            let row: Vec<f64> = measurements
                .iter()
                .map(|z| {
                    if in_view {
                        weights.entry_of_residual(&innovation, &model.residual(z, &innovation.predicted))
                    } else {
                        f64::NEG_INFINITY
                    }
                })
                .collect();
            let unseen = unseen_scans(track.unseen, in_view, &row);
            let lost = self.config.track_loss.is_lost(unseen);
            column(&innovation, in_view && !lost, None);
            predicted.push(Predicted { state, innovation, in_view: in_view && !lost, unseen, lost });
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
    pub(super) fn enumerate_parent(
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
                if children.work_exceeded() {
                    return Err(ReferenceError::WorkBudgetExceeded { budget: self.max_work });
                }
                return Err(StepError::ChildBudgetExceeded { budget: self.max_children }.into());
            }
        }
        Ok(())
    }
}
