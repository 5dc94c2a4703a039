//! Optical (angles-only) measurements of a 3-D inertial state from an observer: topocentric right
//! ascension and declination ([`OpticalRaDec`], docs/maths.md §6.8).
//!
//! With d = r − r_s the line of sight from the observer (inertial position r_s): right ascension
//! α = atan2(d_y, d_x) ∈ (−π, π], declination δ = atan2(d_z, √(d_x² + d_y²)), in the inertial frame of the
//! state (TEME for SGP4 truth: the RA/Dec of a catalogue in GCRF differ by precession and nutation,
//! `sensor::frames`). The Jacobian (2×6) is analytic and zero in the velocity.
//!
//! **Celestial pole.** At d_x = d_y = 0 exactly α is undefined: it is returned as 0 with a zero Jacobian
//! row, and δ's row (a cone point) is zero in its equatorial part. Off the pole α's row grows as 1 / (ρ cos δ).
//!
//! **Residual.** α of z − ẑ is wrapped into (−π, π] ([`OpticalRaDec::residual`], the model's
//! `Measure::residual`); every innovation, gate and score of the tracker goes through it.
//!
//! **Neglected.** Light time (0.12 s at GEO range, ≈ 0.37 km of motion, ≈ 2″ seen from the ground),
//! annual and diurnal aberration (≲ 20.5″ and 0.3″: the catalogue reduction is the caller's), atmospheric
//! refraction (docs/maths.md §6.8).

use super::admissible::optical_births;
use super::radar::topocentric;
use super::{
    AdmissibleRegion, Attributable, BirthComponent, BirthError, BirthGeometry, Measure, SkyPoint, tracklet_births,
};
use crate::real::Real;
use crate::sensor::Placement;
use crate::sensor::frames::wrap_angle;
use nalgebra::{SMatrix, SVector};

/// The "local" basis of [`topocentric`] for right ascension: (a, b, u) = (y, x, z), so that
/// atan2(a, b) = atan2(d_y, d_x).
fn basis<T: Real>() -> [[T; 3]; 3] {
    let (o, i) = (T::zero(), T::one());
    [[o, i, o], [i, o, o], [o, o, i]]
}

/// Topocentric right ascension and declination (rad) of a 3-D inertial state, with independent Gaussian
/// noise of standard deviations `sigma` (rad: 1″ = 4.848e-6 rad).
///
/// # Examples
/// ```
/// use nalgebra::SVector;
/// use tracker_core::model::{Measure, OpticalRaDec};
/// let arcsec = 4.848_136_811e-6_f64;
/// let telescope = OpticalRaDec { observer: [6378.0, 0.0, 0.0, 0.0, 0.465, 0.0], sigma: [arcsec, arcsec] };
/// // A target 1000 km from the observer along the inertial y axis: RA 90°, Dec 0.
/// let z = telescope.measure(&SVector::from([6378.0, 1000.0, 0.0, -7.0, 0.0, 1.0]));
/// assert!((z - SVector::from([core::f64::consts::FRAC_PI_2, 0.0])).norm() < 1e-15);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct OpticalRaDec<T> {
    /// The observer's inertial position and velocity (km, km/s) at the scan (a ground site:
    /// [`crate::sensor::GroundSite::observer`]); set by the caller for every scan. Only the position enters
    /// the measurement (the velocity would enter diurnal aberration, neglected).
    pub observer: [T; 6],
    /// Noise standard deviations: right ascension, declination (rad).
    pub sigma: [T; 2],
}

impl<T: Real> OpticalRaDec<T> {
    /// z − ẑ with the right ascension wrapped into (−π, π].
    ///
    /// # Examples
    /// ```
    /// use core::f64::consts::PI;
    /// use nalgebra::SVector;
    /// use tracker_core::model::OpticalRaDec;
    /// let telescope = OpticalRaDec { observer: [0.0; 6], sigma: [1e-5, 1e-5] };
    /// let nu = telescope.residual(&SVector::from([PI - 0.01, 0.2]), &SVector::from([-PI + 0.01, 0.1]));
    /// assert!((nu - SVector::from([-0.02, 0.1])).norm() < 1e-12);
    /// ```
    pub fn residual(&self, z: &SVector<T, 2>, predicted: &SVector<T, 2>) -> SVector<T, 2> {
        let mut nu = z - predicted;
        nu[0] = wrap_angle(nu[0]);
        nu
    }
}

impl<T: Real> Measure<T, 6, 2> for OpticalRaDec<T> {
    fn measure(&self, state: &SVector<T, 6>) -> SVector<T, 2> {
        let (_, _, (_, ra, dec), _) = topocentric(&self.observer, &basis(), state);
        SVector::from([ra, dec])
    }

    /// ∂α/∂r = (−d_y, d_x, 0) / (d_x² + d_y²), ∂δ/∂r = (−d_z d_x / p, −d_z d_y / p, p) / ρ² with
    /// p = √(d_x² + d_y²); zero in the velocity.
    fn jacobian(&self, state: &SVector<T, 6>) -> SMatrix<T, 2, 6> {
        let (_, _, _, gradient) = topocentric(&self.observer, &basis(), state);
        let [_, ra, dec] = gradient;
        let mut h = SMatrix::<T, 2, 6>::zeros();
        for j in 0..3 {
            h[(0, j)] = ra[j];
            h[(1, j)] = dec[j];
        }
        h
    }

    fn noise_covariance(&self) -> SMatrix<T, 2, 2> {
        let [a, b] = self.sigma;
        SMatrix::from_diagonal(&SVector::from([a * a, b * b]))
    }

    fn residual(&self, z: &SVector<T, 2>, predicted: &SVector<T, 2>) -> SVector<T, 2> {
        OpticalRaDec::residual(self, z, predicted)
    }
}

impl<T: Real> Placement<T, 2> for OpticalRaDec<T> {}

impl<T: Real> BirthGeometry<T, 6, 2> for OpticalRaDec<T> {
    /// Ranges from the line of sight against the region's shell, velocity over its cells
    /// (docs/maths.md §5.7).
    fn birth_components(
        &self,
        z: &SVector<T, 2>,
        region: &AdmissibleRegion<T>,
        out: &mut [BirthComponent<T, 6>],
    ) -> Result<usize, BirthError> {
        optical_births(&self.observer, [z[0], z[1]], self.sigma, region, out)
    }

    fn sky_point(&self, z: &SVector<T, 2>) -> Option<SkyPoint<T>> {
        Some(SkyPoint { angles: [z[0], z[1]], sigma: self.sigma, observer: self.observer })
    }

    fn tracklet_components(
        &self,
        attributable: &Attributable<T>,
        observer: &[T; 6],
        settings: &crate::pool::TrackletBirths<T>,
        out: &mut [BirthComponent<T, 6>],
    ) -> Result<usize, BirthError> {
        tracklet_births(attributable, observer, &settings.region, settings.cells, out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::EARTH_MU;
    use crate::model::radar::tests::{jacobian_error, site};
    use crate::sensor::GroundSite;
    use core::f64::consts::PI;

    const ARCSEC: f64 = PI / (180.0 * 3600.0);

    fn telescope() -> OpticalRaDec<f64> {
        let (site, rotation, t): (GroundSite<f64>, _, _) = site();
        OpticalRaDec { observer: site.observer(&rotation, t), sigma: [ARCSEC, ARCSEC] }
    }

    /// A state at topocentric (ra, dec, range) from the telescope with velocity `v`.
    fn target(tel: &OpticalRaDec<f64>, range: f64, ra: f64, dec: f64, v: [f64; 3]) -> SVector<f64, 6> {
        let o = tel.observer;
        let d = [dec.cos() * ra.cos(), dec.cos() * ra.sin(), dec.sin()].map(|c| c * range);
        SVector::from([o[0] + d[0], o[1] + d[1], o[2] + d[2], v[0], v[1], v[2]])
    }

    #[test]
    fn jacobian_matches_central_differences_leo_and_geo() {
        let tel = telescope();
        let o = tel.observer;
        // LEO at 1200 km from the site; GEO at 42164 km from the centre, 0.2 rad East of the site.
        let leo = target(&tel, 1200.0, 2.9, 0.6, [-3.1, 5.9, 3.4]);
        let (r, lon) = (42_164.0, o[1].atan2(o[0]) + 0.2);
        let v = (EARTH_MU / r).sqrt();
        let geo = SVector::from([r * lon.cos(), r * lon.sin(), 10.0, -v * lon.sin(), v * lon.cos(), 0.01]);
        for x in [leo, geo] {
            let d = (x.fixed_rows::<3>(0) - SVector::from([o[0], o[1], o[2]])).norm();
            let s = [d * 1e-6, d * 1e-6, d * 1e-6, 1e-6, 1e-6, 1e-6];
            let err = jacobian_error(&tel, &x, s, Some(0));
            eprintln!("optical jacobian relative error: {err:.1e}");
            assert!(err < 1e-6, "{err:e}");
            assert_eq!(tel.jacobian(&x).fixed_columns::<3>(3).norm(), 0.0);
        }
        // Measured angles reproduce the construction, RA in (−π, π] across the cut.
        for ra in [PI - 1e-9, PI, -PI + 1e-9, 0.3] {
            let z = tel.measure(&target(&tel, 36_000.0, ra, -0.4, [0.0; 3]));
            assert!(z[0] > -PI && z[0] <= PI && wrap_angle(z[0] - ra).abs() < 1e-9 && (z[1] + 0.4).abs() < 1e-9);
        }
    }

    #[test]
    fn ra_residual_wraps_across_pi() {
        let tel = telescope();
        let nu = tel.residual(&SVector::from([PI - 0.01, 0.1]), &SVector::from([-PI + 0.01, 0.1]));
        assert!((nu[0] + 0.02).abs() < 1e-12 && nu[1] == 0.0, "{nu}");
        let nu = tel.residual(&SVector::from([-PI + 0.01, 0.1]), &SVector::from([PI - 0.01, 0.1]));
        assert!((nu[0] - 0.02).abs() < 1e-12, "{nu}");
    }

    #[test]
    fn near_and_at_the_celestial_pole() {
        let tel = telescope();
        // 1″ and 10″ from the pole at GEO range: the RA row is 1 / (ρ cos δ) per km.
        for off in [1.0, 10.0] {
            let x = target(&tel, 38_000.0, 1.0, PI / 2.0 - off * ARCSEC, [0.0, 3.0, 0.0]);
            let p = 38_000.0 * off * ARCSEC;
            let s = [p * 1e-4, p * 1e-4, p * 1e-4, 1e-3, 1e-3, 1e-3];
            let err = jacobian_error(&tel, &x, s, Some(0));
            eprintln!("optical jacobian {off}″ off the pole: relative error {err:.1e}");
            assert!(err < 1e-6, "{off}: {err:e}");
            assert!((tel.jacobian(&x).row(0).norm() * p - 1.0).abs() < 1e-6);
        }
        // Exactly on the pole (d_x = d_y = 0): RA 0, Dec π/2, finite Jacobian with zero rows.
        let o = tel.observer;
        let x = SVector::from([o[0], o[1], o[2] + 38_000.0, 0.0, 3.0, 0.0]);
        assert_eq!(tel.measure(&x), SVector::from([0.0, PI / 2.0]));
        assert_eq!(tel.jacobian(&x), SMatrix::<f64, 2, 6>::zeros());
    }

    #[test]
    fn f32_agrees_with_f64() {
        let tel = telescope();
        let x = target(&tel, 36_000.0, 2.0, 0.1, [0.0, 3.0, 0.0]);
        let tel32 = OpticalRaDec { observer: tel.observer.map(|v| v as f32), sigma: [ARCSEC as f32; 2] };
        let z = tel.measure(&x);
        let z32 = tel32.measure(&x.map(|v| v as f32));
        // ≈ 2 mm of rounding in 42 000 km positions over 36 000 km: well under 0.1″.
        assert!((f64::from(z32[0]) - z[0]).abs() < 0.1 * ARCSEC && (f64::from(z32[1]) - z[1]).abs() < 0.1 * ARCSEC);
    }
}
