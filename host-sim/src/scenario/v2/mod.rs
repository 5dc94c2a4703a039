//! Scenario files of version 2 (format `rfisst-scenario/2`): 3-D SSA geometry with a UTC epoch, two-body + J2
//! motion, radar or telescope measurements from several ground sensors, and per-scan sensor indices
//! (documented field by field in `docs/scenario-format.md`, "Version 2").
//!
//! Units in the file: km, km/s, seconds since the epoch; every angle in degrees (latitude, longitude,
//! fields of view, measured azimuth, elevation, right ascension and declination) except the noise of an
//! angle, in arcseconds. [`Scenario3d::load`] checks everything the tracker relies on and reports the first
//! problem as a one-line [`ScenarioError`] naming the field; [`load_any`] reads either version.

use crate::scenario::{
    BirthDetectionSpec, EvaluationSpec, MAX_PRIOR_LABEL, ScenarioError, TrackerSpec, TruthObjectSpec, error, finite,
    finite_all, positive,
};
use serde::{Deserialize, Serialize};
use std::path::Path;
use tracker_core::MotionModel;

mod checks;
mod kinds;
mod physics;
pub use checks::check_sensor_names;
use checks::{check_measurement, covariance6};
pub use kinds::Measurement3dSpec;
pub use physics::{LightTimeSpec, RefractionSpec};

/// The format tag of a version 2 file.
pub const FORMAT_V2: &str = "rfisst-scenario/2";

/// The lowest site height (km): deeper is inside the Earth.
pub const MIN_SITE_HEIGHT: f64 = -1.0;

/// The highest site height (km) of a ground site.
pub const MAX_SITE_HEIGHT: f64 = 100.0;

/// The largest number of sensors (the host's networks, [`crate::pipeline::orbital::C`]).
pub const MAX_SENSORS: usize = crate::pipeline::orbital::C;

/// A version 2 scenario.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scenario3d {
    /// Must be [`FORMAT_V2`].
    pub format: String,
    /// Must be 2.
    pub version: u32,
    /// Short name.
    pub name: String,
    /// Free text.
    #[serde(default)]
    pub description: String,
    /// The time every `time` counts from.
    pub epoch: EpochSpec,
    /// How objects move.
    pub motion: Motion3dSpec,
    /// What every sensor measures, or `network`: each sensor's own `kind` ([`Scenario3d::kind`]).
    pub measurement: Measurement3dSpec,
    /// The sensors; a scan names one by its index.
    pub sensors: Vec<Sensor3dSpec>,
    /// Birth model (`cells` may be empty).
    pub birth: Birth3dSpec,
    /// β: probability that an object in the scan's field of view dies before the scan.
    pub death_probability: f64,
    /// Tracker settings (as in version 1).
    pub tracker: TrackerSpec,
    /// The prior hypotheses.
    pub prior: Prior3dSpec,
    /// The scans, in time order.
    pub scans: Vec<Scan3dSpec>,
    /// Ground truth, when known.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub truth: Option<Truth3dSpec>,
    /// How results are scored (lengths in km).
    #[serde(default)]
    pub evaluation: EvaluationSpec,
}

/// The epoch: a UTC time, a Julian date, or both (then they must agree within 1 ms). UT1 = UTC is assumed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EpochSpec {
    /// `YYYY-MM-DDTHH:MM:SS[.fff][Z]`, UTC.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub utc: Option<String>,
    /// Julian date (UTC).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub julian_date: Option<f64>,
}

/// Motion model.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "kebab-case", deny_unknown_fields)]
pub enum Motion3dSpec {
    /// Two-body + J2 about the Earth (WGS-84 μ, R_E; EGM-96 J2), inertial frame (TEME).
    TwoBodyJ2 {
        /// White acceleration noise.
        process_noise: ProcessNoiseSpec,
        /// Largest RK4 sub-step (s).
        max_step: f64,
        /// Most sub-steps per prediction: the longest gap between scans is `max_step × max_substeps`.
        max_substeps: u32,
    },
}

/// White acceleration noise (spectral densities, km²/s³).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "kebab-case", deny_unknown_fields)]
pub enum ProcessNoiseSpec {
    /// The same density along every inertial axis.
    Isotropic {
        /// q (km²/s³).
        q: f64,
    },
    /// Densities along radial, in-track and cross-track.
    Ric {
        /// Radial (km²/s³).
        radial: f64,
        /// In-track (km²/s³).
        in_track: f64,
        /// Cross-track (km²/s³).
        cross_track: f64,
    },
}

/// A ground site on WGS-84.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SiteSpec {
    /// Geodetic latitude (deg), [−90, 90].
    pub latitude_deg: f64,
    /// Longitude (deg, East positive), [−360, 360].
    pub longitude_deg: f64,
    /// Height above the ellipsoid (km), [−1, 100].
    pub height_km: f64,
}

/// Noise standard deviation per measurement component: exactly the fields of the measurement type.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NoiseSpec {
    /// Radar range (km).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub range_km: Option<f64>,
    /// Radar azimuth (arcsec).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub azimuth_arcsec: Option<f64>,
    /// Radar elevation (arcsec).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub elevation_arcsec: Option<f64>,
    /// Radar range-rate (km/s).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub range_rate_km_s: Option<f64>,
    /// Telescope right ascension (arcsec).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub right_ascension_arcsec: Option<f64>,
    /// Telescope declination (arcsec).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub declination_arcsec: Option<f64>,
}

/// Degrees per arcsecond.
const DEG_PER_ARCSEC: f64 = 1.0 / 3600.0;

impl NoiseSpec {
    /// The named fields of a measurement type, in component order, with their unit factor to the tracker's
    /// units (km, rad, km/s).
    fn fields(kind: Measurement3dSpec) -> &'static [&'static str] {
        match kind {
            Measurement3dSpec::Radar => &["range_km", "azimuth_arcsec", "elevation_arcsec"],
            Measurement3dSpec::RadarRangeRate => &["range_km", "azimuth_arcsec", "elevation_arcsec", "range_rate_km_s"],
            Measurement3dSpec::Optical => &["right_ascension_arcsec", "declination_arcsec"],
            Measurement3dSpec::AzEl => &["azimuth_arcsec", "elevation_arcsec"],
            Measurement3dSpec::Range => &["range_km"],
            Measurement3dSpec::RangeRangeRate => &["range_km", "range_rate_km_s"],
            Measurement3dSpec::Network => &[],
        }
    }

    /// Every field's name.
    const ALL: [&'static str; 6] = [
        "range_km",
        "azimuth_arcsec",
        "elevation_arcsec",
        "range_rate_km_s",
        "right_ascension_arcsec",
        "declination_arcsec",
    ];

    fn get(&self, field: &str) -> Option<f64> {
        match field {
            "range_km" => self.range_km,
            "azimuth_arcsec" => self.azimuth_arcsec,
            "elevation_arcsec" => self.elevation_arcsec,
            "range_rate_km_s" => self.range_rate_km_s,
            "right_ascension_arcsec" => self.right_ascension_arcsec,
            "declination_arcsec" => self.declination_arcsec,
            _ => None,
        }
    }

    /// σ per component in the tracker's units (km, rad, km/s).
    pub fn sigma(&self, kind: Measurement3dSpec) -> Vec<f64> {
        self.sigma_or(kind, f64::NAN)
    }

    /// The values per component in the tracker's units, `absent` for a field not given.
    fn sigma_or(&self, kind: Measurement3dSpec, absent: f64) -> Vec<f64> {
        Self::fields(kind)
            .iter()
            .map(|f| {
                let v = self.get(f).unwrap_or(absent);
                if f.ends_with("_arcsec") { (v * DEG_PER_ARCSEC).to_radians() } else { v }
            })
            .collect()
    }
}

/// Look directions of a field of view, in the site's East-North-Up frame (azimuth from North towards East).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "kebab-case", deny_unknown_fields)]
pub enum ShapeSpec {
    /// Every direction within `half_angle_deg` of the boresight.
    Cone {
        /// Boresight azimuth (deg).
        azimuth_deg: f64,
        /// Boresight elevation (deg), [−90, 90].
        elevation_deg: f64,
        /// Half opening angle (deg), (0, 180].
        half_angle_deg: f64,
    },
    /// Azimuths within `half_width_deg` of `azimuth_deg`, elevations in `elevation_deg`.
    Box {
        /// Centre azimuth (deg).
        azimuth_deg: f64,
        /// Half azimuth extent (deg), (0, 180].
        half_width_deg: f64,
        /// [min, max] elevation (deg), within [−90, 90], max > min.
        elevation_deg: [f64; 2],
    },
}

/// A sensor's field of view.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FieldOfView3dSpec {
    /// The cone or box.
    pub shape: ShapeSpec,
    /// Elevation mask (deg), [−90, 90].
    pub min_elevation_deg: f64,
    /// [min, max] range (km): required for radar, absent for optical.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub range_km: Option<[f64; 2]>,
    /// [min, max] range-rate (km/s): required for `radar-range-rate`, absent otherwise.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub range_rate_km_s: Option<[f64; 2]>,
}

/// One sensor.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Sensor3dSpec {
    /// Name (for plots and messages).
    pub name: String,
    /// What it measures: required when the scenario's `measurement` is `network`, else absent or the same.
    #[serde(default, skip_serializing_if = "Option::is_none", with = "kinds::sensor_kind")]
    pub kind: Option<Measurement3dSpec>,
    /// Births from this sensor's measurements in this admissible region instead of `birth.measured`'s
    /// (its other settings apply), or none; only under the measurement type network.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub birth_region: Option<crate::scenario::BirthRegionSpec>,
    /// Where it stands.
    pub site: SiteSpec,
    /// Measurement noise.
    pub noise: NoiseSpec,
    /// What it sees.
    pub field_of_view: FieldOfView3dSpec,
    /// p_D in (0, 1].
    pub detection_probability: f64,
    /// Expected clutter returns per scan (> 0).
    pub clutter_rate: f64,
    /// Known constant bias per component (the fields and units of `noise`), subtracted from every
    /// measurement on the way in; absent: none ([`physics`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bias: Option<NoiseSpec>,
    /// Light time of the measurements; absent: off (`track`: as the TDM states).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub light_time: Option<LightTimeSpec>,
    /// Whether the elevations carry tropospheric refraction; absent: none (`track`: Bennett for AZEL TDMs).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub refraction: Option<RefractionSpec>,
}

/// A Gaussian over the 6-state (x, y, z, vx, vy, vz; km, km/s), inertial.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Gaussian6Spec {
    /// Mean.
    pub mean: [f64; 6],
    /// Covariance, symmetric positive definite.
    pub covariance: [[f64; 6]; 6],
}

/// Birth model.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Birth3dSpec {
    /// α per cell per scan.
    pub probability: f64,
    /// Detection rule.
    #[serde(default)]
    pub detection: BirthDetectionSpec,
    /// At most one birth per scan, or independent births in every cell.
    #[serde(default, skip_serializing_if = "crate::scenario::is_default")]
    pub events: crate::scenario::BirthEventsSpec,
    /// Birth cells made from the measurements (docs/maths.md §5.8).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub measured: Option<crate::scenario::MeasuredBirthsSpec>,
    /// Birth pdf of each cell (may be empty).
    pub cells: Vec<Gaussian6Spec>,
}

/// One prior object.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PriorObject3dSpec {
    /// Label.
    pub label: u32,
    /// Mean (km, km/s).
    pub mean: [f64; 6],
    /// Covariance.
    pub covariance: [[f64; 6]; 6],
}

/// One prior hypothesis.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PriorHypothesis3dSpec {
    /// Relative weight (≥ 0).
    pub weight: f64,
    /// Objects.
    pub objects: Vec<PriorObject3dSpec>,
}

/// The prior.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Prior3dSpec {
    /// Time of the prior (s since the epoch).
    pub time: f64,
    /// Hypotheses.
    pub hypotheses: Vec<PriorHypothesis3dSpec>,
}

/// One scan of one sensor.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scan3dSpec {
    /// Time (s since the epoch), strictly after the previous scan and the prior.
    pub time: f64,
    /// Index into `sensors`.
    pub sensor: usize,
    /// Measurements, each with the components of the measurement type (angles in degrees).
    pub measurements: Vec<Vec<f64>>,
}

/// The true state of one object at a scan.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TruthState3dSpec {
    /// Object id.
    pub id: u64,
    /// Inertial state (km, km/s).
    pub state: [f64; 6],
}

/// The truth of one scan.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TruthScan3dSpec {
    /// Every object that exists at the scan time (in view or not).
    pub objects: Vec<TruthState3dSpec>,
    /// Per measurement, the id of the object that produced it, or `null` for clutter; optional.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub origins: Option<Vec<Option<u64>>>,
}

/// Ground truth.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Truth3dSpec {
    /// The objects (as in version 1).
    pub objects: Vec<TruthObjectSpec>,
    /// One entry per scan.
    pub scans: Vec<TruthScan3dSpec>,
}

impl Scenario3d {
    /// Reads and checks a version 2 file.
    ///
    /// # Errors
    /// A one-line [`ScenarioError`] naming the file's problem.
    pub fn load(path: &Path) -> Result<Self, ScenarioError> {
        match super::load_any(path)? {
            super::AnyScenario::V2(s) => Ok(*s),
            super::AnyScenario::V1(_) => Err(error("version", "this is a version 1 file; version 2 expected")),
        }
    }

    /// Parses and checks a version 2 scenario from JSON text.
    ///
    /// # Errors
    /// A one-line [`ScenarioError`] naming the field.
    pub fn from_json(text: &str) -> Result<Self, ScenarioError> {
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let deserializer = &mut serde_json::Deserializer::from_str(text);
        let scenario: Scenario3d = serde_path_to_error::deserialize(&mut *deserializer).map_err(|e| {
            let path = e.path().to_string();
            let message = e.into_inner().to_string();
            if path == "." { error("invalid scenario JSON", message) } else { error(path, message) }
        })?;
        deserializer.end().map_err(|e| error("invalid scenario JSON", e))?;
        scenario.validate()?;
        Ok(scenario)
    }

    /// Writes the scenario as JSON (compact: the presets' truth is large).
    ///
    /// # Errors
    /// [`crate::Error::Output`] when the file cannot be written.
    pub fn save(&self, path: &Path) -> Result<(), crate::Error> {
        crate::io::atomic::write_json(path, self, false)
    }

    /// The epoch as a Julian date (UTC = UT1).
    pub fn epoch_jd(&self) -> f64 {
        match (&self.epoch.julian_date, &self.epoch.utc) {
            (Some(jd), _) => *jd,
            (None, Some(utc)) => crate::sim::time::parse_iso8601(utc).unwrap_or(f64::NAN),
            (None, None) => f64::NAN,
        }
    }

    /// The Earth rotation angle at the epoch: GMST (IAU-82) of the epoch's Julian date.
    pub fn earth_rotation_at_epoch(&self) -> f64 {
        tracker_core::sensor::gmst_iau82(self.epoch_jd())
    }

    /// The core's motion model.
    pub fn motion_model(&self) -> tracker_core::TwoBodyJ2<f64> {
        let Motion3dSpec::TwoBodyJ2 { process_noise, max_step, max_substeps } = self.motion;
        let noise = match process_noise {
            ProcessNoiseSpec::Isotropic { q } => tracker_core::model::ProcessNoise::Isotropic(q),
            ProcessNoiseSpec::Ric { radial, in_track, cross_track } => {
                tracker_core::model::ProcessNoise::Ric { radial, in_track, cross_track }
            }
        };
        tracker_core::TwoBodyJ2::<f64>::earth(noise, max_step, max_substeps)
    }

    /// The largest number of measurements in one scan.
    pub fn max_measurements(&self) -> usize {
        self.scans.iter().map(|s| s.measurements.len()).max().unwrap_or(0)
    }

    /// What sensor `sensor` measures: its own `kind`, else the scenario's `measurement`.
    pub fn kind(&self, sensor: usize) -> Measurement3dSpec {
        self.sensors.get(sensor).map_or(self.measurement, |s| s.kind_under(self.measurement))
    }

    /// The kinds of the sensors, each once, in the core's order ([`Measurement3dSpec::SENSOR_KINDS`]).
    pub fn sensor_kinds(&self) -> Vec<Measurement3dSpec> {
        let present: Vec<Measurement3dSpec> = (0..self.sensors.len()).map(|i| self.kind(i)).collect();
        Measurement3dSpec::SENSOR_KINDS.into_iter().filter(|kind| present.contains(kind)).collect()
    }

    /// Whether every birth cell comes from a tracklet: `birth.measured.tracklets` with `single_frame` false
    /// and no `link_waiting`, no fixed cells, and only sensors of directions (optical, az/el) with no birth
    /// region of their own.
    pub fn births_from_tracklets_only(&self) -> bool {
        let tracklets_only =
            self.birth.measured.is_some_and(|m| m.tracklets.is_some_and(|t| !t.single_frame) && !m.link_waiting);
        tracklets_only
            && self.birth.cells.is_empty()
            && self.sensors.iter().all(|s| s.birth_region.is_none())
            && (0..self.sensors.len())
                .all(|i| matches!(self.kind(i), Measurement3dSpec::Optical | Measurement3dSpec::AzEl))
    }

    /// Objects of the prior's largest hypothesis.
    pub fn max_prior_objects(&self) -> usize {
        self.prior.hypotheses.iter().map(|h| h.objects.len()).max().unwrap_or(0)
    }

    /// Checks everything the tracker relies on that the JSON types cannot express.
    ///
    /// # Errors
    /// The first problem found.
    pub fn validate(&self) -> Result<(), ScenarioError> {
        if self.format != FORMAT_V2 {
            return Err(error("format", format!("expected \"{FORMAT_V2}\", found \"{}\"", self.format)));
        }
        if self.version != 2 {
            return Err(error("version", format!("expected 2, found {}", self.version)));
        }
        self.validate_epoch()?;
        self.validate_motion()?;
        if self.sensors.is_empty() {
            return Err(error("sensors", "needs at least one sensor"));
        }
        if self.sensors.len() > MAX_SENSORS {
            return Err(error(
                "sensors",
                format!("{} sensors exceed the tracker's capacity of {MAX_SENSORS}", self.sensors.len()),
            ));
        }
        check_sensor_names(self.sensors.iter().map(|s| s.name.as_str()))?;
        for (i, sensor) in self.sensors.iter().enumerate() {
            sensor.validate_kind(i, self.measurement)?;
            sensor.validate(&format!("sensors[{i}]"), self.kind(i))?;
        }
        self.validate_births()?;
        self.validate_prior()?;
        self.validate_scans()?;
        if let Some(truth) = &self.truth {
            truth.validate(&self.scans)?;
        }
        self.evaluation.validate()
    }

    /// Sensor `sensor`'s admissible region for births: its own, else `birth.measured`'s (`None` without
    /// measured births, or when the sensor's births are off).
    pub fn birth_region(&self, sensor: usize) -> Option<tracker_core::model::AdmissibleRegion<f64>> {
        use tracker_core::model::SensorBirths;
        let measured = self.birth.measured.as_ref()?;
        match self.sensors.get(sensor).and_then(|s| s.birth_region).map(|b| b.core()) {
            None | Some(SensorBirths::FromModel) => Some(measured.core().region),
            Some(SensorBirths::Region(region)) => Some(region),
            Some(SensorBirths::Off) => None,
        }
    }

    fn validate_epoch(&self) -> Result<(), ScenarioError> {
        let from_utc = match &self.epoch.utc {
            Some(utc) => Some(crate::sim::time::parse_iso8601(utc).map_err(|e| error("epoch.utc", e))?),
            None => None,
        };
        match (from_utc, self.epoch.julian_date) {
            (None, None) => Err(error("epoch", "needs \"utc\" or \"julian_date\"")),
            (_, Some(jd)) if !(jd.is_finite() && (2_415_020.5..=2_488_069.5).contains(&jd)) => {
                Err(error("epoch.julian_date", format!("{jd} is not a date between 1900 and 2100")))
            }
            (Some(a), Some(b)) if (a - b).abs() * 86_400.0 > 1e-3 => Err(error(
                "epoch",
                format!("utc (JD {a}) and julian_date ({b}) differ by {:.3} s", (a - b).abs() * 86_400.0),
            )),
            _ => Ok(()),
        }
    }

    fn validate_motion(&self) -> Result<(), ScenarioError> {
        let Motion3dSpec::TwoBodyJ2 { process_noise, max_step, max_substeps } = self.motion;
        match process_noise {
            ProcessNoiseSpec::Isotropic { q } => positive("motion.process_noise.q", q)?,
            ProcessNoiseSpec::Ric { radial, in_track, cross_track } => {
                positive("motion.process_noise.radial", radial)?;
                positive("motion.process_noise.in_track", in_track)?;
                positive("motion.process_noise.cross_track", cross_track)?;
            }
        }
        positive("motion.max_step", max_step)?;
        if max_substeps == 0 {
            return Err(error("motion.max_substeps", "must be > 0"));
        }
        Ok(())
    }

    fn validate_births(&self) -> Result<(), ScenarioError> {
        let alpha = self.birth.probability;
        if !(alpha.is_finite() && (0.0..=1.0).contains(&alpha)) {
            return Err(error("birth.probability", format!("{} is not in [0, 1]", crate::scenario::Readable(alpha))));
        }
        if let Some(measured) = &self.birth.measured {
            measured.validate(self.birth.events)?;
        }
        for (i, cell) in self.birth.cells.iter().enumerate() {
            finite_all(&format!("birth.cells[{i}].mean"), &cell.mean)?;
            covariance6(&format!("birth.cells[{i}].covariance"), &cell.covariance)?;
        }
        let beta = self.death_probability;
        if !(beta.is_finite() && (0.0..=1.0).contains(&beta)) {
            return Err(error("death_probability", format!("{} is not in [0, 1]", crate::scenario::Readable(beta))));
        }
        if let Some(gate) = self.tracker.gate {
            positive("tracker.gate", gate)?;
        }
        if self.tracker.max_children_per_scan == 0 {
            return Err(error("tracker.max_children_per_scan", "must be > 0"));
        }
        if self.tracker.sampler.steps == 0 {
            return Err(error("tracker.sampler.steps", "must be > 0"));
        }
        Ok(())
    }

    fn validate_prior(&self) -> Result<(), ScenarioError> {
        let prior = &self.prior;
        finite("prior.time", prior.time)?;
        if prior.hypotheses.is_empty() {
            return Err(error("prior.hypotheses", "needs at least one hypothesis"));
        }
        let mut total = 0.0;
        for (h, hypothesis) in prior.hypotheses.iter().enumerate() {
            let w = hypothesis.weight;
            if !(w.is_finite() && w >= 0.0) {
                return Err(error(
                    format!("prior.hypotheses[{h}].weight"),
                    format!("{} is not finite and >= 0", crate::scenario::Readable(w)),
                ));
            }
            total += w;
            for (o, object) in hypothesis.objects.iter().enumerate() {
                let field = format!("prior.hypotheses[{h}].objects[{o}]");
                if object.label > MAX_PRIOR_LABEL {
                    return Err(error(
                        format!("{field}.label"),
                        format!("{} is above {MAX_PRIOR_LABEL} (labels above it are kept for births)", object.label),
                    ));
                }
                finite_all(&format!("{field}.mean"), &object.mean)?;
                covariance6(&format!("{field}.covariance"), &object.covariance)?;
                if hypothesis.objects[..o].iter().any(|other| other.label == object.label) {
                    return Err(error(
                        format!("{field}.label"),
                        format!("label {} appears twice in the hypothesis", object.label),
                    ));
                }
            }
        }
        if !(total.is_finite() && total > 0.0) {
            return Err(error("prior.hypotheses", "weights must have a finite sum > 0"));
        }
        Ok(())
    }

    /// Times, gaps against the motion model's bound, sensor indices and measurements.
    fn validate_scans(&self) -> Result<(), ScenarioError> {
        // The bound the tracker applies (tracker-core's `place_scan`): a longer gap is TimeStepTooLong.
        let limit = self.motion_model().max_time_step();
        let mut previous = self.prior.time;
        for (k, scan) in self.scans.iter().enumerate() {
            let field = format!("scans[{k}]");
            finite(&format!("{field}.time"), scan.time)?;
            if scan.time <= previous {
                return Err(error(
                    format!("{field}.time"),
                    format!("{} is not after the previous time {previous}", scan.time),
                ));
            }
            if let Some(limit) = limit
                && scan.time - previous > limit
            {
                return Err(error(
                    format!("{field}.time"),
                    format!(
                        "{} s after the previous scan, beyond the motion model's bound of {limit} s \
                         (motion.max_step x motion.max_substeps)",
                        scan.time - previous
                    ),
                ));
            }
            previous = scan.time;
            if scan.sensor >= self.sensors.len() {
                return Err(error(
                    format!("{field}.sensor"),
                    format!("unknown sensor {}: there are {} sensors", scan.sensor, self.sensors.len()),
                ));
            }
            let kind = self.kind(scan.sensor);
            let dimension = kind.dimension();
            for (j, z) in scan.measurements.iter().enumerate() {
                let field = format!("{field}.measurements[{j}]");
                if z.len() != dimension {
                    return Err(error(
                        &field,
                        format!("has {} components, a {} measurement has {dimension}", z.len(), kind.name()),
                    ));
                }
                finite_all(&field, z)?;
                check_measurement(&field, kind, z)?;
            }
        }
        Ok(())
    }
}
