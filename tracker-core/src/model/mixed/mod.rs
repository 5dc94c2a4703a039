//! Sensor networks of mixed kinds in one tracker: radars, telescopes, angles-only and ranging stations
//! (docs/maths.md §6.10).
//!
//! A [`MixedNetwork`] holds up to `C` sensors, each of its own [`SensorKind`]. Its measurements are
//! vectors of the tracker's `D = 4` components: a kind of dimension d fills the first d in its own order
//! ([`SensorKind::components`]) and leaves the rest at zero. The placed model ([`MixedLook`]) pads every
//! quantity so that the padding cannot change a number:
//!
//! - h(x) and the residual are zero in the padding, and H's padded rows are zero;
//! - R is the identity in the padding, so S = H P Hᵀ + R is block-diagonal with an identity block.
//!
//! The Cholesky factor of S is then the d × d factor with an identity block (every padded entry is an
//! exact 0 or 1), the Mahalanobis distance and ln det S are the d-dimensional ones, the gain's padded
//! columns are zero, and the normaliser is (2π)^(−d/2) ([`Measure::dimension`]). So each kind is scored
//! and updated in its own dimension, with the same bits as a tracker of that kind alone: radar, radar
//! with range-rate and right ascension/declination delegate to [`RadarRangeAzEl`], [`RadarRangeRate`]
//! and [`OpticalRaDec`].
//!
//! Each sensor's clutter intensity is in its own measurement units (its field of view's volume in its
//! own coordinates), so every entry p_D g(z | x) / κ(z) is dimensionless and the weights of children
//! under different sensors are comparable. A range-only or range and range-rate sensor measures no
//! angles: whether an object is in its field of view is read from the object's look direction
//! ([`Measure::look_of_state`]), and a measurement is in view when its range (and range-rate) lie in the
//! windows.
//!
//! **Births.** Radar kinds use the radar admissible regions, right ascension/declination the optical one,
//! in the region the tracker's birth model gives or, where a sensor has one, that sensor's own
//! ([`MixedNetwork::with_births`]: a telescope staring at the GEO belt beside a radar fence on LEO), or none
//! where a sensor's measurements should start no track ([`SensorBirths::Off`]);
//! an azimuth/elevation measurement is turned into the inertial direction it names and uses the optical
//! region (with an isotropic angular σ, the larger of σ_A cos E and σ_E). Range-only kinds give no birth
//! density: their objects are born from another sensor's measurements.

mod kind;

pub use kind::{KindError, KindMeasurement, SensorKind};

use super::light_time::{self, LightTime};
use super::network::{angular_volume, check_platform, first_of_network, inertial_frame, observer_and_frame};
use super::{
    AdmissibleRegion, Attributable, BirthComponent, BirthError, BirthGeometry, Measure, OpticalRaDec, Placeable,
    RadarRangeAzEl, RadarRangeRate, SkyPoint, tracklet_births,
};
use crate::real::{Real, atan2, cos, sin, sqrt};
use crate::sensor::frames::{EarthRotation, wrap_angle};
use crate::sensor::{Look, LookAxes, Placement, PlacementError, Platform, Region, ScanGeometry, Sensor, SiteSensor};
use nalgebra::{SMatrix, SVector};

/// The measurement components of a [`MixedNetwork`]: the largest kind's dimension.
pub const MIXED_DIMENSION: usize = 4;

/// One sensor of a [`MixedNetwork`]: its kind, and where it is, its noise and how it detects. `sigma`
/// holds the kind's components first ([`SensorKind::components`]); the rest must be zero.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct MixedSensor<T> {
    /// What it measures.
    pub kind: SensorKind,
    /// Platform, noise (padded with zeros) and detection model.
    pub sensor: SiteSensor<T, MIXED_DIMENSION>,
}

/// The measurement model of one sensor of a [`MixedNetwork`], placed at a scan (see the module
/// documentation for the padding).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct MixedLook<T> {
    /// What it measures.
    pub kind: SensorKind,
    /// The observer's inertial position and velocity (km, km/s).
    pub observer: [T; 6],
    /// The sensor frame's East, North, Up rows in inertial coordinates.
    pub frame: [[T; 3]; 3],
    /// Noise standard deviations of the kind's components, then zeros.
    pub sigma: [T; MIXED_DIMENSION],
    /// Where the sensor's births come from.
    pub births: SensorBirths<T>,
    /// How light time delays its measurements (docs/maths.md §6.12).
    pub light_time: LightTime,
}

/// Where the births of one sensor of a [`MixedNetwork`] come from.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum SensorBirths<T> {
    /// The birth model's admissible region.
    #[default]
    FromModel,
    /// The sensor's own admissible region (a telescope on the GEO belt beside radars on LEO).
    Region(AdmissibleRegion<T>),
    /// None: the sensor's measurements start no track (its objects are born from other sensors').
    Off,
}

type Vector4<T> = SVector<T, MIXED_DIMENSION>;

impl<T: Real> MixedLook<T> {
    fn radar(&self) -> RadarRangeAzEl<T> {
        let [a, b, c, _] = self.sigma;
        RadarRangeAzEl { observer: self.observer, enu: self.frame, sigma: [a, b, c] }
    }

    fn radar_rate(&self) -> RadarRangeRate<T> {
        RadarRangeRate { observer: self.observer, enu: self.frame, sigma: self.sigma }
    }

    fn optical(&self) -> OpticalRaDec<T> {
        let [a, b, ..] = self.sigma;
        OpticalRaDec { observer: self.observer, sigma: [a, b] }
    }

    /// (ρ, A, E, ρ̇) of `state` and the Jacobian rows of the four.
    fn full(&self, state: &SVector<T, 6>) -> (Vector4<T>, SMatrix<T, 4, 6>) {
        let radar = self.radar_rate();
        (radar.measure(state), radar.jacobian(state))
    }
}

/// `values` in the first components, zeros after.
fn pad<T: Real, const K: usize>(values: &SVector<T, K>) -> Vector4<T> {
    let mut padded = Vector4::zeros();
    for (out, value) in padded.iter_mut().zip(values.iter()) {
        *out = *value;
    }
    padded
}

/// Rows `rows` of `h` in the first rows, zeros after.
fn pick_rows<T: Real>(h: &SMatrix<T, 4, 6>, rows: &[usize]) -> SMatrix<T, 4, 6> {
    let mut picked = SMatrix::<T, 4, 6>::zeros();
    for (out, &row) in rows.iter().enumerate() {
        picked.set_row(out, &h.row(row));
    }
    picked
}

/// The first `K` components of `z`.
fn head<T: Real, const K: usize>(z: &Vector4<T>) -> SVector<T, K> {
    SVector::from_fn(|i, _| z[i])
}

/// A [`MixedLook`] measuring the object where it is at the scan time: what light time evaluates at the
/// retarded state (§6.12).
struct Instant<'a, T>(&'a MixedLook<T>);

impl<T: Real> Measure<T, 6, MIXED_DIMENSION> for Instant<'_, T> {
    // Inlined, so that a sensor without light time runs the code of a network without the setting.
    #[inline(always)]
    fn measure(&self, state: &SVector<T, 6>) -> Vector4<T> {
        let (o, look) = (T::zero(), self.0);
        match look.kind {
            SensorKind::Radar => pad(&look.radar().measure(state)),
            SensorKind::RadarRangeRate => look.radar_rate().measure(state),
            SensorKind::OpticalRaDec => pad(&look.optical().measure(state)),
            SensorKind::AzEl => {
                let z = look.radar().measure(state);
                SVector::from([z[1], z[2], o, o])
            }
            SensorKind::Range => {
                let z = look.radar().measure(state);
                SVector::from([z[0], o, o, o])
            }
            SensorKind::RangeRangeRate => {
                let z = look.radar_rate().measure(state);
                SVector::from([z[0], z[3], o, o])
            }
        }
    }

    #[inline(always)]
    fn jacobian(&self, state: &SVector<T, 6>) -> SMatrix<T, 4, 6> {
        let look = self.0;
        match look.kind {
            SensorKind::Radar => {
                let h = look.radar().jacobian(state);
                let mut padded = SMatrix::<T, 4, 6>::zeros();
                for row in 0..3 {
                    padded.set_row(row, &h.row(row));
                }
                padded
            }
            SensorKind::RadarRangeRate => look.radar_rate().jacobian(state),
            SensorKind::OpticalRaDec => {
                let h = look.optical().jacobian(state);
                let mut padded = SMatrix::<T, 4, 6>::zeros();
                for row in 0..2 {
                    padded.set_row(row, &h.row(row));
                }
                padded
            }
            SensorKind::AzEl => pick_rows(&look.full(state).1, &[1, 2]),
            SensorKind::Range => pick_rows(&look.full(state).1, &[0]),
            SensorKind::RangeRangeRate => pick_rows(&look.full(state).1, &[0, 3]),
        }
    }

    fn noise_covariance(&self) -> SMatrix<T, 4, 4> {
        self.0.noise_covariance()
    }
}

impl<T: Real> Measure<T, 6, MIXED_DIMENSION> for MixedLook<T> {
    /// h at the scan time, or at the light-time retarded state (§6.12; component 0 is the range of every
    /// kind that has one).
    fn measure(&self, state: &SVector<T, 6>) -> Vector4<T> {
        match self.light_time {
            LightTime::Off => Instant(self).measure(state),
            mode => light_time::measure(&Instant(self), &self.observer, mode, self.kind.axes().range, state),
        }
    }

    fn jacobian(&self, state: &SVector<T, 6>) -> SMatrix<T, 4, 6> {
        match self.light_time {
            LightTime::Off => Instant(self).jacobian(state),
            mode => light_time::jacobian(&Instant(self), &self.observer, mode, state),
        }
    }

    /// diag(σ²) in the kind's components, the identity in the padding.
    fn noise_covariance(&self) -> SMatrix<T, 4, 4> {
        let dimension = self.kind.dimension();
        SMatrix::from_diagonal(&SVector::from_fn(
            |i, _| {
                if i < dimension { self.sigma[i] * self.sigma[i] } else { T::one() }
            },
        ))
    }

    /// The kind's residual (its angles wrapped), exactly zero in the padding whatever `z` holds there.
    fn residual(&self, z: &Vector4<T>, predicted: &Vector4<T>) -> Vector4<T> {
        let o = T::zero();
        match self.kind {
            SensorKind::Radar => pad(&self.radar().residual(&head::<T, 3>(z), &head::<T, 3>(predicted))),
            SensorKind::RadarRangeRate => self.radar_rate().residual(z, predicted),
            SensorKind::OpticalRaDec => pad(&self.optical().residual(&head::<T, 2>(z), &head::<T, 2>(predicted))),
            SensorKind::AzEl => SVector::from([wrap_angle(z[0] - predicted[0]), z[1] - predicted[1], o, o]),
            SensorKind::Range => SVector::from([z[0] - predicted[0], o, o, o]),
            SensorKind::RangeRangeRate => SVector::from([z[0] - predicted[0], z[1] - predicted[1], o, o]),
        }
    }

    fn dimension(&self) -> usize {
        self.kind.dimension()
    }

    /// For the kinds without angles, the full look (ρ, A, E and ρ̇ where measured) of `state`, retarded
    /// by light time as the measurement is.
    fn look_of_state(&self, state: &SVector<T, 6>) -> Option<Look<T>> {
        if self.kind.measures_angles() {
            return None;
        }
        let radar = self.radar_rate();
        let z = match self.light_time {
            LightTime::Off => radar.measure(state),
            mode => light_time::measure(&radar, &self.observer, mode, true, state),
        };
        let range_rate = self.kind.axes().range_rate.then_some(z[3]);
        Some(Look { azimuth: z[1], elevation: z[2], range: Some(z[0]), range_rate })
    }
}

fn in_window<T: Real>(window: Option<[T; 2]>, value: T) -> bool {
    window.is_none_or(|[low, high]| value >= low && value <= high)
}

impl<T: Real> Placement<T, MIXED_DIMENSION> for MixedLook<T> {
    fn look_axes(&self) -> Option<LookAxes> {
        Some(self.kind.axes())
    }

    /// The look of a measurement that has angles (`None` for the range kinds).
    fn look(&self, z: &Vector4<T>) -> Option<Look<T>> {
        match self.kind {
            SensorKind::Radar => Some(Look { azimuth: z[1], elevation: z[2], range: Some(z[0]), range_rate: None }),
            SensorKind::RadarRangeRate => {
                Some(Look { azimuth: z[1], elevation: z[2], range: Some(z[0]), range_rate: Some(z[3]) })
            }
            SensorKind::OpticalRaDec => <OpticalRaDec<T> as Placeable<T, 2>>::look_in(&self.frame, &head::<T, 2>(z)),
            SensorKind::AzEl => Some(Look { azimuth: z[0], elevation: z[1], range: None, range_rate: None }),
            SensorKind::Range | SensorKind::RangeRangeRate => None,
        }
    }

    fn clutter_volume(&self, region: &Region<T>) -> T {
        kind_volume(self.kind, region, &self.frame)
    }

    fn fits(&self, z: &Vector4<T>) -> bool {
        z.iter().skip(self.kind.dimension()).all(|v| *v == T::zero())
    }

    /// The range kinds: range (and range-rate) in the windows; the others through their look.
    fn measurement_in_view(&self, region: &Region<T>, z: &Vector4<T>) -> bool {
        match (self.kind, region) {
            (SensorKind::Range, Region::Look { range, .. }) => in_window(*range, z[0]),
            (SensorKind::RangeRangeRate, Region::Look { range, range_rate, .. }) => {
                in_window(*range, z[0]) && in_window(*range_rate, z[1])
            }
            _ => region.sees(self, z),
        }
    }
}

/// The clutter volume of `region` in the coordinates of `kind` seen in `frame`.
fn kind_volume<T: Real>(kind: SensorKind, region: &Region<T>, frame: &[[T; 3]; 3]) -> T {
    match (kind, region) {
        (SensorKind::OpticalRaDec, _) => angular_volume::<T, OpticalRaDec<T>, 2>(region, frame),
        (SensorKind::Range | SensorKind::RangeRangeRate, Region::Look { range, range_rate, .. }) => {
            let extent = |window: Option<[T; 2]>| window.map_or(T::one(), |[low, high]| high - low);
            extent(*range) * extent(*range_rate)
        }
        _ => angular_volume::<T, RadarRangeAzEl<T>, 3>(region, frame),
    }
}

impl<T: Real> BirthGeometry<T, 6, MIXED_DIMENSION> for MixedLook<T> {
    fn birth_components(
        &self,
        z: &Vector4<T>,
        region: &AdmissibleRegion<T>,
        out: &mut [BirthComponent<T, 6>],
    ) -> Result<usize, BirthError> {
        let region = match &self.births {
            SensorBirths::FromModel => region,
            SensorBirths::Region(own) => own,
            SensorBirths::Off => return Err(BirthError::Unsupported),
        };
        match self.kind {
            SensorKind::Radar => self.radar().birth_components(&head::<T, 3>(z), region, out),
            SensorKind::RadarRangeRate => self.radar_rate().birth_components(z, region, out),
            SensorKind::OpticalRaDec => self.optical().birth_components(&head::<T, 2>(z), region, out),
            SensorKind::AzEl => {
                let (direction, sigma) = self.az_el_as_ra_dec(z[0], z[1]);
                self.optical().with_sigma(sigma).birth_components(&direction, region, out)
            }
            SensorKind::Range | SensorKind::RangeRangeRate => Err(BirthError::Unsupported),
        }
    }

    fn sky_point(&self, z: &Vector4<T>) -> Option<SkyPoint<T>> {
        if matches!(self.births, SensorBirths::Off) {
            return None;
        }
        let (angles, sigma) = match self.kind {
            SensorKind::OpticalRaDec => ([z[0], z[1]], self.optical().sigma),
            SensorKind::AzEl => {
                let (direction, sigma) = self.az_el_as_ra_dec(z[0], z[1]);
                ([direction[0], direction[1]], sigma)
            }
            _ => return None,
        };
        Some(SkyPoint { angles, sigma, observer: self.observer })
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

impl<T: Real> MixedLook<T> {
    /// The inertial right ascension and declination of look angles (A, E) in the sensor's frame, and an
    /// isotropic σ for them: σ = max(σ_A cos E, σ_E) across the line of sight, σ / cos δ in α.
    fn az_el_as_ra_dec(&self, azimuth: T, elevation: T) -> (SVector<T, 2>, [T; 2]) {
        let (east, north, up) = (sin(azimuth) * cos(elevation), cos(azimuth) * cos(elevation), sin(elevation));
        let [e, n, u] = self.frame;
        let unit: [T; 3] = core::array::from_fn(|k| east * e[k] + north * n[k] + up * u[k]);
        let horizontal = sqrt(unit[0] * unit[0] + unit[1] * unit[1]);
        let (alpha, delta) = (atan2(unit[1], unit[0]), atan2(unit[2], horizontal));
        let [sigma_azimuth, sigma_elevation, ..] = self.sigma;
        let across = sigma_azimuth * cos(elevation);
        let sigma = if across > sigma_elevation { across } else { sigma_elevation };
        (SVector::from([alpha, delta]), [sigma / cos(delta), sigma])
    }
}

impl<T: Real> OpticalRaDec<T> {
    fn with_sigma(self, sigma: [T; 2]) -> Self {
        Self { sigma, ..self }
    }
}

/// Up to `C` sensors of mixed kinds ([`SensorKind`]) for a 6-state inertial motion model, measurements of
/// [`MIXED_DIMENSION`] components (docs/maths.md §6.10).
///
/// # Examples
/// A radar and a range-only station; a range measurement packed for the second one.
/// ```
/// use tracker_core::model::{KindMeasurement, MixedNetwork, MixedSensor, SensorKind};
/// use tracker_core::sensor::{EarthRotation, GroundSite, LookShape, Platform, Region, Sensor, SiteSensor};
/// let field_of_view = |range_rate| Region::Look {
///     shape: LookShape::Cone { azimuth: 0.0, elevation: 1.2, half_angle: 0.6 },
///     min_elevation: 0.1,
///     range: Some([200.0, 3000.0]),
///     range_rate,
/// };
/// let site = Platform::Ground(GroundSite { latitude: 0.7, longitude: 0.1, height: 0.1 });
/// let sensor = |kind, sigma| MixedSensor {
///     kind,
///     sensor: SiteSensor {
///         platform: site,
///         sigma,
///         detection: Sensor { detection_probability: 0.9, clutter_rate: 1.0, field_of_view: field_of_view(None) },
///     },
/// };
/// let network: MixedNetwork<f64, 4> = MixedNetwork::new(
///     EarthRotation::new(0.0),
///     &[sensor(SensorKind::Radar, [0.02, 5e-4, 5e-4, 0.0]), sensor(SensorKind::Range, [0.005, 0.0, 0.0, 0.0])],
/// )?;
/// let z = network.pack(1, &KindMeasurement::Range(1234.5))?;
/// assert_eq!(z.as_slice(), &[1234.5, 0.0, 0.0, 0.0]);
/// assert!(network.pack(1, &KindMeasurement::AzEl([0.1, 0.2])).is_err());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MixedNetwork<T, const C: usize> {
    rotation: EarthRotation<T>,
    sensors: [MixedSensor<T>; C],
    volumes: [T; C],
    births: [SensorBirths<T>; C],
    light_time: [LightTime; C],
    count: usize,
    current: usize,
    placed: MixedLook<T>,
}

impl<T: Real, const C: usize> MixedNetwork<T, C> {
    /// A network with no sensors, built in a `const` context: the measurement model of a placeholder
    /// configuration, so that a tracker can be a compile-time `static` ([`crate::Tracker::empty`]) whose
    /// run-time configuration is installed in place by [`crate::Tracker::reset_with`]. A tracker refuses
    /// it ([`crate::ConfigError::Sensor`]) and every scan of it fails with an unknown sensor.
    pub const fn unconfigured() -> Self {
        let sensor = MixedSensor {
            kind: SensorKind::Radar,
            sensor: SiteSensor {
                platform: Platform::Spacecraft,
                sigma: [T::ZERO; MIXED_DIMENSION],
                detection: Sensor::UNCONFIGURED,
            },
        };
        Self {
            rotation: EarthRotation { angle_at_epoch: T::ZERO, rate: T::ZERO },
            sensors: [sensor; C],
            volumes: [T::ZERO; C],
            births: [SensorBirths::Off; C],
            light_time: [LightTime::Off; C],
            count: 0,
            current: 0,
            placed: MixedLook {
                kind: SensorKind::Radar,
                observer: [T::ZERO; 6],
                frame: [[T::ZERO; 3]; 3],
                sigma: [T::ZERO; MIXED_DIMENSION],
                births: SensorBirths::Off,
                light_time: LightTime::Off,
            },
        }
    }

    /// A network of `sensors`, placed at the first one at time 0.
    ///
    /// # Errors
    /// A static description of the first invalid part: more sensors than `C`, none, a site outside
    /// latitude [−π/2, π/2] or below 1 km under the ellipsoid, a noise of the kind's components that is
    /// not finite and > 0 or a padded one that is not 0, a field of view that is not a look-angle region
    /// with the windows of what the kind measures, or one of zero (or non-finite) volume in the kind's own
    /// coordinates.
    pub fn new(rotation: EarthRotation<T>, sensors: &[MixedSensor<T>]) -> Result<Self, &'static str> {
        const { assert!(C > 0, "a sensor network needs room for one sensor") };
        let first = first_of_network(&rotation, sensors, C)?;
        let mut network = Self {
            rotation,
            sensors: [*first; C],
            volumes: [T::one(); C],
            births: [SensorBirths::FromModel; C],
            light_time: [LightTime::Off; C],
            count: sensors.len(),
            current: 0,
            placed: MixedLook {
                kind: first.kind,
                observer: [T::zero(); 6],
                frame: inertial_frame(),
                sigma: first.sensor.sigma,
                births: SensorBirths::FromModel,
                light_time: LightTime::Off,
            },
        };
        for (index, sensor) in sensors.iter().enumerate() {
            check_platform(&sensor.sensor)?;
            check_noise(sensor)?;
            // The frame at time 0, as [`super::SensorNetwork::new`] forms it (the same volume's bits).
            let frame = match sensor.sensor.platform {
                Platform::Ground(site) => site.enu(&rotation, T::zero()),
                Platform::Spacecraft => inertial_frame(),
            };
            let volume = kind_volume(sensor.kind, &sensor.sensor.detection.field_of_view, &frame);
            sensor.sensor.detection.validate_parts(sensor.kind.dimension(), Some(sensor.kind.axes()), volume)?;
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

    /// The network with sensor `sensor`'s births from `births` instead of the birth model's region: its
    /// own region (a telescope on the GEO belt beside radars on LEO) or none.
    ///
    /// # Errors
    /// An unknown sensor, or a region that is not valid ([`AdmissibleRegion::validate`]).
    pub fn with_births(mut self, sensor: usize, births: SensorBirths<T>) -> Result<Self, &'static str> {
        self.set_births(sensor, births)?;
        Ok(self)
    }

    /// [`MixedNetwork::with_births`] in place: a caller holding the network in a larger value (a
    /// configuration) sets its sensors' births without moving the network through the stack.
    ///
    /// # Errors
    /// As [`MixedNetwork::with_births`]; the network is then unchanged.
    pub fn set_births(&mut self, sensor: usize, births: SensorBirths<T>) -> Result<(), &'static str> {
        if let SensorBirths::Region(region) = &births {
            region.validate()?;
        }
        let count = self.count;
        let slot = self.births.get_mut(..count).and_then(|all| all.get_mut(sensor));
        let Some(slot) = slot else { return Err("sensor network: births for a sensor it does not have") };
        *slot = births;
        if self.current == sensor {
            self.placed.births = births;
        }
        Ok(())
    }

    /// Where sensor `sensor`'s births come from ([`MixedNetwork::with_births`]).
    pub fn births(&self, sensor: usize) -> SensorBirths<T> {
        self.births.get(..self.count).and_then(|all| all.get(sensor)).copied().unwrap_or_default()
    }

    /// The network with sensor `sensor`'s measurements delayed by light time `mode` (docs/maths.md §6.12;
    /// the maths of [`super::light_time`], as [`super::SensorNetwork::with_light_time`]). Every sensor
    /// starts [`LightTime::Off`], which measures exactly as a network without the setting.
    ///
    /// # Errors
    /// An unknown sensor, or a two-way mode for a kind without a range.
    pub fn with_light_time(mut self, sensor: usize, mode: LightTime) -> Result<Self, &'static str> {
        let Some(kind) = self.sensors().get(sensor).map(|s| s.kind) else {
            return Err("sensor network: light time for an unknown sensor");
        };
        if mode.two_way() && !kind.axes().range {
            return Err("sensor network: two-way light time needs a range measurement");
        }
        if let Some(slot) = self.light_time.get_mut(sensor) {
            *slot = mode;
        }
        if self.current == sensor {
            self.placed.light_time = mode;
        }
        Ok(self)
    }

    /// The light time of sensor `sensor` ([`LightTime::Off`] for an unknown one).
    pub fn light_time(&self, sensor: usize) -> LightTime {
        self.light_time.get(..self.count).and_then(|modes| modes.get(sensor)).copied().unwrap_or_default()
    }

    /// The sensors.
    pub fn sensors(&self) -> &[MixedSensor<T>] {
        self.sensors.get(..self.count).unwrap_or(&[])
    }

    /// The sensor the network is placed at.
    pub fn current_sensor(&self) -> usize {
        self.current
    }

    /// The clutter volume of sensor `index`'s field of view in its own measurement coordinates.
    pub fn volume(&self, index: usize) -> Option<T> {
        self.volumes.get(..self.count).and_then(|volumes| volumes.get(index)).copied()
    }

    /// The model of the current placement.
    pub fn placed(&self) -> &MixedLook<T> {
        &self.placed
    }

    /// The kinds present, each once, in [`SensorKind::ALL`]'s order.
    pub fn kinds(&self) -> impl Iterator<Item = SensorKind> + '_ {
        SensorKind::ALL.into_iter().filter(|kind| self.sensors().iter().any(|sensor| sensor.kind == *kind))
    }

    /// `measurement` as the padded vector a scan of sensor `sensor` takes.
    ///
    /// # Errors
    /// [`KindError`] for an unknown sensor or a measurement of another kind.
    pub fn pack(&self, sensor: usize, measurement: &KindMeasurement<T>) -> Result<Vector4<T>, KindError> {
        let Some(site) = self.sensors().get(sensor) else {
            return Err(KindError::UnknownSensor { sensor, sensors: self.count });
        };
        if site.kind != measurement.kind() {
            return Err(KindError::WrongKind { sensor, expected: site.kind, received: measurement.kind() });
        }
        Ok(measurement.padded())
    }

    fn place_at(&self, sensor: usize, time: f64, observer: Option<[T; 6]>) -> Result<Self, PlacementError> {
        let Some(site) = self.sensors().get(sensor) else {
            return Err(PlacementError::UnknownSensor { sensor, sensors: self.count });
        };
        let (state, frame) = observer_and_frame(&self.rotation, site.sensor.platform, time, observer)?;
        let placed = MixedLook {
            kind: site.kind,
            observer: state,
            frame,
            sigma: site.sensor.sigma,
            births: self.births(sensor),
            light_time: self.light_time(sensor),
        };
        Ok(Self { current: sensor, placed, ..*self })
    }
}

/// The kind's noise components finite and > 0, the padding zero.
fn check_noise<T: Real>(sensor: &MixedSensor<T>) -> Result<(), &'static str> {
    let (own, padding) = sensor.sensor.sigma.split_at(sensor.kind.dimension());
    if !own.iter().all(|&s| s.is_finite_value() && s > T::zero()) {
        return Err("sensor network: every noise standard deviation of the kind's components must be finite and > 0");
    }
    if !padding.iter().all(|&s| s == T::zero()) {
        return Err("sensor network: noise beyond the kind's components must be 0");
    }
    Ok(())
}

impl<T: Real, const C: usize> Measure<T, 6, MIXED_DIMENSION> for MixedNetwork<T, C> {
    fn measure(&self, state: &SVector<T, 6>) -> Vector4<T> {
        self.placed.measure(state)
    }

    fn jacobian(&self, state: &SVector<T, 6>) -> SMatrix<T, 4, 6> {
        self.placed.jacobian(state)
    }

    fn noise_covariance(&self) -> SMatrix<T, 4, 4> {
        self.placed.noise_covariance()
    }

    fn residual(&self, z: &Vector4<T>, predicted: &Vector4<T>) -> Vector4<T> {
        self.placed.residual(z, predicted)
    }

    fn dimension(&self) -> usize {
        self.placed.dimension()
    }

    fn look_of_state(&self, state: &SVector<T, 6>) -> Option<Look<T>> {
        self.placed.look_of_state(state)
    }
}

impl<T: Real, const C: usize> Placement<T, MIXED_DIMENSION> for MixedNetwork<T, C> {
    fn look_axes(&self) -> Option<LookAxes> {
        self.placed.look_axes()
    }

    fn look(&self, z: &Vector4<T>) -> Option<Look<T>> {
        self.placed.look(z)
    }

    fn clutter_volume(&self, region: &Region<T>) -> T {
        match (self.sensors().get(self.current), self.volume(self.current)) {
            (Some(sensor), Some(volume)) if sensor.sensor.detection.field_of_view == *region => volume,
            _ => self.placed.clutter_volume(region),
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
        self.sensors().get(self.current).map(|sensor| sensor.sensor.detection)
    }

    fn fits(&self, z: &Vector4<T>) -> bool {
        self.placed.fits(z)
    }

    fn measurement_in_view(&self, region: &Region<T>, z: &Vector4<T>) -> bool {
        self.placed.measurement_in_view(region, z)
    }
}

impl<T: Real, const C: usize> BirthGeometry<T, 6, MIXED_DIMENSION> for MixedNetwork<T, C> {
    fn birth_components(
        &self,
        z: &Vector4<T>,
        region: &AdmissibleRegion<T>,
        out: &mut [BirthComponent<T, 6>],
    ) -> Result<usize, BirthError> {
        self.placed.birth_components(z, region, out)
    }

    fn sky_point(&self, z: &Vector4<T>) -> Option<SkyPoint<T>> {
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
mod tests;
