//! Property tests of the scenario simulator: the scan assumption, origins and measurements inside the
//! field of view, truth bookkeeping, determinism per seed, scan times, validity of the written scenario,
//! and (as fixed-seed statistical tests) the detection frequency and the clutter rate.

use host_sim::pipeline::planar::setup::region;
use host_sim::scenario::{FieldOfViewSpec, Scenario, SensorSpec};
use host_sim::sim::planar::{self, PRESETS, SimObject, Simulation};
use nalgebra::SVector;
use proptest::prelude::*;
use proptest::test_runner::Config;
use std::collections::HashSet;

/// Few cases, and no regression files written into the source tree.
fn config() -> Config {
    Config { cases: 32, failure_persistence: None, ..Config::default() }
}

fn in_view(sensor: &SensorSpec, point: [f64; 2]) -> bool {
    region(&sensor.field_of_view).contains(&SVector::<f64, 2>::from(point))
}

fn alive(object: &SimObject, time: f64) -> bool {
    object.birth_time.is_none_or(|b| b <= time) && !object.death_time.is_some_and(|d| d <= time)
}

/// Every structural property of a simulated scenario.
fn check(simulation: &Simulation, scenario: &Scenario) -> Result<(), TestCaseError> {
    // (f) The written scenario passes the loader's checks, also after a trip through JSON.
    prop_assert_eq!(scenario.validate(), Ok(()));
    let text = serde_json::to_string(scenario).expect("serialise");
    let reloaded = Scenario::from_json(&text);
    prop_assert!(reloaded.is_ok(), "{:?}", reloaded.err());

    prop_assert_eq!(scenario.scans.len(), simulation.scans);
    let truth = scenario.truth.as_ref().expect("the simulator writes the truth");
    prop_assert_eq!(truth.scans.len(), scenario.scans.len());
    prop_assert_eq!(truth.objects.len(), simulation.objects.len());

    // (e) Scan times strictly increase, starting after the prior.
    let mut previous = scenario.prior.time;
    for scan in &scenario.scans {
        prop_assert!(scan.time > previous, "scan time {} is not after {}", scan.time, previous);
        previous = scan.time;
    }

    for (k, (scan, truth_scan)) in scenario.scans.iter().zip(&truth.scans).enumerate() {
        // Truth objects: exactly the objects existing at the scan, each once.
        let ids: Vec<u64> = truth_scan.objects.iter().map(|o| o.id).collect();
        let expected: Vec<u64> = simulation.objects.iter().filter(|o| alive(o, scan.time)).map(|o| o.id).collect();
        prop_assert_eq!(&ids, &expected, "scan {}: truth objects", k);

        // (a) One origin entry per measurement; each object at most once (the scan assumption).
        prop_assert_eq!(truth_scan.origins.len(), scan.measurements.len(), "scan {}", k);
        let mut seen = HashSet::new();
        for id in truth_scan.origins.iter().flatten() {
            prop_assert!(seen.insert(*id), "scan {}: object {} produced two measurements", k, id);
            // (b) The origin exists at this scan and its true position is in the field of view.
            let state = truth_scan.objects.iter().find(|o| o.id == *id);
            prop_assert!(state.is_some(), "scan {}: origin {} does not exist", k, id);
            let state = state.map(|s| s.state).unwrap_or_default();
            prop_assert!(
                in_view(&scenario.sensor, [state[0], state[1]]),
                "scan {}: object {} detected outside the field of view at {:?}",
                k,
                id,
                state
            );
        }
        // (c) Every measurement lies in the field of view.
        for (j, z) in scan.measurements.iter().enumerate() {
            prop_assert!(in_view(&scenario.sensor, *z), "scan {}: measurement {} at {:?} is out of view", k, j, z);
        }
    }

    // The prior: one hypothesis with exactly the objects the prior knows.
    prop_assert_eq!(scenario.prior.hypotheses.len(), 1);
    let labels: Vec<u64> = scenario.prior.hypotheses[0].objects.iter().map(|o| u64::from(o.label)).collect();
    let known: Vec<u64> = simulation.objects.iter().filter(|o| o.in_prior).map(|o| o.id).collect();
    prop_assert_eq!(labels, known);
    Ok(())
}

fn preset(index: usize, seed: u64, scans: usize) -> Simulation {
    let mut simulation = planar::preset(PRESETS[index], seed).expect("a preset");
    simulation.scans = simulation.scans.min(scans);
    simulation
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn presets_satisfy_the_scan_assumption(index in 0..PRESETS.len(), seed in any::<u64>(), scans in 1usize..=30) {
        let simulation = preset(index, seed, scans);
        check(&simulation, &simulation.run())?;
    }

}

proptest! {
    // Two-body propagation of 50 objects over long steps is slow in a debug build: fewer cases.
    #![proptest_config(Config { cases: 6, ..config() })]

    /// With 15-minute scans, 13 to 16 scans of fifty-birth-death reach past its births (all within the
    /// first quarter of the longest period, about 3.1 h).
    #[test]
    fn fifty_birth_death_with_births(seed in any::<u64>(), scans in 13usize..=16) {
        let mut simulation = planar::fifty_birth_death(seed);
        simulation.scan_interval = 900.0;
        simulation.scans = scans;
        let scenario = simulation.run();
        check(&simulation, &scenario)?;
        let births: Vec<u64> = simulation.objects.iter().filter(|o| !o.in_prior).map(|o| o.id).collect();
        prop_assert_eq!(births.len(), 5);
        let last = &scenario.truth.as_ref().expect("truth").scans[scans - 1];
        for id in births {
            prop_assert!(last.objects.iter().any(|o| o.id == id), "birth {} not alive at the end", id);
        }
    }
}

proptest! {
    #![proptest_config(config())]

    /// linear-small under random sensors: every kind of field of view, any p_D and clutter rate.
    #[test]
    fn linear_small_under_random_sensors(
        seed in any::<u64>(),
        scans in 1usize..=30,
        detection_probability in 0.05f64..=1.0,
        clutter_rate in 0.1f64..8.0,
        kind in 0..3usize,
        origin in prop::array::uniform2(-20.0f64..20.0),
        angle in -180.0f64..180.0,
        width in 1.0f64..=360.0,
        size in 5.0f64..80.0,
    ) {
        let mut simulation = planar::linear_small(seed);
        simulation.scans = scans;
        let field_of_view = match kind {
            0 => FieldOfViewSpec::Rectangle { min: origin, max: [origin[0] + size, origin[1] + size] },
            1 => FieldOfViewSpec::Sector {
                origin,
                look_direction_deg: angle,
                field_of_view_deg: width,
                max_range: size,
            },
            _ => FieldOfViewSpec::Everywhere { volume: size * size },
        };
        simulation.sensor = SensorSpec { detection_probability, clutter_rate, field_of_view };
        check(&simulation, &simulation.run())?;
    }

    /// (d) The same seed gives the same scenario; another seed another one.
    #[test]
    fn the_seed_determines_the_scenario(index in 0..PRESETS.len(), seed in any::<u64>(), scans in 1usize..=10) {
        let a = preset(index, seed, scans).run();
        prop_assert_eq!(&a, &preset(index, seed, scans).run());
        let other = seed.wrapping_add(1);
        prop_assert_ne!(&a, &preset(index, other, scans).run());
    }
}

/// Observed detection frequency of in-view objects and mean clutter count per scan.
fn rates(scenario: &Scenario) -> (f64, f64, f64) {
    let truth = scenario.truth.as_ref().expect("truth");
    let (mut in_view_count, mut detected, mut clutter) = (0usize, 0usize, vec![]);
    for truth_scan in &truth.scans {
        for object in &truth_scan.objects {
            if in_view(&scenario.sensor, [object.state[0], object.state[1]]) {
                in_view_count += 1;
                detected += usize::from(truth_scan.origins.contains(&Some(object.id)));
            }
        }
        clutter.push(truth_scan.origins.iter().filter(|o| o.is_none()).count() as f64);
    }
    let n = clutter.len() as f64;
    let mean = clutter.iter().sum::<f64>() / n;
    let variance = clutter.iter().map(|c| (c - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (detected as f64 / in_view_count as f64, mean, variance)
}

/// (g) Stationary objects far from the edges of a rectangle (no noisy return can leave it): the detection
/// frequency is p_D and the clutter count per scan is Poisson with mean Λ_C.
#[test]
fn detection_frequency_and_clutter_rate_match_the_sensor() {
    let mut simulation = planar::linear_small(2024);
    simulation.sensor = SensorSpec {
        detection_probability: 0.7,
        clutter_rate: 2.5,
        field_of_view: FieldOfViewSpec::Rectangle { min: [-100.0, -100.0], max: [100.0, 100.0] },
    };
    simulation.motion = host_sim::scenario::MotionSpec::ConstantVelocity { acceleration_noise: 1e-8 };
    simulation.objects = (0..20u64)
        .map(|i| SimObject {
            id: i,
            state: [-45.0 + 5.0 * i as f64, 10.0, 0.0, 0.0],
            epoch: 0.0,
            in_prior: true,
            birth_time: None,
            death_time: None,
        })
        .collect();
    simulation.scans = 500;
    let scenario = simulation.run();
    let (frequency, mean, variance) = rates(&scenario);
    // 10 000 trials: the standard deviation of the frequency is 0.0046.
    assert!((frequency - 0.7).abs() < 0.02, "detection frequency {frequency}, p_D 0.7");
    // 500 scans: the standard deviation of the mean is 0.07, of the variance about 0.17.
    assert!((mean - 2.5).abs() < 0.3, "mean clutter {mean}, rate 2.5");
    assert!((variance - 2.5).abs() < 0.8, "clutter variance {variance}, Poisson 2.5");
}

/// (g) The same on a full SSA preset: objects on orbits through the sector, p_D = 0.95, Λ_C = 1.
#[test]
fn fifteen_compare_detects_in_view_objects_with_p_d() {
    let simulation = planar::fifteen_compare(7);
    let scenario = simulation.run();
    let (frequency, mean, _) = rates(&scenario);
    assert!((frequency - 0.95).abs() < 0.03, "detection frequency {frequency}, p_D 0.95");
    assert!((mean - 1.0).abs() < 0.15, "mean clutter {mean} over {} scans, rate 1", scenario.scans.len());
}

/// `generate` writes a scenario with `Scenario::save`; `run` reads it back with `Scenario::load`. The
/// reloaded scenario should be the simulated one, bit for bit.
#[test]
fn scenarios_round_trip_through_json_exactly() {
    let mut simulation = planar::linear_small(0);
    simulation.scans = 1;
    let scenario = simulation.run();
    let text = serde_json::to_string(&scenario).expect("serialise");
    assert_eq!(Scenario::from_json(&text).expect("reload"), scenario);
}
