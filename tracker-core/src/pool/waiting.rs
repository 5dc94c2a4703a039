//! Waiting candidates (docs/maths.md §5.8, "Births in clutter"): the cells of unexplained measurements that
//! the full birth pool did not keep. They are never offered as birth cells; at later scans an unexplained
//! measurement inside the gate of a waiting candidate *links* with it, and the pool gets the candidate's
//! posterior given both measurements instead of the new measurement's own single-frame cells:
//!
//! ```text
//! A = Σ_k α_k p_D ĝ_k(z) / λ_C            (k over the candidate's cells whose gate holds z)
//! α' = A / (A + 1 − α_g p_D)              α'_k = α' · α_k ĝ_k(z) / Σ_j α_j ĝ_j(z)
//! ```
//!
//! with each cell's state the EKF update of its prediction by z. This is the posterior probability that the
//! candidate exists and produced z (against z clutter, the candidate absent or missed), so a linked
//! candidate outranks the single-frame cells of the scan's clutter when the pool is full: which cells the
//! pool keeps stops depending on the order of the measurements. The cells are made from earlier scans only,
//! so the birth model of every scan is still fixed before it (§5.6's weights unchanged).

use crate::ekf::{self, Innovation};
use crate::gaussian::Gaussian;
use crate::model::{MeasurementModel, MotionModel};
use crate::pool::PoolCell;
use crate::real::Real;
use crate::sensor::Region;
use crate::tracker::in_field_of_view;
use crate::weight::WeightModel;
use nalgebra::SVector;

/// What linking needs at a scan: the motion model (to predict the waiting cells), the scan sensor's field
/// of view, its weight model (its gate, p_D and λ_C) and its p_D.
#[derive(Debug, Clone, Copy)]
pub struct Linking<'a, T: Real, M> {
    /// The tracker's motion model.
    pub motion: &'a M,
    /// The scan sensor's field of view.
    pub field_of_view: &'a Region<T>,
    /// The scan's weight model: ln(p_D ĝ / λ_C) and the gate.
    pub weights: &'a WeightModel<T>,
    /// The scan sensor's p_D.
    pub detection_probability: T,
}

/// One waiting cell: a pool cell (its `time` the measurement's, for its lifetime) and its state predicted
/// to `state_time`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct WaitingCell<T: Real, const S: usize> {
    /// The cell; its `state` is at `state_time`.
    pub cell: PoolCell<T, S>,
    /// The time of the cell's state (seconds since the tracker's epoch).
    pub state_time: f64,
    /// Whether the cell was in the field of view of the scan at `state_time`.
    pub in_view: bool,
}

/// A measurement's link: the waiting group and α'.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Link<T> {
    pub group: u32,
    pub probability: T,
}

/// At most `B` waiting cells.
#[derive(Debug, Clone, PartialEq)]
pub struct WaitingCells<T: Real, const S: usize, const B: usize> {
    cells: heapless::Vec<WaitingCell<T, S>, B>,
    /// The groups (candidates) that linked at this scan, removed at its end.
    linked: heapless::Vec<u32, B>,
}

impl<T: Real, const S: usize, const B: usize> Default for WaitingCells<T, S, B> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T: Real, const S: usize, const B: usize> WaitingCells<T, S, B> {
    /// None waiting.
    pub const fn new() -> Self {
        Self { cells: heapless::Vec::new(), linked: heapless::Vec::new() }
    }

    /// The waiting cells.
    pub fn cells(&self) -> &[WaitingCell<T, S>] {
        &self.cells
    }

    /// Removes every waiting cell.
    pub fn clear(&mut self) {
        self.cells.clear();
        self.linked.clear();
    }

    /// Forgets the cells past `lifetime` and predicts the others to `time` in place, noting whether the
    /// scan's sensor (`model`, `linking.field_of_view`) has them in view (a cell whose prediction or
    /// innovation fails is forgotten).
    pub(super) fn prepare<G: MeasurementModel<T, S, D>, M: MotionModel<T, S>, const D: usize>(
        &mut self,
        model: &G,
        linking: &Linking<'_, T, M>,
        time: f64,
        lifetime: f64,
    ) {
        self.linked.clear();
        self.cells.retain_mut(|waiting| {
            if !(time - waiting.cell.time <= lifetime) {
                return false;
            }
            let Ok(state) = ekf::predict(linking.motion, &waiting.cell.state, T::of_f64(time - waiting.state_time))
            else {
                return false;
            };
            let Ok(innovation) = ekf::innovation(model, &state) else { return false };
            waiting.cell.state = state;
            waiting.state_time = time;
            waiting.in_view = in_field_of_view(linking.field_of_view, model, &state, &innovation.predicted);
            true
        });
    }

    /// ln(p_D ĝ_k(z) / λ_C) of waiting cell `index` and its innovation; `None` outside the gate or when
    /// the innovation fails.
    fn log_ratio<G: MeasurementModel<T, S, D>, const D: usize>(
        &self,
        index: usize,
        model: &G,
        weights: &WeightModel<T>,
        z: &SVector<T, D>,
    ) -> Option<(T, Innovation<T, D>)> {
        let state = &self.cells.get(index)?.cell.state;
        let innovation = ekf::innovation(model, state).ok()?;
        let entry = weights.entry_of_residual(&innovation, &model.residual(z, &innovation.predicted));
        let log_ratio = entry + weights.finite_miss();
        log_ratio.is_finite_value().then_some((log_ratio, innovation))
    }

    /// The waiting candidate made before `time` that `z` (of the scan at `time`) links with best (largest
    /// α'), if any.
    pub(super) fn best_link<G: MeasurementModel<T, S, D>, M, const D: usize>(
        &self,
        model: &G,
        linking: &Linking<'_, T, M>,
        time: f64,
        z: &SVector<T, D>,
    ) -> Option<Link<T>> {
        let mut ratios = [T::zero(); B];
        for (index, ratio) in ratios.iter_mut().enumerate().take(self.cells.len()) {
            let earlier = self.cells.get(index).is_some_and(|waiting| waiting.cell.time < time);
            if !earlier {
                continue;
            }
            if let Some((log_ratio, _)) = self.log_ratio(index, model, linking.weights, z) {
                *ratio = crate::real::exp(log_ratio);
            }
        }
        let mut best: Option<Link<T>> = None;
        for (first, waiting) in self.cells.iter().enumerate() {
            let group = waiting.cell.group;
            if self.cells.iter().take(first).any(|earlier| earlier.cell.group == group) {
                continue;
            }
            let (mut evidence, mut alpha) = (T::zero(), T::zero());
            for (member, ratio) in self.cells.iter().zip(ratios).filter(|(member, _)| member.cell.group == group) {
                evidence += member.cell.probability * ratio;
                alpha += member.cell.probability;
            }
            let probability = evidence / (evidence + T::one() - alpha * linking.detection_probability);
            if evidence > T::zero()
                && probability.is_finite_value()
                && best.is_none_or(|link| probability > link.probability)
            {
                best = Some(Link { group, probability });
            }
        }
        best
    }

    /// Σ_k α_k ĝ_k(z) p_D / λ_C over `link`'s cells (the unnormalised evidence of its cells).
    pub(super) fn link_evidence<G: MeasurementModel<T, S, D>, const D: usize>(
        &self,
        link: Link<T>,
        model: &G,
        weights: &WeightModel<T>,
        z: &SVector<T, D>,
    ) -> T {
        let mut total = T::zero();
        for (index, waiting) in self.cells.iter().enumerate() {
            if waiting.cell.group == link.group
                && let Some((log_ratio, _)) = self.log_ratio(index, model, weights, z)
            {
                total += waiting.cell.probability * crate::real::exp(log_ratio);
            }
        }
        total
    }

    /// Waiting cell `index` of `link` updated by `z`, with its evidence α_k p_D ĝ_k(z) / λ_C; `None` for a
    /// cell of another candidate, outside the gate, or whose update fails.
    pub(super) fn linked_cell<G: MeasurementModel<T, S, D>, const D: usize>(
        &self,
        index: usize,
        link: Link<T>,
        model: &G,
        weights: &WeightModel<T>,
        z: &SVector<T, D>,
    ) -> Option<(Gaussian<T, S>, T)> {
        let waiting = self.cells.get(index).filter(|waiting| waiting.cell.group == link.group)?;
        let (log_ratio, innovation) = self.log_ratio(index, model, weights, z)?;
        let state = ekf::update(model, &waiting.cell.state, &innovation, z).ok()?;
        Some((state, waiting.cell.probability * crate::real::exp(log_ratio)))
    }

    /// The label of waiting candidate `group`, if it gave a birth before it waited.
    pub(super) fn label_of(&self, group: u32) -> Option<crate::store::TrackLabel> {
        self.cells.iter().find(|waiting| waiting.cell.group == group).and_then(|waiting| waiting.cell.label)
    }

    /// Labels the waiting cells of candidate `group` that hold no label.
    pub(super) fn label_group(&mut self, group: u32, label: crate::store::TrackLabel) {
        for waiting in
            self.cells.iter_mut().filter(|waiting| waiting.cell.group == group && waiting.cell.label.is_none())
        {
            waiting.cell.label = Some(label);
        }
    }

    /// Marks candidate `group` linked at this scan: it is removed at the scan's end and no cell of it gives
    /// way to a new one before.
    pub(super) fn mark_linked(&mut self, group: u32) {
        if !self.linked.contains(&group) {
            // At most B groups wait, so there is room.
            let _ = self.linked.push(group);
        }
    }

    /// Adds `cell` (state at `state_time`); when full, it takes the place of the first cell of smallest α
    /// (of a candidate not linked at this scan) unless that α is larger than the new one's.
    pub(super) fn offer(&mut self, cell: PoolCell<T, S>, state_time: f64) {
        let waiting = WaitingCell { cell, state_time, in_view: false };
        if self.cells.push(waiting).is_ok() {
            return;
        }
        let mut smallest: Option<(usize, T)> = None;
        for (index, other) in self.cells.iter().enumerate() {
            if self.linked.contains(&other.cell.group) {
                continue;
            }
            if smallest.is_none_or(|(_, probability)| other.cell.probability < probability) {
                smallest = Some((index, other.cell.probability));
            }
        }
        if let Some((index, probability)) = smallest
            && probability <= cell.probability
            && let Some(slot) = self.cells.get_mut(index)
        {
            *slot = waiting;
        }
    }

    /// Ends the scan at `time`: removes the candidates that linked, and applies to the others that were
    /// waiting before it the missed-detection update of their group's Bernoulli mixture,
    /// α_k (1 − p_D,k) / (1 − Σ_{j∈g} α_j p_D,j) with p_D,k = `detection_probability` in view and 0 out of it
    /// (docs/maths.md §5.8): a candidate the sensor looked at and did not see loses its α, as a pool cell
    /// does. Cells whose α reaches 0 are forgotten.
    pub(super) fn settle(&mut self, time: f64, detection_probability: T) {
        let linked = &self.linked;
        self.cells.retain(|waiting| !linked.contains(&waiting.cell.group));
        self.linked.clear();
        let p_d = |waiting: &WaitingCell<T, S>| {
            if waiting.in_view && waiting.cell.time < time { detection_probability } else { T::zero() }
        };
        let mut unseen = [T::one(); B];
        for (waiting, unseen) in self.cells.iter().zip(unseen.iter_mut()) {
            let mut seen = T::zero();
            for member in self.cells.iter().filter(|member| member.cell.group == waiting.cell.group) {
                seen += member.cell.probability * p_d(member);
            }
            *unseen = T::one() - seen;
        }
        for (waiting, unseen) in self.cells.iter_mut().zip(unseen) {
            let missed = T::one() - p_d(waiting);
            waiting.cell.probability = waiting.cell.probability * missed / unseen;
        }
        self.cells.retain(|waiting| waiting.cell.probability > T::zero());
    }
}
