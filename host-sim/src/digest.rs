//! `host-sim digest`: replays a scenario with the embedded f32 tracker, as the QEMU firmware does, and returns the
//! digest it prints (being written).

/// Placeholder until the module lands.
///
/// # Errors
/// Always, for now.
pub fn run(_scenario: &crate::scenario::Scenario, _scans: Option<usize>) -> Result<String, String> {
    Err("digest: not implemented yet".into())
}
