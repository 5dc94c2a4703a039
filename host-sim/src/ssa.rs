//! An independent simulator of real SSA scans: ground radars (range, azimuth, elevation, optional
//! range-rate) and telescopes (topocentric right ascension, declination) looking at objects on two-body +
//! J2 orbits, with fields of view, detection and clutter in measurement coordinates.
//!
//! **Independence.** Nothing here calls tracker-core: the time scale, the Earth model, the frames, the
//! measurement functions and the field-of-view tests are written again, so that a test comparing the
//! tracker with this truth compares two implementations. Truth orbits come from [`crate::orbit`]
//! (adaptive RKF7(8), two-body + J2), not from the tracker's fixed-step RK4.
//!
//! **Frames and time.** Inertial frame: Earth-centred, z along the pole, x at the equinox of the
//! scenario's epoch (the frame of SGP4's TEME up to the neglected terms below); km, km/s, radians,
//! seconds since the epoch. The Earth-fixed frame is the inertial one turned about z by the Earth
//! rotation angle θ(t) = GMST(epoch) + ω_E t, with GMST the IAU-82 polynomial (the one SGP4 uses),
//! UT1 = UTC, and ω_E = 7.292115e-5 rad/s. Neglected: polar motion (≲ 0.5″, ≲ 15 m at the site),
//! UT1 − UTC (≤ 0.9 s, ≲ 0.4 km of site motion along the parallel), precession-nutation between epoch
//! and scan (hours: ≪ 1″). Light-time is not modelled (truth and tracker share the instantaneous
//! geometry): for real LEO radar data it is ≲ 10 ms, up to ≈ 70 m of range and ≈ 0.001° of angle; for
//! GEO optical ≈ 0.12 s, ≈ 2″. Annual aberration (≈ 20″) is not modelled either.
//! Sunlight and night are ignored for the telescope.
//!
//! **Sites.** Geodetic latitude, longitude and height on WGS-84; the observer's inertial velocity is
//! ω_E × r. The local frame is East-North-Up.
//!
//! **Measurements.** Radar: ρ = |d|, A = atan2(d·e, d·n) ∈ (−π, π] (from North toward East),
//! E = atan2(d·u, √((d·e)² + (d·n)²)), optional ρ̇ = d·(v − v_s)/ρ, with d = r − r_s. Optical:
//! α = atan2(d_y, d_x) ∈ (−π, π], δ = asin(d_z/|d|). Noise is Gaussian per component; angles are wrapped
//! into (−π, π]; a noisy elevation (declination) above π/2 is reflected over the zenith (pole), turning
//! the azimuth (right ascension) by π, so every reported angle is in its range.
//!
//! **Fields of view** live in the site's local frame: a cone about a boresight (A₀, E₀) or an
//! azimuth/elevation box, always with an elevation mask and, for radar, a range window. An object is
//! detectable when its true (A, E, ρ) is inside; it is detected with probability p_D. Clutter is
//! Poisson per scan and uniform in measurement coordinates over the field of view: (ρ, A, E[, ρ̇]) for
//! radar, (α, δ) for optical (where membership of a sampled (α, δ) goes through the site's ENU basis
//! at the scan time), drawn by rejection from a bounding box in those coordinates.

use serde::{Deserialize, Serialize};

use crate::orbit::{OrbitError, Propagator};
use crate::rng::{Random, Stream};

use core::f64::consts::{FRAC_PI_2, PI, TAU};

/// The core's default measurement capacity: no simulated scan may carry more.
pub const MAX_MEASUREMENTS: usize = 32;
/// Earth rotation rate ω_E (rad/s).
pub const EARTH_ROTATION_RATE: f64 = 7.292_115e-5;
/// WGS-84 equatorial radius (km).
pub const WGS84_A: f64 = 6378.137;
/// WGS-84 flattening.
pub const WGS84_F: f64 = 1.0 / 298.257_223_563;
/// Earth's gravitational parameter used to build orbits (km³/s², as [`crate::orbit::Gravity::EARTH`]).
const MU: f64 = 398_600.441_8;
/// A visibility gap longer than this (s) between two in-view times of one sensor starts a new pass.
pub const PASS_GAP: f64 = 600.0;

/// Degrees to radians.
pub fn deg(x: f64) -> f64 {
    x.to_radians()
}

/// Why a simulation failed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SsaError {
    /// The epoch string is not `YYYY-MM-DDTHH:MM:SS[.fff][Z]` or is out of range.
    BadEpoch,
    /// A sensor is inconsistent (radar without range window, wrong number of σ, p_D outside [0, 1]...).
    BadSensor,
    /// Clutter rejection sampling found no point of the field of view (zero or tiny volume).
    EmptyFieldOfView,
    /// A scan would carry more than [`MAX_MEASUREMENTS`] measurements.
    TooManyMeasurements {
        /// The scan's index.
        scan: usize,
    },
    /// No orbit with the required passes was found for an object in the allowed number of draws.
    OrbitSearch,
    /// Truth propagation failed.
    Orbit(OrbitError),
    /// A missing fraction outside [0, 1], or a break-up asked of a preset without one.
    BadUnknowns,
}

impl core::fmt::Display for SsaError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            SsaError::BadEpoch => f.write_str("epoch is not an ISO-8601 UTC time between 1900 and 2100"),
            SsaError::BadSensor => f.write_str("inconsistent sensor specification"),
            SsaError::EmptyFieldOfView => f.write_str("clutter sampling found no point in the field of view"),
            SsaError::TooManyMeasurements { scan } => {
                write!(f, "scan {scan} has more than {MAX_MEASUREMENTS} measurements")
            }
            SsaError::OrbitSearch => f.write_str("no orbit with enough passes found for an object"),
            SsaError::Orbit(e) => write!(f, "truth propagation: {e}"),
            SsaError::BadUnknowns => f.write_str("--missing-fraction must be in [0, 1]; --breakup needs radar-leo"),
        }
    }
}

impl std::error::Error for SsaError {}

impl From<OrbitError> for SsaError {
    fn from(e: OrbitError) -> Self {
        SsaError::Orbit(e)
    }
}

// ---------------------------------------------------------------------------------------------------
// Time
// ---------------------------------------------------------------------------------------------------

/// The Julian date of a Gregorian UTC calendar time (valid 1900-03-01 to 2100-02-28).
pub fn julian_date(year: i32, month: u32, day: u32, hour: u32, minute: u32, second: f64) -> f64 {
    let (y, m) = (year as f64, month as f64);
    let day_number = 367.0 * y - ((7.0 * (y + ((m + 9.0) / 12.0).floor())) * 0.25).floor()
        + (275.0 * m / 9.0).floor()
        + day as f64
        + 1_721_013.5;
    day_number + (hour as f64 * 3600.0 + minute as f64 * 60.0 + second) / 86_400.0
}

/// Parses `YYYY-MM-DDTHH:MM:SS[.fff][Z]` (UTC) into a Julian date.
///
/// # Errors
/// [`SsaError::BadEpoch`] for any other form, a field out of range, or a year outside 1901–2099.
pub fn parse_iso8601(text: &str) -> Result<f64, SsaError> {
    let text = text.strip_suffix('Z').unwrap_or(text);
    let (date, time) = text.split_once('T').ok_or(SsaError::BadEpoch)?;
    let date: Vec<&str> = date.split('-').collect();
    let time: Vec<&str> = time.split(':').collect();
    if date.len() != 3 || time.len() != 3 || date[0].len() != 4 || date[1].len() != 2 || date[2].len() != 2 {
        return Err(SsaError::BadEpoch);
    }
    let digits = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
    if !date.iter().all(|s| digits(s)) || !digits(time[0]) || !digits(time[1]) {
        return Err(SsaError::BadEpoch);
    }
    let second_ok = time[2].bytes().all(|b| b.is_ascii_digit() || b == b'.') && time[2].len() >= 2;
    if !second_ok {
        return Err(SsaError::BadEpoch);
    }
    let year: i32 = date[0].parse().map_err(|_| SsaError::BadEpoch)?;
    let month: u32 = date[1].parse().map_err(|_| SsaError::BadEpoch)?;
    let day: u32 = date[2].parse().map_err(|_| SsaError::BadEpoch)?;
    let hour: u32 = time[0].parse().map_err(|_| SsaError::BadEpoch)?;
    let minute: u32 = time[1].parse().map_err(|_| SsaError::BadEpoch)?;
    let second: f64 = time[2].parse().map_err(|_| SsaError::BadEpoch)?;
    let leap = year % 4 == 0; // exact for 1901–2099
    let month_days = [31, if leap { 29 } else { 28 }, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31];
    let valid = (1901..=2099).contains(&year)
        && (1..=12).contains(&month)
        && day >= 1
        && day <= month_days[(month.max(1) - 1) as usize]
        && hour < 24
        && minute < 60
        && (0.0..60.0).contains(&second);
    if !valid {
        return Err(SsaError::BadEpoch);
    }
    Ok(julian_date(year, month, day, hour, minute, second))
}

/// Greenwich mean sidereal time (rad, in [0, 2π)) at a UT1 Julian date: the IAU-82 polynomial in
/// Julian centuries T from J2000, GMST = 67310.54841 s + (876600 h + 8640184.812866 s) T
/// + 0.093104 s T² − 6.2e-6 s T³, as SGP4 uses.
pub fn gmst(jd_ut1: f64) -> f64 {
    let t = (jd_ut1 - 2_451_545.0) / 36_525.0;
    let seconds = 67_310.548_41 + (876_600.0 * 3600.0 + 8_640_184.812_866) * t + 0.093_104 * t * t - 6.2e-6 * t * t * t;
    // 1 s of time = 1/240 degree.
    (seconds / 240.0).to_radians().rem_euclid(TAU)
}

/// The Earth rotation angle θ(t) = GMST(epoch) + ω_E t (rad, in [0, 2π)), `t` in s since the epoch.
pub fn earth_rotation_angle(epoch_jd: f64, t: f64) -> f64 {
    (gmst(epoch_jd) + EARTH_ROTATION_RATE * t).rem_euclid(TAU)
}

// ---------------------------------------------------------------------------------------------------
// Small vector helpers
// ---------------------------------------------------------------------------------------------------

type V3 = [f64; 3];

fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn scale(a: V3, s: f64) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
}

fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn cross(a: V3, b: V3) -> V3 {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

fn norm(a: V3) -> f64 {
    dot(a, a).sqrt()
}

fn pos(state: &[f64; 6]) -> V3 {
    [state[0], state[1], state[2]]
}

fn vel(state: &[f64; 6]) -> V3 {
    [state[3], state[4], state[5]]
}

/// The angle between two vectors (rad), by atan2 (accurate for small and large angles).
pub fn angle_between(a: V3, b: V3) -> f64 {
    norm(cross(a, b)).atan2(dot(a, b))
}

/// Wraps an angle into (−π, π].
pub fn wrap_angle(x: f64) -> f64 {
    let y = (x + PI).rem_euclid(TAU) - PI; // [−π, π)
    if y <= -PI { y + TAU } else { y }
}

/// Rotates an Earth-fixed vector into the inertial frame: about z by θ.
pub fn fixed_to_inertial(v: V3, theta: f64) -> V3 {
    let (s, c) = theta.sin_cos();
    [c * v[0] - s * v[1], s * v[0] + c * v[1], v[2]]
}

// ---------------------------------------------------------------------------------------------------
// Sites and observers
// ---------------------------------------------------------------------------------------------------

/// A ground site on WGS-84.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Site {
    /// Geodetic latitude (rad).
    pub latitude: f64,
    /// Longitude, east positive (rad).
    pub longitude: f64,
    /// Height above the ellipsoid (km).
    pub height: f64,
}

impl Site {
    /// The site's Earth-fixed position (km).
    pub fn earth_fixed(&self) -> V3 {
        let e2 = WGS84_F * (2.0 - WGS84_F);
        let (sp, cp) = self.latitude.sin_cos();
        let (sl, cl) = self.longitude.sin_cos();
        let n = WGS84_A / (1.0 - e2 * sp * sp).sqrt();
        [(n + self.height) * cp * cl, (n + self.height) * cp * sl, (n * (1.0 - e2) + self.height) * sp]
    }

    /// The site's East, North, Up unit vectors in the Earth-fixed frame.
    pub fn enu_fixed(&self) -> [V3; 3] {
        let (sp, cp) = self.latitude.sin_cos();
        let (sl, cl) = self.longitude.sin_cos();
        [[-sl, cl, 0.0], [-sp * cl, -sp * sl, cp], [cp * cl, cp * sl, sp]]
    }

    /// The observer at Earth rotation angle `theta`.
    pub fn observer(&self, theta: f64) -> Observer {
        let position = fixed_to_inertial(self.earth_fixed(), theta);
        let velocity = [-EARTH_ROTATION_RATE * position[1], EARTH_ROTATION_RATE * position[0], 0.0];
        let [e, n, u] = self.enu_fixed().map(|v| fixed_to_inertial(v, theta));
        Observer { position, velocity, east: e, north: n, up: u }
    }
}

/// A site at one instant, in the inertial frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Observer {
    /// Position (km).
    pub position: V3,
    /// Velocity ω_E × r (km/s).
    pub velocity: V3,
    /// East unit vector.
    pub east: V3,
    /// North unit vector.
    pub north: V3,
    /// Up unit vector (the geodetic normal).
    pub up: V3,
}

impl Observer {
    /// (azimuth, elevation) of an inertial line of sight `d` (any length > 0).
    pub fn look(&self, d: V3) -> (f64, f64) {
        let (e, n, u) = (dot(d, self.east), dot(d, self.north), dot(d, self.up));
        (e.atan2(n), u.atan2((e * e + n * n).sqrt()))
    }

    /// The inertial unit line of sight of (azimuth, elevation).
    pub fn direction(&self, azimuth: f64, elevation: f64) -> V3 {
        let (sa, ca) = azimuth.sin_cos();
        let (se, ce) = elevation.sin_cos();
        add(add(scale(self.east, ce * sa), scale(self.north, ce * ca)), scale(self.up, se))
    }

    /// (range, azimuth, elevation) of an inertial position.
    pub fn range_az_el(&self, position: V3) -> (f64, f64, f64) {
        let d = sub(position, self.position);
        let (a, e) = self.look(d);
        (norm(d), a, e)
    }

    /// The radar measurement of a state: [ρ, A, E] or, `with_rate`, [ρ, A, E, ρ̇].
    pub fn radar(&self, state: &[f64; 6], with_rate: bool) -> Vec<f64> {
        let d = sub(pos(state), self.position);
        let rho = norm(d);
        let (a, e) = self.look(d);
        let mut z = vec![rho, a, e];
        if with_rate {
            z.push(dot(d, sub(vel(state), self.velocity)) / rho);
        }
        z
    }

    /// The optical measurement [α, δ] of an inertial position.
    pub fn optical(&self, position: V3) -> [f64; 2] {
        radec(sub(position, self.position))
    }
}

/// (right ascension, declination) of an inertial direction.
pub fn radec(d: V3) -> [f64; 2] {
    [d[1].atan2(d[0]), (d[2] / norm(d)).clamp(-1.0, 1.0).asin()]
}

/// The inertial unit vector of (right ascension, declination).
pub fn radec_direction(alpha: f64, delta: f64) -> V3 {
    let (sa, ca) = alpha.sin_cos();
    let (sd, cd) = delta.sin_cos();
    [cd * ca, cd * sa, sd]
}

// ---------------------------------------------------------------------------------------------------
// Fields of view
// ---------------------------------------------------------------------------------------------------

/// The shape of a field of view in the site's local frame (radians).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum LookShape {
    /// Lines of sight within `half_angle` of the boresight (azimuth, elevation).
    Cone {
        /// Boresight azimuth.
        azimuth: f64,
        /// Boresight elevation.
        elevation: f64,
        /// Half-angle of the cone.
        half_angle: f64,
    },
    /// wrap(A − azimuth_centre) within ±azimuth_half_width and E in [elevation_min, elevation_max].
    Box {
        /// Centre azimuth.
        azimuth_centre: f64,
        /// Half width in azimuth (π: all azimuths).
        azimuth_half_width: f64,
        /// Lowest elevation.
        elevation_min: f64,
        /// Highest elevation.
        elevation_max: f64,
    },
}

/// A field of view: a shape, an elevation mask and (radar) a range window.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FieldOfView {
    /// The look shape.
    pub shape: LookShape,
    /// Elevation mask (rad): nothing below it is seen.
    pub min_elevation: f64,
    /// Range window [min, max] (km); radar only.
    pub range: Option<[f64; 2]>,
}

impl FieldOfView {
    /// Whether (azimuth, elevation, range) is inside; `range` None skips the range window (optical).
    pub fn contains(&self, azimuth: f64, elevation: f64, range: Option<f64>) -> bool {
        if !(elevation >= self.min_elevation) {
            return false;
        }
        if let (Some([lo, hi]), Some(r)) = (self.range, range)
            && !(r >= lo && r <= hi)
        {
            return false;
        }
        match self.shape {
            LookShape::Cone { azimuth: a0, elevation: e0, half_angle } => {
                // cos of the angle between the two directions, by the spherical law of cosines.
                let to_unit = |a: f64, e: f64| {
                    let (sa, ca) = a.sin_cos();
                    let (se, ce) = e.sin_cos();
                    [ce * sa, ce * ca, se]
                };
                angle_between(to_unit(azimuth, elevation), to_unit(a0, e0)) <= half_angle
            }
            LookShape::Box { azimuth_centre, azimuth_half_width, elevation_min, elevation_max } => {
                wrap_angle(azimuth - azimuth_centre).abs() <= azimuth_half_width
                    && elevation >= elevation_min
                    && elevation <= elevation_max
            }
        }
    }

    /// Bounding intervals of (azimuth, elevation) of the shape with the mask: azimuth as
    /// (centre, half width), elevation as [lo, hi].
    fn az_el_bounds(&self) -> (f64, f64, f64, f64) {
        const MARGIN: f64 = 1e-6;
        match self.shape {
            LookShape::Cone { azimuth, elevation, half_angle } => {
                let lo = (elevation - half_angle).max(self.min_elevation).max(-FRAC_PI_2);
                let hi = (elevation + half_angle).min(FRAC_PI_2);
                let width = if elevation.abs() + half_angle >= FRAC_PI_2 - MARGIN {
                    PI
                } else {
                    ((half_angle.sin() / elevation.cos()).min(1.0).asin() + MARGIN).min(PI)
                };
                (azimuth, width, lo - MARGIN, hi)
            }
            LookShape::Box { azimuth_centre, azimuth_half_width, elevation_min, elevation_max } => {
                (azimuth_centre, azimuth_half_width.min(PI), elevation_min.max(self.min_elevation), elevation_max)
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------------
// Sensors
// ---------------------------------------------------------------------------------------------------

/// What a sensor measures.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum SensorKind {
    /// Radar: [ρ (km), A, E].
    Radar,
    /// Radar with range-rate: [ρ, A, E, ρ̇ (km/s)]; clutter ρ̇ uniform in ±`max_range_rate`.
    RadarRangeRate {
        /// Largest |ρ̇| of clutter (km/s).
        max_range_rate: f64,
    },
    /// Telescope: [α, δ].
    Optical,
}

impl SensorKind {
    /// The measurement dimension.
    pub fn dimension(&self) -> usize {
        match self {
            SensorKind::Radar => 3,
            SensorKind::RadarRangeRate { .. } => 4,
            SensorKind::Optical => 2,
        }
    }
}

/// A sensor: site, measurement type, field of view, noise, detection and clutter.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SensorSpec {
    /// A label.
    pub name: String,
    /// Where it stands.
    pub site: Site,
    /// What it measures.
    pub kind: SensorKind,
    /// Where it looks.
    pub fov: FieldOfView,
    /// Noise standard deviation per measurement component (km, rad, km/s).
    pub sigma: Vec<f64>,
    /// Probability of detecting an object inside the field of view.
    pub detection_probability: f64,
    /// Mean number of clutter measurements per scan.
    pub clutter_rate: f64,
}

impl SensorSpec {
    fn check(&self) -> Result<(), SsaError> {
        let radar = !matches!(self.kind, SensorKind::Optical);
        let ok = self.sigma.len() == self.kind.dimension()
            && self.sigma.iter().all(|s| s.is_finite() && *s >= 0.0)
            && (0.0..=1.0).contains(&self.detection_probability)
            && self.clutter_rate.is_finite()
            && self.clutter_rate >= 0.0
            && (!radar || matches!(self.fov.range, Some([lo, hi]) if lo >= 0.0 && hi > lo));
        if ok { Ok(()) } else { Err(SsaError::BadSensor) }
    }

    /// The noiseless measurement of `state` by this sensor seen from `observer`.
    pub fn measure(&self, observer: &Observer, state: &[f64; 6]) -> Vec<f64> {
        match self.kind {
            SensorKind::Radar => observer.radar(state, false),
            SensorKind::RadarRangeRate { .. } => observer.radar(state, true),
            SensorKind::Optical => observer.optical(pos(state)).to_vec(),
        }
    }

    /// Whether a true state is inside the field of view.
    pub fn sees(&self, observer: &Observer, state: &[f64; 6]) -> bool {
        let (rho, a, e) = observer.range_az_el(pos(state));
        self.fov.contains(a, e, Some(rho))
    }

    /// Whether a measurement-space point is inside the field of view (its look angles and range).
    pub fn contains_measurement(&self, observer: &Observer, z: &[f64]) -> bool {
        match self.kind {
            SensorKind::Radar | SensorKind::RadarRangeRate { .. } => self.fov.contains(z[1], z[2], Some(z[0])),
            SensorKind::Optical => {
                let (a, e) = observer.look(radec_direction(z[0], z[1]));
                self.fov.contains(a, e, None)
            }
        }
    }

    /// A bounding box of the field of view in measurement coordinates: per component (centre, half
    /// width); angles may extend past ±π and are wrapped after sampling.
    fn measurement_box(&self, observer: &Observer) -> Vec<(f64, f64)> {
        let (az_c, az_w, el_lo, el_hi) = self.fov.az_el_bounds();
        let el = ((el_lo + el_hi) * 0.5, ((el_hi - el_lo) * 0.5).max(0.0));
        match self.kind {
            SensorKind::Radar | SensorKind::RadarRangeRate { .. } => {
                let [lo, hi] = self.fov.range.unwrap_or([0.0, 0.0]);
                let mut b = vec![((lo + hi) * 0.5, (hi - lo) * 0.5), (az_c, az_w), el];
                if let SensorKind::RadarRangeRate { max_range_rate } = self.kind {
                    b.push((0.0, max_range_rate));
                }
                b
            }
            SensorKind::Optical => match self.fov.shape {
                LookShape::Cone { azimuth, elevation, half_angle } => {
                    let [a0, d0] = radec(observer.direction(azimuth, elevation));
                    let d_lo = (d0 - half_angle).max(-FRAC_PI_2);
                    let d_hi = (d0 + half_angle).min(FRAC_PI_2);
                    let width = if d0.abs() + half_angle >= FRAC_PI_2 - 1e-6 {
                        PI
                    } else {
                        ((half_angle.sin() / d0.cos()).min(1.0).asin() + 1e-6).min(PI)
                    };
                    vec![(a0, width), ((d_lo + d_hi) * 0.5, (d_hi - d_lo) * 0.5)]
                }
                // No tight (α, δ) image of a box is computed: the whole sky bounds it.
                LookShape::Box { .. } => vec![(0.0, PI), (0.0, FRAC_PI_2)],
            },
        }
    }

    fn angle_components(&self) -> &'static [usize] {
        match self.kind {
            SensorKind::Radar | SensorKind::RadarRangeRate { .. } => &[1],
            SensorKind::Optical => &[0],
        }
    }

    /// One clutter point, uniform in measurement coordinates over the field of view.
    ///
    /// # Errors
    /// [`SsaError::EmptyFieldOfView`] when 10⁶ draws from the bounding box all fall outside.
    pub fn clutter_point(&self, observer: &Observer, random: &mut Random) -> Result<Vec<f64>, SsaError> {
        let bounds = self.measurement_box(observer);
        for _ in 0..1_000_000 {
            let mut z: Vec<f64> = bounds.iter().map(|&(c, w)| random.between(c - w, c + w)).collect();
            for &i in self.angle_components() {
                z[i] = wrap_angle(z[i]);
            }
            if self.contains_measurement(observer, &z) {
                return Ok(z);
            }
        }
        Err(SsaError::EmptyFieldOfView)
    }

    /// The field-of-view volume in measurement coordinates (km·rad², rad², ...) by Monte Carlo:
    /// the bounding box's volume times the fraction of `samples` uniform draws inside.
    pub fn fov_volume_monte_carlo(&self, observer: &Observer, samples: usize, random: &mut Random) -> f64 {
        let bounds = self.measurement_box(observer);
        let box_volume: f64 = bounds.iter().map(|&(_, w)| 2.0 * w).product();
        let mut inside = 0usize;
        for _ in 0..samples {
            let mut z: Vec<f64> = bounds.iter().map(|&(c, w)| random.between(c - w, c + w)).collect();
            for &i in self.angle_components() {
                z[i] = wrap_angle(z[i]);
            }
            inside += usize::from(self.contains_measurement(observer, &z));
        }
        box_volume * inside as f64 / samples.max(1) as f64
    }

    /// A noisy measurement of `state`: Gaussian noise per component, angles wrapped, an elevation
    /// (declination) above π/2 reflected over the zenith (pole).
    fn noisy(&self, observer: &Observer, state: &[f64; 6], random: &mut Random) -> Vec<f64> {
        let mut z = self.measure(observer, state);
        for (zi, s) in z.iter_mut().zip(&self.sigma) {
            *zi += s * random.normal();
        }
        let (a, e) = match self.kind {
            SensorKind::Optical => (0, 1),
            _ => (1, 2),
        };
        if z[e] > FRAC_PI_2 {
            z[e] = PI - z[e];
            z[a] += PI;
        } else if z[e] < -FRAC_PI_2 {
            z[e] = -PI - z[e];
            z[a] += PI;
        }
        z[a] = wrap_angle(z[a]);
        z
    }
}

// ---------------------------------------------------------------------------------------------------
// Scenarios
// ---------------------------------------------------------------------------------------------------

/// One object's truth.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ObjectTruth {
    /// Inertial state at t = 0 (km, km/s); propagate with [`crate::orbit::Propagator::EARTH`].
    pub initial_state: [f64; 6],
    /// The crossing pair, co-located cluster or break-up it belongs to (index into `groups`), if any.
    pub group: Option<usize>,
    /// Whether the prior knows the object.
    #[serde(default = "known")]
    pub in_prior: bool,
    /// When the object starts to exist (a break-up fragment); `None`: from the start.
    #[serde(default)]
    pub birth_time: Option<f64>,
}

fn known() -> bool {
    true
}

impl ObjectTruth {
    /// An object of the prior that exists from the start.
    pub fn known(initial_state: [f64; 6], group: Option<usize>) -> Self {
        ObjectTruth { initial_state, group, in_prior: true, birth_time: None }
    }

    /// Whether the object exists at `time`.
    pub fn exists_at(&self, time: f64) -> bool {
        self.birth_time.is_none_or(|b| b <= time)
    }
}

/// Objects unknown to the prior: a fraction of the objects missing from it, and a break-up.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Unknowns {
    /// Fraction of the objects (break-up fragments aside) left out of the prior, rounded to the nearest
    /// count; in [0, 1].
    pub missing_fraction: f64,
    /// Fragments of a break-up during the run (`radar-leo` only; 0: none).
    pub breakup: usize,
}

/// Leaves `round(fraction × n)` of the first `n` objects out of the prior, chosen by the seed's stream
/// [`Stream::Scenario`] 2,000,000 (no other draw moves).
fn mark_missing(seed: u64, objects: &mut [ObjectTruth], n: usize, fraction: f64) -> Result<(), SsaError> {
    if !(0.0..=1.0).contains(&fraction) {
        return Err(SsaError::BadUnknowns);
    }
    let mut order: Vec<usize> = (0..n).collect();
    Random::stream(seed, Stream::Scenario, 2_000_000).shuffle(&mut order);
    let missing = (fraction * n as f64).round() as usize;
    for &i in &order[..missing.min(n)] {
        objects[i].in_prior = false;
    }
    Ok(())
}

/// An object's truth at every scan time.
type Track = Vec<[f64; 6]>;

/// A break-up of `parent` into `count` new fragments (stream [`Stream::Scenario`] 3,000,000): at a time
/// 2 to 15 minutes before the start of one of the parent's passes after the first 5 minutes of the run,
/// each fragment takes the parent's state and a velocity kick of 2 to 30 m/s in a uniformly random
/// direction. The parent continues on its orbit. Returns the fragments (born then, unknown to the prior),
/// each with its truth at `schedule`'s times.
fn breakup(
    seed: u64,
    parent: &ObjectTruth,
    count: usize,
    group: usize,
    schedule: &[(f64, usize)],
    visible: &[bool],
    sensors: usize,
) -> Result<Vec<(ObjectTruth, Track)>, SsaError> {
    let mut random = Random::stream(seed, Stream::Scenario, 3_000_000);
    let mut starts = vec![];
    let mut last = vec![f64::NEG_INFINITY; sensors];
    for (k, (&(t, s), &v)) in schedule.iter().zip(visible).enumerate() {
        if v {
            if t - last[s] > PASS_GAP && t >= 300.0 {
                starts.push(k);
            }
            last[s] = t;
        }
    }
    let Some(&last_start) = starts.last() else { return Err(SsaError::OrbitSearch) };
    let start = starts[((random.uniform() * starts.len() as f64) as usize).min(starts.len() - 1)];
    let start = if schedule[start].0 < 300.0 { last_start } else { start };
    let time = (schedule[start].0 - random.between(120.0, 900.0)).max(1.0);
    let at_breakup = Propagator::EARTH.propagate(parent.initial_state, time)?;
    let times: Vec<f64> = schedule.iter().map(|&(t, _)| t).collect();
    let mut fragments = Vec::with_capacity(count);
    for _ in 0..count {
        let direction = [random.normal(), random.normal(), random.normal()];
        let speed = random.between(0.002, 0.030);
        let kick = scale(direction, speed / norm(direction).max(f64::MIN_POSITIVE));
        let v = add(vel(&at_breakup), kick);
        let state = [at_breakup[0], at_breakup[1], at_breakup[2], v[0], v[1], v[2]];
        let initial = Propagator::EARTH.propagate(state, -time)?;
        let fragment =
            ObjectTruth { initial_state: initial, group: Some(group), in_prior: false, birth_time: Some(time) };
        fragments.push((fragment, track(initial, &times)?));
    }
    Ok(fragments)
}

/// A deliberately close group of objects.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Group {
    /// "crossing-pair" or "cluster".
    pub kind: String,
    /// Object indices.
    pub objects: Vec<usize>,
}

/// The truth of one object that is inside the field of view at a scan.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TruthAt {
    /// Object index.
    pub object: usize,
    /// Inertial state at the scan time.
    pub state: [f64; 6],
    /// The index of its measurement in the scan, if detected.
    pub measurement: Option<usize>,
}

/// One scan of one sensor.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Scan3 {
    /// Seconds since the epoch.
    pub time: f64,
    /// Index into `sensors`.
    pub sensor: usize,
    /// Measurements (detections and clutter in random order).
    pub measurements: Vec<Vec<f64>>,
    /// Objects inside the field of view (detected or not), by object index.
    pub truth: Vec<TruthAt>,
}

/// A simulated SSA scenario.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SsaScenario {
    /// Preset name.
    pub name: String,
    /// The seed.
    pub seed: u64,
    /// UTC epoch as written.
    pub epoch: String,
    /// UTC epoch as a Julian date (UT1 = UTC).
    pub epoch_jd: f64,
    /// Duration (s).
    pub duration: f64,
    /// Sensors.
    pub sensors: Vec<SensorSpec>,
    /// Objects (all exist for the whole scenario).
    pub objects: Vec<ObjectTruth>,
    /// Crossing pairs and clusters.
    pub groups: Vec<Group>,
    /// Scans in time order.
    pub scans: Vec<Scan3>,
}

/// Figures of a scenario.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stats {
    /// Number of scans.
    pub scans: usize,
    /// Most measurements in one scan.
    pub max_measurements: usize,
    /// Mean measurements per scan.
    pub mean_measurements: f64,
    /// Most objects in view in one scan.
    pub max_in_view: usize,
    /// Mean objects in view per scan.
    pub mean_in_view: f64,
    /// Scans with at least one object in view.
    pub scans_with_objects: usize,
}

impl SsaScenario {
    /// Scan statistics.
    pub fn stats(&self) -> Stats {
        let n = self.scans.len().max(1) as f64;
        Stats {
            scans: self.scans.len(),
            max_measurements: self.scans.iter().map(|s| s.measurements.len()).max().unwrap_or(0),
            mean_measurements: self.scans.iter().map(|s| s.measurements.len()).sum::<usize>() as f64 / n,
            max_in_view: self.scans.iter().map(|s| s.truth.len()).max().unwrap_or(0),
            mean_in_view: self.scans.iter().map(|s| s.truth.len()).sum::<usize>() as f64 / n,
            scans_with_objects: self.scans.iter().filter(|s| !s.truth.is_empty()).count(),
        }
    }

    /// Passes per object: maximal runs of in-view times of one sensor, split by gaps > [`PASS_GAP`],
    /// summed over the sensors.
    pub fn passes(&self) -> Vec<usize> {
        let mut last = vec![vec![f64::NEG_INFINITY; self.sensors.len()]; self.objects.len()];
        let mut passes = vec![0; self.objects.len()];
        for scan in &self.scans {
            for t in &scan.truth {
                if scan.time - last[t.object][scan.sensor] > PASS_GAP {
                    passes[t.object] += 1;
                }
                last[t.object][scan.sensor] = scan.time;
            }
        }
        passes
    }

    /// Per group, over the scans that see all its members: the smallest and the largest pairwise angle
    /// (rad) between members as seen from the sensor ((∞, 0) if no scan sees them all).
    pub fn group_separations(&self) -> Vec<(f64, f64)> {
        self.groups
            .iter()
            .map(|g| {
                let (mut lo, mut hi) = (f64::INFINITY, 0.0_f64);
                for scan in &self.scans {
                    let o = self.observer(scan);
                    let dirs: Option<Vec<V3>> = g
                        .objects
                        .iter()
                        .map(|&i| scan.truth.iter().find(|t| t.object == i).map(|t| sub(pos(&t.state), o.position)))
                        .collect();
                    let Some(dirs) = dirs else { continue };
                    for (k, x) in dirs.iter().enumerate() {
                        for y in &dirs[k + 1..] {
                            let angle = angle_between(*x, *y);
                            lo = lo.min(angle);
                            hi = hi.max(angle);
                        }
                    }
                }
                (lo, hi)
            })
            .collect()
    }

    /// An object's truth at every scan time (in view or not), propagated from its initial state the way
    /// the simulation did: the states of the scans' `truth` entries are reproduced bit for bit.
    ///
    /// # Errors
    /// [`SsaError::Orbit`] if propagation fails.
    pub fn object_states(&self, object: usize) -> Result<Vec<[f64; 6]>, SsaError> {
        let times: Vec<f64> = self.scans.iter().map(|s| s.time).collect();
        track(self.objects[object].initial_state, &times)
    }

    /// The observer of a scan.
    pub fn observer(&self, scan: &Scan3) -> Observer {
        self.sensors[scan.sensor].site.observer(earth_rotation_angle(self.epoch_jd, scan.time))
    }
}

/// Truth states of one object at `times` (increasing, ≥ 0), propagated step by step from t = 0.
fn track(initial: [f64; 6], times: &[f64]) -> Result<Vec<[f64; 6]>, SsaError> {
    let mut state = initial;
    let mut t = 0.0;
    let mut out = Vec::with_capacity(times.len());
    for &ti in times {
        state = Propagator::EARTH.propagate(state, ti - t)?;
        t = ti;
        out.push(state);
    }
    Ok(out)
}

/// Per scan, whether the object is inside the scan's field of view.
fn visibility(
    sensors: &[SensorSpec],
    schedule: &[(f64, usize)],
    observers: &[Observer],
    states: &[[f64; 6]],
) -> Vec<bool> {
    schedule.iter().zip(observers).zip(states).map(|((&(_, s), o), x)| sensors[s].sees(o, x)).collect()
}

/// The number of passes in a visibility sequence (see [`SsaScenario::passes`]).
fn count_passes(schedule: &[(f64, usize)], visible: &[bool], sensors: usize) -> usize {
    let mut last = vec![f64::NEG_INFINITY; sensors];
    let mut passes = 0;
    for (&(t, s), &v) in schedule.iter().zip(visible) {
        if v {
            if t - last[s] > PASS_GAP {
                passes += 1;
            }
            last[s] = t;
        }
    }
    passes
}

/// Everything a preset decides before the scans are drawn.
struct Plan {
    name: String,
    seed: u64,
    epoch: String,
    duration: f64,
    sensors: Vec<SensorSpec>,
    objects: Vec<ObjectTruth>,
    groups: Vec<Group>,
    /// (time, sensor) of every scan, in time order.
    schedule: Vec<(f64, usize)>,
    /// Truth per object per scan, when the preset already propagated it.
    tracks: Option<Vec<Vec<[f64; 6]>>>,
    /// Per object per scan, whether the object can be seen at all (a telescope sees only sunlit objects);
    /// `None`: always.
    visible: Option<Vec<Vec<bool>>>,
}

fn observers(sensors: &[SensorSpec], epoch_jd: f64, schedule: &[(f64, usize)]) -> Vec<Observer> {
    schedule.iter().map(|&(t, s)| sensors[s].site.observer(earth_rotation_angle(epoch_jd, t))).collect()
}

/// Draws scan `k` of a plan with `seed`: the sensor `s` (`sensor`, seen from `observer`) at `time` looks at
/// the objects at `states` (`None`: object `i` cannot be seen at this scan; object `i` draws its detection and
/// noise from `detection[i]`); Poisson clutter
/// from stream [`Stream::Clutter`] `k`, the order shuffled by stream [`Stream::Scenario`] `k`.
///
/// # Errors
/// [`SsaError::TooManyMeasurements`] above [`MAX_MEASUREMENTS`]; [`SsaError::EmptyFieldOfView`] from clutter.
pub fn draw_scan(
    seed: u64,
    k: usize,
    (time, s): (f64, usize),
    sensor: &SensorSpec,
    observer: &Observer,
    states: impl Iterator<Item = Option<[f64; 6]>>,
    detection: &mut [Random],
) -> Result<Scan3, SsaError> {
    // (measurement, origin)
    let mut items: Vec<(Vec<f64>, Option<usize>)> = Vec::new();
    let mut truth = Vec::new();
    for ((i, state), random) in states.enumerate().zip(detection.iter_mut()) {
        let Some(state) = state.filter(|state| sensor.sees(observer, state)) else { continue };
        truth.push(TruthAt { object: i, state, measurement: None });
        if random.uniform() < sensor.detection_probability {
            items.push((sensor.noisy(observer, &state, random), Some(i)));
        }
    }
    let mut clutter = Random::stream(seed, Stream::Clutter, k as u64);
    for _ in 0..clutter.poisson(sensor.clutter_rate) {
        items.push((sensor.clutter_point(observer, &mut clutter)?, None));
    }
    if items.len() > MAX_MEASUREMENTS {
        return Err(SsaError::TooManyMeasurements { scan: k });
    }
    Random::stream(seed, Stream::Scenario, k as u64).shuffle(&mut items);
    for (j, (_, origin)) in items.iter().enumerate() {
        if let Some(i) = origin
            && let Some(t) = truth.iter_mut().find(|t| t.object == *i)
        {
            t.measurement = Some(j);
        }
    }
    Ok(Scan3 { time, sensor: s, measurements: items.into_iter().map(|(z, _)| z).collect(), truth })
}

/// Draws detections and clutter for every scan of a plan.
fn simulate(plan: Plan) -> Result<SsaScenario, SsaError> {
    let epoch_jd = parse_iso8601(&plan.epoch)?;
    for s in &plan.sensors {
        s.check()?;
    }
    let times: Vec<f64> = plan.schedule.iter().map(|&(t, _)| t).collect();
    let observers = observers(&plan.sensors, epoch_jd, &plan.schedule);
    let tracks = match plan.tracks {
        Some(t) => t,
        None => plan.objects.iter().map(|o| track(o.initial_state, &times)).collect::<Result<_, _>>()?,
    };
    let mut detection: Vec<Random> =
        (0..plan.objects.len()).map(|i| Random::stream(plan.seed, Stream::Detection, i as u64)).collect();
    let mut scans = Vec::with_capacity(plan.schedule.len());
    for (k, (&(time, s), observer)) in plan.schedule.iter().zip(&observers).enumerate() {
        // An object that does not exist yet (a fragment before its break-up) or that the plan marks invisible
        // at this scan (a telescope's unlit object) is not seen.
        let visible = |i: usize| plan.objects[i].exists_at(time) && plan.visible.as_ref().is_none_or(|v| v[i][k]);
        let states = tracks.iter().enumerate().map(|(i, states)| visible(i).then_some(states[k]));
        scans.push(draw_scan(plan.seed, k, (time, s), &plan.sensors[s], observer, states, &mut detection)?);
    }
    Ok(SsaScenario {
        name: plan.name,
        seed: plan.seed,
        epoch: plan.epoch,
        epoch_jd,
        duration: plan.duration,
        sensors: plan.sensors,
        objects: plan.objects,
        groups: plan.groups,
        scans,
    })
}

/// A scenario whose truth the caller propagated (`tracks[object][scan]`, inertial km, km/s, at the
/// `schedule`'s times): detections and clutter drawn as for the presets, an object seen only where
/// `visible[object][scan]` (and inside the sensor's field of view). `objects[i].initial_state` is
/// `tracks`' first state (informative only).
///
/// # Errors
/// As [`radar_leo`].
#[allow(clippy::too_many_arguments)]
pub fn simulate_tracks(
    name: &str,
    seed: u64,
    epoch: &str,
    duration: f64,
    sensors: Vec<SensorSpec>,
    schedule: Vec<(f64, usize)>,
    tracks: Vec<Vec<[f64; 6]>>,
    visible: Vec<Vec<bool>>,
) -> Result<SsaScenario, SsaError> {
    let objects = tracks
        .iter()
        .map(|t| ObjectTruth {
            initial_state: t.first().copied().unwrap_or([0.0; 6]),
            group: None,
            in_prior: true,
            birth_time: None,
        })
        .collect();
    simulate(Plan {
        name: name.into(),
        seed,
        epoch: epoch.into(),
        duration,
        sensors,
        objects,
        groups: vec![],
        schedule,
        tracks: Some(tracks),
        visible: Some(visible),
    })
}

// ---------------------------------------------------------------------------------------------------
// Orbit construction
// ---------------------------------------------------------------------------------------------------

/// The inertial state of a Keplerian orbit (a km, e, angles rad, M mean anomaly).
pub fn kepler_state(a: f64, e: f64, i: f64, raan: f64, argp: f64, mean_anomaly: f64) -> [f64; 6] {
    let mut ea = mean_anomaly;
    for _ in 0..20 {
        ea -= (ea - e * ea.sin() - mean_anomaly) / (1.0 - e * ea.cos());
    }
    let (se, ce) = ea.sin_cos();
    let b = a * (1.0 - e * e).sqrt();
    let r = a * (1.0 - e * ce);
    let n = (MU / (a * a * a)).sqrt();
    // Perifocal position and velocity.
    let (xp, yp) = (a * (ce - e), b * se);
    let (vxp, vyp) = (-a * a * n * se / r, a * b * n * ce / r);
    let (so, co) = raan.sin_cos();
    let (sw, cw) = argp.sin_cos();
    let (si, ci) = i.sin_cos();
    let p = [co * cw - so * sw * ci, so * cw + co * sw * ci, sw * si];
    let q = [-co * sw - so * cw * ci, -so * sw + co * cw * ci, cw * si];
    let r_vec = add(scale(p, xp), scale(q, yp));
    let v_vec = add(scale(p, vxp), scale(q, vyp));
    [r_vec[0], r_vec[1], r_vec[2], v_vec[0], v_vec[1], v_vec[2]]
}

/// A circular orbit of `radius` and `inclination` passing through the inertial direction of
/// (right ascension, declination) `aim`, ascending or descending there; its state at that point.
fn aimed_circular(aim: [f64; 2], radius: f64, inclination: f64, ascending: bool) -> [f64; 6] {
    let [ra, dec] = aim;
    let s = (dec.sin() / inclination.sin()).clamp(-1.0, 1.0).asin();
    let u = if ascending { s } else { PI - s };
    let raan = ra - (inclination.cos() * u.sin()).atan2(u.cos());
    kepler_state(radius, 0.0, inclination, raan, 0.0, u)
}

/// Rodrigues rotation of `v` about unit `k` by `angle`.
fn rotate(v: V3, k: V3, angle: f64) -> V3 {
    let (s, c) = angle.sin_cos();
    add(add(scale(v, c), scale(cross(k, v), s)), scale(k, dot(k, v) * (1.0 - c)))
}

// ---------------------------------------------------------------------------------------------------
// Presets
// ---------------------------------------------------------------------------------------------------

/// Parameters of [`radar_leo_with`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RadarLeoConfig {
    /// Objects on their own orbits.
    pub singles: usize,
    /// Crossing pairs (two objects each).
    pub pairs: usize,
    /// Duration (s).
    pub duration: f64,
    /// Time between two scans of one radar (s); the radars alternate, offset by half of it.
    pub revisit: f64,
    /// Passes every object must have (orbits are redrawn until they do).
    pub min_passes: usize,
    /// Objects unknown to the prior.
    pub unknowns: Unknowns,
}

impl RadarLeoConfig {
    /// The `radar-leo` preset: 100 singles + 10 crossing pairs, 6 h, each radar every 20 s.
    pub const PRESET: RadarLeoConfig = RadarLeoConfig {
        singles: 100,
        pairs: 10,
        duration: 6.0 * 3600.0,
        revisit: 20.0,
        min_passes: 2,
        unknowns: Unknowns { missing_fraction: 0.0, breakup: 0 },
    };
}

/// The two radars of `radar-leo`.
pub fn leo_radars() -> Vec<SensorSpec> {
    let sigma = vec![0.020, deg(0.03), deg(0.03)];
    vec![
        SensorSpec {
            name: "radar-north".into(),
            site: Site { latitude: deg(47.35), longitude: deg(8.50), height: 0.5 },
            kind: SensorKind::Radar,
            fov: FieldOfView {
                shape: LookShape::Box {
                    azimuth_centre: 0.0,
                    azimuth_half_width: PI,
                    elevation_min: deg(15.0),
                    elevation_max: FRAC_PI_2,
                },
                min_elevation: deg(15.0),
                range: Some([200.0, 3000.0]),
            },
            sigma: sigma.clone(),
            detection_probability: 0.9,
            clutter_rate: 2.0,
        },
        SensorSpec {
            name: "radar-south".into(),
            site: Site { latitude: deg(37.40), longitude: deg(-5.90), height: 0.1 },
            kind: SensorKind::Radar,
            fov: FieldOfView {
                shape: LookShape::Cone { azimuth: PI, elevation: deg(55.0), half_angle: deg(45.0) },
                min_elevation: deg(10.0),
                range: Some([200.0, 3000.0]),
            },
            sigma,
            detection_probability: 0.9,
            clutter_rate: 2.0,
        },
    ]
}

const LEO_EPOCH: &str = "2026-03-20T00:00:00Z";

/// `radar-leo`: two ground radars ~1600 km apart (47.35° N 8.50° E: all-azimuth box, elevation
/// 15–90°; 37.40° N 5.90° W: cone of 45° about azimuth 180°, elevation 55°, mask 10°; both 200–3000 km),
/// σ = 20 m, 0.03°, 0.03°, p_D 0.9, 2 clutter per scan; 100 LEO objects and 10 crossing pairs over 6 h,
/// every object with ≥ 2 passes; each radar scans every 20 s, alternating (one scan every 10 s).
///
/// # Errors
/// [`SsaError`] if propagation fails or a scan would exceed [`MAX_MEASUREMENTS`].
pub fn radar_leo(seed: u64) -> Result<SsaScenario, SsaError> {
    radar_leo_with(seed, &RadarLeoConfig::PRESET)
}

/// `radar-leo` with other sizes (tests use a short one).
///
/// Every object's orbit is built to pass over a point near one of the sites (within ±8° of latitude and
/// longitude of it) at a random time: altitude 400–1500 km, inclination between 3° above the aim
/// point's latitude and 3° below its supplement, near circular. The orbit is redrawn (at most 200 times, from the object's
/// own stream) until the object has `min_passes` passes, else [`SsaError::OrbitSearch`]. A crossing pair is an object and a twin that at
/// the aim time is 1–3 km higher on the same radial with its orbit plane turned by 0.3–1.5° about that
/// radial: the two cross in the sky over the aim point.
///
/// # Errors
/// As [`radar_leo`].
pub fn radar_leo_with(seed: u64, config: &RadarLeoConfig) -> Result<SsaScenario, SsaError> {
    let sensors = leo_radars();
    let epoch_jd = parse_iso8601(LEO_EPOCH)?;
    let half = config.revisit * 0.5;
    let steps = (config.duration / half).floor() as usize;
    let schedule: Vec<(f64, usize)> = (0..=steps).map(|k| (k as f64 * half, k % 2)).collect();
    let times: Vec<f64> = schedule.iter().map(|&(t, _)| t).collect();
    let obs = observers(&sensors, epoch_jd, &schedule);
    let mut objects = Vec::new();
    let mut groups = Vec::new();
    let mut tracks = Vec::new();
    let units = config.singles + config.pairs;
    for unit in 0..units {
        let paired = unit >= config.singles;
        let mut random = Random::stream(seed, Stream::Orbit, unit as u64);
        let mut chosen = None;
        for _attempt in 0..200 {
            let site = &sensors[unit % 2].site;
            let aim_site = Site {
                latitude: site.latitude + deg(random.between(-8.0, 8.0)),
                longitude: site.longitude + deg(random.between(-8.0, 8.0)),
                height: 0.0,
            };
            let t_aim = random.between(0.0, config.duration);
            let ground = fixed_to_inertial(aim_site.earth_fixed(), earth_rotation_angle(epoch_jd, t_aim));
            let aim = radec(ground);
            let radius = WGS84_A + random.between(400.0, 1500.0);
            let lo = aim[1].abs() + deg(3.0);
            let inclination = random.between(lo, PI - lo);
            let ascending = random.uniform() < 0.5;
            let at_aim = aimed_circular(aim, radius, inclination, ascending);
            let mut members = vec![at_aim];
            if paired {
                let up = scale(pos(&at_aim), 1.0 / norm(pos(&at_aim)));
                let dr = random.between(1.0, 3.0);
                let turn = deg(random.between(0.3, 1.5)) * if random.uniform() < 0.5 { -1.0 } else { 1.0 };
                let r2 = add(pos(&at_aim), scale(up, dr));
                let v2 = scale(rotate(vel(&at_aim), up, turn), (radius / (radius + dr)).sqrt());
                members.push([r2[0], r2[1], r2[2], v2[0], v2[1], v2[2]]);
            }
            let mut candidate = Vec::new();
            let mut ok = true;
            for m in &members {
                let initial = Propagator::EARTH.propagate(*m, -t_aim)?;
                let states = track(initial, &times)?;
                let visible = visibility(&sensors, &schedule, &obs, &states);
                ok &= count_passes(&schedule, &visible, sensors.len()) >= config.min_passes;
                candidate.push((initial, states));
                if !ok {
                    break;
                }
            }
            if ok {
                chosen = Some(candidate);
                break;
            }
        }
        let candidate = chosen.ok_or(SsaError::OrbitSearch)?;
        let group = paired.then(|| {
            groups.push(Group { kind: "crossing-pair".into(), objects: vec![objects.len(), objects.len() + 1] });
            groups.len() - 1
        });
        for (initial, states) in candidate {
            objects.push(ObjectTruth::known(initial, group));
            tracks.push(states);
        }
    }
    let n = objects.len();
    mark_missing(seed, &mut objects, n, config.unknowns.missing_fraction)?;
    if config.unknowns.breakup > 0 && config.singles > 0 {
        // The parent: a single, chosen by the break-up's own stream.
        let mut random = Random::stream(seed, Stream::Scenario, 3_000_001);
        let parent = ((random.uniform() * config.singles as f64) as usize).min(config.singles - 1);
        let visible = visibility(&sensors, &schedule, &obs, &tracks[parent]);
        groups.push(Group { kind: "breakup".into(), objects: vec![parent] });
        let group = groups.len() - 1;
        objects[parent].group = Some(group);
        let fragments =
            breakup(seed, &objects[parent], config.unknowns.breakup, group, &schedule, &visible, sensors.len())?;
        for (fragment, states) in fragments {
            groups[group].objects.push(objects.len());
            objects.push(fragment);
            tracks.push(states);
        }
    } else if config.unknowns.breakup > 0 {
        return Err(SsaError::BadUnknowns);
    }
    simulate(Plan {
        name: "radar-leo".into(),
        seed,
        epoch: LEO_EPOCH.into(),
        duration: config.duration,
        sensors,
        objects,
        groups,
        schedule,
        tracks: Some(tracks),
        visible: None,
    })
}

/// `tiny-3d`: the northern radar of `radar-leo` alone, 3 LEO objects aimed to pass near it at 40, 50
/// and 60 s, 11 scans every 10 s (0–100 s), p_D 0.95, 0.5 clutter per scan.
///
/// # Errors
/// As [`radar_leo`].
pub fn tiny_3d(seed: u64) -> Result<SsaScenario, SsaError> {
    tiny_3d_with(seed, &Unknowns::default())
}

/// [`tiny_3d`] with objects unknown to the prior (no break-up): a small 3-D scenario with births, small
/// enough for the unbounded reference.
///
/// # Errors
/// [`SsaError::BadUnknowns`] for a break-up or a fraction outside [0, 1].
pub fn tiny_3d_with(seed: u64, unknowns: &Unknowns) -> Result<SsaScenario, SsaError> {
    if unknowns.breakup > 0 {
        return Err(SsaError::BadUnknowns);
    }
    let mut sensor = leo_radars().remove(0);
    sensor.detection_probability = 0.95;
    sensor.clutter_rate = 0.5;
    let epoch_jd = parse_iso8601(LEO_EPOCH)?;
    let mut objects = Vec::new();
    for k in 0..3 {
        let mut random = Random::stream(seed, Stream::Orbit, k);
        let t_aim = 40.0 + 10.0 * k as f64;
        let aim_site = Site {
            latitude: sensor.site.latitude + deg(random.between(-3.0, 3.0)),
            longitude: sensor.site.longitude + deg(random.between(-3.0, 3.0)),
            height: 0.0,
        };
        let aim = radec(fixed_to_inertial(aim_site.earth_fixed(), earth_rotation_angle(epoch_jd, t_aim)));
        let radius = WGS84_A + random.between(500.0, 1200.0);
        let lo = aim[1].abs() + deg(3.0);
        let at_aim = aimed_circular(aim, radius, random.between(lo, PI - lo), random.uniform() < 0.5);
        objects.push(ObjectTruth::known(Propagator::EARTH.propagate(at_aim, -t_aim)?, None));
    }
    mark_missing(seed, &mut objects, 3, unknowns.missing_fraction)?;
    simulate(Plan {
        name: "tiny-3d".into(),
        seed,
        epoch: LEO_EPOCH.into(),
        duration: 100.0,
        sensors: vec![sensor],
        objects,
        groups: Vec::new(),
        schedule: (0..=10).map(|k| (10.0 * k as f64, 0)).collect(),
        tracks: None,
        visible: None,
    })
}

/// Parameters of [`optical_geo_with`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OpticalGeoConfig {
    /// Station-kept objects on their own slots (always in view).
    pub singles: usize,
    /// Uncontrolled inclined objects that sweep north–south through the field.
    pub sweepers: usize,
    /// Co-located clusters.
    pub clusters: usize,
    /// Objects per cluster.
    pub cluster_size: usize,
    /// Duration (s).
    pub duration: f64,
    /// Time between scans (s).
    pub cadence: f64,
    /// Objects unknown to the prior (no break-up: [`Unknowns::breakup`] must be 0).
    pub unknowns: Unknowns,
}

impl OpticalGeoConfig {
    /// The `optical-geo` preset: 6 singles + 3 clusters of 4 + 12 sweepers, 4 h, a frame every 90 s.
    pub const PRESET: OpticalGeoConfig = OpticalGeoConfig {
        singles: 6,
        sweepers: 12,
        clusters: 3,
        cluster_size: 4,
        duration: 4.0 * 3600.0,
        cadence: 90.0,
        unknowns: Unknowns { missing_fraction: 0.0, breakup: 0 },
    };
}

const GEO_EPOCH: &str = "2026-03-20T02:00:00Z";

/// The staring telescope of `optical-geo`, pointed at the GEO belt on its own meridian.
pub fn geo_telescope() -> SensorSpec {
    let site = Site { latitude: deg(32.0), longitude: deg(-110.0), height: 2.0 };
    // Boresight: the look angles of the geostationary point at the site's longitude.
    let geo = Site { latitude: 0.0, longitude: site.longitude, height: geo_radius() - WGS84_A };
    let observer = site.observer(0.0);
    let (_, azimuth, elevation) = observer.range_az_el(fixed_to_inertial(geo.earth_fixed(), 0.0));
    SensorSpec {
        name: "telescope".into(),
        site,
        kind: SensorKind::Optical,
        fov: FieldOfView {
            shape: LookShape::Cone { azimuth, elevation, half_angle: deg(3.0) },
            min_elevation: deg(20.0),
            range: None,
        },
        sigma: vec![deg(1.5 / 3600.0), deg(1.5 / 3600.0)],
        detection_probability: 0.95,
        clutter_rate: 1.0,
    }
}

/// The geosynchronous radius (km): mean motion ω_E.
fn geo_radius() -> f64 {
    (MU / (EARTH_ROTATION_RATE * EARTH_ROTATION_RATE)).cbrt()
}

/// `optical-geo`: one staring telescope at 32° N 110° W, 2 km, a cone of half-angle 3° about the GEO
/// belt on its meridian (az 180°, el ≈ 52.7°), mask 20°, σ 1.5″ per angle, p_D 0.95, 1 clutter per
/// frame; a frame every 90 s for 4 h. Objects: 6 station-kept singles within ±2° of longitude of the
/// meridian (e ≤ 2e-4, i ≤ 0.1°), 3 co-located clusters of 4 (slots near −1.5°, 0°, +1.5°; members
/// within ±0.015° of longitude of the slot, e ≤ 8e-5, i ≤ 0.01°), always in view; and 12 uncontrolled
/// inclined geosynchronous objects (i 10–16°, circular) crossing the equator within ±2° of the meridian
/// at a random time of the run, each in view for about 1–1.5 h. The sweepers keep the number in view at once
/// below the 32 measurements a scan may carry while at least 30 objects are seen.
///
/// # Errors
/// As [`radar_leo`].
pub fn optical_geo(seed: u64) -> Result<SsaScenario, SsaError> {
    optical_geo_with(seed, &OpticalGeoConfig::PRESET)
}

/// `optical-geo` with other sizes.
///
/// # Errors
/// As [`radar_leo`].
pub fn optical_geo_with(seed: u64, config: &OpticalGeoConfig) -> Result<SsaScenario, SsaError> {
    let sensor = geo_telescope();
    let epoch_jd = parse_iso8601(GEO_EPOCH)?;
    let theta0 = earth_rotation_angle(epoch_jd, 0.0);
    let a = geo_radius();
    let mut objects = Vec::new();
    let mut groups = Vec::new();
    let state_at = |random: &mut Random, longitude: f64, e_max: f64, i_max: f64| {
        let e = random.between(0.0, e_max);
        let i = random.between(0.0, i_max);
        let raan = random.between(0.0, TAU);
        let argp = random.between(0.0, TAU);
        // Mean longitude Ω + ω + M = θ₀ + λ.
        let m = theta0 + longitude - raan - argp;
        kepler_state(a, e, i, raan, argp, m)
    };
    let mut random = Random::stream(seed, Stream::Orbit, 0);
    for _ in 0..config.singles {
        let longitude = sensor.site.longitude + deg(random.between(-2.0, 2.0));
        let s = state_at(&mut random, longitude, 2e-4, deg(0.1));
        objects.push(ObjectTruth::known(s, None));
    }
    for _ in 0..config.sweepers {
        let t_node = random.between(0.0, config.duration);
        let longitude = sensor.site.longitude + deg(random.between(-2.0, 2.0));
        let inclination = deg(random.between(10.0, 16.0));
        let at_node = aimed_circular(
            [earth_rotation_angle(epoch_jd, t_node) + longitude, 0.0],
            a,
            inclination,
            random.uniform() < 0.5,
        );
        let s = Propagator::EARTH.propagate(at_node, -t_node)?;
        objects.push(ObjectTruth::known(s, None));
    }
    for c in 0..config.clusters {
        let slot = sensor.site.longitude + deg(-1.5 + 1.5 * c as f64 + random.between(-0.3, 0.3));
        let mut members = Vec::new();
        for _ in 0..config.cluster_size {
            let longitude = slot + deg(random.between(-0.015, 0.015));
            members.push(objects.len());
            let s = state_at(&mut random, longitude, 8e-5, deg(0.01));
            objects.push(ObjectTruth::known(s, Some(groups.len())));
        }
        groups.push(Group { kind: "cluster".into(), objects: members });
    }
    if config.unknowns.breakup > 0 {
        return Err(SsaError::BadUnknowns);
    }
    let n = objects.len();
    mark_missing(seed, &mut objects, n, config.unknowns.missing_fraction)?;
    let steps = (config.duration / config.cadence).floor() as usize;
    simulate(Plan {
        name: "optical-geo".into(),
        seed,
        epoch: GEO_EPOCH.into(),
        duration: config.duration,
        sensors: vec![sensor],
        objects,
        groups,
        schedule: (0..=steps).map(|k| (k as f64 * config.cadence, 0)).collect(),
        tracks: None,
        visible: None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol
    }

    #[test]
    fn julian_date_and_gmst_known_values() {
        // J2000.0 = 2000-01-01 12:00 TT; as UTC it is the Julian date 2451545.0 by definition here.
        assert_eq!(parse_iso8601("2000-01-01T12:00:00Z").unwrap(), 2_451_545.0);
        assert_eq!(parse_iso8601("1992-08-20T12:14:00").unwrap(), julian_date(1992, 8, 20, 12, 14, 0.0));
        // GMST at J2000: 67310.54841 s = 280.46061837°.
        assert!(close(gmst(2_451_545.0).to_degrees(), 280.460_618_37, 1e-8));
        // Vallado, Fundamentals of Astrodynamics, example 3-5: 1992-08-20 12:14 UT1 -> 152.578 787 86°.
        let jd = julian_date(1992, 8, 20, 12, 14, 0.0);
        assert!(close(gmst(jd).to_degrees(), 152.578_787_86, 1e-6), "{}", gmst(jd).to_degrees());
        // One sidereal day later the angle is back.
        let sidereal_day = TAU / EARTH_ROTATION_RATE;
        assert!(close(earth_rotation_angle(jd, sidereal_day), gmst(jd), 1e-12));
        for bad in ["2026-13-01T00:00:00Z", "2026-02-29T00:00:00", "2026-01-01 00:00:00", "26-01-01T00:00:00", "x"] {
            assert_eq!(parse_iso8601(bad), Err(SsaError::BadEpoch), "{bad}");
        }
        assert!(parse_iso8601("2024-02-29T23:59:59.5Z").is_ok());
    }

    #[test]
    fn site_frames() {
        // lat 0 lon 0 at θ = 0: E = y, N = z, U = x; position on the x axis at the equatorial radius.
        let o = Site { latitude: 0.0, longitude: 0.0, height: 0.0 }.observer(0.0);
        for (v, w) in [(o.east, [0.0, 1.0, 0.0]), (o.north, [0.0, 0.0, 1.0]), (o.up, [1.0, 0.0, 0.0])] {
            assert!(v.iter().zip(w).all(|(a, b)| close(*a, b, 1e-15)), "{v:?}");
        }
        assert!(close(o.position[0], WGS84_A, 1e-9) && o.position[1] == 0.0);
        assert!(close(o.velocity[1], EARTH_ROTATION_RATE * WGS84_A, 1e-15));
        // θ = 90°: the same site looks along y; east is −x.
        let o = Site { latitude: 0.0, longitude: 0.0, height: 0.0 }.observer(FRAC_PI_2);
        assert!(close(o.up[1], 1.0, 1e-15) && close(o.east[0], -1.0, 1e-15));
        // The pole: the polar radius b = a (1 − f).
        let p = Site { latitude: FRAC_PI_2, longitude: 0.3, height: 1.0 }.earth_fixed();
        assert!(close(p[2], WGS84_A * (1.0 - WGS84_F) + 1.0, 1e-9) && p[0].abs() < 1e-9);
        // ENU orthonormal and right-handed at an arbitrary site and angle.
        let o = Site { latitude: deg(47.0), longitude: deg(-120.0), height: 0.3 }.observer(1.234);
        assert!(close(dot(o.east, o.north), 0.0, 1e-15) && close(dot(o.up, o.north), 0.0, 1e-15));
        let c = cross(o.east, o.north);
        assert!(c.iter().zip(o.up).all(|(a, b)| close(*a, b, 1e-15)));
    }

    #[test]
    fn radar_and_optical_hand_cases() {
        let site = Site { latitude: deg(40.0), longitude: deg(-75.0), height: 0.2 };
        let o = site.observer(0.7);
        // 800 km straight up: E = 90°, range 800 km.
        let r = add(o.position, scale(o.up, 800.0));
        let (rho, _, e) = o.range_az_el(r);
        assert!(close(rho, 800.0, 1e-9) && close(e, FRAC_PI_2, 1e-12));
        // Due north and 30° up: A = 0, E = 30°; due east on the horizon: A = 90°, E = 0; due west: −90°.
        let (_, a, e) = o.range_az_el(add(o.position, o.direction(0.0, deg(30.0))));
        assert!(close(a, 0.0, 1e-12) && close(e, deg(30.0), 1e-12));
        let (_, a, e) = o.range_az_el(add(o.position, scale(o.east, 500.0)));
        assert!(close(a, FRAC_PI_2, 1e-12) && close(e, 0.0, 1e-12));
        let (_, a, _) = o.range_az_el(add(o.position, scale(o.east, -500.0)));
        assert!(close(a, -FRAC_PI_2, 1e-12));
        // Due south: A = π exactly on the (−π, π] side.
        let (_, a, _) = o.range_az_el(add(o.position, scale(o.north, -500.0)));
        assert!(close(a.abs(), PI, 1e-12));
        // Range-rate: an object moving with the site has ρ̇ = 0; receding along the line of sight at
        // 1 km/s has ρ̇ = 1.
        let d = o.direction(0.4, 0.6);
        let p = add(o.position, scale(d, 1000.0));
        let still = [p[0], p[1], p[2], o.velocity[0], o.velocity[1], o.velocity[2]];
        assert!(close(o.radar(&still, true)[3], 0.0, 1e-15));
        let v = add(o.velocity, d);
        assert!(close(o.radar(&[p[0], p[1], p[2], v[0], v[1], v[2]], true)[3], 1.0, 1e-12));
        // Optical: an object along the site's +x offset has α = 0, δ = 0; along +z: δ = 90°.
        let [al, de] = o.optical(add(o.position, [1000.0, 0.0, 0.0]));
        assert!(close(al, 0.0, 1e-15) && close(de, 0.0, 1e-15));
        let [_, de] = o.optical(add(o.position, [0.0, 0.0, 5.0]));
        assert!(close(de, FRAC_PI_2, 1e-12));
        let [al, _] = o.optical(add(o.position, [-1.0, 1e-12, 0.0]));
        assert!(close(al, PI, 1e-9));
        // radec_direction inverts radec.
        let [al, de] = radec(radec_direction(-2.5, 0.3));
        assert!(close(al, -2.5, 1e-14) && close(de, 0.3, 1e-14));
    }

    #[test]
    fn wrap_into_half_open_interval() {
        assert_eq!(wrap_angle(PI), PI);
        assert_eq!(wrap_angle(-PI), PI);
        assert!(close(wrap_angle(3.0 * PI), PI, 1e-12));
        assert!(close(wrap_angle(PI + 0.1), -PI + 0.1, 1e-12));
        assert!(close(wrap_angle(-PI - 0.1), PI - 0.1, 1e-12));
        assert!(close(wrap_angle(0.3 - 4.0 * TAU), 0.3, 1e-12));
        for k in -1000..1000 {
            let w = wrap_angle(k as f64 * 0.0137);
            assert!(w > -PI && w <= PI);
        }
    }

    #[test]
    fn field_of_view_membership() {
        let cone = FieldOfView {
            shape: LookShape::Cone { azimuth: PI, elevation: deg(30.0), half_angle: deg(10.0) },
            min_elevation: deg(25.0),
            range: Some([100.0, 2000.0]),
        };
        assert!(cone.contains(-PI, deg(30.0), Some(500.0)));
        assert!(cone.contains(PI - deg(9.0), deg(30.0), Some(500.0))); // 9°·cos 30° from the boresight
        assert!(cone.contains(-PI + deg(11.0), deg(30.0), Some(500.0))); // 11°·cos 30° ≈ 9.5°
        assert!(!cone.contains(-PI + deg(12.0), deg(30.0), Some(500.0))); // ≈ 10.4°
        assert!(!cone.contains(PI, deg(24.0), Some(500.0))); // below the mask, inside the cone
        assert!(!cone.contains(PI, deg(30.0), Some(2001.0)));
        assert!(cone.contains(PI, deg(30.0), None));
        assert!(!cone.contains(PI, f64::NAN, None));
        let boxed = FieldOfView {
            shape: LookShape::Box {
                azimuth_centre: deg(170.0),
                azimuth_half_width: deg(20.0),
                elevation_min: deg(20.0),
                elevation_max: deg(60.0),
            },
            min_elevation: deg(10.0),
            range: None,
        };
        assert!(boxed.contains(deg(-175.0), deg(30.0), None)); // across ±π: 15° from the centre
        assert!(!boxed.contains(deg(-169.0), deg(30.0), None)); // 21°
        assert!(!boxed.contains(deg(170.0), deg(61.0), None));
        assert!(!boxed.contains(deg(170.0), deg(19.0), None));
    }

    fn radar_box_sensor() -> SensorSpec {
        SensorSpec {
            name: "r".into(),
            site: Site { latitude: deg(45.0), longitude: 0.1, height: 0.0 },
            kind: SensorKind::Radar,
            fov: FieldOfView {
                shape: LookShape::Box {
                    azimuth_centre: deg(175.0),
                    azimuth_half_width: deg(30.0),
                    elevation_min: deg(5.0),
                    elevation_max: deg(70.0),
                },
                min_elevation: deg(20.0),
                range: Some([300.0, 2500.0]),
            },
            sigma: vec![0.02, 1e-3, 1e-3],
            detection_probability: 0.9,
            clutter_rate: 3.0,
        }
    }

    #[test]
    fn clutter_volume_monte_carlo_matches_box_and_cone() {
        let mut random = Random::stream(3, Stream::Scenario, 0);
        let s = radar_box_sensor();
        let o = s.site.observer(0.2);
        // The box with the mask: Δρ · 2w · (E_max − max(E_min, mask)).
        let exact = 2200.0 * deg(60.0) * deg(50.0);
        let mc = s.fov_volume_monte_carlo(&o, 20_000, &mut random);
        assert!(close(mc, exact, 1e-9 * exact), "{mc} vs {exact}"); // the bounding box is the box
        // With range-rate the volume gains a factor 2 ρ̇_max.
        let mut rr = s.clone();
        rr.kind = SensorKind::RadarRangeRate { max_range_rate: 7.5 };
        rr.sigma.push(1e-3);
        let mc = rr.fov_volume_monte_carlo(&o, 1000, &mut random);
        assert!(close(mc, exact * 15.0, 1e-9 * exact), "{mc}");
        let z = rr.clutter_point(&o, &mut random).unwrap();
        assert!(z.len() == 4 && z[3].abs() <= 7.5);
        // A cone about the zenith region: its (A, E) area is 2π (E range) minus ...: compare with a
        // fine quadrature of the same membership test over (A, E).
        let mut c = s.clone();
        c.fov.shape = LookShape::Cone { azimuth: 0.5, elevation: deg(60.0), half_angle: deg(20.0) };
        let mc = c.fov_volume_monte_carlo(&o, 200_000, &mut random);
        let n = 1000;
        let mut area = 0.0;
        for i in 0..n {
            for j in 0..n {
                let a = -PI + TAU * (i as f64 + 0.5) / n as f64;
                let e = FRAC_PI_2 * (j as f64 + 0.5) / n as f64;
                area += f64::from(u8::from(c.fov.contains(a, e, None))) * (TAU / n as f64) * (FRAC_PI_2 / n as f64);
            }
        }
        let quad = 2200.0 * area;
        assert!(close(mc, quad, 0.02 * quad), "{mc} vs {quad}");
        // Optical cone: the (α, δ) area of a small cone at declination δ₀ is ≈ π h² / cos δ₀.
        let mut t = geo_telescope();
        t.fov.min_elevation = 0.0;
        let o = t.site.observer(1.0);
        let LookShape::Cone { azimuth, elevation, half_angle } = t.fov.shape else { unreachable!() };
        let [_, d0] = radec(o.direction(azimuth, elevation));
        let expected = PI * half_angle * half_angle / d0.cos();
        let mc = t.fov_volume_monte_carlo(&o, 200_000, &mut random);
        assert!(close(mc, expected, 0.02 * expected), "{mc} vs {expected}");
    }

    #[test]
    fn clutter_is_inside_and_uniform() {
        let mut random = Random::stream(4, Stream::Clutter, 0);
        let s = radar_box_sensor();
        let o = s.site.observer(0.0);
        let points: Vec<Vec<f64>> = (0..4000).map(|_| s.clutter_point(&o, &mut random).unwrap()).collect();
        assert!(points.iter().all(|z| s.contains_measurement(&o, z)));
        // Uniform in range: the mean is the window's centre (σ of the mean ≈ 635/√4000 ≈ 10 km).
        let mean = points.iter().map(|z| z[0]).sum::<f64>() / points.len() as f64;
        assert!(close(mean, 1400.0, 40.0), "{mean}");
        // Uniform in elevation over [20°, 70°] (the mask cuts the box): mean 45°.
        let mean_e = points.iter().map(|z| z[2]).sum::<f64>() / points.len() as f64;
        assert!(close(mean_e, deg(45.0), deg(1.0)), "{}", mean_e.to_degrees());
        // Azimuths wrap across ±π.
        assert!(points.iter().any(|z| z[1] < 0.0) && points.iter().any(|z| z[1] > 0.0));
        // Optical clutter lands in the telescope's cone when turned back into look angles.
        let t = geo_telescope();
        let o = t.site.observer(2.0);
        for _ in 0..200 {
            let z = t.clutter_point(&o, &mut random).unwrap();
            let (a, e) = o.look(radec_direction(z[0], z[1]));
            assert!(t.fov.contains(a, e, None));
        }
        // A field of view of zero volume is reported, not looped on.
        let mut empty = radar_box_sensor();
        empty.fov.min_elevation = deg(80.0);
        assert_eq!(empty.clutter_point(&o, &mut random), Err(SsaError::EmptyFieldOfView));
    }

    #[test]
    fn noisy_zenith_elevation_is_reflected() {
        let mut s = radar_box_sensor();
        s.sigma = vec![0.0, 0.0, deg(1.0)];
        let o = s.site.observer(0.0);
        let p = add(o.position, scale(add(o.up, scale(o.north, 1e-6)), 700.0));
        let state = [p[0], p[1], p[2], 0.0, 0.0, 0.0];
        let mut random = Random::stream(1, Stream::Detection, 0);
        let mut flipped = 0;
        for _ in 0..200 {
            let z = s.noisy(&o, &state, &mut random);
            assert!(z[2] <= FRAC_PI_2 && z[1] > -PI && z[1] <= PI);
            flipped += usize::from(z[1].abs() > FRAC_PI_2);
        }
        assert!(flipped > 50 && flipped < 150, "{flipped}");
    }

    /// A short radar-leo (debug-friendly); the full preset is checked by the ignored test below.
    const SHORT_LEO: RadarLeoConfig = RadarLeoConfig {
        singles: 12,
        pairs: 3,
        duration: 3.0 * 3600.0,
        revisit: 40.0,
        min_passes: 2,
        unknowns: Unknowns { missing_fraction: 0.0, breakup: 0 },
    };

    #[test]
    fn missing_objects_and_a_breakup_are_unknown_to_the_prior() {
        let config = RadarLeoConfig { unknowns: Unknowns { missing_fraction: 0.25, breakup: 10 }, ..SHORT_LEO };
        let a = radar_leo_with(3, &config).unwrap();
        assert_eq!(a, radar_leo_with(3, &config).unwrap(), "deterministic");
        let n = SHORT_LEO.singles + 2 * SHORT_LEO.pairs;
        assert_eq!(a.objects.len(), n + 10);
        // The other objects are those of the preset without unknowns.
        let plain = radar_leo_with(3, &SHORT_LEO).unwrap();
        let initial = |s: &SsaScenario| s.objects[..n].iter().map(|o| o.initial_state).collect::<Vec<_>>();
        assert_eq!(initial(&a), initial(&plain));
        assert!(plain.objects.iter().all(|o| o.in_prior && o.birth_time.is_none()));
        let missing = a.objects[..n].iter().filter(|o| !o.in_prior).count();
        assert_eq!(missing, 5, "round(0.25 × 18)");
        assert!(a.objects[..n].iter().all(|o| o.birth_time.is_none()));
        // Fragments: born together, unknown, in the break-up group with the parent.
        let fragments = &a.objects[n..];
        let born = fragments[0].birth_time.expect("a birth time");
        assert!(born > 0.0 && born < SHORT_LEO.duration, "{born}");
        let group = fragments[0].group.expect("a group");
        assert_eq!(a.groups[group].kind, "breakup");
        assert_eq!(a.groups[group].objects.len(), 11);
        let parent = a.groups[group].objects[0];
        assert!(parent < SHORT_LEO.singles);
        let at = Propagator::EARTH.propagate(a.objects[parent].initial_state, born).unwrap();
        for f in fragments {
            assert!(!f.in_prior && f.birth_time == Some(born) && f.group == Some(group));
            // At the break-up: the parent's position, a kick of 2 to 30 m/s.
            let s = Propagator::EARTH.propagate(f.initial_state, born).unwrap();
            assert!(norm(sub(pos(&s), pos(&at))) < 1e-3, "{:?} {:?}", s, at);
            let kick = norm(sub(vel(&s), vel(&at)));
            assert!((0.002 - 1e-6..=0.030 + 1e-6).contains(&kick), "{kick}");
        }
        // Seen only after the break-up, and seen.
        let seen: Vec<f64> = a.scans.iter().filter(|s| s.truth.iter().any(|t| t.object >= n)).map(|s| s.time).collect();
        assert!(!seen.is_empty() && seen.iter().all(|&t| t >= born), "{seen:?}");
        // Another seed, other choices.
        let b = radar_leo_with(4, &config).unwrap();
        assert_ne!(
            a.objects.iter().map(|o| o.in_prior).collect::<Vec<_>>(),
            b.objects.iter().map(|o| o.in_prior).collect::<Vec<_>>()
        );
        // The scenario file: the truth says who is unknown, the prior leaves them out, fragments appear
        // in the truth from their birth.
        let (file, _) = crate::scenario::from_simulation::to_scenario(&a).unwrap();
        let truth = file.truth.as_ref().unwrap();
        assert_eq!(truth.objects.iter().filter(|o| !o.in_prior).count(), 15);
        assert_eq!(file.prior.hypotheses[0].objects.len(), n - 5);
        for (scan, objects) in file.scans.iter().zip(&truth.scans) {
            let fragments = objects.objects.iter().filter(|o| o.id >= n as u64).count();
            assert_eq!(fragments, if scan.time >= born { 10 } else { 0 }, "t = {}", scan.time);
        }
    }

    #[test]
    fn unknowns_out_of_range_are_refused() {
        let bad = |missing_fraction, breakup| Unknowns { missing_fraction, breakup };
        let leo = |u| radar_leo_with(1, &RadarLeoConfig { unknowns: u, ..SHORT_LEO });
        assert_eq!(leo(bad(1.5, 0)).err(), Some(SsaError::BadUnknowns));
        assert_eq!(leo(bad(f64::NAN, 0)).err(), Some(SsaError::BadUnknowns));
        let geo = OpticalGeoConfig { unknowns: bad(0.0, 2), ..OpticalGeoConfig::PRESET };
        assert_eq!(optical_geo_with(1, &geo).err(), Some(SsaError::BadUnknowns));
    }

    fn check_radar_leo(s: &SsaScenario, config: &RadarLeoConfig) {
        assert_eq!(s.objects.len(), config.singles + 2 * config.pairs);
        assert_eq!(s.sensors.len(), 2);
        // Sites 1000–3000 km apart.
        let gap = norm(sub(s.sensors[0].site.earth_fixed(), s.sensors[1].site.earth_fixed()));
        assert!((1000.0..3000.0).contains(&gap), "{gap}");
        let passes = s.passes();
        assert!(passes.iter().all(|&p| p >= config.min_passes), "{passes:?}");
        let stats = s.stats();
        assert!(stats.max_measurements <= MAX_MEASUREMENTS);
        // Both radars see objects.
        for sensor in 0..2 {
            assert!(s.scans.iter().any(|scan| scan.sensor == sensor && !scan.truth.is_empty()));
        }
        // Every crossing pair comes within 0.2° (≈ 7 σ of the angles) in some scan seeing both.
        assert_eq!(s.groups.len(), config.pairs);
        for (g, (closest, _)) in s.groups.iter().zip(s.group_separations()) {
            assert_eq!((g.kind.as_str(), g.objects.len()), ("crossing-pair", 2));
            assert!(closest <= deg(0.2), "pair {:?}: {}°", g.objects, closest.to_degrees());
        }
        // Detections are the noisy images of the truth they are attributed to; range and elevation
        // residuals have the sensors' σ (20 m, 0.03°) within 10 %.
        let (mut n, mut range_sq, mut elevation_sq) = (0.0, 0.0, 0.0);
        for scan in &s.scans {
            let o = s.observer(scan);
            for t in &scan.truth {
                if let Some(j) = t.measurement {
                    let z = &scan.measurements[j];
                    let h = s.sensors[scan.sensor].measure(&o, &t.state);
                    assert!(close(z[0], h[0], 0.2) && close(wrap_angle(z[1] - h[1]), 0.0, deg(0.3)));
                    n += 1.0;
                    range_sq += (z[0] - h[0]).powi(2);
                    elevation_sq += (z[2] - h[2]).powi(2);
                }
            }
        }
        let (range_rms, elevation_rms) = ((range_sq / n).sqrt(), (elevation_sq / n).sqrt().to_degrees());
        assert!(close(range_rms, 0.020, 0.002) && close(elevation_rms, 0.03, 0.003), "{range_rms} {elevation_rms}");
        // The stored truth is what re-propagating the initial states gives, for in-view scans.
        for i in [0, s.objects.len() - 1] {
            let states = s.object_states(i).unwrap();
            for (scan, x) in s.scans.iter().zip(&states) {
                if let Some(t) = scan.truth.iter().find(|t| t.object == i) {
                    assert_eq!(&t.state, x);
                }
            }
        }
    }

    #[test]
    fn radar_leo_short_properties_and_determinism() {
        let a = radar_leo_with(7, &SHORT_LEO).unwrap();
        check_radar_leo(&a, &SHORT_LEO);
        let b = radar_leo_with(7, &SHORT_LEO).unwrap();
        assert_eq!(a, b);
        let c = radar_leo_with(8, &SHORT_LEO).unwrap();
        assert_ne!(a.objects, c.objects);
        // Serde round trip.
        let json = serde_json::to_string(&a).unwrap();
        let back: SsaScenario = serde_json::from_str(&json).unwrap();
        assert_eq!(a, back);
    }

    #[test]
    #[ignore = "full preset: run with --release -- --ignored"]
    fn radar_leo_full_preset() {
        for seed in 1..=5 {
            let s = radar_leo(seed).unwrap();
            check_radar_leo(&s, &RadarLeoConfig::PRESET);
            assert!(s.objects.len() >= 100);
        }
    }

    fn check_optical_geo(s: &SsaScenario, config: &OpticalGeoConfig) {
        let kept = config.singles + config.clusters * config.cluster_size;
        assert_eq!(s.objects.len(), kept + config.sweepers);
        assert!(s.stats().max_measurements <= MAX_MEASUREMENTS);
        // Station-kept objects (singles, then sweepers, then clusters) are in view in every frame.
        let kept_ids: Vec<usize> =
            (0..config.singles).chain(config.singles + config.sweepers..s.objects.len()).collect();
        for scan in &s.scans {
            assert!(kept_ids.iter().all(|i| scan.truth.iter().any(|t| t.object == *i)));
        }
        // Every sweeper is seen, and leaves or enters the field during the run.
        for i in config.singles..config.singles + config.sweepers {
            let frames = s.scans.iter().filter(|scan| scan.truth.iter().any(|t| t.object == i)).count();
            assert!(frames > 0, "sweeper {i} never in view");
            if config.duration >= 3.0 * 3600.0 {
                assert!(frames < s.scans.len(), "sweeper {i} in view all the time");
            }
        }
        // Clusters stay within 0.1° as seen from the telescope (all members are in every frame).
        assert_eq!(s.groups.len(), config.clusters);
        for (g, (_, widest)) in s.groups.iter().zip(s.group_separations()) {
            assert_eq!((g.kind.as_str(), g.objects.len()), ("cluster", config.cluster_size));
            assert!(widest < deg(0.1), "cluster {:?}: {}°", g.objects, widest.to_degrees());
        }
    }

    #[test]
    fn optical_geo_short_properties_and_determinism() {
        let config = OpticalGeoConfig {
            singles: 6,
            sweepers: 4,
            clusters: 2,
            cluster_size: 4,
            duration: 3600.0,
            cadence: 120.0,
            unknowns: Unknowns::default(),
        };
        let a = optical_geo_with(5, &config).unwrap();
        check_optical_geo(&a, &config);
        assert_eq!(a, optical_geo_with(5, &config).unwrap());
        // A quarter missing from the prior: round(0.25 × 18) objects, the same orbits.
        let missing = OpticalGeoConfig { unknowns: Unknowns { missing_fraction: 0.25, breakup: 0 }, ..config };
        let m = optical_geo_with(5, &missing).unwrap();
        assert_eq!(m.objects.iter().filter(|o| !o.in_prior).count(), 5);
        assert_eq!(
            m.objects.iter().map(|o| o.initial_state).collect::<Vec<_>>(),
            a.objects.iter().map(|o| o.initial_state).collect::<Vec<_>>()
        );
        assert!(m.objects.iter().all(|o| o.birth_time.is_none()));
        // Measurement noise about 1.5″: residuals of detections.
        let mut sq = 0.0;
        let mut n = 0.0;
        for scan in &a.scans {
            let o = a.observer(scan);
            for t in &scan.truth {
                if let Some(j) = t.measurement {
                    let h = o.optical(pos(&t.state));
                    sq += wrap_angle(scan.measurements[j][1] - h[1]).powi(2);
                    n += 1.0;
                }
            }
        }
        let rms = (sq / n).sqrt().to_degrees() * 3600.0;
        assert!(close(rms, 1.5, 0.2), "{rms}″");
    }

    #[test]
    #[ignore = "full preset: run with --release -- --ignored"]
    fn optical_geo_full_preset() {
        for seed in 1..=10 {
            let s = optical_geo(seed).unwrap();
            check_optical_geo(&s, &OpticalGeoConfig::PRESET);
            assert!(s.objects.len() >= 30);
        }
    }

    #[test]
    fn tiny_3d_is_small_and_seen() {
        let s = tiny_3d(3).unwrap();
        assert_eq!((s.objects.len(), s.scans.len(), s.sensors.len()), (3, 11, 1));
        for i in 0..3 {
            assert!(s.scans.iter().filter(|scan| scan.truth.iter().any(|t| t.object == i)).count() >= 5, "{i}");
        }
        assert_eq!(s, tiny_3d(3).unwrap());
    }

    #[test]
    fn kepler_state_is_consistent() {
        // Circular: |r| = a, |v| = √(μ/a), r ⊥ v; eccentric: vis-viva.
        let s = kepler_state(7000.0, 0.0, 0.9, 0.3, 0.0, 1.1);
        assert!(close(norm(pos(&s)), 7000.0, 1e-9) && close(norm(vel(&s)), (MU / 7000.0).sqrt(), 1e-12));
        assert!(close(dot(pos(&s), vel(&s)), 0.0, 1e-9));
        let s = kepler_state(9000.0, 0.2, 0.5, 1.0, 2.0, 0.7);
        let (r, v) = (norm(pos(&s)), norm(vel(&s)));
        assert!(close(v * v, MU * (2.0 / r - 1.0 / 9000.0), 1e-9));
        // Angular momentum along (sin i sin Ω, −sin i cos Ω, cos i).
        let h = cross(pos(&s), vel(&s));
        let hn = scale(h, 1.0 / norm(h));
        assert!(close(hn[2], 0.5f64.cos(), 1e-12) && close(hn[0], 0.5f64.sin() * 1.0f64.sin(), 1e-12));
        // An aimed orbit passes through its aim direction.
        let aim = [1.0, deg(40.0)];
        let s = aimed_circular(aim, 7000.0, deg(60.0), false);
        assert!(angle_between(pos(&s), radec_direction(aim[0], aim[1])) < 1e-12);
    }
}
