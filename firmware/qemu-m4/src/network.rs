//! The network replay: an excerpt of a version 2 network scenario (sensors of mixed kinds) through the
//! fused tracker `NetworkTracker<f32>`, after the radar one. `host-sim digest FILE --scans N --excerpt
//! network.rs` writes the excerpt (`RFISST_NETWORK_EXCERPT`; `build.rs` copies it to `$OUT_DIR/network.rs`,
//! included here): `NAME`, `SCANS_IN_FILE`, `EARTH_ROTATION`, `SENSORS`, `BIRTHS`, `CONFIG`, `PRIOR_TIME`,
//! `PRIOR` and `SCANS`, every number as the bits host-sim's `pipeline/digest/network.rs` computes.
//!
//! As the radar tracker, the tracker is a compile-time static whose configuration's network has no sensors
//! (`Network::unconfigured()`); the run-time network (`MixedNetwork::new` computes each sensor's clutter
//! volume) and the prior are installed in place by `Tracker::reset_with`.

use crate::{Record, cycles, stack};
use cortex_m_semihosting::{debug, hprintln};
use nalgebra::{ArrayStorage, SMatrix, SVector};
use tracker_core::config::Selection;
use tracker_core::model::{AdmissibleRegion, MIXED_DIMENSION, ProcessNoise, SensorBirths};
use tracker_core::pool::MeasuredBirths;
use tracker_core::sampler::{Proposal, SamplerConfig};
use tracker_core::sensor::{EarthRotation, GroundSite, LookShape, Platform, ScanGeometry, SiteSensor};
use tracker_core::{
    BirthDetection, BirthEvents, BirthModel, ChildGeneration, Config, Gaussian, MixedSensor, Network, NetworkConfig,
    NetworkTracker, NumericalFailure, PriorHypothesis, PriorObject, Region, Sensor, SensorKind, StoreOverflow,
    TrackLabel, TrackLoss, TwoBodyJ2,
};

/// One scan: its time, sensor and measurements.
pub struct Scan {
    /// Time (s after the epoch).
    pub time: f64,
    /// Index of the sensor.
    pub sensor: usize,
    /// Measurements, each padded to four components.
    pub measurements: &'static [SVector<f32, MIXED_DIMENSION>],
}

include!(concat!(env!("OUT_DIR"), "/network.rs"));

/// Scans replayed.
const COUNT: usize = SCANS.len();

/// The tracker, built at compile time (in `.data`: its initial image is in flash too).
static mut TRACKER: NetworkTracker<f32> = NetworkTracker::empty(CONFIG);

/// Builds the sensor network, then installs it with the rest of the configuration and the prior into the
/// static tracker, in place. Not inlined, so that its frames are given back before the scans.
#[inline(never)]
fn build() -> Result<&'static mut NetworkTracker<f32>, &'static str> {
    static TAKEN: core::sync::atomic::AtomicBool = core::sync::atomic::AtomicBool::new(false);
    if TAKEN.swap(true, core::sync::atomic::Ordering::AcqRel) {
        return Err("the network tracker was already built");
    }
    let mut network = Network::<f32>::new(EarthRotation::new(EARTH_ROTATION), &SENSORS)?;
    for (index, births) in BIRTHS.iter().enumerate() {
        network = network.with_births(index, *births)?;
    }
    // SAFETY: `TAKEN` hands out this one `&mut` exactly once, and the firmware is single-threaded with no
    // interrupt touching the tracker.
    let tracker = unsafe { &mut *core::ptr::addr_of_mut!(TRACKER) };
    tracker
        .reset_with(Config { measurement: network, ..CONFIG }, &PRIOR, PRIOR_TIME)
        .map_err(|_| "tracker configuration rejected")?;
    Ok(tracker)
}

/// The per-scan records, in a static.
#[inline(never)]
fn records() -> Option<&'static mut [Record; COUNT]> {
    cortex_m::singleton!(: [Record; COUNT] = [Record::EMPTY; COUNT])
}

/// Replays the network scans and prints their digest text, ticks and stack.
pub fn run() -> debug::ExitStatus {
    hprintln!(
        "qemu-m4: network scenario {:?}: replaying {} of {} scans of {} sensors through NetworkTracker<f32> ({} \
         bytes, static, configured in place), {} prior objects",
        NAME,
        COUNT,
        SCANS_IN_FILE,
        SENSORS.len(),
        core::mem::size_of::<NetworkTracker<f32>>(),
        PRIOR.iter().map(|h| h.objects.len()).max().unwrap_or(0)
    );
    stack::paint();
    let tracker = match build() {
        Ok(tracker) => tracker,
        Err(error) => {
            hprintln!("qemu-m4: error: network tracker: {}", error);
            return debug::EXIT_FAILURE;
        }
    };
    let build_stack = stack::high_water();
    let Some(records) = records() else {
        hprintln!("qemu-m4: error: the network record table was already taken");
        return debug::EXIT_FAILURE;
    };
    stack::paint();
    let call_depth = stack::depth();
    for (record, scan) in records.iter_mut().zip(&SCANS) {
        let geometry = ScanGeometry { sensor: scan.sensor, time: scan.time, observer: None };
        let start = cycles::now();
        let outcome = tracker.step_scan(&geometry, scan.measurements);
        record.ticks = cycles::now() - start;
        record.outcome = outcome.map(|report| (report.hypotheses, report.tracks));
        record.digest = tracker.digest();
    }
    let scan_stack = stack::high_water();
    crate::print(records, crate::TRACKER_COUNTS);
    hprintln!(
        "qemu-m4: network stack ({} bytes): building the tracker {} bytes; scans {} bytes, of which step_scan and \
         digest {} bytes",
        stack::size(),
        build_stack,
        scan_stack,
        scan_stack.saturating_sub(call_depth)
    );
    debug::EXIT_SUCCESS
}
