//! Planar two-body (Keplerian) motion: state (x, y, vx, vy) with r̈ = −μ r / |r|³.
//!
//! The state and its transition matrix Φ are integrated together by classical fixed-step RK4 on the
//! variational equations Φ̇ = A(x) Φ, with A = [[0, I], [G, 0]] and the gravity gradient
//! G = μ (3 r rᵀ / |r|⁵ − I / |r|³). A time step `dt` is split into `ceil(dt / max_step)` equal sub-steps;
//! more than `max_substeps` is an error, which bounds the cost of one prediction. Process noise is white
//! acceleration noise, as for constant velocity.

use super::{ModelError, MotionModel, Propagation, white_acceleration_noise};
use crate::real::{Real, c, floor, sqrt};
use nalgebra::{SMatrix, SVector};

/// The planar two-body motion model.
///
/// # Examples
/// A circular orbit returns to its start after one period:
/// ```
/// use tracker_core::model::{MotionModel, TwoBody};
/// use nalgebra::SVector;
/// let mu = 398_600.441_8_f64; // km³/s²
/// let r = 7000.0;
/// let v = (mu / r).sqrt();
/// let period = 2.0 * core::f64::consts::PI * (r * r * r / mu).sqrt();
/// let model = TwoBody { mu, acceleration_noise: 1e-9, max_step: 10.0, max_substeps: 10_000 };
/// let p = model.propagate(&SVector::from([r, 0.0, 0.0, v]), period).unwrap();
/// assert!((p.state[0] - r).abs() < 1e-3 && p.state[1].abs() < 1e-3);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TwoBody<T> {
    /// Gravitational parameter μ (length³ / s²; 398600.4418 km³/s² for the Earth).
    pub mu: T,
    /// Power spectral density q of the white acceleration noise (length² / s³).
    pub acceleration_noise: T,
    /// Largest RK4 sub-step (s).
    pub max_step: T,
    /// Most sub-steps one propagation may take; a longer `dt` is [`ModelError::TimeStepTooLarge`].
    pub max_substeps: u32,
}

impl<T: Real> TwoBody<T> {
    /// Time derivative of the state and of Φ: (ẋ, Φ̇) = (f(x), A(x) Φ).
    fn derivative(
        &self,
        state: &SVector<T, 4>,
        phi: &SMatrix<T, 4, 4>,
    ) -> Result<(SVector<T, 4>, SMatrix<T, 4, 4>), ModelError> {
        let (x, y) = (state[0], state[1]);
        let r2 = x * x + y * y;
        if !(r2 > T::zero()) || !r2.is_finite_value() {
            return Err(ModelError::Singular);
        }
        let r = sqrt(r2);
        let inv_r3 = T::one() / (r2 * r);
        let inv_r5 = inv_r3 / r2;
        // a = −μ r / |r|³
        let derivative = SVector::from([state[2], state[3], -self.mu * x * inv_r3, -self.mu * y * inv_r3]);
        // G = μ (3 r rᵀ / |r|⁵ − I / |r|³)
        let three = c::<T>(3.0);
        let gxx = self.mu * (three * x * x * inv_r5 - inv_r3);
        let gxy = self.mu * (three * x * y * inv_r5);
        let gyy = self.mu * (three * y * y * inv_r5 - inv_r3);
        let mut phi_dot = SMatrix::<T, 4, 4>::zeros();
        for col in 0..4 {
            // Rows 0-1: velocity rows of Φ; rows 2-3: G times the position rows of Φ.
            phi_dot[(0, col)] = phi[(2, col)];
            phi_dot[(1, col)] = phi[(3, col)];
            phi_dot[(2, col)] = gxx * phi[(0, col)] + gxy * phi[(1, col)];
            phi_dot[(3, col)] = gxy * phi[(0, col)] + gyy * phi[(1, col)];
        }
        Ok((derivative, phi_dot))
    }
}

impl<T: Real> MotionModel<T, 4> for TwoBody<T> {
    fn propagate(&self, state: &SVector<T, 4>, dt: T) -> Result<Propagation<T, 4>, ModelError> {
        let ratio = dt / self.max_step;
        if !ratio.is_finite_value() || ratio < T::zero() {
            return Err(ModelError::NonFinite);
        }
        // n = ceil(dt / max_step), at least one sub-step.
        let steps_real = -floor(-ratio);
        if steps_real > T::of_f64(f64::from(self.max_substeps)) {
            return Err(ModelError::TimeStepTooLarge);
        }
        let steps = (steps_real.as_f64() as u32).max(1);
        let h = dt / T::of_f64(f64::from(steps));
        let half = c::<T>(0.5);
        let sixth = T::one() / c(6.0);
        let two = c::<T>(2.0);

        let mut x = *state;
        let mut phi = SMatrix::<T, 4, 4>::identity();
        for _ in 0..steps {
            let (k1x, k1p) = self.derivative(&x, &phi)?;
            let (k2x, k2p) = self.derivative(&(x + k1x * (h * half)), &(phi + k1p * (h * half)))?;
            let (k3x, k3p) = self.derivative(&(x + k2x * (h * half)), &(phi + k2p * (h * half)))?;
            let (k4x, k4p) = self.derivative(&(x + k3x * h), &(phi + k3p * h))?;
            x += (k1x + k2x * two + k3x * two + k4x) * (h * sixth);
            phi += (k1p + k2p * two + k3p * two + k4p) * (h * sixth);
        }
        if x.iter().chain(phi.iter()).all(|v| v.is_finite_value()) {
            Ok(Propagation { state: x, transition: phi })
        } else {
            Err(ModelError::NonFinite)
        }
    }

    fn process_noise(&self, _state: &SVector<T, 4>, dt: T) -> SMatrix<T, 4, 4> {
        white_acceleration_noise(self.acceleration_noise, dt)
    }

    fn validate(&self) -> Result<(), &'static str> {
        if !(self.mu.is_finite_value() && self.mu > T::zero()) {
            return Err("two-body: mu must be finite and > 0");
        }
        if !(self.acceleration_noise.is_finite_value() && self.acceleration_noise > T::zero()) {
            return Err("two-body: acceleration_noise must be finite and > 0 (Q positive definite)");
        }
        if !(self.max_step.is_finite_value() && self.max_step > T::zero()) {
            return Err("two-body: max_step must be finite and > 0");
        }
        if self.max_substeps == 0 {
            return Err("two-body: max_substeps must be > 0");
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn leo() -> (TwoBody<f64>, SVector<f64, 4>) {
        let mu = 398_600.441_8;
        let r: f64 = 7000.0;
        let v = (mu / r).sqrt();
        (
            TwoBody { mu, acceleration_noise: 1e-9, max_step: 10.0, max_substeps: 1000 },
            SVector::from([r, 0.0, 0.0, v * 1.05]),
        )
    }

    #[test]
    fn transition_matrix_matches_finite_differences() {
        let (model, x0) = leo();
        let dt = 120.0;
        let base = model.propagate(&x0, dt).unwrap();
        for j in 0..4 {
            let eps = if j < 2 { 1e-3 } else { 1e-6 };
            let mut plus = x0;
            plus[j] += eps;
            let mut minus = x0;
            minus[j] -= eps;
            let column =
                (model.propagate(&plus, dt).unwrap().state - model.propagate(&minus, dt).unwrap().state) / (2.0 * eps);
            for i in 0..4 {
                let expected = column[i];
                let got = base.transition[(i, j)];
                assert!(
                    (got - expected).abs() <= 1e-6 * (1.0 + expected.abs()),
                    "Φ[{i},{j}] = {got}, finite difference {expected}"
                );
            }
        }
    }

    #[test]
    fn energy_is_conserved_over_an_hour() {
        let (model, x0) = leo();
        let energy =
            |x: &SVector<f64, 4>| 0.5 * (x[2] * x[2] + x[3] * x[3]) - model.mu / (x[0] * x[0] + x[1] * x[1]).sqrt();
        let x1 = model.propagate(&x0, 3600.0).unwrap().state;
        assert!((energy(&x1) - energy(&x0)).abs() < 1e-8 * energy(&x0).abs());
    }

    #[test]
    fn too_long_a_step_is_an_error() {
        let (model, x0) = leo();
        assert_eq!(model.propagate(&x0, 10.0 * 1001.0), Err(ModelError::TimeStepTooLarge));
        assert!(model.propagate(&x0, 10.0 * 1000.0).is_ok());
    }

    #[test]
    fn origin_is_singular() {
        let (model, _) = leo();
        assert_eq!(model.propagate(&SVector::from([0.0, 0.0, 1.0, 0.0]), 1.0), Err(ModelError::Singular));
    }
}
