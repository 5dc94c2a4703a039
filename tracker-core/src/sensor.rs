//! The sensor: its field of view, its probability of detection and its clutter.
//!
//! An object whose predicted measurement h(x̂⁻) lies inside the field of view is detected with
//! probability p_D; outside it p_D = 0 and it contributes no missed-detection factor (paper 004's remark
//! on M_t, docs/maths.md §3.1). Clutter is Poisson with mean `clutter_rate` returns per
//! scan, uniform over the field of view, so its intensity is λ_C = clutter_rate / V with V the area of
//! the field of view in measurement space.

use crate::real::{Real, atan2, cos, sin};
use nalgebra::SVector;

/// The region of measurement space the sensor sees.
///
/// `Rectangle` and `Sector` read the first two components of a measurement as a planar position.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Region<T> {
    /// No boundary: every object is detectable and clutter spreads over an abstract `volume`
    /// (for exactness tests that follow the papers' single-volume examples).
    Everywhere {
        /// The measurement-space volume V over which clutter is uniform.
        volume: T,
    },
    /// An axis-aligned rectangle `min ≤ (z₀, z₁) ≤ max`.
    Rectangle {
        /// Lower corner.
        min: [T; 2],
        /// Upper corner.
        max: [T; 2],
    },
    /// A circular sector: the sensor at `origin` looking along `look_direction` (radians from +x),
    /// seeing `half_angle` radians either side, out to `max_range`.
    Sector {
        /// Sensor position.
        origin: [T; 2],
        /// Boresight direction in radians, counter-clockwise from +x.
        look_direction: T,
        /// Half of the field-of-view angle, in radians (0, π].
        half_angle: T,
        /// Largest range seen.
        max_range: T,
    },
}

impl<T: Real> Region<T> {
    /// The measurement-space volume V (an area for planar regions).
    ///
    /// # Examples
    /// ```
    /// use tracker_core::Region;
    /// assert_eq!(Region::Rectangle { min: [-1.0, 0.0], max: [3.0, 5.0] }.volume(), 20.0);
    /// let sector = Region::Sector { origin: [0.0, 0.0], look_direction: 0.0, half_angle: 0.5, max_range: 10.0 };
    /// assert_eq!(sector.volume(), 50.0); // θ R²
    /// ```
    pub fn volume(&self) -> T {
        match *self {
            Region::Everywhere { volume } => volume,
            Region::Rectangle { min, max } => (max[0] - min[0]) * (max[1] - min[1]),
            // Area of a sector of angle 2θ: θ R².
            Region::Sector { half_angle, max_range, .. } => half_angle * max_range * max_range,
        }
    }

    /// Whether the measurement-space point `z` lies in the region (boundary included).
    ///
    /// # Examples
    /// ```
    /// use nalgebra::SVector;
    /// use tracker_core::Region;
    /// let rectangle = Region::Rectangle { min: [0.0, 0.0], max: [10.0, 5.0] };
    /// assert!(rectangle.contains(&SVector::from([10.0, 5.0]))); // the boundary is inside
    /// assert!(!rectangle.contains(&SVector::from([10.5, 1.0])));
    ///
    /// // Looking along +y, 30° either side, out to 100.
    /// let sector = Region::Sector {
    ///     origin: [0.0, 0.0],
    ///     look_direction: core::f64::consts::FRAC_PI_2,
    ///     half_angle: 30f64.to_radians(),
    ///     max_range: 100.0,
    /// };
    /// assert!(sector.contains(&SVector::from([10.0, 50.0])));
    /// assert!(!sector.contains(&SVector::from([50.0, 10.0]))); // 79° off the boresight
    /// assert!(!sector.contains(&SVector::from([0.0, 101.0]))); // out of range
    /// ```
    pub fn contains<const D: usize>(&self, z: &SVector<T, D>) -> bool {
        match *self {
            Region::Everywhere { .. } => true,
            Region::Rectangle { min, max } => {
                D >= 2 && z[0] >= min[0] && z[0] <= max[0] && z[1] >= min[1] && z[1] <= max[1]
            }
            Region::Sector { origin, look_direction, half_angle, max_range } => {
                if D < 2 {
                    return false;
                }
                let dx = z[0] - origin[0];
                let dy = z[1] - origin[1];
                if dx * dx + dy * dy > max_range * max_range {
                    return false;
                }
                // Rotate into the boresight frame and compare the bearing with the half angle.
                let (s, c) = (sin(look_direction), cos(look_direction));
                let along = dx * c + dy * s;
                let across = dy * c - dx * s;
                let bearing = atan2(across, along);
                bearing <= half_angle && bearing >= -half_angle
            }
        }
    }

    pub(crate) fn validate(&self, measurement_dimension: usize) -> Result<(), &'static str> {
        let finite = |v: T| v.is_finite_value();
        match *self {
            Region::Everywhere { volume } => {
                if !(finite(volume) && volume > T::zero()) {
                    return Err("field of view: volume must be finite and > 0");
                }
            }
            Region::Rectangle { min, max } => {
                if measurement_dimension < 2 {
                    return Err("field of view: a rectangle needs measurements of dimension >= 2");
                }
                if !(min.iter().chain(max.iter()).all(|&v| finite(v)) && max[0] > min[0] && max[1] > min[1]) {
                    return Err("field of view: rectangle corners must be finite with max > min");
                }
            }
            Region::Sector { origin, look_direction, half_angle, max_range } => {
                if measurement_dimension < 2 {
                    return Err("field of view: a sector needs measurements of dimension >= 2");
                }
                if !(origin.iter().all(|&v| finite(v)) && finite(look_direction)) {
                    return Err("field of view: sector origin and look direction must be finite");
                }
                if !(finite(half_angle) && half_angle > T::zero() && half_angle <= T::pi()) {
                    return Err("field of view: sector half angle must be in (0, pi]");
                }
                if !(finite(max_range) && max_range > T::zero()) {
                    return Err("field of view: sector max range must be finite and > 0");
                }
            }
        }
        Ok(())
    }
}

/// Detection and clutter model of the single sensor.
///
/// # Examples
/// The sensor is checked when a tracker is built; an invalid one is [`ConfigError::Sensor`] with the
/// reason:
/// ```
/// # use nalgebra::{SMatrix, SVector};
/// # use tracker_core::{BirthModel, Config, ConstantVelocity, Gaussian, LinearTracker, PositionMeasurement, Region, Sensor};
/// # let config = Config {
/// #     motion: ConstantVelocity { acceleration_noise: 0.01 },
/// #     measurement: PositionMeasurement::isotropic(0.5),
/// #     sensor: Sensor {
/// #         detection_probability: 0.9,
/// #         clutter_rate: 1.0,
/// #         field_of_view: Region::Rectangle { min: [-50.0, -50.0], max: [50.0, 50.0] },
/// #     },
/// #     birth: BirthModel::none(),
/// #     death_probability: 0.0,
/// #     gate: None,
/// #     children: Default::default(),
/// #     selection: Default::default(),
/// #     store_overflow: Default::default(),
/// #     numerical_failure: Default::default(),
/// #     seed: 1,
/// # };
/// # let object = Gaussian { mean: SVector::from([0.0, 0.0, 1.0, 0.0]), covariance: SMatrix::identity() };
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
    pub(crate) fn validate(&self, measurement_dimension: usize) -> Result<(), &'static str> {
        let pd = self.detection_probability;
        if !(pd.is_finite_value() && pd > T::zero() && pd <= T::one()) {
            return Err("sensor: detection probability must be in (0, 1]");
        }
        if !(self.clutter_rate.is_finite_value() && self.clutter_rate > T::zero()) {
            return Err("sensor: clutter rate must be finite and > 0");
        }
        self.field_of_view.validate(measurement_dimension)?;
        // The region's volume and the clutter intensity must be representable: a region whose area
        // overflows or underflows the scalar type would make λ_C infinite or zero.
        let volume = self.field_of_view.volume();
        let intensity = self.clutter_intensity();
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

    /// Clutter intensity λ_C = Λ_C / V per unit measurement volume.
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sector_contains_points_inside_only() {
        let fov = Region::Sector {
            origin: [0.0, 0.0],
            look_direction: 15f64.to_radians(),
            half_angle: 15f64.to_radians(),
            max_range: 10.0,
        };
        let at = |deg: f64, r: f64| SVector::from([r * deg.to_radians().cos(), r * deg.to_radians().sin()]);
        assert!(fov.contains(&at(15.0, 5.0)));
        assert!(fov.contains(&at(1.0, 9.9)));
        assert!(fov.contains(&at(29.0, 1.0)));
        assert!(!fov.contains(&at(31.0, 5.0)));
        assert!(!fov.contains(&at(-1.0, 5.0)));
        assert!(!fov.contains(&at(15.0, 10.1)));
        assert!(!fov.contains(&at(195.0, 5.0)));
        // θ R² with θ = 15°.
        assert!((fov.volume() - 15f64.to_radians() * 100.0).abs() < 1e-12);
    }

    #[test]
    fn rectangle_volume_and_membership() {
        let fov = Region::Rectangle { min: [-1.0, 0.0], max: [3.0, 5.0] };
        assert_eq!(fov.volume(), 20.0);
        assert!(fov.contains(&SVector::from([0.0, 0.0])));
        assert!(!fov.contains(&SVector::from([3.5, 1.0])));
    }
}
