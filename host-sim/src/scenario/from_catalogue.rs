//! `host-sim generate catalogue`: a version 2 scenario ([`crate::scenario::v2`]) from a TLE / OMM catalogue
//! ([`crate::io::catalogue`]) and a sensors file ([`SensorsFile`], format `rfisst-sensors/1`,
//! docs/scenario-format.md "Sensors files").
//!
//! Truth: SGP4 for every object at every scan (and at the prior, 1 s before the first scan), in the
//! tracker's frame (TEME, docs/maths.md §6.8). The sensors take turns, one scan every
//! `scan_interval_s / sensors` seconds from the start. Detections, noise and clutter are drawn by
//! [`crate::sim`]'s simulator as for the presets. A telescope scans only while its site is dark (the Sun
//! below `max_sun_elevation_deg`, default −12°) and sees only sunlit objects (outside the Earth's
//! cylindrical shadow); the Sun is [`sun_position`], the Astronomical Almanac's low-precision formula.

use crate::Error;
use crate::io::catalogue;
use crate::pipeline::Profile;
use crate::pipeline::profile::ORBITAL;
use crate::scenario::catalogue_stream::{CatalogueStream, StreamParts};
use crate::scenario::from_simulation::Generated;
use crate::scenario::v2::{MAX_SENSORS, Measurement3dSpec, Scenario3d, Sensor3dSpec, ShapeSpec};
use crate::scenario::{MAX_FILE_BYTES, ScenarioError, error, read_limited};
use crate::sim::field_of_view::FieldOfView;
use crate::sim::field_of_view::LookShape;
use crate::sim::sensor::SensorKind;
use crate::sim::sensor::SensorSpec;
use crate::sim::site::Site;
use crate::sim::{site, time};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The format tag of a sensors file.
pub const SENSORS_FORMAT: &str = "rfisst-sensors/1";

/// The longest scenario: 31 days.
pub const MAX_DURATION_HOURS: f64 = 744.0;

/// The most SGP4 evaluations (objects × scans) one generation may make.
pub const MAX_PROPAGATIONS: u64 = 20_000_000;

/// Bytes of the written scenario (compact JSON), measured on `generate catalogue` outputs (24 LEO objects,
/// two radars, 4 h: 131.6 B per truth state on average, 123 at least): per object and scan (a truth
/// state), per scan (its record and its truth record), per measurement, per object (its prior).
pub const BYTES_PER_TRUTH_STATE: u64 = 130;
/// See [`BYTES_PER_TRUTH_STATE`]: a scan's record (44 B) and its truth record (31 B).
pub const BYTES_PER_SCAN: u64 = 75;
/// See [`BYTES_PER_TRUTH_STATE`]: one measurement (57 B on average).
pub const BYTES_PER_MEASUREMENT: u64 = 57;
/// See [`BYTES_PER_TRUTH_STATE`]: one object's prior (362 B on average).
pub const BYTES_PER_PRIOR_OBJECT: u64 = 362;

/// The scenario a request would write, in bytes (about: [`BYTES_PER_TRUTH_STATE`]), from its objects,
/// scans and the clutter measurements expected per scan (detections not counted).
pub fn estimated_bytes(objects: u64, scans: u64, clutter_per_scan: f64) -> u64 {
    let measurements = (scans as f64 * clutter_per_scan.max(0.0)).min(u64::MAX as f64) as u64;
    let per_scan = BYTES_PER_SCAN.saturating_add(objects.saturating_mul(BYTES_PER_TRUTH_STATE));
    scans
        .saturating_mul(per_scan)
        .saturating_add(measurements.saturating_mul(BYTES_PER_MEASUREMENT))
        .saturating_add(objects.saturating_mul(BYTES_PER_PRIOR_OBJECT))
}

/// Refuses a request whose scenario would be larger than `run` reads ([`MAX_FILE_BYTES`]), before
/// anything grows with it: generation holds the scenario in memory (about three times its file size).
fn check_size(objects: u64, scans: u64, clutter_per_scan: f64) -> Result<(), Error> {
    let bytes = estimated_bytes(objects, scans, clutter_per_scan);
    if bytes <= MAX_FILE_BYTES {
        return Ok(());
    }
    Err(Error::input(format!(
        "{objects} objects x {scans} scans would make a scenario of about {} MiB ({BYTES_PER_TRUTH_STATE} B per \
         object and scan), more than the {} MiB `run` reads: a shorter run, a longer scan_interval_s or fewer \
         objects (run-catalogue draws such a run as it goes)",
        bytes >> 20,
        MAX_FILE_BYTES >> 20
    )))
}

/// Refuses a generated scenario whose file would be larger than `run` reads (the estimate of
/// [`check_size`] is close, not exact): its exact size, counted without writing it.
fn check_written_size(scenario: &Scenario3d) -> Result<(), Error> {
    let bytes = written_bytes(scenario)?;
    if bytes > MAX_FILE_BYTES {
        return Err(Error::input(format!(
            "the generated scenario would be {} MiB, more than the {} MiB `run` reads: a shorter run, a longer \
             scan_interval_s or fewer objects (run-catalogue draws such a run as it goes)",
            bytes >> 20,
            MAX_FILE_BYTES >> 20
        )));
    }
    Ok(())
}

/// The size of `scenario`'s file, counted without writing it.
fn written_bytes(scenario: &Scenario3d) -> Result<u64, Error> {
    struct Count(u64);
    impl std::io::Write for Count {
        fn write(&mut self, bytes: &[u8]) -> std::io::Result<usize> {
            self.0 += bytes.len() as u64;
            Ok(bytes.len())
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }
    let mut count = Count(1); // the final line break
    serde_json::to_writer(&mut count, scenario).map_err(|e| Error::internal(format!("scenario size: {e}")))?;
    Ok(count.0)
}

/// One astronomical unit (km).
pub const ASTRONOMICAL_UNIT_KM: f64 = 149_597_870.7;

fn default_dark() -> f64 {
    -12.0
}

/// A sensors file: the sensors of a version 2 scenario and how often they scan.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SensorsFile {
    /// Must be [`SENSORS_FORMAT`].
    pub format: String,
    /// What every sensor measures (as in a version 2 scenario); `network` for sensors of mixed kinds, each
    /// with its own `kind` (and optionally its own `birth_region`).
    pub measurement: Measurement3dSpec,
    /// Seconds between two scans of one sensor (> 0); the sensors take turns, evenly spaced.
    pub scan_interval_s: f64,
    /// A telescope's site is dark when the Sun is below this elevation (degrees, in [−90, 0]).
    #[serde(default = "default_dark")]
    pub max_sun_elevation_deg: f64,
    /// The sensors, exactly as in a version 2 scenario's `sensors`.
    pub sensors: Vec<Sensor3dSpec>,
}

impl SensorsFile {
    /// Reads and checks a sensors file; errors name the file and the field.
    pub fn load(path: &Path) -> Result<Self, ScenarioError> {
        let text = read_limited(path)?;
        let file = path.display();
        Self::from_json(&text).map_err(|e| ScenarioError(crate::scenario::one_line(&format!("{file}: {e}"))))
    }

    /// Parses and checks a sensors file.
    pub fn from_json(text: &str) -> Result<Self, ScenarioError> {
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let deserializer = &mut serde_json::Deserializer::from_str(text);
        let sensors: SensorsFile = serde_path_to_error::deserialize(&mut *deserializer).map_err(|e| {
            let path = e.path().to_string();
            let message = e.into_inner().to_string();
            if path == "." { error("invalid sensors JSON", message) } else { error(path, message) }
        })?;
        deserializer.end().map_err(|e| error("invalid sensors JSON", e))?;
        sensors.validate()?;
        Ok(sensors)
    }

    fn validate(&self) -> Result<(), ScenarioError> {
        if self.format != SENSORS_FORMAT {
            return Err(error("format", format!("expected \"{SENSORS_FORMAT}\", found \"{}\"", self.format)));
        }
        if !(self.scan_interval_s.is_finite() && self.scan_interval_s > 0.0) {
            return Err(error(
                "scan_interval_s",
                format!("{} is not finite and > 0", crate::scenario::Readable(self.scan_interval_s)),
            ));
        }
        if !(-90.0..=0.0).contains(&self.max_sun_elevation_deg) {
            return Err(error(
                "max_sun_elevation_deg",
                format!("{} is not in [-90, 0]", crate::scenario::Readable(self.max_sun_elevation_deg)),
            ));
        }
        if self.sensors.is_empty() || self.sensors.len() > MAX_SENSORS {
            return Err(error("sensors", format!("{} sensors: needs 1 to {MAX_SENSORS}", self.sensors.len())));
        }
        crate::scenario::v2::check_sensor_names(self.sensors.iter().map(|s| s.name.as_str()))?;
        for (i, sensor) in self.sensors.iter().enumerate() {
            sensor.validate_kind(i, self.measurement)?;
            sensor.validate(&format!("sensors[{i}]"), sensor.kind_under(self.measurement))?;
        }
        Ok(())
    }

    /// What sensor `sensor` measures.
    pub fn kind(&self, sensor: usize) -> Measurement3dSpec {
        self.sensors.get(sensor).map_or(self.measurement, |s| s.kind_under(self.measurement))
    }
}

/// The simulator's form of a file sensor (degrees to radians, arcseconds to radians).
fn simulator_sensor(sensor: &Sensor3dSpec, kind: Measurement3dSpec) -> SensorSpec {
    let fov = &sensor.field_of_view;
    let shape = match fov.shape {
        ShapeSpec::Cone { azimuth_deg, elevation_deg, half_angle_deg } => LookShape::Cone {
            azimuth: azimuth_deg.to_radians(),
            elevation: elevation_deg.to_radians(),
            half_angle: half_angle_deg.to_radians(),
        },
        ShapeSpec::Box { azimuth_deg, half_width_deg, elevation_deg } => LookShape::Box {
            azimuth_centre: azimuth_deg.to_radians(),
            azimuth_half_width: half_width_deg.to_radians(),
            elevation_min: elevation_deg[0].to_radians(),
            elevation_max: elevation_deg[1].to_radians(),
        },
    };
    SensorSpec {
        name: sensor.name.clone(),
        site: Site {
            latitude: sensor.site.latitude_deg.to_radians(),
            longitude: sensor.site.longitude_deg.to_radians(),
            height: sensor.site.height_km,
        },
        kind: match kind {
            Measurement3dSpec::Radar => SensorKind::Radar,
            Measurement3dSpec::RadarRangeRate => SensorKind::RadarRangeRate {
                max_range_rate: fov.range_rate_km_s.map_or(0.0, |[lo, hi]| lo.abs().max(hi.abs())),
            },
            Measurement3dSpec::Optical | Measurement3dSpec::Network => SensorKind::Optical,
            Measurement3dSpec::AzEl => SensorKind::AzEl,
            Measurement3dSpec::Range => SensorKind::Range,
            Measurement3dSpec::RangeRangeRate => SensorKind::RangeRangeRate {
                max_range_rate: fov.range_rate_km_s.map_or(0.0, |[lo, hi]| lo.abs().max(hi.abs())),
            },
        },
        fov: FieldOfView { shape, min_elevation: fov.min_elevation_deg.to_radians(), range: fov.range_km },
        sigma: sensor.noise.sigma(kind),
        detection_probability: sensor.detection_probability,
        clutter_rate: sensor.clutter_rate,
    }
}

/// The simulator's sensors of a sensors file, each of its own kind, and which of them are telescopes (RA/Dec:
/// they see only from a dark site, and only sunlit objects).
fn simulator_sensors(file: &SensorsFile) -> (Vec<SensorSpec>, Vec<bool>) {
    let kinds: Vec<Measurement3dSpec> = (0..file.sensors.len()).map(|i| file.kind(i)).collect();
    let sensors = file.sensors.iter().zip(&kinds).map(|(s, &kind)| simulator_sensor(s, kind)).collect();
    (sensors, kinds.iter().map(|&k| k == Measurement3dSpec::Optical).collect())
}

/// The Sun's position (km) in the inertial frame at UT1 Julian date `jd`: the Astronomical Almanac's
/// low-precision formula (Vallado, Algorithm 29; about 0.01° in 1950-2050), mean equator and equinox of
/// date, taken as TEME (the equation of the equinoxes, ≤ 1.2″, neglected).
pub fn sun_position(jd: f64) -> [f64; 3] {
    let t = (jd - 2_451_545.0) / 36_525.0;
    let mean_longitude = (280.460 + 36_000.771 * t).to_radians();
    let m = (357.529_109_2 + 35_999.050_34 * t).to_radians();
    let longitude = mean_longitude + (1.914_666_471 * m.sin() + 0.019_994_643 * (2.0 * m).sin()).to_radians();
    let distance = (1.000_140_612 - 0.016_708_617 * m.cos() - 0.000_139_589 * (2.0 * m).cos()) * ASTRONOMICAL_UNIT_KM;
    let obliquity = (23.439_291 - 0.013_004_2 * t).to_radians();
    let (sl, cl) = longitude.sin_cos();
    [distance * cl, distance * obliquity.cos() * sl, distance * obliquity.sin() * sl]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// Whether a position (km) is sunlit: outside the Earth's cylindrical shadow (radius 6378.137 km) behind
/// the Earth as seen from the Sun at `sun` (km).
pub fn sunlit(position: [f64; 3], sun: [f64; 3]) -> bool {
    let s = norm(sun);
    let u = [sun[0] / s, sun[1] / s, sun[2] / s];
    let along = dot(position, u);
    if along >= 0.0 {
        return true;
    }
    let across = [position[0] - along * u[0], position[1] - along * u[1], position[2] - along * u[2]];
    norm(across) > site::WGS84_A
}

/// The Sun's elevation (rad) from `site` at Earth rotation angle `theta` and Sun position `sun` (km).
pub fn sun_elevation(site: &Site, theta: f64, sun: [f64; 3]) -> f64 {
    let observer = site.observer(theta);
    let d = [sun[0] - observer.position[0], sun[1] - observer.position[1], sun[2] - observer.position[2]];
    (dot(d, observer.up) / norm(d)).clamp(-1.0, 1.0).asin()
}

/// What `generate catalogue` is given.
#[derive(Debug, Clone, Copy)]
pub struct Request<'a> {
    /// Catalogue file (TLE, 3LE, OMM JSON or CSV).
    pub catalogue: &'a Path,
    /// Sensors file.
    pub sensors: &'a Path,
    /// Start (UTC, `YYYY-MM-DDTHH:MM:SS[.f][Z]`): the scenario's epoch.
    pub start: &'a str,
    /// Duration (hours).
    pub duration_hours: f64,
    /// Seed of detections and clutter (and the prior errors).
    pub seed: u64,
}

/// The scenario of a catalogue seen by a sensor network ([`generate_screened`] without its list of dropped
/// element sets).
///
/// # Errors
/// As [`generate_screened`].
pub fn generate(request: Request<'_>) -> Result<(Scenario3d, Generated), Error> {
    generate_screened(request).map(|(scenario, figures, _)| (scenario, figures))
}

/// The scenario of a catalogue seen by a sensor network, and the element sets left out
/// ([`catalogue::screen`]: inside the Earth, decaying or failing SGP4 during the run, given twice), each
/// also a warning line on stderr: every scan of [`CatalogueStream`] drawn and held. A scan may carry more
/// measurements than one tracker takes only when the catalogue is larger than one tracker's N (the run
/// then partitions it, docs/maths.md §13).
///
/// # Errors
/// [`Error::Input`] for a bad file or argument, a catalogue whose every element set is dropped, a scenario
/// larger than `run` reads, or a scan that would carry more measurements than the tracker takes.
pub fn generate_screened(request: Request<'_>) -> Result<(Scenario3d, Generated, catalogue::CatalogueDropped), Error> {
    let (parts, _) = prepare(request, Hold::Always)?;
    let held = held(CatalogueStream::new(parts)?)?;
    check_written_size(&held.0)?;
    Ok(held)
}

/// A catalogue's run: its scenario held whole, or its scans drawn as the run goes.
pub enum Generation {
    /// The scenario, as [`generate_screened`] gives it.
    Held(Box<(Scenario3d, Generated, catalogue::CatalogueDropped)>),
    /// The scans drawn one at a time ([`stream`]).
    Streamed(Box<CatalogueStream>),
}

/// [`generate_screened`]'s scenario when it fits a scenario file `run` reads ([`MAX_FILE_BYTES`],
/// [`MAX_PROPAGATIONS`]), else its [`stream`] (`run-catalogue`).
///
/// # Errors
/// As [`generate_screened`], but for the scenario's size.
pub fn generate_or_stream(request: Request<'_>) -> Result<Generation, Error> {
    let (parts, held_whole) = prepare(request, Hold::IfItFits)?;
    let scans = CatalogueStream::new(parts)?;
    if !held_whole {
        return Ok(Generation::Streamed(Box::new(scans)));
    }
    let held = held(scans)?;
    // The estimate is close, not exact: a scenario it let through may still be too large to write.
    match written_bytes(&held.0)? <= MAX_FILE_BYTES {
        true => Ok(Generation::Held(Box::new(held))),
        false => stream(request).map(|s| Generation::Streamed(Box::new(s))),
    }
}

/// Every scan of `stream` drawn and held, with the figures of the scenario (its size not checked).
fn held(mut stream: CatalogueStream) -> Result<(Scenario3d, Generated, catalogue::CatalogueDropped), Error> {
    let (mut scans, mut truth_scans) = (Vec::with_capacity(stream.scans()), Vec::with_capacity(stream.scans()));
    for k in 0..stream.scans() {
        let (scan, truth) = stream.scan(k)?;
        scans.push(scan);
        truth_scans.push(truth);
    }
    let (objects, dropped_outside) = (stream.objects(), stream.dropped_outside);
    let (mut scenario, dropped) = stream.into_parts();
    scenario.scans = scans;
    scenario.truth.as_mut().ok_or_else(|| Error::internal("catalogue scenario without truth"))?.scans = truth_scans;
    scenario.validate().map_err(|e| Error::internal(format!("generated scenario: {e}")))?;
    let figures = Generated {
        objects,
        scans: scenario.scans.len(),
        measurements: scenario.scans.iter().map(|s| s.measurements.len()).sum(),
        max_measurements: scenario.max_measurements(),
        dropped_outside,
    };
    check_written_size(&scenario)?;
    Ok((scenario, figures, dropped))
}

/// The scans of a catalogue seen by a sensor network, drawn one at a time: [`generate_screened`]'s scenario
/// without holding it, for a catalogue of any size (scans of any number of measurements; objects screened
/// every [`STREAM_SCREEN_STEP_S`] before the run, and an object that decays between two screening times
/// dropped at the scan, with a warning).
///
/// # Errors
/// As [`generate_screened`], but for the scenario's size and the measurements per scan.
pub fn stream(request: Request<'_>) -> Result<CatalogueStream, Error> {
    let (parts, _) = prepare(request, Hold::Never)?;
    CatalogueStream::new(parts)
}

/// Whether [`prepare`] readies a scenario to be held whole.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Hold {
    /// Held: refused when too large for a scenario file.
    Always,
    /// Streamed.
    Never,
    /// Held when it fits a scenario file, else streamed.
    IfItFits,
}

/// Seconds between two screening times of a streamed catalogue ([`stream`]).
pub const STREAM_SCREEN_STEP_S: f64 = 600.0;

/// What [`CatalogueStream`] needs of a request, and whether its scenario is to be held whole
/// ([`Hold`]): its arguments checked, the schedule, the catalogue screened at every scan time (held) or
/// every [`STREAM_SCREEN_STEP_S`] (streamed); a held scenario's size checked before anything grows with it.
fn prepare(request: Request<'_>, hold: Hold) -> Result<(StreamParts, bool), Error> {
    let hours = request.duration_hours;
    if !(hours.is_finite() && hours > 0.0 && hours <= MAX_DURATION_HOURS) {
        return Err(Error::input(format!(
            "--duration-hours {}: must be in (0, {MAX_DURATION_HOURS}]",
            crate::scenario::Readable(hours)
        )));
    }
    let start = request.start;
    let bad_start =
        || Error::input(format!("--start {start:?}: not a UTC time YYYY-MM-DDTHH:MM:SS[.f][Z] in 1901-2099"));
    let epoch_jd = time::parse_iso8601(start).map_err(|_| bad_start())?;
    let epoch = catalogue::parse_omm_epoch(start).ok_or_else(bad_start)?;
    let entries = catalogue::load(request.catalogue)?;
    let sensors_file = SensorsFile::load(request.sensors)?;
    let (sensors, optical) = simulator_sensors(&sensors_file);

    // The schedule: sensors in turn; a telescope only while its site is dark.
    let duration = hours * 3600.0;
    let slot = sensors_file.scan_interval_s / sensors.len() as f64;
    let slots = (duration / slot).floor() as u64 + 1;
    let propagations = match slots.saturating_mul(entries.len() as u64) > MAX_PROPAGATIONS {
        true => Err(Error::input(format!(
            "{} objects x {slots} scans exceed {MAX_PROPAGATIONS} SGP4 evaluations: a shorter run, a longer \
             scan_interval_s or a smaller catalogue (run-catalogue draws such a run as it goes)",
            entries.len()
        ))),
        false => Ok(()),
    };
    let dark = sensors_file.max_sun_elevation_deg.to_radians();
    let (sites, count, optical_of) = (&sensors[..], sensors.len() as u64, &optical[..]);
    let scheduled = || {
        (0..slots).map(move |j| (j as f64 * slot, (j % count) as usize)).filter(move |&(t, s)| {
            !optical_of[s] || {
                let sun = sun_position(epoch_jd + t / 86_400.0);
                sun_elevation(&sites[s].site, time::earth_rotation_angle(epoch_jd, t), sun) < dark
            }
        })
    };
    // The scenario's size is known from the request: refuse before anything grows with it.
    let clutter = sensors.iter().map(|s| s.clutter_rate).sum::<f64>() / sensors.len() as f64;
    let fits = propagations.and_then(|()| check_size(entries.len() as u64, scheduled().count() as u64, clutter));
    let held_whole = match (hold, fits) {
        (Hold::Always, Err(e)) => return Err(e),
        (Hold::Always, Ok(())) => true,
        (Hold::Never, _) => false,
        (Hold::IfItFits, fits) => fits.is_ok(),
    };
    let schedule: Vec<(f64, usize)> = scheduled().collect();
    if schedule.is_empty() {
        return Err(Error::input(format!(
            "{}: no scan: the telescopes' sites are never dark (Sun below {}°) during the run",
            request.sensors.display(),
            sensors_file.max_sun_elevation_deg
        )));
    }

    let file = request.catalogue.display().to_string();
    let screened = if !held_whole {
        let steps = (duration / STREAM_SCREEN_STEP_S).ceil() as usize;
        let times: Vec<f64> = (0..=steps).map(|k| (k as f64 * STREAM_SCREEN_STEP_S).min(duration)).collect();
        catalogue::screen::screen_scans(&file, entries, epoch, &times)?
    } else {
        let scan_times: Vec<f64> = schedule.iter().map(|&(t, _)| t).collect();
        catalogue::screen::screen_scans(&file, entries, epoch, &scan_times)?
    };
    // One tracker takes at most MAX_MEASUREMENTS a scan; a catalogue larger than one tracker's N is
    // partitioned, and its clusters share a scan's measurements.
    let partitioned = screened.satellites.len() > ORBITAL.of(Profile::Host).objects;
    let name =
        format!("catalogue {}", request.catalogue.file_name().map_or(file.clone(), |n| n.to_string_lossy().into()));
    let parts = StreamParts {
        name,
        seed: request.seed,
        start: start.to_string(),
        epoch_jd,
        epoch,
        duration,
        sensors,
        optical,
        schedule,
        satellites: screened.satellites,
        dropped: screened.dropped,
        max_measurements: (!partitioned).then_some(crate::sim::error::MAX_MEASUREMENTS),
        catalogue_file: file,
        sensors_file: request.sensors.display().to_string(),
        birth_regions: sensors_file.sensors.iter().map(|s| s.birth_region).collect(),
    };
    Ok((parts, held_whole))
}

/// Writes `scenario` to `out` through a temporary file beside it, renamed once complete and only onto a
/// new path or a regular file ([`crate::io::atomic`]): a failed write leaves no partial file.
///
/// # Errors
/// [`Error::Output`] naming `out`.
pub fn save_whole(scenario: &Scenario3d, out: &Path) -> Result<(), Error> {
    scenario.save(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sun_matches_vallado_example_5_1() {
        // Vallado, Example 5-1: 2006-04-02 00:00 UTC (JD_UT1 2453827.5); r_sun (MOD) =
        // [0.9771945, 0.1924424, 0.0834308] AU.
        let r = sun_position(2_453_827.5);
        let expected = [0.977_194_5, 0.192_442_4, 0.083_430_8].map(|x| x * ASTRONOMICAL_UNIT_KM);
        let angle = (dot(r, expected) / (norm(r) * norm(expected))).clamp(-1.0, 1.0).acos().to_degrees();
        assert!(angle < 0.01, "{angle}°");
        assert!((norm(r) / norm(expected) - 1.0).abs() < 1e-4);
    }

    #[test]
    fn shadow_is_behind_the_earth() {
        let sun = [ASTRONOMICAL_UNIT_KM, 0.0, 0.0];
        assert!(sunlit([7000.0, 0.0, 0.0], sun));
        assert!(!sunlit([-7000.0, 0.0, 0.0], sun));
        assert!(sunlit([-7000.0, 6400.0, 0.0], sun));
        assert!(sunlit([0.0, 0.0, 7000.0], sun));
    }
}
