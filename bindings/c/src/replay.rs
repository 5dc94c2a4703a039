//! Host only (`std`): a [`CScenario`] replayed through the C interface's own functions on the host, giving
//! the digest text the C firmware prints (`bindings/c/firmware/main.c`) for any kind, so that the kinds
//! `host-sim digest` does not replay (the optical tracker and every `f64` tracker) are still compared
//! with the host bit for bit (scripts/c-firmware-check.sh).

use crate::api::{
    rfisst_tracker_digest, rfisst_tracker_init, rfisst_tracker_last_error, rfisst_tracker_size, rfisst_tracker_step,
};
use crate::config::RfisstStepReport;
use crate::handle::RfisstKind;
use crate::scenario::CScenario;
use crate::status::RfisstStatus;
use std::ffi::CStr;
use std::fmt::Write as _;
use tracker_core::digest::Fnv1a;

/// The digest text of the first `scans` scans of `scenario` through a tracker of `kind`: one line per scan
/// (`scan K hypotheses H tracks T digest X` or `scan K error MESSAGE digest X`) and
/// `final scans N digest X`, as `host-sim digest` writes it.
///
/// # Errors
/// A one-line message when the tracker refuses the configuration or a call fails other than by a rejected
/// scan.
pub fn digest_text(scenario: &CScenario, kind: RfisstKind, scans: usize) -> Result<String, String> {
    let size = rfisst_tracker_size(kind as u32);
    let mut storage = vec![0u64; size.div_ceil(8)];
    let hypotheses = scenario.hypotheses();
    let mut tracker = core::ptr::null_mut();
    // SAFETY: the storage is `size` bytes, 8-aligned; the configuration and the prior live in `scenario` and
    // `hypotheses` for the call.
    let status = unsafe {
        rfisst_tracker_init(
            storage.as_mut_ptr().cast(),
            size,
            kind as u32,
            &scenario.config,
            hypotheses.as_ptr(),
            hypotheses.len(),
            scenario.prior_time,
            &mut tracker,
        )
    };
    if status != RfisstStatus::RfisstOk {
        // SAFETY: after a failed initialisation the storage holds a header with the error's text.
        let why = unsafe { CStr::from_ptr(rfisst_tracker_last_error(storage.as_ptr().cast())) };
        return Err(format!("{}: initialisation failed: {status:?}: {}", kind.name(), why.to_string_lossy()));
    }
    let mut text = String::new();
    let mut running = Fnv1a::new();
    for (index, scan) in scenario.scans.iter().take(scans).enumerate() {
        let mut report = RfisstStepReport::default();
        let mut digest = 0u64;
        let count = scan.measurements.len() / scenario.dimension.max(1);
        // SAFETY: a ready handle; `count × dimension` doubles at `measurements`.
        let (status, error) = unsafe {
            let status = rfisst_tracker_step(
                tracker,
                scan.time,
                scan.sensor,
                core::ptr::null(),
                scan.measurements.as_ptr(),
                count,
                scenario.dimension,
                &mut report,
            );
            if rfisst_tracker_digest(tracker, &mut digest) != RfisstStatus::RfisstOk {
                return Err(format!("{}: the digest failed", kind.name()));
            }
            (status, CStr::from_ptr(rfisst_tracker_last_error(tracker)).to_string_lossy().into_owned())
        };
        running.write(&digest.to_le_bytes());
        let _ = match status {
            RfisstStatus::RfisstOk => writeln!(
                text,
                "scan {index} hypotheses {} tracks {} digest {digest:016x}",
                report.hypotheses, report.tracks
            ),
            RfisstStatus::RfisstStepRejected => writeln!(text, "scan {index} error {error} digest {digest:016x}"),
            other => return Err(format!("{}: scan {index} failed: {other:?}", kind.name())),
        };
    }
    let _ = write!(text, "final scans {} digest {:016x}", scans.min(scenario.scans.len()), running.finish());
    Ok(text)
}
