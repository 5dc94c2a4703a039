//! The `ssa-network` preset: one network of six sensors of four kinds over LEO, GEO and Molniya objects,
//! some unknown to the prior, for the fused tracker (docs/maths.md §6.10).
//!
//! Sensors (they take turns, one scan every 10 s, so each scans once a minute):
//! - `radar-north`, `radar-south`: the two radars of `radar-leo`, the second with range-rate (σ 1 m/s);
//! - `telescope-west`, `telescope-east`: two staring telescopes 450 km apart on the GEO belt at 110° W
//!   (σ 1.5″ per angle, cones of 3°): their fields of view overlap;
//! - `az-el-station`: a ground station's mount angles (σ 2″) near Bern, zenith cone of 70°, mask 20°;
//! - `ranging-station`: a range-only station near Graz (σ 5 m), zenith cone of 75°, 300–45,000 km.
//!
//! Objects ([`NetworkConfig::PRESET`]): 12 LEO objects aimed over the radar sites (as `radar-leo` builds them, with two passes of
//! the network at least), 6 station-kept GEO objects within ±1° of 110° W, and 3 Molniya objects
//! (a = 26,560 km, e = 0.72, i = 63.4°, ω = 270°) each seen by some sensor at least once. Unknown to the
//! prior: 3 of the LEO objects and 1 of the GEO objects (or `--missing-fraction` of the LEO and GEO
//! objects), chosen by the seed; the Molniya objects are always known (no admissible region covers them
//! yet).

use super::error::SsaError;
use super::field_of_view::{FieldOfView, LookShape};
use super::frames::{fixed_to_inertial, radec};
use super::presets::{geo_telescope_at, leo_radars};
use super::sensor::{SensorKind, SensorSpec};
use super::site::{Site, WGS84_A};
use super::ssa::{Plan, SsaScenario, count_passes, observers, simulate, visibility};
use super::time::{earth_rotation_angle, parse_iso8601};
use super::truth::{ObjectTruth, Unknowns, aimed_circular, kepler_state, track};
use super::vector::deg;
use crate::sim::orbit::Propagator;
use crate::sim::rng::{Random, Stream};
use core::f64::consts::{FRAC_PI_2, PI, TAU};

/// The preset's epoch.
const EPOCH: &str = "2026-03-20T00:00:00Z";
/// Seconds between two scans (of any sensor).
const CADENCE: f64 = 10.0;

/// The sizes of a network scenario.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NetworkConfig {
    /// The preset's name.
    pub name: &'static str,
    /// The run's duration (s).
    pub duration: f64,
    /// LEO objects, and the passes of the network each must have.
    pub leo: usize,
    /// Passes of the network every LEO object must have.
    pub leo_passes: usize,
    /// GEO objects.
    pub geo: usize,
    /// Molniya objects.
    pub molniya: usize,
    /// The LEO and the GEO objects unknown to the prior by default.
    pub unknown: [usize; 2],
}

impl NetworkConfig {
    /// `ssa-network`.
    pub const PRESET: NetworkConfig = NetworkConfig {
        name: "ssa-network",
        duration: 3.0 * 3600.0,
        leo: 12,
        leo_passes: 2,
        geo: 6,
        molniya: 3,
        unknown: [3, 1],
    };

    /// `tiny-network` (tests, `compare` against the reference): 2 LEO objects (one unknown), 1 GEO and 1
    /// Molniya object, 10 minutes.
    pub const TINY: NetworkConfig = NetworkConfig {
        name: "tiny-network",
        duration: 600.0,
        leo: 2,
        leo_passes: 1,
        geo: 1,
        molniya: 1,
        unknown: [1, 0],
    };
}

/// The six sensors.
pub fn network_sensors() -> Vec<SensorSpec> {
    let mut sensors = leo_radars();
    if let Some(south) = sensors.get_mut(1) {
        south.kind = SensorKind::RadarRangeRate { max_range_rate: 8.0 };
        south.sigma.push(1e-3);
    }
    let west = geo_telescope_at("telescope-west", Site { latitude: deg(32.0), longitude: deg(-110.0), height: 2.0 });
    let east = geo_telescope_at("telescope-east", Site { latitude: deg(33.0), longitude: deg(-105.3), height: 2.2 });
    let zenith = |half_angle: f64| LookShape::Cone { azimuth: 0.0, elevation: FRAC_PI_2, half_angle: deg(half_angle) };
    let az_el = SensorSpec {
        name: "az-el-station".into(),
        site: Site { latitude: deg(46.88), longitude: deg(7.47), height: 0.95 },
        kind: SensorKind::AzEl,
        fov: FieldOfView { shape: zenith(70.0), min_elevation: deg(20.0), range: None },
        sigma: vec![deg(2.0 / 3600.0), deg(2.0 / 3600.0)],
        detection_probability: 0.85,
        clutter_rate: 0.5,
    };
    let ranging = SensorSpec {
        name: "ranging-station".into(),
        site: Site { latitude: deg(47.07), longitude: deg(15.49), height: 0.5 },
        kind: SensorKind::Range,
        fov: FieldOfView { shape: zenith(75.0), min_elevation: deg(15.0), range: Some([300.0, 45_000.0]) },
        sigma: vec![0.005],
        detection_probability: 0.8,
        clutter_rate: 0.5,
    };
    sensors.extend([west, east, az_el, ranging]);
    sensors
}

/// `ssa-network` with `seed` (see the module documentation); `unknowns.missing_fraction` > 0 replaces the
/// default unknown objects by that fraction of the LEO and GEO objects.
///
/// # Errors
/// [`SsaError::BadUnknowns`] for a break-up; [`SsaError::OrbitSearch`] when an orbit with the passes it
/// needs is not found in 200 draws; propagation errors.
pub fn ssa_network(seed: u64, unknowns: &Unknowns, config: &NetworkConfig) -> Result<SsaScenario, SsaError> {
    if unknowns.breakup > 0 || !(0.0..=1.0).contains(&unknowns.missing_fraction) {
        return Err(SsaError::BadUnknowns);
    }
    let sensors = network_sensors();
    let epoch_jd = parse_iso8601(EPOCH)?;
    let steps = (config.duration / CADENCE).floor() as usize;
    let schedule: Vec<(f64, usize)> = (0..=steps).map(|k| (k as f64 * CADENCE, k % sensors.len())).collect();
    let times: Vec<f64> = schedule.iter().map(|&(t, _)| t).collect();
    let obs = observers(&sensors, epoch_jd, &schedule);
    let passes = |initial: [f64; 6]| -> Result<usize, SsaError> {
        let states = track(initial, &times)?;
        Ok(count_passes(&schedule, &visibility(&sensors, &schedule, &obs, &states), sensors.len()))
    };
    let mut objects = Vec::with_capacity(config.leo + config.geo + config.molniya);
    for unit in 0..config.leo {
        let mut random = Random::stream(seed, Stream::Orbit, unit as u64);
        let site = sensors[unit % 2].site;
        let initial = search(|| {
            let aim_site = Site {
                latitude: site.latitude + deg(random.between(-8.0, 8.0)),
                longitude: site.longitude + deg(random.between(-8.0, 8.0)),
                height: 0.0,
            };
            let t_aim = random.between(0.0, config.duration);
            let aim = radec(fixed_to_inertial(aim_site.earth_fixed(), earth_rotation_angle(epoch_jd, t_aim)));
            let radius = WGS84_A + random.between(400.0, 1500.0);
            let low = aim[1].abs() + deg(3.0);
            let inclination = random.between(low, PI - low);
            let at_aim = aimed_circular(aim, radius, inclination, random.uniform() < 0.5);
            let initial = Propagator::EARTH.propagate(at_aim, -t_aim)?;
            Ok((passes(initial)? >= config.leo_passes).then_some(initial))
        })?;
        objects.push(ObjectTruth::known(initial, None));
    }
    let theta0 = earth_rotation_angle(epoch_jd, 0.0);
    let geo_radius = super::presets::geo_radius();
    let mut random = Random::stream(seed, Stream::Orbit, config.leo as u64);
    for _ in 0..config.geo {
        let longitude = deg(-110.0 + random.between(-1.0, 1.0));
        let (e, i) = (random.between(0.0, 2e-4), deg(random.between(0.0, 0.1)));
        let (raan, argp) = (random.between(0.0, TAU), random.between(0.0, TAU));
        // Mean longitude Ω + ω + M = θ₀ + λ.
        objects.push(ObjectTruth::known(
            kepler_state(geo_radius, e, i, raan, argp, theta0 + longitude - raan - argp),
            None,
        ));
    }
    for unit in 0..config.molniya {
        let mut random = Random::stream(seed, Stream::Orbit, (config.leo + 1 + unit) as u64);
        let initial = search(|| {
            let state =
                kepler_state(26_560.0, 0.72, deg(63.4), random.between(0.0, TAU), deg(270.0), random.between(0.0, TAU));
            Ok((passes(state)? >= 1).then_some(state))
        })?;
        objects.push(ObjectTruth::known(initial, None));
    }
    mark_unknown(seed, &mut objects, unknowns.missing_fraction, config);
    simulate(Plan {
        name: config.name.into(),
        seed,
        epoch: EPOCH.into(),
        duration: config.duration,
        sensors,
        objects,
        groups: vec![],
        schedule,
        tracks: None,
        visible: None,
    })
}

/// The first orbit `draw` accepts in 200 draws.
fn search(mut draw: impl FnMut() -> Result<Option<[f64; 6]>, SsaError>) -> Result<[f64; 6], SsaError> {
    for _ in 0..200 {
        if let Some(state) = draw()? {
            return Ok(state);
        }
    }
    Err(SsaError::OrbitSearch)
}

/// Leaves objects out of the prior, chosen by the seed's stream [`Stream::Scenario`] 2,000,000: by
/// default `config.unknown` LEO and GEO objects, else `fraction` of each.
fn mark_unknown(seed: u64, objects: &mut [ObjectTruth], fraction: f64, config: &NetworkConfig) {
    let mut random = Random::stream(seed, Stream::Scenario, 2_000_000);
    let (leo, geo) = (0..config.leo, config.leo..config.leo + config.geo);
    for (range, default) in [(leo, config.unknown[0]), (geo, config.unknown[1])] {
        let mut order: Vec<usize> = range.clone().collect();
        random.shuffle(&mut order);
        let count = if fraction > 0.0 { (fraction * order.len() as f64).round() as usize } else { default };
        for &i in order.iter().take(count) {
            objects[i].in_prior = false;
        }
    }
}
