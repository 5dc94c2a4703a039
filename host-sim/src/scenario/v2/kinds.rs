//! What a version 2 file's sensors measure: one kind for every sensor (`measurement`), or `network` with a
//! kind per sensor (`sensors[i].kind`), the core's sensor networks of mixed kinds
//! ([`tracker_core::model::MixedNetwork`]).

use serde::{Deserialize, Serialize};
use tracker_core::model::{AdmissibleRegion, MIXED_DIMENSION, SensorKind};

/// What the sensors measure.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "kebab-case", deny_unknown_fields)]
pub enum Measurement3dSpec {
    /// Radar: [range (km), azimuth (deg), elevation (deg)].
    Radar,
    /// Radar with range-rate: [range (km), azimuth (deg), elevation (deg), range-rate (km/s)].
    RadarRangeRate,
    /// Telescope: [right ascension (deg), declination (deg)], topocentric.
    Optical,
    /// A ground station's mount angles only: [azimuth (deg), elevation (deg)].
    AzEl,
    /// Range only: [range (km)].
    Range,
    /// Range and range-rate: [range (km), range-rate (km/s)].
    RangeRangeRate,
    /// Sensors of mixed kinds, each naming its own (`sensors[i].kind`); never a sensor's kind.
    Network,
}

impl Measurement3dSpec {
    /// Every kind a sensor can have, in the core's order ([`SensorKind::ALL`]).
    pub const SENSOR_KINDS: [Measurement3dSpec; 6] = [
        Measurement3dSpec::Radar,
        Measurement3dSpec::RadarRangeRate,
        Measurement3dSpec::Optical,
        Measurement3dSpec::AzEl,
        Measurement3dSpec::Range,
        Measurement3dSpec::RangeRangeRate,
    ];

    /// Components of one measurement (`network`: the core's padded vector, [`MIXED_DIMENSION`]).
    pub fn dimension(self) -> usize {
        self.core().map_or(MIXED_DIMENSION, SensorKind::dimension)
    }

    /// The name in the file.
    pub fn name(self) -> &'static str {
        match self {
            Measurement3dSpec::Radar => "radar",
            Measurement3dSpec::RadarRangeRate => "radar-range-rate",
            Measurement3dSpec::Optical => "optical",
            Measurement3dSpec::AzEl => "az-el",
            Measurement3dSpec::Range => "range",
            Measurement3dSpec::RangeRangeRate => "range-range-rate",
            Measurement3dSpec::Network => "network",
        }
    }

    /// The core's sensor kind (`None` for `network`).
    pub fn core(self) -> Option<SensorKind> {
        match self {
            Measurement3dSpec::Radar => Some(SensorKind::Radar),
            Measurement3dSpec::RadarRangeRate => Some(SensorKind::RadarRangeRate),
            Measurement3dSpec::Optical => Some(SensorKind::OpticalRaDec),
            Measurement3dSpec::AzEl => Some(SensorKind::AzEl),
            Measurement3dSpec::Range => Some(SensorKind::Range),
            Measurement3dSpec::RangeRangeRate => Some(SensorKind::RangeRangeRate),
            Measurement3dSpec::Network => None,
        }
    }

    /// Whether the core tracks it with a network of mixed kinds ([`tracker_core::model::MixedNetwork`]):
    /// `network`, and the kinds that have no single-kind model of their own.
    pub fn needs_mixed_network(self) -> bool {
        matches!(
            self,
            Measurement3dSpec::Network
                | Measurement3dSpec::AzEl
                | Measurement3dSpec::Range
                | Measurement3dSpec::RangeRangeRate
        )
    }

    /// Which components are angles (degrees in the file, radians in the tracker).
    pub fn is_angle(self, component: usize) -> bool {
        match self {
            Measurement3dSpec::Radar | Measurement3dSpec::RadarRangeRate => component == 1 || component == 2,
            Measurement3dSpec::Optical | Measurement3dSpec::AzEl => component < 2,
            Measurement3dSpec::Range | Measurement3dSpec::RangeRangeRate | Measurement3dSpec::Network => false,
        }
    }

    /// Whether the measurement's `component` is an azimuth or a right ascension (wrapped to
    /// (−180°, 180°] on the way in, [`crate::io::angles`]).
    pub fn wraps(self, component: usize) -> bool {
        match self {
            Measurement3dSpec::Radar | Measurement3dSpec::RadarRangeRate => component == 1,
            Measurement3dSpec::Optical | Measurement3dSpec::AzEl => component == 0,
            Measurement3dSpec::Range | Measurement3dSpec::RangeRangeRate | Measurement3dSpec::Network => false,
        }
    }

    /// Whether a measurement holds the range.
    pub fn has_range(self) -> bool {
        self.core().is_some_and(|kind| kind.axes().range)
    }

    /// Whether a measurement holds the range-rate.
    pub fn has_range_rate(self) -> bool {
        self.core().is_some_and(|kind| kind.axes().range_rate)
    }

    /// Whether a measurement holds an elevation (radar kinds and az/el).
    pub fn measures_elevation(self) -> bool {
        matches!(self, Measurement3dSpec::Radar | Measurement3dSpec::RadarRangeRate | Measurement3dSpec::AzEl)
    }

    /// Whether the sky is drawn in right ascension and declination (a telescope's frame) rather than
    /// azimuth and elevation.
    pub fn sky_in_ra_dec(self) -> bool {
        self == Measurement3dSpec::Optical
    }

    /// Whether the sensor measures no angle (range, range and range-rate): its plot is range against time.
    pub fn sky_in_range(self) -> bool {
        matches!(self, Measurement3dSpec::Range | Measurement3dSpec::RangeRangeRate)
    }

    /// The components' names, in order, with the ranges the file accepts (degrees, km, km/s).
    pub fn components(self) -> (&'static [&'static str], &'static [(f64, f64)]) {
        const TURN: (f64, f64) = crate::io::angles::ACCEPTED_TURN;
        const RANGE: (f64, f64) = (0.0, f64::INFINITY);
        const ELEVATION: (f64, f64) = (-90.0, 90.0);
        const ANY: (f64, f64) = (f64::NEG_INFINITY, f64::INFINITY);
        match self {
            Measurement3dSpec::Radar => (&["range", "azimuth", "elevation"], &[RANGE, TURN, ELEVATION]),
            Measurement3dSpec::RadarRangeRate => {
                (&["range", "azimuth", "elevation", "range-rate"], &[RANGE, TURN, ELEVATION, ANY])
            }
            Measurement3dSpec::Optical => (&["right ascension", "declination"], &[TURN, ELEVATION]),
            Measurement3dSpec::AzEl => (&["azimuth", "elevation"], &[TURN, ELEVATION]),
            Measurement3dSpec::Range => (&["range"], &[RANGE]),
            Measurement3dSpec::RangeRangeRate => (&["range", "range-rate"], &[RANGE, ANY]),
            Measurement3dSpec::Network => (&[], &[]),
        }
    }

    /// The most birth components one measurement can give in the admissible region `region`: radar
    /// headings × speeds × climbs (the range fixes the rest), with range-rate headings × speeds (across the
    /// line of sight); for the angle kinds the region's bound ([`AdmissibleRegion::max_components`]); none
    /// for the range kinds (their objects are born from another sensor's measurements) and for `network`
    /// (see [`super::Scenario3d::kind`]).
    pub fn birth_components(self, region: &AdmissibleRegion<f64>) -> usize {
        match self {
            Measurement3dSpec::Radar => region.headings.saturating_mul(region.speeds).saturating_mul(region.climbs),
            Measurement3dSpec::RadarRangeRate => region.headings.saturating_mul(region.speeds),
            Measurement3dSpec::Optical | Measurement3dSpec::AzEl => region.max_components(),
            Measurement3dSpec::Range | Measurement3dSpec::RangeRangeRate | Measurement3dSpec::Network => 0,
        }
    }

    /// The sensor kind named `name` (never `network`).
    pub fn sensor_kind_named(name: &str) -> Option<Self> {
        Self::SENSOR_KINDS.into_iter().find(|kind| kind.name() == name)
    }
}

/// `sensors[i].kind` as a plain string (`"kind": "az-el"`).
pub(super) mod sensor_kind {
    use super::Measurement3dSpec;
    use serde::{Deserialize, Deserializer, Serializer};

    #[allow(clippy::ref_option)]
    pub fn serialize<S: Serializer>(kind: &Option<Measurement3dSpec>, serializer: S) -> Result<S::Ok, S::Error> {
        match kind {
            Some(kind) => serializer.serialize_str(kind.name()),
            None => serializer.serialize_none(),
        }
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(deserializer: D) -> Result<Option<Measurement3dSpec>, D::Error> {
        let name = String::deserialize(deserializer)?;
        Measurement3dSpec::sensor_kind_named(&name).map(Some).ok_or_else(|| {
            let names: Vec<&str> = Measurement3dSpec::SENSOR_KINDS.iter().map(|k| k.name()).collect();
            serde::de::Error::custom(format!("unknown sensor kind \"{name}\": expected one of {}", names.join(", ")))
        })
    }
}
