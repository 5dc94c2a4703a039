//! Where a sensor is and which one made a scan: the [`Placement`] of a measurement model at each scan
//! ([`ScanGeometry`]: the sensor's index, the time and a spacecraft observer's state), the sensors'
//! platforms, and the whole description of one sensor of a network ([`SiteSensor`]).
//!
//! A measurement model describes one sensor or several (a [`SensorNetwork`](crate::SensorNetwork)); before
//! a scan is scored the tracker places it at the scan, and the placed model answers for the sensor that
//! made it: its detection model, how its field of view reads a measurement (look coordinates) and the
//! field of view's clutter volume in measurement coordinates.

use super::detection::Sensor;
use super::field_of_view::{Look, LookAxes, Region};
use super::frames::GroundSite;
use crate::real::Real;
use nalgebra::SVector;

/// Where a sensor is.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Platform<T> {
    /// A site on the rotating Earth.
    Ground(GroundSite<T>),
    /// A spacecraft: every scan of this sensor passes the observer's inertial state.
    Spacecraft,
}

/// One sensor of a [`SensorNetwork`](crate::SensorNetwork), whole: where it is, its noise, and how it detects (not serde: serde has no arrays of a const-generic length).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SiteSensor<T, const D: usize> {
    /// Where it is.
    pub platform: Platform<T>,
    /// Noise standard deviation of each measurement component (km, rad, km/s).
    pub sigma: [T; D],
    /// p_D, clutter and the field of view ([`Region::Look`]).
    pub detection: Sensor<T>,
}

/// Which sensor made a scan, when, and from where.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ScanGeometry<T> {
    /// The sensor's index in its network (0 for a single sensor).
    pub sensor: usize,
    /// The scan time (s after the configuration's epoch).
    pub time: f64,
    /// A spacecraft observer's inertial position and velocity (km, km/s); `None` for ground sites and
    /// for models without an observer.
    pub observer: Option<[T; 6]>,
}

impl<T> ScanGeometry<T> {
    /// The geometry of a scan of the only sensor, without an observer.
    pub const fn single(time: f64) -> Self {
        Self { sensor: 0, time, observer: None }
    }
}

/// Why a scan's geometry cannot be placed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum PlacementError {
    /// The scan names a sensor the model does not have.
    UnknownSensor {
        /// The sensor named.
        sensor: usize,
        /// How many sensors there are.
        sensors: usize,
    },
    /// A spacecraft sensor's scan has no observer state.
    MissingObserver,
    /// The scan passes an observer state to a sensor that has none (a ground site, a planar model).
    UnexpectedObserver,
    /// The observer state has a NaN or an infinity.
    NonFiniteObserver,
    /// The observer is inside the Earth's WGS-84 ellipsoid.
    ObserverInsideEarth,
    /// The observer is farther from the Earth's centre than [`MAX_OBSERVER_DISTANCE`].
    ObserverTooFar,
}

/// The farthest a spacecraft observer may be from the Earth's centre (km): 10⁷ km, about 26 lunar
/// distances and 6.7 times the Sun–Earth L1/L2 distance (1.5·10⁶ km, the edge of the Earth's Hill sphere),
/// so every observer bound to the Earth is accepted and a state in the wrong units (m, or an overflowed
/// value) is refused before it turns every track's innovation into a numerical failure.
pub const MAX_OBSERVER_DISTANCE: f64 = 1.0e7;

impl core::fmt::Display for PlacementError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            PlacementError::UnknownSensor { sensor, sensors } => {
                write!(f, "scan names sensor {sensor}, but there are {sensors} sensors")
            }
            PlacementError::MissingObserver => f.write_str("scan of a spacecraft sensor has no observer state"),
            PlacementError::UnexpectedObserver => f.write_str("scan passes an observer state to a sensor without one"),
            PlacementError::NonFiniteObserver => f.write_str("observer state is not finite"),
            PlacementError::ObserverInsideEarth => f.write_str("observer is inside the Earth"),
            PlacementError::ObserverTooFar => {
                write!(f, "observer is more than {MAX_OBSERVER_DISTANCE:e} km from the Earth's centre")
            }
        }
    }
}

impl core::error::Error for PlacementError {}

/// The sensor side of a measurement model: how many sensors it describes, the model placed at one scan,
/// and what the placed sensor detects and sees. Every method has a default for one sensor without a
/// sensor frame (planar positions), so such a model implements it with an empty `impl`.
pub trait Placement<T: Real, const D: usize> {
    /// How many sensors this model describes; every scan names one of `0..sensor_count()`.
    fn sensor_count(&self) -> usize {
        1
    }

    /// This model placed for one scan: the sensor the scan names, seen from where it was at the scan's
    /// time. The default describes one sensor without an observer and returns a copy of itself.
    ///
    /// # Errors
    /// [`PlacementError`] for an unknown sensor or an observer that is missing, unexpected, non-finite,
    /// inside the Earth or farther than [`MAX_OBSERVER_DISTANCE`].
    fn place(&self, scan: &ScanGeometry<T>) -> Result<Self, PlacementError>
    where
        Self: Sized + Clone,
    {
        if scan.sensor != 0 {
            return Err(PlacementError::UnknownSensor { sensor: scan.sensor, sensors: 1 });
        }
        if scan.observer.is_some() {
            return Err(PlacementError::UnexpectedObserver);
        }
        Ok(self.clone())
    }

    /// The detection model of the sensor this model is placed at, when the sensor has its own; `None`
    /// uses the configuration's [`Sensor`] ([`Config::detection`](crate::Config::detection)).
    fn detection(&self) -> Option<Sensor<T>> {
        None
    }

    /// Which look coordinates a measurement of this model gives: `None` for models without a sensor
    /// frame (planar positions), which cannot use a [`Region::Look`] field of view.
    fn look_axes(&self) -> Option<LookAxes> {
        None
    }

    /// The look direction (azimuth, elevation, and range and range-rate when measured) of measurement `z`
    /// in the sensor's frame at the current placement; `None` for models without a sensor frame.
    fn look(&self, _z: &SVector<T, D>) -> Option<Look<T>> {
        None
    }

    /// The clutter volume of `region` in this model's measurement coordinates. The default is the
    /// region's own volume ([`Region::volume`]), right when the measurement coordinates are the look
    /// coordinates (planar positions, radar).
    fn clutter_volume(&self, region: &Region<T>) -> T {
        region.volume()
    }

    /// Whether `z` is a measurement of this placed sensor's kind: always, except for a network of mixed
    /// kinds, whose measurements must leave the components beyond their kind's dimension at zero.
    fn fits(&self, _z: &SVector<T, D>) -> bool {
        true
    }

    /// Whether measurement `z` lies in `region`. The default is [`Region::sees`]; a sensor that measures
    /// no angles checks only the windows of what it measures.
    fn measurement_in_view(&self, region: &Region<T>, z: &SVector<T, D>) -> bool
    where
        Self: Sized,
    {
        region.sees(self, z)
    }
}

impl<T: Real> Region<T> {
    /// Whether the measurement `z` of the placed sensor `model` lies in the region: planar regions read `z`
    /// directly, a [`Region::Look`] reads it through the sensor's [`look`](Placement::look).
    pub fn sees<G: Placement<T, D>, const D: usize>(&self, model: &G, z: &SVector<T, D>) -> bool {
        match self {
            Region::Look { .. } => model.look(z).is_some_and(|look| self.contains_look(&look)),
            _ => self.contains(z),
        }
    }
}

impl<T: Real> Sensor<T> {
    /// Checks the sensor for measurements of the placed sensor `model` (`D` components): p_D, the clutter
    /// rate, the field of view and its clutter volume in the model's measurement coordinates.
    pub(crate) fn validate<G: Placement<T, D>, const D: usize>(&self, model: &G) -> Result<(), &'static str> {
        self.validate_parts(D, model.look_axes(), model.clutter_volume(&self.field_of_view))
    }
}
