//! The catalogue's world, streamed: each scan's truth (SGP4 for every object, in parallel) and detections
//! are drawn when the scan comes and dropped after it, so nothing grows with the run's length.
//!
//! The network: a wide-field surveillance ("fence") radar near the equator (Kwajalein, 9.4° N 167.5° E: all
//! azimuths above 10° elevation, 200-4000 km, σ 50 m and 0.05°, p_D 0.9, 5 clutter returns a scan), which
//! sees hundreds of objects at once in a catalogue of 10,000, and the two radars of `radar-leo`
//! ([`presets::leo_radars`]). The sensors take turns, each every [`SCAN_INTERVAL_S`].

use crate::error::Error;
use crate::io::catalogue::{CatalogueEntry, Satellite, screen};
use crate::pipeline::orbital::{FieldOfViewCheck, measurements_in_radians};
use crate::scenario::from_simulation::{KnownTruth, to_scenario_with};
use crate::scenario::v2::{Measurement3dSpec, Scenario3d};
use crate::sim::field_of_view::{FieldOfView, LookShape};
use crate::sim::rng::{Random, Stream};
use crate::sim::sensor::{SensorKind, SensorSpec};
use crate::sim::site::Site;
use crate::sim::ssa::{SsaScenario, draw_scan_any_size};
use crate::sim::truth::ObjectTruth;
use crate::sim::{presets, time};
use nalgebra::SVector;
use rayon::prelude::*;
use sgp4::chrono::NaiveDateTime;

/// Seconds between two scans of one sensor.
pub const SCAN_INTERVAL_S: f64 = 20.0;

/// The run's start (UTC): the synthetic catalogue's epoch.
pub const START: &str = "2026-03-20T00:00:00Z";

/// Fraction of the catalogue missing from the prior (births), chosen by the seed.
pub const MISSING_FRACTION: f64 = 0.02;

/// Seconds between two times of the screening for SGP4 failures before the run (a failure between them is
/// caught at the scan and the object dropped then).
const SCREEN_STEP_S: f64 = 600.0;

/// The wide-field radar.
pub fn fence() -> SensorSpec {
    SensorSpec {
        name: "fence".into(),
        site: Site { latitude: 9.39_f64.to_radians(), longitude: 167.48_f64.to_radians(), height: 0.0 },
        kind: SensorKind::Radar,
        fov: FieldOfView {
            shape: LookShape::Box {
                azimuth_centre: 0.0,
                azimuth_half_width: std::f64::consts::PI,
                elevation_min: 10.0_f64.to_radians(),
                elevation_max: std::f64::consts::FRAC_PI_2,
            },
            min_elevation: 10.0_f64.to_radians(),
            range: Some([200.0, 4000.0]),
        },
        sigma: vec![0.05, 0.05_f64.to_radians(), 0.05_f64.to_radians()],
        detection_probability: 0.9,
        clutter_rate: 5.0,
    }
}

/// One scan as the tracker and the scoring see it.
pub struct Scan {
    pub time: f64,
    pub sensor: usize,
    /// Measurements in the tracker's units (km, rad).
    pub measurements: Vec<SVector<f64, 3>>,
    /// The objects (ids) detected.
    pub detected: Vec<u64>,
    /// Objects in the sensor's field of view.
    pub in_view: usize,
    /// Every object still tracked: id and true position.
    pub truth: Vec<(u64, [f64; 3])>,
}

/// The streamed world.
pub struct World {
    seed: u64,
    epoch: NaiveDateTime,
    epoch_jd: f64,
    pub sensors: Vec<SensorSpec>,
    satellites: Vec<Satellite>,
    /// Per object, whether SGP4 still propagates it.
    alive: Vec<bool>,
    detection: Vec<Random>,
    /// Seconds between two scans (of successive sensors).
    slot: f64,
    scans: usize,
    check: Option<FieldOfViewCheck>,
    /// Element sets left out before the run and objects dropped during it.
    pub dropped: usize,
}

impl World {
    /// The world of `entries` over `hours` from [`START`], objects dropped (with a warning) where SGP4 fails
    /// at one of the screening times.
    ///
    /// # Errors
    /// [`Error::Input`] when every element set is dropped.
    pub fn new(entries: Vec<CatalogueEntry>, hours: f64, seed: u64) -> Result<Self, Error> {
        let epoch = crate::io::catalogue::parse_omm_epoch(START).ok_or_else(|| Error::internal("start"))?;
        let epoch_jd = time::parse_iso8601(START).map_err(|e| Error::internal(format!("start: {e}")))?;
        let duration = hours * 3600.0;
        let steps = (duration / SCREEN_STEP_S).ceil() as usize;
        let times: Vec<f64> =
            std::iter::once(-1.0).chain((0..=steps).map(|k| (k as f64 * SCREEN_STEP_S).min(duration))).collect();
        let screened = screen::screen_for_run("synthetic catalogue", entries, epoch, &times);
        screen::print_warnings(&screened.warnings);
        if screened.satellites.is_empty() {
            return Err(Error::input("synthetic catalogue: every element set is dropped (see the warnings)"));
        }
        let sensors = vec![fence(), presets::leo_radars().remove(0), presets::leo_radars().remove(1)];
        let slot = SCAN_INTERVAL_S / sensors.len() as f64;
        let n = screened.satellites.len();
        let scans = (duration * sensors.len() as f64 / SCAN_INTERVAL_S + 1e-9).floor() as usize + 1;
        Ok(World {
            seed,
            epoch,
            epoch_jd,
            sensors,
            satellites: screened.satellites,
            alive: vec![true; n],
            detection: (0..n).map(|i| Random::stream(seed, Stream::Detection, i as u64)).collect(),
            slot,
            scans,
            check: None,
            dropped: screened.dropped.count,
        })
    }

    /// Objects in the run (those dropped during it included).
    pub fn objects(&self) -> usize {
        self.satellites.len()
    }

    /// Objects SGP4 still propagates.
    pub fn tracked(&self) -> usize {
        self.alive.iter().filter(|&&a| a).count()
    }

    /// Scans of the run.
    pub fn scans(&self) -> usize {
        self.scans
    }

    /// Which objects the prior misses: `round(MISSING_FRACTION × objects)` chosen by the seed.
    fn missing(&self) -> Vec<bool> {
        let n = self.satellites.len();
        let mut order: Vec<usize> = (0..n).collect();
        Random::stream(self.seed, Stream::Scenario, 3_000_000).shuffle(&mut order);
        let mut missing = vec![false; n];
        for &i in &order[..((MISSING_FRACTION * n as f64).round() as usize).min(n)] {
            missing[i] = true;
        }
        missing
    }

    /// The scenario the tracker is configured from (sensors, models, births, prior: each known object's SGP4
    /// state 1 s before the first scan plus a draw of the prior's error; no scans), as `generate catalogue`
    /// makes it; object i's prior label is i.
    ///
    /// # Errors
    /// As [`to_scenario_with`].
    pub fn scenario(&mut self) -> Result<Scenario3d, Error> {
        let missing = self.missing();
        let objects = missing
            .iter()
            .map(|&m| ObjectTruth { initial_state: [0.0; 6], group: None, in_prior: !m, birth_time: None })
            .collect();
        let simulation = SsaScenario {
            name: "catalogue-scale".into(),
            seed: self.seed,
            epoch: START.into(),
            epoch_jd: self.epoch_jd,
            duration: self.slot * (self.scans - 1) as f64,
            sensors: self.sensors.clone(),
            objects,
            groups: vec![],
            scans: vec![],
        };
        let state = |i: usize, t: f64| -> Result<[f64; 6], Error> {
            let (r, v) = self.satellites[i]
                .tracker_state(self.epoch, t)
                .map_err(|e| Error::input(format!("object {}: {e}", self.satellites[i].entry.norad_id)))?;
            Ok([r[0], r[1], r[2], v[0], v[1], v[2]])
        };
        let known = KnownTruth { state: &state, source: "SGP4 (WGS-72, AFSPC mode)" };
        let (scenario, _) = to_scenario_with(&simulation, Some(known))?;
        if scenario.measurement != Measurement3dSpec::Radar {
            return Err(Error::internal("catalogue-scale: the network is not of radars only"));
        }
        self.check = Some(FieldOfViewCheck::new(&scenario)?);
        Ok(scenario)
    }

    /// Scan `k`: every object propagated (in parallel; an object SGP4 fails on is dropped with a warning),
    /// the sensor's detections and clutter drawn, the measurements outside the field of view left out (a
    /// noisy detection at its edge: the tracker refuses them, as `generate catalogue` leaves them out).
    ///
    /// # Errors
    /// The simulator's error (clutter in an empty field of view).
    pub fn scan(&mut self, k: usize) -> Result<Scan, Error> {
        let time = k as f64 * self.slot;
        let sensor = k % self.sensors.len();
        let (epoch, alive) = (self.epoch, &self.alive);
        let states: Vec<Option<Result<[f64; 6], String>>> = self
            .satellites
            .par_iter()
            .zip(alive.par_iter())
            .map(|(s, &alive)| {
                alive.then(|| {
                    let (r, v) = s.tracker_state(epoch, time).map_err(|e| e.to_string())?;
                    Ok([r[0], r[1], r[2], v[0], v[1], v[2]])
                })
            })
            .collect();
        for (i, state) in states.iter().enumerate() {
            if let Some(Err(e)) = state {
                let id = self.satellites[i].entry.norad_id;
                eprintln!("warning: object {id}: dropped at start + {time} s: {e}");
                self.alive[i] = false;
                self.dropped += 1;
            }
        }
        let states: Vec<Option<[f64; 6]>> = states.into_iter().map(|s| s.and_then(Result::ok)).collect();
        let observer = self.sensors[sensor].site.observer(time::earth_rotation_angle(self.epoch_jd, time));
        let spec = &self.sensors[sensor];
        let drawn = draw_scan_any_size(
            self.seed,
            k,
            (time, sensor),
            spec,
            &observer,
            states.iter().copied(),
            &mut self.detection,
        )
        .map_err(|e| Error::internal(format!("scan {k}: {e}")))?;
        let mut origin = vec![None; drawn.measurements.len()];
        for t in &drawn.truth {
            if let Some(j) = t.measurement {
                origin[j] = Some(t.object as u64);
            }
        }
        let check = self.check.as_ref().ok_or_else(|| Error::internal("catalogue-scale: scan before scenario"))?;
        let (mut measurements, mut detected) = (vec![], vec![]);
        for (z, origin) in drawn.measurements.iter().zip(origin) {
            // As a scenario file holds it (degrees) and the tracker reads it back.
            let degrees: Vec<f64> =
                z.iter().enumerate().map(|(i, &v)| if i > 0 { v.to_degrees() } else { v }).collect();
            let z = &measurements_in_radians(Measurement3dSpec::Radar, std::slice::from_ref(&degrees))[0];
            if check.sees(sensor, time, z) {
                measurements.push(SVector::from_column_slice(z));
                detected.extend(origin);
            }
        }
        let truth = states.iter().enumerate().filter_map(|(i, s)| s.map(|x| (i as u64, [x[0], x[1], x[2]]))).collect();
        Ok(Scan { time, sensor, measurements, detected, in_view: drawn.truth.len(), truth })
    }
}
