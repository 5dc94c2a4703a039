//! Position measurement of a planar state: z = (x, y) + v, v ~ N(0, R). Linear: H = [I 0].

use super::admissible::planar_birth;
use super::{AdmissibleRegion, BirthComponent, BirthError, BirthGeometry, Measure};
use crate::real::Real;
use crate::sensor::Placement;
use nalgebra::{SMatrix, SVector};

/// Measures the position (x, y) of a state (x, y, vx, vy) with Gaussian noise of covariance R.
///
/// # Examples
/// ```
/// use tracker_core::model::{Measure, PositionMeasurement};
/// use nalgebra::{SMatrix, SVector};
/// let sensor = PositionMeasurement::isotropic(0.5_f64);
/// assert_eq!(sensor.measure(&SVector::from([1.0, 2.0, 3.0, 4.0])), SVector::from([1.0, 2.0]));
/// assert_eq!(sensor.noise_covariance(), SMatrix::<f64, 2, 2>::identity() * 0.25);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PositionMeasurement<T: Real> {
    /// Measurement noise covariance R (symmetric positive definite).
    pub noise: SMatrix<T, 2, 2>,
}

impl<T: Real> PositionMeasurement<T> {
    /// Independent noise of standard deviation `sigma` on each axis.
    ///
    /// # Examples
    /// ```
    /// use nalgebra::SMatrix;
    /// use tracker_core::PositionMeasurement;
    /// let sensor = PositionMeasurement::isotropic(0.1_f32);
    /// assert_eq!(sensor.noise, SMatrix::<f32, 2, 2>::new(0.1 * 0.1, 0.0, 0.0, 0.1 * 0.1));
    /// ```
    pub fn isotropic(sigma: T) -> Self {
        Self { noise: SMatrix::<T, 2, 2>::identity() * (sigma * sigma) }
    }
}

impl<T: Real> Measure<T, 4, 2> for PositionMeasurement<T> {
    fn measure(&self, state: &SVector<T, 4>) -> SVector<T, 2> {
        SVector::from([state[0], state[1]])
    }

    fn jacobian(&self, _state: &SVector<T, 4>) -> SMatrix<T, 2, 4> {
        let mut h = SMatrix::<T, 2, 4>::zeros();
        h[(0, 0)] = T::one();
        h[(1, 1)] = T::one();
        h
    }

    fn noise_covariance(&self) -> SMatrix<T, 2, 2> {
        self.noise
    }
}

impl<T: Real> Placement<T, 2> for PositionMeasurement<T> {}

impl<T: Real> BirthGeometry<T, 4, 2> for PositionMeasurement<T> {
    /// One component: position z with covariance R, velocity N(0, `velocity_sigma`² I).
    fn birth_components(
        &self,
        z: &SVector<T, 2>,
        region: &AdmissibleRegion<T>,
        out: &mut [BirthComponent<T, 4>],
    ) -> Result<usize, BirthError> {
        planar_birth(z, &self.noise, region, out)
    }
}
