//! Radar measurements of a 3-D inertial state (x, y, z, vx, vy, vz; km, km/s) from a ground site: range,
//! azimuth and elevation ([`RadarRangeAzEl`]), and the same with range-rate ([`RadarRangeRate`])
//! (docs/maths.md §6.8).
//!
//! With d = r − r_s the line of sight from the site (inertial r_s, v_s) and (e, n, u) its components along
//! the site's East, North and Up unit vectors (inertial, [`GroundSite::enu`]):
//! ρ = |d|, azimuth A = atan2(e, n) ∈ (−π, π] (from North towards East), elevation E = atan2(u, √(e² + n²)),
//! range-rate ρ̇ = d · (v − v_s) / ρ. The Jacobians are analytic; the velocity enters only ρ̇.
//!
//! **Zenith.** At e = n = 0 exactly (the target straight overhead) the azimuth is undefined: it is
//! returned as 0 (North) with a zero Jacobian row, and the elevation row (a cone point) is zero in its
//! horizontal part. Off the zenith the azimuth row grows as 1 / (ρ cos E): a pass close to the zenith
//! (the radar's keyhole) needs its azimuth σ inflated or the azimuth dropped, which is the caller's choice.
//!
//! **Residual.** The azimuth of z − ẑ is wrapped into (−π, π] ([`RadarRangeAzEl::residual`], the
//! model's [`Measure::residual`](super::Measure::residual)); every innovation, gate and score of the tracker goes through it.
//!
//! **Neglected.** Light time (ρ / c: 3.3 ms at 1000 km, ≈ 25 m along track in LEO), atmospheric
//! refraction and the Earth-model terms of [`GroundSite`] (docs/maths.md §6.8).

use super::admissible::radar_births;
use super::{AdmissibleRegion, BirthComponent, BirthError, BirthGeometry, Measure};
use crate::real::Real;
use crate::sensor::frames::{EarthRotation, GroundSite, look_angles, wrap_angle};
use crate::sensor::{Look, LookAxes, Placement};
use nalgebra::{SMatrix, SVector};

/// Line of sight d = r − r_s and relative velocity w = v − v_s (inertial), the local components of d in
/// `basis` (rows) and the look angles with their inertial gradients (rows ∂ρ, ∂A, ∂E over ∂r).
#[allow(clippy::type_complexity)]
pub(crate) fn topocentric<T: Real>(
    observer: &[T; 6],
    basis: &[[T; 3]; 3],
    state: &SVector<T, 6>,
) -> ([T; 3], [T; 3], (T, T, T), [[T; 3]; 3]) {
    let [ox, oy, oz, ovx, ovy, ovz] = *observer;
    let d = [state[0] - ox, state[1] - oy, state[2] - oz];
    let w = [state[3] - ovx, state[4] - ovy, state[5] - ovz];
    let dot = |row: &[T; 3]| row[0] * d[0] + row[1] * d[1] + row[2] * d[2];
    let [b0, b1, b2] = basis;
    let (range, alpha, beta, local) = look_angles([dot(b0), dot(b1), dot(b2)]);
    // ∂/∂r = Σ_k (∂/∂local_k) basis_k.
    let mut gradient = [[T::zero(); 3]; 3];
    for (out, g) in gradient.iter_mut().zip(local.iter()) {
        for j in 0..3 {
            out[j] = g[0] * b0[j] + g[1] * b1[j] + g[2] * b2[j];
        }
    }
    (d, w, (range, alpha, beta), gradient)
}

/// Range (km), azimuth and elevation (rad) of a 3-D inertial state seen from a site, with independent
/// Gaussian noise of standard deviations `sigma`.
///
/// # Examples
/// A target 1000 km due East of the site at 30° elevation.
/// ```
/// use nalgebra::SVector;
/// use tracker_core::model::{Measure, RadarRangeAzEl};
/// use tracker_core::sensor::{EarthRotation, GroundSite};
/// let site = GroundSite { latitude: 40.0_f64.to_radians(), longitude: -105.0_f64.to_radians(), height: 1.6 };
/// let radar = RadarRangeAzEl::at_site(&site, &EarthRotation::new(0.3), 120.0, [0.01, 1e-3, 1e-3]);
/// let [east, _, up] = radar.enu.map(SVector::from);
/// let el = 30.0_f64.to_radians();
/// let target = SVector::<f64, 3>::from([radar.observer[0], radar.observer[1], radar.observer[2]])
///     + (east * el.cos() + up * el.sin()) * 1000.0;
/// let x = SVector::from([target[0], target[1], target[2], 0.0, 0.0, 0.0]);
/// let z = radar.measure(&x);
/// assert!((z - SVector::from([1000.0, core::f64::consts::FRAC_PI_2, el])).norm() < 1e-9);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RadarRangeAzEl<T> {
    /// The site's inertial position and velocity (km, km/s) at the scan ([`GroundSite::observer`]); set by
    /// the caller for every scan.
    pub observer: [T; 6],
    /// The site's East, North and Up unit vectors in the inertial frame at the scan (rows,
    /// [`GroundSite::enu`]); set with `observer`.
    pub enu: [[T; 3]; 3],
    /// Noise standard deviations: range (km), azimuth (rad), elevation (rad).
    pub sigma: [T; 3],
}

impl<T: Real> RadarRangeAzEl<T> {
    /// The model for `site` at scan time `t` (seconds since the epoch of `rotation`).
    pub fn at_site(site: &GroundSite<T>, rotation: &EarthRotation<T>, t: T, sigma: [T; 3]) -> Self {
        Self { observer: site.observer(rotation, t), enu: site.enu(rotation, t), sigma }
    }

    /// z − ẑ with the azimuth wrapped into (−π, π].
    ///
    /// # Examples
    /// ```
    /// use core::f64::consts::PI;
    /// use nalgebra::SVector;
    /// use tracker_core::model::RadarRangeAzEl;
    /// let radar = RadarRangeAzEl { observer: [0.0; 6], enu: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
    ///     sigma: [0.01, 1e-3, 1e-3] };
    /// let nu = radar.residual(&SVector::from([500.0, PI - 0.01, 0.2]), &SVector::from([499.0, -PI + 0.01, 0.1]));
    /// assert!((nu - SVector::from([1.0, -0.02, 0.1])).norm() < 1e-12);
    /// ```
    pub fn residual(&self, z: &SVector<T, 3>, predicted: &SVector<T, 3>) -> SVector<T, 3> {
        let mut nu = z - predicted;
        nu[1] = wrap_angle(nu[1]);
        nu
    }
}

impl<T: Real> Measure<T, 6, 3> for RadarRangeAzEl<T> {
    fn measure(&self, state: &SVector<T, 6>) -> SVector<T, 3> {
        let (_, _, (range, azimuth, elevation), _) = topocentric(&self.observer, &self.enu, state);
        SVector::from([range, azimuth, elevation])
    }

    fn jacobian(&self, state: &SVector<T, 6>) -> SMatrix<T, 3, 6> {
        let (_, _, _, gradient) = topocentric(&self.observer, &self.enu, state);
        let mut h = SMatrix::<T, 3, 6>::zeros();
        for (i, row) in gradient.iter().enumerate() {
            for j in 0..3 {
                h[(i, j)] = row[j];
            }
        }
        h
    }

    fn noise_covariance(&self) -> SMatrix<T, 3, 3> {
        let [a, b, c] = self.sigma;
        SMatrix::from_diagonal(&SVector::from([a * a, b * b, c * c]))
    }

    fn residual(&self, z: &SVector<T, 3>, predicted: &SVector<T, 3>) -> SVector<T, 3> {
        RadarRangeAzEl::residual(self, z, predicted)
    }
}

impl<T: Real> Placement<T, 3> for RadarRangeAzEl<T> {
    fn look_axes(&self) -> Option<LookAxes> {
        Some(LookAxes { range: true, range_rate: false })
    }

    fn look(&self, z: &SVector<T, 3>) -> Option<Look<T>> {
        Some(Look { azimuth: z[1], elevation: z[2], range: Some(z[0]), range_rate: None })
    }
}

impl<T: Real> BirthGeometry<T, 6, 3> for RadarRangeAzEl<T> {
    /// Position from (ρ, A, E), velocity over the admissible region's cells (docs/maths.md §5.7).
    fn birth_components(
        &self,
        z: &SVector<T, 3>,
        region: &AdmissibleRegion<T>,
        out: &mut [BirthComponent<T, 6>],
    ) -> Result<usize, BirthError> {
        radar_births(&self.observer, &self.enu, [z[0], z[1], z[2]], None, self.sigma, region, out)
    }
}

/// Range (km), azimuth, elevation (rad) and range-rate (km/s, positive receding) of a 3-D inertial state
/// seen from a site, with independent Gaussian noise of standard deviations `sigma`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RadarRangeRate<T> {
    /// The site's inertial position and velocity (km, km/s) at the scan; set by the caller for every scan.
    pub observer: [T; 6],
    /// The site's East, North and Up unit vectors in the inertial frame at the scan (rows).
    pub enu: [[T; 3]; 3],
    /// Noise standard deviations: range (km), azimuth (rad), elevation (rad), range-rate (km/s).
    pub sigma: [T; 4],
}

impl<T: Real> RadarRangeRate<T> {
    /// The model for `site` at scan time `t` (seconds since the epoch of `rotation`).
    pub fn at_site(site: &GroundSite<T>, rotation: &EarthRotation<T>, t: T, sigma: [T; 4]) -> Self {
        Self { observer: site.observer(rotation, t), enu: site.enu(rotation, t), sigma }
    }

    /// z − ẑ with the azimuth wrapped into (−π, π].
    pub fn residual(&self, z: &SVector<T, 4>, predicted: &SVector<T, 4>) -> SVector<T, 4> {
        let mut nu = z - predicted;
        nu[1] = wrap_angle(nu[1]);
        nu
    }
}

/// ρ̇ = d · w / ρ (0 at ρ = 0).
fn range_rate<T: Real>(d: &[T; 3], w: &[T; 3], range: T) -> T {
    if range > T::zero() { (d[0] * w[0] + d[1] * w[1] + d[2] * w[2]) / range } else { T::zero() }
}

impl<T: Real> Measure<T, 6, 4> for RadarRangeRate<T> {
    fn measure(&self, state: &SVector<T, 6>) -> SVector<T, 4> {
        let (d, w, (range, azimuth, elevation), _) = topocentric(&self.observer, &self.enu, state);
        SVector::from([range, azimuth, elevation, range_rate(&d, &w, range)])
    }

    /// Rows ρ, A, E as [`RadarRangeAzEl`]; ∂ρ̇/∂r = (w − ρ̇ d / ρ) / ρ, ∂ρ̇/∂v = d / ρ (zero at ρ = 0).
    fn jacobian(&self, state: &SVector<T, 6>) -> SMatrix<T, 4, 6> {
        let (d, w, (range, _, _), gradient) = topocentric(&self.observer, &self.enu, state);
        let mut h = SMatrix::<T, 4, 6>::zeros();
        for (i, row) in gradient.iter().enumerate() {
            for j in 0..3 {
                h[(i, j)] = row[j];
            }
        }
        if range > T::zero() {
            let rate = range_rate(&d, &w, range);
            for j in 0..3 {
                let u = d[j] / range;
                h[(3, j)] = (w[j] - rate * u) / range;
                h[(3, j + 3)] = u;
            }
        }
        h
    }

    fn noise_covariance(&self) -> SMatrix<T, 4, 4> {
        let [a, b, c, d] = self.sigma;
        SMatrix::from_diagonal(&SVector::from([a * a, b * b, c * c, d * d]))
    }

    fn residual(&self, z: &SVector<T, 4>, predicted: &SVector<T, 4>) -> SVector<T, 4> {
        RadarRangeRate::residual(self, z, predicted)
    }
}

impl<T: Real> Placement<T, 4> for RadarRangeRate<T> {
    fn look_axes(&self) -> Option<LookAxes> {
        Some(LookAxes { range: true, range_rate: true })
    }

    fn look(&self, z: &SVector<T, 4>) -> Option<Look<T>> {
        Some(Look { azimuth: z[1], elevation: z[2], range: Some(z[0]), range_rate: Some(z[3]) })
    }
}

impl<T: Real> BirthGeometry<T, 6, 4> for RadarRangeRate<T> {
    /// Position from (ρ, A, E), velocity along the line of sight from ρ̇, across it over the admissible
    /// region's cells (docs/maths.md §5.7).
    fn birth_components(
        &self,
        z: &SVector<T, 4>,
        region: &AdmissibleRegion<T>,
        out: &mut [BirthComponent<T, 6>],
    ) -> Result<usize, BirthError> {
        let [a, b, c, d] = self.sigma;
        radar_births(&self.observer, &self.enu, [z[0], z[1], z[2]], Some((z[3], d)), [a, b, c], region, out)
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::model::EARTH_MU;
    use crate::sensor::{EarthRotation, GroundSite};
    use core::f64::consts::PI;

    /// Largest |H − H_fd| over each row, relative to the row's largest |H| entry, with central differences
    /// of step `steps[j]` in state component j.
    pub(crate) fn jacobian_error<const D: usize>(
        model: &impl Measure<f64, 6, D>,
        x: &SVector<f64, 6>,
        steps: [f64; 6],
        wrap: Option<usize>,
    ) -> f64 {
        let h = model.jacobian(x);
        let mut worst = 0.0_f64;
        for i in 0..D {
            let scale = (0..6).map(|j| h[(i, j)].abs()).fold(0.0, f64::max);
            for j in 0..6 {
                let (mut plus, mut minus) = (*x, *x);
                plus[j] += steps[j];
                minus[j] -= steps[j];
                let mut diff = model.measure(&plus)[i] - model.measure(&minus)[i];
                if wrap == Some(i) {
                    diff = wrap_angle(diff);
                }
                let fd = diff / (2.0 * steps[j]);
                worst = worst.max((fd - h[(i, j)]).abs() / scale);
            }
        }
        worst
    }

    pub(crate) fn site() -> (GroundSite<f64>, EarthRotation<f64>, f64) {
        let site = GroundSite { latitude: 40.0_f64.to_radians(), longitude: -105.0_f64.to_radians(), height: 1.6 };
        (site, EarthRotation::new(1.2), 500.0)
    }

    /// A state at range `range`, azimuth `az` and elevation `el` from the radar, with velocity `v`.
    fn target(radar: &RadarRangeAzEl<f64>, range: f64, az: f64, el: f64, v: [f64; 3]) -> SVector<f64, 6> {
        let [e, n, u] = radar.enu.map(SVector::from);
        let d = (e * az.sin() * el.cos() + n * az.cos() * el.cos() + u * el.sin()) * range;
        let o = radar.observer;
        SVector::from([o[0] + d[0], o[1] + d[1], o[2] + d[2], v[0], v[1], v[2]])
    }

    /// LEO (≈ 7000 km radius, 7.5 km/s) and GEO (42164 km, 3.07 km/s) states seen from the site at 40°N.
    fn leo_and_geo(radar: &RadarRangeAzEl<f64>) -> [SVector<f64, 6>; 2] {
        let leo = target(radar, 1200.0, 2.3, 0.4, [-3.1, 5.9, 3.4]);
        let r = 42_164.0;
        let o = radar.observer;
        let lon = o[1].atan2(o[0]) + 0.2;
        let v = (EARTH_MU / r).sqrt();
        let geo = SVector::from([r * lon.cos(), r * lon.sin(), 10.0, -v * lon.sin(), v * lon.cos(), 0.01]);
        [leo, geo]
    }

    fn steps(x: &SVector<f64, 6>, observer: &[f64; 6], relative: f64) -> [f64; 6] {
        let d = (x.fixed_rows::<3>(0) - SVector::from([observer[0], observer[1], observer[2]])).norm();
        let v = x.fixed_rows::<3>(3).norm();
        [d * relative, d * relative, d * relative, v * relative, v * relative, v * relative]
    }

    #[test]
    fn jacobians_match_central_differences_leo_and_geo() {
        let (site, rotation, t) = site();
        let radar = RadarRangeAzEl::at_site(&site, &rotation, t, [0.01, 1e-3, 1e-3]);
        let rate = RadarRangeRate::at_site(&site, &rotation, t, [0.01, 1e-3, 1e-3, 1e-4]);
        for x in leo_and_geo(&radar) {
            let s = steps(&x, &radar.observer, 1e-6);
            let e3 = jacobian_error(&radar, &x, s, Some(1));
            let e4 = jacobian_error(&rate, &x, s, Some(1));
            eprintln!("radar jacobian relative error: az/el {e3:.1e}, with range-rate {e4:.1e}");
            assert!(e3 < 1e-6 && e4 < 1e-6, "{e3:e} {e4:e}");
            // The range-rate model agrees with the az/el model on the first three components.
            let (z3, z4) = (radar.measure(&x), rate.measure(&x));
            assert_eq!(z3, z4.fixed_rows::<3>(0).into_owned());
        }
    }

    #[test]
    fn range_rate_is_the_derivative_of_range() {
        let (site, rotation, t) = site();
        let rate = RadarRangeRate::at_site(&site, &rotation, t, [0.01, 1e-3, 1e-3, 1e-4]);
        let radar = RadarRangeAzEl::at_site(&site, &rotation, t, [0.01, 1e-3, 1e-3]);
        let x = leo_and_geo(&radar)[0];
        // Move the target and the site for ±dt along their straight-line velocities.
        let dt = 1e-3;
        let range_at = |s: f64| {
            let o = site.observer(&rotation, t + s);
            let p = x.fixed_rows::<3>(0) + x.fixed_rows::<3>(3) * s;
            (p - SVector::from([o[0], o[1], o[2]])).norm()
        };
        let fd = (range_at(dt) - range_at(-dt)) / (2.0 * dt);
        let predicted = rate.measure(&x)[3];
        eprintln!("range-rate against d|d|/dt: {:.1e} km/s", fd - predicted);
        assert!((fd - predicted).abs() < 1e-6, "{fd} vs {predicted}");
    }

    #[test]
    fn azimuth_residual_wraps_across_pi() {
        let (site, rotation, t) = site();
        let radar = RadarRangeAzEl::at_site(&site, &rotation, t, [0.01, 1e-3, 1e-3]);
        let nu = radar.residual(&SVector::from([1.0, PI - 0.01, 0.3]), &SVector::from([1.0, -PI + 0.01, 0.3]));
        assert!((nu[1] + 0.02).abs() < 1e-12, "{nu}");
        let nu = radar.residual(&SVector::from([1.0, -PI + 0.01, 0.3]), &SVector::from([1.0, PI - 0.01, 0.3]));
        assert!((nu[1] - 0.02).abs() < 1e-12, "{nu}");
        // Measured azimuths lie in (−π, π]: due South, on either side of the cut.
        for az in [PI - 1e-9, PI, -PI + 1e-9] {
            let x = target(&radar, 800.0, az, 0.5, [0.0; 3]);
            let a = radar.measure(&x)[1];
            assert!(a > -PI && a <= PI && wrap_angle(a - az).abs() < 1e-9, "{a}");
        }
    }

    #[test]
    fn near_the_zenith_the_jacobian_still_matches() {
        let (site, rotation, t) = site();
        let radar = RadarRangeAzEl::at_site(&site, &rotation, t, [0.01, 1e-3, 1e-3]);
        // 0.01° and 0.001° off the zenith: the azimuth row is 1 / (ρ cos E) ≈ 0.57 and 5.7 /km at 1000 km.
        for off in [0.01_f64, 0.001] {
            let x = target(&radar, 1000.0, 0.7, (90.0 - off).to_radians(), [-3.1, 5.9, 3.4]);
            let h = 1000.0 * off.to_radians();
            let s = [h * 1e-4, h * 1e-4, h * 1e-4, 1e-3, 1e-3, 1e-3];
            let err = jacobian_error(&radar, &x, s, Some(1));
            eprintln!("radar jacobian {off}° off zenith: relative error {err:.1e}");
            assert!(err < 1e-6, "{off}: {err:e}");
            let row = radar.jacobian(&x).row(1).norm();
            assert!((row * h - 1.0).abs() < 1e-6, "{row}");
        }
    }

    #[test]
    fn exactly_at_the_zenith_azimuth_is_zero_and_finite() {
        // Basis East = y, North = z, Up = x: a target on the x axis above the site is exactly overhead.
        let radar = RadarRangeAzEl {
            observer: [7000.0, 0.0, 0.0, 0.0, 0.5, 0.0],
            enu: [[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]],
            sigma: [0.01, 1e-3, 1e-3],
        };
        let x = SVector::from([7800.0, 0.0, 0.0, 0.0, 7.0, 1.0]);
        let z = radar.measure(&x);
        assert_eq!(z, SVector::from([800.0, 0.0, PI / 2.0]));
        let h = radar.jacobian(&x);
        assert!(h.iter().all(|v| v.is_finite()));
        assert_eq!(h.row(0).into_owned(), SMatrix::<f64, 1, 6>::from_row_slice(&[1.0, 0.0, 0.0, 0.0, 0.0, 0.0]));
        assert_eq!((h.row(1).norm(), h.row(2).norm()), (0.0, 0.0));
        // At the observer itself: range 0, every row zero, nothing non-finite.
        let rate = RadarRangeRate { observer: radar.observer, enu: radar.enu, sigma: [0.01, 1e-3, 1e-3, 1e-4] };
        let at = SVector::from([7000.0, 0.0, 0.0, 1.0, 0.0, 0.0]);
        assert_eq!(rate.measure(&at), SVector::<f64, 4>::zeros());
        assert_eq!(rate.jacobian(&at), SMatrix::<f64, 4, 6>::zeros());
    }

    /// The models plug into the EKF as they are (away from the azimuth cut, where the unwrapped residual is
    /// right): one noise-free radar update of a LEO track 1 km and 10 m/s off pulls it towards the truth.
    #[test]
    fn an_ekf_update_moves_a_leo_track_towards_the_truth() {
        let (site, rotation, t) = site();
        let sigma = [0.01, 1e-3, 1e-3, 1e-4];
        let radar = RadarRangeRate::at_site(&site, &rotation, t, sigma);
        let truth = leo_and_geo(&RadarRangeAzEl::at_site(&site, &rotation, t, [0.01, 1e-3, 1e-3]))[0];
        let offset = SVector::from([0.6, -0.5, 0.6, 0.006, 0.005, -0.006]);
        let mut covariance = SMatrix::<f64, 6, 6>::identity();
        for k in 3..6 {
            covariance[(k, k)] = 1e-4;
        }
        let track = crate::Gaussian { mean: truth + offset, covariance };
        let innovation = crate::ekf::innovation(&radar, &track).unwrap();
        let updated = crate::ekf::update(&radar, &track, &innovation, &radar.measure(&truth)).unwrap();
        let before = offset.fixed_rows::<3>(0).norm();
        let after = (updated.mean - truth).fixed_rows::<3>(0).norm();
        // σ 10 m in range but 1 mrad in angle (1.2 km across the line of sight at 1200 km): the update pins
        // the range direction and leaves the cross-range error to the prior.
        let los = (truth.fixed_rows::<3>(0) - SVector::from([radar.observer[0], radar.observer[1], radar.observer[2]]))
            .normalize();
        let along_los = (updated.mean - truth).fixed_rows::<3>(0).dot(&los).abs();
        eprintln!(
            "ekf radar update: position error {before:.3} km → {after:.3} km, along the line of sight {along_los:.4} km"
        );
        assert!(after < before && along_los < 0.02, "{before} {after} {along_los}");
    }

    #[test]
    fn f32_agrees_with_f64() {
        let (site, rotation, t) = site();
        let radar = RadarRangeRate::at_site(&site, &rotation, t, [0.01, 1e-3, 1e-3, 1e-4]);
        let x = leo_and_geo(&RadarRangeAzEl::at_site(&site, &rotation, t, [0.01, 1e-3, 1e-3]))[0];
        let site32 = GroundSite { latitude: site.latitude as f32, longitude: site.longitude as f32, height: 1.6 };
        let radar32 = RadarRangeRate::at_site(&site32, &EarthRotation::new(1.2_f32), 500.0, [0.01, 1e-3, 1e-3, 1e-4]);
        let z = radar.measure(&x);
        let z32 = radar32.measure(&x.map(|v| v as f32));
        // Positions near 7000 km round to ≈ 0.5 m in f32: a few metres and a few µrad.
        assert!((f64::from(z32[0]) - z[0]).abs() < 5e-3, "{z32} {z}");
        assert!((f64::from(z32[1]) - z[1]).abs() < 5e-6 && (f64::from(z32[2]) - z[2]).abs() < 5e-6);
        assert!((f64::from(z32[3]) - z[3]).abs() < 1e-5);
        assert_eq!(radar32.noise_covariance()[(3, 3)], 1e-4_f32 * 1e-4);
    }
}
