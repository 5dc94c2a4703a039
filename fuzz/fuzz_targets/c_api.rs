//! Fuzz target `c_api`: the C interface (`bindings/c`, crate `rfisst-c`) called as a careless C program
//! would, through its `extern "C"` functions: a planar tracker (`SsaTracker<f64>` or `<f32>`) initialised in
//! caller storage from the `fifty-birth-death` prior, then arbitrary calls of `rfisst_tracker_step` (any
//! time bits, any sensor index, any measurement count up to Z + 3 and any dimension, each with a buffer of
//! exactly that many values, any value bits; null measurements, observer or report), and
//! `rfisst_tracker_init_json` on arbitrary text.
//!
//! Checked on every input (under the address sanitizer: no out-of-bounds read or write, no use of
//! uninitialised memory reported):
//! - nothing panics or crashes;
//! - a call that fails leaves the tracker's digest unchanged, and its status is not `OK`;
//! - a storage that was never initialised, or garbage, is `INVALID_HANDLE`, never used;
//! - the same calls on a fresh tracker give the same statuses and digests (determinism).
#![no_main]

use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;
use rfisst::scenario::{CScenario, from_json, rfisst_tracker_init_json};
use rfisst::*;
use std::ffi::{CString, c_void};
use std::sync::OnceLock;

/// The planar prior and configuration, read once.
fn planar() -> &'static CScenario {
    static SCENARIO: OnceLock<CScenario> = OnceLock::new();
    SCENARIO.get_or_init(|| {
        let mut simulation = host_sim::sim::planar::preset("fifty-birth-death", 1).expect("preset");
        simulation.scans = 2;
        let json = serde_json::to_string(&simulation.run()).expect("JSON");
        from_json(&json, RfisstKind::RfisstSsaF64, None).expect("planar scenario")
    })
}

/// Storage for any tracker, 16-byte aligned.
struct Storage(Vec<u128>);

impl Storage {
    fn new(kind: u32) -> Self {
        Storage(vec![0; rfisst_tracker_size(kind) / 16 + 1])
    }
    fn ptr(&mut self) -> *mut c_void {
        self.0.as_mut_ptr().cast()
    }
    fn size(&self) -> usize {
        self.0.len() * 16
    }
}

/// A number: any bits, or a value of a useful size.
#[derive(Debug, Clone, Copy, Arbitrary)]
enum Num {
    Bits(u64),
    Small(i16),
    Special(u8),
}

impl Num {
    fn value(self) -> f64 {
        const SPECIAL: [f64; 8] = [0.0, -0.0, f64::NAN, f64::INFINITY, f64::NEG_INFINITY, f64::MAX, 1e-300, 1e300];
        match self {
            Num::Bits(b) => f64::from_bits(b),
            Num::Small(v) => f64::from(v) / 4.0,
            Num::Special(i) => SPECIAL[usize::from(i) % SPECIAL.len()],
        }
    }
}

#[derive(Debug, Arbitrary)]
struct Call {
    /// Seconds after the previous scan, or any bits.
    dt: Num,
    sensor: u8,
    count: u8,
    /// The dimension passed: the tracker's (2) or any other.
    dimension: u8,
    values: Vec<Num>,
    null_measurements: bool,
    observer: Option<[Num; 6]>,
    null_report: bool,
}

#[derive(Debug, Arbitrary)]
struct Input {
    f32_tracker: bool,
    calls: Vec<Call>,
    json: String,
    garbage: Vec<u8>,
}

/// Runs the calls on a fresh tracker; returns every (status, digest).
fn run(input: &Input) -> Vec<(RfisstStatus, u64)> {
    let scenario = planar();
    let kind = if input.f32_tracker { RfisstKind::RfisstSsaF32 } else { RfisstKind::RfisstSsaF64 } as u32;
    let mut storage = Storage::new(kind);
    let hypotheses = scenario.hypotheses();
    let mut tracker = core::ptr::null_mut();
    // SAFETY: valid storage of the kind's size, a valid configuration and prior, a writable handle slot.
    let status = unsafe {
        rfisst_tracker_init(
            storage.ptr(),
            storage.size(),
            kind,
            &scenario.config,
            hypotheses.as_ptr(),
            hypotheses.len(),
            scenario.prior_time,
            &mut tracker,
        )
    };
    assert_eq!(status, RfisstStatus::RfisstOk);
    let digest = |tracker| {
        let mut d = 0;
        // SAFETY: a handle from init.
        assert_eq!(unsafe { rfisst_tracker_digest(tracker, &mut d) }, RfisstStatus::RfisstOk);
        d
    };
    let mut time = scenario.prior_time;
    let mut trace = vec![];
    for call in input.calls.iter().take(12) {
        let dt = call.dt.value();
        let t = if matches!(call.dt, Num::Small(_)) { time + dt.abs() } else { dt };
        let (count, dimension) = (usize::from(call.count % 12), usize::from(call.dimension % 5));
        let values: Vec<f64> = (0..count * dimension)
            .map(|i| call.values.get(i % call.values.len().max(1)).map_or(1.0, |v| v.value()))
            .collect();
        let measurements = if call.null_measurements { core::ptr::null() } else { values.as_ptr() };
        let observer = call.observer.map(|o| o.map(Num::value));
        let observer_ptr = observer.as_ref().map_or(core::ptr::null(), |o| o.as_ptr());
        let mut report = core::mem::MaybeUninit::<RfisstStepReport>::uninit();
        let report_ptr = if call.null_report { core::ptr::null_mut() } else { report.as_mut_ptr() };
        let before = digest(tracker);
        // SAFETY: `measurements` is null or holds exactly count × dimension values; `observer` null or 6.
        let status = unsafe {
            rfisst_tracker_step(
                tracker,
                t,
                usize::from(call.sensor),
                observer_ptr,
                measurements,
                count,
                dimension,
                report_ptr,
            )
        };
        let after = digest(tracker);
        if status == RfisstStatus::RfisstOk {
            time = t;
        } else {
            assert_eq!(before, after, "a failed step ({status:?}) changed the tracker");
        }
        trace.push((status, after));
    }
    // Garbage is never taken for a tracker.
    let mut junk = Storage::new(kind);
    let bytes = junk.size().min(input.garbage.len());
    // SAFETY: `junk` holds at least `bytes` bytes.
    unsafe { core::ptr::copy_nonoverlapping(input.garbage.as_ptr(), junk.ptr().cast::<u8>(), bytes) };
    let mut d = 0;
    // SAFETY: readable storage of the kind's size; the interface must refuse it as a handle.
    let status = unsafe { rfisst_tracker_digest(junk.ptr().cast(), &mut d) };
    assert!(status == RfisstStatus::RfisstInvalidHandle, "garbage storage gave {status:?}");
    trace
}

fuzz_target!(|input: Input| {
    let first = run(&input);
    assert_eq!(first, run(&input), "the same calls gave other results");
    // Arbitrary text as a scenario: a status, never a crash; a success is a usable tracker.
    if let Ok(json) = CString::new(input.json.as_bytes()) {
        let kind = RfisstKind::RfisstSsaF64 as u32;
        let mut storage = Storage::new(kind);
        let mut tracker = core::ptr::null_mut();
        // SAFETY: valid storage, a NUL-terminated string, a writable handle slot.
        let status = unsafe { rfisst_tracker_init_json(storage.ptr(), storage.size(), kind, json.as_ptr(), &mut tracker) };
        if status == RfisstStatus::RfisstOk {
            let mut d = 0;
            // SAFETY: a handle from init.
            assert_eq!(unsafe { rfisst_tracker_digest(tracker, &mut d) }, RfisstStatus::RfisstOk);
        } else {
            assert!(tracker.is_null());
        }
    }
});
