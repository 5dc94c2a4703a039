//! The filter's consistency over a 3-D soak: the normalised estimation error squared (NEES) of the MAP
//! tracks against the truth, and its χ² band (docs/maths.md §8.6).
//!
//! An object's NEES at a scan is ε = (x̂ − x)ᵀ P⁻¹ (x̂ − x) over its whole state (position and velocity,
//! S = 6), with x̂ and P the MAP hypothesis's track of its label. A consistent filter gives E[ε] = S. The
//! samples of one object are correlated from scan to scan, so the band is that of one scan's mean over
//! the M objects it holds: M·ε̄ ~ χ²(M·S) when the filter is consistent, and the report gives the share of
//! scans whose ε̄ falls in the two-sided 95 % band.

use crate::eval::consistency::nis_band;
use nalgebra::{SMatrix, SVector};

/// The state dimension whose NEES is taken.
pub const STATE: usize = 6;

/// ε = eᵀ P⁻¹ e with e = `mean` − `truth`, or `None` when P is not positive definite.
pub fn nees(mean: &SVector<f64, STATE>, covariance: &SMatrix<f64, STATE, STATE>, truth: &[f64; STATE]) -> Option<f64> {
    let error = mean - SVector::<f64, STATE>::from_column_slice(truth);
    let cholesky = covariance.cholesky()?;
    let value = error.dot(&cholesky.solve(&error));
    value.is_finite().then_some(value)
}

/// The two-sided 95 % band of the mean of `samples` NEES values ([`nis_band`]: the same χ² band, with
/// Wilson and Hilferty's quantiles, within 0.1 % of the exact ones for k = 6 M ≥ 30).
fn mean_band(samples: usize) -> [f64; 2] {
    nis_band(samples.max(1), STATE)
}

/// NEES figures over a soak's scans.
#[derive(Debug, Clone, Default)]
pub struct NeesTally {
    sum: f64,
    samples: u64,
    sum_last_tenth: f64,
    samples_last_tenth: u64,
    /// Scans with at least one NEES sample, and of them those whose mean is in its band.
    scans: u64,
    scans_in_band: u64,
    /// Samples whose covariance was not positive definite.
    undefined: u64,
}

/// The NEES part of a soak's report.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NeesFigures {
    /// Mean NEES over every object-scan with a track (S = 6 when consistent).
    pub mean: Option<f64>,
    /// The same over the last tenth of the scans.
    pub mean_last_tenth: Option<f64>,
    /// The share of scans whose mean NEES over their tracked objects is within its 95 % band.
    pub scans_in_band_fraction: Option<f64>,
    /// The band of one scan's mean when it holds every object.
    pub band_all_objects: [f64; 2],
    /// Samples left out because the track's covariance was not positive definite.
    pub undefined: u64,
}

impl NeesTally {
    /// One scan's samples (`values`, one per object with a track); `last_tenth` when the scan is in the
    /// last tenth of the run; `undefined` samples whose covariance was not positive definite.
    pub fn record(&mut self, values: &[f64], undefined: u64, last_tenth: bool) {
        self.undefined += undefined;
        if values.is_empty() {
            return;
        }
        let sum: f64 = values.iter().sum();
        self.sum += sum;
        self.samples += values.len() as u64;
        if last_tenth {
            self.sum_last_tenth += sum;
            self.samples_last_tenth += values.len() as u64;
        }
        let [low, high] = mean_band(values.len());
        let mean = sum / values.len() as f64;
        self.scans += 1;
        self.scans_in_band += u64::from((low..=high).contains(&mean));
    }

    /// The figures, for a soak of `objects` objects.
    pub fn figures(&self, objects: usize) -> NeesFigures {
        let ratio = |sum: f64, n: u64| (n > 0).then(|| sum / n as f64);
        NeesFigures {
            mean: ratio(self.sum, self.samples),
            mean_last_tenth: ratio(self.sum_last_tenth, self.samples_last_tenth),
            scans_in_band_fraction: ratio(self.scans_in_band as f64, self.scans),
            band_all_objects: mean_band(objects),
            undefined: self.undefined,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nees_is_the_mahalanobis_square_of_the_error() {
        let covariance = SMatrix::<f64, 6, 6>::from_diagonal(&SVector::from([4.0, 1.0, 1.0, 0.25, 1.0, 1.0]));
        let mean = SVector::<f64, 6>::from([2.0, 0.0, 0.0, 1.0, 0.0, 0.0]);
        let value = nees(&mean, &covariance, &[0.0; 6]).unwrap();
        assert!((value - (1.0 + 4.0)).abs() < 1e-12, "{value}");
        assert_eq!(nees(&mean, &SMatrix::zeros(), &[0.0; 6]), None);
    }

    #[test]
    fn the_band_of_thirty_objects_matches_exact_chi_square_quantiles() {
        // χ²(180) (the regularised incomplete gamma function inverted by bisection): 2.5 % 144.741,
        // 97.5 % 219.044.
        let [low, high] = mean_band(30);
        assert!((low * 30.0 - 144.741).abs() < 0.01 && (high * 30.0 - 219.044).abs() < 0.01, "{low} {high}");
    }

    #[test]
    fn the_tally_counts_scans_in_band() {
        let mut tally = NeesTally::default();
        tally.record(&[6.0; 30], 0, false);
        tally.record(&[60.0; 30], 1, true);
        tally.record(&[], 0, true);
        let figures = tally.figures(30);
        assert_eq!(figures.mean, Some(33.0));
        assert_eq!(figures.mean_last_tenth, Some(60.0));
        assert_eq!(figures.scans_in_band_fraction, Some(0.5));
        assert_eq!(figures.undefined, 1);
    }
}
