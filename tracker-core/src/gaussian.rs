//! The Gaussian density N(mean, covariance) that each object has under each hypothesis: what the EKF
//! ([`crate::ekf`]) predicts and updates, what the track store holds and what a birth component is.

use crate::real::Real;
use nalgebra::{SMatrix, SVector};

/// A Gaussian density N(mean, covariance): the pdf of one object under one hypothesis.
///
/// # Examples
/// One EKF cycle: predict, score a measurement, update.
/// ```
/// use nalgebra::{SMatrix, SVector};
/// use tracker_core::{ConstantVelocity, Gaussian, PositionMeasurement, ekf};
/// let prior = Gaussian { mean: SVector::from([0.0, 0.0, 1.0, 0.0]), covariance: SMatrix::<f64, 4, 4>::identity() };
/// let motion = ConstantVelocity { acceleration_noise: 0.01 };
/// let sensor = PositionMeasurement::isotropic(0.5);
///
/// let predicted = ekf::predict(&motion, &prior, 1.0)?;
/// let innovation = ekf::innovation(&sensor, &predicted)?;
/// let z = SVector::from([1.2, -0.1]);
/// let (distance_squared, log_likelihood) = innovation.score(&z);
/// assert!(distance_squared < 1.0 && log_likelihood.is_finite());
/// let posterior = ekf::update(&sensor, &predicted, &innovation, &z)?;
/// assert!(posterior.covariance[(0, 0)] < predicted.covariance[(0, 0)]);
/// assert!(ekf::is_valid_covariance(&posterior.covariance));
/// # Ok::<(), tracker_core::NumericalError>(())
/// ```
///
/// [`ekf::update`](crate::ekf::update) with P = I and R = 0.25 I: the position gain is 1 / 1.25 = 0.8.
/// ```
/// use nalgebra::{SMatrix, SVector};
/// use tracker_core::{Gaussian, PositionMeasurement, ekf};
/// let sensor = PositionMeasurement::isotropic(0.5);
/// let track = Gaussian { mean: SVector::zeros(), covariance: SMatrix::<f64, 4, 4>::identity() };
/// let innovation = ekf::innovation(&sensor, &track)?;
/// let updated = ekf::update(&sensor, &track, &innovation, &SVector::from([1.0, -2.0]))?;
/// assert!((updated.mean - SVector::from([0.8, -1.6, 0.0, 0.0])).abs().max() < 1e-12);
/// assert!((updated.covariance[(0, 0)] - 0.2).abs() < 1e-12); // (1 − 0.8) · 1
/// assert_eq!(updated.covariance[(2, 2)], 1.0); // the velocity is not correlated with the position
/// # Ok::<(), tracker_core::NumericalError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Gaussian<T: Real, const S: usize> {
    /// Mean x̂.
    pub mean: SVector<T, S>,
    /// Covariance P (symmetric positive semi-definite).
    pub covariance: SMatrix<T, S, S>,
}

impl<T: Real, const S: usize> Default for Gaussian<T, S> {
    fn default() -> Self {
        Self::ZERO
    }
}

impl<T: Real, const S: usize> Gaussian<T, S> {
    /// Zero mean and zero covariance (a placeholder in fixed storage).
    pub const ZERO: Self = Self { mean: crate::real::zeros(), covariance: crate::real::zeros() };
}
