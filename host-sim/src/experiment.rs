//! `host-sim experiment`: the papers' experiments (being written).

/// Placeholder until the module lands.
///
/// # Errors
/// Always, for now.
pub fn run(_name: &str, _out: &std::path::Path, _seed: u64, _runs: u64, _quiet: bool) -> Result<(), String> {
    Err("experiment: not implemented yet".into())
}
