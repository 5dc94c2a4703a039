//! `host-sim digest` on version 2 network scenarios (`measurement: network`, sensors of mixed kinds):
//! replays an excerpt through the embedded fused tracker, `NetworkTracker<f32>`, exactly as the QEMU
//! firmware (`firmware/qemu-m4`, `RFISST_NETWORK_EXCERPT`) does, and returns the same digest text as the
//! other digests ([`super::text`]).
//!
//! **The configuration** is the one `host-sim run` gives the core tracker (R-FISST: sampled children,
//! [`crate::pipeline::orbital::tracker::config3d`], measured births and each sensor's own birth region
//! included), every value computed in `f64` and rounded once with `as f32`: the sensors, their birth
//! regions, the Earth rotation angle at the epoch, the motion, the birth model and the prior. The sensor
//! network is then built from those `f32` sensors by `MixedNetwork::new` (its clutter volumes computed in
//! `f32`), on the host and on the target alike. Measurements are those `host-sim run` feeds the tracker
//! (degrees to radians, corrections), rounded once. The prior is the file's whole prior (it must fit
//! N = 64).
//!
//! **The excerpt file** ([`super::excerpt::source`]) writes these `f32` values as bits in Rust source for
//! the firmware, so that both sides start from the same bits without a second converter.

use super::convert;
use crate::pipeline::orbital::C;
use crate::pipeline::orbital::corrections::corrected_measurements;
use crate::pipeline::orbital::tracker::config3d;
use crate::pipeline::settings;
use crate::pipeline::tracker::TrackerKind;
use crate::scenario::ScenarioError;
use crate::scenario::v2::{Measurement3dSpec, Scenario3d};
use nalgebra::SVector;
use tracker_core::model::{MixedNetwork, SensorBirths};
use tracker_core::sensor::{EarthRotation, ScanGeometry, SiteSensor};
use tracker_core::{
    BirthModel, Config, MixedSensor, Network, NetworkConfig, NetworkTracker, PriorHypothesis, PriorObject, Real,
    model::MIXED_DIMENSION, ssa_caps,
};

/// The embedded tracker's parts, in `f32`: what the firmware's excerpt holds.
pub struct Parts {
    /// The Earth rotation angle at the epoch (rad).
    pub rotation: f32,
    /// The sensors.
    pub sensors: Vec<MixedSensor<f32>>,
    /// Per sensor, where its births come from.
    pub births: Vec<SensorBirths<f32>>,
    /// The configuration, with a network of no sensors ([`MixedNetwork::unconfigured`]) in place of the
    /// one [`Parts::network`] builds.
    pub config: NetworkConfig<f32>,
    /// The prior: (weight, objects) per hypothesis.
    pub prior: Vec<(f32, Vec<PriorObject<f32, 6>>)>,
}

/// One scan in the tracker's units and scalar.
pub struct Scan {
    /// Time (s after the epoch).
    pub time: f64,
    /// The sensor.
    pub sensor: usize,
    /// The measurements, padded to four components.
    pub measurements: Vec<SVector<f32, MIXED_DIMENSION>>,
}

/// Replays the first `scans` scans of the network scenario `scenario` (all when `None`) through
/// `NetworkTracker<f32>` and returns the digest text the firmware prints.
///
/// # Errors
/// A one-line message when `scans` exceeds the scenario's scans, the scenario is not a network one, it
/// exceeds the embedded capacities, or the core rejects its configuration.
pub fn run(scenario: &Scenario3d, scans: Option<usize>) -> Result<String, ScenarioError> {
    let count = super::excerpt(scans, scenario.scans.len())?;
    let parts = parts(scenario)?;
    let mut tracker = tracker(&parts, scenario.prior.time)?;
    let scans = self::scans(scenario, count);
    Ok(super::text(count, |index| {
        let scan = &scans[index];
        let geometry = ScanGeometry { sensor: scan.sensor, time: scan.time, observer: None };
        let outcome = tracker.step_scan(&geometry, &scan.measurements);
        (outcome, tracker.digest())
    }))
}

/// The network of `parts`, as the firmware builds it: `MixedNetwork::new` of the sensors, then each
/// sensor's births.
///
/// # Errors
/// The core's message when it rejects the network.
pub fn network(parts: &Parts) -> Result<Network<f32>, ScenarioError> {
    let reject = |e: &str| ScenarioError(format!("sensors: {e}"));
    let mut network = MixedNetwork::new(EarthRotation::new(parts.rotation), &parts.sensors).map_err(reject)?;
    for (index, births) in parts.births.iter().enumerate() {
        network = network.with_births(index, *births).map_err(reject)?;
    }
    Ok(network)
}

/// The embedded tracker of `parts` with its prior at `time`, built in place on the heap with
/// `Tracker::reset_with` as the firmware builds it in a static.
///
/// # Errors
/// The core's message when it rejects the configuration or the prior.
pub fn tracker(parts: &Parts, time: f64) -> Result<Box<NetworkTracker<f32>>, ScenarioError> {
    let config = Config { measurement: network(parts)?, ..parts.config.clone() };
    let hypotheses: Vec<PriorHypothesis<'_, f32, 6>> =
        parts.prior.iter().map(|(weight, objects)| PriorHypothesis { weight: *weight, objects }).collect();
    let mut tracker = Box::new(NetworkTracker::<f32>::empty(parts.config.clone()));
    tracker.reset_with(config, &hypotheses, time).map_err(|e| ScenarioError(format!("tracker configuration: {e}")))?;
    Ok(tracker)
}

/// The first `count` scans in the tracker's units: as `host-sim run` corrects them in `f64`, each component
/// then rounded once, padded with zeros.
pub fn scans(scenario: &Scenario3d, count: usize) -> Vec<Scan> {
    scenario.scans[..count.min(scenario.scans.len())]
        .iter()
        .map(|scan| Scan {
            time: scan.time,
            sensor: scan.sensor,
            measurements: corrected_measurements(scenario, scan)
                .iter()
                .map(|z| SVector::from_fn(|i, _| f32::of_f64(z.get(i).copied().unwrap_or(0.0))))
                .collect(),
        })
        .collect()
}

/// The parts of the embedded tracker for `scenario`.
///
/// # Errors
/// Not a network scenario, more sensors or birth cells than the embedded capacities, or a configuration
/// host-sim refuses.
pub fn parts(scenario: &Scenario3d) -> Result<Parts, ScenarioError> {
    if scenario.measurement != Measurement3dSpec::Network {
        return Err(ScenarioError(format!(
            "measurement: the embedded network replay runs NetworkTracker (\"network\"); this scenario is {}",
            scenario.measurement.name()
        )));
    }
    if scenario.sensors.len() > ssa_caps::NETWORK_SENSORS {
        return Err(ScenarioError(format!(
            "sensors: {} exceed the embedded network's {}",
            scenario.sensors.len(),
            ssa_caps::NETWORK_SENSORS
        )));
    }
    let (host, _) =
        config3d::<MixedNetwork<f64, C>, MIXED_DIMENSION, { ssa_caps::BIRTH_CELLS }>(scenario, TrackerKind::Rfisst)
            .map_err(|e| ScenarioError(e.to_string()))?;
    let of = f32::of_f64;
    let sensors: Vec<MixedSensor<f32>> = host
        .measurement
        .sensors()
        .iter()
        .map(|s| MixedSensor {
            kind: s.kind,
            sensor: SiteSensor {
                platform: convert::platform(s.sensor.platform),
                sigma: s.sensor.sigma.map(of),
                detection: convert::sensor(&s.sensor.detection),
            },
        })
        .collect();
    let births = (0..sensors.len()).map(|i| convert::sensor_births(host.measurement.births(i))).collect();
    let first = sensors.first().map(|s| s.sensor.detection).ok_or_else(|| ScenarioError("sensors: none".into()))?;
    let config = Config {
        motion: convert::motion(scenario),
        measurement: MixedNetwork::unconfigured(),
        sensor: first,
        birth: BirthModel {
            probability: of(host.birth.probability),
            cells: host.birth.cells.iter().map(convert::gaussian).collect(),
            detection: host.birth.detection,
            events: host.birth.events,
            measured: host.birth.measured.map(|m| convert::measured(&m)),
        },
        death_probability: of(host.death_probability),
        gate: host.gate.map(of),
        children: host.children,
        selection: host.selection,
        store_overflow: host.store_overflow,
        numerical_failure: host.numerical_failure,
        track_loss: host.track_loss,
        seed: host.seed,
    };
    let prior = settings::prior(
        scenario
            .prior
            .hypotheses
            .iter()
            .map(|h| (h.weight, h.objects.iter().map(|o| (o.label, &o.mean, &o.covariance)))),
    );
    Ok(Parts { rotation: of(scenario.earth_rotation_at_epoch()), sensors, births, config, prior })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tiny() -> Scenario3d {
        let simulation = crate::scenario::from_simulation::Preset3d::TinyNetwork.simulate(1).expect("tiny-network");
        crate::scenario::from_simulation::to_scenario(&simulation).expect("scenario").0
    }

    #[test]
    fn network_digest_text_repeats_and_grows_by_scans() {
        let scenario = tiny();
        let text = run(&scenario, Some(12)).expect("digest");
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 13);
        assert!(lines[0].starts_with("scan 0 "), "{text}");
        assert_eq!(run(&scenario, Some(12)).expect("digest"), text);
        let six = run(&scenario, Some(6)).expect("digest");
        assert_eq!(text.lines().take(6).collect::<Vec<_>>(), six.lines().take(6).collect::<Vec<_>>());
        // Several kinds measure in the excerpt.
        let parts = parts(&scenario).expect("parts");
        let kinds: std::collections::HashSet<&str> = scans(&scenario, 12)
            .iter()
            .filter(|s| !s.measurements.is_empty())
            .map(|s| parts.sensors[s.sensor].kind.name())
            .collect();
        assert!(kinds.len() >= 2, "{kinds:?}");
    }

    #[test]
    fn the_embedded_parts_round_the_host_configuration_once() {
        let scenario = tiny();
        let parts = parts(&scenario).expect("parts");
        let network = network(&parts).expect("network");
        assert_eq!(network.sensors(), &parts.sensors[..]);
        assert_eq!(parts.sensors.len(), scenario.sensors.len());
        let host = &scenario.sensors[0];
        let latitude = host.site.latitude_deg.to_radians() as f32;
        assert!(
            matches!(parts.sensors[0].sensor.platform, tracker_core::sensor::Platform::Ground(site) if site.latitude == latitude)
        );
        assert!(parts.config.birth.measured.is_some() == scenario.birth.measured.is_some());
        // The placeholder network is refused on its own.
        let mut tracker = Box::new(NetworkTracker::<f32>::empty(parts.config.clone()));
        assert!(tracker.reset(&[], 0.0).is_err());
    }

    #[test]
    fn a_radar_scenario_is_refused() {
        let simulation = crate::sim::presets::tiny_3d(1).expect("tiny-3d");
        let scenario = crate::scenario::from_simulation::to_scenario(&simulation).expect("scenario").0;
        let error = run(&scenario, Some(2)).expect_err("refused");
        assert!(error.0.starts_with("measurement:"), "{error}");
    }
}
