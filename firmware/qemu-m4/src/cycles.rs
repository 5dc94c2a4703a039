//! Tick counting with SysTick: the 24-bit down-counter runs from the core clock and reloads at 2²⁴ − 1;
//! its exception counts the wraps, which gives a 64-bit count of core-clock ticks.
//!
//! Under QEMU the core clock is virtual. With `-icount shift=0` the virtual clock advances exactly 1 ns per
//! guest instruction, and the mps2-an386 SysTick runs at 25 MHz of it, so one tick is 40 guest
//! instructions ([`calibrate`] measures this). The counts repeat from run to run; they are **not**
//! cycle-accurate (QEMU models no pipeline, flash wait states or FPU latencies). On a real board the same
//! code counts real core-clock cycles.

use core::sync::atomic::{AtomicU32, Ordering};
use cortex_m::peripheral::syst::SystClkSource;
use cortex_m::peripheral::{SCB, SYST};
use cortex_m_rt::exception;

/// The counter's reload value: it counts 2²⁴ ticks per wrap.
const RELOAD: u32 = 0x00FF_FFFF;

/// Completed wraps of the counter.
static WRAPS: AtomicU32 = AtomicU32::new(0);

/// Starts the counter from zero on the core clock, with its wrap exception enabled.
pub fn start(syst: &mut SYST) {
    syst.set_clock_source(SystClkSource::Core);
    syst.set_reload(RELOAD);
    syst.clear_current();
    syst.enable_interrupt();
    syst.enable_counter();
    // Cleared, the counter reads 0 until its first tick reloads it; wait for that, so that 0 always means
    // "a wrap is due" in `now`.
    while SYST::get_current() == 0 {}
}

/// Ticks since [`start`].
pub fn now() -> u64 {
    loop {
        let wraps = WRAPS.load(Ordering::Relaxed);
        let current = SYST::get_current();
        let pending = SCB::is_pendst_pending();
        if WRAPS.load(Ordering::Relaxed) != wraps {
            continue;
        }
        let wraps = u64::from(wraps);
        let wraps = if current == 0 {
            // The period's last tick: its wrap is counted once the exception has run (not pending any more).
            if pending { wraps } else { wraps.saturating_sub(1) }
        } else {
            // A wrap whose exception has not run yet: the counter has reloaded (it reads high), so count it.
            wraps + u64::from(pending && current > RELOAD / 2)
        };
        return (wraps << 24) + u64::from(RELOAD - current);
    }
}

/// Runs a loop of exactly `2 × iterations` instructions (`subs`, `bne`) and returns the ticks it took:
/// under `-icount shift=0` this shows how many guest instructions one tick is.
pub fn calibrate(iterations: u32) -> u64 {
    let start = now();
    if iterations > 0 {
        // SAFETY: a register-only countdown loop; it touches no memory and no stack.
        unsafe {
            core::arch::asm!(
                "2:",
                "subs {n}, {n}, #1",
                "bne 2b",
                n = inout(reg) iterations => _,
                options(nomem, nostack),
            );
        }
    }
    now() - start
}

#[exception]
fn SysTick() {
    WRAPS.fetch_add(1, Ordering::Relaxed);
}
