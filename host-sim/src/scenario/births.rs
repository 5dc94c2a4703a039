//! The admissible regions of births from the measurements: the birth model's (`birth.measured`,
//! [`MeasuredBirthsSpec`]) and a network sensor's own (`sensors[i].birth_region`, [`BirthRegionSpec`]).

use super::{BirthEventsSpec, ScenarioError, error};
use serde::{Deserialize, Serialize};

/// The admissible region a measurement's birth density is cut from (`tracker_core::model::AdmissibleRegion`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum AdmissiblePresetSpec {
    /// Planar positions: velocity N(0, `velocity_sigma`² I).
    #[default]
    Planar,
    /// Low Earth orbit (bound orbits, perigee ≥ R_E + 200 km, apogee ≤ R_E + 2000 km).
    Leo,
    /// The GEO belt (near-circular, inclination ≤ 15°).
    Geo,
    /// Geosynchronous orbits: perigee and apogee within 25 km of the geosynchronous radius, inclination
    /// ≤ 15° (station-kept satellites and inclined ones that keep their longitude; not drifting objects).
    Geosynchronous,
    /// Every bound orbit: perigee ≥ R_E + 150 km, apogee ≤ 50,000 km (LEO to beyond GEO, GTO, Molniya).
    Bound,
}

impl AdmissiblePresetSpec {
    /// The core's region.
    pub fn region(self, velocity_sigma: f64) -> tracker_core::model::AdmissibleRegion<f64> {
        use tracker_core::model::AdmissibleRegion;
        match self {
            AdmissiblePresetSpec::Planar => AdmissibleRegion::planar(velocity_sigma),
            AdmissiblePresetSpec::Leo => AdmissibleRegion::leo(),
            AdmissiblePresetSpec::Geo => AdmissibleRegion::geo(),
            AdmissiblePresetSpec::Geosynchronous => AdmissibleRegion::geosynchronous(),
            AdmissiblePresetSpec::Bound => AdmissibleRegion::bound(),
        }
    }
}

/// Tracklet births (`birth.measured.tracklets`, `tracker_core::pool::TrackletBirths`, docs/maths.md
/// §5.10): angles of successive frames of one sensor linked into short arcs whose admissible region in
/// (range, range-rate) gives the birth cells. Rates in degrees.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TrackletSpec {
    /// Frames per tracklet, the current one included: 3 or 4.
    pub frames: usize,
    /// The longest time from a tracklet's first frame to its last (s).
    pub max_span: f64,
    /// The largest χ² of the fit (2 (frames − 3) degrees of freedom).
    pub max_chi_squared: f64,
    /// The largest angular rate (°/s).
    pub max_rate_deg_s: f64,
    /// The largest angular acceleration per axis (°/s²).
    pub max_acceleration_deg_s2: f64,
    /// The largest angular jerk per axis the fit neglects (°/s³).
    #[serde(default)]
    pub max_jerk_deg_s3: f64,
    /// The admissible region of the tracklets' range and range-rate.
    #[serde(default = "bound_region")]
    pub region: AdmissiblePresetSpec,
    /// Cells in ln(range) and in range-rate.
    pub cells: [usize; 2],
    /// Whether a direction that links with nothing yet makes its own single-frame cells (default: no).
    #[serde(default)]
    pub single_frame: bool,
}

fn bound_region() -> AdmissiblePresetSpec {
    AdmissiblePresetSpec::Bound
}

impl TrackletSpec {
    /// The core's settings.
    pub fn core(&self) -> tracker_core::pool::TrackletBirths<f64> {
        tracker_core::pool::TrackletBirths {
            frames: self.frames,
            max_span: self.max_span,
            limits: tracker_core::model::LinkLimits {
                max_chi_squared: self.max_chi_squared,
                max_rate: self.max_rate_deg_s.to_radians(),
                max_acceleration: self.max_acceleration_deg_s2.to_radians(),
                max_jerk: self.max_jerk_deg_s3.to_radians(),
            },
            region: self.region.region(1.0),
            cells: self.cells,
            single_frame: self.single_frame,
        }
    }
}

/// Birth cells made from unexplained measurements (`tracker_core::pool::MeasuredBirths`,
/// docs/maths.md §5.8).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeasuredBirthsSpec {
    /// The admissible region.
    #[serde(default)]
    pub region: AdmissiblePresetSpec,
    /// Planar: the standard deviation of each velocity component of a new object.
    #[serde(default = "default_velocity_sigma")]
    pub velocity_sigma: f64,
    /// Cells of the region's discretisation (each one optional: the preset's value).
    #[serde(default)]
    pub headings: Option<usize>,
    /// Cells of horizontal speed.
    #[serde(default)]
    pub speeds: Option<usize>,
    /// Cells of radial speed.
    #[serde(default)]
    pub climbs: Option<usize>,
    /// Optical: cells of radius.
    #[serde(default)]
    pub ranges: Option<usize>,
    /// λ_B: expected births per scan.
    pub expected_births: f64,
    /// The largest α of one measurement's cells, in (0, 1).
    pub max_probability: f64,
    /// The smallest r_U for a measurement to make cells.
    #[serde(default = "default_min_unexplained")]
    pub min_unexplained: f64,
    /// Seconds a cell lives.
    pub lifetime: f64,
    /// Tracklet births for sensors that measure directions (none: single-frame cells only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tracklets: Option<TrackletSpec>,
    /// Whether the cells the full pool does not keep wait for a later measurement to link with (default:
    /// no; docs/maths.md §5.8 "Births in clutter").
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub link_waiting: bool,
}

fn default_velocity_sigma() -> f64 {
    1.0
}

fn default_min_unexplained() -> f64 {
    0.5
}

impl MeasuredBirthsSpec {
    /// The core's settings.
    pub fn core(&self) -> tracker_core::pool::MeasuredBirths<f64> {
        let preset = self.region.region(self.velocity_sigma);
        let region = with_cells(preset, [self.headings, self.speeds, self.climbs, self.ranges]);
        tracker_core::pool::MeasuredBirths {
            region,
            expected_births: self.expected_births,
            max_probability: self.max_probability,
            min_unexplained: self.min_unexplained,
            lifetime: self.lifetime,
            tracklets: self.tracklets.map(|t| t.core()),
            link_waiting: self.link_waiting,
        }
    }

    /// Checks the settings as the core will.
    pub(crate) fn validate(&self, events: BirthEventsSpec) -> Result<(), ScenarioError> {
        if events != BirthEventsSpec::Independent {
            return Err(error("birth.measured", "needs birth.events \"independent\"".to_string()));
        }
        self.core().validate().map_err(|reason| error("birth.measured", reason.to_string()))
    }
}

/// `region` with the cells given (headings, speeds, climbs, ranges; `None`: the region's own).
fn with_cells(
    region: tracker_core::model::AdmissibleRegion<f64>,
    [headings, speeds, climbs, ranges]: [Option<usize>; 4],
) -> tracker_core::model::AdmissibleRegion<f64> {
    tracker_core::model::AdmissibleRegion {
        headings: headings.unwrap_or(region.headings),
        speeds: speeds.unwrap_or(region.speeds),
        climbs: climbs.unwrap_or(region.climbs),
        ranges: ranges.unwrap_or(region.ranges),
        ..region
    }
}

/// The admissible region of one sensor's births.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SensorRegionSpec {
    /// Low Earth orbit.
    Leo,
    /// The GEO belt.
    Geo,
    /// Geosynchronous orbits (`AdmissibleRegion::geosynchronous`).
    Geosynchronous,
    /// None: the sensor's measurements start no track.
    None,
}

/// A sensor's own births (`sensors[i].birth_region` of a version 2 file): an admissible region and its
/// cells (each one optional: the region's own), or none.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BirthRegionSpec {
    /// The admissible region, or `none`.
    pub region: SensorRegionSpec,
    /// Cells of heading.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub headings: Option<usize>,
    /// Cells of horizontal speed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub speeds: Option<usize>,
    /// Cells of radial speed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub climbs: Option<usize>,
    /// Optical: cells of radius.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ranges: Option<usize>,
}

impl BirthRegionSpec {
    /// The core's setting.
    pub fn core(&self) -> tracker_core::model::SensorBirths<f64> {
        use tracker_core::model::{AdmissibleRegion, SensorBirths};
        let cells = [self.headings, self.speeds, self.climbs, self.ranges];
        match self.region {
            SensorRegionSpec::Leo => SensorBirths::Region(with_cells(AdmissibleRegion::leo(), cells)),
            SensorRegionSpec::Geo => SensorBirths::Region(with_cells(AdmissibleRegion::geo(), cells)),
            SensorRegionSpec::Geosynchronous => {
                SensorBirths::Region(with_cells(AdmissibleRegion::geosynchronous(), cells))
            }
            SensorRegionSpec::None => SensorBirths::Off,
        }
    }
}
