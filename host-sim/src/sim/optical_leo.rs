//! The `optical-leo` preset (issue 31 item 5): a ground telescope at twilight staring with a wide field at
//! sunlit LEO objects that pass through it, some of them unknown to the prior (born from tracklets).
//!
//! A telescope sees LEO objects only in twilight: the site dark (the Sun below −6°) while the objects
//! overhead are still sunlit (outside the Earth's cylindrical shadow). Frames are taken only while the Sun
//! is between −18° and −6° at the site; an object is seen only while sunlit
//! ([`crate::scenario::from_catalogue::sunlit`]). A LEO object crosses the 10° field in 10–30 s, so frames
//! come every 2 s: a pass gives 5 to about 15 frames (median 12 on seeds 1 and 2), enough for a tracklet
//! (≥ 3 frames, docs/maths.md §5.10) and a few more to confirm its track.

use super::error::SsaError;
use super::field_of_view::{FieldOfView, LookShape};
use super::frames::radec;
use super::sensor::{SensorKind, SensorSpec};
use super::site::{Site, WGS84_A};
use super::ssa::{Plan, SsaScenario, observers, simulate, visibility};
use super::time::{earth_rotation_angle, parse_iso8601};
use super::truth::{ObjectTruth, Unknowns, aimed_circular, mark_missing, track};
use super::vector::{deg, norm};
use crate::scenario::from_catalogue::{sun_elevation, sun_position, sunlit};
use crate::sim::orbit::Propagator;
use crate::sim::rng::{Random, Stream};
use core::f64::consts::PI;

/// Parameters of [`optical_leo_with`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OpticalLeoConfig {
    /// Objects, each aimed to cross the field once during the run.
    pub objects: usize,
    /// Length of the window (s) from the epoch; frames are taken only in its twilight part.
    pub duration: f64,
    /// Time between frames (s).
    pub cadence: f64,
    /// Frames in which every object is seen (its orbit is redrawn until it is).
    pub min_frames: usize,
    /// Objects unknown to the prior (no break-up: [`Unknowns::breakup`] must be 0).
    pub unknowns: Unknowns,
}

impl OpticalLeoConfig {
    /// The `optical-leo` preset: 100 objects, the twilight part of the 90 minutes after 01:30 UTC (1717
    /// frames from 01:56 to 02:53 UTC, the Sun from −6° to −18°), a frame every 2 s.
    pub const PRESET: OpticalLeoConfig = OpticalLeoConfig {
        objects: 100,
        duration: 5400.0,
        cadence: 2.0,
        min_frames: 4,
        unknowns: Unknowns { missing_fraction: 0.0, breakup: 0 },
    };
}

/// The epoch: evening twilight at the site on the March equinox (sunset about 01:20 UTC).
const OPTICAL_LEO_EPOCH: &str = "2026-03-21T01:30:00Z";

/// Frames are taken while the Sun's elevation at the site is in this interval (degrees).
const TWILIGHT_DEG: [f64; 2] = [-18.0, -6.0];

/// The wide-field telescope of `optical-leo`: 32° N 110° W, 2 km; a cone of half-angle 5° about azimuth
/// 180°, elevation 60° (declination ≈ 2°, far from the pole), mask 20°; σ 2″ per angle (a wide field's
/// larger pixels); p_D 0.9; 2 clutter returns per frame (stars not removed, hot pixels, cosmic rays).
pub fn leo_telescope() -> SensorSpec {
    SensorSpec {
        name: "wide-field".into(),
        site: Site { latitude: deg(32.0), longitude: deg(-110.0), height: 2.0 },
        kind: SensorKind::Optical,
        fov: FieldOfView {
            shape: LookShape::Cone { azimuth: PI, elevation: deg(60.0), half_angle: deg(5.0) },
            min_elevation: deg(20.0),
            range: None,
        },
        sigma: vec![deg(2.0 / 3600.0), deg(2.0 / 3600.0)],
        detection_probability: 0.9,
        clutter_rate: 2.0,
    }
}

/// `optical-leo`: the telescope of [`leo_telescope`] at evening twilight; 100 circular LEO objects (altitude
/// 500–1500 km, any inclination that reaches the aim point), each aimed at a random time of the run at a
/// point within half the field's half-angle of the boresight, and redrawn (at most 200 times, from its own
/// stream) until it is seen, sunlit and in the field, in at least 4 frames.
///
/// # Errors
/// [`SsaError`] if propagation fails, an orbit search fails, or a scan would exceed the measurements a
/// scan may carry.
pub fn optical_leo(seed: u64) -> Result<SsaScenario, SsaError> {
    optical_leo_with(seed, &OpticalLeoConfig::PRESET)
}

/// The frames of `optical-leo`: every `cadence` seconds of `duration` while the Sun is in [`TWILIGHT_DEG`].
fn twilight_schedule(site: &Site, epoch_jd: f64, config: &OpticalLeoConfig) -> Vec<(f64, usize)> {
    let steps = (config.duration / config.cadence).floor() as usize;
    let [low, high] = TWILIGHT_DEG.map(f64::to_radians);
    (0..=steps)
        .map(|k| k as f64 * config.cadence)
        .filter(|&t| {
            let sun = sun_position(epoch_jd + t / 86_400.0);
            let elevation = sun_elevation(site, earth_rotation_angle(epoch_jd, t), sun);
            (low..=high).contains(&elevation)
        })
        .map(|t| (t, 0))
        .collect()
}

/// `optical-leo` with other sizes (tests use a short one).
///
/// # Errors
/// As [`optical_leo`]; [`SsaError::BadUnknowns`] for a break-up or a fraction outside [0, 1].
pub fn optical_leo_with(seed: u64, config: &OpticalLeoConfig) -> Result<SsaScenario, SsaError> {
    if config.unknowns.breakup > 0 {
        return Err(SsaError::BadUnknowns);
    }
    let sensors = vec![leo_telescope()];
    let sensor = &sensors[0];
    let epoch_jd = parse_iso8601(OPTICAL_LEO_EPOCH)?;
    let schedule = twilight_schedule(&sensor.site, epoch_jd, config);
    let (Some(&(first, _)), Some(&(last, _))) = (schedule.first(), schedule.last()) else {
        return Err(SsaError::OrbitSearch);
    };
    let times: Vec<f64> = schedule.iter().map(|&(t, _)| t).collect();
    let obs = observers(&sensors, epoch_jd, &schedule);
    let lit: Vec<[f64; 3]> = times.iter().map(|t| sun_position(epoch_jd + t / 86_400.0)).collect();
    let LookShape::Cone { azimuth, elevation, half_angle } = sensor.fov.shape else {
        return Err(SsaError::BadSensor);
    };
    let mut objects = Vec::with_capacity(config.objects);
    let mut tracks = Vec::with_capacity(config.objects);
    let mut visible = Vec::with_capacity(config.objects);
    for unit in 0..config.objects {
        let mut random = Random::stream(seed, Stream::Orbit, unit as u64);
        let mut chosen = None;
        for _attempt in 0..200 {
            let t_aim = random.between(first, last);
            let observer = sensor.site.observer(earth_rotation_angle(epoch_jd, t_aim));
            // A line of sight within half the half-angle of the boresight.
            let el = elevation + random.between(-0.5, 0.5) * half_angle;
            let az = azimuth + random.between(-0.5, 0.5) * half_angle / el.cos();
            let d = observer.direction(az, el);
            let radius = WGS84_A + random.between(500.0, 1500.0);
            let point = observer.sphere_crossing(d, radius);
            let aim = radec(point);
            let lo = aim[1].abs() + deg(3.0);
            let inclination = random.between(lo, PI - lo);
            let at_aim = aimed_circular(aim, norm(point), inclination, random.uniform() < 0.5);
            let initial = Propagator::EARTH.propagate(at_aim, -t_aim)?;
            let states = track(initial, &times)?;
            let in_view = visibility(&sensors, &schedule, &obs, &states);
            let seen: Vec<bool> = in_view
                .iter()
                .zip(&states)
                .zip(&lit)
                .map(|((&v, x), sun)| v && sunlit([x[0], x[1], x[2]], *sun))
                .collect();
            if seen.iter().filter(|&&s| s).count() >= config.min_frames {
                chosen = Some((initial, states, seen));
                break;
            }
        }
        let (initial, states, seen) = chosen.ok_or(SsaError::OrbitSearch)?;
        objects.push(ObjectTruth::known(initial, None));
        tracks.push(states);
        visible.push(seen);
    }
    let n = objects.len();
    mark_missing(seed, &mut objects, n, config.unknowns.missing_fraction)?;
    simulate(Plan {
        name: "optical-leo".into(),
        seed,
        epoch: OPTICAL_LEO_EPOCH.into(),
        duration: config.duration,
        sensors,
        objects,
        groups: Vec::new(),
        schedule,
        tracks: Some(tracks),
        visible: Some(visible),
    })
}
