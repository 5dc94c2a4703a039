//! Frames for Earth-based sensors: WGS-84 geodetic → Earth-fixed Cartesian, the Earth's rotation about the
//! inertial z axis, a ground site's inertial position, velocity and local East-North-Up basis, GMST (IAU-82,
//! host side) and the angle wrap of angular measurements (docs/maths.md §6.8).
//!
//! **Frames.** Earth-fixed (ECEF, km) is rotated from the inertial frame of the motion models (TEME for SGP4
//! truth, docs/maths.md §6.7) by one angle θ about the common z axis: r_I = R_z(θ) r_EF. θ(t) =
//! θ₀ + ω t, with t the scan time in seconds since the tracker's epoch and θ₀ the caller's angle at that
//! epoch (GMST of the epoch's UT1 for TEME, [`gmst_iau82`]).
//!
//! **Neglected** (sizes at the Earth's surface, R_E ≈ 6378 km):
//! - polar motion, x_p, y_p ≲ 0.3″ ≈ 1.5e-6 rad: ≲ 10 m of site position;
//! - UT1 − UTC (|·| < 0.9 s, ≈ 0.4 km of rotation at the equator): not neglected but the caller's, folded
//!   into θ₀ by evaluating GMST at UT1;
//! - precession and nutation between this rotation's inertial frame (true equator, mean equinox: TEME) and
//!   GCRF: the equinox moves ≈ 50″ a year (≈ 0.35° in 2025 since J2000), the pole ≈ 20″ a year (≈ 0.14°),
//!   nutation adds ≲ 17″; a GCRF caller must rotate the sites itself. The equation of the equinoxes
//!   (≲ 1.2″, TEME against true of date) is of the same kind.
//!
//! **Precision in f32.** Positions near 6378 km carry ≈ 0.5 m of rounding, and θ(t) = θ₀ + ω t carries
//! ≈ 6e-8 |ω t| rad (≈ 2.4 m at the surface after one day): keep the tracker's epoch within a day of the scans.

use crate::real::{Real, atan2, c, cos, floor, sin, sqrt};
use nalgebra::{SMatrix, SVector};

/// The Earth's equatorial radius R_E (km): the WGS-84 semi-major axis, and the reference radius of J2
/// ([`TwoBodyJ2`](crate::TwoBodyJ2)).
pub const EARTH_RADIUS: f64 = 6378.137;
/// WGS-84 flattening f = 1 / 298.257223563 (the semi-major axis is [`EARTH_RADIUS`]).
pub const WGS84_FLATTENING: f64 = 1.0 / 298.257_223_563;
/// The Earth's nominal rotation rate ω (rad/s), WGS-84 / IERS: 7.292115e-5 rad/s (one sidereal day of
/// 86164.09 s).
pub const EARTH_ROTATION_RATE: f64 = 7.292_115e-5;

/// π in `T`.
fn pi<T: Real>() -> T {
    c(core::f64::consts::PI)
}

/// `angle` wrapped into (−π, π]: angle − 2π ⌈(angle − π) / 2π⌉. A non-finite angle stays non-finite.
///
/// # Examples
/// ```
/// use tracker_core::sensor::wrap_angle;
/// use core::f64::consts::PI;
/// assert!((wrap_angle(2.0 * PI - 0.02_f64) + 0.02).abs() < 1e-12);
/// assert_eq!(wrap_angle(-PI), PI);
/// ```
pub fn wrap_angle<T: Real>(angle: T) -> T {
    let two_pi = c::<T>(2.0 * core::f64::consts::PI);
    let turns = -floor(-(angle - pi::<T>()) / two_pi);
    let wrapped = angle - turns * two_pi;
    // Rounding can leave the result a hair outside the interval: one correction either way.
    if wrapped <= -pi::<T>() {
        wrapped + two_pi
    } else if wrapped > pi::<T>() {
        wrapped - two_pi
    } else {
        wrapped
    }
}

/// Greenwich mean sidereal time (rad, in [0, 2π)) of a Julian date in UT1, by the IAU-82 expression that
/// SGP4 uses (seconds of time, T in Julian centuries of UT1 from J2000.0):
/// GMST = 67310.54841 + (876600 h + 8640184.812866) T + 0.093104 T² − 6.2e-6 T³.
/// Host side: f64 only; the tracker takes θ₀ = GMST at its epoch as [`EarthRotation::angle_at_epoch`].
/// A whole-day Julian date in f64 resolves ≈ 40 µs of time, 0.6 mas of rotation.
///
/// # Examples
/// Vallado, *Fundamentals of Astrodynamics and Applications*, Example 3-5: 1992 August 20, 12:14 UT1 →
/// 152.578787810°.
/// ```
/// use tracker_core::sensor::gmst_iau82;
/// let jd = 2_448_854.5 + (12.0 + 14.0 / 60.0) / 24.0;
/// assert!((gmst_iau82(jd).to_degrees() - 152.578_787_810).abs() < 1e-6);
/// ```
pub fn gmst_iau82(jd_ut1: f64) -> f64 {
    let t = (jd_ut1 - 2_451_545.0) / 36_525.0;
    let seconds = ((-6.2e-6 * t + 0.093_104) * t + (876_600.0 * 3600.0 + 8_640_184.812_866)) * t + 67_310.548_41;
    // 86400 s of time are 2π rad.
    let day = 86_400.0;
    let within_day = seconds - day * floor(seconds / day);
    let angle = within_day * (2.0 * core::f64::consts::PI / day);
    if angle >= 2.0 * core::f64::consts::PI { 0.0 } else { angle }
}

/// The Earth's rotation about the inertial z axis: θ(t) = `angle_at_epoch` + `rate` · t.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct EarthRotation<T> {
    /// θ₀ (rad): the angle from the inertial x axis to the Earth-fixed x axis (Greenwich) at the tracker's
    /// epoch, t = 0 (GMST at UT1 for TEME).
    pub angle_at_epoch: T,
    /// ω (rad/s), by default [`EARTH_ROTATION_RATE`].
    pub rate: T,
}

impl<T: Real> EarthRotation<T> {
    /// The nominal rate [`EARTH_ROTATION_RATE`] from `angle_at_epoch` (rad).
    pub fn new(angle_at_epoch: T) -> Self {
        Self { angle_at_epoch, rate: c(EARTH_ROTATION_RATE) }
    }

    /// θ(t) (rad) wrapped into (−π, π], for `t` seconds since the epoch.
    pub fn angle(&self, t: T) -> T {
        wrap_angle(self.angle_at_epoch + self.rate * t)
    }

    /// The rotation R_z(θ) from Earth-fixed to inertial coordinates at `t`: r_I = R r_EF.
    ///
    /// # Examples
    /// A quarter of a sidereal day turns Greenwich from the inertial x axis to the y axis.
    /// ```
    /// use nalgebra::SVector;
    /// use tracker_core::sensor::EarthRotation;
    /// let rotation = EarthRotation::new(0.0_f64);
    /// let t = core::f64::consts::FRAC_PI_2 / rotation.rate;
    /// let r = rotation.earth_fixed_to_inertial(t) * SVector::from([1.0, 0.0, 0.0]);
    /// assert!((r - SVector::from([0.0, 1.0, 0.0])).norm() < 1e-12);
    /// ```
    pub fn earth_fixed_to_inertial(&self, t: T) -> SMatrix<T, 3, 3> {
        let theta = self.angle(t);
        let (ct, st) = (cos(theta), sin(theta));
        let zero = T::zero();
        SMatrix::<T, 3, 3>::new(ct, -st, zero, st, ct, zero, zero, zero, T::one())
    }
}

/// A site on the Earth: WGS-84 geodetic latitude and longitude (rad, longitude positive East) and height
/// above the ellipsoid (km).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct GroundSite<T> {
    /// Geodetic latitude φ (rad).
    pub latitude: T,
    /// Longitude λ (rad, East positive).
    pub longitude: T,
    /// Height h above the WGS-84 ellipsoid (km).
    pub height: T,
}

/// The unit vectors East, North and Up at geodetic latitude `lat` and at the azimuth `lon` of the site's
/// meridian about z (the longitude in the Earth-fixed frame, λ + θ in the inertial frame).
fn enu_at<T: Real>(lat: T, lon: T) -> [[T; 3]; 3] {
    let (cl, sl) = (cos(lat), sin(lat));
    let (co, so) = (cos(lon), sin(lon));
    [[-so, co, T::zero()], [-sl * co, -sl * so, cl], [cl * co, cl * so, sl]]
}

impl<T: Real> GroundSite<T> {
    /// Earth-fixed Cartesian position (km): with e² = f (2 − f) and N = a / √(1 − e² sin² φ),
    /// ((N + h) cos φ cos λ, (N + h) cos φ sin λ, (N (1 − e²) + h) sin φ).
    ///
    /// # Examples
    /// ```
    /// use tracker_core::sensor::GroundSite;
    /// let origin = GroundSite { latitude: 0.0_f64, longitude: 0.0, height: 0.0 }.earth_fixed();
    /// assert_eq!((origin[0], origin[1], origin[2]), (6378.137, 0.0, 0.0));
    /// ```
    pub fn earth_fixed(&self) -> SVector<T, 3> {
        let f = c::<T>(WGS84_FLATTENING);
        let e2 = f * (c::<T>(2.0) - f);
        let (cl, sl) = (cos(self.latitude), sin(self.latitude));
        let n = c::<T>(EARTH_RADIUS) / sqrt(T::one() - e2 * sl * sl);
        let horizontal = (n + self.height) * cl;
        SVector::from([
            horizontal * cos(self.longitude),
            horizontal * sin(self.longitude),
            (n * (T::one() - e2) + self.height) * sl,
        ])
    }

    /// The site's inertial position and velocity (km, km/s) at scan time `t`: r_I = R_z(θ) r_EF and
    /// v_I = ω ẑ × r_I (the site is at rest on the Earth). This is the `observer` of the radar and optical
    /// measurement models.
    pub fn observer(&self, rotation: &EarthRotation<T>, t: T) -> [T; 6] {
        let r = rotation.earth_fixed_to_inertial(t) * self.earth_fixed();
        let w = rotation.rate;
        [r[0], r[1], r[2], -w * r[1], w * r[0], T::zero()]
    }

    /// The site's local East-North-Up basis in the inertial frame at scan time `t`: rows East, North, Up
    /// (Up is the ellipsoid normal, the geodetic vertical). The basis of the radar models.
    pub fn enu(&self, rotation: &EarthRotation<T>, t: T) -> [[T; 3]; 3] {
        enu_at(self.latitude, self.longitude + rotation.angle(t))
    }

    /// The Earth-fixed East-North-Up basis (rows), for `θ = 0`.
    pub fn enu_earth_fixed(&self) -> [[T; 3]; 3] {
        enu_at(self.latitude, self.longitude)
    }
}

/// Range and two angles of a line of sight `d` given in a local basis (a, b, u), and their gradients with
/// respect to `d` in that basis: ρ = |d|, α = atan2(a, b) ∈ (−π, π], β = atan2(u, √(a² + b²)).
/// For the radar (a, b, u) = (East, North, Up) and (α, β) = (azimuth, elevation); for the optical sensor
/// (a, b, u) = (y, x, z) and (α, β) = (right ascension, declination).
///
/// On the polar axis (a = b = 0: zenith, celestial pole) α is undefined: it is returned as 0 and its
/// gradient as zero, and β's gradient (a cone point there) as zero. At ρ = 0 every gradient is zero.
pub(crate) fn look_angles<T: Real>(d: [T; 3]) -> (T, T, T, [[T; 3]; 3]) {
    let [a, b, u] = d;
    let h2 = a * a + b * b;
    let h = sqrt(h2);
    let range = sqrt(h2 + u * u);
    let zero = T::zero();
    let mut gradient = [[zero; 3]; 3];
    if range > zero {
        gradient[0] = [a / range, b / range, u / range];
    }
    if !(h > zero) {
        // On the axis: α undefined (reported 0), β = ±π/2 (or 0 at ρ = 0).
        return (range, zero, atan2(u, h), gradient);
    }
    let mut alpha = atan2(a, b);
    if alpha <= -pi::<T>() {
        alpha = pi();
    }
    let beta = atan2(u, h);
    // ∂α/∂d = (b, −a, 0) / h², written as (b/h)/h so that no h² underflows or overflows.
    let (ah, bh) = (a / h, b / h);
    gradient[1] = [bh / h, -ah / h, zero];
    // ∂β/∂d = (−u a/h, −u b/h, h) / ρ²: with ρ > 0 here, again as ratios first.
    let (ur, hr) = (u / range, h / range);
    gradient[2] = [-ur * ah / range, -ur * bh / range, hr / range];
    (range, alpha, beta, gradient)
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::f64::consts::PI;

    #[test]
    fn geodetic_reference_points() {
        let a = EARTH_RADIUS;
        let origin = GroundSite { latitude: 0.0_f64, longitude: 0.0, height: 0.0 }.earth_fixed();
        assert_eq!(origin, SVector::from([a, 0.0, 0.0]));
        // The North pole is at the WGS-84 semi-minor axis b = a (1 − f) = 6356.752314245 km (NIMA TR8350.2).
        let pole = GroundSite { latitude: PI / 2.0, longitude: 0.3, height: 1.0 }.earth_fixed();
        assert!((pole[2] - 6_357.752_314_245).abs() < 1e-8, "{pole}");
        assert!(pole[0].abs() < 1e-9 && pole[1].abs() < 1e-9);
        // 90°E on the equator, 2 km up.
        let east = GroundSite { latitude: 0.0_f64, longitude: PI / 2.0, height: 2.0 }.earth_fixed();
        assert!((east - SVector::from([0.0, a + 2.0, 0.0])).norm() < 1e-9);
    }

    /// Inverse (Bowring's fixed point on the geodetic latitude) recovers the site: an independent check of
    /// the ellipsoid formula at 40°N.
    #[test]
    fn geodetic_round_trip_at_40n() {
        let site = GroundSite { latitude: 40.0_f64.to_radians(), longitude: -105.0_f64.to_radians(), height: 1.6 };
        let r = site.earth_fixed();
        let e2 = WGS84_FLATTENING * (2.0 - WGS84_FLATTENING);
        let p = (r[0] * r[0] + r[1] * r[1]).sqrt();
        let mut lat = r[2].atan2(p * (1.0 - e2));
        let mut height = 0.0;
        for _ in 0..10 {
            let n = EARTH_RADIUS / (1.0 - e2 * lat.sin() * lat.sin()).sqrt();
            height = p / lat.cos() - n;
            lat = r[2].atan2(p * (1.0 - e2 * n / (n + height)));
        }
        assert!((lat - site.latitude).abs() < 1e-12, "{lat}");
        assert!((height - site.height).abs() < 1e-8, "{height}");
        assert!((r[1].atan2(r[0]) - site.longitude).abs() < 1e-12);
    }

    /// Vallado Example 3-5 (1992-08-20 12:14 UT1 → 152.578787810°), to 1e-6° (3.6 mas); measured 4.8e-10°.
    #[test]
    fn gmst_vallado_example() {
        let jd = 2_448_854.5 + (12.0 + 14.0 / 60.0) / 24.0;
        let gmst = gmst_iau82(jd).to_degrees();
        eprintln!("gmst Vallado 3-5: {gmst:.12}° (off by {:.1e}°)", gmst - 152.578_787_810);
        assert!((gmst - 152.578_787_810).abs() < 1e-6, "{gmst}");
        // J2000.0 (2000-01-01 12:00 UT1): 67310.54841 s = 280.46061837°.
        assert!((gmst_iau82(2_451_545.0).to_degrees() - 280.460_618_375).abs() < 1e-8);
        // One solar day later the Earth has turned 360.98564736629°.
        let step = (gmst_iau82(jd + 1.0) - gmst_iau82(jd)).to_degrees().rem_euclid(360.0);
        assert!((step - 0.985_647_366).abs() < 1e-7, "{step}");
    }

    #[test]
    fn rotation_angle_and_site_velocity() {
        let rotation = EarthRotation { angle_at_epoch: 3.0_f64, rate: EARTH_ROTATION_RATE };
        // 3 + ω · 10⁴ s = 3.729 rad wraps to 3.729 − 2π.
        assert!((rotation.angle(1e4) - (3.0 + EARTH_ROTATION_RATE * 1e4 - 2.0 * PI)).abs() < 1e-12);
        let site = GroundSite { latitude: 40.0_f64.to_radians(), longitude: 0.5, height: 0.2 };
        let obs = site.observer(&rotation, 1e4);
        // v = ω ẑ × r: the velocity is the time derivative of the inertial position.
        let dt = 1.0;
        let (plus, minus) = (site.observer(&rotation, 1e4 + dt), site.observer(&rotation, 1e4 - dt));
        for k in 0..3 {
            let fd = (plus[k] - minus[k]) / (2.0 * dt);
            assert!((fd - obs[k + 3]).abs() < 1e-9, "{k}: {fd} vs {}", obs[k + 3]);
        }
        // |r| is invariant under the rotation, the basis is orthonormal and right-handed, Up ⟂ the ellipsoid.
        let r = SVector::from([obs[0], obs[1], obs[2]]);
        assert!((r.norm() - site.earth_fixed().norm()).abs() < 1e-9);
        let [e, n, u] = site.enu(&rotation, 1e4).map(SVector::from);
        assert!((e.cross(&n) - u).norm() < 1e-14 && e.dot(&n).abs() < 1e-15 && (e.norm() - 1.0).abs() < 1e-15);
        // Up is geodetic: it points 0.19° off the geocentric direction at 40°N, towards the equator.
        let tilt = (u.dot(&r) / r.norm()).acos().to_degrees();
        assert!((tilt - 0.19).abs() < 0.005, "{tilt}");
    }

    #[test]
    fn wrap_angle_edges() {
        assert_eq!(wrap_angle(PI), PI);
        assert_eq!(wrap_angle(-PI), PI);
        assert!((wrap_angle(-2.0 * PI + 0.02) - 0.02).abs() < 1e-12);
        assert!((wrap_angle(7.0 * PI) - PI).abs() < 1e-12);
        assert_eq!(wrap_angle(0.0_f32), 0.0);
        assert!(wrap_angle(f64::NAN).is_nan());
        for k in -20..=20 {
            let x = 0.37 * f64::from(k);
            let w = wrap_angle(x);
            assert!(w > -PI && w <= PI && ((x - w) / (2.0 * PI) - ((x - w) / (2.0 * PI)).round()).abs() < 1e-12);
        }
    }
}
