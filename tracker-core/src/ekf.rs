//! Per-object estimation: the extended Kalman filter.
//!
//! - Predict: x̂⁻ = f(x̂), P⁻ = Φ P Φᵀ + Q.
//! - Innovation: ẑ = h(x̂⁻), S = H P⁻ Hᵀ + R, factored once as S = L Lᵀ (Cholesky). A failed
//!   factorisation is [`NumericalError::NotPositiveDefinite`], never ignored.
//! - Likelihood: ln ĝ = ln N(z; ẑ, S) = −½ |L⁻¹ν|² − Σ ln Lᵢᵢ − (D/2) ln 2π with ν = z − ẑ; no explicit
//!   inverse. For a linear model ĝ is the exact predicted likelihood ∫ g(z|x) p⁻(x) dx (docs/maths.md §6.2).
//! - Update: K = P⁻ Hᵀ S⁻¹ (solved through L), x̂ = x̂⁻ + K ν and the Joseph form
//!   P = (I − K H) P⁻ (I − K H)ᵀ + K R Kᵀ. K, H and P depend on the predicted track only, not on z, so
//!   [`correction`] computes them once per track and [`Correction::apply`] adds K ν for each measurement;
//!   [`update`] is the two in one call, with the same bits.
//!
//! **Invariant.** Every covariance in an `Ok` result of [`predict`] and [`update`] (and of
//! [`correction`]) is finite, exactly symmetric and positive definite by a Cholesky factorisation: it
//! passes [`is_valid_covariance`], so one bad step cannot poison the next scans. Covariances are
//! symmetrised after every operation, and the result is then factored. Exact arithmetic keeps P positive
//! definite; rounding does not when P is so wide that the step must cancel most of its digits (a
//! velocity variance of 10²⁵ against a measurement variance of 0.25 needs 26 significant digits; f64 has
//! 16, f32 7), and the Joseph form then returned negative variances. Now:
//! - a covariance that factors is returned as computed, the same bits as without the check;
//! - one that does not is repaired once, each variance multiplied by 1 + 8 ε (ε the scalar's machine
//!   epsilon: a change of the order of the rounding that broke it, and conservative); this keeps tracks
//!   whose covariance is singular only to rounding (wide priors, a rank-deficient R);
//! - one the repair does not fix is [`NumericalError::NotPositiveDefinite`], handled by the tracker's
//!   [`crate::config::NumericalFailure`] policy.
//!
//! In f32 this is not only a matter of absurd priors: on the QEMU scenario (fifty-birth-death, seed 1)
//! the embedded `SsaTracker<f32>` produced a covariance that fails Cholesky at scan 34; the repair keeps
//! that track. A square-root (Cholesky-factor) filter would keep P positive semi-definite by
//! construction, but it changes the bits of every step (the QEMU digest and the golden files) and costs
//! more per update.

use crate::gaussian::Gaussian;
use crate::model::{Measure, MotionModel};
use crate::real::{Real, c, ln};
use nalgebra::{Cholesky, SMatrix, SVector};

/// Why an EKF operation failed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum NumericalError {
    /// A covariance that must be positive definite is not: S, or the result of a prediction or an update
    /// (rounding lost its definiteness, see the module documentation).
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
        Self::with_dimension(predicted, covariance, D)
    }

    /// [`Innovation::new`] for a measurement of `dimension` ≤ `D` components padded to `D`: the padding's
    /// rows and columns of S are those of the identity, so the Cholesky factor, the distance and the
    /// determinant are the `dimension`-component ones, and the normaliser is (2π)^(−dimension/2)
    /// (docs/maths.md §6.10).
    ///
    /// # Errors
    /// As [`Innovation::new`].
    pub fn with_dimension(
        predicted: SVector<T, D>,
        covariance: SMatrix<T, D, D>,
        dimension: usize,
    ) -> Result<Self, NumericalError> {
        if !predicted.iter().chain(covariance.iter()).all(|v| v.is_finite_value()) {
            return Err(NumericalError::NonFinite);
        }
        let cholesky = Cholesky::new(covariance).ok_or(NumericalError::NotPositiveDefinite)?.unpack();
        let mut log_normaliser = -c::<T>(0.5) * T::of_f64(dimension.min(D) as f64) * ln(T::two_pi());
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
        self.score_residual(&(z - self.predicted))
    }

    /// [`Innovation::score`] from the residual ν = z − ẑ (as the measurement model forms it).
    pub fn score_residual(&self, residual: &SVector<T, D>) -> (T, T) {
        let whitened = self.solve_lower(residual);
        // Σ w_i² in component order (nalgebra sums a 4-vector pairwise), so that the zeros of a padded
        // measurement add nothing and a kind is scored with the bits of its own dimension (docs/maths.md §6.10).
        let distance_squared = whitened.iter().fold(T::zero(), |sum, w| sum + *w * *w);
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
/// The motion model's error, [`NumericalError::NonFinite`], or [`NumericalError::NotPositiveDefinite`]
/// when P⁻ does not factor.
pub fn predict<T: Real, M: MotionModel<T, S>, const S: usize>(
    model: &M,
    prior: &Gaussian<T, S>,
    dt: T,
) -> Result<Gaussian<T, S>, NumericalError> {
    let propagation = model.propagate(&prior.mean, dt).map_err(NumericalError::Model)?;
    let phi = propagation.transition;
    // P⁻ = Φ P Φᵀ + Q
    let covariance = symmetrise(&(phi * prior.covariance * phi.transpose() + model.process_noise(&prior.mean, dt)));
    check(Gaussian { mean: propagation.state, covariance })
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
pub fn innovation<T: Real, G: Measure<T, S, D>, const S: usize, const D: usize>(
    model: &G,
    predicted: &Gaussian<T, S>,
) -> Result<Innovation<T, D>, NumericalError> {
    let h = model.jacobian(&predicted.mean);
    // S = H P⁻ Hᵀ + R
    let s = symmetrise(&(h * predicted.covariance * h.transpose() + model.noise_covariance()));
    Innovation::with_dimension(model.measure(&predicted.mean), s, model.dimension())
}

/// The measurement-independent part of an update: the gain K and the posterior covariance P.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Correction<T: Real, const S: usize, const D: usize> {
    /// K = P⁻ Hᵀ S⁻¹.
    pub gain: SMatrix<T, S, D>,
    /// The Joseph-form posterior covariance (passes [`is_valid_covariance`]).
    pub covariance: SMatrix<T, S, S>,
}

/// The gain and the posterior covariance of a predicted track (Joseph form); they do not depend on the
/// measurement.
///
/// # Errors
/// [`NumericalError::NonFinite`] when they are not finite, [`NumericalError::NotPositiveDefinite`] when
/// the posterior covariance does not factor.
pub fn correction<T: Real, G: Measure<T, S, D>, const S: usize, const D: usize>(
    model: &G,
    predicted: &Gaussian<T, S>,
    innovation: &Innovation<T, D>,
) -> Result<Correction<T, S, D>, NumericalError> {
    let h = model.jacobian(&predicted.mean);
    let hp = h * predicted.covariance; // H P⁻ (D × S)
    // Kᵀ = S⁻¹ H P⁻, column by column through L Lᵀ.
    let mut gain_t = SMatrix::<T, D, S>::zeros();
    for col in 0..S {
        let solved = innovation.solve_upper(&innovation.solve_lower(&hp.column(col).into_owned()));
        gain_t.set_column(col, &solved);
    }
    let gain = gain_t.transpose();
    // P = (I − K H) P⁻ (I − K H)ᵀ + K R Kᵀ   (Joseph)
    let i_kh = SMatrix::<T, S, S>::identity() - gain * h;
    let covariance =
        symmetrise(&(i_kh * predicted.covariance * i_kh.transpose() + gain * model.noise_covariance() * gain_t));
    if !gain.iter().chain(covariance.iter()).all(|v| v.is_finite_value()) {
        return Err(NumericalError::NonFinite);
    }
    Ok(Correction { gain, covariance: positive_definite(covariance)? })
}

impl<T: Real, const S: usize, const D: usize> Correction<T, S, D> {
    /// The posterior of `predicted` given measurement `z`: mean x̂⁻ + K (z − ẑ), covariance P.
    ///
    /// # Errors
    /// [`NumericalError::NonFinite`] when the mean is not finite.
    pub fn apply(
        &self,
        predicted: &Gaussian<T, S>,
        innovation: &Innovation<T, D>,
        z: &SVector<T, D>,
    ) -> Result<Gaussian<T, S>, NumericalError> {
        self.apply_residual(predicted, &(z - innovation.predicted))
    }

    /// [`Correction::apply`] from the residual ν = z − ẑ (as the measurement model forms it).
    ///
    /// # Errors
    /// [`NumericalError::NonFinite`] when the mean is not finite.
    pub fn apply_residual(
        &self,
        predicted: &Gaussian<T, S>,
        residual: &SVector<T, D>,
    ) -> Result<Gaussian<T, S>, NumericalError> {
        let mean = predicted.mean + self.gain * residual;
        if mean.iter().all(|v| v.is_finite_value()) {
            Ok(Gaussian { mean, covariance: self.covariance })
        } else {
            Err(NumericalError::NonFinite)
        }
    }
}

/// Updates a predicted track with measurement `z` (Joseph form): [`correction`] then
/// [`Correction::apply`].
///
/// # Errors
/// [`NumericalError::NonFinite`] when the result is not finite, [`NumericalError::NotPositiveDefinite`]
/// when the posterior covariance does not factor.
pub fn update<T: Real, G: Measure<T, S, D>, const S: usize, const D: usize>(
    model: &G,
    predicted: &Gaussian<T, S>,
    innovation: &Innovation<T, D>,
    z: &SVector<T, D>,
) -> Result<Gaussian<T, S>, NumericalError> {
    correction(model, predicted, innovation)?.apply_residual(predicted, &model.residual(z, &innovation.predicted))
}

/// `gaussian` when it is finite and its covariance factors (after [`positive_definite`]).
fn check<T: Real, const S: usize>(gaussian: Gaussian<T, S>) -> Result<Gaussian<T, S>, NumericalError> {
    if !gaussian.mean.iter().chain(gaussian.covariance.iter()).all(|v| v.is_finite_value()) {
        return Err(NumericalError::NonFinite);
    }
    Ok(Gaussian { mean: gaussian.mean, covariance: positive_definite(gaussian.covariance)? })
}

/// Relative inflation of the diagonal in the repair of [`positive_definite`], in units of ε.
const REPAIR_EPSILONS: f64 = 8.0;

/// A finite symmetric `covariance` when it factors (the same bits); otherwise, once, with each variance
/// multiplied by 1 + 8 ε (ε the scalar's machine epsilon), a change of the order of the rounding of the
/// operation that produced it, when that factors; otherwise [`NumericalError::NotPositiveDefinite`].
fn positive_definite<T: Real, const S: usize>(
    covariance: SMatrix<T, S, S>,
) -> Result<SMatrix<T, S, S>, NumericalError> {
    if Cholesky::new(covariance).is_some() {
        return Ok(covariance);
    }
    let factor = T::one() + T::of_f64(REPAIR_EPSILONS) * T::default_epsilon();
    let mut inflated = covariance;
    for i in 0..S {
        inflated[(i, i)] *= factor;
    }
    match Cholesky::new(inflated) {
        Some(_) => Ok(inflated),
        None => Err(NumericalError::NotPositiveDefinite),
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

    /// The issue-17 priors: a track whose velocity variance is 10ⁿ, predicted and updated scan after
    /// scan. Every `Ok` covariance passes `is_valid_covariance`; every failure is typed.
    fn wide_prior<T: Real>(variance: f64, dt: f64, scans: usize) -> Result<(), NumericalError> {
        let motion = ConstantVelocity { acceleration_noise: T::of_f64(0.01) };
        let sensor = PositionMeasurement::isotropic(T::of_f64(0.5));
        let mut track = Gaussian {
            mean: SVector::from([0.0, 0.0, 1.0, 1.0].map(T::of_f64)),
            covariance: SMatrix::from_diagonal(&SVector::from([1.0, 1.0, variance, variance].map(T::of_f64))),
        };
        for _ in 0..scans {
            let predicted = predict(&motion, &track, T::of_f64(dt))?;
            assert!(is_valid_covariance(&predicted.covariance), "{:?}", predicted.covariance);
            let innov = innovation(&sensor, &predicted)?;
            let z = innov.predicted + SVector::from([0.3, -0.2].map(T::of_f64));
            track = update(&sensor, &predicted, &innov, &z)?;
            assert!(is_valid_covariance(&track.covariance), "{:?}", track.covariance);
        }
        Ok(())
    }

    fn typed(result: Result<(), NumericalError>) -> bool {
        matches!(result, Ok(()) | Err(NumericalError::NotPositiveDefinite | NumericalError::NonFinite))
    }

    #[test]
    fn wide_prior_gives_a_positive_definite_covariance_or_a_typed_error() {
        let mut failed = [0usize; 2];
        for exponent in 0..=36 {
            let variance = 10f64.powi(exponent);
            for dt in [1e-3, 1.0, 60.0] {
                let results = [wide_prior::<f64>(variance, dt, 4), wide_prior::<f32>(variance, dt, 4)];
                for (count, result) in failed.iter_mut().zip(results) {
                    assert!(typed(result), "variance {variance:e}, dt {dt}: {result:?}");
                    *count += usize::from(result.is_err());
                }
            }
        }
        // Moderate priors work in both precisions; f64 survives wider priors than f32 (with the
        // repair); f32 fails on some (typed, never indefinite).
        assert_eq!(wide_prior::<f64>(1e10, 1.0, 4), Ok(()));
        assert_eq!(wide_prior::<f32>(1e5, 1.0, 4), Ok(()));
        assert_eq!(wide_prior::<f64>(1e25, 1.0, 4), Ok(()));
        assert_eq!(wide_prior::<f32>(1e25, 1.0, 4), Err(NumericalError::NotPositiveDefinite));
        assert!(failed[1] > failed[0], "failures f64/f32: {failed:?}");
    }

    #[test]
    fn repair_is_bounded_and_only_touches_failing_covariances() {
        // A covariance that factors is returned unchanged (same bits).
        let good = SMatrix::<f64, 2, 2>::new(2.0, 0.3, 0.3, 1.0);
        assert_eq!(positive_definite(good), Ok(good));
        // Singular to rounding: repaired by the 1 + 8ε inflation of the diagonal, nothing else.
        let singular = SMatrix::<f64, 2, 2>::repeat(1e25);
        let repaired = positive_definite(singular).unwrap();
        assert!(Cholesky::new(singular).is_none() && is_valid_covariance(&repaired));
        assert_eq!(repaired[(0, 1)], singular[(0, 1)]);
        assert_eq!(repaired[(0, 0)], 1e25 * (1.0 + 8.0 * f64::EPSILON));
        // Indefinite beyond rounding: an error.
        let indefinite = SMatrix::<f64, 2, 2>::new(1.0, 1.0 + 1e-12, 1.0 + 1e-12, 1.0);
        assert_eq!(positive_definite(indefinite), Err(NumericalError::NotPositiveDefinite));
        let negative = SMatrix::<f32, 2, 2>::new(1.0, 0.0, 0.0, -57.5);
        assert_eq!(positive_definite(negative), Err(NumericalError::NotPositiveDefinite));
    }

    /// Without the final check the Joseph form of a 10²⁵ prior is indefinite: the check is what stops it.
    #[test]
    fn unchecked_joseph_form_of_a_wide_prior_is_indefinite() {
        let sensor = PositionMeasurement::isotropic(0.5f32);
        let predicted = Gaussian {
            mean: SVector::from([1.0f32, 1.0, 1.0, 1.0]),
            covariance: SMatrix::from_fn(|i, j| if i % 2 == j % 2 { 1e25f32 } else { 0.0 }),
        };
        let innov = innovation(&sensor, &predicted).unwrap();
        let h = sensor.jacobian(&predicted.mean);
        let hp = h * predicted.covariance;
        let gain_t = SMatrix::<f32, 2, 4>::from_fn(|i, j| hp[(i, j)] / (1e25 + 0.25));
        let gain = gain_t.transpose();
        let i_kh = SMatrix::<f32, 4, 4>::identity() - gain * h;
        let joseph = symmetrise(&(i_kh * predicted.covariance * i_kh.transpose() + gain * sensor.noise * gain_t));
        assert!(!is_valid_covariance(&joseph), "{joseph:?}");
        let z = innov.predicted;
        assert_eq!(update(&sensor, &predicted, &innov, &z), Err(NumericalError::NotPositiveDefinite));
    }

    #[test]
    fn f32_after_a_long_gap_is_positive_definite_or_a_typed_error() {
        for dt in [1e3, 1e6, 1e8, 1e9, 3e9, 1e10, 1e12] {
            for q in [1e-13, 1e-6, 1e-2, 1.0] {
                for variance in [1e-8, 1.0, 1e4] {
                    let motion = ConstantVelocity { acceleration_noise: q as f32 };
                    let sensor = PositionMeasurement::isotropic(0.5f32);
                    let prior = Gaussian {
                        mean: SVector::from([10.0f32, -3.0, 0.1, 0.2]),
                        covariance: SMatrix::from_diagonal(&SVector::from([
                            1.0,
                            1.0,
                            variance as f32,
                            variance as f32,
                        ])),
                    };
                    let result = predict(&motion, &prior, dt as f32).and_then(|predicted| {
                        assert!(is_valid_covariance(&predicted.covariance));
                        let innov = innovation(&sensor, &predicted)?;
                        update(&sensor, &predicted, &innov, &(innov.predicted + SVector::from([0.4f32, 0.1])))
                    });
                    match result {
                        Ok(posterior) => assert!(is_valid_covariance(&posterior.covariance), "{posterior:?}"),
                        Err(e) => assert!(matches!(e, NumericalError::NotPositiveDefinite | NumericalError::NonFinite)),
                    }
                }
            }
        }
    }

    /// Seeded random priors (log-uniform scales 10⁻⁶ … 10³⁰, random correlations), time steps and
    /// measurements: the invariant holds in both precisions.
    #[test]
    fn random_priors_keep_the_invariant() {
        use rand_core::{Rng, SeedableRng};
        fn check<T: Real>(rng: &mut rand_xoshiro::Xoshiro256PlusPlus) -> bool {
            let mut uniform = || (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
            let mut factor = SMatrix::<f64, 4, 4>::zeros();
            for i in 0..4 {
                for j in 0..=i {
                    factor[(i, j)] = if i == j { 1.0 } else { 2.0 * uniform() - 1.0 };
                }
            }
            let scales = SVector::<f64, 4>::from_fn(|_, _| 10f64.powf(-3.0 + 18.0 * uniform()));
            let l = SMatrix::<f64, 4, 4>::from_diagonal(&scales) * factor;
            let prior = Gaussian {
                mean: SVector::from_fn(|_, _| T::of_f64(200.0 * uniform() - 100.0)),
                covariance: symmetrise(&(l * l.transpose()).map(T::of_f64)),
            };
            let dt = T::of_f64(10f64.powf(-3.0 + 12.0 * uniform()));
            let motion = ConstantVelocity { acceleration_noise: T::of_f64(10f64.powf(-12.0 + 12.0 * uniform())) };
            let sensor = PositionMeasurement::isotropic(T::of_f64(10f64.powf(-2.0 + 4.0 * uniform())));
            let offset = SVector::from([uniform() - 0.5, uniform() - 0.5].map(T::of_f64));
            if !is_valid_covariance(&prior.covariance) {
                return false;
            }
            let result = predict(&motion, &prior, dt).and_then(|predicted| {
                assert!(is_valid_covariance(&predicted.covariance));
                let innov = innovation(&sensor, &predicted)?;
                update(&sensor, &predicted, &innov, &(innov.predicted + offset))
            });
            match result {
                Ok(posterior) => assert!(is_valid_covariance(&posterior.covariance), "{prior:?} {posterior:?}"),
                Err(e) => assert!(matches!(e, NumericalError::NotPositiveDefinite | NumericalError::NonFinite)),
            }
            result.is_ok()
        }
        let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(17);
        let (mut ok64, mut ok32) = (0, 0);
        for _ in 0..2000 {
            ok64 += usize::from(check::<f64>(&mut rng));
            ok32 += usize::from(check::<f32>(&mut rng));
        }
        // Most draws are ordinary and succeed.
        assert!(ok64 > 1000 && ok32 > 500, "{ok64} {ok32}");
    }

    #[test]
    fn update_is_correction_then_apply() {
        let sensor = PositionMeasurement::isotropic(0.5);
        let predicted = predict(
            &ConstantVelocity { acceleration_noise: 0.1 },
            &Gaussian { mean: SVector::from([1.0, 2.0, 3.0, 4.0]), covariance: SMatrix::<f64, 4, 4>::identity() },
            2.0,
        )
        .unwrap();
        let innov = innovation(&sensor, &predicted).unwrap();
        let correction = correction(&sensor, &predicted, &innov).unwrap();
        for z in [SVector::from([7.0, 10.0]), SVector::from([6.5, 10.25])] {
            assert_eq!(update(&sensor, &predicted, &innov, &z), correction.apply(&predicted, &innov, &z));
        }
    }
}
