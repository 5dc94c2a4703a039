//! `host-sim perf`: speed and memory measured side by side in one process (being written).

/// Placeholder until the module lands.
///
/// # Errors
/// Always, for now.
pub fn run() -> Result<serde_json::Value, String> {
    Err("perf: not implemented yet".into())
}
