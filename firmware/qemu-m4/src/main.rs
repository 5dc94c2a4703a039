//! QEMU replay firmware for the Cortex-M4F (`mps2-an386`): runs a recorded host-sim scenario through
//! tracker-core's `SsaTracker<f32>` (then, when built with them, a radar scenario through `RadarTracker<f32>`,
//! a network excerpt through `NetworkTracker<f32>` and the radar scenario again through a `ClusterPool` of
//! cluster trackers) and prints, over semihosting, the same digest text as
//! `host-sim digest` plus SysTick counts per scan and the stack high-water mark.
//!
//! Lines starting with `scan ` or `final ` are the digest text, compared byte for byte with the host's by
//! `scripts/qemu-check.sh`; every other line starts with `qemu-m4:` or `ticks `. The exit status is 0 when
//! every scan was replayed (rejected scans are part of the digest text), 1 when the tracker could not be
//! built, on a panic or on a fault. See docs/embedded.md.
#![no_std]
#![no_main]

mod cycles;
#[cfg(rfisst_network)]
mod network;
#[cfg(rfisst_radar)]
mod pool;
#[cfg(rfisst_radar)]
mod radar;
mod scenario;
mod stack;

use cortex_m_rt::{ExceptionFrame, entry, exception};
use cortex_m_semihosting::{debug, hprintln};
use tracker_core::digest::Fnv1a;
use tracker_core::{ConfigError, SsaTracker, StepError};

/// Scans replayed.
const SCANS: usize = scenario::SCANS.len();

/// What one scan gave.
#[derive(Clone, Copy)]
pub(crate) struct Record<E = StepError> {
    /// `Tracker::digest` after the scan.
    pub(crate) digest: u64,
    /// Hypotheses and tracks kept (the pool: clusters and their hypotheses), or why the scan was rejected.
    pub(crate) outcome: Result<(usize, usize), E>,
    /// SysTick ticks taken by `step`.
    pub(crate) ticks: u64,
}

impl<E> Record<E> {
    pub(crate) const EMPTY: Record<E> = Record { digest: 0, outcome: Ok((0, 0)), ticks: 0 };
}

/// Iterations of the calibration loop (2 instructions each).
const CALIBRATION_ITERATIONS: u32 = 1_000_000;

#[entry]
fn main() -> ! {
    let status = run();
    exit(status)
}

fn run() -> debug::ExitStatus {
    hprintln!(
        "qemu-m4: scenario {:?}: replaying {} of {} scans through SsaTracker<f32> ({} bytes, static)",
        scenario::NAME,
        SCANS,
        scenario::SCANS_IN_FILE,
        core::mem::size_of::<SsaTracker<f32>>()
    );
    let Some(mut peripherals) = cortex_m::Peripherals::take() else {
        hprintln!("qemu-m4: error: core peripherals already taken");
        return debug::EXIT_FAILURE;
    };
    cycles::start(&mut peripherals.SYST);
    hprintln!(
        "qemu-m4: calibration: {} instructions took {} ticks",
        2 * u64::from(CALIBRATION_ITERATIONS),
        cycles::calibrate(CALIBRATION_ITERATIONS)
    );

    let tracker = match build() {
        Ok(tracker) => tracker,
        Err(Some(error)) => {
            hprintln!("qemu-m4: error: tracker configuration: {}", error);
            return debug::EXIT_FAILURE;
        }
        Err(None) => {
            hprintln!("qemu-m4: error: the tracker was already built");
            return debug::EXIT_FAILURE;
        }
    };
    let build_stack = stack::high_water();

    // Replay first, print afterwards: the ticks and the stack measured during the scans are the tracker's
    // alone, with no semihosting in between.
    let Some(records) = records() else {
        hprintln!("qemu-m4: error: the record table was already taken");
        return debug::EXIT_FAILURE;
    };
    stack::paint();
    let call_depth = stack::depth();
    for (record, scan) in records.iter_mut().zip(&scenario::SCANS) {
        let start = cycles::now();
        let outcome = tracker.step(scan.time, scan.measurements);
        record.ticks = cycles::now() - start;
        record.outcome = outcome.map(|report| (report.hypotheses, report.tracks));
        record.digest = tracker.digest();
    }
    let scan_stack = stack::high_water();

    print(records, TRACKER_COUNTS);
    hprintln!(
        "qemu-m4: stack ({} bytes): start-up with building the tracker {} bytes; scans {} bytes, of which step and \
         digest {} bytes",
        stack::size(),
        build_stack,
        scan_stack,
        scan_stack.saturating_sub(call_depth)
    );
    #[cfg(rfisst_radar)]
    if radar::run() != debug::EXIT_SUCCESS {
        return debug::EXIT_FAILURE;
    }
    #[cfg(rfisst_network)]
    if network::run() != debug::EXIT_SUCCESS {
        return debug::EXIT_FAILURE;
    }
    #[cfg(rfisst_radar)]
    if pool::run() != debug::EXIT_SUCCESS {
        return debug::EXIT_FAILURE;
    }
    debug::EXIT_SUCCESS
}

/// The names of a tracker's two counts per scan in the digest text.
pub(crate) const TRACKER_COUNTS: [&str; 2] = ["hypotheses", "tracks"];

/// Prints the digest text of `records` (one line per scan, its two counts named `names`, then the final
/// digest), each scan's ticks, and the ticks' min, median, max and total. Sorts `records` by ticks.
pub(crate) fn print<E: core::fmt::Display>(records: &mut [Record<E>], names: [&str; 2]) {
    let count = records.len();
    let mut running = Fnv1a::new();
    for (index, record) in records.iter().enumerate() {
        running.write(&record.digest.to_le_bytes());
        match &record.outcome {
            Ok((a, b)) => {
                hprintln!("scan {} {} {} {} {} digest {:016x}", index, names[0], a, names[1], b, record.digest)
            }
            Err(error) => hprintln!("scan {} error {} digest {:016x}", index, error, record.digest),
        }
        hprintln!("ticks {} {}", index, record.ticks);
    }
    hprintln!("final scans {} digest {:016x}", count, running.finish());

    if count > 0 {
        let total: u64 = records.iter().map(|record| record.ticks).sum();
        // The records are printed: sort them by ticks for the median.
        records.sort_unstable_by_key(|record| record.ticks);
        let ticks = |index: usize| records[index].ticks;
        let middle = count / 2;
        let median = if count % 2 == 1 { ticks(middle) } else { (ticks(middle - 1) + ticks(middle)) / 2 };
        hprintln!(
            "qemu-m4: ticks per scan (step only): min {} median {} max {} total {}",
            ticks(0),
            median,
            ticks(count - 1),
            total
        );
    }
}

/// The tracker, built at compile time by the `const fn` `SsaTracker::empty`: it lives in a static and
/// takes no stack to build. `reset` then checks the configuration and loads the prior in place.
static mut TRACKER: SsaTracker<f32> = SsaTracker::empty(scenario::CONFIG);

/// Loads the prior into the static tracker. `Err(None)` when called twice.
#[inline(never)]
fn build() -> Result<&'static mut SsaTracker<f32>, Option<ConfigError>> {
    static TAKEN: core::sync::atomic::AtomicBool = core::sync::atomic::AtomicBool::new(false);
    if TAKEN.swap(true, core::sync::atomic::Ordering::AcqRel) {
        return Err(None);
    }
    // SAFETY: `TAKEN` hands out this one `&mut` exactly once, and the firmware is single-threaded with no
    // interrupt touching the tracker.
    let tracker = unsafe { &mut *core::ptr::addr_of_mut!(TRACKER) };
    tracker.reset(&scenario::PRIOR, scenario::PRIOR_TIME).map_err(Some)?;
    Ok(tracker)
}

/// The table of per-scan records, in a static. Not inlined, so that its initial value is built on a stack frame
/// that is given back before the scans. `None` when called twice.
#[inline(never)]
fn records() -> Option<&'static mut [Record; SCANS]> {
    cortex_m::singleton!(: [Record; SCANS] = [Record::EMPTY; SCANS])
}

/// Ends the QEMU run with `status`.
fn exit(status: debug::ExitStatus) -> ! {
    debug::exit(status);
    // Only reached without a semihosting host.
    loop {
        cortex_m::asm::wfi();
    }
}

#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    hprintln!("qemu-m4: panic: {}", info);
    exit(debug::EXIT_FAILURE)
}

#[exception]
unsafe fn HardFault(frame: &ExceptionFrame) -> ! {
    hprintln!("qemu-m4: hard fault at pc {:#010x}", frame.pc());
    exit(debug::EXIT_FAILURE)
}

#[exception]
unsafe fn DefaultHandler(irq: i16) {
    hprintln!("qemu-m4: unexpected exception {}", irq);
    exit(debug::EXIT_FAILURE)
}
