//! The `optical-heo` preset (issue 31): a wide-field telescope at night about `optical-geo`'s boresight,
//! with objects on transfer (GTO) and Molniya orbits that the prior does not know, crossing its field; the
//! telescope must start them itself from tracklets (docs/maths.md §5.10) in the region of every bound orbit.
//!
//! Station-kept GEO objects (known to the prior) stay in the field. Each eccentric object is aimed at a
//! point of the field at a random frame time, at a true anomaly of the far half of its orbit (90°–270°:
//! 11,000 to 46,000 km from the Earth's centre), where it crosses the field; it is redrawn until it is
//! sunlit and in the field in enough frames. Frames come every 30 s while the Sun is below −12° at the site.
//! The field is wide (20° half-angle: an array of cameras as survey systems for faint moving objects use),
//! because from one site range along the line of sight is observed only over tens of minutes of arc: with
//! `optical-geo`'s 3° field most passes lasted minutes and 34 of 80 objects ended more than 10 km off along
//! the line of sight (docs/results.md, "optical-heo").

use super::error::SsaError;
use super::field_of_view::LookShape;
use super::frames::radec;
use super::presets::{geo_radius, geo_telescope};
use super::site::{Site, WGS84_A};
use super::ssa::{Plan, SsaScenario, observers, simulate, visibility};
use super::time::{EARTH_ROTATION_RATE, earth_rotation_angle, parse_iso8601};
use super::truth::{ObjectTruth, geosynchronous, kepler_state, track};
use super::vector::deg;
use crate::scenario::from_catalogue::{sun_elevation, sun_position, sunlit};
use crate::sim::orbit::Propagator;
use crate::sim::rng::{Random, Stream};
use core::f64::consts::{PI, TAU};

/// Parameters of [`optical_heo_with`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OpticalHeoConfig {
    /// Station-kept GEO objects, known to the prior.
    pub geo: usize,
    /// Objects on transfer orbits (GTO), unknown to the prior.
    pub gto: usize,
    /// Objects on Molniya orbits, unknown to the prior.
    pub molniya: usize,
    /// Length of the window (s) from the epoch; frames are taken only in its dark part.
    pub duration: f64,
    /// Time between frames (s).
    pub cadence: f64,
    /// Frames in which every eccentric object is seen (its orbit is redrawn until it is).
    pub min_frames: usize,
    /// Half-angle of the telescope's field (degrees), about `optical-geo`'s boresight.
    pub half_angle_deg: f64,
}

impl OpticalHeoConfig {
    /// The `optical-heo` preset: 6 GEO objects, 4 GTO and 4 Molniya objects, the dark part of 4 hours
    /// from 02:00 UTC, a frame every 30 s.
    pub const PRESET: OpticalHeoConfig = OpticalHeoConfig {
        geo: 6,
        gto: 4,
        molniya: 4,
        duration: 4.0 * 3600.0,
        cadence: 30.0,
        min_frames: 8,
        half_angle_deg: 20.0,
    };
}

/// The epoch: `optical-geo`'s, evening at the site (18:40 local mean solar time).
const OPTICAL_HEO_EPOCH: &str = "2026-03-20T02:00:00Z";

/// Frames are taken while the Sun's elevation at the site is below this (degrees): nautical twilight over.
const DARK_DEG: f64 = -12.0;

/// `optical-heo`: the telescope of `optical-geo` ([`geo_telescope`]: 32° N 110° W, about the GEO belt on its
/// meridian, σ 1.5″, p_D 0.95, 1 clutter per frame) with a cone of half-angle 20° (`half_angle_deg`;
/// `optical-geo`'s is 3°), a frame every 30 s while the Sun is below −12° at the site within 4 h of 02:00 UTC
/// on 2026-03-20. Objects: 6 station-kept GEO objects within ±2° of longitude of the meridian (known to the
/// prior); 4 GTO objects (perigee altitude 200–600 km, apogee radius 42,164 ± 500 km, inclination up to 28.5°)
/// and 4 Molniya objects (a 26,560 km, e 0.70–0.74, i 63.4°, the argument of perigee the one that puts the aim
/// point at the drawn true anomaly), unknown to the prior; each aimed at a point within half the field's
/// half-angle of the boresight at a random frame time with a true anomaly in 90°–270°, and redrawn (at most 200
/// times, from its own stream) until it is seen, sunlit and in the field, in at least 8 frames.
///
/// # Errors
/// [`SsaError`] if propagation fails, an orbit search fails, or a scan would exceed the measurements a
/// scan may carry.
pub fn optical_heo(seed: u64) -> Result<SsaScenario, SsaError> {
    optical_heo_with(seed, &OpticalHeoConfig::PRESET)
}

/// The frames: every `cadence` seconds of `duration` while the Sun is below [`DARK_DEG`] at `site`.
fn dark_schedule(site: &Site, epoch_jd: f64, config: &OpticalHeoConfig) -> Vec<(f64, usize)> {
    let steps = (config.duration / config.cadence).floor() as usize;
    (0..=steps)
        .map(|k| k as f64 * config.cadence)
        .filter(|&t| {
            let sun = sun_position(epoch_jd + t / 86_400.0);
            sun_elevation(site, earth_rotation_angle(epoch_jd, t), sun) < DARK_DEG.to_radians()
        })
        .map(|t| (t, 0))
        .collect()
}

/// The shape of an eccentric orbit: semi-major axis (km), eccentricity, inclination range (rad).
struct Shape {
    a: f64,
    e: f64,
    inclination: [f64; 2],
}

/// A GTO (`transfer`) or a Molniya orbit's shape drawn from `random`.
fn draw_shape(random: &mut Random, transfer: bool) -> Shape {
    if transfer {
        let perigee = WGS84_A + random.between(200.0, 600.0);
        let apogee = geo_radius() + random.between(-500.0, 500.0);
        Shape { a: 0.5 * (perigee + apogee), e: (apogee - perigee) / (apogee + perigee), inclination: [0.0, deg(28.5)] }
    } else {
        Shape { a: 26_560.0, e: random.between(0.70, 0.74), inclination: [deg(63.4), deg(63.4)] }
    }
}

/// The state of an orbit of `shape` at true anomaly `nu` at the inertial point `point` (whose radius must
/// be the orbit's at `nu`), with inclination `inclination` ≥ the point's declination, ascending or
/// descending there.
fn aimed_eccentric(point: [f64; 3], shape: &Shape, inclination: f64, nu: f64, ascending: bool) -> [f64; 6] {
    let [ra, dec] = radec(point);
    let s = (dec.sin() / inclination.sin()).clamp(-1.0, 1.0).asin();
    // The argument of latitude u = ω + ν and the node that put the point at (ra, dec).
    let u = if ascending { s } else { PI - s };
    let raan = ra - (inclination.cos() * u.sin()).atan2(u.cos());
    let argp = u - nu;
    let e = shape.e;
    let eccentric = 2.0 * (((1.0 - e) / (1.0 + e)).sqrt() * (0.5 * nu).tan()).atan();
    kepler_state(shape.a, e, inclination, raan, argp, eccentric - e * eccentric.sin())
}

/// `optical-heo` with other sizes (tests use a short one).
///
/// # Errors
/// As [`optical_heo`].
pub fn optical_heo_with(seed: u64, config: &OpticalHeoConfig) -> Result<SsaScenario, SsaError> {
    let mut telescope = geo_telescope();
    if let LookShape::Cone { half_angle, .. } = &mut telescope.fov.shape {
        *half_angle = deg(config.half_angle_deg);
    }
    let sensors = vec![telescope];
    let sensor = &sensors[0];
    let epoch_jd = parse_iso8601(OPTICAL_HEO_EPOCH)?;
    let schedule = dark_schedule(&sensor.site, epoch_jd, config);
    if schedule.is_empty() {
        return Err(SsaError::OrbitSearch);
    }
    let times: Vec<f64> = schedule.iter().map(|&(t, _)| t).collect();
    let obs = observers(&sensors, epoch_jd, &schedule);
    let lit: Vec<[f64; 3]> = times.iter().map(|t| sun_position(epoch_jd + t / 86_400.0)).collect();
    let seen_in = |states: &[[f64; 6]]| -> Vec<bool> {
        let in_view = visibility(&sensors, &schedule, &obs, states);
        in_view.iter().zip(states).zip(&lit).map(|((&v, x), sun)| v && sunlit([x[0], x[1], x[2]], *sun)).collect()
    };
    let LookShape::Cone { azimuth, elevation, half_angle } = sensor.fov.shape else {
        return Err(SsaError::BadSensor);
    };
    let total = config.geo + config.gto + config.molniya;
    let mut objects = Vec::with_capacity(total);
    let mut tracks = Vec::with_capacity(total);
    let mut visible = Vec::with_capacity(total);
    // GEO objects as `optical-geo`'s singles: mean longitude Ω + ω + M = θ₀ + λ.
    let theta0 = earth_rotation_angle(epoch_jd, 0.0);
    let mut random = Random::stream(seed, Stream::Orbit, 0);
    for _ in 0..config.geo {
        let longitude = sensor.site.longitude + deg(random.between(-2.0, 2.0));
        let (e, i) = (random.between(0.0, 2e-4), random.between(0.0, deg(0.1)));
        let (raan, argp) = (random.between(0.0, TAU), random.between(0.0, TAU));
        let state = kepler_state(geo_radius(), e, i, raan, argp, theta0 + longitude - raan - argp);
        let initial = geosynchronous(state, EARTH_ROTATION_RATE)?;
        let states = track(initial, &times)?;
        visible.push(seen_in(&states));
        objects.push(ObjectTruth::known(initial, None));
        tracks.push(states);
    }
    for unit in 0..config.gto + config.molniya {
        let transfer = unit < config.gto;
        let mut random = Random::stream(seed, Stream::Orbit, 1 + unit as u64);
        let mut chosen = None;
        for _attempt in 0..200 {
            let shape = draw_shape(&mut random, transfer);
            let nu = random.between(deg(90.0), deg(270.0));
            let radius = shape.a * (1.0 - shape.e * shape.e) / (1.0 + shape.e * nu.cos());
            let t_aim = times[random.below(times.len())];
            let observer = sensor.site.observer(earth_rotation_angle(epoch_jd, t_aim));
            // A line of sight within half the half-angle of the boresight, and its crossing of the sphere
            // of the orbit's radius at ν (the site is inside it: the far root).
            let el = elevation + random.between(-0.5, 0.5) * half_angle;
            let az = azimuth + random.between(-0.5, 0.5) * half_angle / el.cos();
            let point = observer.sphere_crossing(observer.direction(az, el), radius);
            let low = shape.inclination[0].max(radec(point)[1].abs() + deg(1.0));
            let high = shape.inclination[1].max(low);
            let inclination = random.between(low, high);
            let at_aim = aimed_eccentric(point, &shape, inclination, nu, random.uniform() < 0.5);
            let initial = Propagator::EARTH.propagate(at_aim, -t_aim)?;
            let states = track(initial, &times)?;
            let seen = seen_in(&states);
            if seen.iter().filter(|&&s| s).count() >= config.min_frames {
                chosen = Some((initial, states, seen));
                break;
            }
        }
        let (initial, states, seen) = chosen.ok_or(SsaError::OrbitSearch)?;
        objects.push(ObjectTruth { in_prior: false, ..ObjectTruth::known(initial, None) });
        tracks.push(states);
        visible.push(seen);
    }
    simulate(Plan {
        name: "optical-heo".into(),
        seed,
        epoch: OPTICAL_HEO_EPOCH.into(),
        duration: config.duration,
        sensors,
        objects,
        groups: Vec::new(),
        schedule,
        tracks: Some(tracks),
        visible: Some(visible),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::truth::MU;
    use crate::sim::vector::{add, norm, pos, scale, vel};

    #[test]
    fn an_aimed_eccentric_orbit_passes_through_its_point_with_its_shape() {
        let shape = Shape { a: 26_560.0, e: 0.72, inclination: [deg(63.4), deg(63.4)] };
        let nu = deg(200.0);
        let radius = shape.a * (1.0 - shape.e * shape.e) / (1.0 + shape.e * nu.cos());
        let direction = [0.3_f64, -0.9, -0.1];
        let point = scale(direction, radius / norm(direction));
        for ascending in [true, false] {
            let state = aimed_eccentric(point, &shape, deg(63.4), nu, ascending);
            let r = pos(&state);
            assert!(norm(add(r, scale(point, -1.0))) < 1e-6, "{r:?} is not {point:?}");
            // Vis-viva gives the semi-major axis back; the angular momentum the inclination.
            let v = norm(vel(&state));
            let a = 1.0 / (2.0 / norm(r) - v * v / MU);
            assert!((a - shape.a).abs() < 1e-6, "a {a}");
            let h = crate::sim::vector::cross(r, vel(&state));
            assert!((h[2] / norm(h) - deg(63.4).cos()).abs() < 1e-12);
        }
    }
}
