//! The one check of a scan's inputs, shared by the tracker and the host's unbounded reference tracker.

use crate::config::Config;
use crate::error::StepError;
use crate::model::{MeasurementModel, MotionModel};
use crate::real::Real;
use crate::sensor::ScanGeometry;
use crate::sensor::{Region, Sensor};
use crate::weight::WeightModel;
use nalgebra::SVector;

/// Checks a scan taken at `time` after a last scan (or prior) at `last_time`: at most `capacity`
/// measurements, a finite time after the last one, every measurement finite and inside the sensor's
/// `field_of_view` as `model` sees it ([`Region::sees`]).
///
/// # Errors
/// The first [`StepError`] found, in the order above.
///
/// # Examples
/// ```
/// use nalgebra::SVector;
/// use tracker_core::{PositionMeasurement, Region, StepError, tracker::check_scan};
/// let view = Region::Rectangle { min: [0.0, 0.0], max: [10.0, 10.0] };
/// let model = PositionMeasurement::isotropic(0.5);
/// let z = [SVector::from([1.0, 2.0])];
/// assert_eq!(check_scan(&model, &view, 0.0, 1.0, &z, 4), Ok(()));
/// assert_eq!(check_scan(&model, &view, 1.0, 1.0, &z, 4), Err(StepError::TimeNotAfterLastScan));
/// assert_eq!(check_scan(&model, &view, 0.0, 1.0, &z, 0), Err(StepError::TooManyMeasurements { received: 1, capacity: 0 }));
/// let far = [SVector::from([11.0, 2.0])];
/// assert_eq!(check_scan(&model, &view, 0.0, 1.0, &far, 4), Err(StepError::MeasurementOutsideFieldOfView { index: 0 }));
/// ```
pub fn check_scan<T: Real, G: MeasurementModel<T, S, D>, const S: usize, const D: usize>(
    model: &G,
    field_of_view: &Region<T>,
    last_time: f64,
    time: f64,
    measurements: &[SVector<T, D>],
    capacity: usize,
) -> Result<(), StepError> {
    check_time(measurements.len(), capacity, last_time, time)?;
    for (index, z) in measurements.iter().enumerate() {
        if !z.iter().all(|v| v.is_finite_value()) {
            return Err(StepError::NonFiniteMeasurement { index });
        }
        if !model.fits(z) {
            return Err(StepError::MeasurementOfWrongKind { index });
        }
        if !model.measurement_in_view(field_of_view, z) {
            return Err(StepError::MeasurementOutsideFieldOfView { index });
        }
    }
    Ok(())
}

/// At most `capacity` measurements, and a finite time after the last one.
fn check_time(received: usize, capacity: usize, last_time: f64, time: f64) -> Result<(), StepError> {
    if received > capacity {
        return Err(StepError::TooManyMeasurements { received, capacity });
    }
    if !time.is_finite() {
        return Err(StepError::NonFiniteTime);
    }
    if time <= last_time {
        return Err(StepError::TimeNotAfterLastScan);
    }
    Ok(())
}

/// The sensor of one scan: the measurement model placed at the scan's geometry, the sensor's detection
/// model and the weight model that follows from them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlacedScan<T: Real, G> {
    /// The measurement model of this scan.
    pub model: G,
    /// p_D, clutter and field of view of this scan's sensor.
    pub detection: Sensor<T>,
    /// The weight model of this scan.
    pub weights: WeightModel<T>,
}

/// Checks a scan and places its sensor: the checks of [`check_scan`] with the time step against the motion
/// model's bound and the geometry against the measurement model ([`Placement::place`](crate::Placement::place)), in that
/// order, the field of view read through the placed model. The tracker and the host's unbounded reference
/// both start a scan here.
///
/// # Errors
/// The first [`StepError`] found.
///
/// # Examples
/// ```
/// use nalgebra::SVector;
/// use tracker_core::sensor::{PlacementError, ScanGeometry};
/// use tracker_core::{BirthModel, Config, ConstantVelocity, PositionMeasurement, Region, Sensor, StepError};
/// use tracker_core::tracker::place_scan;
/// let config = Config {
///     motion: ConstantVelocity { acceleration_noise: 0.01 },
///     measurement: PositionMeasurement::isotropic(0.5),
///     sensor: Sensor { detection_probability: 0.9, clutter_rate: 1.0, field_of_view: Region::Everywhere { volume: 1e4 } },
///     birth: BirthModel::<f64, 4, 1>::none(),
///     death_probability: 0.0,
///     gate: None,
///     children: Default::default(),
///     selection: Default::default(),
///     store_overflow: Default::default(),
///     numerical_failure: Default::default(),
///     track_loss: Default::default(),
///     seed: 1,
/// };
/// let z = [SVector::from([1.0, 2.0])];
/// let placed = place_scan(&config, &ScanGeometry::single(1.0), 0.0, &z, 4)?;
/// assert_eq!(placed.detection, config.sensor);
/// let elsewhere = ScanGeometry { sensor: 1, time: 1.0, observer: None };
/// assert_eq!(
///     place_scan(&config, &elsewhere, 0.0, &z, 4).unwrap_err(),
///     StepError::Placement(PlacementError::UnknownSensor { sensor: 1, sensors: 1 })
/// );
/// # Ok::<(), StepError>(())
/// ```
pub fn place_scan<T, M, G, const S: usize, const D: usize, const B: usize>(
    config: &Config<T, M, G, S, B>,
    geometry: &ScanGeometry<T>,
    last_time: f64,
    measurements: &[SVector<T, D>],
    capacity: usize,
) -> Result<PlacedScan<T, G>, StepError>
where
    T: Real,
    M: MotionModel<T, S>,
    G: MeasurementModel<T, S, D> + Clone,
{
    check_time(measurements.len(), capacity, last_time, geometry.time)?;
    if let Some(limit) = config.motion.max_time_step()
        && geometry.time - last_time > limit
    {
        return Err(StepError::TimeStepTooLong { limit_seconds: limit as u64 });
    }
    let model = config.measurement.place(geometry).map_err(StepError::Placement)?;
    let detection = config.detection(&model);
    check_scan(&model, &detection.field_of_view, last_time, geometry.time, measurements, capacity)?;
    let weights = WeightModel::placed(config, &model, &detection);
    Ok(PlacedScan { model, detection, weights })
}
