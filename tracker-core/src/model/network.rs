//! Sensor networks: several sensors of one measurement type (radars, or telescopes) on ground sites or
//! spacecraft, each with its own noise, field of view, p_D and clutter, placed at every scan
//! (docs/maths.md §6.9).
//!
//! A scan names its sensor and, for a spacecraft, passes the observer's inertial state
//! ([`ScanGeometry`]). [`SensorNetwork::place`](crate::Placement::place) turns that into the
//! measurement model of the scan: the observer's inertial position and velocity, and the sensor's frame
//! (East, North, Up of a ground site at the scan's Earth rotation angle; the inertial axes, arranged so that
//! azimuth is right ascension and elevation declination, for a spacecraft). A ground site's Earth rotation
//! angle is computed in `f64` from the scan time and cast once, so an `f32` tracker loses no precision to a
//! large time.
//!
//! The clutter volume of each sensor's field of view in measurement coordinates is computed once, when
//! the network is built (the quadrature of the model's [`Placeable::density`], see [`crate::sensor::LookShape::area`]): Earth rotation
//! turns a ground site's frame about the pole, which leaves the density unchanged.

use super::light_time::{self, LightTime};
use super::{
    AdmissibleRegion, Attributable, BirthComponent, BirthError, BirthGeometry, Measure, OpticalRaDec, RadarRangeAzEl,
    RadarRangeRate, SkyPoint,
};
use crate::real::{Real, c, cos, sin, sqrt};
use crate::sensor::frames::{EarthRotation, look_angles, wrap_angle};
use crate::sensor::{
    EARTH_ROTATION_RATE, Look, LookAxes, MAX_OBSERVER_DISTANCE, Placement, PlacementError, Platform, Region,
    ScanGeometry, Sensor, SiteSensor, WGS84_FLATTENING,
};
use nalgebra::{SMatrix, SVector};

/// A measurement model that a [`SensorNetwork`] places at each scan: built from the observer's inertial
/// state, the sensor's frame (rows: East, North, Up in inertial coordinates) and the noise.
pub trait Placeable<T: Real, const D: usize>: Measure<T, 6, D> + BirthGeometry<T, 6, D> + Copy {
    /// The coordinates besides the angles.
    const AXES: LookAxes;

    /// A model with every number zero: what [`SensorNetwork::unconfigured`] holds before any sensor.
    const UNPLACED: Self;

    /// The model for one scan.
    fn placed(observer: [T; 6], frame: [[T; 3]; 3], sigma: [T; D]) -> Self;

    /// Measurement `z` as a look direction in `frame`; `None` when its angles are outside their ranges.
    fn look_in(frame: &[[T; 3]; 3], z: &SVector<T, D>) -> Option<Look<T>>;

    /// |∂(measured angles)/∂(azimuth, elevation)| at a look direction: the factor that turns an area in
    /// look angles into one in measurement coordinates. `frame_z` holds the inertial z components of the
    /// frame's rows. The default, 1, is right when the measured angles are the look angles.
    fn density(_frame_z: [T; 3], _azimuth: T, _elevation: T) -> T {
        T::one()
    }
}

impl<T: Real> Placeable<T, 3> for RadarRangeAzEl<T> {
    const AXES: LookAxes = LookAxes { range: true, range_rate: false };
    const UNPLACED: Self = Self { observer: [T::ZERO; 6], enu: [[T::ZERO; 3]; 3], sigma: [T::ZERO; 3] };

    fn placed(observer: [T; 6], frame: [[T; 3]; 3], sigma: [T; 3]) -> Self {
        Self { observer, enu: frame, sigma }
    }

    fn look_in(_frame: &[[T; 3]; 3], z: &SVector<T, 3>) -> Option<Look<T>> {
        Some(Look { azimuth: z[1], elevation: z[2], range: Some(z[0]), range_rate: None })
    }
}

impl<T: Real> Placeable<T, 4> for RadarRangeRate<T> {
    const AXES: LookAxes = LookAxes { range: true, range_rate: true };
    const UNPLACED: Self = Self { observer: [T::ZERO; 6], enu: [[T::ZERO; 3]; 3], sigma: [T::ZERO; 4] };

    fn placed(observer: [T; 6], frame: [[T; 3]; 3], sigma: [T; 4]) -> Self {
        Self { observer, enu: frame, sigma }
    }

    fn look_in(_frame: &[[T; 3]; 3], z: &SVector<T, 4>) -> Option<Look<T>> {
        Some(Look { azimuth: z[1], elevation: z[2], range: Some(z[0]), range_rate: Some(z[3]) })
    }
}

impl<T: Real> Placeable<T, 2> for OpticalRaDec<T> {
    const AXES: LookAxes = LookAxes { range: false, range_rate: false };
    const UNPLACED: Self = Self { observer: [T::ZERO; 6], sigma: [T::ZERO; 2] };

    fn placed(observer: [T; 6], _frame: [[T; 3]; 3], sigma: [T; 2]) -> Self {
        Self { observer, sigma }
    }

    fn look_in(frame: &[[T; 3]; 3], z: &SVector<T, 2>) -> Option<Look<T>> {
        // The inertial unit vector of (α, δ), then its components along the frame's rows.
        let (alpha, delta) = (z[0], z[1]);
        let half_pi = T::frac_pi_2();
        if !(alpha >= -T::pi() && alpha <= T::pi() && delta >= -half_pi && delta <= half_pi) {
            return None;
        }
        let unit = [cos(delta) * cos(alpha), cos(delta) * sin(alpha), sin(delta)];
        let along = |row: &[T; 3]| row[0] * unit[0] + row[1] * unit[1] + row[2] * unit[2];
        let (_, azimuth, elevation, _) = look_angles([along(&frame[0]), along(&frame[1]), along(&frame[2])]);
        Some(Look { azimuth, elevation, range: None, range_rate: None })
    }

    /// dα dδ = dΩ / cos δ and dA dE = dΩ / cos E, so the factor is cos E / cos δ, with
    /// sin δ the inertial z component of the look direction.
    fn density(frame_z: [T; 3], azimuth: T, elevation: T) -> T {
        let sin_delta = frame_z[0] * sin(azimuth) * cos(elevation)
            + frame_z[1] * cos(azimuth) * cos(elevation)
            + frame_z[2] * sin(elevation);
        cos(elevation) / sqrt(T::one() - sin_delta * sin_delta)
    }
}

/// Azimuth samples per elevation row of the clutter-volume quadrature when the density varies with
/// azimuth.
const AZIMUTH_POINTS: usize = 64;

/// Up to `C` sensors of one measurement type `X` (`D` components), for a 6-state inertial motion model.
///
/// # Examples
/// Two radars; a scan of the second one, 100 s after the epoch.
/// ```
/// use tracker_core::model::{RadarRangeAzEl, SensorNetwork};
/// use tracker_core::sensor::{EarthRotation, GroundSite, Placement, Platform, ScanGeometry, SiteSensor};
/// use tracker_core::sensor::{LookShape, Region, Sensor};
/// let field_of_view = Region::Look {
///     shape: LookShape::Cone { azimuth: 0.0, elevation: 1.0, half_angle: 0.6 },
///     min_elevation: 0.2,
///     range: Some([200.0, 3000.0]),
///     range_rate: None,
/// };
/// let detection = Sensor { detection_probability: 0.9, clutter_rate: 2.0, field_of_view };
/// let radar = |latitude: f64, longitude: f64| SiteSensor {
///     platform: Platform::Ground(GroundSite { latitude, longitude, height: 0.1 }),
///     sigma: [0.02, 5e-4, 5e-4],
///     detection,
/// };
/// let network: SensorNetwork<f64, RadarRangeAzEl<f64>, 3, 4> =
///     SensorNetwork::new(EarthRotation::new(0.0), &[radar(0.7, 0.1), radar(0.5, -0.3)])?;
/// assert_eq!(network.sensor_count(), 2);
/// let placed = network.place(&ScanGeometry { sensor: 1, time: 100.0, observer: None })?;
/// assert_eq!(placed.detection(), Some(detection));
/// assert!(network.place(&ScanGeometry { sensor: 2, time: 100.0, observer: None }).is_err());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SensorNetwork<T, X, const D: usize, const C: usize> {
    rotation: EarthRotation<T>,
    sensors: [SiteSensor<T, D>; C],
    volumes: [T; C],
    count: usize,
    current: usize,
    frame: [[T; 3]; 3],
    placed: X,
    /// Per sensor, how light time delays its measurements (all [`LightTime::Off`] unless set).
    light_time: [LightTime; C],
    /// The observer's inertial state at the current placement (for light time).
    observer: [T; 6],
}

/// The spacecraft frame: rows "East" = ŷ, "North" = x̂, "Up" = ẑ, so that azimuth is right ascension and
/// elevation declination.
pub(super) fn inertial_frame<T: Real>() -> [[T; 3]; 3] {
    let (o, l) = (T::zero(), T::one());
    [[o, l, o], [l, o, o], [o, o, l]]
}

impl<T: Real, X: Placeable<T, D>, const D: usize, const C: usize> SensorNetwork<T, X, D, C> {
    /// A network with no sensors, built in a `const` context: the measurement model of a placeholder
    /// configuration, so that a tracker can be a compile-time `static` ([`crate::Tracker::empty`]) whose
    /// run-time configuration is installed in place by [`crate::Tracker::reset_with`]. A tracker refuses
    /// it ([`crate::ConfigError::Sensor`]) and every scan of it fails with an unknown sensor.
    pub const fn unconfigured() -> Self {
        let sensor =
            SiteSensor { platform: Platform::Spacecraft, sigma: [T::ZERO; D], detection: Sensor::UNCONFIGURED };
        Self {
            rotation: EarthRotation { angle_at_epoch: T::ZERO, rate: T::ZERO },
            sensors: [sensor; C],
            volumes: [T::ZERO; C],
            count: 0,
            current: 0,
            frame: [[T::ZERO; 3]; 3],
            placed: X::UNPLACED,
            light_time: [LightTime::Off; C],
            observer: [T::ZERO; 6],
        }
    }

    /// A network of `sensors`, placed at the first one at time 0.
    ///
    /// # Errors
    /// A static description of the first invalid part: more sensors than `C`, none, a site outside
    /// latitude [−π/2, π/2] or below 1 km under the ellipsoid, a non-positive noise, a detection model
    /// that is not a valid look-angle field of view for `X`, or a clutter volume that is not finite.
    pub fn new(rotation: EarthRotation<T>, sensors: &[SiteSensor<T, D>]) -> Result<Self, &'static str> {
        const { assert!(C > 0, "a sensor network needs room for one sensor") };
        let first = first_of_network(&rotation, sensors, C)?;
        let mut network = Self {
            rotation,
            sensors: [*first; C],
            volumes: [T::one(); C],
            count: sensors.len(),
            current: 0,
            frame: inertial_frame(),
            placed: X::placed([T::zero(); 6], inertial_frame(), first.sigma),
            light_time: [LightTime::Off; C],
            observer: [T::zero(); 6],
        };
        for (index, sensor) in sensors.iter().enumerate() {
            check_sensor(sensor)?;
            let frame = match sensor.platform {
                Platform::Ground(site) => site.enu(&rotation, T::zero()),
                Platform::Spacecraft => inertial_frame(),
            };
            let volume = angular_volume::<T, X, D>(&sensor.detection.field_of_view, &frame);
            // p_D, clutter, the look region (windows as the model measures) and the clutter volume.
            sensor.detection.validate_parts(D, Some(X::AXES), volume)?;
            if let (Some(slot), Some(volume_slot)) = (network.sensors.get_mut(index), network.volumes.get_mut(index)) {
                *slot = *sensor;
                *volume_slot = volume;
            }
        }
        if let Ok(placed) = network.place_at(0, 0.0, None) {
            network = placed;
        }
        Ok(network)
    }

    /// The sensors.
    pub fn sensors(&self) -> &[SiteSensor<T, D>] {
        self.sensors.get(..self.count).unwrap_or(&[])
    }

    /// The sensor the network is placed at.
    pub fn current_sensor(&self) -> usize {
        self.current
    }

    /// The clutter volume of sensor `index`'s field of view in measurement coordinates.
    pub fn volume(&self, index: usize) -> Option<T> {
        self.volumes.get(..self.count).and_then(|volumes| volumes.get(index)).copied()
    }

    /// The model of the current placement.
    pub fn placed(&self) -> &X {
        &self.placed
    }

    fn place_at(&self, sensor: usize, time: f64, observer: Option<[T; 6]>) -> Result<Self, PlacementError> {
        let Some(site) = self.sensors().get(sensor) else {
            return Err(PlacementError::UnknownSensor { sensor, sensors: self.count });
        };
        let (state, frame) = observer_and_frame(&self.rotation, site.platform, time, observer)?;
        Ok(Self { current: sensor, frame, placed: X::placed(state, frame, site.sigma), observer: state, ..*self })
    }

    /// The network with sensor `index`'s measurements delayed by light time `mode`
    /// ([`super::light_time`]; docs/maths.md §6.12). Every sensor starts [`LightTime::Off`], which measures
    /// exactly as a network without the setting.
    ///
    /// # Errors
    /// An unknown sensor, or a two-way mode for a model without a range.
    pub fn with_light_time(mut self, index: usize, mode: LightTime) -> Result<Self, &'static str> {
        if mode.two_way() && !X::AXES.range {
            return Err("sensor network: two-way light time needs a range measurement");
        }
        match self.light_time.get_mut(..self.count).and_then(|modes| modes.get_mut(index)) {
            Some(slot) => *slot = mode,
            None => return Err("sensor network: light time for an unknown sensor"),
        }
        Ok(self)
    }

    /// The light time of sensor `index` ([`LightTime::Off`] for an unknown one).
    pub fn light_time(&self, index: usize) -> LightTime {
        self.light_time.get(..self.count).and_then(|modes| modes.get(index)).copied().unwrap_or_default()
    }
}

/// Where a sensor on `platform` is at scan `time` and how its frame lies: the observer's inertial state
/// and the frame's rows (East, North, Up of a ground site at the scan's Earth rotation angle; the inertial
/// frame of [`inertial_frame`] for a spacecraft, whose state the scan passes as `observer`).
pub(super) fn observer_and_frame<T: Real>(
    rotation: &EarthRotation<T>,
    platform: Platform<T>,
    time: f64,
    observer: Option<[T; 6]>,
) -> Result<([T; 6], [[T; 3]; 3]), PlacementError> {
    match (platform, observer) {
        (Platform::Ground(_), Some(_)) => Err(PlacementError::UnexpectedObserver),
        (Platform::Spacecraft, None) => Err(PlacementError::MissingObserver),
        (Platform::Ground(ground), None) => {
            // The rotation angle in f64 from the f64 scan time, then one cast.
            // The nominal rate at f64 precision: its f32 rounding alone (3e-8 relative) would move a site
            // by 13 m after ten days.
            let nominal = rotation.rate == T::of_f64(EARTH_ROTATION_RATE);
            let rate = if nominal { EARTH_ROTATION_RATE } else { rotation.rate.as_f64() };
            let angle = rotation.angle_at_epoch.as_f64() + rate * time;
            let at = EarthRotation { angle_at_epoch: T::of_f64(wrap_angle(angle)), rate: rotation.rate };
            Ok((ground.observer(&at, T::zero()), ground.enu(&at, T::zero())))
        }
        (Platform::Spacecraft, Some(state)) => {
            if !state.iter().all(|v| v.is_finite_value()) {
                return Err(PlacementError::NonFiniteObserver);
            }
            if inside_earth(&state) {
                return Err(PlacementError::ObserverInsideEarth);
            }
            if beyond_plausible_distance(&state) {
                return Err(PlacementError::ObserverTooFar);
            }
            Ok((state, inertial_frame()))
        }
    }
}

/// The checks every network's constructor starts with: at least one sensor, at most `capacity`, a finite
/// Earth rotation; returns the first sensor.
pub(super) fn first_of_network<'a, T: Real, S>(
    rotation: &EarthRotation<T>,
    sensors: &'a [S],
    capacity: usize,
) -> Result<&'a S, &'static str> {
    let Some(first) = sensors.first() else {
        return Err("sensor network: no sensors");
    };
    if sensors.len() > capacity {
        return Err("sensor network: more sensors than its capacity C");
    }
    if !(rotation.angle_at_epoch.is_finite_value() && rotation.rate.is_finite_value()) {
        return Err("sensor network: Earth rotation angle and rate must be finite");
    }
    Ok(first)
}

/// Whether an inertial position lies inside the WGS-84 ellipsoid (x² + y²) / a² + z² / b² < 1.
fn inside_earth<T: Real>(state: &[T; 6]) -> bool {
    let a = super::EARTH_RADIUS;
    let b = a * (1.0 - WGS84_FLATTENING);
    let [x, y, z, ..] = state.map(T::as_f64);
    (x * x + y * y) / (a * a) + z * z / (b * b) < 1.0
}

/// Whether an inertial position is farther from the Earth's centre than [`MAX_OBSERVER_DISTANCE`].
fn beyond_plausible_distance<T: Real>(state: &[T; 6]) -> bool {
    let [x, y, z, ..] = state.map(T::as_f64);
    x * x + y * y + z * z > MAX_OBSERVER_DISTANCE * MAX_OBSERVER_DISTANCE
}

fn check_sensor<T: Real, const D: usize>(sensor: &SiteSensor<T, D>) -> Result<(), &'static str> {
    check_platform(sensor)?;
    if !sensor.sigma.iter().all(|&s| s.is_finite_value() && s > T::zero()) {
        return Err("sensor network: every noise standard deviation must be finite and > 0");
    }
    Ok(())
}

/// The checks of a sensor besides its noise: a ground site on the ellipsoid, a look-angle field of view.
pub(super) fn check_platform<T: Real, const D: usize>(sensor: &SiteSensor<T, D>) -> Result<(), &'static str> {
    if let Platform::Ground(site) = sensor.platform {
        let half_pi = T::frac_pi_2();
        if !(site.latitude.is_finite_value() && site.latitude >= -half_pi && site.latitude <= half_pi) {
            return Err("sensor network: site latitude must be in [-pi/2, pi/2]");
        }
        if !site.longitude.is_finite_value() {
            return Err("sensor network: site longitude must be finite");
        }
        // Below −1 km the site is inside the Earth; above 100 km it is no ground site.
        if !(site.height.is_finite_value() && site.height >= c(-1.0) && site.height <= c(100.0)) {
            return Err("sensor network: site height must be in [-1, 100] km (a ground site on the ellipsoid)");
        }
    }
    if !matches!(sensor.detection.field_of_view, Region::Look { .. }) {
        return Err("sensor network: a sensor's field of view must be a look-angle region");
    }
    Ok(())
}

/// The clutter volume of a look-angle `region` for measurements of `X` seen in `frame`.
pub(super) fn angular_volume<T: Real, X: Placeable<T, D>, const D: usize>(
    region: &Region<T>,
    frame: &[[T; 3]; 3],
) -> T {
    let Region::Look { shape, min_elevation, range, range_rate } = *region else {
        return region.volume();
    };
    let extent = |window: Option<[T; 2]>| window.map_or(T::one(), |[low, high]| high - low);
    let frame_z = [frame[0][2], frame[1][2], frame[2][2]];
    let varies = X::density(frame_z, T::zero(), c(0.3)) != X::density(frame_z, c(1.0), c(0.3));
    let points = if varies { AZIMUTH_POINTS } else { 1 };
    let area = shape.area(min_elevation, points, |azimuth, elevation| X::density(frame_z, azimuth, elevation));
    area * extent(range) * extent(range_rate)
}

impl<T: Real, X: Placeable<T, D>, const D: usize, const C: usize> Measure<T, 6, D> for SensorNetwork<T, X, D, C> {
    fn measure(&self, state: &SVector<T, 6>) -> SVector<T, D> {
        match self.light_time(self.current) {
            LightTime::Off => self.placed.measure(state),
            mode => light_time::measure(&self.placed, &self.observer, mode, X::AXES.range, state),
        }
    }

    fn jacobian(&self, state: &SVector<T, 6>) -> SMatrix<T, D, 6> {
        match self.light_time(self.current) {
            LightTime::Off => self.placed.jacobian(state),
            mode => light_time::jacobian(&self.placed, &self.observer, mode, state),
        }
    }

    fn noise_covariance(&self) -> SMatrix<T, D, D> {
        self.placed.noise_covariance()
    }

    fn residual(&self, z: &SVector<T, D>, predicted: &SVector<T, D>) -> SVector<T, D> {
        self.placed.residual(z, predicted)
    }
}

impl<T: Real, X: Placeable<T, D>, const D: usize, const C: usize> Placement<T, D> for SensorNetwork<T, X, D, C> {
    fn look_axes(&self) -> Option<LookAxes> {
        Some(X::AXES)
    }

    fn look(&self, z: &SVector<T, D>) -> Option<Look<T>> {
        X::look_in(&self.frame, z)
    }

    fn clutter_volume(&self, region: &Region<T>) -> T {
        match (self.sensors().get(self.current), self.volume(self.current)) {
            (Some(sensor), Some(volume)) if sensor.detection.field_of_view == *region => volume,
            _ => angular_volume::<T, X, D>(region, &self.frame),
        }
    }

    fn sensor_count(&self) -> usize {
        self.count
    }

    fn place(&self, scan: &ScanGeometry<T>) -> Result<Self, PlacementError>
    where
        Self: Sized + Clone,
    {
        self.place_at(scan.sensor, scan.time, scan.observer)
    }

    fn detection(&self) -> Option<Sensor<T>> {
        self.sensors().get(self.current).map(|sensor| sensor.detection)
    }
}

impl<T: Real, X: Placeable<T, D>, const D: usize, const C: usize> BirthGeometry<T, 6, D> for SensorNetwork<T, X, D, C> {
    fn birth_components(
        &self,
        z: &SVector<T, D>,
        region: &AdmissibleRegion<T>,
        out: &mut [BirthComponent<T, 6>],
    ) -> Result<usize, BirthError> {
        self.placed.birth_components(z, region, out)
    }

    fn sky_point(&self, z: &SVector<T, D>) -> Option<SkyPoint<T>> {
        self.placed.sky_point(z)
    }

    fn tracklet_components(
        &self,
        attributable: &Attributable<T>,
        observer: &[T; 6],
        settings: &crate::pool::TrackletBirths<T>,
        out: &mut [BirthComponent<T, 6>],
    ) -> Result<usize, BirthError> {
        self.placed.tracklet_components(attributable, observer, settings, out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{EARTH_MU, MotionModel, ProcessNoise, TwoBodyJ2};
    use crate::sensor::{GroundSite, LookShape};
    use crate::store::TrackLabel;
    use crate::{BirthModel, Config, Gaussian, PriorObject, StepError, Tracker};
    use rand_core::Rng;

    const DEGREE: f64 = core::f64::consts::PI / 180.0;

    fn radar_site(latitude: f64, longitude: f64) -> SiteSensor<f64, 3> {
        SiteSensor {
            platform: Platform::Ground(GroundSite {
                latitude: latitude * DEGREE,
                longitude: longitude * DEGREE,
                height: 0.2,
            }),
            sigma: [0.02, 0.02 * DEGREE, 0.02 * DEGREE],
            detection: Sensor {
                detection_probability: 0.95,
                clutter_rate: 1.0,
                field_of_view: Region::Look {
                    shape: LookShape::Cone { azimuth: 0.0, elevation: 90.0 * DEGREE, half_angle: 80.0 * DEGREE },
                    min_elevation: 5.0 * DEGREE,
                    range: Some([0.0, 4000.0]),
                    range_rate: None,
                },
            },
        }
    }

    fn telescope() -> SiteSensor<f64, 2> {
        SiteSensor {
            platform: Platform::Ground(GroundSite { latitude: 40.0 * DEGREE, longitude: -105.0 * DEGREE, height: 1.6 }),
            sigma: [2e-6, 2e-6],
            detection: Sensor {
                detection_probability: 0.9,
                clutter_rate: 3.0,
                field_of_view: Region::Look {
                    shape: LookShape::Cone {
                        azimuth: 170.0 * DEGREE,
                        elevation: 42.0 * DEGREE,
                        half_angle: 5.0 * DEGREE,
                    },
                    min_elevation: 10.0 * DEGREE,
                    range: None,
                    range_rate: None,
                },
            },
        }
    }

    /// The inertial unit vector of look angles (A, E) in `frame`.
    fn direction(frame: &[[f64; 3]; 3], azimuth: f64, elevation: f64) -> [f64; 3] {
        let (e, n, u) = (azimuth.sin() * elevation.cos(), azimuth.cos() * elevation.cos(), elevation.sin());
        core::array::from_fn(|k| e * frame[0][k] + n * frame[1][k] + u * frame[2][k])
    }

    #[test]
    fn optical_clutter_volume_in_right_ascension_and_declination_matches_monte_carlo_at_any_time() {
        let network: SensorNetwork<f64, OpticalRaDec<f64>, 2, 1> =
            SensorNetwork::new(EarthRotation::new(1.1), &[telescope()]).unwrap();
        let volume = network.volume(0).unwrap();
        let region = telescope().detection.field_of_view;
        for time in [0.0, 5_000.0] {
            let placed = network.place(&ScanGeometry::single(time)).unwrap();
            // Sample (α, δ) uniformly in a box around the boresight's (α, δ).
            let axis = direction(&placed.frame, 170.0 * DEGREE, 42.0 * DEGREE);
            let (alpha0, delta0) = (axis[1].atan2(axis[0]), axis[2].asin());
            let (half_alpha, half_delta) = (0.2, 0.1);
            let mut rng = crate::random::test_stream(11);
            let samples = 400_000;
            let mut inside = 0usize;
            for _ in 0..samples {
                let uniform = |rng: &mut rand_xoshiro::SplitMix64, low: f64, high: f64| {
                    low + (high - low) * ((rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64)
                };
                let alpha = uniform(&mut rng, alpha0 - half_alpha, alpha0 + half_alpha);
                let delta = uniform(&mut rng, delta0 - half_delta, delta0 + half_delta);
                let z = SVector::from([wrap_angle(alpha), delta]);
                inside += usize::from(region.sees(&placed, &z));
            }
            let fraction = inside as f64 / samples as f64;
            let box_area = 4.0 * half_alpha * half_delta;
            let (estimate, error) =
                (fraction * box_area, box_area * (fraction * (1.0 - fraction) / samples as f64).sqrt());
            eprintln!("t = {time}: volume {volume:.6e} rad², Monte Carlo {estimate:.6e} ± {error:.1e}");
            assert!((volume - estimate).abs() < 4.0 * error, "{volume} vs {estimate} ± {error}");
            // In (α, δ) the cone covers Ω / cos δ, not its look-angle area Ω / cos E.
            assert!((volume - region.volume()).abs() > 0.1 * volume, "{volume} vs {}", region.volume());
            assert_eq!(placed.clutter_volume(&region), volume);
        }
    }

    #[test]
    fn placement_errors_are_typed_and_ground_sites_move_with_the_earth() {
        let rotation = EarthRotation::new(0.4);
        let spacecraft = SiteSensor { platform: Platform::Spacecraft, ..radar_site(0.0, 0.0) };
        let network: SensorNetwork<f64, RadarRangeAzEl<f64>, 3, 3> =
            SensorNetwork::new(rotation, &[radar_site(40.0, -105.0), spacecraft]).unwrap();
        let at = |sensor, observer| ScanGeometry { sensor, time: 600.0, observer };
        let leo = [7000.0, 0.0, 0.0, 0.0, 7.5, 0.0];
        assert_eq!(network.place(&at(2, None)), Err(PlacementError::UnknownSensor { sensor: 2, sensors: 2 }));
        assert_eq!(network.place(&at(0, Some(leo))), Err(PlacementError::UnexpectedObserver));
        assert_eq!(network.place(&at(1, None)), Err(PlacementError::MissingObserver));
        let nan = [f64::NAN, 0.0, 0.0, 0.0, 7.5, 0.0];
        assert_eq!(network.place(&at(1, Some(nan))), Err(PlacementError::NonFiniteObserver));
        let underground = [6000.0, 0.0, 0.0, 0.0, 7.5, 0.0];
        assert_eq!(network.place(&at(1, Some(underground))), Err(PlacementError::ObserverInsideEarth));
        assert_eq!(network.place(&at(1, Some(leo))).unwrap().placed().observer, leo);
        // A ground site is where GroundSite puts it at that time.
        let placed = network.place(&at(0, None)).unwrap();
        let site = GroundSite { latitude: 40.0 * DEGREE, longitude: -105.0 * DEGREE, height: 0.2 };
        let expected = site.observer(&rotation, 600.0);
        for (a, b) in placed.placed().observer.iter().zip(expected) {
            assert!((a - b).abs() < 1e-9, "{a} vs {b}");
        }
        // Bad networks.
        let too_many = [radar_site(0.0, 0.0); 4];
        assert!(SensorNetwork::<f64, RadarRangeAzEl<f64>, 3, 3>::new(rotation, &too_many).is_err());
        assert!(SensorNetwork::<f64, RadarRangeAzEl<f64>, 3, 3>::new(rotation, &[]).is_err());
        let mut inside = radar_site(0.0, 0.0);
        inside.platform = Platform::Ground(GroundSite { latitude: 0.0, longitude: 0.0, height: -50.0 });
        assert!(SensorNetwork::<f64, RadarRangeAzEl<f64>, 3, 3>::new(rotation, &[inside]).is_err());
        let mut pole = radar_site(0.0, 0.0);
        pole.platform = Platform::Ground(GroundSite { latitude: 2.0, longitude: 0.0, height: 0.0 });
        assert!(SensorNetwork::<f64, RadarRangeAzEl<f64>, 3, 3>::new(rotation, &[pole]).is_err());
        let mut flat = radar_site(0.0, 0.0);
        flat.detection.field_of_view = Region::Look {
            shape: LookShape::Cone { azimuth: 0.0, elevation: 0.5, half_angle: 0.1 },
            min_elevation: 0.0,
            range: Some([1.0, 1.0]),
            range_rate: None,
        };
        assert!(SensorNetwork::<f64, RadarRangeAzEl<f64>, 3, 3>::new(rotation, &[flat]).is_err());
    }

    #[test]
    fn an_f32_site_keeps_its_place_at_large_times() {
        let rotation = EarthRotation::new(0.4);
        let f64_network: SensorNetwork<f64, RadarRangeAzEl<f64>, 3, 1> =
            SensorNetwork::new(rotation, &[radar_site(40.0, -105.0)]).unwrap();
        let site32 = SiteSensor {
            platform: Platform::Ground(GroundSite {
                latitude: (40.0 * DEGREE) as f32,
                longitude: (-105.0 * DEGREE) as f32,
                height: 0.2,
            }),
            sigma: [0.02f32, 3e-4, 3e-4],
            detection: Sensor {
                detection_probability: 0.95,
                clutter_rate: 1.0,
                field_of_view: Region::Look {
                    shape: LookShape::Cone {
                        azimuth: 0.0,
                        elevation: (90.0 * DEGREE) as f32,
                        half_angle: (80.0 * DEGREE) as f32,
                    },
                    min_elevation: (5.0 * DEGREE) as f32,
                    range: Some([0.0, 4000.0]),
                    range_rate: None,
                },
            },
        };
        let f32_network: SensorNetwork<f32, RadarRangeAzEl<f32>, 3, 1> =
            SensorNetwork::new(EarthRotation::new(0.4f32), &[site32]).unwrap();
        // Ten days in: the f64 angle is cast once, so the f32 site is within f32 rounding of the f64 one.
        let time = 864_000.123;
        let a = f64_network.place(&ScanGeometry::single(time)).unwrap().placed().observer;
        let b = f32_network.place(&ScanGeometry::single(time)).unwrap().placed().observer;
        for (x, y) in a.iter().zip(b) {
            assert!((x - f64::from(y)).abs() < 2e-3, "{x} vs {y}");
        }
    }

    /// A circular LEO object seen from `frame`/`observer` at look angles (A, E) and range ρ, moving
    /// westwards (its azimuth grows through ±π when it starts due south).
    fn object_at(
        observer: &[f64; 6],
        frame: &[[f64; 3]; 3],
        azimuth: f64,
        elevation: f64,
        range: f64,
    ) -> SVector<f64, 6> {
        let u = direction(frame, azimuth, elevation);
        let p: [f64; 3] = core::array::from_fn(|k| observer[k] + range * u[k]);
        let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        let west = frame[0].map(|v| -v);
        let along = (west[0] * p[0] + west[1] * p[1] + west[2] * p[2]) / r;
        let mut w: [f64; 3] = core::array::from_fn(|k| west[k] - along * p[k] / r);
        let norm = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
        let speed = (EARTH_MU / r).sqrt();
        w = w.map(|v| v * speed / norm);
        SVector::from([p[0], p[1], p[2], w[0], w[1], w[2]])
    }

    type Radars = SensorNetwork<f64, RadarRangeAzEl<f64>, 3, 2>;

    #[test]
    fn two_radars_track_a_pass_through_azimuth_pi_and_refuse_bad_scans_unchanged() {
        let network: Radars =
            SensorNetwork::new(EarthRotation::new(0.3), &[radar_site(40.0, -105.0), radar_site(38.0, -100.0)]).unwrap();
        let motion = TwoBodyJ2::<f64>::earth(ProcessNoise::Isotropic(1e-10), 20.0, 2000);
        let first = network.place(&ScanGeometry::single(0.0)).unwrap();
        let truth0 = object_at(&first.placed().observer, &first.frame, 160.0 * DEGREE, 45.0 * DEGREE, 900.0);
        let mut covariance = SMatrix::<f64, 6, 6>::zeros();
        for k in 0..3 {
            covariance[(k, k)] = 0.25;
            covariance[(k + 3, k + 3)] = 1e-4;
        }
        let mut start = truth0;
        start[0] += 0.3;
        start[4] -= 0.005;
        let config = Config {
            motion,
            measurement: network,
            sensor: radar_site(0.0, 0.0).detection,
            birth: BirthModel::<f64, 6, 1>::none(),
            death_probability: 0.0,
            gate: None,
            children: Default::default(),
            selection: Default::default(),
            store_overflow: Default::default(),
            numerical_failure: Default::default(),
            track_loss: Default::default(),
            seed: 3,
        };
        let objects = [PriorObject { label: TrackLabel(0), state: Gaussian { mean: start, covariance } }];
        let prior = [crate::PriorHypothesis { weight: 1.0, objects: &objects }];
        let mut tracker: Tracker<f64, TwoBodyJ2<f64>, Radars, 6, 3, 8, 4, 8, 16, 1> =
            Tracker::new(config, &prior, 0.0).unwrap();
        let mut rng = crate::random::test_stream(5);
        let mut gaussian = move || {
            // Box–Muller from two uniforms in (0, 1].
            let u1 = ((rng.next_u64() >> 11) as f64 + 1.0) / (1u64 << 53) as f64;
            let u2 = (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
            (-2.0 * u1.ln()).sqrt() * (2.0 * core::f64::consts::PI * u2).cos()
        };
        let mut truth = truth0;
        let mut azimuth_signs = [false; 2];
        let mut last_error = f64::INFINITY;
        for scan in 1..=12u32 {
            let time = 10.0 * f64::from(scan);
            truth = motion.propagate(&truth, 10.0).unwrap().state;
            let geometry = ScanGeometry { sensor: scan as usize % 2, time, observer: None };
            let placed = network.place(&geometry).unwrap();
            let exact = placed.measure(&truth);
            let sigma = placed.sensors()[geometry.sensor].sigma;
            let z = SVector::from([
                exact[0] + sigma[0] * gaussian(),
                wrap_angle(exact[1] + sigma[1] * gaussian()),
                exact[2] + sigma[2] * gaussian(),
            ]);
            azimuth_signs[usize::from(z[1] > 0.0)] = true;
            // Bad scans first: each is refused and leaves the tracker as it was.
            let before = tracker.digest();
            let unknown = ScanGeometry { sensor: 2, ..geometry };
            assert_eq!(
                tracker.step_scan(&unknown, &[z]),
                Err(StepError::Placement(PlacementError::UnknownSensor { sensor: 2, sensors: 2 }))
            );
            let observed = ScanGeometry { observer: Some([7000.0, 0.0, 0.0, 0.0, 7.5, 0.0]), ..geometry };
            assert_eq!(
                tracker.step_scan(&observed, &[z]),
                Err(StepError::Placement(PlacementError::UnexpectedObserver))
            );
            let far = ScanGeometry { time: 1e6, ..geometry };
            assert_eq!(tracker.step_scan(&far, &[z]), Err(StepError::TimeStepTooLong { limit_seconds: 40_000 }));
            let below = SVector::from([z[0], z[1], -0.5]);
            assert_eq!(
                tracker.step_scan(&geometry, &[below]),
                Err(StepError::MeasurementOutsideFieldOfView { index: 0 })
            );
            assert_eq!(tracker.digest(), before);

            tracker.step_scan(&geometry, &[z]).unwrap();
            let map = tracker.map_hypothesis();
            let track = map.tracks().next().expect("the object is kept");
            let error = (track.state.mean.fixed_rows::<3>(0) - truth.fixed_rows::<3>(0)).norm();
            eprintln!("scan {scan}: sensor {} azimuth {:.4} rad, position error {error:.3} km", geometry.sensor, z[1]);
            // σ of 0.02° is 0.3 km across the line of sight at 900 km.
            assert!(map.weight() > 0.99 && error < 1.0, "scan {scan}: weight {} error {error} km", map.weight());
            last_error = error;
        }
        assert!(last_error < 0.3, "{last_error} km after twelve scans");
        // The pass crossed azimuth ±π: measurements on both sides of it.
        assert_eq!(azimuth_signs, [true, true]);
    }
}
