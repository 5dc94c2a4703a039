//! # rfisst-c: tracker-core from C
//!
//! An opaque tracker handle for the default configurations of tracker-core (`SsaTracker`, `RadarTracker`,
//! `OpticalTracker`, `NetworkTracker`, each in `f32` and `f64`), for C programs and flight software:
//! `librfisst.a` and the header `include/rfisst.h`, generated from this crate by cbindgen (a test checks
//! that the checked-in header is current). docs/c-api.md is the user's guide.
//!
//! - **Memory**: the caller provides the storage (`rfisst_tracker_size(kind)` bytes aligned to
//!   `rfisst_tracker_align(kind)`, static or allocated); nothing is allocated, and the configuration and a
//!   step's measurements are converted in the handle's scratch. The JSON path (`rfisst_tracker_init_json`, feature `std`) allocates while
//!   it parses only.
//! - **Errors**: every function returns an `RfisstStatus`; `rfisst_status_message` gives its static text,
//!   `rfisst_tracker_last_error` the handle's detailed one. Null pointers, misaligned or short storage, bad
//!   dimensions and unknown codes are statuses, checked before anything is read; the core's own errors
//!   leave the tracker unchanged.
//! - **No panic**: the crate calls nothing that panics on these paths (slices through `get`, bounded
//!   pushes); without `std` its panic handler is never reached.
//!
//! `unsafe` is confined to this crate (pointer reads and writes at the C boundary); tracker-core stays
//! `forbid(unsafe_code)`.
#![cfg_attr(not(feature = "std"), no_std)]
#![deny(missing_docs)]
#![allow(clippy::missing_safety_doc)]

pub mod api;
pub mod config;
pub mod convert;
pub mod handle;
pub mod placeholder;
#[cfg(feature = "std")]
pub mod replay;
#[cfg(feature = "std")]
pub mod scenario;
pub mod status;

pub use api::*;
pub use config::*;
pub use handle::RfisstKind;
pub use status::RfisstStatus;

/// Without `std` there is no unwinding: a panic (none is reachable from the C functions) stops here.
#[cfg(all(not(feature = "std"), not(test)))]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {
        core::hint::spin_loop();
    }
}
