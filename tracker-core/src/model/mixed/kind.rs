//! What each sensor of a [`super::MixedNetwork`] measures: its [`SensorKind`], a measurement of a named
//! kind ([`KindMeasurement`]) and the error of a measurement given to a sensor of another kind.

use super::MIXED_DIMENSION;
use crate::real::Real;
use crate::sensor::LookAxes;
use nalgebra::SVector;

/// What a sensor measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum SensorKind {
    /// Range, azimuth, elevation (km, rad, rad).
    Radar,
    /// Range, azimuth, elevation, range-rate (km, rad, rad, km/s).
    RadarRangeRate,
    /// Topocentric right ascension and declination (rad).
    OpticalRaDec,
    /// Azimuth and elevation only (rad): a ground station's mount angles.
    AzEl,
    /// Range only (km).
    Range,
    /// Range and range-rate (km, km/s).
    RangeRangeRate,
}

impl SensorKind {
    /// Every kind, in a fixed order.
    pub const ALL: [SensorKind; 6] = [
        SensorKind::Radar,
        SensorKind::RadarRangeRate,
        SensorKind::OpticalRaDec,
        SensorKind::AzEl,
        SensorKind::Range,
        SensorKind::RangeRangeRate,
    ];

    /// How many components it measures.
    pub const fn dimension(self) -> usize {
        match self {
            SensorKind::Radar => 3,
            SensorKind::RadarRangeRate => 4,
            SensorKind::OpticalRaDec | SensorKind::AzEl | SensorKind::RangeRangeRate => 2,
            SensorKind::Range => 1,
        }
    }

    /// Its components in order, by name.
    pub const fn components(self) -> &'static [&'static str] {
        match self {
            SensorKind::Radar => &["range", "azimuth", "elevation"],
            SensorKind::RadarRangeRate => &["range", "azimuth", "elevation", "range_rate"],
            SensorKind::OpticalRaDec => &["right_ascension", "declination"],
            SensorKind::AzEl => &["azimuth", "elevation"],
            SensorKind::Range => &["range"],
            SensorKind::RangeRangeRate => &["range", "range_rate"],
        }
    }

    /// The look coordinates besides the angles that it measures (the windows its field of view has).
    pub const fn axes(self) -> LookAxes {
        match self {
            SensorKind::Radar | SensorKind::Range => LookAxes { range: true, range_rate: false },
            SensorKind::RadarRangeRate | SensorKind::RangeRangeRate => LookAxes { range: true, range_rate: true },
            SensorKind::OpticalRaDec | SensorKind::AzEl => LookAxes { range: false, range_rate: false },
        }
    }

    /// Whether it measures angles.
    pub const fn measures_angles(self) -> bool {
        !matches!(self, SensorKind::Range | SensorKind::RangeRangeRate)
    }

    /// A short name (also the scenario files' spelling).
    pub const fn name(self) -> &'static str {
        match self {
            SensorKind::Radar => "radar",
            SensorKind::RadarRangeRate => "radar_range_rate",
            SensorKind::OpticalRaDec => "optical",
            SensorKind::AzEl => "az_el",
            SensorKind::Range => "range",
            SensorKind::RangeRangeRate => "range_range_rate",
        }
    }
}

impl core::fmt::Display for SensorKind {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.name())
    }
}

/// One measurement of a named kind: what a caller hands to [`MixedNetwork::pack`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum KindMeasurement<T> {
    /// (ρ, A, E).
    Radar([T; 3]),
    /// (ρ, A, E, ρ̇).
    RadarRangeRate([T; 4]),
    /// (α, δ).
    OpticalRaDec([T; 2]),
    /// (A, E).
    AzEl([T; 2]),
    /// ρ.
    Range(T),
    /// (ρ, ρ̇).
    RangeRangeRate([T; 2]),
}

impl<T: Real> KindMeasurement<T> {
    /// Its kind.
    pub const fn kind(&self) -> SensorKind {
        match self {
            KindMeasurement::Radar(_) => SensorKind::Radar,
            KindMeasurement::RadarRangeRate(_) => SensorKind::RadarRangeRate,
            KindMeasurement::OpticalRaDec(_) => SensorKind::OpticalRaDec,
            KindMeasurement::AzEl(_) => SensorKind::AzEl,
            KindMeasurement::Range(_) => SensorKind::Range,
            KindMeasurement::RangeRangeRate(_) => SensorKind::RangeRangeRate,
        }
    }

    /// The padded vector: its components first, zeros after.
    pub fn padded(&self) -> SVector<T, MIXED_DIMENSION> {
        let o = T::zero();
        SVector::from(match *self {
            KindMeasurement::Radar([a, b, c]) => [a, b, c, o],
            KindMeasurement::RadarRangeRate(z) => z,
            KindMeasurement::OpticalRaDec([a, b]) | KindMeasurement::AzEl([a, b]) => [a, b, o, o],
            KindMeasurement::RangeRangeRate([a, b]) => [a, b, o, o],
            KindMeasurement::Range(a) => [a, o, o, o],
        })
    }
}

/// A measurement of the wrong kind for the sensor it was given to ([`MixedNetwork::pack`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum KindError {
    /// The network has no such sensor.
    UnknownSensor {
        /// The index given.
        sensor: usize,
        /// How many sensors there are.
        sensors: usize,
    },
    /// The measurement's kind is not the sensor's.
    WrongKind {
        /// The sensor's index.
        sensor: usize,
        /// The sensor's kind.
        expected: SensorKind,
        /// The measurement's kind.
        received: SensorKind,
    },
}

impl core::fmt::Display for KindError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            KindError::UnknownSensor { sensor, sensors } => {
                write!(f, "sensor {sensor} is unknown (the network has {sensors})")
            }
            KindError::WrongKind { sensor, expected, received } => {
                write!(f, "sensor {sensor} measures {expected}, not {received}")
            }
        }
    }
}

impl core::error::Error for KindError {}
