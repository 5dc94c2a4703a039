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

use crate::ekf;
use crate::gaussian::Gaussian;
use crate::model::{AdmissibleRegion, BirthComponent, MeasurementModel, MotionModel};
use crate::real::Real;
use nalgebra::SVector;
pub use tracklets::{MAX_LINKED_FRAMES, TRACKLET_FRAMES, TRACKLET_POINTS, TrackletBirths, TrackletBuffer};

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
}

/// At most `B` birth cells made from measurements (docs/maths.md §5.8).
#[derive(Debug, Clone, PartialEq)]
pub struct BirthPool<T: Real, const S: usize, const B: usize> {
    cells: heapless::Vec<PoolCell<T, S>, B>,
    /// The earlier frames' unexplained directions, for tracklets.
    tracklets: TrackletBuffer<T>,
}

impl<T: Real, const S: usize, const B: usize> Default for BirthPool<T, S, B> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T: Real, const S: usize, const B: usize> BirthPool<T, S, B> {
    /// An empty pool.
    pub const fn new() -> Self {
        Self { cells: heapless::Vec::new(), tracklets: TrackletBuffer::new() }
    }

    /// The cells, oldest first.
    pub fn cells(&self) -> &[PoolCell<T, S>] {
        &self.cells
    }

    /// The earlier frames kept for tracklets.
    pub fn tracklet_frames(&self) -> &TrackletBuffer<T> {
        &self.tracklets
    }

    /// Removes every cell and tracklet frame.
    pub fn clear(&mut self) {
        self.cells.clear();
        self.tracklets.clear();
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

    /// Updates the pool after `scan`: each cell's α times 1 − `born[l]` (the posterior probability that
    /// cell l gave birth in the scan; missing entries count as 0) and (1 − p_D) / (1 − α p_D) with p_D =
    /// `detection[l]` (docs/maths.md §5.8), cells past their lifetime removed, then
    /// the cells of every measurement whose `unexplained[z]` (r_U) is at least the settings' minimum added,
    /// made by `model` (the measurement model placed at the scan). At most
    /// `capacity` (≤ `B`) cells are kept: the smallest α give way, the older first among equals.
    pub fn update<G: MeasurementModel<T, S, D>, const D: usize>(
        &mut self,
        settings: &MeasuredBirths<T>,
        capacity: usize,
        model: &G,
        scan: &ScanUse<'_, T, D>,
    ) -> PoolUpdate {
        let ScanUse { time, sensor, measurements, unexplained, born, detection } = *scan;
        let capacity = capacity.min(B);
        let mut update = PoolUpdate::default();
        // Age the old cells.
        let mut index = 0;
        let mut old_index = 0;
        while index < self.cells.len() {
            let given_birth = unit(born.get(old_index).copied().unwrap_or(T::zero()));
            let p_d = unit(detection.get(old_index).copied().unwrap_or(T::zero()));
            old_index += 1;
            let Some(cell) = self.cells.get_mut(index) else { break };
            // The candidate object, had it existed, was missed: the Bernoulli update α (1 − p_D) / (1 − α p_D)
            // of what did not give birth (docs/maths.md §5.8).
            let alpha = cell.probability;
            cell.probability = alpha * (T::one() - given_birth) * (T::one() - p_d) / (T::one() - alpha * p_d);
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
        // Σ_z r_U(z) over the measurements that make cells.
        let minimum = settings.min_unexplained;
        let total = unexplained
            .iter()
            .take(measurements.len())
            .fold(T::zero(), |sum, &r_u| if r_u >= minimum && r_u > T::zero() { sum + r_u } else { sum });
        if !(total > T::zero()) {
            self.record_frame(settings, sensor, model, scan);
            return update;
        }
        let mut components = [BirthComponent::<T, S>::ZERO; B];
        for (z, &r_u) in measurements.iter().zip(unexplained) {
            if !(r_u >= minimum && r_u > T::zero()) {
                continue;
            }
            let share = settings.expected_births * r_u / total;
            let alpha = if share < settings.max_probability { share } else { settings.max_probability };
            let linked = self.tracklet_components(settings, sensor, time, model, z, &mut components);
            update.tracklets += usize::from(linked.is_some());
            let awaits_link = settings.tracklets.is_some_and(|t| !t.single_frame) && model.sky_point(z).is_some();
            if linked.is_none() && awaits_link {
                continue;
            }
            let own = || model.birth_components(z, &settings.region, &mut components);
            let count = match linked.map_or_else(own, Ok) {
                Ok(count) if count > 0 => count.min(B),
                _ => {
                    update.without_density += 1;
                    continue;
                }
            };
            for component in components.iter().take(count) {
                let cell = PoolCell { state: component.state, time, probability: alpha * component.weight };
                if !(cell.probability > T::zero()) {
                    continue;
                }
                let (kept, gave_way) = self.insert(cell, capacity);
                update.added += usize::from(kept);
                update.evicted += usize::from(gave_way);
            }
        }
        self.record_frame(settings, sensor, model, scan);
        update
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
    /// the new one's; returns whether `cell` was kept and whether a cell (old or new) gave way.
    fn insert(&mut self, cell: PoolCell<T, S>, capacity: usize) -> (bool, bool) {
        if self.cells.len() < capacity {
            return (self.cells.push(cell).is_ok(), false);
        }
        match self.smallest() {
            Some((index, probability)) if probability <= cell.probability => {
                self.remove_at(index);
                (self.cells.push(cell).is_ok(), true)
            }
            _ => (false, true),
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
    use crate::model::PositionMeasurement;

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
        ScanUse { time, sensor: 0, measurements: zs, unexplained: r_u, born, detection: &[] }
    }

    #[test]
    fn unexplained_measurements_make_cells_with_alpha_shared_by_r_u_and_capped() {
        let model = PositionMeasurement::isotropic(0.5);
        let zs = [SVector::from([1.0, 2.0]), SVector::from([5.0, 5.0]), SVector::from([9.0, 0.0])];
        let mut pool = BirthPool::<f64, 4, 4>::new();
        // r_U 0.9 and 0.3 (below the minimum) and 0.1: only the first makes a cell, α = min(0.3, 1 · 0.9 / 0.9).
        let update = pool.update(&settings(), 4, &model, &scan(1.0, &zs, &[0.9, 0.3, 0.1], &[]));
        assert_eq!((update.added, update.evicted, update.expired), (1, 0, 0));
        assert_eq!(pool.cells()[0].probability, 0.3);
        assert_eq!(pool.cells()[0].state.mean, SVector::from([1.0, 2.0, 0.0, 0.0]));
        // Two unexplained measurements share λ_B = 1: α = 0.6 / 1.1 and 0.5 / 1.1, capped at 0.3.
        let update = pool.update(&settings(), 4, &model, &scan(2.0, &zs[1..], &[0.6, 0.5], &[0.5]));
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
        pool.update(&settings, 4, &model, &scan(0.0, &zs, &[1.0, 1.0], &[]));
        // The first in view of a sensor of p_D 0.8, no birth: 0.5 · 0.2 / (1 − 0.4) = 1/6; the second out
        // of view and born with probability 0.2: 0.5 · 0.8 = 0.4.
        let in_view = ScanUse {
            time: 1.0,
            sensor: 0,
            measurements: &[],
            unexplained: &[],
            born: &[0.0, 0.2],
            detection: &[0.8, 0.0],
        };
        pool.update(&settings, 4, &model, &in_view);
        let alphas: std::vec::Vec<f64> = pool.cells().iter().map(|c| c.probability).collect();
        assert!((alphas[0] - 1.0 / 6.0).abs() < 1e-15 && (alphas[1] - 0.4).abs() < 1e-15, "{alphas:?}");
        // p_D = 1 in view: the candidate would have been seen, so the cell is gone.
        let certain = ScanUse { detection: &[1.0, 0.0], born: &[], ..in_view };
        let update = pool.update(&settings, 4, &model, &ScanUse { time: 2.0, ..certain });
        assert_eq!((update.expired, pool.cells().len()), (1, 1));
    }

    #[test]
    fn a_full_pool_keeps_the_largest_alphas_and_old_cells_expire() {
        let model = PositionMeasurement::isotropic(0.5);
        let zs = [SVector::from([0.0, 0.0]), SVector::from([1.0, 0.0]), SVector::from([2.0, 0.0])];
        let mut pool = BirthPool::<f64, 4, 2>::new();
        let settings = MeasuredBirths { max_probability: 0.9, min_unexplained: 0.1, ..settings() };
        // α = 0.5, 0.3, 0.2 (r_U shares of λ_B = 1): the smallest gives way.
        let update = pool.update(&settings, 2, &model, &scan(0.0, &zs, &[1.0, 0.6, 0.4], &[]));
        assert_eq!((update.added, update.evicted), (2, 1));
        let alphas: std::vec::Vec<f64> = pool.cells().iter().map(|c| c.probability).collect();
        assert_eq!(alphas, [0.5, 0.3]);
        // Past the lifetime both expire.
        let update = pool.update(&settings, 2, &model, &scan(10.5, &[], &[], &[]));
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
        let update = pool.update(&broken, 2, &model, &scan(0.0, &zs, &[1.0], &[]));
        assert_eq!((update.added, update.without_density), (0, 1));
        assert!(pool.cells().is_empty());
    }
}
