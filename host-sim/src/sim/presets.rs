//! The 3-D presets: `radar-leo` (ground radars, LEO objects), `optical-geo` (a telescope, GEO objects) and `tiny-3d`.

use super::breakup::breakup;
use super::error::SsaError;
use super::field_of_view::{FieldOfView, LookShape};
use super::frames::{fixed_to_inertial, radec};
use super::sensor::{SensorKind, SensorSpec};
use super::site::{Site, WGS84_A};
use super::ssa::{Plan, SsaScenario, count_passes, observers, simulate, visibility};
use super::time::{EARTH_ROTATION_RATE, earth_rotation_angle, parse_iso8601};
use super::truth::{
    Group, MU, ObjectTruth, Unknowns, aimed_circular, geosynchronous, kepler_state, mark_missing, track,
};
use super::vector::{add, deg, norm, pos, rotate, scale, vel};
use crate::sim::orbit::Propagator;
use crate::sim::rng::{Random, Stream};
use core::f64::consts::{FRAC_PI_2, PI, TAU};

/// Parameters of [`radar_leo_with`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RadarLeoConfig {
    /// Objects on their own orbits.
    pub singles: usize,
    /// Crossing pairs (two objects each).
    pub pairs: usize,
    /// Duration (s).
    pub duration: f64,
    /// Time between two scans of one radar (s); the radars alternate, offset by half of it.
    pub revisit: f64,
    /// Passes every object must have (orbits are redrawn until they do).
    pub min_passes: usize,
    /// Objects unknown to the prior.
    pub unknowns: Unknowns,
}

impl RadarLeoConfig {
    /// The `radar-leo` preset: 100 singles + 10 crossing pairs, 6 h, each radar every 20 s.
    pub const PRESET: RadarLeoConfig = RadarLeoConfig {
        singles: 100,
        pairs: 10,
        duration: 6.0 * 3600.0,
        revisit: 20.0,
        min_passes: 2,
        unknowns: Unknowns { missing_fraction: 0.0, breakup: 0 },
    };
}

/// The two radars of `radar-leo`.
pub fn leo_radars() -> Vec<SensorSpec> {
    let sigma = vec![0.020, deg(0.03), deg(0.03)];
    vec![
        SensorSpec {
            name: "radar-north".into(),
            site: Site { latitude: deg(47.35), longitude: deg(8.50), height: 0.5 },
            kind: SensorKind::Radar,
            fov: FieldOfView {
                shape: LookShape::Box {
                    azimuth_centre: 0.0,
                    azimuth_half_width: PI,
                    elevation_min: deg(15.0),
                    elevation_max: FRAC_PI_2,
                },
                min_elevation: deg(15.0),
                range: Some([200.0, 3000.0]),
            },
            sigma: sigma.clone(),
            detection_probability: 0.9,
            clutter_rate: 2.0,
        },
        SensorSpec {
            name: "radar-south".into(),
            site: Site { latitude: deg(37.40), longitude: deg(-5.90), height: 0.1 },
            kind: SensorKind::Radar,
            fov: FieldOfView {
                shape: LookShape::Cone { azimuth: PI, elevation: deg(55.0), half_angle: deg(45.0) },
                min_elevation: deg(10.0),
                range: Some([200.0, 3000.0]),
            },
            sigma,
            detection_probability: 0.9,
            clutter_rate: 2.0,
        },
    ]
}

const LEO_EPOCH: &str = "2026-03-20T00:00:00Z";

/// `radar-leo`: two ground radars ~1600 km apart (47.35° N 8.50° E: all-azimuth box, elevation
/// 15–90°; 37.40° N 5.90° W: cone of 45° about azimuth 180°, elevation 55°, mask 10°; both 200–3000 km),
/// σ = 20 m, 0.03°, 0.03°, p_D 0.9, 2 clutter per scan; 100 LEO objects and 10 crossing pairs over 6 h,
/// every object with ≥ 2 passes; each radar scans every 20 s, alternating (one scan every 10 s).
///
/// # Errors
/// [`SsaError`] if propagation fails or a scan would exceed [`MAX_MEASUREMENTS`].
pub fn radar_leo(seed: u64) -> Result<SsaScenario, SsaError> {
    radar_leo_with(seed, &RadarLeoConfig::PRESET)
}

/// `radar-leo` with other sizes (tests use a short one).
///
/// Every object's orbit is built to pass over a point near one of the sites (within ±8° of latitude and
/// longitude of it) at a random time: altitude 400–1500 km, inclination between 3° above the aim
/// point's latitude and 3° below its supplement, near circular. The orbit is redrawn (at most 200 times, from the object's
/// own stream) until the object has `min_passes` passes, else [`SsaError::OrbitSearch`]. A crossing pair is an object and a twin that at
/// the aim time is 1–3 km higher on the same radial with its orbit plane turned by 0.3–1.5° about that
/// radial: the two cross in the sky over the aim point.
///
/// # Errors
/// As [`radar_leo`].
pub fn radar_leo_with(seed: u64, config: &RadarLeoConfig) -> Result<SsaScenario, SsaError> {
    let sensors = leo_radars();
    let epoch_jd = parse_iso8601(LEO_EPOCH)?;
    let half = config.revisit * 0.5;
    let steps = (config.duration / half).floor() as usize;
    let schedule: Vec<(f64, usize)> = (0..=steps).map(|k| (k as f64 * half, k % 2)).collect();
    let times: Vec<f64> = schedule.iter().map(|&(t, _)| t).collect();
    let obs = observers(&sensors, epoch_jd, &schedule);
    let mut objects = Vec::new();
    let mut groups = Vec::new();
    let mut tracks = Vec::new();
    let units = config.singles + config.pairs;
    for unit in 0..units {
        let paired = unit >= config.singles;
        let mut random = Random::stream(seed, Stream::Orbit, unit as u64);
        let mut chosen = None;
        for _attempt in 0..200 {
            let site = &sensors[unit % 2].site;
            let aim_site = Site {
                latitude: site.latitude + deg(random.between(-8.0, 8.0)),
                longitude: site.longitude + deg(random.between(-8.0, 8.0)),
                height: 0.0,
            };
            let t_aim = random.between(0.0, config.duration);
            let ground = fixed_to_inertial(aim_site.earth_fixed(), earth_rotation_angle(epoch_jd, t_aim));
            let aim = radec(ground);
            let radius = WGS84_A + random.between(400.0, 1500.0);
            let lo = aim[1].abs() + deg(3.0);
            let inclination = random.between(lo, PI - lo);
            let ascending = random.uniform() < 0.5;
            let at_aim = aimed_circular(aim, radius, inclination, ascending);
            let mut members = vec![at_aim];
            if paired {
                let up = scale(pos(&at_aim), 1.0 / norm(pos(&at_aim)));
                let dr = random.between(1.0, 3.0);
                let turn = deg(random.between(0.3, 1.5)) * if random.uniform() < 0.5 { -1.0 } else { 1.0 };
                let r2 = add(pos(&at_aim), scale(up, dr));
                let v2 = scale(rotate(vel(&at_aim), up, turn), (radius / (radius + dr)).sqrt());
                members.push([r2[0], r2[1], r2[2], v2[0], v2[1], v2[2]]);
            }
            let mut candidate = Vec::new();
            let mut ok = true;
            for m in &members {
                let initial = Propagator::EARTH.propagate(*m, -t_aim)?;
                let states = track(initial, &times)?;
                let visible = visibility(&sensors, &schedule, &obs, &states);
                ok &= count_passes(&schedule, &visible, sensors.len()) >= config.min_passes;
                candidate.push((initial, states));
                if !ok {
                    break;
                }
            }
            if ok {
                chosen = Some(candidate);
                break;
            }
        }
        let candidate = chosen.ok_or(SsaError::OrbitSearch)?;
        let group = paired.then(|| {
            groups.push(Group { kind: "crossing-pair".into(), objects: vec![objects.len(), objects.len() + 1] });
            groups.len() - 1
        });
        for (initial, states) in candidate {
            objects.push(ObjectTruth::known(initial, group));
            tracks.push(states);
        }
    }
    let n = objects.len();
    mark_missing(seed, &mut objects, n, config.unknowns.missing_fraction)?;
    if config.unknowns.breakup > 0 && config.singles > 0 {
        // The parent: a single, chosen by the break-up's own stream.
        let mut random = Random::stream(seed, Stream::Scenario, 3_000_001);
        let parent = ((random.uniform() * config.singles as f64) as usize).min(config.singles - 1);
        let visible = visibility(&sensors, &schedule, &obs, &tracks[parent]);
        groups.push(Group { kind: "breakup".into(), objects: vec![parent] });
        let group = groups.len() - 1;
        objects[parent].group = Some(group);
        let fragments =
            breakup(seed, &objects[parent], config.unknowns.breakup, group, &schedule, &visible, sensors.len())?;
        for (fragment, states) in fragments {
            groups[group].objects.push(objects.len());
            objects.push(fragment);
            tracks.push(states);
        }
    } else if config.unknowns.breakup > 0 {
        return Err(SsaError::BadUnknowns);
    }
    simulate(Plan {
        name: "radar-leo".into(),
        seed,
        epoch: LEO_EPOCH.into(),
        duration: config.duration,
        sensors,
        objects,
        groups,
        schedule,
        tracks: Some(tracks),
        visible: None,
    })
}

/// `tiny-3d`: the northern radar of `radar-leo` alone, 3 LEO objects aimed to pass near it at 40, 50
/// and 60 s, 11 scans every 10 s (0–100 s), p_D 0.95, 0.5 clutter per scan.
///
/// # Errors
/// As [`radar_leo`].
pub fn tiny_3d(seed: u64) -> Result<SsaScenario, SsaError> {
    tiny_3d_with(seed, &Unknowns::default())
}

/// [`tiny_3d`] with objects unknown to the prior (no break-up): a small 3-D scenario with births, small
/// enough for the unbounded reference.
///
/// # Errors
/// [`SsaError::BadUnknowns`] for a break-up or a fraction outside [0, 1].
pub fn tiny_3d_with(seed: u64, unknowns: &Unknowns) -> Result<SsaScenario, SsaError> {
    if unknowns.breakup > 0 {
        return Err(SsaError::BadUnknowns);
    }
    let mut sensor = leo_radars().remove(0);
    sensor.detection_probability = 0.95;
    sensor.clutter_rate = 0.5;
    let epoch_jd = parse_iso8601(LEO_EPOCH)?;
    let mut objects = Vec::new();
    for k in 0..3 {
        let mut random = Random::stream(seed, Stream::Orbit, k);
        let t_aim = 40.0 + 10.0 * k as f64;
        let aim_site = Site {
            latitude: sensor.site.latitude + deg(random.between(-3.0, 3.0)),
            longitude: sensor.site.longitude + deg(random.between(-3.0, 3.0)),
            height: 0.0,
        };
        let aim = radec(fixed_to_inertial(aim_site.earth_fixed(), earth_rotation_angle(epoch_jd, t_aim)));
        let radius = WGS84_A + random.between(500.0, 1200.0);
        let lo = aim[1].abs() + deg(3.0);
        let at_aim = aimed_circular(aim, radius, random.between(lo, PI - lo), random.uniform() < 0.5);
        objects.push(ObjectTruth::known(Propagator::EARTH.propagate(at_aim, -t_aim)?, None));
    }
    mark_missing(seed, &mut objects, 3, unknowns.missing_fraction)?;
    simulate(Plan {
        name: "tiny-3d".into(),
        seed,
        epoch: LEO_EPOCH.into(),
        duration: 100.0,
        sensors: vec![sensor],
        objects,
        groups: Vec::new(),
        schedule: (0..=10).map(|k| (10.0 * k as f64, 0)).collect(),
        tracks: None,
        visible: None,
    })
}

/// Parameters of [`optical_geo_with`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OpticalGeoConfig {
    /// Station-kept objects on their own slots (always in view).
    pub singles: usize,
    /// Uncontrolled inclined objects that sweep north–south through the field.
    pub sweepers: usize,
    /// Co-located clusters.
    pub clusters: usize,
    /// Objects per cluster.
    pub cluster_size: usize,
    /// Duration (s).
    pub duration: f64,
    /// Time between scans (s).
    pub cadence: f64,
    /// Objects unknown to the prior (no break-up: [`Unknowns::breakup`] must be 0).
    pub unknowns: Unknowns,
}

impl OpticalGeoConfig {
    /// The `optical-geo` preset: 6 singles + 3 clusters of 4 + 12 sweepers, 4 h, a frame every 90 s.
    pub const PRESET: OpticalGeoConfig = OpticalGeoConfig {
        singles: 6,
        sweepers: 12,
        clusters: 3,
        cluster_size: 4,
        duration: 4.0 * 3600.0,
        cadence: 90.0,
        unknowns: Unknowns { missing_fraction: 0.0, breakup: 0 },
    };
}

const GEO_EPOCH: &str = "2026-03-20T02:00:00Z";

/// The staring telescope of `optical-geo`, pointed at the GEO belt on its own meridian.
pub fn geo_telescope() -> SensorSpec {
    geo_telescope_at("telescope", Site { latitude: deg(32.0), longitude: deg(-110.0), height: 2.0 })
}

/// A telescope like [`geo_telescope`] at `site`, staring at the geostationary point at 110° W.
pub fn geo_telescope_at(name: &str, site: Site) -> SensorSpec {
    // Boresight: the look angles of the geostationary point at the site's longitude.
    let geo = Site { latitude: 0.0, longitude: deg(-110.0), height: geo_radius() - WGS84_A };
    let observer = site.observer(0.0);
    let (_, azimuth, elevation) = observer.range_az_el(fixed_to_inertial(geo.earth_fixed(), 0.0));
    SensorSpec {
        name: name.into(),
        site,
        kind: SensorKind::Optical,
        fov: FieldOfView {
            shape: LookShape::Cone { azimuth, elevation, half_angle: deg(3.0) },
            min_elevation: deg(20.0),
            range: None,
        },
        sigma: vec![deg(1.5 / 3600.0), deg(1.5 / 3600.0)],
        detection_probability: 0.95,
        clutter_rate: 1.0,
    }
}

/// The geosynchronous radius (km): mean motion ω_E.
pub(crate) fn geo_radius() -> f64 {
    (MU / (EARTH_ROTATION_RATE * EARTH_ROTATION_RATE)).cbrt()
}

/// `optical-geo`: one staring telescope at 32° N 110° W, 2 km, a cone of half-angle 3° about the GEO
/// belt on its meridian (az 180°, el ≈ 52.7°), mask 20°, σ 1.5″ per angle, p_D 0.95, 1 clutter per
/// frame; a frame every 90 s for 4 h. Objects: 6 station-kept singles within ±2° of longitude of the
/// meridian (e ≤ 2e-4, i ≤ 0.1°), 3 co-located clusters of 4 (slots near −1.5°, 0°, +1.5°; members
/// within ±0.015° of longitude of the slot, e ≤ 8e-5, i ≤ 0.01°), always in view; and 12 uncontrolled
/// inclined geosynchronous objects (i 10–16°, circular) crossing the equator within ±2° of the meridian
/// at a random time of the run, each in view for about 1–1.5 h. The sweepers keep the number in view at once
/// below the 32 measurements a scan may carry while at least 30 objects are seen.
///
/// # Errors
/// As [`radar_leo`].
pub fn optical_geo(seed: u64) -> Result<SsaScenario, SsaError> {
    optical_geo_with(seed, &OpticalGeoConfig::PRESET)
}

/// `optical-geo` with other sizes.
///
/// # Errors
/// As [`radar_leo`].
pub fn optical_geo_with(seed: u64, config: &OpticalGeoConfig) -> Result<SsaScenario, SsaError> {
    let sensor = geo_telescope();
    let epoch_jd = parse_iso8601(GEO_EPOCH)?;
    let theta0 = earth_rotation_angle(epoch_jd, 0.0);
    let a = geo_radius();
    let mut objects = Vec::new();
    let mut groups = Vec::new();
    let state_at = |random: &mut Random, longitude: f64, e_max: f64, i_max: f64| {
        let e = random.between(0.0, e_max);
        let i = random.between(0.0, i_max);
        let raan = random.between(0.0, TAU);
        let argp = random.between(0.0, TAU);
        // Mean longitude Ω + ω + M = θ₀ + λ.
        let m = theta0 + longitude - raan - argp;
        geosynchronous(kepler_state(a, e, i, raan, argp, m), EARTH_ROTATION_RATE)
    };
    let mut random = Random::stream(seed, Stream::Orbit, 0);
    for _ in 0..config.singles {
        let longitude = sensor.site.longitude + deg(random.between(-2.0, 2.0));
        let s = state_at(&mut random, longitude, 2e-4, deg(0.1))?;
        objects.push(ObjectTruth::known(s, None));
    }
    for _ in 0..config.sweepers {
        let t_node = random.between(0.0, config.duration);
        let longitude = sensor.site.longitude + deg(random.between(-2.0, 2.0));
        let inclination = deg(random.between(10.0, 16.0));
        let at_node = aimed_circular(
            [earth_rotation_angle(epoch_jd, t_node) + longitude, 0.0],
            a,
            inclination,
            random.uniform() < 0.5,
        );
        let at_node = geosynchronous(at_node, EARTH_ROTATION_RATE)?;
        let s = Propagator::EARTH.propagate(at_node, -t_node)?;
        objects.push(ObjectTruth::known(s, None));
    }
    for c in 0..config.clusters {
        let slot = sensor.site.longitude + deg(-1.5 + 1.5 * c as f64 + random.between(-0.3, 0.3));
        let mut members = Vec::new();
        for _ in 0..config.cluster_size {
            let longitude = slot + deg(random.between(-0.015, 0.015));
            members.push(objects.len());
            let s = state_at(&mut random, longitude, 8e-5, deg(0.01))?;
            objects.push(ObjectTruth::known(s, Some(groups.len())));
        }
        groups.push(Group { kind: "cluster".into(), objects: members });
    }
    if config.unknowns.breakup > 0 {
        return Err(SsaError::BadUnknowns);
    }
    let n = objects.len();
    mark_missing(seed, &mut objects, n, config.unknowns.missing_fraction)?;
    let steps = (config.duration / config.cadence).floor() as usize;
    simulate(Plan {
        name: "optical-geo".into(),
        seed,
        epoch: GEO_EPOCH.into(),
        duration: config.duration,
        sensors: vec![sensor],
        objects,
        groups,
        schedule: (0..=steps).map(|k| (k as f64 * config.cadence, 0)).collect(),
        tracks: None,
        visible: None,
    })
}
