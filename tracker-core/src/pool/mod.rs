//! The measurement-driven birth pool (docs/maths.md §5.8): birth cells made from the measurements of
//! earlier scans that no track explains, so that new objects are born wherever a sensor sees them, without
//! birth cells fixed in advance.
//!
//! After every scan, each measurement z gets r_U(z), the posterior probability that no object took it
//! (the weight of the kept hypotheses that call it clutter). A measurement with r_U(z) at least
//! `min_unexplained` becomes the cells of its birth density ([`BirthGeometry::birth_components`](crate::BirthGeometry::birth_components): the
//! measurement's admissible region as a Gaussian mixture), with a birth probability
//!
//! ```text
//! α_z = min(max_probability, expected_births · r_U(z) / Σ_z' r_U(z'))
//! ```
//!
//! shared among its components by their weights. At the next scans the cells are predicted to the scan's
//! time and are birth cells of the independent birth model (§5.6): the birth model of a scan is known
//! before the scan, so the recursion's weights are those of §4 and §5.6 unchanged. A cell lives for
//! `lifetime` seconds after its measurement; each scan its α is multiplied by the probability that it gave
//! no birth in that scan and, when the scan's sensor had it in view, by the Bernoulli missed-detection factor
//! (1 − p_D) / (1 − α p_D). When the pool is full the cells with the smallest α give way.

pub mod tracklets;
pub mod waiting;

use crate::ekf;
use crate::gaussian::Gaussian;
use crate::model::{AdmissibleRegion, BirthComponent, MeasurementModel, MotionModel};
use crate::real::Real;
use crate::store::TrackLabel;
use nalgebra::SVector;
pub use tracklets::{MAX_LINKED_FRAMES, TRACKLET_FRAMES, TRACKLET_POINTS, TrackletBirths, TrackletBuffer};
pub use waiting::{Linking, WaitingCell, WaitingCells};

/// The settings of measurement-driven births.
///
/// # Examples
/// ```
/// use tracker_core::model::AdmissibleRegion;
/// use tracker_core::pool::MeasuredBirths;
/// let births = MeasuredBirths::new(AdmissibleRegion::<f64>::planar(2.0));
/// assert!(births.validate().is_ok());
/// assert!(MeasuredBirths { max_probability: 1.0, ..births }.validate().is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct MeasuredBirths<T> {
    /// The admissible region each measurement's birth density is cut from.
    pub region: AdmissibleRegion<T>,
    /// Expected births per scan, λ_B, shared among the scan's unexplained measurements by their r_U.
    pub expected_births: T,
    /// The largest α of one measurement's cells together, in (0, 1).
    pub max_probability: T,
    /// The smallest r_U for a measurement to make cells, in [0, 1].
    pub min_unexplained: T,
    /// Seconds a cell lives after its measurement.
    pub lifetime: f64,
    /// Births from tracklets for sensors that measure directions (docs/maths.md §5.10): a measurement
    /// that links with earlier frames gives the cells of its tracklet's admissible region instead of its
    /// own. `None`: single-frame cells only.
    #[cfg_attr(feature = "serde", serde(default))]
    pub tracklets: Option<TrackletBirths<T>>,
    /// Whether the cells the full pool does not keep wait for a later measurement to link with
    /// ([`waiting`], docs/maths.md §5.8 "Births in clutter"). `false`: they are dropped.
    #[cfg_attr(feature = "serde", serde(default))]
    pub link_waiting: bool,
}

impl<T: Real> MeasuredBirths<T> {
    /// Settings with `region`: λ_B = 0.1, α at most 0.1 per measurement, r_U ≥ 0.5, cells living 600 s.
    pub fn new(region: AdmissibleRegion<T>) -> Self {
        Self {
            region,
            expected_births: T::of_f64(0.1),
            max_probability: T::of_f64(0.1),
            min_unexplained: T::of_f64(0.5),
            lifetime: 600.0,
            tracklets: None,
            link_waiting: false,
        }
    }

    /// Checks the settings.
    ///
    /// # Errors
    /// A static description of the first invalid field.
    pub fn validate(&self) -> Result<(), &'static str> {
        self.region.validate()?;
        if !(self.expected_births.is_finite_value() && self.expected_births > T::zero()) {
            return Err("measured births: expected_births must be finite and > 0");
        }
        if !(self.max_probability > T::zero() && self.max_probability < T::one()) {
            return Err("measured births: max_probability must be in (0, 1)");
        }
        if !(self.min_unexplained >= T::zero() && self.min_unexplained <= T::one()) {
            return Err("measured births: min_unexplained must be in [0, 1]");
        }
        if !(self.lifetime.is_finite() && self.lifetime > 0.0) {
            return Err("measured births: lifetime must be finite and > 0");
        }
        match &self.tracklets {
            Some(tracklets) => tracklets.validate(),
            None => Ok(()),
        }
    }
}

/// One cell of the pool: a birth density at the time of the measurement it was made from, and its α.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PoolCell<T: Real, const S: usize> {
    /// The birth density at `time`.
    pub state: Gaussian<T, S>,
    /// Time of the measurement (seconds since the tracker's epoch).
    pub time: f64,
    /// α: the probability that the cell gives birth at a scan.
    pub probability: T,
    /// The candidate object the cell is one alternative of: the cells of one measurement's (or one
    /// tracklet's) mixture share it and age as one Bernoulli (docs/maths.md §5.8).
    #[cfg_attr(feature = "serde", serde(default))]
    pub group: u32,
    /// The label the candidate's first birth was given (docs/maths.md §5.8, "One label per candidate"): a
    /// later birth from its cells, in a hypothesis that does not hold it, takes it too. `None` until then.
    #[cfg_attr(feature = "serde", serde(default))]
    pub label: Option<TrackLabel>,
}

/// What one pool update did.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PoolUpdate {
    /// Cells made from this scan's measurements and put in the pool.
    pub added: usize,
    /// Cells that gave way because the pool was full: old ones removed, or new ones not put in.
    pub evicted: usize,
    /// Cells past their lifetime, or whose α fell to zero.
    pub expired: usize,
    /// Unexplained measurements that gave no birth density (an empty admissible region, a non-finite
    /// result, more components than the pool holds).
    pub without_density: usize,
    /// Unexplained measurements whose cells came from a tracklet (docs/maths.md §5.10).
    pub tracklets: usize,
    /// Unexplained measurements whose cells came from a waiting candidate they linked with (§5.8).
    #[cfg_attr(feature = "serde", serde(default))]
    pub linked: usize,
    /// New cells the full pool did not keep that wait for a link.
    #[cfg_attr(feature = "serde", serde(default))]
    pub waiting: usize,
}

/// What one scan tells the pool: its time and measurements, each measurement's r_U and each pool cell's
/// probability of having given birth in the scan (docs/maths.md §5.8).
#[derive(Debug, Clone, Copy)]
pub struct ScanUse<'a, T, const D: usize> {
    /// Time of the scan (seconds since the tracker's epoch).
    pub time: f64,
    /// The scan's sensor (its index in the network; 0 for a single sensor).
    pub sensor: usize,
    /// The scan's measurements.
    pub measurements: &'a [SVector<T, D>],
    /// Per measurement, r_U.
    pub unexplained: &'a [T],
    /// Per pool cell (in the pool's order before the update), the probability that it gave birth.
    pub born: &'a [T],
    /// Per pool cell (same order), the scan sensor's p_D when the cell was in its field of view, else 0
    /// (missing entries count as 0): a cell in view that gave no birth was missed (docs/maths.md §5.8).
    pub detection: &'a [T],
    /// Per measurement, the label of the object born from it in the best kept child that gave it one
    /// (missing entries: none). A candidate made from the measurement takes it (§5.8, "One label per
    /// candidate").
    pub labels: &'a [Option<TrackLabel>],
}

/// Where a scan's new cells go: the scan's time, the pool's capacity, whether unkept cells wait.
#[derive(Debug, Clone, Copy)]
struct Place {
    time: f64,
    capacity: usize,
    link_waiting: bool,
    /// The label of the object born from the measurement in other hypotheses, if any.
    label: Option<TrackLabel>,
}

/// At most `B` birth cells made from measurements (docs/maths.md §5.8).
#[derive(Debug, Clone, PartialEq)]
pub struct BirthPool<T: Real, const S: usize, const B: usize> {
    cells: heapless::Vec<PoolCell<T, S>, B>,
    /// The earlier frames' unexplained directions, for tracklets.
    tracklets: TrackletBuffer<T>,
    /// The cells the full pool did not keep, waiting for a link.
    waiting: WaitingCells<T, S, B>,
    /// The group of the next measurement's cells (wrapping: a group lives at most `lifetime`, far fewer
    /// than 2³² measurements).
    next_group: u32,
}

impl<T: Real, const S: usize, const B: usize> Default for BirthPool<T, S, B> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T: Real, const S: usize, const B: usize> BirthPool<T, S, B> {
    /// An empty pool.
    pub const fn new() -> Self {
        Self {
            cells: heapless::Vec::new(),
            tracklets: TrackletBuffer::new(),
            waiting: WaitingCells::new(),
            next_group: 0,
        }
    }

    /// The cells, oldest first.
    pub fn cells(&self) -> &[PoolCell<T, S>] {
        &self.cells
    }

    /// Whether the pool holds nothing: no cell, no waiting cell, no tracklet frame.
    pub fn is_empty(&self) -> bool {
        self.cells.is_empty() && self.waiting.cells().is_empty() && self.tracklets.is_empty()
    }

    /// The cells waiting for a link.
    pub fn waiting(&self) -> &[WaitingCell<T, S>] {
        self.waiting.cells()
    }

    /// The earlier frames kept for tracklets.
    pub fn tracklet_frames(&self) -> &TrackletBuffer<T> {
        &self.tracklets
    }

    /// Removes every cell and tracklet frame.
    pub fn clear(&mut self) {
        self.cells.clear();
        self.tracklets.clear();
        self.waiting.clear();
        self.next_group = 0;
    }

    /// The cells predicted to `time` with `motion`, with their α; a cell whose prediction fails is left
    /// out of this scan (it stays in the pool).
    pub fn predicted<'a, M: MotionModel<T, S>>(
        &'a self,
        motion: &'a M,
        time: f64,
    ) -> impl Iterator<Item = (usize, Gaussian<T, S>, T)> + 'a {
        self.cells.iter().enumerate().filter_map(move |(index, cell)| {
            let state = ekf::predict(motion, &cell.state, T::of_f64(time - cell.time)).ok()?;
            Some((index, state, cell.probability))
        })
    }

    /// Gives each candidate (group) of `labels` the label its first birth was given, unless it holds one
    /// (docs/maths.md §5.8, "One label per candidate"): its cells in the pool and those waiting. O(B²).
    pub fn adopt_labels(&mut self, labels: &[(u32, TrackLabel)]) {
        for &(group, label) in labels {
            for cell in self.cells.iter_mut().filter(|cell| cell.group == group && cell.label.is_none()) {
                cell.label = Some(label);
            }
            self.waiting.label_group(group, label);
        }
    }

    /// Updates the pool after `scan`: each cell's α times 1 − `born[l]` (the posterior probability that
    /// cell l gave birth in the scan; missing entries count as 0) and (1 − p_D) / (1 − α p_D) with p_D =
    /// `detection[l]` (docs/maths.md §5.8), cells past their lifetime removed, then
    /// the cells of every measurement whose `unexplained[z]` (r_U) is at least the settings' minimum added,
    /// made by `model` (the measurement model placed at the scan), or, when it links with a waiting
    /// candidate (`settings.link_waiting`, with `linking`), that candidate's posterior. At most
    /// `capacity` (≤ `B`) cells are kept: the smallest α give way, the older first among equals.
    pub fn update<G: MeasurementModel<T, S, D>, M: MotionModel<T, S>, const D: usize>(
        &mut self,
        settings: &MeasuredBirths<T>,
        capacity: usize,
        model: &G,
        linking: &Linking<'_, T, M>,
        scan: &ScanUse<'_, T, D>,
    ) -> PoolUpdate {
        let ScanUse { time, sensor, measurements, unexplained, born, detection, labels } = *scan;
        let capacity = capacity.min(B);
        let mut update = PoolUpdate::default();
        // Age the old cells, each group as one Bernoulli (docs/maths.md §5.8).
        let factors = self.ageing_factors(born, detection);
        let mut index = 0;
        let mut old_index = 0;
        while index < self.cells.len() {
            let (unborn, missed, unseen) = factors.get(old_index).copied().unwrap_or((T::one(), T::one(), T::one()));
            old_index += 1;
            let Some(cell) = self.cells.get_mut(index) else { break };
            cell.probability = cell.probability * unborn * missed / unseen;
            if !(time - cell.time <= settings.lifetime && cell.probability > T::zero()) {
                self.remove_at(index);
                update.expired += 1;
            } else {
                index += 1;
            }
        }
        while self.cells.len() > capacity {
            self.remove_smallest();
            update.evicted += 1;
        }
        if settings.link_waiting {
            self.waiting.prepare(model, linking, time, settings.lifetime);
        }
        // Σ_z r_U(z) over the measurements that make cells.
        let minimum = settings.min_unexplained;
        let total = unexplained
            .iter()
            .take(measurements.len())
            .fold(T::zero(), |sum, &r_u| if r_u >= minimum && r_u > T::zero() { sum + r_u } else { sum });
        if !(total > T::zero()) {
            self.waiting.settle(time, linking.detection_probability);
            self.record_frame(settings, sensor, model, scan);
            return update;
        }
        for (row, (z, &r_u)) in measurements.iter().zip(unexplained).enumerate() {
            if !(r_u >= minimum && r_u > T::zero()) {
                continue;
            }
            let label = labels.get(row).copied().flatten();
            let share = settings.expected_births * r_u / total;
            let alpha = if share < settings.max_probability { share } else { settings.max_probability };
            let place = Place { time, capacity, link_waiting: settings.link_waiting, label };
            if settings.link_waiting
                && let Some(link) = self.waiting.best_link(model, linking, time, z)
                && self.add_linked(link, model, linking.weights, z, &place, &mut update)
            {
                update.linked += 1;
                continue;
            }
            self.add_own(settings, sensor, model, z, alpha, &place, &mut update);
        }
        self.waiting.settle(time, linking.detection_probability);
        self.record_frame(settings, sensor, model, scan);
        update
    }

    /// Per cell (in order), the factors (1 − b_g, 1 − p_D,k, 1 − Σ_{j∈g} α_j p_D,j) of the missed-detection
    /// and no-birth update of its group's Bernoulli mixture (docs/maths.md §5.8),
    ///
    /// ```text
    /// α_k ← α_k (1 − b_g) (1 − p_D,k) / (1 − Σ_{j∈g} α_j p_D,j),     b_g = Σ_{j∈g} b_j
    /// ```
    ///
    /// with `born[j]` = b_j and `detection[j]` = p_D,j (missing entries 0, each clamped into [0, 1]). A
    /// group of one cell gives the single Bernoulli's α (1 − b)(1 − p_D)/(1 − α p_D). O(B²), B the cap.
    fn ageing_factors(&self, born: &[T], detection: &[T]) -> [(T, T, T); B] {
        let at = |values: &[T], index: usize| unit(values.get(index).copied().unwrap_or(T::zero()));
        let mut factors = [(T::one(), T::one(), T::one()); B];
        for (index, (cell, factor)) in self.cells.iter().zip(factors.iter_mut()).enumerate() {
            let mut given_birth = T::zero();
            let mut seen = T::zero();
            for (other, member) in self.cells.iter().enumerate().filter(|(_, member)| member.group == cell.group) {
                given_birth += at(born, other);
                seen += member.probability * at(detection, other);
            }
            let p_d = at(detection, index);
            *factor = (T::one() - unit(given_birth), T::one() - p_d, T::one() - unit(seen));
        }
        factors
    }

    /// Adds the cells of waiting candidate `link` updated by `z` (docs/maths.md §5.8, "Births in clutter"),
    /// a new group; false when none could be formed. Never inlined, and without a buffer of components:
    /// the EKF update's frame is on the stack only here.
    #[inline(never)]
    fn add_linked<G: MeasurementModel<T, S, D>, const D: usize>(
        &mut self,
        link: waiting::Link<T>,
        model: &G,
        weights: &crate::weight::WeightModel<T>,
        z: &SVector<T, D>,
        place: &Place,
        update: &mut PoolUpdate,
    ) -> bool {
        let total = self.waiting.link_evidence(link, model, weights, z);
        if !(total > T::zero()) {
            return false;
        }
        self.waiting.mark_linked(link.group);
        // The linked cells are the same candidate's: they keep its label (else the measurement's).
        let label = self.waiting.label_of(link.group).or(place.label);
        let group = self.next_group;
        self.next_group = self.next_group.wrapping_add(1);
        for index in 0..self.waiting.cells().len() {
            if let Some((state, evidence)) = self.waiting.linked_cell(index, link, model, weights, z) {
                let probability = link.probability * evidence / total;
                let cell = PoolCell { state, time: place.time, probability, group, label };
                self.put(cell, place, update);
            }
        }
        true
    }

    /// Adds the cells of unexplained `z` with birth probability `alpha`: its tracklet's or its own region's
    /// (§5.7, §5.10), a new group; nothing (counted) when it gives none, or when it awaits its tracklet's
    /// link. Never inlined: its buffer of components is on the stack only here.
    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    fn add_own<G: MeasurementModel<T, S, D>, const D: usize>(
        &mut self,
        settings: &MeasuredBirths<T>,
        sensor: usize,
        model: &G,
        z: &SVector<T, D>,
        alpha: T,
        place: &Place,
        update: &mut PoolUpdate,
    ) {
        let mut components = [BirthComponent::<T, S>::ZERO; B];
        let linked = self.tracklet_components(settings, sensor, place.time, model, z, &mut components);
        update.tracklets += usize::from(linked.is_some());
        let awaits_link = settings.tracklets.is_some_and(|t| !t.single_frame) && model.sky_point(z).is_some();
        if linked.is_none() && awaits_link {
            return;
        }
        let own = || model.birth_components(z, &settings.region, &mut components);
        let count = match linked.map_or_else(own, Ok) {
            Ok(count) if count > 0 => count.min(B),
            _ => {
                update.without_density += 1;
                return;
            }
        };
        let group = self.next_group;
        self.next_group = self.next_group.wrapping_add(1);
        for component in components.iter().take(count) {
            let probability = alpha * component.weight;
            let cell = PoolCell { state: component.state, time: place.time, probability, group, label: place.label };
            self.put(cell, place, update);
        }
    }

    /// Puts a new cell in the pool (§5.8: the smallest α gives way); a new cell not kept (this one, or one of
    /// this scan's that gave way) waits for a link when waiting is on.
    fn put(&mut self, cell: PoolCell<T, S>, place: &Place, update: &mut PoolUpdate) {
        if !(cell.probability > T::zero()) {
            return;
        }
        let (kept, gave_way) = self.insert(cell, place.capacity);
        update.added += usize::from(kept);
        update.evicted += usize::from(gave_way.is_some() || !kept);
        let unkept = if kept { gave_way.filter(|old| old.time == place.time) } else { Some(cell) };
        if let Some(unkept) = unkept.filter(|_| place.link_waiting) {
            self.waiting.offer(unkept, place.time);
            update.waiting += 1;
        }
    }

    /// The cells of the best tracklet through `z` (docs/maths.md §5.10), written to `out`: `Some(count)`
    /// when tracklets are on, `z` is a direction and it links with the sensor's earlier frames and its
    /// region gives cells; `None` otherwise (the caller falls back to `z`'s own cells). Never inlined: its
    /// frame (the linked arcs and the attributable) is on the stack only when tracklets are on.
    #[inline(never)]
    fn tracklet_components<G: MeasurementModel<T, S, D>, const D: usize>(
        &self,
        settings: &MeasuredBirths<T>,
        sensor: usize,
        time: f64,
        model: &G,
        z: &SVector<T, D>,
        out: &mut [BirthComponent<T, S>],
    ) -> Option<usize> {
        let tracklets = settings.tracklets.as_ref()?;
        let point = model.sky_point(z)?;
        let attributable = self.tracklets.link(sensor, time, &point, tracklets)?;
        let count = model.tracklet_components(&attributable, &point.observer, tracklets, out).ok()?;
        (count > 0).then_some(count)
    }

    /// Keeps this scan's unexplained directions (r_U at least the minimum) for later tracklets, and
    /// forgets frames older than the tracklets' span. Nothing when tracklets are off.
    fn record_frame<G: MeasurementModel<T, S, D>, const D: usize>(
        &mut self,
        settings: &MeasuredBirths<T>,
        sensor: usize,
        model: &G,
        scan: &ScanUse<'_, T, D>,
    ) {
        let Some(tracklets) = &settings.tracklets else {
            return;
        };
        self.tracklets.expire(scan.time, tracklets.max_span);
        let minimum = settings.min_unexplained;
        let unexplained = |(z, &r_u): (&SVector<T, D>, &T)| {
            if !(r_u >= minimum && r_u > T::zero()) {
                return None;
            }
            model.sky_point(z).map(|point| (point, r_u))
        };
        let pairs = || scan.measurements.iter().zip(scan.unexplained).filter_map(unexplained);
        // One σ per frame: the first direction's (a sensor's directions share it, up to the 1/cos δ of
        // az/el converted to right ascension).
        if let Some((first, _)) = pairs().next() {
            self.tracklets.record(sensor, scan.time, first.sigma, pairs().map(|(point, r_u)| (point.angles, r_u)));
        }
    }

    /// Adds `cell`, making room by removing the (oldest) cell of smallest α unless that α is larger than
    /// the new one's; returns whether `cell` was kept and the cell that gave way to it.
    fn insert(&mut self, cell: PoolCell<T, S>, capacity: usize) -> (bool, Option<PoolCell<T, S>>) {
        if self.cells.len() < capacity {
            return (self.cells.push(cell).is_ok(), None);
        }
        match self.smallest() {
            Some((index, probability)) if probability <= cell.probability => {
                let removed = self.cells.get(index).copied();
                self.remove_at(index);
                (self.cells.push(cell).is_ok(), removed)
            }
            _ => (false, None),
        }
    }

    /// The first cell of smallest α (the oldest among equals) and its α.
    fn smallest(&self) -> Option<(usize, T)> {
        let mut smallest: Option<(usize, T)> = None;
        for (index, cell) in self.cells.iter().enumerate() {
            if smallest.is_none_or(|(_, probability)| cell.probability < probability) {
                smallest = Some((index, cell.probability));
            }
        }
        smallest
    }

    fn remove_smallest(&mut self) {
        if let Some((index, _)) = self.smallest() {
            self.remove_at(index);
        }
    }

    /// Removes the cell at `index`, keeping the order of the others (nothing when there is none).
    fn remove_at(&mut self, index: usize) {
        if let Some(tail) = self.cells.get_mut(index..)
            && !tail.is_empty()
        {
            tail.rotate_left(1);
            self.cells.pop();
        }
    }
}

/// `x` clamped into [0, 1] (NaN to 0).
fn unit<T: Real>(x: T) -> T {
    if x > T::one() {
        T::one()
    } else if x > T::zero() {
        x
    } else {
        T::zero()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{ConstantVelocity, PositionMeasurement};
    use crate::weight::WeightModel;
    use crate::{BirthDetection, Region, Sensor};

    /// Linking for the tests: constant velocity, p_D 0.8, λ_C = 1 / 100, gate d² ≤ 16.
    fn linking() -> Linking<'static, f64, ConstantVelocity<f64>> {
        Linking { motion: &MOTION, field_of_view: &FIELD, weights: &WEIGHTS, detection_probability: 0.8 }
    }
    static MOTION: ConstantVelocity<f64> = ConstantVelocity { acceleration_noise: 0.01 };
    static FIELD: Region<f64> = Region::Rectangle { min: [0.0, 0.0], max: [10.0, 10.0] };
    static WEIGHTS: std::sync::LazyLock<WeightModel<f64>> = std::sync::LazyLock::new(|| {
        let sensor = Sensor {
            detection_probability: 0.8,
            clutter_rate: 1.0,
            field_of_view: Region::Rectangle { min: [0.0, 0.0], max: [10.0, 10.0] },
        };
        WeightModel::new(&sensor, Some(16.0), 0.0, 0, BirthDetection::AllDetected, 0.0)
    });

    fn settings() -> MeasuredBirths<f64> {
        MeasuredBirths {
            expected_births: 1.0,
            max_probability: 0.3,
            min_unexplained: 0.5,
            lifetime: 10.0,
            ..MeasuredBirths::new(AdmissibleRegion::planar(1.0))
        }
    }

    fn scan<'a>(time: f64, zs: &'a [SVector<f64, 2>], r_u: &'a [f64], born: &'a [f64]) -> ScanUse<'a, f64, 2> {
        ScanUse { time, sensor: 0, measurements: zs, unexplained: r_u, born, detection: &[], labels: &[] }
    }

    #[test]
    fn unexplained_measurements_make_cells_with_alpha_shared_by_r_u_and_capped() {
        let model = PositionMeasurement::isotropic(0.5);
        let zs = [SVector::from([1.0, 2.0]), SVector::from([5.0, 5.0]), SVector::from([9.0, 0.0])];
        let mut pool = BirthPool::<f64, 4, 4>::new();
        // r_U 0.9 and 0.3 (below the minimum) and 0.1: only the first makes a cell, α = min(0.3, 1 · 0.9 / 0.9).
        let update = pool.update(&settings(), 4, &model, &linking(), &scan(1.0, &zs, &[0.9, 0.3, 0.1], &[]));
        assert_eq!((update.added, update.evicted, update.expired), (1, 0, 0));
        assert_eq!(pool.cells()[0].probability, 0.3);
        assert_eq!(pool.cells()[0].state.mean, SVector::from([1.0, 2.0, 0.0, 0.0]));
        // Two unexplained measurements share λ_B = 1: α = 0.6 / 1.1 and 0.5 / 1.1, capped at 0.3.
        let update = pool.update(&settings(), 4, &model, &linking(), &scan(2.0, &zs[1..], &[0.6, 0.5], &[0.5]));
        assert_eq!(update.added, 2);
        let alphas: std::vec::Vec<f64> = pool.cells().iter().map(|c| c.probability).collect();
        assert_eq!(alphas, [0.15, 0.3, 0.3], "the first cell gave birth with probability 1/2");
    }

    #[test]
    fn a_cell_in_view_that_gave_no_birth_was_missed() {
        let model = PositionMeasurement::isotropic(0.5);
        let zs = [SVector::from([1.0, 2.0]), SVector::from([5.0, 5.0])];
        let mut pool = BirthPool::<f64, 4, 4>::new();
        let settings = MeasuredBirths { max_probability: 0.9, ..settings() };
        // Two cells of α = 0.5 each (r_U 1 and 1 share λ_B = 1).
        pool.update(&settings, 4, &model, &linking(), &scan(0.0, &zs, &[1.0, 1.0], &[]));
        // The first in view of a sensor of p_D 0.8, no birth: 0.5 · 0.2 / (1 − 0.4) = 1/6; the second out
        // of view and born with probability 0.2: 0.5 · 0.8 = 0.4.
        let in_view = ScanUse {
            time: 1.0,
            sensor: 0,
            measurements: &[],
            unexplained: &[],
            born: &[0.0, 0.2],
            detection: &[0.8, 0.0],
            labels: &[],
        };
        pool.update(&settings, 4, &model, &linking(), &in_view);
        let alphas: std::vec::Vec<f64> = pool.cells().iter().map(|c| c.probability).collect();
        assert!((alphas[0] - 1.0 / 6.0).abs() < 1e-15 && (alphas[1] - 0.4).abs() < 1e-15, "{alphas:?}");
        // p_D = 1 in view: the candidate would have been seen, so the cell is gone.
        let certain = ScanUse { detection: &[1.0, 0.0], born: &[], ..in_view };
        let update = pool.update(&settings, 4, &model, &linking(), &ScanUse { time: 2.0, ..certain });
        assert_eq!((update.expired, pool.cells().len()), (1, 1));
    }

    #[test]
    fn the_cells_of_one_measurement_age_as_one_bernoulli() {
        let model = PositionMeasurement::isotropic(0.5);
        let mut pool = BirthPool::<f64, 4, 4>::new();
        let settings = MeasuredBirths { max_probability: 0.9, ..settings() };
        // Two groups: cells 0 and 1 one candidate (α 0.2 + 0.3), cell 2 another (α 0.4).
        for (probability, group) in [(0.2, 7), (0.3, 7), (0.4, 8)] {
            let cell = PoolCell { state: Gaussian::default(), time: 0.0, probability, group, label: None };
            assert!(pool.cells.push(cell).is_ok());
        }
        // Cell 0 gave birth with probability 0.5: its sibling gave none in that child, but the candidate is
        // now a track there, so both lose the factor 1 − 0.5; cell 2 is in view of p_D 0.5 and was missed.
        let ageing = ScanUse {
            time: 1.0,
            sensor: 0,
            measurements: &[],
            unexplained: &[],
            born: &[0.5, 0.0, 0.0],
            detection: &[0.0, 0.0, 0.5],
            labels: &[],
        };
        pool.update(&settings, 4, &model, &linking(), &ageing);
        let alphas: std::vec::Vec<f64> = pool.cells().iter().map(|c| c.probability).collect();
        assert_eq!(alphas, [0.1, 0.15, 0.4 * 0.5 / (1.0 - 0.2)]);
        // The group's cell 1 in view (p_D 0.8) and cell 0 not: the mixture's missed update moves the
        // group's mass to cell 0, α_k (1 − p_D,k) / (1 − Σ α_j p_D,j) with Σ = 0.15 · 0.8.
        let missed = ScanUse { born: &[], detection: &[0.0, 0.8, 0.0], time: 2.0, ..ageing };
        pool.update(&settings, 4, &model, &linking(), &missed);
        let alphas: std::vec::Vec<f64> = pool.cells().iter().map(|c| c.probability).collect();
        let unseen = 1.0 - 0.15 * 0.8;
        assert!(
            (alphas[0] - 0.1 / unseen).abs() < 1e-15 && (alphas[1] - 0.15 * 0.2 / unseen).abs() < 1e-15,
            "{alphas:?}"
        );
        // Cells of one measurement share a fresh group.
        let zs = [SVector::from([1.0, 2.0]), SVector::from([5.0, 5.0])];
        pool.clear();
        pool.update(&settings, 4, &model, &linking(), &scan(3.0, &zs, &[1.0, 1.0], &[]));
        let groups: std::vec::Vec<u32> = pool.cells().iter().map(|c| c.group).collect();
        assert_eq!(groups, [0, 1]);
    }

    #[test]
    fn a_cell_the_full_pool_does_not_keep_waits_and_a_later_measurement_links_with_it() {
        let model = PositionMeasurement::isotropic(0.5);
        let settings = MeasuredBirths { link_waiting: true, ..settings() };
        let mut pool = BirthPool::<f64, 4, 2>::new();
        // Two candidates of α 0.3 for a pool of one: the first gives way to the second and waits.
        let zs = [SVector::from([1.0, 2.0]), SVector::from([5.0, 5.0])];
        let update = pool.update(&settings, 1, &model, &linking(), &scan(0.0, &zs, &[1.0, 1.0], &[]));
        assert_eq!((update.added, update.evicted, update.waiting), (2, 1, 1));
        assert_eq!(pool.cells()[0].state.mean, SVector::from([5.0, 5.0, 0.0, 0.0]));
        assert_eq!(pool.waiting()[0].cell.state.mean, SVector::from([1.0, 2.0, 0.0, 0.0]));
        // One second later a measurement at the waiting candidate's predicted position links with it:
        // S = P_position + R = (0.25 + 1 + q/3) + 0.25, ĝ = 1 / (2π S), λ_C = 1/100, p_D = 0.8.
        let z = [SVector::from([1.0, 2.0])];
        let update = pool.update(&settings, 1, &model, &linking(), &scan(1.0, &z, &[1.0], &[]));
        assert_eq!(update.linked, 1);
        let s = 0.25 + 1.0 + 0.01 / 3.0 + 0.25;
        let evidence = 0.3 * 0.8 / (2.0 * core::f64::consts::PI * s) / 0.01;
        let expected = evidence / (evidence + 1.0 - 0.3 * 0.8);
        let linked = pool.cells().iter().find(|c| c.time == 1.0).expect("the linked cell is kept");
        assert!((linked.probability - expected).abs() < 1e-12, "{} against {expected}", linked.probability);
        assert_eq!((linked.state.mean[0], linked.state.mean[1]), (1.0, 2.0));
        assert!(pool.waiting().is_empty(), "the linked candidate no longer waits");
    }

    #[test]
    fn a_waiting_candidate_in_view_and_not_linked_was_missed() {
        let model = PositionMeasurement::isotropic(0.5);
        let settings = MeasuredBirths { link_waiting: true, ..settings() };
        let mut pool = BirthPool::<f64, 4, 2>::new();
        let zs = [SVector::from([1.0, 2.0]), SVector::from([5.0, 5.0])];
        pool.update(&settings, 1, &model, &linking(), &scan(0.0, &zs, &[1.0, 1.0], &[]));
        // A scan with nothing near it: α 0.3 (1 − 0.8) / (1 − 0.3 · 0.8).
        let far = [SVector::from([9.0, 9.0])];
        pool.update(&settings, 1, &model, &linking(), &scan(1.0, &far, &[0.0], &[]));
        let waiting = pool.waiting().iter().find(|w| w.cell.time == 0.0).expect("still waiting");
        assert!((waiting.cell.probability - 0.3 * 0.2 / (1.0 - 0.24)).abs() < 1e-15);
        // Without linking nothing waits.
        let mut plain = BirthPool::<f64, 4, 2>::new();
        let off = MeasuredBirths { link_waiting: false, ..settings };
        let update = plain.update(&off, 1, &model, &linking(), &scan(0.0, &zs, &[1.0, 1.0], &[]));
        assert_eq!((update.waiting, plain.waiting().len()), (0, 0));
    }

    #[test]
    fn a_full_pool_keeps_the_largest_alphas_and_old_cells_expire() {
        let model = PositionMeasurement::isotropic(0.5);
        let zs = [SVector::from([0.0, 0.0]), SVector::from([1.0, 0.0]), SVector::from([2.0, 0.0])];
        let mut pool = BirthPool::<f64, 4, 2>::new();
        let settings = MeasuredBirths { max_probability: 0.9, min_unexplained: 0.1, ..settings() };
        // α = 0.5, 0.3, 0.2 (r_U shares of λ_B = 1): the smallest gives way.
        let update = pool.update(&settings, 2, &model, &linking(), &scan(0.0, &zs, &[1.0, 0.6, 0.4], &[]));
        assert_eq!((update.added, update.evicted), (2, 1));
        let alphas: std::vec::Vec<f64> = pool.cells().iter().map(|c| c.probability).collect();
        assert_eq!(alphas, [0.5, 0.3]);
        // Past the lifetime both expire.
        let update = pool.update(&settings, 2, &model, &linking(), &scan(10.5, &[], &[], &[]));
        assert_eq!((update.expired, pool.cells().len()), (2, 0));
    }

    #[test]
    fn a_measurement_without_a_birth_density_is_counted_and_makes_no_cell() {
        // A GEO region for a planar model is still a density (position models ignore the orbit); an
        // invalid region is not.
        let model = PositionMeasurement::isotropic(0.5);
        let zs = [SVector::from([0.0, 0.0])];
        let mut pool = BirthPool::<f64, 4, 2>::new();
        let broken = MeasuredBirths { region: AdmissibleRegion { mu: -1.0, ..settings().region }, ..settings() };
        let update = pool.update(&broken, 2, &model, &linking(), &scan(0.0, &zs, &[1.0], &[]));
        assert_eq!((update.added, update.without_density), (0, 1));
        assert!(pool.cells().is_empty());
    }
}
