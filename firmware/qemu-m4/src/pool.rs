//! The pool replay: the radar replay's scenario, scans, configuration and restricted prior ([`crate::radar`])
//! through tracker-core's fixed pool of cluster trackers, `ClusterPool<f32, ..>`, after the network one: every
//! object of the prior its own cluster, exact splits (ε = 0). Per scan it prints the clusters of objects and
//! their hypotheses after the scan and `ClusterPool::digest`, as `host-sim digest RADAR_SCENARIO --pool`
//! does (`host-sim/src/pipeline/digest/pool.rs`).
//!
//! As the radar tracker, the pool is a compile-time static whose three cores hold the placeholder
//! configuration (a network of no sensors); `ClusterPool::reset_with` installs the run-time network and the
//! prior's objects in place, so the pool never passes through the stack.

use crate::radar::{PLACEHOLDER, PRIOR, PRIOR_TIME, SCANS};
use crate::{Record, cycles, stack};
use cortex_m_semihosting::{debug, hprintln};
use nalgebra::SVector;
use tracker_core::partition::{ClusterPool, PoolError, PoolReport};
use tracker_core::sensor::ScanGeometry;
use tracker_core::{Config, RadarNetwork, TwoBodyJ2, ssa_caps};

// The pool's capacities: the same list is in `host-sim/src/pipeline/digest/pool.rs`; keep the two in step.
/// Hypotheses per cluster.
const H: usize = 16;
/// Objects per hypothesis of a cluster.
const N: usize = 8;
/// Measurements per cluster and scan.
const Z: usize = 32;
/// Tracks per cluster.
const K: usize = 32;
/// Birth cells (the radar configuration's).
const B: usize = ssa_caps::BIRTH_CELLS;
/// Clusters (radar-leo's excerpt starts with 43).
const P: usize = 64;
/// Measurements per scan.
const L: usize = 64;

/// The embedded pool of radar cluster trackers.
type Pool = ClusterPool<f32, TwoBodyJ2<f32>, RadarNetwork<f32>, 6, 3, H, N, Z, K, B, P, L>;

/// Scans replayed.
const COUNT: usize = SCANS.len();

/// The pool, built at compile time (in `.data`: its initial image is in flash too).
static mut POOL: Pool = Pool::empty(PLACEHOLDER, PLACEHOLDER, PLACEHOLDER);

/// Installs the radar configuration and the objects of the prior (one hypothesis) into the static pool, in
/// place. Not inlined, so that its frames are given back before the scans.
#[inline(never)]
fn build() -> Result<&'static mut Pool, &'static str> {
    static TAKEN: core::sync::atomic::AtomicBool = core::sync::atomic::AtomicBool::new(false);
    if TAKEN.swap(true, core::sync::atomic::Ordering::AcqRel) {
        return Err("the pool was already built");
    }
    let [prior] = PRIOR.as_slice() else { return Err("the pool replay takes one prior hypothesis") };
    let network = crate::radar::network()?;
    // SAFETY: `TAKEN` hands out this one `&mut` exactly once, and the firmware is single-threaded with no
    // interrupt touching the pool.
    let pool = unsafe { &mut *core::ptr::addr_of_mut!(POOL) };
    pool.reset_with(Config { measurement: network, ..PLACEHOLDER }, prior.objects, PRIOR_TIME, 0.0)
        .map_err(|_| "pool configuration rejected")?;
    Ok(pool)
}

/// The per-scan records, in a static.
#[inline(never)]
fn records() -> Option<&'static mut [Record<PoolError>; COUNT]> {
    cortex_m::singleton!(: [Record<PoolError>; COUNT] = [Record::EMPTY; COUNT])
}

/// `ClusterPool::step`, not inlined: its frames lie below the replay's, where the stack measure counts them.
#[inline(never)]
fn step(
    pool: &mut Pool,
    geometry: &ScanGeometry<f32>,
    measurements: &[SVector<f32, 3>],
) -> Result<PoolReport<f32>, PoolError> {
    pool.step(geometry, measurements)
}

/// `ClusterPool::digest`, not inlined (as [`step`]).
#[inline(never)]
fn digest(pool: &mut Pool) -> u64 {
    pool.digest()
}

/// Replays the radar scans through the pool and prints their digest text, what the pool did, ticks and
/// stack.
pub fn run() -> debug::ExitStatus {
    hprintln!(
        "qemu-m4: pool scenario {:?}: replaying {} scans through ClusterPool<f32> (H {} N {} Z {} K {} B {} P {} \
         L {}; {} bytes, static, configured in place), {} prior objects, each its own cluster",
        crate::radar::NAME,
        COUNT,
        H,
        N,
        Z,
        K,
        B,
        P,
        L,
        core::mem::size_of::<Pool>(),
        PRIOR.iter().map(|h| h.objects.len()).max().unwrap_or(0)
    );
    stack::paint();
    let pool = match build() {
        Ok(pool) => pool,
        Err(error) => {
            hprintln!("qemu-m4: error: pool: {}", error);
            return debug::EXIT_FAILURE;
        }
    };
    let build_stack = stack::high_water();
    let Some(records) = records() else {
        hprintln!("qemu-m4: error: the pool record table was already taken");
        return debug::EXIT_FAILURE;
    };
    // Merged, born, split, most clusters, refused scans: the host prints the same line to stderr.
    let mut totals = [0usize; 5];
    stack::paint();
    let call_depth = stack::depth();
    for (record, scan) in records.iter_mut().zip(&SCANS) {
        let geometry = ScanGeometry { sensor: scan.sensor, time: scan.time, observer: None };
        let start = cycles::now();
        let outcome = step(pool, &geometry, scan.measurements);
        record.ticks = cycles::now() - start;
        match &outcome {
            Ok(report) => {
                totals[0] += report.merged;
                totals[1] += report.born_clusters;
                totals[2] += report.split;
                totals[3] = totals[3].max(report.clusters);
            }
            Err(_) => totals[4] += 1,
        }
        record.outcome = outcome.map(|report| (report.clusters, report.hypotheses));
        record.digest = digest(pool);
    }
    let scan_stack = stack::high_water();
    crate::print(records, ["clusters", "hypotheses"]);
    hprintln!(
        "qemu-m4: pool: merged {}, born {}, split {}, at most {} clusters, {} scans refused",
        totals[0],
        totals[1],
        totals[2],
        totals[3],
        totals[4]
    );
    hprintln!(
        "qemu-m4: pool stack ({} bytes): building the pool {} bytes; scans {} bytes, of which step and digest {} \
         bytes",
        stack::size(),
        build_stack,
        scan_stack,
        scan_stack.saturating_sub(call_depth)
    );
    debug::EXIT_SUCCESS
}
