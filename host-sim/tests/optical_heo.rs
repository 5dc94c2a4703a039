//! The `optical-heo` preset (issue 31): a small one (2 GEO objects known to the prior, a GTO and a Molniya
//! object unknown to it, the first two hours of the night, each in the field for at least 20 minutes) is generated
//! and run; each eccentric object is born from tracklets and confirmed under one label. The preset asks 4
//! minutes only; passes shorter than about half an hour often end before their range along the line of sight
//! comes within the 10 km bound (docs/results.md, "optical-heo"), so the preset's field is wide.

mod common;

use host_sim::pipeline::{Profile, TrackerKind};
use host_sim::scenario::from_simulation::to_scenario;
use host_sim::sim::optical_heo::{OpticalHeoConfig, optical_heo_with};

/// A small `optical-heo`: one GTO and one Molniya object in the field for 40 frames (20 minutes) of the
/// first two hours of frames (they start when the Sun reaches −12° at the site, 1440 s after the epoch).
fn small(seed: u64) -> host_sim::scenario::v2::Scenario3d {
    let config = OpticalHeoConfig {
        geo: 2,
        gto: 1,
        molniya: 1,
        duration: 1440.0 + 7200.0,
        min_frames: 40,
        ..OpticalHeoConfig::PRESET
    };
    let sim = optical_heo_with(seed, &config).expect("optical-heo simulates");
    to_scenario(&sim).expect("scenario").0
}

#[test]
fn a_small_optical_heo_confirms_each_eccentric_object_under_one_label() {
    // The host profile's tracker is built on the stack in debug builds.
    let worker = std::thread::Builder::new().stack_size(1 << 30).spawn(small_run_check).expect("thread");
    worker.join().expect("the check passes");
}

fn small_run_check() {
    let scenario = small(SEED);
    assert!(scenario.births_from_tracklets_only(), "optical-heo's births come from tracklets only");
    let dir = common::TempDir::new("optical-heo");
    let (summary, clean) =
        host_sim::pipeline::orbital::run(&scenario, TrackerKind::Rfisst, Some(Profile::Host), true, &dir.0)
            .expect("run");
    assert!(clean, "every scan accepted");
    let births = &summary.births;
    assert_eq!(births.births_total, 2);
    assert_eq!(births.births_confirmed, 2, "both eccentric objects confirmed: {births:?}");
    assert!(births.birth_confirmations.iter().all(|r| r.confirmed_labels == 1), "{births:?}");
    assert_eq!(births.max_labels_per_birth, Some(1));
    assert_eq!(births.false_tracks, Some(0));
    // The only confirmed born labels are the two objects' (no track from clutter).
    assert_eq!(summary.tracklet_births, Some(2));
}

/// The seed of the small run. With the preset's 20° field every one of seeds 1–8 of this small scenario
/// confirms both objects under one label each with no false track; with `optical-geo`'s 3° field only seeds 4
/// and 6 did (the others ended one object more than 10 km off along the line of sight).
const SEED: u64 = 1;

#[test]
fn optical_heo_is_deterministic_and_its_eccentric_objects_are_unknown_to_the_prior() {
    let (a, b) = (small(2), small(2));
    assert_eq!(serde_json::to_string(&a).expect("json"), serde_json::to_string(&b).expect("json"));
    let truth = &a.truth.as_ref().expect("truth").objects;
    let unknown: Vec<u64> = truth.iter().filter(|o| !o.in_prior).map(|o| o.id).collect();
    assert_eq!(unknown, vec![2, 3], "the GTO and Molniya objects, after the 2 GEO objects");
    assert_eq!(a.prior.hypotheses[0].objects.len(), 2);
    assert!(a.scans.windows(2).all(|w| w[1].time - w[0].time == 30.0), "a frame every 30 s");
}
