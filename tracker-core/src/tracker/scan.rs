//! The one check of a scan's inputs, shared by the tracker and the host's unbounded reference tracker.

use crate::error::StepError;
use crate::real::Real;
use crate::sensor::Region;
use nalgebra::SVector;

/// Checks a scan taken at `time` after a last scan (or prior) at `last_time`: at most `capacity`
/// measurements, a finite time after the last one, every measurement finite and inside the sensor's
/// `field_of_view`.
///
/// # Errors
/// The first [`StepError`] found, in the order above.
///
/// # Examples
/// ```
/// use nalgebra::SVector;
/// use tracker_core::{Region, StepError, tracker::check_scan};
/// let view = Region::Rectangle { min: [0.0, 0.0], max: [10.0, 10.0] };
/// let z = [SVector::from([1.0, 2.0])];
/// assert_eq!(check_scan(&view, 0.0, 1.0, &z, 4), Ok(()));
/// assert_eq!(check_scan(&view, 1.0, 1.0, &z, 4), Err(StepError::TimeNotAfterLastScan));
/// assert_eq!(check_scan(&view, 0.0, 1.0, &z, 0), Err(StepError::TooManyMeasurements { received: 1, capacity: 0 }));
/// let far = [SVector::from([11.0, 2.0])];
/// assert_eq!(check_scan(&view, 0.0, 1.0, &far, 4), Err(StepError::MeasurementOutsideFieldOfView { index: 0 }));
/// ```
pub fn check_scan<T: Real, const D: usize>(
    field_of_view: &Region<T>,
    last_time: f64,
    time: f64,
    measurements: &[SVector<T, D>],
    capacity: usize,
) -> Result<(), StepError> {
    if measurements.len() > capacity {
        return Err(StepError::TooManyMeasurements { received: measurements.len(), capacity });
    }
    if !time.is_finite() {
        return Err(StepError::NonFiniteTime);
    }
    if time <= last_time {
        return Err(StepError::TimeNotAfterLastScan);
    }
    for (index, z) in measurements.iter().enumerate() {
        if !z.iter().all(|v| v.is_finite_value()) {
            return Err(StepError::NonFiniteMeasurement { index });
        }
        if !field_of_view.contains(z) {
            return Err(StepError::MeasurementOutsideFieldOfView { index });
        }
    }
    Ok(())
}
