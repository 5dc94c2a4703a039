//! `rfisst-c-scenario KIND SCENARIO.json SCANS PREFIX OUT.c`: writes the first SCANS scans of a scenario,
//! its configuration and its prior (3-D radar and optical scenarios: restricted to the objects those scans
//! detect, as `host-sim digest` and the QEMU firmware do; network scenarios: the whole prior) as C source
//! for a firmware that links `librfisst.a` (bindings/c/firmware, scripts/c-firmware-check.sh). KIND is a
//! kind code (0 = SsaTracker<f32>, 2 = RadarTracker<f32>, ...).
//!
//! `rfisst-c-scenario --digest KIND SCENARIO.json SCANS [REPLAY]`: prints the digest text of the first
//! REPLAY (default SCANS) of those scans replayed through the C interface on the host with a tracker of
//! KIND, the text the C firmware prints (the reference of the kinds `host-sim digest` does not replay).

use rfisst::RfisstKind;
use rfisst::replay::digest_text;
use rfisst::scenario::{CScenario, c_source, from_json};

fn main() {
    if let Err(message) = run() {
        eprintln!("rfisst-c-scenario: {message}");
        std::process::exit(2);
    }
}

fn run() -> Result<(), String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.as_slice() {
        [flag, kind, file, scans, rest @ ..] if flag == "--digest" && rest.len() <= 1 => {
            let (kind, scans, scenario) = read(kind, file, scans)?;
            let replay = match rest.first() {
                Some(replay) => count(replay, "REPLAY")?.min(scans),
                None => scans,
            };
            println!("{}", digest_text(&scenario, kind, replay).map_err(|e| format!("{file}: {e}"))?);
            Ok(())
        }
        [kind, file, scans, prefix, out] => {
            let (_, scans, scenario) = read(kind, file, scans)?;
            std::fs::write(out, c_source(&scenario, prefix, scans)).map_err(|e| format!("{out}: {e}"))
        }
        _ => Err("usage: rfisst-c-scenario KIND SCENARIO.json SCANS PREFIX OUT.c, or rfisst-c-scenario --digest \
                  KIND SCENARIO.json SCANS [REPLAY]"
            .into()),
    }
}

fn count(text: &str, what: &str) -> Result<usize, String> {
    text.parse::<usize>().map_err(|e| format!("{what} {text}: {e}"))
}

/// The kind, the scans and the scenario (as the C interface's values) of the arguments.
fn read(kind: &str, file: &str, scans: &str) -> Result<(RfisstKind, usize, CScenario), String> {
    let kind = kind.parse::<u32>().ok().and_then(RfisstKind::of).ok_or(format!("KIND {kind}: not a kind code 0..7"))?;
    let scans = count(scans, "SCANS")?;
    let text = std::fs::read_to_string(file).map_err(|e| format!("{file}: {e}"))?;
    let detected_in = (!kind.is_planar()).then_some(scans);
    let scenario = from_json(&text, kind, detected_in).map_err(|e| format!("{file}: {e}"))?;
    if scans > scenario.scans.len() {
        return Err(format!("SCANS {scans}: the scenario has only {} scans", scenario.scans.len()));
    }
    Ok((kind, scans, scenario))
}
