//! Fuzz target `oem`: arbitrary bytes into host-sim's CCSDS OEM reader (`host_sim::io::oem::read::parse`)
//! and the prior `track --prior-oem` makes of it for tiny-3d's configuration
//! (`host_sim::pipeline::orbital::prior_oem::prior_from_oem`).
//!
//! Checked on every input:
//! - nothing panics;
//! - a refused OEM gets a one-line message naming a line of the file (or the line after the last);
//! - an accepted prior makes a valid scenario, and written back as an OEM (`OemTracks`) and read again it
//!   is the same prior, bit for bit (labels, states, covariances, time).
#![no_main]

use host_sim::io::ccsds::Instant;
use host_sim::io::oem::OemTracks;
use host_sim::io::oem::read::{OemError, parse};
use host_sim::pipeline::orbital::prior_oem::prior_from_oem;
use host_sim::pipeline::snapshot::Track6;
use host_sim::scenario::v2::{PriorObject3dSpec, Scenario3d};
use libfuzzer_sys::fuzz_target;
use std::sync::OnceLock;

/// tiny-3d, built once.
fn config() -> &'static Scenario3d {
    static CONFIG: OnceLock<Scenario3d> = OnceLock::new();
    CONFIG.get_or_init(|| {
        let simulation = host_sim::sim::presets::tiny_3d(1).expect("tiny-3d");
        host_sim::scenario::from_simulation::to_scenario(&simulation).expect("scenario").0
    })
}

fn check_error(text: &str, e: &OemError) {
    let message = e.to_string();
    assert!(!message.contains(['\n', '\r']), "multi-line error message: {message}");
    assert!(message.chars().count() < 400, "long error message: {message}");
    assert!(e.line >= 1 && e.line <= text.lines().count() + 1, "line {} of {} lines", e.line, text.lines().count());
}

/// The objects sorted by label, as bits.
fn bits(objects: &[PriorObject3dSpec]) -> Vec<(u32, [u64; 6], [[u64; 6]; 6])> {
    let mut v: Vec<_> =
        objects.iter().map(|o| (o.label, o.mean.map(f64::to_bits), o.covariance.map(|r| r.map(f64::to_bits)))).collect();
    v.sort_by_key(|o| o.0);
    v
}

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let oem = match parse(text) {
        Ok(oem) => oem,
        Err(e) => return check_error(text, &e),
    };
    let config = config();
    let epoch = Instant::epoch_of(config);
    let prior = match prior_from_oem(&oem, &epoch, 64, "embedded") {
        Ok(prior) => prior,
        Err(e) => return check_error(text, &e),
    };
    let mut scenario = config.clone();
    scenario.truth = None;
    scenario.scans = vec![];
    scenario.prior = prior.prior.clone();
    scenario.validate().expect("a prior read from an OEM makes a valid scenario");
    if epoch.after(prior.prior.time).is_err() {
        // Beyond the writer's 1e11 s after the epoch: nothing to write back.
        return;
    }
    let objects = &prior.prior.hypotheses[0].objects;
    let mut tracks = OemTracks::new(config);
    let map: Vec<Track6> = objects
        .iter()
        .map(|o| Track6 { label: o.label, mean: o.mean, existence: 1.0, covariance: o.covariance })
        .collect();
    tracks.record(prior.prior.time, &map);
    let again = parse(&tracks.text()).expect("a written OEM parses");
    let back = prior_from_oem(&again, &epoch, 64, "embedded").expect("a written OEM gives a prior");
    assert_eq!(back.prior.time.to_bits(), prior.prior.time.to_bits(), "round trip changed the time");
    assert_eq!(back.epoch, epoch.after(prior.prior.time).expect("written"), "round trip changed the epoch");
    assert_eq!(bits(&back.prior.hypotheses[0].objects), bits(objects), "round trip changed the objects");
});
