//! `host-sim soak`: a long run with objects entering and leaving (being written).

/// Placeholder until the module lands.
///
/// # Errors
/// Always, for now.
pub fn run(_scans: u64, _seed: u64, _quiet: bool) -> Result<serde_json::Value, String> {
    Err("soak: not implemented yet".into())
}
