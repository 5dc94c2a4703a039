//! Fuzz target `scenario`: arbitrary bytes into `host_sim::scenario::Scenario::from_json`.
//!
//! Checked on every input:
//! - nothing panics;
//! - a rejected file gets a one-line message (the CLI prints it and exits with code 2);
//! - an accepted scenario survives a round trip through JSON unchanged;
//! - an accepted scenario that fits the embedded profile builds the core trackers (exhaustive and
//!   R-FISST), and their first scans run without a panic (integrator and sampler budgets are capped first,
//!   so that one input stays fast).
#![no_main]

use host_sim::pipeline::planar::runner;
use host_sim::pipeline::planar::setup;
use host_sim::pipeline::{Profile, ReferenceBudget, TrackerKind};
use host_sim::scenario::{MotionSpec, Scenario};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let mut scenario = match Scenario::from_json(text) {
        Ok(scenario) => scenario,
        Err(error) => {
            // Every error message is one line, whatever the keys contain.
            assert!(!error.0.contains(['\n', '\r']), "multi-line error message: {error}");
            // Keys and values are quoted as excerpts (issue 33): a message never echoes them whole.
            assert!(error.0.len() <= 16 << 10, "a message of {} bytes", error.0.len());
            return;
        }
    };
    let json = serde_json::to_string(&scenario).expect("an accepted scenario serialises");
    assert_eq!(Scenario::from_json(&json).as_ref(), Ok(&scenario), "round trip changed the scenario");

    // Bound the work of one input.
    if let MotionSpec::TwoBody { max_substeps, .. } = &mut scenario.motion {
        *max_substeps = (*max_substeps).min(2_000);
    }
    scenario.tracker.max_children_per_scan = scenario.tracker.max_children_per_scan.min(100_000);
    scenario.tracker.sampler.burn_in = scenario.tracker.sampler.burn_in.min(100);
    scenario.tracker.sampler.steps = scenario.tracker.sampler.steps.min(500);
    // `runner::build` holds the host profile's tracker (several MiB) in its frame, as the CLI's worker thread
    // allows: run it on a thread with the CLI's stack size.
    let worker = std::thread::Builder::new().stack_size(512 << 20).spawn(move || {
        for kind in [TrackerKind::Homht, TrackerKind::Rfisst] {
            let Ok(mut tracker) = runner::build(kind, Profile::Embedded, &scenario, ReferenceBudget::default()) else {
                continue;
            };
            for scan in scenario.scans.iter().take(8) {
                let _ = tracker.step(scan.time, &setup::measurements(scan));
            }
            let _ = tracker.snapshot();
        }
    });
    if let Ok(handle) = worker {
        if let Err(panic) = handle.join() {
            std::panic::resume_unwind(panic);
        }
    }
});
