//! A catalogue seen by a sensor network, drawn scan by scan: `generate catalogue`'s scenario without holding
//! its scans. Each scan's truth (SGP4 for every object, in parallel), detections and clutter are drawn when
//! the scan is asked for, with the random streams the whole scenario uses, so that drawing every scan in
//! order gives exactly the scans and truth of the written scenario ([`super::from_catalogue`] builds it
//! so), and a catalogue too large for a scenario file can be tracked as it is drawn (`run-catalogue`).
//!
//! An object SGP4 cannot propagate at a scan (or whose radius is below the decay floor,
//! [`screen::state_in_orbit`]) is dropped from then on, with a warning, and listed in
//! [`CatalogueStream::dropped`]; the written scenario screens every scan time first, so it never drops one
//! here.

use crate::Error;
use crate::io::catalogue::screen::{self, CatalogueDropped, DroppedElementSet};
use crate::io::catalogue::{CatalogueEntry, Satellite};
use crate::pipeline::orbital::{FieldOfViewCheck, measurements_in_radians};
use crate::scenario::from_simulation::{
    CATALOGUE_SELECTION, CATALOGUE_TRACK_LOSS, KnownTruth, description, to_scenario_with,
};
use crate::scenario::v2::{Measurement3dSpec, Scan3dSpec, Scenario3d, TruthScan3dSpec, TruthState3dSpec};
use crate::sim::rng::{Random, Stream};
use crate::sim::sensor::SensorSpec;
use crate::sim::ssa::{SsaScenario, draw_scan_any_size};
use crate::sim::time;
use crate::sim::truth::ObjectTruth;
use rayon::prelude::*;
use sgp4::chrono::NaiveDateTime;

/// Where the truth comes from, as the scenario's description says.
const TRUTH_SOURCE: &str = "SGP4 (WGS-72, AFSPC mode)";

/// What a stream is made of: the request's sensors, schedule and screened catalogue.
pub struct StreamParts {
    /// The scenario's name.
    pub name: String,
    /// Seed of detections, clutter and the prior's errors.
    pub seed: u64,
    /// The start as given (UTC) and as a Julian date.
    pub start: String,
    pub epoch_jd: f64,
    /// The start as SGP4 reads it.
    pub epoch: NaiveDateTime,
    /// Duration (s).
    pub duration: f64,
    /// The simulator's sensors and which of them are telescopes (they see only sunlit objects).
    pub sensors: Vec<SensorSpec>,
    pub optical: Vec<bool>,
    /// (time, sensor) of every scan.
    pub schedule: Vec<(f64, usize)>,
    /// The element sets kept, as SGP4 propagators (object i is the i-th).
    pub satellites: Vec<Satellite>,
    /// The element sets left out before the run.
    pub dropped: CatalogueDropped,
    /// The most measurements a scan may carry (`None`: any number).
    pub max_measurements: Option<usize>,
    /// The catalogue and sensors files, as messages name them.
    pub catalogue_file: String,
    pub sensors_file: String,
    /// Per sensor, the sensors file's own birth region (network sensors files), which replaces the
    /// simulation's default.
    pub birth_regions: Vec<Option<crate::scenario::BirthRegionSpec>>,
}

/// A catalogue's scans, drawn in order.
pub struct CatalogueStream {
    parts: StreamParts,
    /// The simulation the scenario is configured from (its objects and sensors; no scans).
    simulation: SsaScenario,
    /// The scenario's configuration and prior (no scans; truth objects without truth scans).
    scenario: Scenario3d,
    check: FieldOfViewCheck,
    /// Per object: its detection stream, and whether it is still propagated.
    detection: Vec<Random>,
    alive: Vec<bool>,
    /// The next scan to draw.
    next: usize,
    /// Measurements left out at the field of view's edge so far.
    pub dropped_outside: usize,
}

/// One drawn scan: as a scenario file holds it (angles in degrees) and its truth.
pub type DrawnScan = (Scan3dSpec, TruthScan3dSpec);

impl CatalogueStream {
    /// The stream of `parts`.
    ///
    /// # Errors
    /// As [`to_scenario_with`]: the simulator's sensor checks, an SGP4 failure at the prior's time.
    pub fn new(parts: StreamParts) -> Result<Self, Error> {
        for s in &parts.sensors {
            s.check().map_err(|e| Error::input(format!("{}: {e}", parts.sensors_file)))?;
        }
        let objects = (0..parts.satellites.len())
            .map(|_| ObjectTruth { initial_state: [0.0; 6], group: None, in_prior: true, birth_time: None })
            .collect();
        let simulation = SsaScenario {
            name: parts.name.clone(),
            seed: parts.seed,
            epoch: parts.start.clone(),
            epoch_jd: parts.epoch_jd,
            duration: parts.duration,
            sensors: parts.sensors.clone(),
            objects,
            groups: vec![],
            scans: vec![],
        };
        let (satellites, epoch, start, file) = (&parts.satellites, parts.epoch, &parts.start, &parts.catalogue_file);
        let state = |i: usize, t: f64| -> Result<[f64; 6], Error> {
            satellites[i].tracker_state(epoch, t).map(|(r, v)| [r[0], r[1], r[2], v[0], v[1], v[2]]).map_err(|e| {
                let entry = &satellites[i].entry;
                Error::input(format!("{file}:{}: object {}: at {start} + {t} s: {e}", entry.line, entry.norad_id))
            })
        };
        let known = KnownTruth { state: &state, source: TRUTH_SOURCE };
        let (mut scenario, _) = to_scenario_with(&simulation, Some(known))?;
        scenario.tracker.selection = CATALOGUE_SELECTION;
        // Not for a telescope alone: it misses every object in the Earth's shadow, which the field of view
        // counts as in view.
        if !matches!(scenario.measurement, Measurement3dSpec::Optical | Measurement3dSpec::AzEl) {
            scenario.tracker.lost_after_unseen_scans =
                scenario.tracker.lost_after_unseen_scans.or(CATALOGUE_TRACK_LOSS);
        }
        for (spec, own) in scenario.sensors.iter_mut().zip(&parts.birth_regions) {
            spec.birth_region = own.or(spec.birth_region);
        }
        let check = FieldOfViewCheck::new(&scenario)?;
        let n = parts.satellites.len();
        let detection = (0..n).map(|i| Random::stream(parts.seed, Stream::Detection, i as u64)).collect();
        Ok(Self { parts, simulation, scenario, check, detection, alive: vec![true; n], next: 0, dropped_outside: 0 })
    }

    /// The scenario's configuration and prior (no scans).
    pub fn scenario(&self) -> &Scenario3d {
        &self.scenario
    }

    /// Sets the trackers' track loss (`tracker.lost_after_unseen_scans`, docs/maths.md §5.9; `None`: never).
    pub fn set_lost_after_unseen_scans(&mut self, scans: Option<core::num::NonZeroU16>) {
        self.scenario.tracker.lost_after_unseen_scans = scans;
    }

    /// Scans in the run.
    pub fn scans(&self) -> usize {
        self.parts.schedule.len()
    }

    /// Time of scan `k` (s since the start).
    pub fn time(&self, k: usize) -> f64 {
        self.parts.schedule[k].0
    }

    /// Sensor of scan `k`.
    pub fn sensor(&self, k: usize) -> usize {
        self.parts.schedule[k].1
    }

    /// Objects in the run (those dropped during it included).
    pub fn objects(&self) -> usize {
        self.parts.satellites.len()
    }

    /// The element sets left out before the run and the objects dropped during it.
    pub fn dropped(&self) -> &CatalogueDropped {
        &self.parts.dropped
    }

    /// Draws scan `k`, the next one (scans are drawn once each, in order: each object's detections come
    /// from its own stream): every object still in orbit propagated, the sensor's detections and clutter
    /// drawn, the measurements a scenario file would hold (in degrees; a noisy detection outside the field of
    /// view left out, as the tracker refuses it) and the truth (every object in orbit, its state; each
    /// measurement's origin).
    ///
    /// # Errors
    /// A scan asked for out of order (internal), more measurements than the stream allows, the simulator's
    /// error (clutter in an empty field of view).
    pub fn scan(&mut self, k: usize) -> Result<DrawnScan, Error> {
        if k != self.next || k >= self.scans() {
            return Err(Error::internal(format!("catalogue scan {k} drawn out of order (next {})", self.next)));
        }
        self.next += 1;
        let (time, sensor) = self.parts.schedule[k];
        let parts = &self.parts;
        let states: Vec<Option<Result<[f64; 6], String>>> = parts
            .satellites
            .par_iter()
            .zip(self.alive.par_iter())
            .map(|(s, &alive)| alive.then(|| screen::state_in_orbit(s, parts.epoch, time)))
            .collect();
        let mut truth = TruthScan3dSpec { objects: Vec::with_capacity(states.len()), origins: None };
        for (i, state) in states.iter().enumerate() {
            match state {
                Some(Ok(state)) => truth.objects.push(TruthState3dSpec { id: i as u64, state: *state }),
                Some(Err(reason)) => self.drop_object(i, reason.clone()),
                None => {}
            }
        }
        let sun = crate::scenario::from_catalogue::sun_position(self.parts.epoch_jd + time / 86_400.0);
        let optical = self.parts.optical[sensor];
        let seen = states.iter().map(|s| match s {
            Some(Ok(x)) if !optical || crate::scenario::from_catalogue::sunlit([x[0], x[1], x[2]], sun) => Some(*x),
            _ => None,
        });
        let spec = &self.parts.sensors[sensor];
        let observer = spec.site.observer(time::earth_rotation_angle(self.parts.epoch_jd, time));
        let drawn = draw_scan_any_size(self.parts.seed, k, (time, sensor), spec, &observer, seen, &mut self.detection)
            .map_err(|e| Error::input(format!("{}: {e}", self.parts.sensors_file)))?;
        if let Some(cap) = self.parts.max_measurements
            && drawn.measurements.len() > cap
        {
            return Err(Error::input(format!(
                "scan {k} would carry more than {cap} measurements (the tracker's limit): fewer objects, a \
                 narrower field of view or less clutter"
            )));
        }
        let mut origin_of = vec![None; drawn.measurements.len()];
        for t in &drawn.truth {
            if let Some(j) = t.measurement {
                origin_of[j] = Some(t.object as u64);
            }
        }
        let kind = self.scenario.kind(sensor);
        let (mut measurements, mut origins) = (vec![], vec![]);
        for (z, origin) in drawn.measurements.iter().zip(origin_of) {
            let in_file: Vec<f64> =
                z.iter().enumerate().map(|(i, &v)| if kind.is_angle(i) { v.to_degrees() } else { v }).collect();
            // The test the tracker applies, to the value it reads back from the file.
            let read_back = measurements_in_radians(kind, std::slice::from_ref(&in_file));
            if !self.check.sees(sensor, time, &read_back[0]) {
                self.dropped_outside += 1;
                continue;
            }
            measurements.push(in_file);
            origins.push(origin);
        }
        truth.origins = Some(origins);
        Ok((Scan3dSpec { time, sensor, measurements }, truth))
    }

    /// Drops object `i` from the run (SGP4 failed on it, or it decays), with a warning.
    fn drop_object(&mut self, i: usize, reason: String) {
        self.alive[i] = false;
        let entry: &CatalogueEntry = &self.parts.satellites[i].entry;
        let file = &self.parts.catalogue_file;
        eprintln!("warning: {file}:{}: object {}: dropped: {reason}", entry.line, entry.norad_id);
        let dropped = &mut self.parts.dropped;
        dropped.objects.push(DroppedElementSet {
            norad_id: entry.norad_id,
            name: entry.name.clone(),
            line: entry.line,
            reason,
        });
        dropped.count = dropped.objects.len();
    }

    /// The scenario (its description counting the scans drawn) and the element sets dropped.
    pub fn into_parts(self) -> (Scenario3d, CatalogueDropped) {
        let mut scenario = self.scenario;
        scenario.description = description(&self.simulation, self.next, TRUTH_SOURCE);
        (scenario, self.parts.dropped)
    }
}
