//! Fuzz target `tdm`: arbitrary bytes into host-sim's CCSDS TDM reader (`host_sim::io::tdm::parse`) and the
//! scans it gives tiny-3d's configuration (`host_sim::io::tdm::scans_of`).
//!
//! Checked on every input:
//! - nothing panics;
//! - a refused TDM gets a one-line message naming a line of the file (or the line after the last);
//! - accepted scans that make a valid scenario survive a round trip through the TDM writer unchanged, bit
//!   for bit.
#![no_main]

use host_sim::io::tdm;
use host_sim::scenario::v2::Scenario3d;
use libfuzzer_sys::fuzz_target;
use std::sync::OnceLock;

/// tiny-3d (one radar named `radar-north`), built once.
fn config() -> &'static Scenario3d {
    static CONFIG: OnceLock<Scenario3d> = OnceLock::new();
    CONFIG.get_or_init(|| {
        let simulation = host_sim::sim::presets::tiny_3d(1).expect("tiny-3d");
        host_sim::scenario::from_simulation::to_scenario(&simulation).expect("scenario").0
    })
}

fn check_error(text: &str, e: &tdm::TdmError) {
    let message = e.to_string();
    let message = host_sim::scenario::one_line(&message);
    assert!(!message.contains(['\n', '\r']), "multi-line error message: {message}");
    // Quoted input is cut to an excerpt (issue 33): a message never echoes a long keyword or value whole.
    assert!(message.len() <= 32 << 10, "a message of {} bytes", message.len());
    assert!(e.line >= 1 && e.line <= text.lines().count() + 1, "line {} of {} lines", e.line, text.lines().count());
}

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let parsed = match tdm::parse(text) {
        Ok(parsed) => parsed,
        Err(e) => return check_error(text, &e),
    };
    let config = config();
    let scans = match tdm::scans_of(&parsed, config) {
        Ok(scans) => scans,
        Err(e) => return check_error(text, &e),
    };
    let mut scenario = config.clone();
    scenario.truth = None;
    scenario.scans = scans.into_iter().map(|(scan, _)| scan).collect();
    scenario.scans.sort_by(|a, b| a.time.total_cmp(&b.time));
    if scenario.validate().is_err() {
        return;
    }
    let Ok(written) = tdm::write(&scenario, 0) else { return };
    let again = tdm::parse(&written).expect("a written TDM parses");
    let back: Vec<_> =
        tdm::scans_of(&again, config).expect("a written TDM gives scans").into_iter().map(|(s, _)| s).collect();
    let bits = |scans: &[host_sim::scenario::v2::Scan3dSpec]| -> Vec<(u64, usize, Vec<Vec<u64>>)> {
        let mut v: Vec<_> = scans
            .iter()
            .map(|s| {
                (
                    s.time.to_bits(),
                    s.sensor,
                    s.measurements.iter().map(|z| z.iter().map(|x| x.to_bits()).collect()).collect(),
                )
            })
            .collect();
        v.sort_by_key(|e| e.0);
        v
    };
    assert_eq!(bits(&back), bits(&scenario.scans), "round trip changed the scans");
});
