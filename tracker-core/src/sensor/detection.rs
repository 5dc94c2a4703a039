//! How a sensor detects: its probability of detection and its clutter, over its field of view.
//!
//! An object whose predicted measurement h(x̂⁻) lies inside the field of view is detected with
//! probability p_D; outside it p_D = 0 and it contributes no missed-detection factor (paper 004's remark
//! on M_t, docs/maths.md §3.1). Clutter is Poisson with mean `clutter_rate` returns per
//! scan, uniform over the field of view, so its intensity is λ_C = clutter_rate / V with V the volume of
//! the field of view in measurement coordinates.

use super::field_of_view::{LookAxes, Region};
use crate::real::Real;

/// How a sensor detects: p_D inside its field of view and the clutter over it.
///
/// # Examples
/// The sensor is checked when a tracker is built; an invalid one is [`ConfigError::Sensor`] with the
/// reason:
/// ```
/// # use tracker_core::{Config, LinearTracker, Region, Sensor};
/// # let (config, object) = (tracker_core::examples::config(), tracker_core::examples::object());
/// use tracker_core::ConfigError;
/// let blind = Config { sensor: Sensor { detection_probability: 0.0, ..config.sensor }, ..config.clone() };
/// match LinearTracker::<f64, 8, 4, 4, 16, 1>::with_objects(blind, &[object], 0.0) {
///     Err(ConfigError::Sensor(why)) => assert!(why.contains("detection probability")),
///     other => panic!("unexpected {other:?}"),
/// }
/// let field_of_view = Region::Rectangle { min: [0.0, 0.0], max: [0.0, 1.0] }; // zero width
/// let flat = Config { sensor: Sensor { field_of_view, ..config.sensor }, ..config };
/// assert!(matches!(
///     LinearTracker::<f64, 8, 4, 4, 16, 1>::with_objects(flat, &[object], 0.0),
///     Err(ConfigError::Sensor(_))
/// ));
/// ```
///
/// [`ConfigError::Sensor`]: crate::ConfigError::Sensor
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Sensor<T> {
    /// Probability of detection p_D of an object inside the field of view, in (0, 1].
    pub detection_probability: T,
    /// Expected number of clutter returns per scan Λ_C (> 0), uniform over the field of view.
    pub clutter_rate: T,
    /// What the sensor sees.
    pub field_of_view: Region<T>,
}

impl<T: Real> Sensor<T> {
    /// A sensor that detects nothing (p_D = 0, which no check accepts): the detection model of a
    /// placeholder configuration, before the run-time one is installed ([`crate::Tracker::reset_with`]).
    pub const UNCONFIGURED: Self = Sensor {
        detection_probability: T::ZERO,
        clutter_rate: T::ZERO,
        field_of_view: Region::Everywhere { volume: T::ZERO },
    };

    /// Checks the sensor from its parts: the measurement dimension, the model's look axes (`None`
    /// without a sensor frame) and the field of view's clutter volume in measurement coordinates.
    pub(crate) fn validate_parts(
        &self,
        measurement_dimension: usize,
        look_axes: Option<LookAxes>,
        volume: T,
    ) -> Result<(), &'static str> {
        let pd = self.detection_probability;
        if !(pd.is_finite_value() && pd > T::zero() && pd <= T::one()) {
            return Err("sensor: detection probability must be in (0, 1]");
        }
        if !(self.clutter_rate.is_finite_value() && self.clutter_rate > T::zero()) {
            return Err("sensor: clutter rate must be finite and > 0");
        }
        self.field_of_view.validate(measurement_dimension)?;
        if let Region::Look { range, range_rate, .. } = self.field_of_view {
            let Some(axes) = look_axes else {
                return Err("field of view: a look-angle field of view needs a measurement model with a sensor frame");
            };
            if axes.range != range.is_some() {
                return Err("field of view: a range window is required exactly when the sensor measures range");
            }
            if axes.range_rate != range_rate.is_some() {
                return Err(
                    "field of view: a range-rate window is required exactly when the sensor measures range-rate",
                );
            }
        }
        // The region's volume and the clutter intensity must be representable: a region whose volume
        // overflows or underflows the scalar type would make λ_C infinite or zero.
        let intensity = self.clutter_rate / volume;
        if !(volume.is_finite_value() && volume > T::zero()) {
            return Err("field of view: its volume is not a finite positive number in this scalar type");
        }
        if !(intensity.is_finite_value() && intensity > T::zero() && crate::real::ln(intensity).is_finite_value()) {
            return Err(
                "sensor: clutter intensity (clutter rate / field-of-view volume) is not finite and > 0 in this scalar type",
            );
        }
        Ok(())
    }

    /// Clutter intensity λ_C = Λ_C / V per unit measurement volume, with V the region's own
    /// [`Region::volume`] (planar regions, radar look coordinates).
    ///
    /// # Examples
    /// ```
    /// use tracker_core::{Region, Sensor};
    /// let field_of_view = Region::Rectangle { min: [0.0, 0.0], max: [100.0, 50.0] };
    /// let sensor = Sensor { detection_probability: 0.9, clutter_rate: 2.0, field_of_view };
    /// assert_eq!(sensor.clutter_intensity(), 2.0 / 5000.0);
    /// ```
    pub fn clutter_intensity(&self) -> T {
        self.clutter_rate / self.field_of_view.volume()
    }
}
