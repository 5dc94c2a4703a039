//! The network tracker from C with births from the measurements (issue 28): a network scenario read
//! through the C configuration (measured births, each sensor's own births) gives `host-sim digest`'s
//! digests scan by scan, and the new fields' bad values are statuses naming the field.

use core::ffi::{CStr, c_void};
use host_sim::scenario::from_simulation::{Preset3d, to_scenario};
use rfisst::config::sensor;
use rfisst::replay::digest_text;
use rfisst::scenario::{CScenario, from_json};
use rfisst::*;

/// The tiny network preset (seed 1) as a scenario and as JSON.
fn tiny_network() -> (host_sim::scenario::v2::Scenario3d, String) {
    let simulation = Preset3d::TinyNetwork.simulate(1).expect("tiny-network");
    let scenario = to_scenario(&simulation).expect("scenario").0;
    let json = serde_json::to_string(&scenario).expect("JSON");
    (scenario, json)
}

fn with_big_stack(f: impl FnOnce() + Send + 'static) {
    std::thread::Builder::new().stack_size(256 << 20).spawn(f).expect("thread").join().expect("no panic");
}

/// Initialises `kind` from `config` and `scenario`'s prior; the status and the last error.
fn init_status(kind: RfisstKind, config: &RfisstConfig, scenario: &CScenario) -> (RfisstStatus, String) {
    let size = rfisst_tracker_size(kind as u32);
    let mut words = vec![0u64; size / 8 + 1];
    let hypotheses = scenario.hypotheses();
    let mut tracker = core::ptr::null_mut();
    // SAFETY: `words` holds `size` bytes, 8-aligned; the configuration and the prior outlive the call.
    let status = unsafe {
        rfisst_tracker_init(
            words.as_mut_ptr().cast::<c_void>(),
            size,
            kind as u32,
            config,
            hypotheses.as_ptr(),
            hypotheses.len(),
            scenario.prior_time,
            &mut tracker,
        )
    };
    // SAFETY: the storage went through `rfisst_tracker_init`'s checks.
    let error = unsafe { CStr::from_ptr(rfisst_tracker_last_error(words.as_ptr().cast())) };
    (status, error.to_string_lossy().into_owned())
}

#[test]
fn a_network_scenario_with_measured_births_gives_host_sim_digests() {
    with_big_stack(|| {
        let (parsed, json) = tiny_network();
        assert!(parsed.birth.measured.is_some(), "the preset has births from the measurements");
        let count = parsed.scans.len().min(40);
        let scenario = from_json(&json, RfisstKind::RfisstNetworkF32, Some(count)).expect("network");
        assert_eq!(scenario.config.measured_births.enabled, 1);
        let sensors = &scenario.config.sensors[..scenario.config.sensor_count as usize];
        assert!(sensors.iter().any(|s| s.births != sensor::RFISST_BIRTHS_FROM_MODEL), "a sensor's own births");
        let host = host_sim::pipeline::digest::network::run(&parsed, Some(count)).expect("host digest");
        assert_eq!(digest_text(&scenario, RfisstKind::RfisstNetworkF32, count).expect("C digest"), host);
        // Without the measured births the run differs: the setting is read.
        let mut off = scenario.clone();
        off.config.measured_births.enabled = 0;
        assert_ne!(digest_text(&off, RfisstKind::RfisstNetworkF32, count).expect("C digest"), host);
    });
}

#[test]
fn bad_birth_settings_are_statuses_naming_the_field() {
    with_big_stack(|| {
        let (_, json) = tiny_network();
        let scenario = from_json(&json, RfisstKind::RfisstNetworkF32, None).expect("network");
        let network = RfisstKind::RfisstNetworkF32;
        assert_eq!(init_status(network, &scenario.config, &scenario).0, RfisstStatus::RfisstOk);

        let mut config = scenario.config;
        config.measured_births.enabled = 2;
        let (status, error) = init_status(network, &config, &scenario);
        assert_eq!(status, RfisstStatus::RfisstInvalidConfig);
        assert!(error.contains("measured_births.enabled"), "{error}");

        let mut config = scenario.config;
        config.sensors[0].births = 7;
        let (status, error) = init_status(network, &config, &scenario);
        assert_eq!(status, RfisstStatus::RfisstInvalidConfig);
        assert!(error.contains("sensors[].births"), "{error}");

        // A sensor's own region that is not valid is the core's error.
        let mut config = scenario.config;
        config.sensors[0].births = sensor::RFISST_BIRTHS_REGION;
        config.sensors[0].birth_region = RfisstAdmissibleRegion::ZERO;
        assert_eq!(init_status(network, &config, &scenario).0, RfisstStatus::RfisstConfigRejected);

        // The radar tracker takes births from the model only.
        let radar = {
            let simulation = host_sim::sim::presets::tiny_3d(1).expect("tiny-3d");
            let parsed = to_scenario(&simulation).expect("scenario").0;
            let json = serde_json::to_string(&parsed).expect("JSON");
            from_json(&json, RfisstKind::RfisstRadarF32, None).expect("radar")
        };
        let mut config = radar.config;
        config.sensors[0].births = sensor::RFISST_BIRTHS_OFF;
        let (status, error) = init_status(RfisstKind::RfisstRadarF32, &config, &radar);
        assert_eq!(status, RfisstStatus::RfisstInvalidConfig);
        assert!(error.contains("RFISST_BIRTHS_FROM_MODEL"), "{error}");
    });
}
