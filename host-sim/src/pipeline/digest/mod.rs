//! `host-sim digest`: the QEMU firmware's digest, replayed on the host with the embedded (f32) tracker of
//! the planar world ([`planar`]), the radar network ([`orbital`]) or a network of mixed kinds
//! ([`network`], whose firmware excerpt [`excerpt`] writes), and the radar excerpt through the fixed pool
//! of cluster trackers ([`pool`]). All print the same text, written once here ([`text`], [`text_of`]).

pub mod convert;
pub mod excerpt;
pub mod network;
pub mod orbital;
pub mod planar;
pub mod pool;

use crate::scenario::ScenarioError;
use std::fmt::{Display, Write as _};
use tracker_core::digest::Fnv1a;
use tracker_core::{StepError, StepReport};

/// The scans replayed: `scans` (all `total` when `None`).
///
/// # Errors
/// When `scans` exceeds the scenario's.
pub fn excerpt(scans: Option<usize>, total: usize) -> Result<usize, ScenarioError> {
    let count = scans.unwrap_or(total);
    if count > total {
        return Err(ScenarioError(format!("--scans {count}: the scenario has only {total} scans")));
    }
    Ok(count)
}

/// The digest text of `count` scans, `scan(index)` stepping the tracker and giving the outcome and the
/// tracker's digest after it: one line per scan and a final line,
///
/// ```text
/// scan 0 hypotheses 1 tracks 45 digest 1c0ffee15bad5eed
/// scan 1 error scan time is not after the previous scan digest 1c0ffee15bad5eed
/// final scans 2 digest 0123456789abcdef
/// ```
///
/// where the final digest is a 64-bit FNV-1a over every scan's digest as 8 little-endian bytes.
pub fn text(count: usize, mut scan: impl FnMut(usize) -> (Result<StepReport<f32>, StepError>, u64)) -> String {
    text_of(count, ["hypotheses", "tracks"], |index| {
        let (outcome, digest) = scan(index);
        (outcome.map(|report| (report.hypotheses, report.tracks)), digest)
    })
}

/// The digest text of [`text`] with another pair of counts per scan, named `names` (the pool's
/// `scan 0 clusters 43 hypotheses 43 digest …`).
pub fn text_of<E: Display>(
    count: usize,
    names: [&str; 2],
    mut scan: impl FnMut(usize) -> (Result<(usize, usize), E>, u64),
) -> String {
    let mut text = String::new();
    let mut running = Fnv1a::new();
    let [first, second] = names;
    for index in 0..count {
        let (outcome, digest) = scan(index);
        running.write(&digest.to_le_bytes());
        // `write!` to a String cannot fail.
        let _ = match outcome {
            Ok((a, b)) => writeln!(text, "scan {index} {first} {a} {second} {b} digest {digest:016x}"),
            Err(error) => writeln!(text, "scan {index} error {error} digest {digest:016x}"),
        };
    }
    let _ = write!(text, "final scans {count} digest {:016x}", running.finish());
    text
}
