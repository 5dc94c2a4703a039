//! `host-sim digest` on version 2 radar scenarios: replays an excerpt through the embedded 3-D tracker,
//! `RadarTracker<f32>`, exactly as the QEMU firmware (`firmware/qemu-m4`, `RFISST_SCENARIO_3D`) does, and
//! returns the same digest text as the planar digest ([`crate::pipeline::digest::planar`]).
//!
//! **The excerpt.** The first `scans` scans, and a prior restricted to the objects they detect: a prior
//! object is kept when its label is the id of an object that produced a measurement of the excerpt
//! (`truth.scans[k].origins`; the generator labels prior objects by their truth ids). The others are not
//! in view of any sensor during the excerpt, so they produce no measurements there; the restriction lets
//! the prior fit the embedded capacity N = 64 (radar-leo seed 1: 43 of 120 objects in its first 200
//! scans). The file therefore needs its truth with `origins`.
//!
//! **Conversions.** Every value is computed in `f64` as [`crate::pipeline::orbital::run`] computes it (degrees and
//! arcseconds to radians, the Earth rotation angle at the epoch) and rounded once with `value as f32`;
//! times stay `f64`. The firmware's build script does the same, so both trackers start from the same bits.

use crate::pipeline::digest::convert;
use crate::pipeline::settings;
use crate::scenario::ScenarioError;
use crate::scenario::v2::{Measurement3dSpec, Scenario3d};
use nalgebra::SVector;
use std::collections::HashSet;
use tracker_core::model::SensorNetwork;
use tracker_core::sensor::{EarthRotation, GroundSite, Platform, ScanGeometry, SiteSensor};
use tracker_core::{
    BirthModel, ChildGeneration, Config, PriorHypothesis, PriorObject, RadarConfig, RadarTracker, Real, Sensor,
};

/// Replays the first `scans` scans of the radar scenario `scenario` (all when `None`) through
/// `RadarTracker<f32>`, with the prior restricted to the objects those scans detect, and returns the digest
/// text the firmware prints.
///
/// # Errors
/// A one-line message when `scans` exceeds the scenario's scans, the scenario is not a radar
/// (range, azimuth, elevation) scenario, it has no truth origins for the excerpt, it exceeds the embedded
/// capacities, or the tracker rejects its configuration.
pub fn run(scenario: &Scenario3d, scans: Option<usize>) -> Result<String, ScenarioError> {
    let count = super::excerpt(scans, scenario.scans.len())?;
    let mut tracker = tracker(scenario, count)?;
    Ok(super::text(count, |index| {
        let scan = &scenario.scans[index];
        let measurements: Vec<SVector<f32, 3>> =
            scan.measurements.iter().map(|z| measurement(scenario.measurement, z)).collect();
        let geometry = ScanGeometry { sensor: scan.sensor, time: scan.time, observer: None };
        let outcome = tracker.step_scan(&geometry, &measurements);
        (outcome, tracker.digest())
    }))
}

/// One measurement in the tracker's units and scalar: angles from degrees to radians in `f64` (azimuth
/// and right ascension first wrapped to (−180°, 180°], [`crate::io::angles::wrap`]), then each component
/// rounded once.
pub fn measurement(kind: Measurement3dSpec, z: &[f64]) -> SVector<f32, 3> {
    SVector::from_fn(|i, _| {
        let v = z.get(i).copied().unwrap_or(f64::NAN);
        let v = if kind.wraps(i) { crate::io::angles::wrap(v) } else { v };
        f32::of_f64(if kind.is_angle(i) { v.to_radians() } else { v })
    })
}

/// The ids of the objects that produced a measurement in the first `count` scans.
///
/// # Errors
/// When the scenario has no truth, or a scan of the excerpt has no `origins`.
pub fn detected(scenario: &Scenario3d, count: usize) -> Result<HashSet<u64>, ScenarioError> {
    let truth = scenario.truth.as_ref().ok_or_else(|| {
        ScenarioError("truth: digest restricts the prior to the detected objects and needs the truth".into())
    })?;
    let mut ids = HashSet::new();
    for (k, scan) in truth.scans[..count.min(truth.scans.len())].iter().enumerate() {
        let origins = scan.origins.as_ref().ok_or_else(|| {
            ScenarioError(format!("truth.scans[{k}].origins: digest needs the origin of every measurement"))
        })?;
        ids.extend(origins.iter().flatten());
    }
    Ok(ids)
}

/// The embedded radar tracker for the first `count` scans of `scenario`, on the heap.
///
/// # Errors
/// As [`run`].
pub fn tracker(scenario: &Scenario3d, count: usize) -> Result<Box<RadarTracker<f32>>, ScenarioError> {
    radar_only(scenario)?;
    let config = config(scenario)?;
    let prior = prior(scenario, count)?;
    let hypotheses: Vec<PriorHypothesis<'_, f32, 6>> =
        prior.iter().map(|(weight, objects)| PriorHypothesis { weight: *weight, objects }).collect();
    // Built in place on the heap: the tracker is too large for a default thread stack.
    let mut tracker = Box::new(RadarTracker::<f32>::empty(config));
    tracker
        .reset(&hypotheses, scenario.prior.time)
        .map_err(|e| ScenarioError(format!("tracker configuration: {e}")))?;
    Ok(tracker)
}

/// Refuses a scenario that is not a radar (range, azimuth, elevation) one.
///
/// # Errors
/// A one-line message naming the scenario's measurement.
pub fn radar_only(scenario: &Scenario3d) -> Result<(), ScenarioError> {
    if scenario.measurement != Measurement3dSpec::Radar {
        return Err(ScenarioError(format!(
            "measurement: the embedded 3-D replay runs RadarTracker (range, azimuth, elevation); this scenario is \
             {}",
            scenario.measurement.name()
        )));
    }
    Ok(())
}

/// Prior hypotheses in `f32`: each weight and its objects.
pub type Prior = Vec<(f32, Vec<PriorObject<f32, 6>>)>;

/// The prior of the first `count` scans in `f32`: each hypothesis restricted to the objects they detect.
///
/// # Errors
/// As [`detected`].
pub fn prior(scenario: &Scenario3d, count: usize) -> Result<Prior, ScenarioError> {
    let detected = detected(scenario, count)?;
    Ok(settings::prior(scenario.prior.hypotheses.iter().map(|h| {
        let objects = h.objects.iter().filter(|o| detected.contains(&u64::from(o.label)));
        (h.weight, objects.map(|o| (o.label, &o.mean, &o.covariance)))
    })))
}

/// The configuration of the embedded radar tracker: `f64` values rounded once to `f32`.
///
/// # Errors
/// More birth cells than the embedded capacity, or a sensor network the core rejects.
pub fn config(scenario: &Scenario3d) -> Result<RadarConfig<f32>, ScenarioError> {
    let of = f32::of_f64;
    let sensors: Vec<SiteSensor<f32, 3>> = scenario
        .sensors
        .iter()
        .map(|s| {
            let sigma = s.noise.sigma(scenario.measurement);
            let site = GroundSite {
                latitude: s.site.latitude_deg.to_radians(),
                longitude: s.site.longitude_deg.to_radians(),
                height: s.site.height_km,
            };
            let detection = Sensor {
                detection_probability: s.detection_probability,
                clutter_rate: s.clutter_rate,
                field_of_view: s.field_of_view.region(),
            };
            SiteSensor {
                platform: convert::platform(Platform::Ground(site)),
                sigma: core::array::from_fn(|i| of(sigma.get(i).copied().unwrap_or(f64::NAN))),
                detection: convert::sensor(&detection),
            }
        })
        .collect();
    let rotation = EarthRotation::<f32>::new(of(scenario.earth_rotation_at_epoch()));
    let network = SensorNetwork::new(rotation, &sensors).map_err(|e| ScenarioError(format!("sensors: {e}")))?;
    let cells =
        settings::birth_cells(scenario.birth.cells.iter().map(|c| (&c.mean, &c.covariance)), "the embedded capacity")
            .map_err(ScenarioError)?;
    let spec = &scenario.tracker;
    let (selection, store_overflow, numerical_failure, track_loss) = settings::policies(spec);
    // As `run3d`: the configuration's own sensor is the first sensor's (each scan uses its sensor's).
    let sensor = *sensors.first().map(|s| &s.detection).ok_or_else(|| ScenarioError("sensors: none".into()))?;
    Ok(Config {
        motion: convert::motion(scenario),
        measurement: network,
        sensor,
        birth: BirthModel {
            events: Default::default(),
            measured: None,
            probability: of(scenario.birth.probability),
            cells,
            detection: settings::birth_detection(scenario.birth.detection),
        },
        death_probability: of(scenario.death_probability),
        gate: spec.gate.map(of),
        children: ChildGeneration::Sampled(settings::sampler_config(spec)),
        selection,
        store_overflow,
        numerical_failure,
        track_loss,
        seed: spec.seed,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tiny() -> Scenario3d {
        let simulation = crate::sim::presets::tiny_3d(1).expect("tiny-3d");
        crate::scenario::from_simulation::to_scenario(&simulation).expect("scenario").0
    }

    #[test]
    fn digest_text_has_one_line_per_scan_and_repeats() {
        let scenario = tiny();
        let text = run(&scenario, Some(4)).expect("digest");
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 5);
        assert!(lines[0].starts_with("scan 0 hypotheses "), "{text}");
        assert!(lines[4].starts_with("final scans 4 digest "));
        assert_eq!(run(&scenario, Some(4)).expect("digest"), text);
        let three = run(&scenario, Some(3)).expect("digest");
        assert!(text.starts_with(three.lines().next().expect("a line")));
    }

    #[test]
    fn prior_keeps_only_detected_objects() {
        let scenario = tiny();
        let ids = detected(&scenario, 4).expect("origins");
        let tracker = tracker(&scenario, 4).expect("tracker");
        let labels: Vec<u32> = tracker.map_hypothesis().tracks().map(|t| t.label.0).collect();
        assert!(labels.iter().all(|l| ids.contains(&u64::from(*l))), "{labels:?} {ids:?}");
        let prior = scenario.prior.hypotheses[0].objects.iter().filter(|o| ids.contains(&u64::from(o.label)));
        assert_eq!(labels.len(), prior.count());
    }

    #[test]
    fn missing_truth_and_too_many_scans_are_errors() {
        let mut scenario = tiny();
        let error = run(&scenario, Some(scenario.scans.len() + 1)).expect_err("too many");
        assert!(error.0.contains("only"), "{error}");
        scenario.truth = None;
        let error = run(&scenario, Some(2)).expect_err("no truth");
        assert!(error.0.starts_with("truth:"), "{error}");
    }
}
