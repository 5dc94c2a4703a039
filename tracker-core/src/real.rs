//! The scalar type of the tracker: `f32` (the on-board default on a single-precision FPU) or `f64` (the
//! host reference).
//!
//! Every transcendental function the core calls goes through this module to `libm`, never to the
//! platform's own `std` math, so the host and a bare-metal target compute the same bits for the same
//! inputs. The free functions ([`ln`], [`exp`], [`sqrt`], ...) read like the maths and avoid clashing with
//! nalgebra's `ComplexField` methods of the same name.

use nalgebra::RealField;

/// A floating-point scalar the tracker can run on.
///
/// Implemented for `f32` and `f64`. The methods are named after `libm` so that call sites cannot pick up
/// a `std` implementation by accident; use the free functions of this module in code.
pub trait Real: RealField + Copy + Default + core::fmt::Debug + core::fmt::Display + 'static {
    /// Zero.
    const ZERO: Self;
    /// One.
    const ONE: Self;
    /// Positive infinity.
    const INFINITY: Self;
    /// Negative infinity: the log-weight of an impossible event.
    const NEG_INFINITY: Self;
    /// Not a number: every comparison with it is false but `!=`.
    const NAN: Self;
    /// Converts from `f64`, rounding to nearest.
    fn of_f64(value: f64) -> Self;
    /// Converts to `f64` exactly.
    fn as_f64(self) -> f64;
    /// `true` unless the value is NaN or infinite.
    fn is_finite_value(self) -> bool;
    /// NaN if `poison`, else the value itself bit for bit; bitwise, without a branch or a select.
    fn nan_if(self, poison: bool) -> Self;
    /// Natural logarithm (`libm::log` / `logf`).
    fn libm_ln(self) -> Self;
    /// Exponential (`libm::exp` / `expf`).
    fn libm_exp(self) -> Self;
    /// Square root (`libm::sqrt` / `sqrtf`).
    fn libm_sqrt(self) -> Self;
    /// Sine (`libm::sin` / `sinf`).
    fn libm_sin(self) -> Self;
    /// Cosine (`libm::cos` / `cosf`).
    fn libm_cos(self) -> Self;
    /// Four-quadrant arctangent of `self / x` (`libm::atan2` / `atan2f`).
    fn libm_atan2(self, x: Self) -> Self;
    /// Largest integer not greater than the value (`libm::floor` / `floorf`).
    fn libm_floor(self) -> Self;
}

macro_rules! impl_real {
    ($t:ty, $ln:path, $exp:path, $sqrt:path, $sin:path, $cos:path, $atan2:path, $floor:path) => {
        impl Real for $t {
            const ZERO: Self = 0.0;
            const ONE: Self = 1.0;
            const INFINITY: Self = <$t>::INFINITY;
            const NEG_INFINITY: Self = <$t>::NEG_INFINITY;
            const NAN: Self = <$t>::NAN;
            #[inline]
            fn of_f64(value: f64) -> Self {
                value as $t
            }
            #[inline]
            fn as_f64(self) -> f64 {
                self as f64
            }
            #[inline]
            fn is_finite_value(self) -> bool {
                <$t>::is_finite(self)
            }
            #[inline(always)]
            fn nan_if(self, poison: bool) -> Self {
                let mask = (<$t>::NAN.to_bits()).wrapping_mul(poison.into());
                <$t>::from_bits(self.to_bits() | mask)
            }
            #[inline]
            fn libm_ln(self) -> Self {
                $ln(self)
            }
            #[inline]
            fn libm_exp(self) -> Self {
                $exp(self)
            }
            #[inline]
            fn libm_sqrt(self) -> Self {
                $sqrt(self)
            }
            #[inline]
            fn libm_sin(self) -> Self {
                $sin(self)
            }
            #[inline]
            fn libm_cos(self) -> Self {
                $cos(self)
            }
            #[inline]
            fn libm_atan2(self, x: Self) -> Self {
                $atan2(self, x)
            }
            #[inline]
            fn libm_floor(self) -> Self {
                $floor(self)
            }
        }
    };
}

impl_real!(f64, libm::log, libm::exp, libm::sqrt, libm::sin, libm::cos, libm::atan2, libm::floor);
impl_real!(f32, libm::logf, libm::expf, libm::sqrtf, libm::sinf, libm::cosf, libm::atan2f, libm::floorf);

/// Natural logarithm; `ln(0) = -inf`.
///
/// # Examples
/// ```
/// use tracker_core::real::ln;
/// assert_eq!(ln(1.0_f64), 0.0);
/// assert_eq!(ln(0.0_f32), f32::NEG_INFINITY); // the log-weight of an impossible event
/// ```
#[inline]
pub fn ln<T: Real>(x: T) -> T {
    x.libm_ln()
}

/// Exponential.
///
/// # Examples
/// ```
/// use tracker_core::real::exp;
/// assert_eq!(exp(0.0_f64), 1.0);
/// assert_eq!(exp(f64::NEG_INFINITY), 0.0);
/// ```
#[inline]
pub fn exp<T: Real>(x: T) -> T {
    x.libm_exp()
}

/// Square root.
///
/// # Examples
/// ```
/// assert_eq!(tracker_core::real::sqrt(2.25_f32), 1.5);
/// ```
#[inline]
pub fn sqrt<T: Real>(x: T) -> T {
    x.libm_sqrt()
}

/// Sine.
///
/// # Examples
/// ```
/// assert_eq!(tracker_core::real::sin(0.0_f64), 0.0);
/// assert!((tracker_core::real::sin(core::f64::consts::FRAC_PI_2) - 1.0).abs() < 1e-15);
/// ```
#[inline]
pub fn sin<T: Real>(x: T) -> T {
    x.libm_sin()
}

/// Cosine.
///
/// # Examples
/// ```
/// assert_eq!(tracker_core::real::cos(0.0_f64), 1.0);
/// assert!((tracker_core::real::cos(core::f64::consts::PI) + 1.0).abs() < 1e-15);
/// ```
#[inline]
pub fn cos<T: Real>(x: T) -> T {
    x.libm_cos()
}

/// Four-quadrant arctangent of `y / x`.
///
/// # Examples
/// ```
/// use tracker_core::real::atan2;
/// assert!((atan2(1.0_f64, -1.0) - 3.0 * core::f64::consts::FRAC_PI_4).abs() < 1e-15); // second quadrant
/// ```
#[inline]
pub fn atan2<T: Real>(y: T, x: T) -> T {
    y.libm_atan2(x)
}

/// Largest integer not greater than `x`.
///
/// # Examples
/// ```
/// assert_eq!(tracker_core::real::floor(-1.5_f64), -2.0);
/// ```
#[inline]
pub fn floor<T: Real>(x: T) -> T {
    x.libm_floor()
}

/// The constant `value` in the scalar type `T`.
///
/// # Examples
/// ```
/// use tracker_core::real::c;
/// let half: f32 = c(0.5);
/// assert_eq!(half, 0.5);
/// let tenth: f32 = c(0.1);
/// assert_eq!(tenth, 0.1_f32); // rounded to nearest
/// ```
#[inline]
pub fn c<T: Real>(value: f64) -> T {
    T::of_f64(value)
}

/// `ln(exp(a) + exp(b))` without overflow; exact when either side is `-inf`.
///
/// # Examples
/// ```
/// use tracker_core::real::log_add;
/// assert!((log_add(2f64.ln(), 3f64.ln()) - 5f64.ln()).abs() < 1e-15);
/// assert_eq!(log_add(f64::NEG_INFINITY, 1.5), 1.5);
/// // e^1000 overflows f64; its log-sum does not.
/// assert!((log_add(1000.0_f64, 1000.0) - (1000.0 + 2f64.ln())).abs() < 1e-12);
/// ```
#[inline]
pub fn log_add<T: Real>(a: T, b: T) -> T {
    if a == T::NEG_INFINITY {
        return b;
    }
    if b == T::NEG_INFINITY {
        return a;
    }
    let (hi, lo) = if a >= b { (a, b) } else { (b, a) };
    hi + ln(T::one() + exp(lo - hi))
}

/// The `R × C` zero matrix, in a `const` context.
///
/// # Examples
/// ```
/// use nalgebra::SMatrix;
/// const Z: SMatrix<f32, 2, 3> = tracker_core::real::zeros();
/// assert_eq!(Z, SMatrix::<f32, 2, 3>::zeros());
/// ```
pub const fn zeros<T: Real, const R: usize, const C: usize>() -> nalgebra::SMatrix<T, R, C> {
    nalgebra::SMatrix::from_array_storage(nalgebra::ArrayStorage([[T::ZERO; R]; C]))
}

/// The `D × D` identity matrix, in a `const` context.
///
/// # Examples
/// ```
/// use nalgebra::SMatrix;
/// const I: SMatrix<f64, 3, 3> = tracker_core::real::identity();
/// assert_eq!(I, SMatrix::<f64, 3, 3>::identity());
/// ```
pub const fn identity<T: Real, const D: usize>() -> nalgebra::SMatrix<T, D, D> {
    let mut columns = [[T::ZERO; D]; D];
    let mut i = 0;
    while i < D {
        columns[i][i] = T::ONE;
        i += 1;
    }
    nalgebra::SMatrix::from_array_storage(nalgebra::ArrayStorage(columns))
}

/// A running log-sum-exp: the log of the sum of `exp` of every value added, kept as a maximum and a sum
/// scaled by it, so that one `exp` is evaluated per value and nothing overflows.
///
/// # Examples
/// Normalising log-weights far below `ln f64::MIN_POSITIVE`:
/// ```
/// use tracker_core::real::LogSumExp;
/// let log_weights = [-2000.0_f64, -2001.0, -2003.0];
/// let mut total = LogSumExp::new();
/// for &w in &log_weights {
///     total.add(w);
/// }
/// assert!(total.value().is_finite()); // Σ e^w itself underflows to 0
/// let sum: f64 = log_weights.iter().map(|&w| total.normalise(w).exp()).sum();
/// assert!((sum - 1.0).abs() < 1e-15);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LogSumExp<T> {
    max: T,
    scaled_sum: T,
}

impl<T: Real> Default for LogSumExp<T> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T: Real> LogSumExp<T> {
    /// The empty sum (`ln 0 = -inf`).
    ///
    /// # Examples
    /// ```
    /// use tracker_core::real::LogSumExp;
    /// let empty = LogSumExp::<f64>::new();
    /// assert_eq!(empty.value(), f64::NEG_INFINITY); // ln 0
    /// ```
    pub const fn new() -> Self {
        Self { max: T::NEG_INFINITY, scaled_sum: T::ZERO }
    }

    /// Adds `exp(value)` to the sum. `-inf` adds nothing.
    ///
    /// # Examples
    /// ```
    /// use tracker_core::real::LogSumExp;
    /// let mut total = LogSumExp::new();
    /// total.add(1f64.ln());
    /// total.add(f64::NEG_INFINITY); // adds nothing
    /// total.add(3f64.ln());
    /// assert!((total.value() - 4f64.ln()).abs() < 1e-15);
    /// ```
    #[inline]
    pub fn add(&mut self, value: T) {
        if value == T::NEG_INFINITY {
            return;
        }
        if value > self.max {
            // Rescale the sum to the new maximum: s·e^(m−v) + 1.
            self.scaled_sum = self.scaled_sum * exp(self.max - value) + T::one();
            self.max = value;
        } else {
            self.scaled_sum += exp(value - self.max);
        }
    }

    /// The log of the sum so far; `-inf` when nothing finite was added.
    ///
    /// # Examples
    /// ```
    /// use tracker_core::real::LogSumExp;
    /// let mut total = LogSumExp::new();
    /// for w in [0.5_f64, 0.25, 0.25] {
    ///     total.add(w.ln());
    /// }
    /// assert!(total.value().abs() < 1e-15); // ln 1
    /// ```
    pub fn value(&self) -> T {
        if self.max == T::NEG_INFINITY { T::NEG_INFINITY } else { self.max + ln(self.scaled_sum) }
    }

    /// `value − ln(sum)`: `value` normalised by this sum. The largest term is subtracted first (exactly,
    /// for values near it), so the result stays accurate even when the values are so large that
    /// `ln(sum)` is below their rounding step.
    ///
    /// # Examples
    /// ```
    /// use tracker_core::real::LogSumExp;
    /// let mut total = LogSumExp::new();
    /// total.add(1e18_f64);
    /// total.add(1e18_f64);
    /// // ln 2 is below the rounding step of 1e18: `value − total.value()` would give 0, not −ln 2.
    /// assert!((total.normalise(1e18) - (-2f64.ln())).abs() < 1e-15);
    /// ```
    pub fn normalise(&self, value: T) -> T {
        (value - self.max) - ln(self.scaled_sum)
    }

    /// ln(this sum / `other` sum), accurate in the same way as [`LogSumExp::normalise`].
    ///
    /// # Examples
    /// The fraction of a total held by some of its terms (the tracker's captured mass):
    /// ```
    /// use tracker_core::real::LogSumExp;
    /// let (mut kept, mut all) = (LogSumExp::new(), LogSumExp::new());
    /// for (w, keep) in [(3.0_f64, true), (1.0, false), (4.0, true)] {
    ///     all.add(w.ln());
    ///     if keep {
    ///         kept.add(w.ln());
    ///     }
    /// }
    /// assert!((kept.log_ratio(&all).exp() - 7.0 / 8.0).abs() < 1e-15);
    /// ```
    pub fn log_ratio(&self, other: &LogSumExp<T>) -> T {
        if self.max == T::NEG_INFINITY {
            return T::NEG_INFINITY;
        }
        (self.max - other.max) + ln(self.scaled_sum / other.scaled_sum)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nan_if_poisons_or_keeps_every_bit() {
        for value in [0.0f64, -0.0, 1.5e-310, -2.0, 7.25e300, f64::INFINITY, f64::NEG_INFINITY] {
            assert_eq!(value.nan_if(false).to_bits(), value.to_bits());
            assert!(value.nan_if(true).is_nan());
            assert_eq!((value as f32).nan_if(false).to_bits(), (value as f32).to_bits());
            assert!((value as f32).nan_if(true).is_nan());
        }
    }

    #[test]
    fn log_sum_exp_matches_direct_sum() {
        let values = [-3.0f64, 0.5, -700.0, 2.0, f64::NEG_INFINITY];
        let mut acc = LogSumExp::new();
        for v in values {
            acc.add(v);
        }
        let direct: f64 = values.iter().map(|v| v.exp()).sum::<f64>().ln();
        assert!((acc.value() - direct).abs() < 1e-14);
    }

    #[test]
    fn normalising_huge_values_keeps_the_sum_at_one() {
        // ln 2 is far below the rounding step of 1e18: value() − value() would give weights 1 and 1.
        let mut acc = LogSumExp::new();
        acc.add(-1e18f64);
        acc.add(-1e18f64);
        let weights: f64 = [-1e18f64, -1e18].iter().map(|&v| acc.normalise(v).exp()).sum();
        assert!((weights - 1.0).abs() < 1e-15);
        assert_eq!(acc.log_ratio(&acc), 0.0);
    }

    #[test]
    fn empty_log_sum_exp_is_negative_infinity() {
        let acc = LogSumExp::<f32>::new();
        assert_eq!(acc.value(), f32::NEG_INFINITY);
    }

    #[test]
    fn log_add_handles_infinities() {
        assert_eq!(log_add(f64::NEG_INFINITY, 1.5), 1.5);
        assert!((log_add(0.0f64, 0.0) - 2f64.ln()).abs() < 1e-15);
    }
}
