//! What every command's outputs share: JSON files, the progress bar, means, the peak resident memory.

use crate::error::Error;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use serde::Serialize;
use std::io::IsTerminal;
use std::path::Path;

/// The mean of `values`, 0 when there is none.
pub fn mean(values: &[f64]) -> f64 {
    if values.is_empty() { 0.0 } else { values.iter().sum::<f64>() / values.len() as f64 }
}

/// A progress bar over `scans` scans on stderr, hidden when `quiet` or stderr is not a terminal.
pub fn progress(scans: usize, quiet: bool, message: &'static str) -> ProgressBar {
    if quiet || !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::with_draw_target(Some(scans as u64), ProgressDrawTarget::stderr());
    if let Ok(style) = ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} scans, {elapsed} (eta {eta})") {
        bar.set_style(style.progress_chars("=> "));
    }
    bar.set_message(message);
    bar
}

/// Writes `value` as pretty JSON and a line break to `path` ([`crate::io::atomic`]: never onto anything
/// but a regular file, never half-written).
///
/// # Errors
/// [`Error::Output`] when the file cannot be written.
pub fn write_json(path: &Path, value: &impl Serialize) -> Result<(), Error> {
    crate::io::atomic::write_json(path, value, true)
}

/// CPU time (ns) the process's threads have run so far: the sum of the first field of every
/// /proc/self/task/*/schedstat (threads that have ended not counted); `None` where there is none.
pub fn cpu_time_ns() -> Option<u64> {
    let mut total = 0u64;
    for task in std::fs::read_dir("/proc/self/task").ok()? {
        let stat = std::fs::read_to_string(task.ok()?.path().join("schedstat")).ok()?;
        total += stat.split_whitespace().next()?.parse::<u64>().ok()?;
    }
    Some(total)
}

/// VmHWM of /proc/self/status in KiB, where there is one.
pub fn peak_resident_kib() -> Option<u64> {
    status_kib("VmHWM:")
}

/// The process's resident memory now (KiB, VmRSS of /proc/self/status), where there is one.
pub fn resident_kib() -> Option<u64> {
    status_kib("VmRSS:")
}

fn status_kib(key: &str) -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with(key))?;
    line.split_whitespace().nth(1)?.parse().ok()
}
