//! Per-object estimation: the extended Kalman filter.
//!
//! - Predict: x̂⁻ = f(x̂), P⁻ = Φ P Φᵀ + Q.
//! - Innovation: ẑ = h(x̂⁻), S = H P⁻ Hᵀ + R, factored once as S = L Lᵀ (Cholesky). A failed
//!   factorisation is [`NumericalError::NotPositiveDefinite`], never ignored.
//! - Likelihood: ln ĝ = ln N(z; ẑ, S) = −½ |L⁻¹ν|² − Σ ln Lᵢᵢ − (D/2) ln 2π with ν = z − ẑ; no explicit
//!   inverse. For a linear model ĝ is the exact predicted likelihood ∫ g(z|x) p⁻(x) dx (docs/maths.md §6.2).
//! - Update: K = P⁻ Hᵀ S⁻¹ (solved through L), x̂ = x̂⁻ + K ν and the Joseph form
//!   P = (I − K H) P⁻ (I − K H)ᵀ + K R Kᵀ, which keeps P symmetric positive semi-definite.
//!
//! Covariances are symmetrised after every operation so that rounding never breaks symmetry.

use crate::model::{MeasurementModel, MotionModel};
use crate::real::{Real, c, ln};
use nalgebra::{Cholesky, SMatrix, SVector};

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
/// [`update`] with P = I and R = 0.25 I: the position gain is 1 / 1.25 = 0.8.
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

/// Why an EKF operation failed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum NumericalError {
    /// A covariance that must be positive definite (S, or a prior covariance) is not.
    NotPositiveDefinite,
    /// A NaN or infinity appeared in a mean or covariance.
    NonFinite,
    /// The motion model failed.
    Model(crate::model::ModelError),
}

impl core::fmt::Display for NumericalError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            NumericalError::NotPositiveDefinite => f.write_str("covariance is not positive definite"),
            NumericalError::NonFinite => f.write_str("non-finite value in a mean or covariance"),
            NumericalError::Model(e) => write!(f, "motion model: {e}"),
        }
    }
}

impl core::error::Error for NumericalError {}

/// The predicted measurement of one predicted track and the Cholesky factor of its innovation
/// covariance: everything needed to score and to apply any measurement.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Innovation<T: Real, const D: usize> {
    /// ẑ = h(x̂⁻).
    pub predicted: SVector<T, D>,
    /// Lower-triangular L with S = L Lᵀ.
    pub cholesky: SMatrix<T, D, D>,
    /// −Σ ln Lᵢᵢ − (D/2) ln 2π: the log-density at ν = 0.
    pub log_normaliser: T,
}

impl<T: Real, const D: usize> Default for Innovation<T, D> {
    fn default() -> Self {
        Self::EMPTY
    }
}

impl<T: Real, const D: usize> Innovation<T, D> {
    /// A placeholder in fixed storage: ẑ = 0, L = I.
    pub(crate) const EMPTY: Self =
        Self { predicted: crate::real::zeros(), cholesky: crate::real::identity(), log_normaliser: T::ZERO };
}

impl<T: Real, const D: usize> Innovation<T, D> {
    /// Factors `covariance` (S) and keeps the factor.
    ///
    /// # Errors
    /// [`NumericalError::NotPositiveDefinite`] when the Cholesky factorisation fails,
    /// [`NumericalError::NonFinite`] on a non-finite input.
    ///
    /// # Examples
    /// ```
    /// use nalgebra::{SMatrix, SVector};
    /// use tracker_core::NumericalError;
    /// use tracker_core::ekf::Innovation;
    /// let s = SMatrix::<f64, 2, 2>::new(4.0, 2.0, 2.0, 3.0);
    /// let innovation = Innovation::new(SVector::zeros(), s)?;
    /// let l = innovation.cholesky;
    /// assert!((l * l.transpose() - s).abs().max() < 1e-12);
    ///
    /// let indefinite = SMatrix::<f64, 2, 2>::new(1.0, 2.0, 2.0, 1.0);
    /// assert_eq!(Innovation::new(SVector::zeros(), indefinite), Err(NumericalError::NotPositiveDefinite));
    /// # Ok::<(), NumericalError>(())
    /// ```
    pub fn new(predicted: SVector<T, D>, covariance: SMatrix<T, D, D>) -> Result<Self, NumericalError> {
        if !predicted.iter().chain(covariance.iter()).all(|v| v.is_finite_value()) {
            return Err(NumericalError::NonFinite);
        }
        let cholesky = Cholesky::new(covariance).ok_or(NumericalError::NotPositiveDefinite)?.unpack();
        let mut log_normaliser = -c::<T>(0.5) * T::of_f64(D as f64) * ln(T::two_pi());
        for i in 0..D {
            let diagonal = cholesky[(i, i)];
            if !(diagonal > T::zero()) {
                return Err(NumericalError::NotPositiveDefinite);
            }
            log_normaliser -= ln(diagonal);
        }
        Ok(Self { predicted, cholesky, log_normaliser })
    }

    /// Solves L y = b (forward substitution).
    fn solve_lower(&self, b: &SVector<T, D>) -> SVector<T, D> {
        let mut y = *b;
        for i in 0..D {
            let mut sum = y[i];
            for k in 0..i {
                sum -= self.cholesky[(i, k)] * y[k];
            }
            y[i] = sum / self.cholesky[(i, i)];
        }
        y
    }

    /// Solves Lᵀ x = y (back substitution).
    fn solve_upper(&self, y: &SVector<T, D>) -> SVector<T, D> {
        let mut x = *y;
        for i in (0..D).rev() {
            let mut sum = x[i];
            for k in (i + 1)..D {
                sum -= self.cholesky[(k, i)] * x[k];
            }
            x[i] = sum / self.cholesky[(i, i)];
        }
        x
    }

    /// The squared Mahalanobis distance d² = νᵀ S⁻¹ ν of `z` and ln N(z; ẑ, S).
    ///
    /// # Examples
    /// ```
    /// use nalgebra::{SMatrix, SVector};
    /// use tracker_core::ekf::Innovation;
    /// let innovation = Innovation::new(SVector::from([1.0, 1.0]), SMatrix::<f64, 2, 2>::identity())?;
    /// let (distance_squared, log_likelihood) = innovation.score(&SVector::from([4.0, 5.0]));
    /// assert_eq!(distance_squared, 25.0); // ν = (3, 4), S = I
    /// let expected = -12.5 - (2.0 * core::f64::consts::PI).ln();
    /// assert!((log_likelihood - expected).abs() < 1e-12);
    /// # Ok::<(), tracker_core::NumericalError>(())
    /// ```
    pub fn score(&self, z: &SVector<T, D>) -> (T, T) {
        let whitened = self.solve_lower(&(z - self.predicted));
        let distance_squared = whitened.norm_squared();
        (distance_squared, self.log_normaliser - c::<T>(0.5) * distance_squared)
    }
}

/// Predicts `prior` over `dt`: x̂⁻ = f(x̂), P⁻ = Φ P Φᵀ + Q.
///
/// # Examples
/// ```
/// use nalgebra::{SMatrix, SVector};
/// use tracker_core::{ConstantVelocity, Gaussian, ekf};
/// let prior = Gaussian { mean: SVector::from([0.0, 0.0, 1.0, 0.0]), covariance: SMatrix::<f64, 4, 4>::identity() };
/// let q = 0.01;
/// let predicted = ekf::predict(&ConstantVelocity { acceleration_noise: q }, &prior, 2.0)?;
/// assert_eq!(predicted.mean, SVector::from([2.0, 0.0, 1.0, 0.0]));
/// // Φ P Φᵀ + Q on x: 1 + dt² from the velocity, plus q dt³ / 3.
/// assert!((predicted.covariance[(0, 0)] - (1.0 + 4.0 + q * 8.0 / 3.0)).abs() < 1e-12);
/// # Ok::<(), tracker_core::NumericalError>(())
/// ```
///
/// # Errors
/// The motion model's error, or [`NumericalError::NonFinite`].
pub fn predict<T: Real, M: MotionModel<T, S>, const S: usize>(
    model: &M,
    prior: &Gaussian<T, S>,
    dt: T,
) -> Result<Gaussian<T, S>, NumericalError> {
    let propagation = model.propagate(&prior.mean, dt).map_err(NumericalError::Model)?;
    let phi = propagation.transition;
    // P⁻ = Φ P Φᵀ + Q
    let covariance = symmetrise(&(phi * prior.covariance * phi.transpose() + model.process_noise(&prior.mean, dt)));
    let predicted = Gaussian { mean: propagation.state, covariance };
    if predicted.mean.iter().chain(predicted.covariance.iter()).all(|v| v.is_finite_value()) {
        Ok(predicted)
    } else {
        Err(NumericalError::NonFinite)
    }
}

/// The innovation of a predicted track: ẑ = h(x̂⁻) and S = H P⁻ Hᵀ + R, factored.
///
/// # Errors
/// [`NumericalError::NotPositiveDefinite`] when S cannot be factored.
///
/// # Examples
/// ```
/// use nalgebra::{SMatrix, SVector};
/// use tracker_core::{Gaussian, PositionMeasurement, ekf};
/// let track = Gaussian { mean: SVector::from([3.0, 4.0, 1.0, 0.0]), covariance: SMatrix::<f64, 4, 4>::identity() };
/// let innovation = ekf::innovation(&PositionMeasurement::isotropic(0.5), &track)?;
/// assert_eq!(innovation.predicted, SVector::from([3.0, 4.0]));
/// // S = H P Hᵀ + R = (1 + 0.25) I.
/// let l = innovation.cholesky;
/// assert!((l * l.transpose() - SMatrix::<f64, 2, 2>::identity() * 1.25).abs().max() < 1e-12);
/// # Ok::<(), tracker_core::NumericalError>(())
/// ```
pub fn innovation<T: Real, G: MeasurementModel<T, S, D>, const S: usize, const D: usize>(
    model: &G,
    predicted: &Gaussian<T, S>,
) -> Result<Innovation<T, D>, NumericalError> {
    let h = model.jacobian(&predicted.mean);
    // S = H P⁻ Hᵀ + R
    let s = symmetrise(&(h * predicted.covariance * h.transpose() + model.noise_covariance()));
    Innovation::new(model.measure(&predicted.mean), s)
}

/// Updates a predicted track with measurement `z` (Joseph form).
///
/// # Errors
/// [`NumericalError::NonFinite`] when the result is not finite.
pub fn update<T: Real, G: MeasurementModel<T, S, D>, const S: usize, const D: usize>(
    model: &G,
    predicted: &Gaussian<T, S>,
    innovation: &Innovation<T, D>,
    z: &SVector<T, D>,
) -> Result<Gaussian<T, S>, NumericalError> {
    let h = model.jacobian(&predicted.mean);
    let hp = h * predicted.covariance; // H P⁻ (D × S)
    // Kᵀ = S⁻¹ H P⁻, column by column through L Lᵀ.
    let mut gain_t = SMatrix::<T, D, S>::zeros();
    for col in 0..S {
        let solved = innovation.solve_upper(&innovation.solve_lower(&hp.column(col).into_owned()));
        gain_t.set_column(col, &solved);
    }
    let gain = gain_t.transpose();
    let nu = z - innovation.predicted;
    let mean = predicted.mean + gain * nu;
    // P = (I − K H) P⁻ (I − K H)ᵀ + K R Kᵀ   (Joseph)
    let i_kh = SMatrix::<T, S, S>::identity() - gain * h;
    let covariance =
        symmetrise(&(i_kh * predicted.covariance * i_kh.transpose() + gain * model.noise_covariance() * gain_t));
    let updated = Gaussian { mean, covariance };
    if updated.mean.iter().chain(updated.covariance.iter()).all(|v| v.is_finite_value()) {
        Ok(updated)
    } else {
        Err(NumericalError::NonFinite)
    }
}

/// ½ (A + Aᵀ).
pub(crate) fn symmetrise<T: Real, const S: usize>(a: &SMatrix<T, S, S>) -> SMatrix<T, S, S> {
    (a + a.transpose()) * c::<T>(0.5)
}

/// Whether `covariance` is finite, symmetric and positive definite (checked by Cholesky).
///
/// # Examples
/// ```
/// use nalgebra::SMatrix;
/// use tracker_core::ekf::is_valid_covariance;
/// assert!(is_valid_covariance(&SMatrix::<f64, 2, 2>::new(2.0, 0.5, 0.5, 1.0)));
/// assert!(!is_valid_covariance(&SMatrix::<f64, 2, 2>::new(2.0, 0.5, 0.4, 1.0))); // not symmetric
/// assert!(!is_valid_covariance(&SMatrix::<f64, 2, 2>::new(1.0, 2.0, 2.0, 1.0))); // indefinite
/// assert!(!is_valid_covariance(&SMatrix::<f64, 2, 2>::new(f64::NAN, 0.0, 0.0, 1.0)));
/// ```
pub fn is_valid_covariance<T: Real, const S: usize>(covariance: &SMatrix<T, S, S>) -> bool {
    covariance.iter().all(|v| v.is_finite_value())
        && *covariance == covariance.transpose()
        && Cholesky::new(*covariance).is_some()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{ConstantVelocity, PositionMeasurement};

    #[test]
    fn log_likelihood_matches_the_gaussian_density() {
        let s = SMatrix::<f64, 2, 2>::new(2.0, 0.3, 0.3, 1.0);
        let innovation = Innovation::new(SVector::from([1.0, -1.0]), s).unwrap();
        let z = SVector::from([1.5, 0.2]);
        let nu = z - SVector::from([1.0, -1.0]);
        let direct = (-0.5 * (nu.transpose() * s.try_inverse().unwrap() * nu)[0]).exp()
            / (2.0 * core::f64::consts::PI * s.determinant().sqrt());
        let (_, log_g) = innovation.score(&z);
        assert!((log_g.exp() - direct).abs() < 1e-15);
    }

    #[test]
    fn update_matches_the_textbook_kalman_filter() {
        let model = PositionMeasurement::isotropic(0.7);
        let prior = Gaussian {
            mean: SVector::from([1.0, 2.0, 0.5, -0.5]),
            covariance: SMatrix::<f64, 4, 4>::from_diagonal(&SVector::from([4.0, 3.0, 1.0, 2.0])),
        };
        let predicted = predict(&ConstantVelocity { acceleration_noise: 0.2 }, &prior, 1.5).unwrap();
        let innov = innovation(&model, &predicted).unwrap();
        let z = SVector::from([2.0, 1.0]);
        let posterior = update(&model, &predicted, &innov, &z).unwrap();
        // Simple form: K = P Hᵀ (H P Hᵀ + R)⁻¹, P = (I − K H) P.
        let h = model.jacobian(&predicted.mean);
        let s = h * predicted.covariance * h.transpose() + model.noise;
        let k = predicted.covariance * h.transpose() * s.try_inverse().unwrap();
        let mean = predicted.mean + k * (z - h * predicted.mean);
        let cov = (SMatrix::<f64, 4, 4>::identity() - k * h) * predicted.covariance;
        assert!((posterior.mean - mean).abs().max() < 1e-12);
        assert!((posterior.covariance - cov).abs().max() < 1e-12);
    }

    #[test]
    fn indefinite_innovation_covariance_is_an_error() {
        let s = SMatrix::<f64, 2, 2>::new(1.0, 2.0, 2.0, 1.0);
        assert_eq!(Innovation::new(SVector::zeros(), s), Err(NumericalError::NotPositiveDefinite));
    }
}
