//! The weight of a child hypothesis (docs/maths.md §4.1–§4.2, [000]'s FISST form), in the pieces the association
//! matrix needs. The tracker and the host's unbounded reference tracker both compute weights here.
//!
//! ```text
//! ln w̃ = ln w_i + ln P(e) + N'_F ln(1 − p_D) + m ln λ_C + Σ_{(z,o)∈σ} δ_{z,o}
//! δ_{z,o} = ln p_D + ln ĝ_{z,o} − ln λ_C − ln(1 − p_D)
//! ```
//!
//! - ĝ_{z,o} = N(z; ẑ_o, S_o) is the predicted likelihood of the measurement under the object's track.
//! - P(e) is R-FISST's first-order event model ([003] §II-C): no event 1 − M_b α − M_d β, a birth in
//!   one of M_b cells α each, the death of one of the M_d objects in the field of view β each.
//! - When p_D = 1, ln(1 − p_D) = −∞: the missed factor is left out of the baseline and the entries, and
//!   every object in the field of view becomes a required column instead (a child that misses it has
//!   weight 0).

use crate::config::{BirthDetection, BirthEvents, Config};
use crate::ekf::Innovation;
use crate::model::MeasurementModel;
use crate::real::{Real, ln};
use crate::sensor::Sensor;
use nalgebra::SVector;

/// The birth/death event of a child.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Event {
    /// No birth and no death: probability 1 − M_b α − M_d β.
    #[default]
    None,
    /// One object born in birth cell `cell`: probability α.
    Birth {
        /// Index of the birth cell.
        cell: u16,
    },
    /// The object at position `object` of the parent dies: probability β.
    Death {
        /// Position of the dying object in the parent hypothesis.
        object: u16,
    },
}

/// Everything of the configuration that enters a child's weight, with the logarithms taken once.
///
/// # Examples
/// The child of a parent with one object that assigns the scan's one measurement to it weighs
/// w P(e) p_D ĝ (docs/maths.md §4.1): the baseline and the entry add up to it.
/// ```
/// use nalgebra::{SMatrix, SVector};
/// use tracker_core::ekf::Innovation;
/// use tracker_core::weight::{Event, WeightModel};
/// use tracker_core::{BirthDetection, Region, Sensor};
///
/// let field_of_view = Region::Rectangle { min: [0.0, 0.0], max: [10.0, 10.0] };
/// let sensor = Sensor { detection_probability: 0.9, clutter_rate: 1.0, field_of_view };
/// let model = WeightModel::new(&sensor, None, 0.0, 0, BirthDetection::AllDetected, 0.1);
/// let innovation = Innovation::new(SVector::from([5.0, 5.0]), SMatrix::identity())?;
/// let z = SVector::from([5.5, 5.0]);
/// let (_, log_g) = innovation.score(&z);
///
/// let (parent, event) = (0.5_f64.ln(), model.event_log_probability(Event::None, 1));
/// let child = model.baseline(parent, event, 1, 1) + model.entry(&innovation, &z);
/// assert!((child - (0.5 * 0.9 * 0.9 * log_g.exp()).ln()).abs() < 1e-12); // P(no event) = 1 − β = 0.9
/// # Ok::<(), tracker_core::NumericalError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WeightModel<T> {
    log_detect: T,
    log_miss: T,
    log_clutter: T,
    gate: Option<T>,
    birth_probability: T,
    birth_cells: usize,
    birth_detection: BirthDetection,
    birth_events: BirthEvents,
    /// Independent births: Σ_l ln(1 − α_l) over the scan's cells.
    no_birth: T,
    death_probability: T,
}

impl<T: Real> WeightModel<T> {
    /// The weight model of a configuration.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::Config;
    /// # let config = tracker_core::Config { death_probability: 0.1, ..tracker_core::examples::config() };
    /// # let object = tracker_core::examples::object();
    /// use tracker_core::BirthDetection;
    /// use tracker_core::weight::WeightModel;
    /// let model = WeightModel::from_config(&config);
    /// assert_eq!(model, WeightModel::new(&config.sensor, None, 0.0, 0, BirthDetection::AllDetected, 0.1));
    /// assert!(model.deaths_possible() && !model.births_possible());
    /// ```
    pub fn from_config<M, G, const S: usize, const B: usize>(config: &Config<T, M, G, S, B>) -> Self {
        let sensor = &config.sensor;
        Self::of_config(config, sensor.detection_probability, sensor.clutter_intensity())
    }

    /// The weight model of `config` with the detection probability `pd` and clutter intensity `clutter`.
    fn of_config<M, G, const S: usize, const B: usize>(config: &Config<T, M, G, S, B>, pd: T, clutter: T) -> Self {
        let birth = &config.birth;
        let parts = (birth.probability, birth.cells.len(), birth.detection, config.death_probability);
        Self::of_parts(pd, clutter, config.gate, parts).with_birth_events(birth.events)
    }

    /// The weight model of a scan whose sensor is `model` placed at the scan, with `detection` its p_D,
    /// clutter and field of view: λ_C is the clutter rate over the field of view's volume in the model's
    /// measurement coordinates ([`Placement::clutter_volume`](crate::Placement::clutter_volume)).
    pub fn placed<M, G: MeasurementModel<T, S, D>, const S: usize, const D: usize, const B: usize>(
        config: &Config<T, M, G, S, B>,
        model: &G,
        detection: &Sensor<T>,
    ) -> Self {
        // The configuration's own sensor is not used: its field of view's volume (a numerical integral for a
        // look region) would be computed at every scan for nothing.
        let volume = model.clutter_volume(&detection.field_of_view);
        Self::of_config(config, detection.detection_probability, detection.clutter_rate / volume)
    }

    /// A weight model from its parts.
    ///
    /// # Examples
    /// ```
    /// use tracker_core::{BirthDetection, Region, Sensor};
    /// use tracker_core::weight::{Event, WeightModel};
    /// // p_D = 0.9, λ_C = 1 / 100.
    /// let field_of_view = Region::Rectangle { min: [0.0, 0.0], max: [10.0, 10.0] };
    /// let sensor = Sensor { detection_probability: 0.9, clutter_rate: 1.0, field_of_view };
    /// let model = WeightModel::new(&sensor, Some(9.0), 0.05, 2, BirthDetection::AllowUndetected, 0.1);
    /// assert_eq!(model.birth_cells(), 2);
    /// assert!(!model.birth_required() && !model.detection_required());
    /// ```
    pub fn new(
        sensor: &Sensor<T>,
        gate: Option<T>,
        birth_probability: T,
        birth_cells: usize,
        birth_detection: BirthDetection,
        death_probability: T,
    ) -> Self {
        let births = (birth_probability, birth_cells, birth_detection, death_probability);
        Self::of_parts(sensor.detection_probability, sensor.clutter_intensity(), gate, births)
    }

    /// [`WeightModel::new`] from p_D, λ_C, the gate and (α, birth cells, birth detection, β).
    fn of_parts(pd: T, clutter: T, gate: Option<T>, births: (T, usize, BirthDetection, T)) -> Self {
        let (birth_probability, birth_cells, birth_detection, death_probability) = births;
        Self {
            log_detect: ln(pd),
            log_miss: ln(T::one() - pd),
            log_clutter: ln(clutter),
            gate,
            birth_probability,
            birth_cells,
            birth_detection,
            birth_events: BirthEvents::FirstOrder,
            no_birth: T::zero(),
            death_probability,
        }
    }

    /// This model with births combining as `events` (the default of [`WeightModel::new`] is
    /// [`BirthEvents::FirstOrder`]).
    ///
    /// # Examples
    /// Independent births: P(no birth and no death) = (1 − α)^{M_b} (1 − M_d β) (docs/maths.md §5.6).
    /// ```
    /// # use tracker_core::{BirthDetection, BirthEvents, Region, Sensor};
    /// # use tracker_core::weight::{Event, WeightModel};
    /// # let sensor = Sensor { detection_probability: 0.9, clutter_rate: 1.0, field_of_view: Region::Everywhere { volume: 100.0 } };
    /// let model = WeightModel::new(&sensor, None, 0.05, 2, BirthDetection::AllDetected, 0.1)
    ///     .with_birth_events(BirthEvents::Independent);
    /// let expected = (0.95f64 * 0.95 * (1.0 - 3.0 * 0.1)).ln();
    /// assert!((model.event_log_probability(Event::None, 3) - expected).abs() < 1e-15);
    /// assert!(model.independent_births());
    /// ```
    pub fn with_birth_events(self, birth_events: BirthEvents) -> Self {
        let no_birth = match birth_events {
            BirthEvents::FirstOrder => T::zero(),
            BirthEvents::Independent => T::of_f64(self.birth_cells as f64) * ln(T::one() - self.birth_probability),
        };
        Self { birth_events, no_birth, ..self }
    }

    /// The scan's birth cells, when they are not the configuration's (measured births, docs/maths.md §5.8):
    /// `cells` cells with `no_birth` = Σ_l ln(1 − α_l).
    pub fn set_birth_cells(&mut self, cells: usize, no_birth: T) {
        self.birth_cells = cells;
        self.no_birth = no_birth;
    }

    /// Whether every birth cell is a column of every matrix ([`BirthEvents::Independent`]).
    pub fn independent_births(&self) -> bool {
        self.birth_events == BirthEvents::Independent && self.birth_cells > 0
    }

    /// δ_{z,l} of birth cell l for measurement z, from the cell's object entry `object_entry` (as
    /// [`WeightModel::entry_of_residual`] gives it). First-order births: the entry itself (the birth is the
    /// child's event, its α in the baseline). Independent births: ln(α p_D ĝ / ((1 − α) λ_C)), the odds of
    /// the cell giving birth to an object that takes z against no birth (docs/maths.md §5.6).
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::{BirthDetection, BirthEvents, Region, Sensor};
    /// # use tracker_core::weight::WeightModel;
    /// # let sensor = Sensor { detection_probability: 0.9, clutter_rate: 1.0, field_of_view: Region::Everywhere { volume: 100.0 } };
    /// let first_order = WeightModel::new(&sensor, None, 0.05, 2, BirthDetection::AllDetected, 0.1);
    /// assert_eq!(first_order.birth_entry(1.5), 1.5);
    /// let independent = first_order.with_birth_events(BirthEvents::Independent);
    /// let expected = 1.5 + 0.1f64.ln() + (0.05f64 / 0.95).ln(); // without the 1 / (1 − p_D), with the odds
    /// assert!((independent.birth_entry(1.5) - expected).abs() < 1e-15);
    /// assert_eq!(independent.birth_entry(f64::NEG_INFINITY), f64::NEG_INFINITY);
    /// ```
    pub fn birth_entry(&self, object_entry: T) -> T {
        self.birth_entry_with(object_entry, self.birth_probability)
    }

    /// [`WeightModel::birth_entry`] for a cell of birth probability `alpha`.
    pub fn birth_entry_with(&self, object_entry: T, alpha: T) -> T {
        if !self.independent_births() {
            return object_entry;
        }
        object_entry + self.finite_miss() + ln(alpha) - ln(T::one() - alpha)
    }

    /// δ_{z,o} = ln(p_D ĝ / ((1 − p_D) λ_C)) for a track (or birth cell) with `innovation` and measurement
    /// `z`; `-inf` when the squared Mahalanobis distance exceeds the gate. Without the (1 − p_D) when
    /// p_D = 1.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::{BirthDetection, Region, Sensor};
    /// # use tracker_core::weight::{Event, WeightModel};
    /// # // p_D = 0.9, λ_C = 1 / 100.
    /// # let field_of_view = Region::Rectangle { min: [0.0, 0.0], max: [10.0, 10.0] };
    /// # let sensor = Sensor { detection_probability: 0.9, clutter_rate: 1.0, field_of_view };
    /// # use nalgebra::{SMatrix, SVector};
    /// use tracker_core::ekf::Innovation;
    /// let model = WeightModel::new(&sensor, Some(4.0), 0.0, 0, BirthDetection::AllDetected, 0.0);
    /// let innovation = Innovation::new(SVector::from([5.0, 5.0]), SMatrix::identity())?;
    /// // At ẑ: ln(p_D N(0; 0, I) / ((1 − p_D) λ_C)).
    /// let at_mean = model.entry(&innovation, &SVector::from([5.0, 5.0]));
    /// let expected = (0.9 / (2.0 * core::f64::consts::PI) / (0.1 * 0.01_f64)).ln();
    /// assert!((at_mean - expected).abs() < 1e-12);
    /// // Three standard deviations away is beyond the gate of d² = 4.
    /// assert_eq!(model.entry(&innovation, &SVector::from([8.0, 5.0])), f64::NEG_INFINITY);
    /// # Ok::<(), tracker_core::NumericalError>(())
    /// ```
    pub fn entry<const D: usize>(&self, innovation: &Innovation<T, D>, z: &SVector<T, D>) -> T {
        self.entry_of_residual(innovation, &(z - innovation.predicted))
    }

    /// [`WeightModel::entry`] from the residual ν = z − ẑ (as the measurement model forms it, angles
    /// wrapped).
    pub fn entry_of_residual<const D: usize>(&self, innovation: &Innovation<T, D>, residual: &SVector<T, D>) -> T {
        let (distance_squared, log_likelihood) = innovation.score_residual(residual);
        if self.gate.is_some_and(|gate| distance_squared > gate) {
            return T::NEG_INFINITY;
        }
        self.log_detect + log_likelihood - self.log_clutter - self.finite_miss()
    }

    /// ln(1 − p_D) when finite, else 0.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::{BirthDetection, Region, Sensor};
    /// # use tracker_core::weight::{Event, WeightModel};
    /// # // p_D = 0.9, λ_C = 1 / 100.
    /// # let field_of_view = Region::Rectangle { min: [0.0, 0.0], max: [10.0, 10.0] };
    /// # let sensor = Sensor { detection_probability: 0.9, clutter_rate: 1.0, field_of_view };
    /// let model = WeightModel::new(&sensor, None, 0.0, 0, BirthDetection::AllDetected, 0.0);
    /// assert!((model.finite_miss() - 0.1f64.ln()).abs() < 1e-15); // ln(1 − p_D)
    /// let certain = Sensor { detection_probability: 1.0, ..sensor };
    /// assert_eq!(WeightModel::new(&certain, None, 0.0, 0, BirthDetection::AllDetected, 0.0).finite_miss(), 0.0);
    /// ```
    pub fn finite_miss(&self) -> T {
        if self.log_miss.is_finite_value() { self.log_miss } else { T::zero() }
    }

    /// Whether every object in the field of view must be detected (p_D = 1).
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::{BirthDetection, Region, Sensor};
    /// # use tracker_core::weight::{Event, WeightModel};
    /// # // p_D = 0.9, λ_C = 1 / 100.
    /// # let field_of_view = Region::Rectangle { min: [0.0, 0.0], max: [10.0, 10.0] };
    /// # let sensor = Sensor { detection_probability: 0.9, clutter_rate: 1.0, field_of_view };
    /// let certain = Sensor { detection_probability: 1.0, ..sensor };
    /// assert!(WeightModel::new(&certain, None, 0.0, 0, BirthDetection::AllDetected, 0.0).detection_required());
    /// assert!(!WeightModel::new(&sensor, None, 0.0, 0, BirthDetection::AllDetected, 0.0).detection_required());
    /// ```
    pub fn detection_required(&self) -> bool {
        !self.log_miss.is_finite_value()
    }

    /// Whether a born object must take a measurement (p_D = 1 or "all births detected").
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::{BirthDetection, Region, Sensor};
    /// # use tracker_core::weight::{Event, WeightModel};
    /// # // p_D = 0.9, λ_C = 1 / 100.
    /// # let field_of_view = Region::Rectangle { min: [0.0, 0.0], max: [10.0, 10.0] };
    /// # let sensor = Sensor { detection_probability: 0.9, clutter_rate: 1.0, field_of_view };
    /// assert!(WeightModel::new(&sensor, None, 0.01, 1, BirthDetection::AllDetected, 0.0).birth_required());
    /// assert!(!WeightModel::new(&sensor, None, 0.01, 1, BirthDetection::AllowUndetected, 0.0).birth_required());
    /// ```
    pub fn birth_required(&self) -> bool {
        self.detection_required() || self.birth_detection == BirthDetection::AllDetected
    }

    /// Number of birth cells M_b.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::{BirthDetection, Region, Sensor};
    /// # use tracker_core::weight::WeightModel;
    /// # let sensor = Sensor { detection_probability: 0.9, clutter_rate: 1.0, field_of_view: Region::Everywhere { volume: 100.0 } };
    /// let model = WeightModel::new(&sensor, None, 0.01, 3, BirthDetection::AllDetected, 0.0);
    /// assert_eq!(model.birth_cells(), 3);
    /// ```
    pub fn birth_cells(&self) -> usize {
        self.birth_cells
    }

    /// Whether births can happen (α > 0 and at least one cell).
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::{BirthDetection, Region, Sensor};
    /// # use tracker_core::weight::{Event, WeightModel};
    /// # // p_D = 0.9, λ_C = 1 / 100.
    /// # let field_of_view = Region::Rectangle { min: [0.0, 0.0], max: [10.0, 10.0] };
    /// # let sensor = Sensor { detection_probability: 0.9, clutter_rate: 1.0, field_of_view };
    /// let model = |alpha, cells| WeightModel::new(&sensor, None, alpha, cells, BirthDetection::AllDetected, 0.0);
    /// assert!(model(0.01, 1).births_possible());
    /// assert!(!model(0.01, 0).births_possible()); // no cell
    /// assert!(!model(0.0, 1).births_possible()); // α = 0
    /// ```
    pub fn births_possible(&self) -> bool {
        self.birth_cells > 0 && (self.birth_probability > T::zero() || self.birth_events == BirthEvents::Independent)
    }

    /// Whether deaths can happen (β > 0).
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::{BirthDetection, Region, Sensor};
    /// # use tracker_core::weight::{Event, WeightModel};
    /// # // p_D = 0.9, λ_C = 1 / 100.
    /// # let field_of_view = Region::Rectangle { min: [0.0, 0.0], max: [10.0, 10.0] };
    /// # let sensor = Sensor { detection_probability: 0.9, clutter_rate: 1.0, field_of_view };
    /// assert!(WeightModel::new(&sensor, None, 0.0, 0, BirthDetection::AllDetected, 0.01).deaths_possible());
    /// assert!(!WeightModel::new(&sensor, None, 0.0, 0, BirthDetection::AllDetected, 0.0).deaths_possible());
    /// ```
    pub fn deaths_possible(&self) -> bool {
        self.death_probability > T::zero()
    }

    /// ln P(e) for a parent with `parent_in_view` objects in the field of view (M_d).
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::{BirthDetection, Region, Sensor};
    /// # use tracker_core::weight::{Event, WeightModel};
    /// # // p_D = 0.9, λ_C = 1 / 100.
    /// # let field_of_view = Region::Rectangle { min: [0.0, 0.0], max: [10.0, 10.0] };
    /// # let sensor = Sensor { detection_probability: 0.9, clutter_rate: 1.0, field_of_view };
    /// // α = 0.05 in each of 2 cells, β = 0.1, and 3 objects in view: P(no event) = 1 − 2 α − 3 β.
    /// let model = WeightModel::new(&sensor, None, 0.05, 2, BirthDetection::AllDetected, 0.1);
    /// assert!((model.event_log_probability(Event::None, 3) - 0.6f64.ln()).abs() < 1e-15);
    /// assert_eq!(model.event_log_probability(Event::Birth { cell: 1 }, 3), 0.05f64.ln());
    /// assert_eq!(model.event_log_probability(Event::Death { object: 0 }, 3), 0.1f64.ln());
    /// ```
    pub fn event_log_probability(&self, event: Event, parent_in_view: usize) -> T {
        if self.independent_births() {
            // No birth in any cell, times the first-order death model (docs/maths.md §5.6).
            let in_view = T::of_f64(parent_in_view as f64);
            return self.no_birth
                + match event {
                    Event::None => ln(T::one() - in_view * self.death_probability),
                    Event::Death { .. } => ln(self.death_probability),
                    // A birth is a column of every matrix, never an event.
                    Event::Birth { .. } => T::NEG_INFINITY,
                };
        }
        match event {
            Event::None => {
                let cells = T::of_f64(self.birth_cells as f64);
                let in_view = T::of_f64(parent_in_view as f64);
                ln(T::one() - cells * self.birth_probability - in_view * self.death_probability)
            }
            Event::Birth { .. } => ln(self.birth_probability),
            Event::Death { .. } => ln(self.death_probability),
        }
    }

    /// The association matrix's baseline: ln w_i + ln P(e) + N'_F ln(1 − p_D) + m ln λ_C, the log-weight
    /// of the child that misses all `child_in_view` objects in the field of view and calls all
    /// `measurements` clutter.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::{BirthDetection, Region, Sensor};
    /// # use tracker_core::weight::{Event, WeightModel};
    /// # // p_D = 0.9, λ_C = 1 / 100.
    /// # let field_of_view = Region::Rectangle { min: [0.0, 0.0], max: [10.0, 10.0] };
    /// # let sensor = Sensor { detection_probability: 0.9, clutter_rate: 1.0, field_of_view };
    /// let model = WeightModel::new(&sensor, None, 0.0, 0, BirthDetection::AllDetected, 0.0);
    /// // Parent weight 1/2, P(e) = 1, two objects missed (1 − p_D)², three clutter returns λ_C³.
    /// let baseline = model.baseline(0.5f64.ln(), 0.0, 2, 3);
    /// assert!((baseline - (0.5 * 0.1 * 0.1 * 1e-6_f64).ln()).abs() < 1e-12);
    /// ```
    pub fn baseline(
        &self,
        parent_log_weight: T,
        event_log_probability: T,
        child_in_view: usize,
        measurements: usize,
    ) -> T {
        parent_log_weight
            + event_log_probability
            + T::of_f64(child_in_view as f64) * self.finite_miss()
            + T::of_f64(measurements as f64) * self.log_clutter
    }
}
