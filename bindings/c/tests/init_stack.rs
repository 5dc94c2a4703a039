//! `rfisst_tracker_init` builds the tracker in the caller's storage (a compile-time image copied in, then
//! `Tracker::reset_with`), so it needs little stack: every kind initialises on a thread of 192 KiB, less than
//! the smallest handle (216 KB), so no tracker can pass through it: one built on the stack (as before, about
//! 2.2 × its size) overflows it and aborts this test. Measured (x86-64, debug build): 87–143 KB.
//!
//! `RFISST_STACK_SEARCH=1 cargo test --release -p rfisst-c --test init_stack -- --nocapture` also prints
//! each kind's smallest thread stack that initialises, to 1 KiB (each try in a child process of this
//! test binary, since an overflow aborts the process).

use core::ffi::c_void;
use rfisst::scenario::{CScenario, from_json};
use rfisst::*;

/// The thread stack every kind must initialise on.
const SMALL_STACK: usize = 192 << 10;

/// The scenario each kind initialises from (the optical kinds: the radar's with telescopes).
fn scenario(kind: RfisstKind) -> CScenario {
    if kind.is_planar() {
        let mut simulation = host_sim::sim::planar::preset("fifty-birth-death", 1).expect("preset");
        simulation.scans = 1;
        let json = serde_json::to_string(&simulation.run()).expect("JSON");
        return from_json(&json, kind, None).expect("planar");
    }
    let simulation = host_sim::sim::presets::tiny_3d(1).expect("tiny-3d");
    let scenario = host_sim::scenario::from_simulation::to_scenario(&simulation).expect("scenario").0;
    let json = serde_json::to_string(&scenario).expect("JSON");
    if !matches!(kind, RfisstKind::RfisstOpticalF32 | RfisstKind::RfisstOpticalF64) {
        return from_json(&json, kind, None).expect("radar");
    }
    let mut scenario = from_json(&json, RfisstKind::RfisstRadarF64, None).expect("radar");
    for sensor in &mut scenario.config.sensors[..scenario.config.sensor_count as usize] {
        sensor.kind = rfisst::config::sensor::RFISST_SENSOR_OPTICAL;
        sensor.sigma = [1e-5, 1e-5, 0.0, 0.0];
        sensor.detection.field_of_view.has_range = 0;
    }
    scenario
}

/// Initialises `kind` from `scenario` on a thread of `stack` bytes; the status.
fn init_on_stack(kind: RfisstKind, scenario: CScenario, stack: usize) -> RfisstStatus {
    let size = rfisst_tracker_size(kind as u32);
    let mut words: Vec<u128> = vec![0; size / 16 + 1];
    let address = words.as_mut_ptr() as usize;
    let status = std::thread::Builder::new()
        .stack_size(stack)
        .spawn(move || {
            let hypotheses = scenario.hypotheses();
            let mut tracker = core::ptr::null_mut();
            // SAFETY: `words` outlives the thread (joined below) and holds `size` bytes, 16-byte aligned.
            unsafe {
                rfisst_tracker_init(
                    address as *mut c_void,
                    size,
                    kind as u32,
                    &scenario.config,
                    hypotheses.as_ptr(),
                    hypotheses.len(),
                    scenario.prior_time,
                    &mut tracker,
                )
            }
        })
        .expect("thread")
        .join()
        .expect("no panic");
    drop(words);
    status
}

#[test]
fn every_kind_initialises_on_a_small_stack() {
    if let Some(child) = std::env::var_os("RFISST_STACK_CHILD") {
        // A child of the search below: one try, its outcome the exit status.
        let text = child.to_string_lossy().into_owned();
        let (code, stack) = text.split_once(':').expect("kind:stack");
        let kind = RfisstKind::of(code.parse().expect("kind")).expect("kind");
        let status = init_on_stack(kind, scenario(kind), stack.parse().expect("stack"));
        std::process::exit(i32::from(status != RfisstStatus::RfisstOk));
    }
    if std::env::var_os("RFISST_STACK_SEARCH").is_some() {
        for kind in RfisstKind::ALL {
            eprintln!("{}: smallest thread stack that initialises: {} bytes", kind.name(), smallest_stack(kind));
        }
    }
    for kind in RfisstKind::ALL {
        let size = rfisst_tracker_size(kind as u32);
        assert!(size > SMALL_STACK, "{kind:?}: {size} bytes, more than the stack");
        assert_eq!(init_on_stack(kind, scenario(kind), SMALL_STACK), RfisstStatus::RfisstOk, "{kind:?}");
    }
}

/// The smallest thread stack (to 1 KiB, at least 16 KiB) on which `kind` initialises, each try a child
/// process.
fn smallest_stack(kind: RfisstKind) -> usize {
    let exe = std::env::current_exe().expect("test binary");
    let works = |stack: usize| {
        std::process::Command::new(&exe)
            .args(["--exact", "every_kind_initialises_on_a_small_stack", "--test-threads=1"])
            .env("RFISST_STACK_CHILD", format!("{}:{stack}", kind as u32))
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .status()
            .expect("child")
            .success()
    };
    let (mut low, mut high) = (16usize << 10, 8usize << 20);
    assert!(works(high), "{kind:?} fails on 8 MiB");
    while high - low > 1024 {
        let middle = (low + high) / 2;
        if works(middle) { high = middle } else { low = middle }
    }
    high
}
