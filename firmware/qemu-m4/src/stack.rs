//! Stack usage by painting: fill the free stack with a known word, run, then find the deepest word that
//! changed. The stack is `_stack_end .. _stack_start` (cortex-m-rt's symbols: from the end of `.bss` to the
//! top of RAM); cortex-m-rt's `paint-stack` feature paints it with the same word before `main`.

use cortex_m::register::msp;

/// cortex-m-rt's `STACK_PAINT_VALUE`.
const PAINT: u32 = 0xCCCC_CCCC;

/// Bytes left unpainted below the stack pointer, for the frame of [`paint`] itself.
const MARGIN: usize = 256;

unsafe extern "C" {
    /// Top of the stack (initial stack pointer).
    static _stack_start: u32;
    /// Lowest address the stack may grow to.
    static _stack_end: u32;
}

/// (lowest, highest) address of the stack.
fn bounds() -> (usize, usize) {
    (&raw const _stack_end as usize, &raw const _stack_start as usize)
}

/// Size of the stack region, in bytes.
pub fn size() -> usize {
    let (bottom, top) = bounds();
    top - bottom
}

/// Bytes of stack in use at the caller.
pub fn depth() -> usize {
    bounds().1 - msp::read() as usize
}

/// Repaints the free stack below the caller, so that [`high_water`] then measures what runs from here on.
#[inline(never)]
pub fn paint() {
    let (bottom, _) = bounds();
    let end = (msp::read() as usize).saturating_sub(MARGIN);
    let mut address = bottom;
    while address < end {
        // SAFETY: `bottom .. end` is stack memory below the live frames (and MARGIN below this one);
        // nothing else lives there and no interrupt handler uses that much stack.
        unsafe { core::ptr::write_volatile(address as *mut u32, PAINT) };
        address += 4;
    }
}

/// The most bytes of stack used since the last paint: top of the stack minus the lowest changed word.
pub fn high_water() -> usize {
    let (bottom, top) = bounds();
    let mut address = bottom;
    // SAFETY: reads of word-aligned stack memory, which is always mapped.
    while address < top && unsafe { core::ptr::read_volatile(address as *const u32) } == PAINT {
        address += 4;
    }
    top - address
}
