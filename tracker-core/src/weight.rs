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

use crate::config::{BirthDetection, Config};
use crate::ekf::Innovation;
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
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WeightModel<T> {
    log_detect: T,
    log_miss: T,
    log_clutter: T,
    gate: Option<T>,
    birth_probability: T,
    birth_cells: usize,
    birth_detection: BirthDetection,
    death_probability: T,
}

impl<T: Real> WeightModel<T> {
    /// A placeholder until a configuration is checked (no births, no deaths, neutral terms).
    pub(crate) const EMPTY: Self = Self {
        log_detect: T::ZERO,
        log_miss: T::ZERO,
        log_clutter: T::ZERO,
        gate: None,
        birth_probability: T::ZERO,
        birth_cells: 0,
        birth_detection: BirthDetection::AllDetected,
        death_probability: T::ZERO,
    };

    /// The weight model of a configuration.
    pub fn from_config<M, G, const S: usize, const B: usize>(config: &Config<T, M, G, S, B>) -> Self {
        Self::new(
            &config.sensor,
            config.gate,
            config.birth.probability,
            config.birth.cells.len(),
            config.birth.detection,
            config.death_probability,
        )
    }

    /// A weight model from its parts.
    pub fn new(
        sensor: &Sensor<T>,
        gate: Option<T>,
        birth_probability: T,
        birth_cells: usize,
        birth_detection: BirthDetection,
        death_probability: T,
    ) -> Self {
        let pd = sensor.detection_probability;
        Self {
            log_detect: ln(pd),
            log_miss: ln(T::one() - pd),
            log_clutter: ln(sensor.clutter_intensity()),
            gate,
            birth_probability,
            birth_cells,
            birth_detection,
            death_probability,
        }
    }

    /// δ_{z,o} = ln(p_D ĝ / ((1 − p_D) λ_C)) for a track (or birth cell) with `innovation` and measurement
    /// `z`; `-inf` when the squared Mahalanobis distance exceeds the gate. Without the (1 − p_D) when
    /// p_D = 1.
    pub fn entry<const D: usize>(&self, innovation: &Innovation<T, D>, z: &SVector<T, D>) -> T {
        let (distance_squared, log_likelihood) = innovation.score(z);
        if self.gate.is_some_and(|gate| distance_squared > gate) {
            return T::NEG_INFINITY;
        }
        self.log_detect + log_likelihood - self.log_clutter - self.finite_miss()
    }

    /// ln(1 − p_D) when finite, else 0.
    pub fn finite_miss(&self) -> T {
        if self.log_miss.is_finite_value() { self.log_miss } else { T::zero() }
    }

    /// Whether every object in the field of view must be detected (p_D = 1).
    pub fn detection_required(&self) -> bool {
        !self.log_miss.is_finite_value()
    }

    /// Whether a born object must take a measurement (p_D = 1 or "all births detected").
    pub fn birth_required(&self) -> bool {
        self.detection_required() || self.birth_detection == BirthDetection::AllDetected
    }

    /// Number of birth cells M_b.
    pub fn birth_cells(&self) -> usize {
        self.birth_cells
    }

    /// Whether births can happen (α > 0 and at least one cell).
    pub fn births_possible(&self) -> bool {
        self.birth_probability > T::zero() && self.birth_cells > 0
    }

    /// Whether deaths can happen (β > 0).
    pub fn deaths_possible(&self) -> bool {
        self.death_probability > T::zero()
    }

    /// ln P(e) for a parent with `parent_in_view` objects in the field of view (M_d).
    pub fn event_log_probability(&self, event: Event, parent_in_view: usize) -> T {
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
