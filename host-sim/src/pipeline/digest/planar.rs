//! `host-sim digest`: replays a scenario with the embedded tracker, `SsaTracker<f32>`, exactly as the QEMU
//! firmware (`firmware/qemu-m4`) does, and returns the text the firmware prints, line for line.
//!
//! The configuration is [`setup::config`]'s, with R-FISST children ([`setup::sampled`]: the scenario's
//! `tracker.sampler`, `SamplerConfig::default()` when the file leaves it out), built in `f64` and then
//! rounded to `f32` value by value (`value as f32`). The firmware's build script rounds the same `f64`
//! values the same way, so both trackers start from the same bits.
//!
//! The text (see [`run`]) is one line per scan and a final line:
//!
//! ```text
//! scan 0 hypotheses 1 tracks 45 digest 1c0ffee15bad5eed
//! scan 1 error scan time is not after the previous scan digest 1c0ffee15bad5eed
//! final scans 2 digest 0123456789abcdef
//! ```
//!
//! `digest` is [`tracker_core::Tracker::digest`] after the scan (after a rejected scan the tracker is
//! unchanged); the final digest is a 64-bit FNV-1a over every scan's digest as 8 little-endian bytes.

use super::convert;
use crate::pipeline::planar::setup;
use crate::scenario::{Scenario, ScenarioError};
use nalgebra::SVector;
use tracker_core::{
    BirthModel, Config, PositionMeasurement, PriorHypothesis, PriorObject, Real, Sensor, SsaConfig, SsaTracker,
    TwoBody, ssa_caps,
};

/// Replays the first `scans` scans of `scenario` (all when `None`) through `SsaTracker<f32>` and returns the
/// digest text the firmware prints.
///
/// # Errors
/// A one-line message when `scans` exceeds the scenario's scans, the scenario is not two-body (the embedded
/// tracker's motion model), it has more birth cells than the embedded capacity, or the tracker rejects its
/// configuration.
pub fn run(scenario: &Scenario, scans: Option<usize>) -> Result<String, ScenarioError> {
    let count = super::excerpt(scans, scenario.scans.len())?;
    let mut tracker = Box::new(tracker::<f32>(scenario)?);
    Ok(super::text(count, |index| {
        let scan = &scenario.scans[index];
        let measurements: Vec<SVector<f32, 2>> =
            scan.measurements.iter().map(|z| SVector::from([f32::of_f64(z[0]), f32::of_f64(z[1])])).collect();
        let outcome = tracker.step(scan.time, &measurements);
        (outcome, tracker.digest())
    }))
}

/// The embedded tracker for `scenario` in scalar `T`: [`setup`]'s `f64` configuration and prior, each value
/// rounded to `T`.
///
/// # Errors
/// As [`run`].
pub fn tracker<T: Real>(scenario: &Scenario) -> Result<SsaTracker<T>, ScenarioError> {
    let motion = setup::two_body(&scenario.motion).ok_or_else(|| {
        ScenarioError(
            "motion: the embedded tracker (SsaTracker) is two-body; this scenario is constant-velocity".into(),
        )
    })?;
    let config: Config<f64, TwoBody<f64>, PositionMeasurement<f64>, 4, { ssa_caps::BIRTH_CELLS }> =
        setup::config(scenario, motion, setup::sampled(scenario))?;
    let prior: Vec<(T, Vec<PriorObject<T, 4>>)> = setup::prior(scenario)
        .iter()
        .map(|(weight, objects)| {
            let objects =
                objects.iter().map(|o| PriorObject { label: o.label, state: convert::gaussian(&o.state) }).collect();
            (T::of_f64(*weight), objects)
        })
        .collect();
    let hypotheses: Vec<PriorHypothesis<'_, T, 4>> =
        prior.iter().map(|(weight, objects)| PriorHypothesis { weight: *weight, objects }).collect();
    SsaTracker::<T>::new(ssa_config(&config), &hypotheses, scenario.prior.time)
        .map_err(|e| ScenarioError(format!("tracker configuration: {e}")))
}

/// An `f64` configuration of the embedded tracker in scalar `T`, every value rounded with [`Real::of_f64`].
pub fn ssa_config<T: Real>(
    config: &Config<f64, TwoBody<f64>, PositionMeasurement<f64>, 4, { ssa_caps::BIRTH_CELLS }>,
) -> SsaConfig<T> {
    let of = T::of_f64;
    let mut cells = heapless::Vec::new();
    for cell in &config.birth.cells {
        // Same capacity on both sides: cannot overflow.
        let _ = cells.push(convert::gaussian(cell));
    }
    Config {
        motion: TwoBody {
            mu: of(config.motion.mu),
            acceleration_noise: of(config.motion.acceleration_noise),
            max_step: of(config.motion.max_step),
            max_substeps: config.motion.max_substeps,
            min_radius: of(config.motion.min_radius),
        },
        measurement: PositionMeasurement { noise: config.measurement.noise.map(of) },
        sensor: Sensor {
            detection_probability: of(config.sensor.detection_probability),
            clutter_rate: of(config.sensor.clutter_rate),
            field_of_view: convert::region(&config.sensor.field_of_view),
        },
        birth: BirthModel {
            probability: of(config.birth.probability),
            cells,
            detection: config.birth.detection,
            events: Default::default(),
            measured: None,
        },
        death_probability: of(config.death_probability),
        gate: config.gate.map(of),
        children: config.children,
        selection: config.selection,
        store_overflow: config.store_overflow,
        numerical_failure: Default::default(),
        track_loss: Default::default(),
        seed: config.seed,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scenario(scans: usize) -> Scenario {
        let mut simulation = crate::sim::planar::preset("fifty-birth-death", 1).expect("preset");
        simulation.scans = scans;
        simulation.run()
    }

    #[test]
    fn digest_text_has_one_line_per_scan_and_repeats() {
        let scenario = scenario(3);
        let text = run(&scenario, None).expect("digest");
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 4);
        assert!(lines[0].starts_with("scan 0 hypotheses "));
        assert!(lines[3].starts_with("final scans 3 digest "));
        assert_eq!(run(&scenario, None).expect("digest"), text);
        // A prefix of the scans gives a prefix of the lines.
        let two = run(&scenario, Some(2)).expect("digest");
        assert!(text.starts_with(two.lines().next().expect("a line")));
    }

    #[test]
    fn too_many_scans_is_an_error() {
        let error = run(&scenario(2), Some(3)).expect_err("only 2 scans");
        assert!(error.0.contains("only 2 scans"), "{error}");
    }

    #[test]
    fn constant_velocity_is_rejected() {
        let mut simulation = crate::sim::planar::preset("linear-small", 1).expect("preset");
        simulation.scans = 2;
        let error = run(&simulation.run(), None).expect_err("not two-body");
        assert!(error.0.contains("two-body"), "{error}");
    }
}
