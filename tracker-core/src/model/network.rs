//! Sensor networks: several sensors of one measurement type (radars, or telescopes) on ground sites or
//! spacecraft, each with its own noise, field of view, p_D and clutter, placed at every scan
//! (docs/maths.md §6.9).
//!
//! A scan names its sensor and, for a spacecraft, passes the observer's inertial state
//! ([`ScanGeometry`]). [`SensorNetwork::place`](crate::MeasurementModel::place) turns that into the
//! measurement model of the scan: the observer's inertial position and velocity, and the sensor's frame
//! (East, North, Up of a ground site at the scan's Earth rotation angle; the inertial axes, arranged so that
//! azimuth is right ascension and elevation declination, for a spacecraft). A ground site's Earth rotation
//! angle is computed in `f64` from the scan time and cast once, so an `f32` tracker loses no precision to a
//! large time.
//!
//! The clutter volume of each sensor's field of view in measurement coordinates is computed once, when
//! the network is built (the quadrature of the model's [`Placeable::density`], see [`crate::sensor::LookShape::area`]): Earth rotation
//! turns a ground site's frame about the pole, which leaves the density unchanged.

use super::frames::{EarthRotation, GroundSite, look_angles, wrap_angle};
use super::{MeasurementModel, OpticalRaDec, RadarRangeAzEl, RadarRangeRate, WGS84_FLATTENING};
use crate::real::{Real, c, cos, sin, sqrt};
use crate::sensor::{Look, LookAxes, Region, Sensor};
use nalgebra::{SMatrix, SVector};

/// Where a sensor is.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Platform<T> {
    /// A site on the rotating Earth.
    Ground(GroundSite<T>),
    /// A spacecraft: every scan of this sensor passes the observer's inertial state.
    Spacecraft,
}

/// One sensor of a [`SensorNetwork`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SiteSensor<T, const D: usize> {
    /// Where it is.
    pub platform: Platform<T>,
    /// Noise standard deviation of each measurement component (km, rad, km/s).
    pub sigma: [T; D],
    /// p_D, clutter and the field of view ([`Region::Look`]).
    pub detection: Sensor<T>,
}

/// Which sensor made a scan, when, and from where.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ScanGeometry<T> {
    /// The sensor's index in its network (0 for a single sensor).
    pub sensor: usize,
    /// The scan time (s after the configuration's epoch).
    pub time: f64,
    /// A spacecraft observer's inertial position and velocity (km, km/s); `None` for ground sites and
    /// for models without an observer.
    pub observer: Option<[T; 6]>,
}

impl<T> ScanGeometry<T> {
    /// The geometry of a scan of the only sensor, without an observer.
    pub const fn single(time: f64) -> Self {
        Self { sensor: 0, time, observer: None }
    }
}

/// Why a scan's geometry cannot be placed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum PlacementError {
    /// The scan names a sensor the model does not have.
    UnknownSensor {
        /// The sensor named.
        sensor: usize,
        /// How many sensors there are.
        sensors: usize,
    },
    /// A spacecraft sensor's scan has no observer state.
    MissingObserver,
    /// The scan passes an observer state to a sensor that has none (a ground site, a planar model).
    UnexpectedObserver,
    /// The observer state has a NaN or an infinity.
    NonFiniteObserver,
    /// The observer is inside the Earth's WGS-84 ellipsoid.
    ObserverInsideEarth,
}

impl core::fmt::Display for PlacementError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            PlacementError::UnknownSensor { sensor, sensors } => {
                write!(f, "scan names sensor {sensor}, but there are {sensors} sensors")
            }
            PlacementError::MissingObserver => f.write_str("scan of a spacecraft sensor has no observer state"),
            PlacementError::UnexpectedObserver => f.write_str("scan passes an observer state to a sensor without one"),
            PlacementError::NonFiniteObserver => f.write_str("observer state is not finite"),
            PlacementError::ObserverInsideEarth => f.write_str("observer is inside the Earth"),
        }
    }
}

impl core::error::Error for PlacementError {}

/// A measurement model that a [`SensorNetwork`] places at each scan: built from the observer's inertial
/// state, the sensor's frame (rows: East, North, Up in inertial coordinates) and the noise.
pub trait Placeable<T: Real, const D: usize>: MeasurementModel<T, 6, D> + Copy {
    /// The coordinates besides the angles.
    const AXES: LookAxes;

    /// The model for one scan.
    fn placed(observer: [T; 6], frame: [[T; 3]; 3], sigma: [T; D]) -> Self;

    /// Measurement `z` as a look direction in `frame`.
    fn look_in(frame: &[[T; 3]; 3], z: &SVector<T, D>) -> Look<T>;

    /// |∂(measured angles)/∂(azimuth, elevation)| at a look direction: the factor that turns an area in
    /// look angles into one in measurement coordinates. `frame_z` holds the inertial z components of the
    /// frame's rows. The default, 1, is right when the measured angles are the look angles.
    fn density(_frame_z: [T; 3], _azimuth: T, _elevation: T) -> T {
        T::one()
    }
}

impl<T: Real> Placeable<T, 3> for RadarRangeAzEl<T> {
    const AXES: LookAxes = LookAxes { range: true, range_rate: false };

    fn placed(observer: [T; 6], frame: [[T; 3]; 3], sigma: [T; 3]) -> Self {
        Self { observer, enu: frame, sigma }
    }

    fn look_in(_frame: &[[T; 3]; 3], z: &SVector<T, 3>) -> Look<T> {
        Look { azimuth: z[1], elevation: z[2], range: Some(z[0]), range_rate: None }
    }
}

impl<T: Real> Placeable<T, 4> for RadarRangeRate<T> {
    const AXES: LookAxes = LookAxes { range: true, range_rate: true };

    fn placed(observer: [T; 6], frame: [[T; 3]; 3], sigma: [T; 4]) -> Self {
        Self { observer, enu: frame, sigma }
    }

    fn look_in(_frame: &[[T; 3]; 3], z: &SVector<T, 4>) -> Look<T> {
        Look { azimuth: z[1], elevation: z[2], range: Some(z[0]), range_rate: Some(z[3]) }
    }
}

impl<T: Real> Placeable<T, 2> for OpticalRaDec<T> {
    const AXES: LookAxes = LookAxes { range: false, range_rate: false };

    fn placed(observer: [T; 6], _frame: [[T; 3]; 3], sigma: [T; 2]) -> Self {
        Self { observer, sigma }
    }

    fn look_in(frame: &[[T; 3]; 3], z: &SVector<T, 2>) -> Look<T> {
        // The inertial unit vector of (α, δ), then its components along the frame's rows.
        let (alpha, delta) = (z[0], z[1]);
        let unit = [cos(delta) * cos(alpha), cos(delta) * sin(alpha), sin(delta)];
        let along = |row: &[T; 3]| row[0] * unit[0] + row[1] * unit[1] + row[2] * unit[2];
        let (_, azimuth, elevation, _) = look_angles([along(&frame[0]), along(&frame[1]), along(&frame[2])]);
        Look { azimuth, elevation, range: None, range_rate: None }
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
/// use tracker_core::model::{EarthRotation, GroundSite, Platform, RadarRangeAzEl, ScanGeometry, SensorNetwork, SiteSensor};
/// use tracker_core::sensor::{LookShape, Region, Sensor};
/// use tracker_core::MeasurementModel;
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
}

/// The spacecraft frame: rows "East" = ŷ, "North" = x̂, "Up" = ẑ, so that azimuth is right ascension and
/// elevation declination.
fn inertial_frame<T: Real>() -> [[T; 3]; 3] {
    let (o, l) = (T::zero(), T::one());
    [[o, l, o], [l, o, o], [o, o, l]]
}

impl<T: Real, X: Placeable<T, D>, const D: usize, const C: usize> SensorNetwork<T, X, D, C> {
    /// A network of `sensors`, placed at the first one at time 0.
    ///
    /// # Errors
    /// A static description of the first invalid part: more sensors than `C`, none, a site outside
    /// latitude [−π/2, π/2] or below 1 km under the ellipsoid, a non-positive noise, a detection model
    /// that is not a valid look-angle field of view for `X`, or a clutter volume that is not finite.
    pub fn new(rotation: EarthRotation<T>, sensors: &[SiteSensor<T, D>]) -> Result<Self, &'static str> {
        const { assert!(C > 0, "a sensor network needs room for one sensor") };
        let Some(first) = sensors.first() else {
            return Err("sensor network: no sensors");
        };
        if sensors.len() > C {
            return Err("sensor network: more sensors than its capacity C");
        }
        if !(rotation.angle_at_epoch.is_finite_value() && rotation.rate.is_finite_value()) {
            return Err("sensor network: Earth rotation angle and rate must be finite");
        }
        let mut network = Self {
            rotation,
            sensors: [*first; C],
            volumes: [T::one(); C],
            count: sensors.len(),
            current: 0,
            frame: inertial_frame(),
            placed: X::placed([T::zero(); 6], inertial_frame(), first.sigma),
        };
        for (index, sensor) in sensors.iter().enumerate() {
            check_sensor(sensor)?;
            let frame = match sensor.platform {
                Platform::Ground(site) => site.enu(&rotation, T::zero()),
                Platform::Spacecraft => inertial_frame(),
            };
            let volume = angular_volume::<T, X, D>(&sensor.detection.field_of_view, &frame);
            let intensity = sensor.detection.clutter_rate / volume;
            if !(volume.is_finite_value()
                && volume > T::zero()
                && intensity.is_finite_value()
                && intensity > T::zero()
                && crate::real::ln(intensity).is_finite_value())
            {
                return Err("sensor network: a field of view's clutter volume or intensity is not finite and > 0");
            }
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
        let (state, frame) = match (site.platform, observer) {
            (Platform::Ground(_), Some(_)) => return Err(PlacementError::UnexpectedObserver),
            (Platform::Spacecraft, None) => return Err(PlacementError::MissingObserver),
            (Platform::Ground(ground), None) => {
                // The rotation angle in f64 from the f64 scan time, then one cast.
                let angle = self.rotation.angle_at_epoch.as_f64() + self.rotation.rate.as_f64() * time;
                let at = EarthRotation { angle_at_epoch: T::of_f64(wrap_angle(angle)), rate: self.rotation.rate };
                (ground.observer(&at, T::zero()), ground.enu(&at, T::zero()))
            }
            (Platform::Spacecraft, Some(state)) => {
                if !state.iter().all(|v| v.is_finite_value()) {
                    return Err(PlacementError::NonFiniteObserver);
                }
                if inside_earth(&state) {
                    return Err(PlacementError::ObserverInsideEarth);
                }
                (state, inertial_frame())
            }
        };
        Ok(Self { current: sensor, frame, placed: X::placed(state, frame, site.sigma), ..*self })
    }
}

/// Whether an inertial position lies inside the WGS-84 ellipsoid (x² + y²) / a² + z² / b² < 1.
fn inside_earth<T: Real>(state: &[T; 6]) -> bool {
    let a = super::EARTH_RADIUS;
    let b = a * (1.0 - WGS84_FLATTENING);
    let [x, y, z, ..] = state.map(T::as_f64);
    (x * x + y * y) / (a * a) + z * z / (b * b) < 1.0
}

fn check_sensor<T: Real, const D: usize>(sensor: &SiteSensor<T, D>) -> Result<(), &'static str> {
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
    if !sensor.sigma.iter().all(|&s| s.is_finite_value() && s > T::zero()) {
        return Err("sensor network: every noise standard deviation must be finite and > 0");
    }
    if !matches!(sensor.detection.field_of_view, Region::Look { .. }) {
        return Err("sensor network: a sensor's field of view must be a look-angle region");
    }
    Ok(())
}

/// The clutter volume of a look-angle `region` for measurements of `X` seen in `frame`.
fn angular_volume<T: Real, X: Placeable<T, D>, const D: usize>(region: &Region<T>, frame: &[[T; 3]; 3]) -> T {
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

impl<T: Real, X: Placeable<T, D>, const D: usize, const C: usize> MeasurementModel<T, 6, D>
    for SensorNetwork<T, X, D, C>
{
    fn measure(&self, state: &SVector<T, 6>) -> SVector<T, D> {
        self.placed.measure(state)
    }

    fn jacobian(&self, state: &SVector<T, 6>) -> SMatrix<T, D, 6> {
        self.placed.jacobian(state)
    }

    fn noise_covariance(&self) -> SMatrix<T, D, D> {
        self.placed.noise_covariance()
    }

    fn residual(&self, z: &SVector<T, D>, predicted: &SVector<T, D>) -> SVector<T, D> {
        self.placed.residual(z, predicted)
    }

    fn look_axes(&self) -> Option<LookAxes> {
        Some(X::AXES)
    }

    fn look(&self, z: &SVector<T, D>) -> Option<Look<T>> {
        Some(X::look_in(&self.frame, z))
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
