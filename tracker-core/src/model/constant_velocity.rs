//! 2-D constant velocity: state (x, y, vx, vy), x(t+dt) = F x(t) with F = [[I, dt I], [0, I]], and white
//! acceleration noise. Linear, so the EKF is an exact Kalman filter: the model of the exactness tests.

use super::{ModelError, MotionModel, Propagation, white_acceleration_noise};
use crate::real::Real;
use nalgebra::{SMatrix, SVector};

/// The 2-D constant-velocity motion model.
///
/// # Examples
/// ```
/// use tracker_core::model::{ConstantVelocity, MotionModel};
/// use nalgebra::SVector;
/// let model = ConstantVelocity { acceleration_noise: 0.1_f64 };
/// let p = model.propagate(&SVector::from([0.0, 0.0, 1.0, 2.0]), 2.0).unwrap();
/// assert_eq!(p.state, SVector::from([2.0, 4.0, 1.0, 2.0]));
/// ```
///
/// Its process noise is white acceleration noise, Q = q [[dt³/3 I, dt²/2 I], [dt²/2 I, dt I]]:
/// ```
/// use tracker_core::model::{ConstantVelocity, MotionModel};
/// use nalgebra::SVector;
/// let model = ConstantVelocity { acceleration_noise: 0.3_f64 };
/// let q = model.process_noise(&SVector::zeros(), 2.0);
/// assert!((q[(0, 0)] - 0.3 * 8.0 / 3.0).abs() < 1e-15);
/// assert!((q[(0, 2)] - 0.3 * 2.0).abs() < 1e-15 && (q[(2, 2)] - 0.3 * 2.0).abs() < 1e-15);
/// assert_eq!(q[(0, 1)], 0.0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ConstantVelocity<T> {
    /// Power spectral density q of the white acceleration noise (position units² / s³).
    pub acceleration_noise: T,
}

impl<T: Real> MotionModel<T, 4> for ConstantVelocity<T> {
    fn propagate(&self, state: &SVector<T, 4>, dt: T) -> Result<Propagation<T, 4>, ModelError> {
        let mut transition = SMatrix::<T, 4, 4>::identity();
        transition[(0, 2)] = dt;
        transition[(1, 3)] = dt;
        let propagated = transition * state;
        if propagated.iter().all(|v| v.is_finite_value()) {
            Ok(Propagation { state: propagated, transition })
        } else {
            Err(ModelError::NonFinite)
        }
    }

    fn process_noise(&self, _state: &SVector<T, 4>, dt: T) -> SMatrix<T, 4, 4> {
        white_acceleration_noise(self.acceleration_noise, dt)
    }

    fn validate(&self) -> Result<(), &'static str> {
        if self.acceleration_noise.is_finite_value() && self.acceleration_noise > T::zero() {
            Ok(())
        } else {
            Err("constant velocity: acceleration_noise must be finite and > 0 (Q positive definite)")
        }
    }
}
