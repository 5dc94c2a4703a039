//! A sensor's measurement physics in a version 2 file (docs/scenario-format.md, "Sensor corrections"):
//! its known bias (`bias`, the fields and units of `noise`), its light time (`light_time`) and whether its
//! elevations carry tropospheric refraction (`refraction`). Every field is optional; absent, the sensor
//! measures as before (no bias, no light time, no refraction), except that `host-sim track` takes light
//! time and refraction from the TDMs ([`crate::io::tdm`]) when the configuration does not state them.

use super::{Measurement3dSpec, NoiseSpec, Sensor3dSpec};
use crate::scenario::{ScenarioError, error, finite};
use serde::{Deserialize, Serialize};
use tracker_core::model::LightTime;

/// How light time delays a sensor's measurements (tracker-core's [`LightTime`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum LightTimeSpec {
    /// The object at the scan time.
    #[default]
    Off,
    /// One-way, time tag at reception (a downlink, TDM `PATH = 2,1`): the object at t − τ.
    OneWayReceive,
    /// One-way, time tag at transmission (an uplink, `PATH = 1,2`): the object at t + τ.
    OneWayTransmit,
    /// Two-way (`PATH = 1,2,1`), time tag at reception: bounce at t − τ.
    TwoWayReceive,
    /// Two-way, time tag at transmission: bounce at t + τ.
    TwoWayTransmit,
}

impl LightTimeSpec {
    /// The core's setting.
    pub fn core(self) -> LightTime {
        match self {
            LightTimeSpec::Off => LightTime::Off,
            LightTimeSpec::OneWayReceive => LightTime::OneWayReceive,
            LightTimeSpec::OneWayTransmit => LightTime::OneWayTransmit,
            LightTimeSpec::TwoWayReceive => LightTime::TwoWayReceive,
            LightTimeSpec::TwoWayTransmit => LightTime::TwoWayTransmit,
        }
    }

    /// The name in the file.
    pub fn name(self) -> &'static str {
        match self {
            LightTimeSpec::Off => "off",
            LightTimeSpec::OneWayReceive => "one-way-receive",
            LightTimeSpec::OneWayTransmit => "one-way-transmit",
            LightTimeSpec::TwoWayReceive => "two-way-receive",
            LightTimeSpec::TwoWayTransmit => "two-way-transmit",
        }
    }
}

/// Whether a sensor's measured elevations carry tropospheric refraction.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "model", rename_all = "kebab-case", deny_unknown_fields)]
pub enum RefractionSpec {
    /// The elevations are geometric (already corrected, or simulated without refraction).
    None,
    /// The elevations are apparent: Bennett's refraction ([`crate::sim::refraction`]) is removed on the
    /// way in.
    Bennett {
        /// Pressure at the site (kPa); 101.0 when absent.
        #[serde(default = "standard_pressure")]
        pressure_kpa: f64,
        /// Temperature at the site (°C); 10 when absent.
        #[serde(default = "standard_temperature")]
        temperature_c: f64,
    },
}

fn standard_pressure() -> f64 {
    crate::sim::refraction::Atmosphere::STANDARD.pressure_kpa
}

fn standard_temperature() -> f64 {
    crate::sim::refraction::Atmosphere::STANDARD.temperature_c
}

impl RefractionSpec {
    /// Bennett's refraction in the standard air (101.0 kPa, 10 °C).
    pub const STANDARD: RefractionSpec = RefractionSpec::Bennett {
        pressure_kpa: crate::sim::refraction::Atmosphere::STANDARD.pressure_kpa,
        temperature_c: crate::sim::refraction::Atmosphere::STANDARD.temperature_c,
    };

    /// The air of the model, or `None` without refraction.
    pub fn atmosphere(self) -> Option<crate::sim::refraction::Atmosphere> {
        match self {
            RefractionSpec::None => None,
            RefractionSpec::Bennett { pressure_kpa, temperature_c } => {
                Some(crate::sim::refraction::Atmosphere { pressure_kpa, temperature_c })
            }
        }
    }
}

impl NoiseSpec {
    /// The values per component in the tracker's units (km, rad, km/s), 0 for a field absent.
    pub fn values(&self, kind: Measurement3dSpec) -> Vec<f64> {
        self.sigma_or(kind, 0.0)
    }
}

impl Sensor3dSpec {
    /// The known bias per component in the tracker's units (zeros without `bias`).
    pub fn bias_values(&self, kind: Measurement3dSpec) -> Vec<f64> {
        self.bias.map_or_else(|| vec![0.0; kind.dimension()], |b| b.values(kind))
    }

    /// The air whose refraction the sensor's elevations carry, or `None`.
    pub fn atmosphere(&self) -> Option<crate::sim::refraction::Atmosphere> {
        self.refraction.and_then(RefractionSpec::atmosphere)
    }

    /// The light time of the sensor's measurements (off when absent).
    pub fn light_time_mode(&self) -> LightTime {
        self.light_time.unwrap_or_default().core()
    }

    /// `bias`, `light_time` and `refraction` against the measurement type; errors name `field`.
    pub(super) fn validate_physics(&self, field: &str, kind: Measurement3dSpec) -> Result<(), ScenarioError> {
        if let Some(bias) = &self.bias {
            let wanted = NoiseSpec::fields(kind);
            for name in NoiseSpec::ALL {
                match (bias.get(name), wanted.contains(&name)) {
                    (Some(v), true) => finite(&format!("{field}.bias.{name}"), v)?,
                    (Some(_), false) => {
                        return Err(error(
                            format!("{field}.bias.{name}"),
                            format!("not part of a {} measurement", kind.name()),
                        ));
                    }
                    (None, _) => {}
                }
            }
        }
        if let Some(mode) = self.light_time
            && mode.core().two_way()
            && !kind.has_range()
        {
            return Err(error(
                format!("{field}.light_time"),
                format!("\"{}\" needs a range: a {} measurement has none", mode.name(), kind.name()),
            ));
        }
        match self.refraction {
            Some(RefractionSpec::Bennett { .. }) if kind.sky_in_ra_dec() => Err(error(
                format!("{field}.refraction"),
                "applies to azimuth and elevation: astrometric right ascension and declination, reduced \
                 against catalogue stars, have it removed already",
            )),
            Some(RefractionSpec::Bennett { .. }) if !kind.measures_elevation() => Err(error(
                format!("{field}.refraction"),
                format!("applies to elevations: a {} measurement has none", kind.name()),
            )),
            Some(RefractionSpec::Bennett { pressure_kpa, temperature_c })
                if !(pressure_kpa.is_finite()
                    && (0.0..=120.0).contains(&pressure_kpa)
                    && temperature_c.is_finite()
                    && (-90.0..=60.0).contains(&temperature_c)) =>
            {
                Err(error(
                    format!("{field}.refraction"),
                    "pressure_kpa must be in [0, 120] and temperature_c in [-90, 60]",
                ))
            }
            _ => Ok(()),
        }
    }
}
