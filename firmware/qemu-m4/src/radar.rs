//! The radar replay: a recorded version 2 radar scenario (`RFISST_SCENARIO_3D`) through `RadarTracker<f32>`,
//! after the planar one. `build.rs` turns the file into `$OUT_DIR/radar.rs`, included here; it defines
//! `NAME`, `SCANS_IN_FILE`, `EPOCH_JD`, `MOTION`, `SENSORS`, `BIRTH`, `DEATH_PROBABILITY`, `GATE`, `CHILDREN`,
//! `SELECTION`, `STORE_OVERFLOW`, `NUMERICAL_FAILURE`, `SEED`, `PRIOR_TIME`, `PRIOR` (restricted to the objects
//! the replayed scans detect), `PRIOR_OBJECTS_IN_FILE` and `SCANS`, every value as the bits host-sim's
//! `digest3d.rs` computes.
//!
//! The sensor network computes its clutter volumes when it is built, which is not `const`: the tracker is a
//! compile-time static holding a placeholder configuration (a network of no sensors,
//! `RadarNetwork::unconfigured()`), and `Tracker::reset_with` installs the run-time configuration and the
//! prior in place, so the tracker never passes through the stack.

use crate::{Record, cycles, stack};
use cortex_m_semihosting::{debug, hprintln};
use nalgebra::{ArrayStorage, SMatrix, SVector};
use tracker_core::config::Selection;
use tracker_core::model::ProcessNoise;
use tracker_core::sampler::{Proposal, SamplerConfig};
use tracker_core::sensor::{EarthRotation, GroundSite, Platform, ScanGeometry, SiteSensor, gmst_iau82};
use tracker_core::{
    BirthDetection, BirthEvents, BirthModel, ChildGeneration, Config, Gaussian, LookShape, NumericalFailure,
    PriorHypothesis, PriorObject, RadarConfig, RadarNetwork, RadarTracker, Region, Sensor, SensorNetwork,
    StoreOverflow, TrackLabel, TwoBodyJ2, ssa_caps,
};

/// One scan: its time, sensor and measurements.
pub struct Scan {
    /// Time (s after the epoch).
    pub time: f64,
    /// Index of the sensor.
    pub sensor: usize,
    /// Measurements (range km, azimuth rad, elevation rad).
    pub measurements: &'static [SVector<f32, 3>],
}

/// A 3-vector.
const fn vector3(v: [f32; 3]) -> SVector<f32, 3> {
    SVector::from_array_storage(ArrayStorage([v]))
}

/// A Gaussian over the 6-state from its mean and its covariance's rows.
const fn gaussian6(mean: [f32; 6], r: [[f32; 6]; 6]) -> Gaussian<f32, 6> {
    let mut columns = [[0.0; 6]; 6];
    let mut i = 0;
    while i < 6 {
        let mut j = 0;
        while j < 6 {
            columns[j][i] = r[i][j];
            j += 1;
        }
        i += 1;
    }
    Gaussian {
        mean: SVector::from_array_storage(ArrayStorage([mean])),
        covariance: SMatrix::from_array_storage(ArrayStorage(columns)),
    }
}

include!(concat!(env!("OUT_DIR"), "/radar.rs"));

/// Scans replayed.
const COUNT: usize = SCANS.len();

/// The configuration with a network of no sensors: the compile-time placeholder of the static tracker.
pub(crate) const PLACEHOLDER: RadarConfig<f32> = Config {
    motion: MOTION,
    measurement: RadarNetwork::unconfigured(),
    // As host-sim: the first sensor's (each scan uses its own sensor's).
    sensor: SENSORS[0].detection,
    birth: BIRTH,
    death_probability: DEATH_PROBABILITY,
    gate: GATE,
    children: CHILDREN,
    selection: SELECTION,
    store_overflow: STORE_OVERFLOW,
    numerical_failure: NUMERICAL_FAILURE,
    track_loss: tracker_core::TrackLoss::Never,
    seed: SEED,
};

/// The tracker, built at compile time (in `.data`: its initial image is in flash too).
static mut TRACKER: RadarTracker<f32> = RadarTracker::empty(PLACEHOLDER);

/// The sensor network, with the Earth rotation angle at the epoch computed in `f64`, rounded once.
pub(crate) fn network() -> Result<RadarNetwork<f32>, &'static str> {
    SensorNetwork::new(EarthRotation::new(gmst_iau82(EPOCH_JD) as f32), &SENSORS)
}

/// Installs the configuration ([`network`]) and the prior into the static tracker, in place. Not inlined,
/// so that its frames are given back before the scans.
#[inline(never)]
fn build() -> Result<&'static mut RadarTracker<f32>, &'static str> {
    static TAKEN: core::sync::atomic::AtomicBool = core::sync::atomic::AtomicBool::new(false);
    if TAKEN.swap(true, core::sync::atomic::Ordering::AcqRel) {
        return Err("the radar tracker was already built");
    }
    let network = network()?;
    // SAFETY: `TAKEN` hands out this one `&mut` exactly once, and the firmware is single-threaded with no
    // interrupt touching the tracker.
    let tracker = unsafe { &mut *core::ptr::addr_of_mut!(TRACKER) };
    tracker
        .reset_with(Config { measurement: network, ..PLACEHOLDER }, &PRIOR, PRIOR_TIME)
        .map_err(|_| "tracker configuration rejected")?;
    Ok(tracker)
}

/// The per-scan records, in a static.
#[inline(never)]
fn records() -> Option<&'static mut [Record; COUNT]> {
    cortex_m::singleton!(: [Record; COUNT] = [Record::EMPTY; COUNT])
}

/// Replays the radar scans and prints their digest text, ticks and stack.
pub fn run() -> debug::ExitStatus {
    hprintln!(
        "qemu-m4: radar scenario {:?}: replaying {} of {} scans through RadarTracker<f32> ({} bytes, static, configured \
         in place), prior restricted to the {} of {} objects they detect",
        NAME,
        COUNT,
        SCANS_IN_FILE,
        core::mem::size_of::<RadarTracker<f32>>(),
        PRIOR.iter().map(|h| h.objects.len()).max().unwrap_or(0),
        PRIOR_OBJECTS_IN_FILE
    );
    stack::paint();
    let tracker = match build() {
        Ok(tracker) => tracker,
        Err(error) => {
            hprintln!("qemu-m4: error: radar tracker: {}", error);
            return debug::EXIT_FAILURE;
        }
    };
    let build_stack = stack::high_water();
    let Some(records) = records() else {
        hprintln!("qemu-m4: error: the radar record table was already taken");
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
        "qemu-m4: radar stack ({} bytes): building the tracker {} bytes; scans {} bytes, of which step_scan and \
         digest {} bytes",
        stack::size(),
        build_stack,
        scan_stack,
        scan_stack.saturating_sub(call_depth)
    );
    debug::EXIT_SUCCESS
}
