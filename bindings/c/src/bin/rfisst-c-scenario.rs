//! `rfisst-c-scenario KIND SCENARIO.json SCANS PREFIX OUT.c`: writes the first SCANS scans of a scenario,
//! its configuration and its prior (3-D: restricted to the objects those scans detect, as `host-sim
//! digest` and the QEMU firmware do) as C source for a firmware that links `librfisst.a`
//! (bindings/c/firmware, scripts/c-firmware-check.sh). KIND is a kind code (0 = SsaTracker<f32>, 2 =
//! RadarTracker<f32>, ...).

use rfisst::RfisstKind;
use rfisst::scenario::{c_source, from_json};

fn main() {
    if let Err(message) = run() {
        eprintln!("rfisst-c-scenario: {message}");
        std::process::exit(2);
    }
}

fn run() -> Result<(), String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [kind, file, scans, prefix, out] = args.as_slice() else {
        return Err("usage: rfisst-c-scenario KIND SCENARIO.json SCANS PREFIX OUT.c".into());
    };
    let kind = kind.parse::<u32>().ok().and_then(RfisstKind::of).ok_or(format!("KIND {kind}: not a kind code 0..7"))?;
    let scans = scans.parse::<usize>().map_err(|e| format!("SCANS {scans}: {e}"))?;
    let text = std::fs::read_to_string(file).map_err(|e| format!("{file}: {e}"))?;
    let detected_in = (!kind.is_planar()).then_some(scans);
    let scenario = from_json(&text, kind, detected_in).map_err(|e| format!("{file}: {e}"))?;
    if scans > scenario.scans.len() {
        return Err(format!("SCANS {scans}: the scenario has only {} scans", scenario.scans.len()));
    }
    std::fs::write(out, c_source(&scenario, prefix, scans)).map_err(|e| format!("{out}: {e}"))
}
